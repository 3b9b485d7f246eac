//! Truncated power series ("jets") evaluated order by order on a [`Tape`]:
//! the Taylor coefficients of an ODE's solution from its vector field
//! written once over a generic [`Scalar`] (Moore 1966; Jorba and Zou 2005).
//!
//! The Taylor method needs `y_{k+1} = f(y)_k/(k+1)`: coefficient `k` of
//! the field needs coefficients `0..=k` of the state, which are known only
//! once the previous order is done. So the field is evaluated once per
//! order `k` ("a pass"): every operation is a node of the tape, and in pass
//! `k` it computes its own coefficient `k` from the coefficients `0..=k`
//! its operands already hold, by the standard recurrences (a product is a
//! convolution, a quotient is solved term by term, sine and cosine follow
//! from `(sin x)' = cos x · x'`). Nodes are numbered in the order they are
//! made, so every pass must perform the same operations in the same order:
//! the field may branch on parameters and on [`Scalar::value`] to compute a
//! value, never on them to choose which jet operations it performs. The
//! whole expansion to order `p` costs `O(p²)` per node, as hand-written
//! recurrences do.
//!
//! Contract: `L` is the number of coefficients kept (orders `0..L`); a
//! pass beyond `L − 1` is refused by [`Tape::begin`]. A jet read outside
//! its tape's nodes reads zeros (a misuse, caught by a debug assertion).

use std::cell::{Cell, RefCell};
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::Scalar;

/// The nodes of one expansion and the order of the current pass.
#[derive(Debug)]
pub struct Tape<const L: usize> {
    /// Coefficients of every node, in the order the nodes were made.
    nodes: RefCell<Vec<[f64; L]>>,
    /// Index of the next node the current pass makes.
    next: Cell<usize>,
    /// The coefficient the current pass computes.
    order: Cell<usize>,
}

/// A node of a [`Tape`]: a truncated power series.
#[derive(Clone, Copy, Debug)]
pub struct Jet<'t, const L: usize> {
    tape: &'t Tape<L>,
    id: usize,
}

impl<const L: usize> Default for Tape<L> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const L: usize> Tape<L> {
    /// An empty tape. Its node storage grows on the first pass and is kept
    /// for the later ones (64 nodes reserved: a block mode makes fewer).
    pub fn new() -> Self {
        Self {
            nodes: RefCell::new(Vec::with_capacity(64)),
            next: Cell::new(0),
            order: Cell::new(0),
        }
    }

    /// Starts the pass that computes coefficient `k` of every node; pass 0
    /// forgets the nodes of an earlier expansion. `false` (and nothing
    /// done) for `k >= L`.
    pub fn begin(&self, k: usize) -> bool {
        if k >= L {
            return false;
        }
        if k == 0 {
            self.nodes.borrow_mut().clear();
        }
        self.order.set(k);
        self.next.set(0);
        true
    }

    /// An unknown of the expansion: its coefficient `k` is `coeff` in pass
    /// `k` (the lower ones are those given in the earlier passes).
    pub(crate) fn variable(&self, coeff: f64) -> Jet<'_, L> {
        self.make(|_, _, _| coeff)
    }

    /// An input whose whole series is known ahead (a forcing): the first
    /// `L` entries of `series` (missing ones are zero), stored in pass 0.
    pub fn known(&self, series: &[f64]) -> Jet<'_, L> {
        let jet = self.node();
        if self.order.get() == 0 {
            let mut nodes = self.nodes.borrow_mut();
            if let Some(n) = nodes.get_mut(jet.id) {
                for (c, s) in n.iter_mut().zip(series) {
                    *c = *s;
                }
            }
        }
        jet
    }

    /// Coefficient `k` of `jet` (zero for a coefficient not computed yet).
    pub(crate) fn coeff(&self, jet: Jet<'_, L>, k: usize) -> f64 {
        self.nodes
            .borrow()
            .get(jet.id)
            .and_then(|n| n.get(k))
            .copied()
            .unwrap_or(0.0)
    }

    /// The next node of this pass (made in pass 0, revisited afterwards).
    #[inline]
    fn node(&self) -> Jet<'_, L> {
        let id = self.next.get();
        self.next.set(id + 1);
        let mut nodes = self.nodes.borrow_mut();
        debug_assert!(id <= nodes.len(), "a pass made more nodes than the first");
        if id == nodes.len() {
            nodes.push([0.0; L]);
        }
        Jet { tape: self, id }
    }

    /// A new node whose current coefficient is `f(nodes, k, id)`: `nodes`
    /// holds every node, its own lower coefficients included.
    #[inline]
    fn make(&self, f: impl FnOnce(&[[f64; L]], usize, usize) -> f64) -> Jet<'_, L> {
        let jet = self.node();
        let k = self.order.get();
        let mut nodes = self.nodes.borrow_mut();
        let v = f(&nodes[..], k, jet.id);
        if let Some(c) = nodes.get_mut(jet.id).and_then(|n| n.get_mut(k)) {
            *c = v;
        }
        jet
    }
}

/// Coefficient `k` of node `id`, zero outside the tape.
#[inline(always)]
fn at<const L: usize>(nodes: &[[f64; L]], id: usize, k: usize) -> f64 {
    nodes.get(id).and_then(|n| n.get(k)).copied().unwrap_or(0.0)
}

/// `Σ_{j=lo..=k} a_j b_{k−j}`.
#[inline(always)]
fn conv<const L: usize>(a: &[f64; L], b: &[f64; L], k: usize, lo: usize) -> f64 {
    let k = k.min(L - 1);
    (lo..=k).map(|j| a[j] * b[k - j]).sum()
}

impl<'t, const L: usize> Jet<'t, L> {
    /// Coefficient `k` of this series (zero if not computed yet).
    pub(crate) fn coeff(self, k: usize) -> f64 {
        self.tape.coeff(self, k)
    }

    #[inline(always)]
    fn unary(self, f: impl FnOnce(f64, usize) -> f64) -> Self {
        let a = self.id;
        self.tape.make(|n, k, _| f(at(n, a, k), k))
    }

    #[inline(always)]
    fn binary(self, o: Self, f: impl FnOnce(&[f64; L], &[f64; L], usize) -> f64) -> Self {
        let (a, b) = (self.id, o.id);
        self.tape.make(|n, k, _| match (n.get(a), n.get(b)) {
            (Some(x), Some(y)) => f(x, y, k),
            _ => 0.0,
        })
    }
}

impl<const L: usize> Add for Jet<'_, L> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        self.binary(o, |a, b, k| a[k] + b[k])
    }
}

impl<const L: usize> Sub for Jet<'_, L> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self.binary(o, |a, b, k| a[k] - b[k])
    }
}

impl<const L: usize> Mul for Jet<'_, L> {
    type Output = Self;
    /// `(ab)_k = Σ_{j=0..=k} a_j b_{k−j}`.
    fn mul(self, o: Self) -> Self {
        self.binary(o, |a, b, k| conv(a, b, k, 0))
    }
}

impl<const L: usize> Div for Jet<'_, L> {
    type Output = Self;
    /// `q = a/b` from `b q = a`: `q_k = (a_k − Σ_{j=1..=k} b_j q_{k−j})/b_0`.
    fn div(self, o: Self) -> Self {
        let (a, b) = (self.id, o.id);
        self.tape.make(|n, k, q| match (n.get(a), n.get(b), n.get(q)) {
            (Some(a), Some(b), Some(q)) => (a[k] - conv(b, q, k, 1)) / b[0],
            // The new node itself: pass 0 has pushed it before `f` runs.
            _ => 0.0,
        })
    }
}

impl<const L: usize> Neg for Jet<'_, L> {
    type Output = Self;
    fn neg(self) -> Self {
        self.unary(|a, _| -a)
    }
}

impl<const L: usize> Add<f64> for Jet<'_, L> {
    type Output = Self;
    fn add(self, c: f64) -> Self {
        self.unary(|a, k| if k == 0 { a + c } else { a })
    }
}

impl<const L: usize> Sub<f64> for Jet<'_, L> {
    type Output = Self;
    fn sub(self, c: f64) -> Self {
        self.unary(|a, k| if k == 0 { a - c } else { a })
    }
}

impl<const L: usize> Mul<f64> for Jet<'_, L> {
    type Output = Self;
    fn mul(self, c: f64) -> Self {
        self.unary(|a, _| a * c)
    }
}

impl<const L: usize> Div<f64> for Jet<'_, L> {
    type Output = Self;
    fn div(self, c: f64) -> Self {
        self.unary(|a, _| a / c)
    }
}

impl<const L: usize> Scalar for Jet<'_, L> {
    fn value(self) -> f64 {
        self.coeff(0)
    }

    fn constant(self, c: f64) -> Self {
        self.tape.make(|_, k, _| if k == 0 { c } else { 0.0 })
    }

    /// `(sin x)_k = (1/k) Σ_{j=1..=k} j x_j (cos x)_{k−j}` and
    /// `(cos x)_k = −(1/k) Σ_{j=1..=k} j x_j (sin x)_{k−j}`, from the
    /// given values at `k = 0`.
    fn sin_cos_from(self, sin: f64, cos: f64) -> (Self, Self) {
        let tape = self.tape;
        let (s, c) = (tape.node(), tape.node());
        let k = tape.order.get();
        let mut nodes = tape.nodes.borrow_mut();
        let (sk, ck) = if k == 0 {
            (sin, cos)
        } else {
            match (nodes.get(self.id), nodes.get(s.id), nodes.get(c.id)) {
                (Some(x), Some(sn), Some(cs)) => {
                    let (mut ds, mut dc) = (0.0, 0.0);
                    for j in 1..=k.min(L - 1) {
                        let jx = j as f64 * x[j];
                        ds += jx * cs[k - j];
                        dc += jx * sn[k - j];
                    }
                    (ds / k as f64, -dc / k as f64)
                }
                _ => (0.0, 0.0),
            }
        };
        for (id, v) in [(s.id, sk), (c.id, ck)] {
            if let Some(slot) = nodes.get_mut(id).and_then(|n| n.get_mut(k)) {
                *slot = v;
            }
        }
        (s, c)
    }
}
