//! The stack as a [`Perturbable`] system, for its largest exponent by two
//! trajectories. Its tangent equations are not written, so it has no
//! spectrum.
//!
//! Tangent coordinates `z = (q_1 … q_5, q_1' … q_5', u'/R₁)`, the
//! rotations padded to [`MAX_BLOCKS`] as in the state: every component is
//! dimensionless (radians, radians per τ, and the slip rate over the
//! bottom block's half-diagonal R₁, as the block's X' = x'/R). The slip u
//! itself is neutral (nothing depends on where along the base the stack
//! stands) and is left out, as the block's X is.

use super::tangent::Perturbable;
use crate::model::stack::{Contact, MAX_BLOCKS, NS, SLIDE_RATE, StackMode, StackSystem};

/// Number of tangent coordinates of a stack.
pub(crate) const STACK_DIM: usize = 2 * MAX_BLOCKS + 1;

impl Perturbable<NS, STACK_DIM> for StackSystem {
    fn coords(&self, y: &[f64; NS]) -> [f64; STACK_DIM] {
        let mut z = [0.0; STACK_DIM];
        z[..2 * MAX_BLOCKS].copy_from_slice(&y[..2 * MAX_BLOCKS]);
        z[2 * MAX_BLOCKS] = y[SLIDE_RATE] / self.geo.r1;
        z
    }

    /// Two per open interface (its q and q'), one for the base's slip
    /// rate while it slides: a closed or glued interface holds its q and
    /// q' at 0, a stuck base its u' at 0.
    fn tangent_dim(&self, mode: StackMode) -> usize {
        if mode.end.is_some() {
            return 0;
        }
        let open = mode.contacts[..self.geo.k]
            .iter()
            .filter(|&&c| c != Contact::Closed)
            .count();
        2 * open + usize::from(mode.sliding())
    }

    /// Each open interface's q and q' displaced, keeping its corner
    /// (s q > 0); the slip rate displaced while the base slides, keeping
    /// its sense. Closed faces and a stuck base are not moved: their
    /// coordinates are the mode's constraints.
    fn displaced(&self, mode: StackMode, _t: f64, y: &[f64; NS], dz: &[f64; STACK_DIM]) -> Option<[f64; NS]> {
        if mode.end.is_some() {
            return None;
        }
        let mut yp = *y;
        for (i, c) in mode.contacts[..self.geo.k].iter().enumerate() {
            if *c == Contact::Closed {
                continue;
            }
            yp[i] += dz[i];
            yp[MAX_BLOCKS + i] += dz[MAX_BLOCKS + i];
            if c.sign() * yp[i] <= 0.0 {
                return None;
            }
        }
        if mode.sliding() {
            yp[SLIDE_RATE] += dz[2 * MAX_BLOCKS] * self.geo.r1;
            if mode.slip.sign() * yp[SLIDE_RATE] <= 0.0 {
                return None;
            }
        }
        Some(yp)
    }
}
