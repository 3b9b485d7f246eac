//! Runs a block model with a chosen method and collects its outputs.
//!
//! This layer holds the typed [`Scenario`] (what to run, validated once) and
//! the typed [`Param`]s that analyses vary, and connects a concrete
//! [`Model`](crate::model::Model) to a
//! [`Stepper`](crate::integrate::Stepper) through the hybrid driver. It
//! knows nothing of files, config keys read from text, or windows.

pub mod answer;
pub mod catalogue;
mod collect;
mod end_state;
pub mod job;
pub mod method;
pub mod protocol;
mod run;
pub mod runner;
pub mod scenario;
pub mod stack_answer;
mod stack_rules;
pub mod stack_run;
mod validate;

pub use answer::Physical;
pub use catalogue::Param;
pub use collect::{HistoryRow, Keep, SectionRow, Sink, Tallies};
pub use end_state::EndState;
pub use method::{Method, TAYLOR_DEFAULT_RTOL};
pub use run::{
    EnergyAudit, InitialState, Outcome, RunOptions, RunResult, SimError, initial_mode, simulate, simulate_into,
};
pub use scenario::{Scenario, ScenarioError};
