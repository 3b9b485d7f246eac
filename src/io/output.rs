//! Writers for a batch run's files, and an output directory that appears
//! whole or not at all.
//!
//! Numbers are written with Rust's shortest round-trip formatting, so a
//! value read back is bit-identical. The run never produces NaN (the
//! stepper stops with an error first); a non-finite number reaching a
//! writer is an error, never written.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::json;

use super::config::to_json;
use super::csv::{self, Num, Row};
use super::output_error::{OutputError, io_err};
use super::staging::{self, Staging};
use crate::model::frame::Frame;
use crate::model::geometry::G;
use crate::model::system::EventRecord;
use crate::model::{Geometry, Mode};
use crate::sim::{HistoryRow, Physical, RunResult, Scenario, SectionRow, Sink};

/// A row of `events.csv`: the normalised state (`tau`, `theta`, …) and the
/// same event in physical units (`t_s`, `theta_rad`, `sliding_m`).
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
    t_s: Num,
    theta_rad: Num,
    sliding_m: Num,
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
        "t_s",
        "theta_rad",
        "sliding_m",
    ];
}

/// `events.csv` of a run of block `geo`.
pub fn events_csv(events: &[EventRecord], geo: &Geometry) -> String {
    csv::to_string(events.iter().map(|e| event_row(e, geo)))
}

/// The `events.csv` row of event `e` of block `geo`.
fn event_row(e: &EventRecord, geo: &Geometry) -> EventRow {
    EventRow {
        tau: Num(e.tau),
        kind: e.kind.name(),
        mode_before: e.before.name(),
        mode_after: e.after.name(),
        theta: Num(e.theta),
        theta_dot_before: Num(e.theta_dot_before),
        theta_dot_after: Num(e.theta_dot_after),
        x_dot: Num(e.x_dot),
        t_s: Num(e.tau / geo.p),
        theta_rad: Num(e.theta * geo.psi),
        sliding_m: Num(geo.sliding(e.theta, e.x) * geo.r),
    }
}

/// A frame's `events.csv` `body`: every event of a frame is at its columns
/// (they lift, land and overturn together, the beam carried on their top
/// corners).
pub const FRAME_EVENT_BODY: &str = "columns";

/// The per-body columns a frame's `history.csv` adds, as the stack's:
/// `theta_j_rad`, `theta_dot_j_rad_s`, `x_j_m` and `y_j_m` for each column
/// j from 0, then the beam. A frame's `x_j_m` and `y_j_m` are the body's
/// centre's displacement from where it stands at rest (the model needs no
/// spacing between the columns, so it has no common origin).
pub fn frame_history_header(frame: &Frame) -> Vec<String> {
    (0..=frame.columns)
        .flat_map(|j| {
            [
                format!("theta_{j}_rad"),
                format!("theta_dot_{j}_rad_s"),
                format!("x_{j}_m"),
                format!("y_{j}_m"),
            ]
        })
        .collect()
}

/// Each body's cells of a frame's `history.csv` row `r`
/// ([`frame_history_header`]; [`Frame::bodies`]).
pub fn frame_body_cells(frame: &Frame, geo: &Geometry, r: &HistoryRow) -> Vec<Num> {
    let [column, beam] = frame.bodies(geo, r.theta * geo.psi);
    let rate = r.theta_dot * geo.psi * geo.p;
    let mut cells = Vec::with_capacity(4 * (frame.columns as usize + 1));
    for _ in 0..frame.columns {
        cells.extend([column[0], rate, column[1], column[2]].map(Num));
    }
    cells.extend([beam[0], 0.0, beam[1], beam[2]].map(Num));
    cells
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
    csv::to_string(points.iter().map(poincare_row))
}

/// The `poincare.csv` row of section point `p`.
fn poincare_row(p: &SectionRow) -> PoincareRow {
    PoincareRow {
        k: p.k,
        tau: Num(p.tau),
        theta: Num(p.theta),
        theta_dot: Num(p.theta_dot),
        x: Num(p.x),
        x_dot: Num(p.x_dot),
        mode: p.mode.name(),
    }
}

/// A row of `history.csv`: the normalised state and, after `mode`, the
/// same instant in physical units.
#[derive(Serialize)]
struct HistoryCsvRow {
    tau: Num,
    theta: Num,
    theta_dot: Num,
    x: Num,
    x_dot: Num,
    mode: &'static str,
    t_s: Num,
    theta_rad: Num,
    sliding_m: Num,
}

impl Row for HistoryCsvRow {
    const HEADER: &'static [&'static str] = &[
        "tau",
        "theta",
        "theta_dot",
        "x",
        "x_dot",
        "mode",
        "t_s",
        "theta_rad",
        "sliding_m",
    ];
}

/// `history.csv` of a run of block `geo`.
pub fn history_csv(rows: &[HistoryRow], geo: &Geometry) -> String {
    csv::to_string(rows.iter().map(|r| history_row(r, geo)))
}

/// The `history.csv` row of history row `r` of block `geo`.
fn history_row(r: &HistoryRow, geo: &Geometry) -> HistoryCsvRow {
    HistoryCsvRow {
        tau: Num(r.tau),
        theta: Num(r.theta),
        theta_dot: Num(r.theta_dot),
        x: Num(r.x),
        x_dot: Num(r.x_dot),
        mode: r.mode.name(),
        t_s: Num(r.tau / geo.p),
        theta_rad: Num(r.theta * geo.psi),
        sliding_m: Num(geo.sliding(r.theta, r.x) * geo.r),
    }
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
        "events": res.tallies.events,
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
        crate::io::resolved::structure_key(cfg): match &cfg.frame {
            None => json!({
                "psi_rad": geo.psi,
                "p_per_s": geo.p,
                "r_m": geo.r,
                "housner_r": geo.housner_r(),
                "seconds_per_tau": 1.0 / geo.p,
            }),
            // The columns' ψ, p and R (τ = p t with the column's p), and
            // the frame's own factor and impact coefficient.
            Some(frame) => json!({
                "psi_rad": geo.psi,
                "p_per_s": geo.p,
                "r_m": geo.r,
                "kappa": frame.kappa(),
                "impact_r": frame.restitution(&geo),
                "seconds_per_tau": 1.0 / geo.p,
            }),
        },
        "physical": Physical::of(cfg, res),
        "resolved": resolved_json(cfg),
        "g_m_s2": G,
        "units": "normalised: tau = p t, theta = θ/ψ, x = x_G/R, energies per m g R (MODEL-DECISIONS); `physical` and `resolved` give seconds, radians, degrees, metres and g",
        "version": env!("CARGO_PKG_VERSION"),
        "config": to_json(cfg),
    })
}

/// A run's three CSV files written as the run produces them, into a
/// staging folder ([`Staging`]), so that a batch run's memory does not grow
/// with its length. The first write error (a full disk) or non-finite
/// number is kept and reported by [`RunFiles::finish`]; nothing after it
/// is written.
pub(crate) struct RunFiles {
    events: ::csv::Writer<BufWriter<File>>,
    poincare: ::csv::Writer<BufWriter<File>>,
    history: ::csv::Writer<BufWriter<File>>,
    paths: [PathBuf; 3],
    geo: Geometry,
    /// A frame's, whose files add each body ([`frame_history_header`]).
    frame: Option<Frame>,
    /// History rows kept for an analysis that needs them (the spectrum).
    kept: Option<Vec<HistoryRow>>,
    error: Option<OutputError>,
}

impl RunFiles {
    /// Opens `events.csv`, `poincare.csv` and `history.csv` in `staging`
    /// and writes their headers; with `keep_history` the history rows are
    /// also kept in memory (for `analysis.spectrum`).
    pub fn create(
        staging: &mut Staging,
        geo: Geometry,
        frame: Option<Frame>,
        keep_history: bool,
    ) -> Result<Self, OutputError> {
        let paths = [
            staging.path("events.csv"),
            staging.path("poincare.csv"),
            staging.path("history.csv"),
        ];
        let open = |path: &Path, header: &[&str]| -> Result<::csv::Writer<BufWriter<File>>, OutputError> {
            let file = File::create(path).map_err(|error| OutputError::Io {
                path: path.display().to_string(),
                error,
            })?;
            // 64 KiB buffers: large enough that a write costs little per
            // byte, small enough to stay in the cache and be reused. A
            // 1 MiB buffer is fresh memory that is page-faulted in 4 KiB at
            // a time as it fills (256 faults for each MiB of output) and
            // costs a short run more than the writes it saves.
            let mut w = ::csv::WriterBuilder::new()
                .has_headers(false)
                .from_writer(BufWriter::with_capacity(64 << 10, file));
            w.write_record(header).map_err(|e| csv_error(path, e))?;
            Ok(w)
        };
        let owned = |h: &[&str]| h.iter().map(|s| s.to_string()).collect::<Vec<String>>();
        let (events, history) = match &frame {
            None => (owned(EventRow::HEADER), owned(HistoryCsvRow::HEADER)),
            Some(f) => (
                owned(&[EventRow::HEADER, &["body"]].concat()),
                [owned(HistoryCsvRow::HEADER), frame_history_header(f)].concat(),
            ),
        };
        fn refs(h: &[String]) -> Vec<&str> {
            h.iter().map(String::as_str).collect()
        }
        Ok(Self {
            events: open(&paths[0], &refs(&events))?,
            poincare: open(&paths[1], PoincareRow::HEADER)?,
            history: open(&paths[2], &refs(&history))?,
            paths,
            geo,
            frame,
            kept: keep_history.then(Vec::new),
            error: None,
        })
    }

    /// Flushes the files; the first error met while writing, if any.
    /// Returns the history rows kept for the spectrum (empty unless asked).
    pub fn finish(mut self) -> Result<Vec<HistoryRow>, OutputError> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        for (w, path) in [&mut self.events, &mut self.poincare, &mut self.history]
            .into_iter()
            .zip(&self.paths)
        {
            w.flush().map_err(|error| OutputError::Io {
                path: path.display().to_string(),
                error,
            })?;
        }
        Ok(self.kept.take().unwrap_or_default())
    }

    fn write<R: Serialize>(
        error: &mut Option<OutputError>,
        w: &mut ::csv::Writer<BufWriter<File>>,
        path: &Path,
        values: &[f64],
        row: R,
    ) {
        if error.is_some() {
            return;
        }
        if values.iter().any(|v| !v.is_finite()) {
            *error = Some(OutputError::NonFinite(path.display().to_string()));
        } else if let Err(e) = w.serialize(row) {
            *error = Some(csv_error(path, e));
        }
    }
}

/// A CSV writer's error as an output error naming the file.
fn csv_error(path: &Path, e: ::csv::Error) -> OutputError {
    let error = match e.into_kind() {
        ::csv::ErrorKind::Io(error) => error,
        other => std::io::Error::other(format!("{other:?}")),
    };
    OutputError::Io {
        path: path.display().to_string(),
        error,
    }
}

impl Sink for RunFiles {
    fn sample(&mut self, row: &HistoryRow) {
        let values = [row.tau, row.theta, row.theta_dot, row.x, row.x_dot];
        let csv_row = history_row(row, &self.geo);
        match &self.frame {
            None => Self::write(&mut self.error, &mut self.history, &self.paths[2], &values, csv_row),
            Some(f) => {
                let bodies = frame_body_cells(f, &self.geo, row);
                Self::write(
                    &mut self.error,
                    &mut self.history,
                    &self.paths[2],
                    &values,
                    (csv_row, bodies),
                );
            }
        }
        if let Some(kept) = &mut self.kept {
            kept.push(*row);
        }
    }

    fn section(&mut self, row: &SectionRow) {
        let values = [row.tau, row.theta, row.theta_dot, row.x, row.x_dot];
        Self::write(
            &mut self.error,
            &mut self.poincare,
            &self.paths[1],
            &values,
            poincare_row(row),
        );
    }

    fn event(&mut self, e: &EventRecord) {
        let values = [e.tau, e.theta, e.theta_dot_before, e.theta_dot_after, e.x_dot, e.x];
        let row = event_row(e, &self.geo);
        match self.frame {
            None => Self::write(&mut self.error, &mut self.events, &self.paths[0], &values, row),
            Some(_) => Self::write(
                &mut self.error,
                &mut self.events,
                &self.paths[0],
                &values,
                (row, FRAME_EVENT_BODY),
            ),
        }
    }
}

pub use super::resolved::resolved_json;

/// Checks that `dir` can be written, before a run starts: it is a
/// directory or can be created, and a file can be made in it.
pub(crate) fn check_writable(dir: &Path) -> Result<(), OutputError> {
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
    // Numbers, not text: a record or scene name may spell "inf" or "nan".
    for (name, text) in files {
        if name.ends_with(".csv") && csv::has_non_finite(text) {
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
        let geo = Geometry::new(1.0, 4.0);
        let e = EventRecord {
            tau: 0.0,
            kind: EventKind::Impact,
            before: Mode::Rest,
            after: Mode::Rest,
            theta: 0.0,
            theta_dot_before: 0.0,
            theta_dot_after: 0.0,
            x_dot: 0.0,
            x: 0.0,
        };
        let header = |text: String| text.lines().next().unwrap_or_default().to_string();
        assert_eq!(header(events_csv(&[e], &geo)), csv::header::<EventRow>());
        assert_eq!(header(poincare_csv(&[])), csv::header::<PoincareRow>());
        assert_eq!(header(history_csv(&[], &geo)), csv::header::<HistoryCsvRow>());
    }

    #[test]
    fn numbers_are_written_shortest_round_trip_with_their_physical_twins() {
        // B = 0.6, H = 0.8: R = 0.5 m, ψ = atan(0.75), p = √(3g/2).
        let geo = Geometry::new(0.6, 0.8);
        let rows = [HistoryRow {
            tau: 0.1 + 0.2,
            theta: 1e-5,
            theta_dot: -1.0,
            x: 1e16,
            x_dot: 0.0001,
            mode: Mode::Slide { slip: Sign::Neg },
        }];
        let t_s = 0.30000000000000004 / geo.p;
        let theta_rad = 1e-5 * geo.psi;
        let expected = format!(
            "tau,theta,theta_dot,x,x_dot,mode,t_s,theta_rad,sliding_m\n0.30000000000000004,1e-5,-1.0,1e16,0.0001,slide,{t_s:?},{theta_rad:?},5000000000000000.0\n"
        );
        assert_eq!(history_csv(&rows, &geo), expected);
        // Rocking on the left corner (s = −1) at Θ = −0.5 with X = −0.1:
        // U = X − (sin(ψ/2) − sin ψ), and sliding_m = R·U.
        let e = EventRecord {
            tau: 2.5,
            kind: EventKind::Impact,
            before: Mode::Rock { pivot: Sign::Neg },
            after: Mode::Rest,
            theta: -0.5,
            theta_dot_before: 0.25,
            theta_dot_after: 0.0,
            x_dot: 0.0,
            x: -0.1,
        };
        let u = -0.1 - ((0.5 * geo.psi).sin() - geo.psi.sin());
        let (t_s, theta_rad, sliding_m) = (2.5 / geo.p, -0.5 * geo.psi, 0.5 * u);
        let expected = format!("2.5,impact,rock,rest,-0.5,0.25,0.0,0.0,{t_s:?},{theta_rad:?},{sliding_m:?}");
        assert_eq!(events_csv(&[e], &geo).lines().nth(1).unwrap_or_default(), expected);
    }
}
