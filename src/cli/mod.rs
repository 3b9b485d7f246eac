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
pub(crate) mod eng_motion;
pub mod error;
mod exponents;
pub mod flags;
pub mod fragility;
pub mod interrupt;
pub mod map;
pub mod merge;
pub mod progress;
pub mod pulse_map;
pub mod reproduce;
pub mod sliding_spectrum;
pub mod spectrum;
pub mod stack_batch;
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

/// The subcommands. Their arguments are built only for the one that is
/// used (`defer`, completed by [`Cli::command_deferred`]).
#[derive(Debug, Subcommand)]
#[command(defer = true)]
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
    /// Sliding spectrum: peak and residual sliding displacement against the
    /// friction coefficient under one record or pulse, for a block that
    /// cannot rock and for the given block (sliding_spectrum.csv/json/png/svg).
    SlidingSpectrum(sliding_spectrum::SlidingSpectrumArgs),
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

impl Cli {
    /// Parses the process's arguments: what `Cli::parse()` does (the same
    /// help, errors and exit codes), with each subcommand's arguments built
    /// only when it is the one used. `rocking --batch`, which a scripted
    /// sweep starts once per point, then does not build the hundred-odd
    /// arguments of the subcommands at every start (about 0.2 ms of the
    /// process's CPU time).
    pub fn parse_deferred() -> Self {
        use clap::FromArgMatches as _;
        let mut matches = Self::command_deferred().get_matches();
        match Self::from_arg_matches_mut(&mut matches) {
            Ok(cli) => cli,
            Err(e) => e.format(&mut Self::command_deferred()).exit(),
        }
    }

    /// The command line's definition with its subcommands deferred. clap's
    /// derived `defer` would apply an arguments struct's own doc comment
    /// ("Arguments of `rocking sweep`") after the variant's, so each
    /// subcommand is deferred here again, keeping the variant's about.
    pub(crate) fn command_deferred() -> clap::Command {
        use clap::CommandFactory as _;
        /// Adds `A`'s arguments to subcommand `cmd`, keeping its about.
        fn augment<A: clap::Args>(cmd: clap::Command) -> clap::Command {
            use clap::builder::Resettable;
            let reset =
                |text: Option<&clap::builder::StyledStr>| text.cloned().map_or(Resettable::Reset, Resettable::Value);
            let (about, long_about) = (reset(cmd.get_about()), reset(cmd.get_long_about()));
            A::augment_args(cmd).about(about).long_about(long_about)
        }
        /// Builds one subcommand's arguments.
        type Augment = fn(clap::Command) -> clap::Command;
        let deferred: [(&str, Augment); 9] = [
            ("sweep", augment::<sweep::SweepArgs>),
            ("merge", augment::<merge::MergeArgs>),
            ("spectrum", augment::<spectrum::SpectrumArgs>),
            ("sliding-spectrum", augment::<sliding_spectrum::SlidingSpectrumArgs>),
            ("pulse-map", augment::<pulse_map::PulseMapArgs>),
            ("fragility", augment::<fragility::FragilityArgs>),
            ("map", augment::<map::MapArgs>),
            ("reproduce", augment::<reproduce::ReproduceArgs>),
            ("bench", augment::<bench::BenchArgs>),
        ];
        deferred.into_iter().fold(Self::command(), |cli, (name, f)| {
            cli.mut_subcommand(name, |c| c.defer(f))
        })
    }
}

impl Command {
    /// Runs the subcommand.
    pub fn run(&self) -> Result<(), error::BatchError> {
        match self {
            Command::Sweep(args) if args.output.lyapunov => {
                sweep::run_with(args, Some(&lyapunov::largest_for_scenario))
            }
            Command::Sweep(args) => sweep::run(args),
            Command::Merge(args) if fragility::are_fragility_shards(&args.shards) => fragility::merge(args),
            Command::Merge(args) => merge::run(args),
            Command::Spectrum(args) => spectrum::run(args),
            Command::SlidingSpectrum(args) => sliding_spectrum::run(args),
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
pub fn report(e: &error::BatchError) -> i32 {
    let (e, code) = match e {
        error::BatchError::Input(e) => (e, EXIT_BAD_INPUT),
        error::BatchError::Run(e) => (e, EXIT_RUN_FAILED),
    };
    eprintln!("error: {e:#}");
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every subcommand is deferred with its own arguments, and its help
    /// starts with the variant's text, as without deferring.
    #[test]
    fn deferred_subcommands_keep_their_arguments_and_about() {
        let mut cmd = Cli::command_deferred();
        let before: Vec<(String, Option<String>, Option<String>)> = cmd
            .get_subcommands()
            .map(|c| {
                (
                    c.get_name().to_string(),
                    c.get_about().map(ToString::to_string),
                    c.get_long_about().map(ToString::to_string),
                )
            })
            .collect();
        assert_eq!(before.len(), 9);
        cmd.build();
        cmd.clone().debug_assert();
        for (name, about, long_about) in before {
            let sub = cmd.find_subcommand(&name).unwrap();
            assert!(about.is_some(), "{name}");
            assert_eq!(sub.get_about().map(ToString::to_string), about, "{name}");
            assert_eq!(sub.get_long_about().map(ToString::to_string), long_about, "{name}");
            assert!(
                sub.get_arguments().any(|a| a.get_long() == Some("out")),
                "{name} has no --out"
            );
        }
    }
}
