//! Files in and out: the configuration (TOML, presets, `--set`, a previous
//! `summary.json`) read into a typed [`Scenario`](crate::sim::Scenario),
//! recorded ground motions (`record`: PEER `.AT2` and two-column text), and
//! the CSV/JSON outputs of a run. Every output carries the resolved
//! configuration and the crate version.
//!
//! `io` imports `sim` (to build scenarios and write results); `sim` never
//! imports `io`.

pub mod config;
pub mod csv;
pub mod engineering_files;
pub mod output;
pub mod output_error;
pub mod presets;
pub mod record;
mod resolved;
pub mod shipped;
pub mod sliding_files;
pub mod stack_files;
pub mod staging;
pub mod sweep_files;

pub use config::{ConfigError, load};
