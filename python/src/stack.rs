//! `simulate` on a scene with a `[[stack]]`: one run of stacked blocks,
//! as `rocking --batch` makes it, returned as the columns of its
//! `history.csv` and `events.csv` and its summary.json.

use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::io::stack_files::{body_states, stack_summary};
use rocking::model::stack::SLIDE;
use rocking::sim::Scenario;
use rocking::sim::stack_run::{StackRun, simulate_stack};
use serde_json::Value as Json;

use crate::convert::json_to_py;
use crate::errors::Failure;

/// A stack's run and its summary.json.
pub struct StackSimulated {
    run: StackRun,
    summary: Json,
}

/// Runs the stack of `cfg` as `rocking --batch` does. A face that would
/// slip is bad input (its `static` is too low), as the CLI's exit 2.
pub fn run_stack(cfg: &Scenario) -> Result<StackSimulated, Failure> {
    let input = |key: &str, message: String| Failure::Input {
        key: key.to_string(),
        message,
    };
    let geo = cfg
        .stack_geometry()
        .ok_or_else(|| input("stack", "stack: its blocks do not stand on each other".into()))?;
    let excitation = cfg.excitation().map_err(|e| input(&e.key.clone(), e.to_string()))?;
    let run = simulate_stack(geo, excitation, cfg.run.zeno_eps, &cfg.run_options()).map_err(|e| match e.key() {
        Some(key) => input(&key, e.to_string()),
        None => Failure::Run(anyhow::Error::new(e).context("simulation failed")),
    })?;
    let mut summary = stack_summary(cfg, &run);
    if cfg.analyses.lyapunov {
        let l = crate::simulate::scenario_lyapunov(cfg, crate::simulate::method_of(cfg.analyses.lyapunov_method))?;
        if let Some(obj) = summary.as_object_mut() {
            obj.insert("lyapunov".to_string(), l.summary());
        }
    }
    Ok(StackSimulated { run, summary })
}

/// The columns of a stack's run: `history` (`tau`, `t_s`, `mode`,
/// `sliding_m`, then
/// each body's `theta_J_rad`, `theta_dot_J_rad_s`, `x_J_m`, `y_J_m`) and
/// `events` as history.csv's and events.csv's columns, and `summary`.
pub fn stack_columns<'py>(py: Python<'py>, s: &StackSimulated, p: f64) -> PyResult<Bound<'py, PyDict>> {
    let run = &s.run;
    let k = run.geo.k;
    let h = &run.history;
    let col = |v: Vec<f64>| v.into_pyarray(py).into_any();
    let history = PyDict::new(py);
    history.set_item("tau", col(h.iter().map(|r| r.tau).collect()))?;
    history.set_item("t_s", col(h.iter().map(|r| r.tau / p).collect()))?;
    history.set_item("mode", h.iter().map(|r| r.mode.name(k)).collect::<Vec<String>>())?;
    history.set_item("sliding_m", col(h.iter().map(|r| r.y[SLIDE]).collect()))?;
    let states: Vec<_> = h.iter().map(|r| body_states(run, r, p)).collect();
    for j in 0..k {
        for (c, name) in ["theta_{j}_rad", "theta_dot_{j}_rad_s", "x_{j}_m", "y_{j}_m"]
            .iter()
            .enumerate()
        {
            let name = name.replace("{j}", &j.to_string());
            history.set_item(name, col(states.iter().map(|b| b[j][c]).collect()))?;
        }
    }
    let e = &run.events;
    let events = PyDict::new(py);
    events.set_item("tau", col(e.iter().map(|r| r.tau).collect()))?;
    events.set_item("t_s", col(e.iter().map(|r| r.tau / p).collect()))?;
    events.set_item("kind", e.iter().map(|r| r.kind.name()).collect::<Vec<&str>>())?;
    events.set_item(
        "body",
        e.iter().map(|r| r.body as i64).collect::<Vec<i64>>().into_pyarray(py),
    )?;
    events.set_item(
        "mode_before",
        e.iter().map(|r| r.before.name(k)).collect::<Vec<String>>(),
    )?;
    events.set_item("mode_after", e.iter().map(|r| r.after.name(k)).collect::<Vec<String>>())?;
    events.set_item(
        "q_dot_before_rad_s",
        col(e.iter().map(|r| r.q_dot_before * p).collect()),
    )?;
    events.set_item("q_dot_after_rad_s", col(e.iter().map(|r| r.q_dot_after * p).collect()))?;
    let out = PyDict::new(py);
    out.set_item("blocks", k)?;
    out.set_item("history", history)?;
    out.set_item("events", events)?;
    out.set_item("summary", json_to_py(py, &s.summary)?)?;
    Ok(out)
}
