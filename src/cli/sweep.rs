//! `rocking sweep`: the bifurcation diagram of one parameter.
//!
//! Writes into `--out`:
//! - `points.csv`: `value,k,tau,theta,theta_dot`, every Poincaré point at
//!   τ_k ≥ transient, values increasing (none for tumbled or flight values);
//! - `classes.csv`: `value,outcome,period,max_abs_theta,lyapunov`, one row
//!   per value; `period` only for `periodic` (the paper's (1,period) mode),
//!   `lyapunov` empty unless an exponent was computed;
//! - `sweep.json`: the base configuration, the sweep (parameter, grid,
//!   window, continuation, shard, classifier thresholds) and the crate
//!   version — what `rocking merge` checks shards against;
//! - `bifurcation.png`, `bifurcation.svg` (not for a shard: the merge draws
//!   them).
//!
//! Bad input exits 2 with a one-line error naming the flag or key, before
//! anything runs or is written; the directory appears whole or not at all.

use std::time::Instant;

use anyhow::Context as _;
use indicatif::ProgressBar;
use serde_json::{Value as Json, json};

use super::args::{SceneArgs, StudyArgs, StudyOutput};
use super::error::BatchError;
use super::flags::Flags;
use crate::analysis::Progress;
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::orbit_diagram::{
    BlockSweep, Continuation, Grid, Plan, PlanError, Shard, block_sweep, response_ranges,
};
use crate::analysis::steady::{LyapunovFn, Window};
use crate::io::config::{self, to_json};
use crate::io::output;
use crate::io::sweep_files::{classes_csv, points_csv};
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::labels::{
    fixed_parameters, grid_decimals, grid_num, num, param_label, param_symbol, section_theta, section_units,
};
use crate::sim::{Param, Scenario};

/// Continuation as a command-line value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ContinuationArg {
    /// Every value from the configuration's initial state (parallel).
    None,
    /// Each value from the previous smaller value's final state.
    Up,
    /// Each value from the previous larger value's final state.
    Down,
}

impl From<ContinuationArg> for Continuation {
    fn from(c: ContinuationArg) -> Self {
        match c {
            ContinuationArg::None => Continuation::None,
            ContinuationArg::Up => Continuation::Up,
            ContinuationArg::Down => Continuation::Down,
        }
    }
}

/// Arguments of `rocking sweep`.
#[derive(Debug, Clone, clap::Args)]
pub struct SweepArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The config key swept, e.g. excitation.a_v.
    #[arg(long, value_name = "KEY")]
    pub param: String,
    /// First value.
    #[arg(long, value_name = "A", allow_negative_numbers = true)]
    pub from: f64,
    /// Last value (included within half a step).
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    pub to: f64,
    /// Spacing of the values (> 0); value i is A + i·S on the decimal grid
    /// as typed (2.3, not 2.3000000000000003).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub step: f64,
    /// Window and threads.
    #[command(flatten)]
    pub study: StudyArgs,
    /// Seed each value from the previous one's final state, sweeping up or
    /// down (sequential), or not at all (parallel).
    #[arg(long, value_enum, default_value = "none")]
    pub continuation: ContinuationArg,
    /// Compute only values i with i mod N = K (K from 0), for cluster array
    /// jobs; join the shards with `rocking merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Output folder, Lyapunov exponents, quiet.
    #[command(flatten)]
    pub output: StudyOutput,
}

/// Everything about a sweep except its results: what `sweep.json` records
/// and what the figure's titles are made from.
#[derive(Clone, Debug)]
pub(crate) struct SweepMeta {
    /// The swept parameter.
    pub param: Param,
    /// Its values.
    pub grid: Grid,
    /// Seeding.
    pub continuation: Continuation,
    /// Transient and run end.
    pub window: Window,
    /// Classifier thresholds.
    pub classify: ClassifyOptions,
    /// The base scenario (run.tau_end set to the window's end).
    pub config: Scenario,
}

impl SweepMeta {
    /// `sweep.json` for this sweep and `shard` (keys sorted, so the text is
    /// a function of the content).
    pub fn to_json(&self, shard: Option<Shard>) -> Json {
        json!({
            "command": "rocking sweep",
            "version": env!("CARGO_PKG_VERSION"),
            "param": self.param.key(),
            "grid": self.grid,
            "continuation": self.continuation,
            "shard": shard,
            "window": self.window,
            "classify": self.classify,
            "config": to_json(&self.config),
            "units": format!("tau = p t, {}; lyapunov per unit τ; config: the base configuration, `param` takes each value in turn", section_units(&self.config)),
        })
    }

    /// The bifurcation figure of `values` (responses) and `points` (value, Θ).
    pub fn figure<'a>(&self, values: &'a [(f64, Response)], points: &'a [(f64, f64)]) -> BifurcationFigure<'a> {
        let sym = param_symbol(self.param);
        let d = grid_decimals(self.grid.from, self.grid.step);
        let seeding = match self.continuation {
            Continuation::None => "every value from the initial state".to_string(),
            Continuation::Up => "continuation upwards".to_string(),
            Continuation::Down => "continuation downwards".to_string(),
        };
        BifurcationFigure {
            title: format!(
                "Bifurcation diagram over {sym}: {}",
                fixed_parameters(&self.config, &[self.param])
            ),
            subtitle: format!(
                "Θ at τ_k = 2πk/Ω_h for {} ≤ τ_k ≤ {}; {sym} = {} … {} step {}; {seeding}",
                num(self.window.transient),
                num(self.window.tau_end),
                grid_num(self.grid.from, d),
                grid_num(self.grid.value(self.grid.count - 1), d),
                num(self.grid.step)
            ),
            x_label: param_label(self.param),
            y_label: section_theta(&self.config),
            values,
            points,
            step: self.grid.step,
        }
    }
}

/// A progress bar on stderr: drawn on a terminal, a line every few
/// seconds in a log ([`super::progress::bar`]), nothing when quiet.
pub(crate) fn progress_bar(len: usize, what: &str, quiet: bool) -> ProgressBar {
    super::progress::bar(len, what, quiet)
}

/// The analyses' progress callback drawing on `bar`.
pub(crate) fn progress_fn(bar: &ProgressBar) -> impl Fn(Progress) + Sync + '_ {
    move |p| match p {
        Progress::Total(n) => bar.set_length(n),
        Progress::Done => bar.inc(1),
    }
}

/// Most worker threads per core: sweep values are CPU-bound, so threads
/// beyond the cores only add switching; a few per core is room for a user
/// who oversubscribes on purpose.
pub const MAX_THREADS_PER_CORE: usize = 4;

/// A rayon pool of `threads` workers (default: one per core), named.
pub(crate) fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, BatchError> {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let most = MAX_THREADS_PER_CORE * cores;
    match threads {
        Some(0) => return Err(BatchError::Input(anyhow::anyhow!("--threads 0: must be >= 1"))),
        Some(n) if n > most => {
            return Err(BatchError::Input(anyhow::anyhow!(
                "--threads {n}: at most {most} ({MAX_THREADS_PER_CORE} per core on {cores} cores); more only adds switching"
            )));
        }
        _ => {}
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .thread_name(|i| format!("sweep-{i}"))
        .build()
        .context("starting the worker threads")
        .map_err(BatchError::Run)
}

fn input(e: impl Into<anyhow::Error>) -> BatchError {
    BatchError::Input(e.into())
}

/// A sweep's definition refused, its inputs named by their flags.
pub(crate) fn plan_input(e: PlanError) -> BatchError {
    BatchError::Input(anyhow::anyhow!(e.render(&Flags)))
}

/// Everything `run` checked and resolved before computing.
struct Prepared {
    base: Scenario,
    meta: SweepMeta,
    plan: Plan,
    shard: Option<Shard>,
}

fn prepare(args: &SweepArgs) -> Result<Prepared, BatchError> {
    let base = args.scene.load().map_err(input)?;
    let param = config::param(&args.param).map_err(|e| input(anyhow::anyhow!("--param {e}")))?;
    if param == Param::TauEnd {
        return Err(input(anyhow::anyhow!(
            "--param run.tau_end: the run length is set by --tau-end, it cannot be swept"
        )));
    }
    let continuation = Continuation::from(args.continuation);
    if continuation != Continuation::None && matches!(param, Param::Theta0 | Param::ThetaDot0 | Param::XDot0) {
        return Err(input(anyhow::anyhow!(
            "--param {}: continuation replaces the initial state, so an initial.* key cannot be swept with --continuation {}",
            args.param,
            continuation.name()
        )));
    }
    let grid = Grid::new(args.from, args.to, args.step).map_err(plan_input)?;
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()
        .map_err(plan_input)?;
    let plan = Plan::new(grid, continuation, shard).map_err(plan_input)?;
    let mut config = base.clone();
    let window = args.study.window(&base).map_err(|e| input(anyhow::anyhow!(e)))?;
    config.run.tau_end = window.tau_end;
    let meta = SweepMeta {
        param,
        grid,
        continuation,
        window,
        classify: ClassifyOptions::default(),
        config,
    };
    Ok(Prepared {
        base,
        meta,
        plan,
        shard,
    })
}

/// Runs `rocking sweep` without Lyapunov exponents.
pub fn run(args: &SweepArgs) -> Result<(), BatchError> {
    run_with(args, None)
}

/// Runs `rocking sweep`; `lyapunov`, if given, fills the `lyapunov` column
/// and decides between quasiperiodic and chaotic.
pub(crate) fn run_with(args: &SweepArgs, lyapunov: Option<&LyapunovFn<'_>>) -> Result<(), BatchError> {
    let Prepared {
        base,
        meta,
        plan,
        shard,
    } = prepare(args)?;
    let spec = BlockSweep {
        base: &base,
        param: meta.param,
        window: meta.window,
        classify: meta.classify,
        lyapunov,
    };
    spec.scenarios(&plan).map_err(|e| {
        input(anyhow::anyhow!(
            "--param {} = {}: {}",
            meta.param.key(),
            e.value,
            e.error.render(&Flags)
        ))
    })?;
    let pool = thread_pool(args.study.threads)?;
    output::check_writable(&args.output.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(BatchError::Input)?;

    let start = Instant::now();
    let bar = progress_bar(plan.indices().len(), "values", args.output.quiet);
    let values = pool
        .install(|| block_sweep(&spec, &plan, &progress_fn(&bar)))
        .map_err(|e| {
            let message = anyhow::anyhow!("{} = {}: {}", meta.param.key(), e.value, e.error.render(&Flags));
            BatchError::of(message, e.error.is_input())
        })?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();

    super::write::staged(&args.output.out, |staging| {
        let (classes, points) = (classes_csv(&values), points_csv(&values));
        let mut json = meta.to_json(shard);
        if shard.is_some()
            && let Some(obj) = json.as_object_mut()
        {
            // What makes a shard checkable by `merge`: each file's rows and
            // CRC-32, so a cut or changed file is noticed.
            obj.insert(
                "files".to_string(),
                serde_json::json!({
                    "classes.csv": file_check(&classes),
                    "points.csv": file_check(&points),
                }),
            );
        }
        staging.text("classes.csv", &classes)?;
        staging.text("points.csv", &points)?;
        staging.text("sweep.json", &(serde_json::to_string_pretty(&json)? + "\n"))?;
        if shard.is_none() {
            let classes: Vec<(f64, Response)> = values.iter().map(|v| (v.value, v.response)).collect();
            let points: Vec<(f64, f64)> = values
                .iter()
                .flat_map(|v| v.points.iter().map(move |p| (v.value, p.theta)))
                .collect();
            let fig = meta.figure(&classes, &points);
            super::write::figure(staging, "bifurcation", &fig)?;
        }
        Ok(())
    })?;

    if !args.output.quiet {
        let npoints: usize = values.iter().map(|v| v.points.len()).sum();
        let d = grid_decimals(meta.grid.from, meta.grid.step);
        crate::say!(
            "swept {} = {} … {} ({} values{}) in {wall:.1} s; {npoints} Poincaré points",
            meta.param.key(),
            grid_num(meta.grid.from, d),
            grid_num(meta.grid.value(meta.grid.count - 1), d),
            values.len(),
            shard.map_or(String::new(), |s| format!(", shard {}/{}", s.index, s.count)),
        );
        let pairs: Vec<(f64, Response)> = values.iter().map(|v| (v.value, v.response)).collect();
        for r in response_ranges(&pairs) {
            crate::say!("  {} … {}: {}", grid_num(r.from, d), grid_num(r.to, d), r.response);
        }
        crate::say!("wrote {}", args.output.out.display());
    }
    Ok(())
}

/// A shard file's check for `sweep.json`: its data rows (lines after the
/// header) and the CRC-32 of its bytes, as 8 hex digits.
pub(crate) fn file_check(text: &str) -> serde_json::Value {
    serde_json::json!({
        "rows": text.lines().count().saturating_sub(1),
        "crc32": format!("{:08x}", crc32fast::hash(text.as_bytes())),
    })
}
