//! `simulate`: one run, as `rocking --batch` makes it, returned as columns
//! (numpy arrays) and the summary.json dict.

use anyhow::Context as _;
use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::analysis::lyapunov::{self, Lyapunov, LyapunovOptions, Method};
use rocking::analysis::spectrum::{SpectrumOptions, SpectrumWindow, theta_spectrum};
use rocking::io::csv::Num;
use rocking::io::output::{self, FRAME_EVENT_BODY, frame_body_cells, frame_history_header};
use rocking::model::Geometry;
use rocking::model::frame::Frame;
use rocking::model::system::EventRecord;
use rocking::sim::scenario::{LyapunovChoice, SpectrumRange};
use rocking::sim::{self, HistoryRow, Keep, RunResult, Scenario, SectionRow, Sink};
use serde_json::Value as Json;

use crate::convert::json_to_py;
use crate::errors::{Failure, run_error};
use crate::interrupt::{self, Cancel};
use crate::scene::Scene;

/// The Lyapunov exponents of a configured run, as `rocking --batch` computes
/// them for `analysis.lyapunov` (over the run's own `tau_end`).
pub fn scenario_lyapunov(cfg: &Scenario, method: Method) -> Result<Lyapunov, Failure> {
    let opts = LyapunovOptions::for_scenario(cfg, method);
    lyapunov::of_scenario(cfg, &opts).map_err(|e| {
        if e.is_input() {
            Failure::Input {
                key: "analysis.lyapunov".to_string(),
                message: format!("analysis.lyapunov: {e}"),
            }
        } else {
            Failure::Run(anyhow::Error::new(e).context("lyapunov exponents failed"))
        }
    })
}

/// The method `analysis.lyapunov_method` names.
pub fn method_of(choice: LyapunovChoice) -> Method {
    match choice {
        LyapunovChoice::Tangent => Method::Tangent,
        LyapunovChoice::Benettin => Method::Benettin,
        LyapunovChoice::Both => Method::Both,
    }
}

/// summary.json's `spectrum` entry (`analysis.spectrum`): the ten dominant
/// peaks of Θ(τ), as `rocking --batch` writes it.
fn spectrum_summary(cfg: &Scenario, res: &RunResult) -> Result<Json, Failure> {
    let window = match cfg.analyses.spectrum_window {
        SpectrumRange::Paper => SpectrumWindow::Paper,
        SpectrumRange::All => SpectrumWindow::All,
    };
    let sp = theta_spectrum(&res.history, window, &SpectrumOptions::default())
        .context("analysis.spectrum")
        .map_err(Failure::Run)?;
    let peaks = sp.peaks(10, 1e-6, cfg.excitation.omega_h);
    Ok(serde_json::json!({
        "window": cfg.analyses.spectrum_window.name(),
        "samples": sp.n,
        "dt": sp.dt,
        "taper": "hann",
        "peaks": peaks,
    }))
}

/// A finished run and its summary.json.
pub struct Simulated {
    /// The run.
    pub result: RunResult,
    /// summary.json as the CLI writes it.
    pub summary: Json,
}

/// The sink of a run that can be cancelled: keeps everything, and stops
/// the run at its next output once the call is cancelled (Ctrl-C).
struct Cancellable<'a> {
    keep: Keep,
    cancel: &'a Cancel,
}

impl Sink for Cancellable<'_> {
    fn sample(&mut self, row: &HistoryRow) {
        self.cancel.check();
        self.keep.sample(row);
    }

    fn section(&mut self, row: &SectionRow) {
        self.cancel.check();
        self.keep.section(row);
    }

    fn event(&mut self, record: &EventRecord) {
        self.cancel.check();
        self.keep.event(record);
    }
}

/// Runs `cfg` as `rocking --batch` does (run, then the configured
/// analyses) without touching the GIL, stopping at its next output once
/// `cancel` is set.
pub fn run_scene(cfg: &Scenario, cancel: &Cancel) -> Result<Simulated, Failure> {
    let model = cfg.model().map_err(|e| Failure::Input {
        key: e.key.clone(),
        message: e.to_string(),
    })?;
    let mut sink = Cancellable {
        keep: Keep::default(),
        cancel,
    };
    // As `sim::simulate`, through a sink that can stop the run.
    let mut result = sim::simulate_into(model, &cfg.initial, &cfg.run_options(), &mut sink)
        .context("simulation failed")
        .map_err(Failure::Run)?;
    result.events = sink.keep.events;
    result.section = sink.keep.section;
    result.history = sink.keep.history;
    let mut summary = output::summary_json(cfg, &result);
    if cfg.analyses.lyapunov {
        let l = scenario_lyapunov(cfg, method_of(cfg.analyses.lyapunov_method))?;
        if let Some(obj) = summary.as_object_mut() {
            obj.insert("lyapunov".to_string(), l.summary());
        }
    }
    if cfg.analyses.spectrum {
        let s = spectrum_summary(cfg, &result)?;
        if let Some(obj) = summary.as_object_mut() {
            obj.insert("spectrum".to_string(), s);
        }
    }
    Ok(Simulated { result, summary })
}

/// Issues the scene's warnings as Python `UserWarning`s, with the line the
/// CLI prints on stderr less its `warning: ` prefix.
pub fn warn(py: Python<'_>, cfg: &Scenario) -> PyResult<()> {
    let warnings = py.import("warnings")?;
    for w in cfg.warnings() {
        let text = w.strip_prefix("warning: ").unwrap_or(&w);
        warnings.call_method1("warn", (text,))?;
    }
    Ok(())
}

/// Issues a Python `UserWarning` when `record`'s PGA as read suggests a
/// wrong unit (the CLI's `warning: --record …` line), naming it by its
/// keyword `keyword` (`record`, `record_v`).
pub fn warn_unit(py: Python<'_>, keyword: &str, record: &rocking::sim::scenario::Record) -> PyResult<()> {
    if let Some(doubt) = record.unit_doubt() {
        let text = format!("{keyword}={}: {doubt}", record.path.display());
        py.import("warnings")?.call_method1("warn", (text,))?;
    }
    Ok(())
}

/// Column `name` of `rows` as a float64 array.
fn column<'py, T>(py: Python<'py>, rows: &[T], f: impl Fn(&T) -> f64) -> Bound<'py, PyAny> {
    rows.iter().map(f).collect::<Vec<f64>>().into_pyarray(py).into_any()
}

/// Names as a list (numpy makes them a string array on the Python side).
fn names<T>(rows: &[T], f: impl Fn(&T) -> &'static str) -> Vec<&'static str> {
    rows.iter().map(f).collect()
}

/// The columns of a run: `history`, `events` and `poincare` as dicts of
/// arrays named as the CSV columns of `rocking --batch` (same numbers:
/// physical columns computed as in `io::output`), and `summary`.
fn columns<'py>(py: Python<'py>, s: &Simulated, geo: &Geometry, frame: Option<&Frame>) -> PyResult<Bound<'py, PyDict>> {
    let res = &s.result;
    let h = &res.history;
    let history = PyDict::new(py);
    history.set_item("tau", column(py, h, |r| r.tau))?;
    history.set_item("theta", column(py, h, |r| r.theta))?;
    history.set_item("theta_dot", column(py, h, |r| r.theta_dot))?;
    history.set_item("x", column(py, h, |r| r.x))?;
    history.set_item("x_dot", column(py, h, |r| r.x_dot))?;
    history.set_item("mode", names(h, |r| r.mode.name()))?;
    history.set_item("t_s", column(py, h, |r| r.tau / geo.p))?;
    history.set_item("theta_rad", column(py, h, |r| r.theta * geo.psi))?;
    history.set_item("sliding_m", column(py, h, |r| geo.sliding(r.theta, r.x) * geo.r))?;
    if let Some(f) = frame {
        // Each body's columns, as a frame's history.csv adds them.
        let cells: Vec<Vec<Num>> = h.iter().map(|r| frame_body_cells(f, geo, r)).collect();
        for (i, name) in frame_history_header(f).iter().enumerate() {
            history.set_item(name, column(py, &cells, |c| c[i].0))?;
        }
    }

    let e = &res.events;
    let events = PyDict::new(py);
    events.set_item("tau", column(py, e, |r| r.tau))?;
    events.set_item("kind", names(e, |r| r.kind.name()))?;
    events.set_item("mode_before", names(e, |r| r.before.name()))?;
    events.set_item("mode_after", names(e, |r| r.after.name()))?;
    events.set_item("theta", column(py, e, |r| r.theta))?;
    events.set_item("theta_dot_before", column(py, e, |r| r.theta_dot_before))?;
    events.set_item("theta_dot_after", column(py, e, |r| r.theta_dot_after))?;
    events.set_item("x_dot", column(py, e, |r| r.x_dot))?;
    events.set_item("t_s", column(py, e, |r| r.tau / geo.p))?;
    events.set_item("theta_rad", column(py, e, |r| r.theta * geo.psi))?;
    events.set_item("sliding_m", column(py, e, |r| geo.sliding(r.theta, r.x) * geo.r))?;
    if frame.is_some() {
        events.set_item("body", names(e, |_| FRAME_EVENT_BODY))?;
    }

    let p = &res.section;
    let poincare = PyDict::new(py);
    poincare.set_item("k", p.iter().map(|r| r.k as i64).collect::<Vec<i64>>().into_pyarray(py))?;
    poincare.set_item("tau", column(py, p, |r| r.tau))?;
    poincare.set_item("theta", column(py, p, |r| r.theta))?;
    poincare.set_item("theta_dot", column(py, p, |r| r.theta_dot))?;
    poincare.set_item("x", column(py, p, |r| r.x))?;
    poincare.set_item("x_dot", column(py, p, |r| r.x_dot))?;
    poincare.set_item("mode", names(p, |r| r.mode.name()))?;

    let out = PyDict::new(py);
    out.set_item("history", history)?;
    out.set_item("events", events)?;
    out.set_item("poincare", poincare)?;
    out.set_item("summary", json_to_py(py, &s.summary)?)?;
    Ok(out)
}

/// Runs `scene` as `rocking --batch` does, without the GIL, Ctrl-C
/// stopping it within a few hundredths of a second, and returns
/// its columns and summary (the Python `simulate` wraps them in a `Run`).
#[pyfunction]
pub fn _simulate<'py>(py: Python<'py>, scene: &Scene) -> PyResult<Bound<'py, PyDict>> {
    let cfg = scene.scenario();
    warn(py, cfg)?;
    let owned = cfg.clone();
    if cfg.stack.is_some() {
        // A stack's run offers no place to stop: after Ctrl-C it finishes
        // on its own thread (milliseconds), its result dropped.
        let done = interrupt::run(py, move |_| crate::stack::run_stack(&owned))?.map_err(Failure::into_py)?;
        return crate::stack::stack_columns(py, &done, cfg.geometry().p);
    }
    let done = interrupt::run(py, move |cancel| run_scene(&owned, cancel))?.map_err(Failure::into_py)?;
    columns(py, &done, &cfg.geometry(), cfg.frame.as_ref())
}

/// The Lyapunov exponents of `scene` over its run (`run.tau_end`) by its
/// `analysis.lyapunov_method`, as `analysis.lyapunov` computes them.
/// Returns the full result (`result`, `convergence` as pairs) and
/// summary.json's entry (`summary`).
#[pyfunction]
pub fn _lyapunov<'py>(py: Python<'py>, scene: &Scene) -> PyResult<Bound<'py, PyAny>> {
    let cfg = scene.scenario();
    warn(py, cfg)?;
    let method = method_of(cfg.analyses.lyapunov_method);
    let owned = cfg.clone();
    // The Lyapunov run offers no place to stop: after Ctrl-C it finishes
    // on its own thread, its result dropped.
    let l = interrupt::run(py, move |_| scenario_lyapunov(&owned, method))?.map_err(Failure::into_py)?;
    let full = serde_json::to_value(&l).map_err(|e| run_error(&anyhow::Error::new(e)))?;
    let out = PyDict::new(py);
    out.set_item("result", json_to_py(py, &full)?)?;
    out.set_item("summary", json_to_py(py, &l.summary())?)?;
    Ok(out.into_any())
}
