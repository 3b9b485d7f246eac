//! Runs a block model with a chosen method and collects its outputs.
//!
//! This layer connects a concrete [`Model`](crate::model::Model) to a
//! [`Stepper`](crate::integrate::Stepper) through the hybrid driver. It
//! knows nothing of files or windows.

mod collect;
pub mod protocol;
mod run;
pub mod runner;

pub use collect::{HistoryRow, SectionRow};
pub use run::{EnergyAudit, InitialState, Method, Outcome, RunOptions, RunResult, SimError, initial_mode, simulate};
