//! Automatic differentiation for equations written once over a generic
//! [`Scalar`]: the same code evaluated over `f64` gives the value, over
//! [`Dual`] numbers its partial derivatives (forward mode), and over
//! [`Jet`]s on a [`Tape`] its Taylor coefficients (Moore's recurrences).
//!
//! Contract: nothing here knows a model. A model writes its vector field as
//! a function generic over `S: Scalar`, using only the arithmetic below and
//! [`Scalar::sin_cos_from`]; evaluated over `f64` that function compiles to
//! the same operations, in the same order, as if written for `f64` alone,
//! so writing the equations generically changes no bit of a run.
//!
//! Mixed operations take the constant on the right (`x * 2.0`, not
//! `2.0 * x`): IEEE multiplication and addition are commutative, so
//! `x * c` has the bits of `c * x`, while a generic `f64 * S` would need a
//! bound on `f64` that every caller repeats.

mod dual;
mod jet;

use std::ops::{Add, Div, Mul, Neg, Sub};

pub use dual::Dual;
pub use jet::{Jet, Tape};

/// A number the equations of a model can be written over.
pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// The value (the `f64` itself, a dual's real part, a jet's constant
    /// coefficient): what a model may branch on to pick a formula for its
    /// value, never to pick which operations it performs on `Self`.
    fn value(self) -> f64;

    /// The constant `c` as a number of the same kind as `self` (on the same
    /// tape for a jet): zero derivatives, a series with one term.
    fn constant(self, c: f64) -> Self;

    /// The sine and cosine of `self`, given `sin` and `cos` of its value.
    ///
    /// The caller computes the value's sine and cosine however it prefers
    /// (a short series for small angles, an angle-sum identity); the
    /// derivatives and series follow from `(sin x)' = cos x · x'` and
    /// `(cos x)' = −sin x · x'`.
    fn sin_cos_from(self, sin: f64, cos: f64) -> (Self, Self);

    /// The sine and cosine of `self`, by the library's `sin_cos` of its value.
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        let (sin, cos) = self.value().sin_cos();
        self.sin_cos_from(sin, cos)
    }
}

impl Scalar for f64 {
    #[inline(always)]
    fn value(self) -> f64 {
        self
    }

    #[inline(always)]
    fn constant(self, c: f64) -> Self {
        c
    }

    #[inline(always)]
    fn sin_cos_from(self, sin: f64, cos: f64) -> (Self, Self) {
        (sin, cos)
    }
}

#[cfg(test)]
mod tests;
