//! `outcome_map`: `rocking map` over the library's one map engine
//! ([`MapRun`]), checked with the CLI's messages.
//!
//! The engine hands out batches of cells (the coarse lattice first, then
//! only where classes meet, unless the map is `full`), each cell is
//! computed on its own (stopped early once its class is certain, unless
//! `full`), and the results go back to the engine in any order. Here the
//! batches are computed either on this machine, in chunks on the rayon
//! workers without the GIL with Ctrl-C and progress between chunks, or by
//! a Python `executor` (`rocking.dask` passes one that runs chunks on a
//! cluster through [`_outcome_cells`]). The driver, and so the map, is the
//! same either way: identical to `rocking map` (same flags: `full` is
//! `--full`, `coarse` is `--coarse`) for any chunking and thread count.

use anyhow::anyhow;
use numpy::{IntoPyArray as _, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use rocking::analysis::classify::{ClassifyOptions, Response};
use rocking::analysis::outcome_map::{Axis, BlockMap, COARSE_CELLS, MapPlan, MapRun, OutcomeMap};
use rocking::analysis::settle::CellResponse;
use rocking::analysis::steady::{SteadyError, Window};
use rocking::io::config;
use rocking::sim::{Param, Scenario};

use crate::errors::{MAP_ARGS, key_error, with_python_args};
use crate::names::Keywords;
use crate::scene::Scene;
use crate::study::{Stop, Workers, checkpoint, input, lyapunov_hook, response_columns, window};

/// Cells computed between two Ctrl-C checks on this machine: a few
/// hundred (a second or two of work on a small machine), and at least 16
/// per thread so that the slowest cell of a chunk leaves few threads idle.
fn chunk_cells(workers: &Workers) -> usize {
    (16 * workers.threads()).max(256)
}

/// One axis from its key, first and last value and count, checked as
/// `rocking map` checks `--x`/`--y`; `keyword` (`x`, `y`) names it in the
/// axis's own errors.
fn axis(flag: &str, keyword: &str, spec: (String, f64, f64, i64)) -> PyResult<(Axis, Param)> {
    let (key, a, b, n) = spec;
    let param = config::param(&key).map_err(|e| key_error(&key, format!("{flag} {e}")))?;
    let n = usize::try_from(n).map_err(|_| input(format!("{flag} {key}: N = '{n}' is not a positive integer")))?;
    let axis = Axis::new(keyword, &key, a, b, n).map_err(input)?;
    Ok((axis, param))
}

/// A checked map: its axes, window and how it is computed.
struct Checked {
    x: Axis,
    x_param: Param,
    y: Axis,
    y_param: Param,
    window: Window,
    plan: MapPlan,
    lyapunov: bool,
}

impl Checked {
    /// The engine's specification over `base`.
    fn spec<'a>(&'a self, base: &'a Scenario) -> BlockMap<'a> {
        BlockMap {
            base,
            x_param: self.x_param,
            x: &self.x,
            y_param: self.y_param,
            y: &self.y,
            window: self.window,
            classify: ClassifyOptions::default(),
            lyapunov: lyapunov_hook(self.lyapunov),
        }
    }

    /// The (x, y) values of cell `index` (row order: y outer, x inner),
    /// as [`MapRun::xy`] has them.
    fn xy(&self, index: usize) -> (f64, f64) {
        (self.x.value(index % self.x.n), self.y.value(index / self.x.n))
    }

    /// The message of a failed cell, as `rocking map` prints it (a window
    /// in Python's keywords).
    fn failure(&self, index: usize, error: &SteadyError) -> String {
        let (x, y) = self.xy(index);
        format!(
            "{} = {x}, {} = {y}: {}",
            self.x.key,
            self.y.key,
            error.render(&Keywords)
        )
    }
}

/// `--full` and `--coarse N` as a plan, checked as `rocking map` checks
/// them (`coarse` is not used by a full map).
fn plan(full: bool, coarse: i64) -> PyResult<MapPlan> {
    if full {
        return Ok(MapPlan::FULL);
    }
    match usize::try_from(coarse) {
        Ok(n) if n >= 2 => Ok(MapPlan {
            early_stop: true,
            coarse: Some(n),
        }),
        _ => Err(input(format!("--coarse {coarse}: must be >= 2"))),
    }
}

/// Checks a map as `rocking map` does, before anything runs; every cell's
/// scenario too when `every_cell` (the driver; a worker computing cells
/// of a checked map skips it).
#[allow(clippy::too_many_arguments)]
fn check(
    base: &Scenario,
    x: (String, f64, f64, i64),
    y: (String, f64, f64, i64),
    transient: f64,
    tau_end: Option<f64>,
    lyapunov: bool,
    full: bool,
    coarse: i64,
    every_cell: bool,
) -> PyResult<Checked> {
    let (x, x_param) = axis("--x", "x", x)?;
    let (y, y_param) = axis("--y", "y", y)?;
    if x_param == y_param {
        return Err(key_error(
            &y.key,
            format!("--y {}: the two axes must be different keys", y.key),
        ));
    }
    for (flag, p) in [("--x", x_param), ("--y", y_param)] {
        if p == Param::TauEnd {
            return Err(key_error(
                p.key(),
                format!("{flag} run.tau_end: the run length is set by --tau-end, it cannot be an axis"),
            ));
        }
    }
    let plan = plan(full, coarse)?;
    let window = window(base, transient, tau_end)?;
    let checked = Checked {
        x,
        x_param,
        y,
        y_param,
        window,
        plan,
        lyapunov,
    };
    if every_cell {
        checked.spec(base).check().map_err(|e| {
            input(format!(
                "--x {} = {}, --y {} = {}: {}",
                checked.x.key,
                e.x,
                checked.y.key,
                e.y,
                e.error.render(&Keywords)
            ))
        })?;
    }
    Ok(checked)
}

/// Cell `index` of the map, as [`MapRun::compute`] computes it (which
/// needs the whole run; a worker has only the map's specification).
/// `known` and `labels`: the attractors' cycles and the basin labels the
/// driver's run had when it handed out the cell's batch
/// ([`MapRun::known`], [`MapRun::basin_labels`]).
fn compute(
    checked: &Checked,
    spec: &BlockMap<'_>,
    index: usize,
    known: &[Vec<[f64; 3]>],
    labels: Option<&[i64]>,
) -> Result<CellResponse, String> {
    let (x, y) = checked.xy(index);
    let basins = labels.and_then(|l| spec.basin_lookup(l));
    spec.cell(x, y, checked.plan.early_stop, known, basins)
        .map_err(|e| checked.failure(index, &e))
}

/// Where a map's cells are computed.
enum Cells<'a> {
    /// On this machine, in chunks on these workers.
    Local(&'a Workers),
    /// By `executor(indices)`, which returns an iterable of packed chunks
    /// (the dicts of [`_outcome_cells`]) covering those indices.
    Executor(&'a Py<PyAny>),
}

/// What a chunk of cells came back as: the computed cells, and the
/// failure with the smallest index, if any.
struct Chunk {
    cells: Vec<(usize, CellResponse)>,
    failed: Option<(usize, String)>,
}

impl Chunk {
    /// Computes `indices` with `cell` in parallel on the current rayon
    /// pool; every cell is computed, so that the failure kept is the
    /// chunk's first in index order whatever the chunking.
    fn compute(indices: &[usize], cell: impl Fn(usize) -> Result<CellResponse, String> + Sync) -> Self {
        let results: Vec<(usize, Result<CellResponse, String>)> =
            indices.par_iter().map(|&index| (index, cell(index))).collect();
        let mut chunk = Chunk {
            cells: Vec::with_capacity(results.len()),
            failed: None,
        };
        for (index, r) in results {
            match r {
                Ok(cell) => chunk.cells.push((index, cell)),
                Err(message) => {
                    if chunk.failed.as_ref().is_none_or(|(i, _)| index < *i) {
                        chunk.failed = Some((index, message));
                    }
                }
            }
        }
        chunk
    }
}

/// Runs the engine to the end: each batch's cells computed where `cells`
/// says, progress (total: every cell; an inherited cell counts as done)
/// and Ctrl-C checked between batches and chunks. The first failed cell
/// in index order within its batch stops the map, as in `rocking map`.
fn drive(run: &mut MapRun<'_>, checked: &Checked, cells: &Cells<'_>, progress: Option<&Py<PyAny>>) -> Result<(), Stop> {
    let total = run.len();
    let mut done = 0;
    while let Some((todo, inherited)) = run.next_batch() {
        if inherited > 0 {
            done += inherited;
            checkpoint(progress, done, total).map_err(Stop::Raised)?;
        }
        let batch = match cells {
            Cells::Local(workers) => local_batch(run, checked, workers, &todo, progress, &mut done, total)?,
            Cells::Executor(f) => remote_batch(run, f, &todo, progress, &mut done, total)?,
        };
        run.record(batch);
    }
    Ok(())
}

/// One batch on this machine, chunk by chunk (contiguous runs of the
/// batch's increasing indices, so the first failure met is the batch's
/// first in index order).
fn local_batch(
    run: &MapRun<'_>,
    checked: &Checked,
    workers: &Workers,
    todo: &[usize],
    progress: Option<&Py<PyAny>>,
    done: &mut usize,
    total: usize,
) -> Result<Vec<(usize, CellResponse)>, Stop> {
    let mut batch = Vec::with_capacity(todo.len());
    for indices in todo.chunks(chunk_cells(workers)) {
        let chunk = workers.run(|| {
            Chunk::compute(indices, |index| {
                run.compute(index).map_err(|e| checked.failure(index, &e))
            })
        });
        if let Some((_, message)) = chunk.failed {
            return Err(Stop::Failed(anyhow!(message)));
        }
        batch.extend(chunk.cells);
        *done += indices.len();
        checkpoint(progress, *done, total).map_err(Stop::Raised)?;
    }
    Ok(batch)
}

/// One batch by the executor, called with the batch's indices, the
/// known attractors' cycles (lists of (Θ, Θ', X') triples) and the basin
/// labels (an int64 array, or None), which its tasks pass on to
/// [`_outcome_cells`]: its chunks in the order they come back, progress
/// and Ctrl-C checked after each; every index asked for must come back
/// exactly once. The failure reported is the batch's first in index
/// order, whichever chunk it was in.
fn remote_batch(
    run: &MapRun<'_>,
    executor: &Py<PyAny>,
    todo: &[usize],
    progress: Option<&Py<PyAny>>,
    done: &mut usize,
    total: usize,
) -> Result<Vec<(usize, CellResponse)>, Stop> {
    let cells = run.len();
    let mut asked = vec![false; cells];
    for &i in todo {
        asked[i] = true;
    }
    let mut batch = Vec::with_capacity(todo.len());
    let mut failed: Option<(usize, String)> = None;
    let iter = Python::attach(|py| -> PyResult<Py<PyAny>> {
        let indices = PyList::new(py, todo)?;
        let labels = run.basin_labels().map(|l| l.to_vec().into_pyarray(py));
        let parts = executor.call1(py, (indices, run.known().to_vec(), labels))?;
        Ok(parts.bind(py).try_iter()?.into_any().unbind())
    })
    .map_err(Stop::Raised)?;
    loop {
        let next = Python::attach(|py| -> PyResult<Option<Chunk>> {
            let it = iter.bind(py);
            match it.call_method0("__next__") {
                Ok(part) => unpack(&part).map(Some),
                Err(e) if e.is_instance_of::<pyo3::exceptions::PyStopIteration>(py) => Ok(None),
                Err(e) => Err(e),
            }
        })
        .map_err(Stop::Raised)?;
        let Some(chunk) = next else { break };
        let mut count = chunk.cells.len();
        for (index, cell) in chunk.cells {
            if !asked.get(index).copied().unwrap_or(false) {
                return Err(Stop::Failed(anyhow!(
                    "the executor returned cell {index}, not asked for or returned twice"
                )));
            }
            asked[index] = false;
            batch.push((index, cell));
        }
        if let Some((index, message)) = chunk.failed {
            count += 1;
            if failed.as_ref().is_none_or(|(i, _)| index < *i) {
                failed = Some((index, message));
            }
        }
        *done += count;
        checkpoint(progress, (*done).min(total), total).map_err(Stop::Raised)?;
    }
    Python::attach(|_| drop(iter));
    if let Some((_, message)) = failed {
        return Err(Stop::Failed(anyhow!(message)));
    }
    if let Some(&missing) = todo.iter().find(|&&i| asked[i]) {
        return Err(Stop::Failed(anyhow!(
            "the executor returned no result for cell {missing}"
        )));
    }
    Ok(batch)
}

/// A packed chunk (the dict of [`_outcome_cells`]) read back, losslessly.
fn unpack(part: &Bound<'_, PyAny>) -> PyResult<Chunk> {
    let field = |name: &str| part.get_item(name);
    let f64s =
        |name: &str| -> PyResult<Vec<f64>> { Ok(field(name)?.extract::<PyReadonlyArray1<f64>>()?.as_array().to_vec()) };
    let i64s =
        |name: &str| -> PyResult<Vec<i64>> { Ok(field(name)?.extract::<PyReadonlyArray1<i64>>()?.as_array().to_vec()) };
    let bools = |name: &str| -> PyResult<Vec<bool>> {
        Ok(field(name)?.extract::<PyReadonlyArray1<bool>>()?.as_array().to_vec())
    };
    let bad = |what: &str| crate::errors::run_error(&anyhow!("a chunk of map cells came back malformed: {what}"));
    let index = i64s("index")?;
    let outcome: Vec<String> = field("outcome")?.extract()?;
    let period = i64s("period")?;
    let max_abs_theta = f64s("max_abs_theta")?;
    let lyapunov = f64s("lyapunov")?;
    let has_lyapunov = bools("has_lyapunov")?;
    let stopped_at = f64s("stopped_at")?;
    let has_stopped_at = bools("has_stopped_at")?;
    let settled_at = f64s("settled_at")?;
    let reached_known = bools("reached_known")?;
    let cycle_len = i64s("cycle_len")?;
    let cycle = f64s("cycle")?;
    let n = index.len();
    if [
        outcome.len(),
        period.len(),
        max_abs_theta.len(),
        lyapunov.len(),
        has_lyapunov.len(),
        stopped_at.len(),
        has_stopped_at.len(),
        settled_at.len(),
        reached_known.len(),
        cycle_len.len(),
    ]
    .iter()
    .any(|&len| len != n)
    {
        return Err(bad("columns of different lengths"));
    }
    let mut points = cycle.chunks_exact(3).map(|p| [p[0], p[1], p[2]]);
    let mut cells = Vec::with_capacity(n);
    for k in 0..n {
        let index = usize::try_from(index[k]).map_err(|_| bad("a negative index"))?;
        let period = u32::try_from(period[k]).ok().filter(|&p| p > 0);
        let response = Response::from_name(&outcome[k], period).ok_or_else(|| bad(&outcome[k]))?;
        let len = usize::try_from(cycle_len[k]).map_err(|_| bad("a negative cycle length"))?;
        let cycle: Vec<[f64; 3]> = points.by_ref().take(len).collect();
        if cycle.len() != len {
            return Err(bad("a cycle cut short"));
        }
        cells.push((
            index,
            CellResponse {
                response,
                max_abs_theta: max_abs_theta[k],
                lyapunov: has_lyapunov[k].then_some(lyapunov[k]),
                cycle,
                stopped_at: has_stopped_at[k].then_some(stopped_at[k]),
                settled_at: settled_at[k],
                reached_known: reached_known[k],
            },
        ));
    }
    let failed: Option<(usize, String)> = field("failed")?.extract()?;
    Ok(Chunk { cells, failed })
}

/// A chunk as a dict of numpy arrays (lossless: f64 as f64).
fn pack<'py>(py: Python<'py>, chunk: &Chunk) -> PyResult<Bound<'py, PyDict>> {
    let cells = &chunk.cells;
    let col = |f: &dyn Fn(&CellResponse) -> f64| cells.iter().map(|(_, c)| f(c)).collect::<Vec<f64>>();
    let out = PyDict::new(py);
    out.set_item(
        "index",
        cells
            .iter()
            .map(|(i, _)| *i as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "outcome",
        cells.iter().map(|(_, c)| c.response.name()).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "period",
        cells
            .iter()
            .map(|(_, c)| i64::from(c.response.period().unwrap_or(0)))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item("max_abs_theta", col(&|c| c.max_abs_theta).into_pyarray(py))?;
    out.set_item("lyapunov", col(&|c| c.lyapunov.unwrap_or(f64::NAN)).into_pyarray(py))?;
    out.set_item(
        "has_lyapunov",
        cells
            .iter()
            .map(|(_, c)| c.lyapunov.is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "stopped_at",
        col(&|c| c.stopped_at.unwrap_or(f64::NAN)).into_pyarray(py),
    )?;
    out.set_item(
        "has_stopped_at",
        cells
            .iter()
            .map(|(_, c)| c.stopped_at.is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item("settled_at", col(&|c| c.settled_at).into_pyarray(py))?;
    out.set_item(
        "reached_known",
        cells
            .iter()
            .map(|(_, c)| c.reached_known)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "cycle_len",
        cells
            .iter()
            .map(|(_, c)| c.cycle.len() as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "cycle",
        cells
            .iter()
            .flat_map(|(_, c)| c.cycle.iter().flatten().copied())
            .collect::<Vec<f64>>()
            .into_pyarray(py),
    )?;
    out.set_item("failed", chunk.failed.clone())?;
    Ok(out)
}

/// The finished map as columns: the response columns (`max_abs_theta`
/// NaN for a cell that inherited its class), `attractor` (-1 where none),
/// `computed`, the attractors and the counts.
fn map_columns<'py>(py: Python<'py>, checked: &Checked, map: &OutcomeMap) -> PyResult<Bound<'py, PyDict>> {
    let cells = &map.cells;
    let out = PyDict::new(py);
    out.set_item("x_key", &checked.x.key)?;
    out.set_item("y_key", &checked.y.key)?;
    out.set_item("x_values", checked.x.values().into_pyarray(py))?;
    out.set_item("y_values", checked.y.values().into_pyarray(py))?;
    out.set_item("x", cells.iter().map(|c| c.x).collect::<Vec<_>>().into_pyarray(py))?;
    out.set_item("y", cells.iter().map(|c| c.y).collect::<Vec<_>>().into_pyarray(py))?;
    response_columns(
        py,
        &out,
        cells
            .iter()
            .map(|c| (c.response, c.max_abs_theta.unwrap_or(f64::NAN), c.lyapunov)),
    )?;
    out.set_item(
        "attractor",
        cells
            .iter()
            .map(|c| c.attractor.map_or(-1, i64::from))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "computed",
        cells.iter().map(|c| c.computed).collect::<Vec<_>>().into_pyarray(py),
    )?;
    let attractors = PyList::empty(py);
    for a in &map.attractors {
        let d = PyDict::new(py);
        d.set_item("id", a.id)?;
        d.set_item("period", a.period)?;
        d.set_item("point", (a.point[0], a.point[1], a.point[2]))?;
        d.set_item("cycle", a.cycle.iter().map(|p| (p[0], p[1], p[2])).collect::<Vec<_>>())?;
        d.set_item("cells", a.cells)?;
        attractors.append(d)?;
    }
    out.set_item("attractors", attractors)?;
    out.set_item("cells_run", map.computed)?;
    out.set_item("cells_stopped_early", map.stopped_early)?;
    out.set_item("cells_on_known_attractor", map.reached_known)?;
    Ok(out)
}

/// `rocking map` (without files): the outcome map over `x = (key, A, B, N)`
/// and `y = (key, A, B, N)`, cells in map.csv's order (y outer, x inner).
/// `full` and `coarse` are `--full` and `--coarse N`. `executor`, if
/// given, computes each batch's cells instead of this machine's threads:
/// called with a list of cell indices, it returns an iterable of the
/// packed chunks of [`_outcome_cells`] covering them (`rocking.dask`).
#[pyfunction]
#[pyo3(signature = (scene, x, y, *, transient=600.0, tau_end=None, lyapunov=false, threads=None, full=false, coarse=COARSE_CELLS as i64, executor=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn _outcome_map<'py>(
    py: Python<'py>,
    scene: &Scene,
    x: (String, f64, f64, i64),
    y: (String, f64, f64, i64),
    transient: f64,
    tau_end: Option<f64>,
    lyapunov: bool,
    threads: Option<usize>,
    full: bool,
    coarse: i64,
    executor: Option<Py<PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = scene.scenario();
    let computed = (|| {
        let checked = check(base, x, y, transient, tau_end, lyapunov, full, coarse, true)?;
        let workers = Workers::new(threads)?;
        let map = py
            .detach(|| {
                let mut run = MapRun::new(checked.spec(base), checked.plan);
                let cells = match &executor {
                    Some(f) => Cells::Executor(f),
                    None => Cells::Local(&workers),
                };
                drive(&mut run, &checked, &cells, progress.as_ref())?;
                run.finish().map_err(|e| {
                    Stop::Failed(anyhow!(
                        "{} = {}, {} = {}: {}",
                        checked.x.key,
                        e.x,
                        checked.y.key,
                        e.y,
                        e.error.render(&Keywords)
                    ))
                })
            })
            .map_err(Stop::into_py)?;
        Ok((checked, map))
    })();
    let (checked, map) = computed.map_err(|e| with_python_args(e, MAP_ARGS))?;
    map_columns(py, &checked, &map)
}

/// Cells `indices` of the map that `_outcome_map` with the same arguments
/// computes, each as the engine computes it (for `rocking.dask`'s
/// workers), packed in arrays: `index`, `outcome`, `period` (0 where not
/// periodic), `max_abs_theta`, `lyapunov` and `has_lyapunov`,
/// `stopped_at` and `has_stopped_at`, `settled_at`, `reached_known`, `cycle_len` and `cycle` (the
/// periodic cycles' section points (Θ, Θ', X'), flattened, cell after
/// cell), and `failed`: `(index, message)` of the first failed cell in
/// index order (left out of the arrays), or None. `known`: the cycles of
/// the attractors the driver had found, which a cell's run stops on
/// reaching, and `labels` its basin labels (the executor's second and
/// third arguments).
#[pyfunction]
#[pyo3(signature = (scene, x, y, indices, *, transient=600.0, tau_end=None, lyapunov=false, threads=None, full=false, coarse=COARSE_CELLS as i64, known=Vec::new(), labels=None))]
#[allow(clippy::too_many_arguments)]
pub fn _outcome_cells<'py>(
    py: Python<'py>,
    scene: &Scene,
    x: (String, f64, f64, i64),
    y: (String, f64, f64, i64),
    indices: Vec<usize>,
    transient: f64,
    tau_end: Option<f64>,
    lyapunov: bool,
    threads: Option<usize>,
    full: bool,
    coarse: i64,
    known: Vec<Vec<[f64; 3]>>,
    labels: Option<PyReadonlyArray1<'py, i64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let labels: Option<Vec<i64>> = labels.map(|l| l.as_array().to_vec());
    let base = scene.scenario();
    let computed = (|| {
        let checked = check(base, x, y, transient, tau_end, lyapunov, full, coarse, false)?;
        let cells = checked.x.n * checked.y.n;
        if let Some(&i) = indices.iter().find(|&&i| i >= cells) {
            return Err(input(format!("indices: {i} is not a cell of the {cells}")));
        }
        let workers = Workers::new(threads)?;
        let spec = checked.spec(base);
        let chunk = py.detach(|| {
            workers.run(|| {
                Chunk::compute(&indices, |index| {
                    compute(&checked, &spec, index, &known, labels.as_deref())
                })
            })
        });
        Ok(chunk)
    })();
    let chunk = computed.map_err(|e| with_python_args(e, MAP_ARGS))?;
    pack(py, &chunk)
}
