//! Writers for a batch run's files, and an output directory that appears
//! whole or not at all.
//!
//! Numbers are written with Rust's shortest round-trip formatting, so a
//! value read back is bit-identical. The run never produces NaN (the
//! stepper stops with an error first); a non-finite number reaching a
//! writer is an error, never written.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde_json::json;

use super::config::to_json;
use super::staging::Staging;
use crate::model::Mode;
use crate::model::system::EventRecord;
use crate::sim::{HistoryRow, RunResult, Scenario, SectionRow};

/// A number for CSV/JSON: shortest round-trip form.
fn num(x: f64) -> String {
    format!("{x:?}")
}

/// `events.csv`.
pub fn events_csv(events: &[EventRecord]) -> String {
    let mut s = String::from("tau,kind,mode_before,mode_after,theta,theta_dot_before,theta_dot_after,x_dot\n");
    for e in events {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            num(e.tau),
            e.kind.name(),
            e.before.name(),
            e.after.name(),
            num(e.theta),
            num(e.theta_dot_before),
            num(e.theta_dot_after),
            num(e.x_dot)
        );
    }
    s
}

/// `poincare.csv`.
pub fn poincare_csv(points: &[SectionRow]) -> String {
    let mut s = String::from("k,tau,theta,theta_dot,x,x_dot,mode\n");
    for p in points {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{}",
            p.k,
            num(p.tau),
            num(p.theta),
            num(p.theta_dot),
            num(p.x),
            num(p.x_dot),
            p.mode.name()
        );
    }
    s
}

/// `history.csv`.
pub fn history_csv(rows: &[HistoryRow]) -> String {
    let mut s = String::from("tau,theta,theta_dot,x,x_dot,mode\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{}",
            num(r.tau),
            num(r.theta),
            num(r.theta_dot),
            num(r.x),
            num(r.x_dot),
            r.mode.name()
        );
    }
    s
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
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
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
