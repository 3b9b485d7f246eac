//! Dual numbers with `D` partial derivatives: forward-mode automatic
//! differentiation, all `D` directions in one evaluation.

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::Scalar;

/// A value and its partial derivatives with respect to `D` independent
/// variables. Operations follow the chain rule; a non-finite value gives
/// non-finite partials, as the `f64` code would give a non-finite value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const D: usize> {
    /// The value.
    pub v: f64,
    /// ∂v/∂x_i for each independent variable x_i.
    pub d: [f64; D],
}

impl<const D: usize> Dual<D> {
    /// A constant: every partial zero.
    #[inline]
    pub fn constant(v: f64) -> Self {
        Self { v, d: [0.0; D] }
    }

    /// Independent variable `i` at value `v` (∂/∂x_i = 1, the others 0).
    #[inline]
    pub(crate) fn variable(v: f64, i: usize) -> Self {
        let mut d = [0.0; D];
        if let Some(di) = d.get_mut(i) {
            *di = 1.0;
        }
        Self { v, d }
    }

    /// The state `y` as constants but for its components `coords`, the
    /// `j`-th of which is independent variable `j` (a model's tangent
    /// coordinates seeded for its Jacobian).
    #[inline]
    pub(crate) fn seeded<const N: usize>(y: &[f64; N], coords: &[usize]) -> [Self; N] {
        let mut out = y.map(Self::constant);
        for (j, &i) in coords.iter().enumerate() {
            out[i] = Self::variable(y[i], j);
        }
        out
    }

    /// A value with given partials (an input whose derivatives are known,
    /// such as a forcing's rate of change).
    #[inline]
    pub(crate) fn with_partials(v: f64, d: [f64; D]) -> Self {
        Self { v, d }
    }

    #[inline(always)]
    fn map(self, v: f64, f: impl Fn(f64) -> f64) -> Self {
        Self { v, d: self.d.map(f) }
    }

    #[inline(always)]
    fn zip(self, o: Self, v: f64, f: impl Fn(f64, f64) -> f64) -> Self {
        Self {
            v,
            d: std::array::from_fn(|i| f(self.d[i], o.d[i])),
        }
    }
}

impl<const D: usize> Add for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.zip(o, self.v + o.v, |a, b| a + b)
    }
}

impl<const D: usize> Sub for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.zip(o, self.v - o.v, |a, b| a - b)
    }
}

impl<const D: usize> Mul for Dual<D> {
    type Output = Self;
    /// The product rule.
    #[inline(always)]
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn mul(self, o: Self) -> Self {
        self.zip(o, self.v * o.v, |a, b| a * o.v + self.v * b)
    }
}

impl<const D: usize> Div for Dual<D> {
    type Output = Self;
    /// (a/b)' = (a' − (a/b) b')/b.
    #[inline(always)]
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        self.zip(o, q, |a, b| (a - q * b) / o.v)
    }
}

impl<const D: usize> Neg for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(-self.v, |a| -a)
    }
}

impl<const D: usize> Add<f64> for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn add(self, c: f64) -> Self {
        Self { v: self.v + c, ..self }
    }
}

impl<const D: usize> Sub<f64> for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, c: f64) -> Self {
        Self { v: self.v - c, ..self }
    }
}

impl<const D: usize> Mul<f64> for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, c: f64) -> Self {
        self.map(self.v * c, |a| a * c)
    }
}

impl<const D: usize> Div<f64> for Dual<D> {
    type Output = Self;
    #[inline(always)]
    fn div(self, c: f64) -> Self {
        self.map(self.v / c, |a| a / c)
    }
}

impl<const D: usize> Scalar for Dual<D> {
    #[inline(always)]
    fn value(self) -> f64 {
        self.v
    }

    #[inline(always)]
    fn constant(self, c: f64) -> Self {
        Self::constant(c)
    }

    #[inline(always)]
    fn sin_cos_from(self, sin: f64, cos: f64) -> (Self, Self) {
        (self.map(sin, |a| cos * a), self.map(cos, |a| -sin * a))
    }
}
