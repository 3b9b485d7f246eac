//! `sweep`: the CLI's `rocking sweep` over the library's analyses,
//! checked with the CLI's messages, computed in chunks without the GIL on
//! all cores, with Ctrl-C checked between chunks, and returned as columns
//! (numpy arrays); and what `sweep` and `outcome_map` ([`crate::map`])
//! share: the workers, the window, the checkpoint between chunks.
//!
//! Chunks never change a number: a sweep without continuation is computed
//! as shards of its grid (the mechanism of `rocking sweep --shard K/N`),
//! and every value depends only on its own index.

use anyhow::anyhow;
use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::analysis::classify::{ClassifyOptions, Response};
use rocking::analysis::lyapunov::largest_for_scenario;
use rocking::analysis::orbit_diagram::{
    BifurcationValue, BlockSweep, Continuation, Grid, Plan, PlanError, Shard, SweepError, block_sweep,
};
use rocking::analysis::silent;
use rocking::analysis::steady::{LyapunovFn, SteadyError, Window, steady_response};
use rocking::io::config;
use rocking::sim::{InitialState, Param, Scenario};

use crate::errors::{SWEEP_ARGS, config_error, key_error, run_error, with_python_args};
use crate::names::Keywords;
use crate::scene::Scene;

/// Most worker threads per core, as the CLI allows (`--threads`).
const MAX_THREADS_PER_CORE: usize = 4;

/// Bad input without a key (a flag's value).
pub fn input(message: impl std::fmt::Display) -> PyErr {
    config_error(message.to_string(), crate::errors::Origin::default())
}

/// Between two chunks of a long call, with the GIL taken back for a
/// moment: Ctrl-C (the pending KeyboardInterrupt, or another signal
/// handler's error), then `progress(done, total)` if given (an error it
/// raises stops the call too).
pub fn checkpoint(progress: Option<&Py<PyAny>>, done: usize, total: usize) -> Result<(), PyErr> {
    Python::attach(|py| {
        py.check_signals()?;
        if let Some(f) = progress {
            f.call1(py, (done, total))?;
        }
        Ok(())
    })
}

/// Where the parallel parts of a computation run: rayon's global pool
/// (one thread per core) or a pool of the asked size. The loop over chunks
/// stays on the calling thread, so that Ctrl-C (delivered to Python's main
/// thread) is seen between chunks.
pub enum Workers {
    Global,
    Pool(rayon::ThreadPool),
}

impl Workers {
    /// `threads` workers (default one per core), checked as the CLI checks
    /// `--threads`.
    pub fn new(threads: Option<usize>) -> PyResult<Self> {
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        let most = MAX_THREADS_PER_CORE * cores;
        match threads {
            None => Ok(Workers::Global),
            Some(0) => Err(input("threads=0: must be >= 1")),
            Some(n) if n > most => Err(input(format!(
                "threads={n}: at most {most} ({MAX_THREADS_PER_CORE} per core on {cores} cores); more only adds switching"
            ))),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .thread_name(|i| format!("rocking-py-{i}"))
                .build()
                .map(Workers::Pool)
                .map_err(|e| run_error(&anyhow!("starting the worker threads: {e}"))),
        }
    }

    /// Runs `f`, whose parallel iterators use these workers.
    pub fn run<T: Send>(&self, f: impl FnOnce() -> T + Send) -> T {
        match self {
            Workers::Global => f(),
            Workers::Pool(pool) => pool.install(f),
        }
    }

    /// Threads available to one chunk.
    pub fn threads(&self) -> usize {
        match self {
            Workers::Global => rayon::current_num_threads(),
            Workers::Pool(pool) => pool.current_num_threads(),
        }
    }
}

/// The window of a study: `transient` and `tau_end` (default: the scene's
/// `run.tau_end`), checked with the CLI's messages.
pub fn window(base: &Scenario, transient: f64, tau_end: Option<f64>) -> PyResult<Window> {
    Window::of_study(base, transient, tau_end).map_err(|e| input(e.render(&Keywords)))
}

/// The hook that fills the `lyapunov` column, as `--lyapunov` does.
pub fn lyapunov_hook(on: bool) -> Option<&'static LyapunovFn<'static>> {
    on.then_some(&largest_for_scenario as &LyapunovFn<'static>)
}

/// Values per chunk between two Ctrl-C checks: enough to keep every
/// thread busy, few enough to answer within a few values' time.
pub fn chunk_len(workers: &Workers) -> usize {
    4 * workers.threads().max(2)
}

/// A parsed `continuation`.
fn continuation(name: &str) -> PyResult<Continuation> {
    match name {
        "none" => Ok(Continuation::None),
        "up" => Ok(Continuation::Up),
        "down" => Ok(Continuation::Down),
        other => Err(input(format!("--continuation {other}: expected none, up or down"))),
    }
}

/// A checked sweep, ready to compute.
struct SweepPlan<'a> {
    spec: BlockSweep<'a>,
    plan: Plan,
}

/// Checks a sweep as `rocking sweep` does, before anything runs.
#[allow(clippy::too_many_arguments)]
fn sweep_plan<'a>(
    base: &'a Scenario,
    key: &str,
    start: f64,
    stop: f64,
    step: f64,
    transient: f64,
    tau_end: Option<f64>,
    continuation_name: &str,
    lyapunov: bool,
    shard: Option<(usize, usize)>,
) -> PyResult<SweepPlan<'a>> {
    let param = config::param(key).map_err(|e| key_error(key, format!("--param {e}")))?;
    if param == Param::TauEnd {
        return Err(key_error(
            key,
            "--param run.tau_end: the run length is set by --tau-end, it cannot be swept",
        ));
    }
    let cont = continuation(continuation_name)?;
    if cont != Continuation::None && matches!(param, Param::Theta0 | Param::ThetaDot0 | Param::XDot0) {
        return Err(key_error(
            key,
            format!(
                "--param {key}: continuation replaces the initial state, so an initial.* key cannot be swept with --continuation {}",
                cont.name()
            ),
        ));
    }
    let plan_input = |e: PlanError| input(e.render(&Keywords));
    let grid = Grid::new(start, stop, step).map_err(plan_input)?;
    let shard = shard
        .map(|(k, n)| Shard::parse(&format!("{k}/{n}")))
        .transpose()
        .map_err(plan_input)?;
    let plan = Plan::new(grid, cont, shard).map_err(plan_input)?;
    let window = window(base, transient, tau_end)?;
    let spec = BlockSweep {
        base,
        param,
        window,
        classify: ClassifyOptions::default(),
        lyapunov: lyapunov_hook(lyapunov),
    };
    spec.scenarios(&plan).map_err(|e| {
        key_error(
            param.key(),
            format!("--param {} = {}: {}", param.key(), e.value, e.error.render(&Keywords)),
        )
    })?;
    Ok(SweepPlan { spec, plan })
}

/// Why a computation stopped: a failed value (the CLI's exit 1), or an
/// exception to pass on as it is (Ctrl-C's KeyboardInterrupt, an error
/// raised by a `progress` callback or a map's executor).
pub enum Stop {
    Failed(anyhow::Error),
    Raised(PyErr),
}

impl Stop {
    pub fn into_py(self) -> PyErr {
        match self {
            Stop::Failed(e) => run_error(&e),
            Stop::Raised(e) => e,
        }
    }
}

/// The message of a failed sweep value, as the CLI prints it.
fn sweep_failure(param: Param, e: &SweepError<SteadyError>) -> Stop {
    Stop::Failed(anyhow!("{} = {}: {}", param.key(), e.value, e.error.render(&Keywords)))
}

/// The values of `sp` with their grid indices, in index order. Without
/// continuation: as shards of the grid, Ctrl-C checked between them
/// (`interruptible`), the first failure in index order reported as the
/// CLI reports it. With continuation: one value after another, seeding
/// each from the one before as `block_sweep` does.
fn compute_sweep(
    sp: &SweepPlan<'_>,
    workers: &Workers,
    interruptible: bool,
    progress: Option<&Py<PyAny>>,
) -> Result<Vec<(usize, BifurcationValue)>, Stop> {
    let SweepPlan { spec, plan } = sp;
    if plan.continuation != Continuation::None {
        return compute_continuation(spec, plan, interruptible, progress);
    }
    if let Some(s) = plan.shard {
        let values = workers
            .run(|| block_sweep(spec, plan, &silent))
            .map_err(|e| sweep_failure(spec.param, &e))?;
        return Ok((s.index..plan.grid.count).step_by(s.count).zip(values).collect());
    }
    let count = plan.grid.count;
    let shards = count.div_ceil(chunk_len(workers)).max(1);
    let mut parts: Vec<Vec<BifurcationValue>> = Vec::with_capacity(shards);
    let mut first_failure: Option<SweepError<SteadyError>> = None;
    let mut done = 0;
    for index in 0..shards {
        let shard = Plan {
            shard: Some(Shard { index, count: shards }),
            ..*plan
        };
        match workers.run(|| block_sweep(spec, &shard, &silent)) {
            Ok(values) => {
                done += values.len();
                parts.push(values);
            }
            Err(e) => {
                if first_failure.as_ref().is_none_or(|f| e.index < f.index) {
                    first_failure = Some(e);
                }
                parts.push(Vec::new());
            }
        }
        if interruptible && let Err(e) = checkpoint(progress, done, count) {
            return Err(Stop::Raised(e));
        }
    }
    if let Some(e) = first_failure {
        return Err(sweep_failure(spec.param, &e));
    }
    // Value i is the (i / N)-th of shard i mod N.
    let mut iters: Vec<_> = parts.into_iter().map(Vec::into_iter).collect();
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        match iters[i % shards].next() {
            Some(v) => out.push((i, v)),
            None => {
                return Err(Stop::Failed(anyhow!(
                    "shard {} of {shards} is missing value {i}",
                    i % shards
                )));
            }
        }
    }
    Ok(out)
}

/// A continuation sweep, value by value in its direction (the seeding of
/// `orbit_diagram::block_sweep`: each value from the previous value's last
/// section state, from the configuration's own after a tumble or flight).
fn compute_continuation(
    spec: &BlockSweep<'_>,
    plan: &Plan,
    interruptible: bool,
    progress: Option<&Py<PyAny>>,
) -> Result<Vec<(usize, BifurcationValue)>, Stop> {
    let total = plan.indices().len();
    let mut order = plan.indices();
    if plan.continuation == Continuation::Down {
        order.reverse();
    }
    let mut out = Vec::with_capacity(order.len());
    let mut seed: Option<InitialState> = None;
    for i in order {
        let value = plan.grid.value(i);
        let fail = |error| sweep_failure(spec.param, &SweepError { index: i, value, error });
        let cfg = spec.scenario(value).map_err(fail)?;
        let cfg = match &seed {
            Some(s) => cfg.seeded(s),
            None => cfg,
        };
        let s = steady_response(&cfg, &spec.window, &spec.classify, spec.lyapunov).map_err(fail)?;
        seed = s.seed;
        out.push((
            i,
            BifurcationValue {
                value,
                response: s.response,
                max_abs_theta: s.max_abs_theta,
                lyapunov: s.lyapunov,
                points: s.points,
            },
        ));
        if interruptible && let Err(e) = checkpoint(progress, out.len(), total) {
            return Err(Stop::Raised(e));
        }
    }
    out.sort_by_key(|(i, _)| *i);
    Ok(out)
}

/// Response columns shared by sweeps and maps: `outcome`, `period` (0
/// where not periodic), `max_abs_theta`, `lyapunov` (NaN where none) and
/// `has_lyapunov`.
pub fn response_columns(
    py: Python<'_>,
    out: &Bound<'_, PyDict>,
    rows: impl Iterator<Item = (Response, f64, Option<f64>)>,
) -> PyResult<()> {
    let (mut outcome, mut period, mut max_abs, mut lyap, mut has) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (r, m, l) in rows {
        outcome.push(r.name());
        period.push(r.period().unwrap_or(0));
        max_abs.push(m);
        lyap.push(l.unwrap_or(f64::NAN));
        has.push(l.is_some());
    }
    out.set_item("outcome", outcome)?;
    out.set_item("period", period.into_pyarray(py))?;
    out.set_item("max_abs_theta", max_abs.into_pyarray(py))?;
    out.set_item("lyapunov", lyap.into_pyarray(py))?;
    out.set_item("has_lyapunov", has.into_pyarray(py))?;
    Ok(())
}

/// The columns of computed sweep values.
fn sweep_columns<'py>(
    py: Python<'py>,
    grid: &Grid,
    values: &[(usize, BifurcationValue)],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("count", grid.count)?;
    out.set_item(
        "index",
        values
            .iter()
            .map(|(i, _)| *i as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "value",
        values.iter().map(|(_, v)| v.value).collect::<Vec<_>>().into_pyarray(py),
    )?;
    response_columns(
        py,
        &out,
        values.iter().map(|(_, v)| (v.response, v.max_abs_theta, v.lyapunov)),
    )?;
    let points = PyDict::new(py);
    let all = || {
        values
            .iter()
            .flat_map(|(i, v)| v.points.iter().map(move |p| (*i, v.value, p)))
    };
    let f = |g: &dyn Fn(&rocking::sim::SectionRow) -> f64| all().map(|(_, _, p)| g(p)).collect::<Vec<f64>>();
    points.set_item(
        "index",
        all().map(|(i, _, _)| i as i64).collect::<Vec<_>>().into_pyarray(py),
    )?;
    points.set_item("value", all().map(|(_, v, _)| v).collect::<Vec<_>>().into_pyarray(py))?;
    points.set_item(
        "k",
        all().map(|(_, _, p)| p.k as i64).collect::<Vec<_>>().into_pyarray(py),
    )?;
    points.set_item("tau", f(&|p| p.tau).into_pyarray(py))?;
    points.set_item("theta", f(&|p| p.theta).into_pyarray(py))?;
    points.set_item("theta_dot", f(&|p| p.theta_dot).into_pyarray(py))?;
    points.set_item("x", f(&|p| p.x).into_pyarray(py))?;
    points.set_item("x_dot", f(&|p| p.x_dot).into_pyarray(py))?;
    points.set_item("mode", all().map(|(_, _, p)| p.mode.name()).collect::<Vec<_>>())?;
    out.set_item("points", points)?;
    Ok(out)
}

/// `rocking sweep` (without files): the bifurcation diagram of `param`
/// over `start … stop` by `step`. `shard=(K, N)` computes only the values
/// with index ≡ K (mod N), as `--shard K/N` does (for `rocking.dask`).
#[pyfunction]
#[pyo3(signature = (scene, param, start, stop, step, *, transient=600.0, tau_end=None, continuation="none", lyapunov=false, threads=None, shard=None, check_only=false, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn _sweep<'py>(
    py: Python<'py>,
    scene: &Scene,
    param: &str,
    start: f64,
    stop: f64,
    step: f64,
    transient: f64,
    tau_end: Option<f64>,
    continuation: &str,
    lyapunov: bool,
    threads: Option<usize>,
    shard: Option<(usize, usize)>,
    check_only: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = scene.scenario();
    let computed = (|| {
        let sp = sweep_plan(
            base,
            param,
            start,
            stop,
            step,
            transient,
            tau_end,
            continuation,
            lyapunov,
            shard,
        )?;
        if check_only {
            return Ok((sp.plan.grid, Vec::new()));
        }
        let workers = Workers::new(threads)?;
        let interruptible = shard.is_none();
        let values = py
            .detach(|| compute_sweep(&sp, &workers, interruptible, progress.as_ref()))
            .map_err(Stop::into_py)?;
        Ok((sp.plan.grid, values))
    })();
    let (grid, values) = computed.map_err(|e| with_python_args(e, SWEEP_ARGS))?;
    sweep_columns(py, &grid, &values)
}
