//! The `rocking` command line: `--batch` runs one simulation headless.

pub mod batch;

use std::path::PathBuf;

use clap::Parser;

/// Exit code for bad input (config, files, arguments), as clap uses.
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for a run that failed after its input was accepted.
pub const EXIT_RUN_FAILED: i32 = 1;

/// rocking — exact simulator of a rigid block that rocks, slides,
/// slide-rocks, lifts off and tumbles on a shaken base.
#[derive(Debug, Parser)]
#[command(name = "rocking", version, about, long_about = None)]
pub struct Cli {
    /// Run one simulation without a window and write summary.json,
    /// events.csv, poincare.csv and history.csv into --out.
    #[arg(long)]
    pub batch: bool,
    /// A preset from assets/presets (default, fig3 … fig19).
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// A config file: TOML, or a summary.json to repeat its run.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Override one key, e.g. --set excitation.a_v=2.5 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// List the presets and exit.
    #[arg(long)]
    pub list_presets: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}
