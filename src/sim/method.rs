//! The one place a [`Method`] becomes a stepper: [`with_stepper`] calls a
//! [`StepperVisitor`] with the stepper of the method chosen at run time, so
//! the batch run ([`super::simulate`]) and the live session
//! ([`super::runner`]) choose it alike and stay monomorphised over it.

use super::Method;
use crate::integrate::{Dop853, Dopri5, Ralston, Stepper, Taylor, Tolerances};
use crate::model::state::N;

/// What to do with the stepper of a method (a generic closure, which Rust
/// spells as a trait).
pub trait StepperVisitor {
    /// What the visit returns.
    type Output;

    /// Called once, with the stepper.
    fn visit<S: Stepper<N> + Send + 'static>(self, stepper: S) -> Self::Output;
}

/// Calls `visitor` with a new stepper of `method` at tolerances `tol` (and
/// `tol.h_fixed` for Ralston's fixed step).
pub fn with_stepper<V: StepperVisitor>(method: Method, tol: Tolerances, visitor: V) -> V::Output {
    match method {
        Method::Dop853 => visitor.visit(Dop853::new(tol)),
        Method::Dopri5 => visitor.visit(Dopri5::new(tol)),
        Method::Ralston => visitor.visit(Ralston::new(tol)),
        Method::Taylor => visitor.visit(Taylor::new(tol)),
    }
}
