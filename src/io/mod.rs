//! Files in and out: the configuration (TOML, presets, `--set`), recorded
//! ground motions (`record`), and the CSV/JSON outputs of a run. Every output carries the resolved
//! configuration and the crate version.

pub mod config;
pub mod output;
pub mod presets;
pub mod record;
pub mod table;

pub use config::{Config, load};
pub use table::ConfigError;
