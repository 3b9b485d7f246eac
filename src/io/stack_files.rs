//! A stack's run as files: `summary.json` (the single block's fields for
//! the stack as a whole, `physical.bodies` for each block), `events.csv`
//! with the `body` each event is at, and `history.csv` with each body's
//! columns. Bodies are numbered from 0 at the bottom, as
//! `physical.bodies` lists them.

use std::fmt::Write as _;

use serde_json::{Value as Json, json};

use super::config::to_json;
use super::output_error::OutputError;
use super::resolved::resolved_json;
use super::staging::Staging;
use crate::model::geometry::G;
use crate::model::stack::{MAX_BLOCKS, Pose, SLIDE};
use crate::sim::stack_run::{StackRun, StackSample};
use crate::sim::{Physical, Scenario};

/// `summary.json` of a stack's run.
pub fn stack_summary(cfg: &Scenario, run: &StackRun) -> Json {
    let geo = cfg.geometry();
    let k = run.geo.k;
    json!({
        "outcome": run.outcome,
        "tau_end": run.tau_end,
        "impacts": run.tally.impacts,
        "events": run.events.len(),
        "final_mode": run.last.mode.name(k),
        "energy": run.energy,
        "solver": {
            "method": if cfg.run.method() == crate::sim::Method::Dopri5 { "dopri5" } else { "dop853" },
            "steps": run.stats.accepted,
            "rejected_steps": run.stats.rejected,
            "rhs_evals": run.stats.rhs_evals,
            "wall_s": run.wall_s,
        },
        // τ = p t with the bottom block's p.
        "stack": {
            "blocks": k,
            "p_per_s": geo.p,
            "seconds_per_tau": 1.0 / geo.p,
            "mass_fraction": (0..k).map(|j| run.geo.mass[j] / run.geo.total_mass).collect::<Vec<_>>(),
        },
        "physical": Physical::of_stack(cfg, run),
        "resolved": resolved_json(cfg),
        "g_m_s2": G,
        "units": "tau = p t with the bottom block's p; angles in rad; energies per M g R with M the stack's mass and R the bottom block's half-diagonal; `physical` gives seconds, degrees, metres and g",
        "version": env!("CARGO_PKG_VERSION"),
        "config": to_json(cfg),
    })
}

/// A number as the CSV files write it: shortest round trip.
fn num(out: &mut String, x: f64) {
    let _ = write!(out, "{x:?}");
}

/// `events.csv`: `tau,t_s,kind,body,mode_before,mode_after,q_dot_before_rad_s,q_dot_after_rad_s`,
/// with `body` the interface under that block (0: the base).
pub fn events_csv(run: &StackRun, p: f64) -> String {
    let k = run.geo.k;
    let mut out = String::from("tau,t_s,kind,body,mode_before,mode_after,q_dot_before_rad_s,q_dot_after_rad_s\n");
    for e in &run.events {
        num(&mut out, e.tau);
        out.push(',');
        num(&mut out, e.tau / p);
        let _ = write!(
            out,
            ",{},{},{},{},",
            e.kind.name(),
            e.body,
            e.before.name(k),
            e.after.name(k)
        );
        num(&mut out, e.q_dot_before * p);
        out.push(',');
        num(&mut out, e.q_dot_after * p);
        out.push('\n');
    }
    out
}

/// Each body's `theta_j_rad`, `theta_dot_j_rad_s`, `x_j_m` and `y_j_m`
/// at sample `s` of `run` (p in 1/s), bottom to top; the entries past the
/// stack's blocks are 0. `history.csv` and Python's `StackRun.history`
/// are made of these.
pub fn body_states(run: &StackRun, s: &StackSample, p: f64) -> [[f64; 4]; MAX_BLOCKS] {
    let pose = Pose::new(&run.geo, &s.mode.contacts, &s.y);
    let mut out = [[0.0; 4]; MAX_BLOCKS];
    for (j, o) in out.iter_mut().enumerate().take(run.geo.k) {
        *o = [pose.phi[j], pose.omega[j] * p, pose.centre[j][0], pose.centre[j][1]];
    }
    out
}

/// `history.csv`: `tau,t_s,mode,sliding_m` (the base face's slip: the
/// whole stack's displacement along the base caused by sliding), then for
/// each body j from 0:
/// `theta_j_rad` (its rotation, clockwise), `theta_dot_j_rad_s`, `x_j_m`
/// and `y_j_m` (its centre relative to the base).
pub fn history_csv(run: &StackRun, p: f64) -> String {
    let k = run.geo.k;
    let mut out = String::from("tau,t_s,mode,sliding_m");
    for j in 0..k {
        let _ = write!(out, ",theta_{j}_rad,theta_dot_{j}_rad_s,x_{j}_m,y_{j}_m");
    }
    out.push('\n');
    let row = |out: &mut String, s: &StackSample| {
        num(out, s.tau);
        out.push(',');
        num(out, s.tau / p);
        let _ = write!(out, ",{},", s.mode.name(k));
        num(out, s.y[SLIDE]);
        for body in &body_states(run, s, p)[..k] {
            for &v in body {
                out.push(',');
                num(out, v);
            }
        }
        out.push('\n');
    };
    for s in &run.history {
        row(&mut out, s);
    }
    out
}

/// Writes a stack's three files into `staging`.
pub(crate) fn write_stack(
    staging: &mut Staging,
    cfg: &Scenario,
    run: &StackRun,
    summary: &str,
) -> Result<(), OutputError> {
    let p = cfg.geometry().p;
    let (events, history) = (events_csv(run, p), history_csv(run, p));
    // Never a NaN in an output: refused, as the block's files refuse it.
    for (name, text) in [("events.csv", &events), ("history.csv", &history)] {
        if text.contains("NaN") || text.contains("inf") {
            return Err(OutputError::NonFinite(name.to_string()));
        }
    }
    staging.text("summary.json", summary)?;
    staging.text("events.csv", &events)?;
    staging.text("history.csv", &history)?;
    Ok(())
}
