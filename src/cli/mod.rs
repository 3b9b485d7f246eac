//! The `rocking` command line: `--batch` runs one simulation headless;
//! the subcommands `sweep`, `merge` and `map` run the analyses headless.

/// `println!` that never panics: a closed stdout (`rocking … | head`) is
/// not an error of the run, so write failures are ignored.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

use crate::analysis::lyapunov;

pub mod args;
pub mod batch;
pub mod bench;
pub mod eng_args;
pub mod fragility;
pub mod interrupt;
pub mod map;
pub mod merge;
pub mod progress;
pub mod pulse_map;
pub mod reproduce;
pub mod spectrum;
pub mod suite;
pub mod sweep;
pub mod write;

use std::path::PathBuf;

use clap::{Parser, Subcommand};

/// Exit code for bad input (config, files, arguments), as clap uses.
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for a run that failed after its input was accepted.
pub const EXIT_RUN_FAILED: i32 = 1;

/// rocking — exact simulator of a rigid block that rocks, slides,
/// slide-rocks, lifts off and tumbles on a shaken base.
#[derive(Debug, Parser)]
#[command(
    name = "rocking",
    version,
    about,
    long_about = None,
    args_conflicts_with_subcommands = true,
    after_help = "With no --batch and no subcommand, rocking opens the desktop app on the scene \
                  (the `default` preset unless --preset, --config or --set say otherwise). Without a \
                  display, run the same scene headless: rocking --batch --preset default --out out"
)]
pub struct Cli {
    /// Run one simulation without a window and write summary.json,
    /// events.csv, poincare.csv and history.csv into --out.
    #[arg(long)]
    pub batch: bool,
    /// The scene (for --batch and the app).
    #[command(flatten)]
    pub scene: args::SceneArgs,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// List the presets and exit.
    #[arg(long)]
    pub list_presets: bool,
    /// Open the app paused on its first frame (Space plays): for a lecture
    /// that starts with the question "what will it do?".
    #[arg(long, conflicts_with = "batch")]
    pub paused: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// A headless analysis instead of `--batch` or the window.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Bifurcation diagram: sweep one config key, classify each value's
    /// steady response and collect its Poincaré points (points.csv,
    /// classes.csv, sweep.json, bifurcation.png/svg).
    Sweep(sweep::SweepArgs),
    /// Join the shards of a `sweep --shard K/N` or a `fragility --shard K/N`
    /// into the files one run writes.
    Merge(merge::MergeArgs),
    /// Rocking spectrum: peak θ/α and overturning of a range of block sizes
    /// under one record or pulse, optionally each block's smallest
    /// overturning scale (spectrum.csv, spectrum.json, spectrum.png/svg).
    Spectrum(spectrum::SpectrumArgs),
    /// Pulse overturning map: the smallest a_p/(g tan α) that overturns a
    /// block against ω_p/p, for one-sine, one-cosine and type-C pulses
    /// (pulse_map.csv/json/png/svg).
    PulseMap(pulse_map::PulseMapArgs),
    /// Fragility curves: a suite of records scaled to intensity levels, the
    /// fraction of blocks overturned per level and a lognormal fit by
    /// maximum likelihood (runs.csv, fractions.csv, fragility.json/png/svg).
    Fragility(fragility::FragilityArgs),
    /// Outcome map over two config keys (map.csv, map.png/svg, map.json).
    Map(map::MapArgs),
    /// Recompute every figure of the paper (Figs. 3–19) and write them with
    /// report.md, which sets each beside the paper's statements.
    Reproduce(reproduce::ReproduceArgs),
    /// Work–precision benchmark: run time against error for every method
    /// (work_precision.json/.csv/.png/.svg).
    Bench(bench::BenchArgs),
}

impl Command {
    /// Runs the subcommand.
    pub fn run(&self) -> Result<(), batch::BatchError> {
        match self {
            Command::Sweep(args) if args.output.lyapunov => {
                sweep::run_with(args, Some(&lyapunov::largest_for_scenario))
            }
            Command::Sweep(args) => sweep::run(args),
            Command::Merge(args) if fragility::are_fragility_shards(&args.shards) => fragility::merge(args),
            Command::Merge(args) => merge::run(args),
            Command::Spectrum(args) => spectrum::run(args),
            Command::PulseMap(args) => pulse_map::run(args),
            Command::Fragility(args) => fragility::run(args),
            Command::Map(args) if args.output.lyapunov => map::run_with(args, Some(&lyapunov::largest_for_scenario)),
            Command::Map(args) => map::run(args),
            Command::Reproduce(args) => reproduce::run(args),
            Command::Bench(args) => bench::run(args),
        }
    }
}

/// Prints `error: …` for a failed command and returns its exit code
/// ([`EXIT_BAD_INPUT`] or [`EXIT_RUN_FAILED`]).
pub fn report(e: &batch::BatchError) -> i32 {
    let (e, code) = match e {
        batch::BatchError::Input(e) => (e, EXIT_BAD_INPUT),
        batch::BatchError::Run(e) => (e, EXIT_RUN_FAILED),
    };
    eprintln!("error: {e:#}");
    code
}
