//! The integration methods a run can choose ([`Method`]), and the one place
//! a method becomes a stepper: [`with_stepper`] calls a
//! [`StepperVisitor`] with the stepper of the method chosen at run time, so
//! the batch run ([`super::simulate`]) and the live session
//! ([`super::runner`]) choose it alike and stay monomorphised over it.

use serde::Serialize;

use crate::integrate::{Dop853, Dopri5, Ralston, Stepper, Taylor, Tolerances};
use crate::model::state::N;

/// Integration method (config `run.method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Dormand–Prince 8(5,3) with 7th-order dense output (the default at
    /// loose tolerances, [`Method::default_for`]).
    Dop853,
    /// Dormand–Prince 5(4) with 4th-order dense output.
    Dopri5,
    /// The paper's Ralston RK2, fixed step 0.004, step cut by 10 at a sign
    /// change until |Θ| < 1e-6.
    Ralston,
    /// Taylor series of high order ([`Taylor`]), DOP853 where the
    /// excitation has no series (pulses, records); the default at tight
    /// tolerances ([`Method::default_for`]).
    Taylor,
}

/// The loosest rtol at which the default method is the Taylor method.
pub const TAYLOR_DEFAULT_RTOL: f64 = 1e-6;

impl Method {
    /// The method a run takes when the config names none, chosen by
    /// tolerance as DifferentialEquations.jl chooses its default: the Taylor
    /// method at rtol ≤ [`TAYLOR_DEFAULT_RTOL`] (the default rtol is 1e-10),
    /// where it is the fastest on every scene of `rocking bench` (the
    /// paper's sweep point 6.0 ms against DOP853's 9.6, the app's default
    /// scene 103,000 τ/s against 63,000, docs/performance.md); DOP853 at
    /// looser tolerances, where the minimum order of a Taylor series
    /// (8) makes its steps no cheaper and DOP853 is up to 1.3× faster at
    /// the same error. For excitations without a series (pulses, records)
    /// the Taylor method takes DOP853's steps anyway.
    pub fn default_for(rtol: f64) -> Self {
        if rtol <= TAYLOR_DEFAULT_RTOL {
            Method::Taylor
        } else {
            Method::Dop853
        }
    }

    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Dop853 => "dop853",
            Method::Dopri5 => "dopri5",
            Method::Ralston => "ralston",
            Method::Taylor => "taylor",
        }
    }
}

/// What to do with the stepper of a method (a generic closure, which Rust
/// spells as a trait).
pub(crate) trait StepperVisitor {
    /// What the visit returns.
    type Output;

    /// Called once, with the stepper.
    fn visit<S: Stepper<N> + Send + 'static>(self, stepper: S) -> Self::Output;
}

/// Calls `visitor` with a new stepper of `method` at tolerances `tol` (and
/// `tol.h_fixed` for Ralston's fixed step).
pub(crate) fn with_stepper<V: StepperVisitor>(method: Method, tol: Tolerances, visitor: V) -> V::Output {
    match method {
        Method::Dop853 => visitor.visit(Dop853::new(tol)),
        Method::Dopri5 => visitor.visit(Dopri5::new(tol)),
        Method::Ralston => visitor.visit(Ralston::new(tol)),
        Method::Taylor => visitor.visit(Taylor::new(tol)),
    }
}
