//! Numerical integration methods. This layer knows nothing about blocks.
//!
//! Contract:
//! - States are fixed-size `[f64; N]` arrays; no stepping loop allocates.
//! - A [`Stepper`] advances one accepted step at a time and exposes dense
//!   output over that step (the scipy `OdeSolver.step` pattern). It knows
//!   nothing of events.
//! - The [`hybrid`] driver owns the non-smooth logic: guards, root finding,
//!   reset maps and restarts.
//! - Non-finite states are reported as [`StepError::NonFinite`], never passed on.

mod controller;
pub mod dop853;
mod dop853_tableau;
pub mod dopri5;
pub mod embedded;
pub mod hybrid;
pub mod ralston;
pub mod root;
mod stages;
pub mod stepper;
#[cfg(test)]
mod stepper_checks;
pub mod taylor;

pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use ralston::Ralston;
pub use stepper::{Rhs, StepError, StepStats, Stepper, Tolerances};
pub use taylor::Taylor;
