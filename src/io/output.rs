//! Writers for a batch run's files, and an output directory that appears
//! whole or not at all.
//!
//! Numbers are written with Rust's shortest round-trip formatting, so a
//! value read back is bit-identical. The run never produces NaN (the
//! stepper stops with an error first); a non-finite number reaching a
//! writer is an error, never written.

use std::path::Path;

use serde::Serialize;
use serde_json::json;

use super::config::to_json;
use super::csv::{self, Num, Row};
use super::staging::{self, Staging};
use crate::model::Mode;
use crate::model::system::EventRecord;
use crate::sim::{HistoryRow, RunResult, Scenario, SectionRow};

/// A row of `events.csv`.
#[derive(Serialize)]
struct EventRow {
    tau: Num,
    kind: &'static str,
    mode_before: &'static str,
    mode_after: &'static str,
    theta: Num,
    theta_dot_before: Num,
    theta_dot_after: Num,
    x_dot: Num,
}

impl Row for EventRow {
    const HEADER: &'static [&'static str] = &[
        "tau",
        "kind",
        "mode_before",
        "mode_after",
        "theta",
        "theta_dot_before",
        "theta_dot_after",
        "x_dot",
    ];
}

/// `events.csv`.
pub fn events_csv(events: &[EventRecord]) -> String {
    csv::to_string(events.iter().map(|e| EventRow {
        tau: Num(e.tau),
        kind: e.kind.name(),
        mode_before: e.before.name(),
        mode_after: e.after.name(),
        theta: Num(e.theta),
        theta_dot_before: Num(e.theta_dot_before),
        theta_dot_after: Num(e.theta_dot_after),
        x_dot: Num(e.x_dot),
    }))
}

/// A row of `poincare.csv`.
#[derive(Serialize)]
struct PoincareRow {
    k: u64,
    tau: Num,
    theta: Num,
    theta_dot: Num,
    x: Num,
    x_dot: Num,
    mode: &'static str,
}

impl Row for PoincareRow {
    const HEADER: &'static [&'static str] = &["k", "tau", "theta", "theta_dot", "x", "x_dot", "mode"];
}

/// `poincare.csv`.
pub fn poincare_csv(points: &[SectionRow]) -> String {
    csv::to_string(points.iter().map(|p| PoincareRow {
        k: p.k,
        tau: Num(p.tau),
        theta: Num(p.theta),
        theta_dot: Num(p.theta_dot),
        x: Num(p.x),
        x_dot: Num(p.x_dot),
        mode: p.mode.name(),
    }))
}

/// A row of `history.csv`.
#[derive(Serialize)]
struct HistoryCsvRow {
    tau: Num,
    theta: Num,
    theta_dot: Num,
    x: Num,
    x_dot: Num,
    mode: &'static str,
}

impl Row for HistoryCsvRow {
    const HEADER: &'static [&'static str] = &["tau", "theta", "theta_dot", "x", "x_dot", "mode"];
}

/// `history.csv`.
pub fn history_csv(rows: &[HistoryRow]) -> String {
    csv::to_string(rows.iter().map(|r| HistoryCsvRow {
        tau: Num(r.tau),
        theta: Num(r.theta),
        theta_dot: Num(r.theta_dot),
        x: Num(r.x),
        x_dot: Num(r.x_dot),
        mode: r.mode.name(),
    }))
}

/// `summary.json`: outcome, times, the energy audit, work counters and the
/// complete resolved configuration with the crate version.
pub fn summary_json(cfg: &Scenario, res: &RunResult) -> serde_json::Value {
    let mode_time: serde_json::Map<String, serde_json::Value> = Mode::NAMES[..4]
        .iter()
        .zip(res.mode_time)
        .map(|(n, t)| (n.to_string(), json!(t)))
        .collect();
    let geo = cfg.geometry();
    json!({
        "outcome": res.outcome,
        "tau_end": res.tau_end,
        "tumble_tau": res.tumble_tau,
        "side_landing_tau": res.side_landing_tau,
        "flight_tau": res.flight_tau,
        "max_abs_theta": res.max_abs_theta,
        "impacts": res.tally.impacts,
        "events": res.events.len(),
        "flight_violations": res.tally.flight_violations,
        "final_mode": res.final_mode.name(),
        "mode_time": mode_time,
        "energy": res.energy,
        "solver": {
            "method": cfg.run.method().name(),
            "steps": res.stats.accepted,
            "rejected_steps": res.stats.rejected,
            "rhs_evals": res.stats.rhs_evals,
            "wall_s": res.wall_s,
        },
        "block": {
            "psi_rad": geo.psi,
            "p_per_s": geo.p,
            "r_m": geo.r,
            "housner_r": geo.housner_r(),
            "seconds_per_tau": 1.0 / geo.p,
        },
        "units": "normalised: tau = p t, theta = θ/ψ, x = x_G/R, energies per m g R (MODEL-DECISIONS)",
        "version": env!("CARGO_PKG_VERSION"),
        "config": to_json(cfg),
    })
}

/// Errors writing outputs.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A file system operation failed.
    #[error("{path}: {source}")]
    Io {
        /// The path involved.
        path: String,
        /// The error.
        source: std::io::Error,
    },
    /// The output path exists and is not a directory.
    #[error("{0}: exists and is not a directory")]
    NotADirectory(String),
    /// A value to be written was not finite.
    #[error("refusing to write a non-finite number to {0}")]
    NonFinite(String),
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Checks that `dir` can be written, before a run starts: it is a
/// directory or can be created, and a file can be made in it.
pub fn check_writable(dir: &Path) -> Result<(), OutputError> {
    if dir.exists() && !dir.is_dir() {
        return Err(OutputError::NotADirectory(dir.display().to_string()));
    }
    let parent = staging::parent_of(dir);
    std::fs::create_dir_all(&parent).map_err(io_err(&parent))?;
    let probe = parent.join(format!(".rocking-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(io_err(&parent))?;
    std::fs::remove_file(&probe).map_err(io_err(&probe))?;
    Ok(())
}

/// Writes `files` (name, contents) into `dir` so that no half-written set is
/// ever left ([`Staging`]). Every file is checked before anything is
/// created.
pub fn write_all(dir: &Path, files: &[(&str, String)]) -> Result<(), OutputError> {
    // CSV cells are numbers and lower-case names, none of which contains
    // "NaN" or "inf": finding either means a non-finite number.
    for (name, text) in files {
        if name.ends_with(".csv") && (text.contains("NaN") || text.contains("inf")) {
            return Err(OutputError::NonFinite(name.to_string()));
        }
    }
    let mut staging = Staging::new(dir)?;
    for (name, text) in files {
        staging.text(name, text)?;
    }
    staging.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{EventKind, Sign};

    #[test]
    fn headers_are_the_row_fields() {
        let e = EventRow {
            tau: Num(0.0),
            kind: "impact",
            mode_before: "rock",
            mode_after: "rock",
            theta: Num(0.0),
            theta_dot_before: Num(0.0),
            theta_dot_after: Num(0.0),
            x_dot: Num(0.0),
        };
        assert_eq!(csv::header_of(&e), csv::header::<EventRow>());
        let p = PoincareRow {
            k: 0,
            tau: Num(0.0),
            theta: Num(0.0),
            theta_dot: Num(0.0),
            x: Num(0.0),
            x_dot: Num(0.0),
            mode: "rest",
        };
        assert_eq!(csv::header_of(&p), csv::header::<PoincareRow>());
        let h = HistoryCsvRow {
            tau: Num(0.0),
            theta: Num(0.0),
            theta_dot: Num(0.0),
            x: Num(0.0),
            x_dot: Num(0.0),
            mode: "rest",
        };
        assert_eq!(csv::header_of(&h), csv::header::<HistoryCsvRow>());
    }

    #[test]
    fn numbers_are_written_shortest_round_trip() {
        let rows = [HistoryRow {
            tau: 0.1 + 0.2,
            theta: 1e-5,
            theta_dot: -1.0,
            x: 1e16,
            x_dot: 0.0001,
            mode: Mode::Rock { pivot: Sign::Neg },
        }];
        assert_eq!(
            history_csv(&rows),
            "tau,theta,theta_dot,x,x_dot,mode\n0.30000000000000004,1e-5,-1.0,1e16,0.0001,rock\n"
        );
        assert_eq!(history_csv(&[]), "tau,theta,theta_dot,x,x_dot,mode\n");
        let e = EventRecord {
            tau: 2.5,
            kind: EventKind::Impact,
            before: Mode::Rock { pivot: Sign::Pos },
            after: Mode::Rest,
            theta: 0.0,
            theta_dot_before: 0.25,
            theta_dot_after: 0.0,
            x_dot: 0.0,
        };
        assert_eq!(
            events_csv(&[e]).lines().nth(1),
            Some("2.5,impact,rock,rest,0.0,0.25,0.0,0.0")
        );
    }
}
