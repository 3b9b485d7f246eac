//! Exports from the app: the current plots as one PNG (plotters), the data
//! as CSV (the batch writers of [`crate::io::output`]), and scene files.
//!
//! Contract: nothing half-written. Every file is written beside its target
//! under a temporary name and renamed into place; CSV sets go through
//! `io::output::write_all`, which stages a directory. Errors are one line
//! naming the file.

use std::ops::Range;
use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use crate::gui::history::{DensityGrid, RunHistory};
use crate::io::output::{events_csv, history_csv, poincare_csv, write_all};
use crate::sim::{HistoryRow, SectionRow};

/// Writes `bytes` to `path` through a temporary file in the same directory.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let tmp = temp_beside(path);
    let r = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r.map_err(|e| format!("{}: {e}", path.display()))
}

fn temp_beside(path: &Path) -> std::path::PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.partial-{}", std::process::id()))
}

/// Writes `history.csv` (the samples kept), `poincare.csv` and `events.csv`
/// into `dir`, in the batch run's formats.
pub(crate) fn data_csv(dir: &Path, hist: &RunHistory, geo: &crate::model::Geometry) -> Result<(), String> {
    // A sample is a batch history row with the base's motion beside it.
    let history: Vec<HistoryRow> = hist.samples.iter().map(|s| s.state).collect();
    let section: Vec<SectionRow> = hist.section_rows.iter().copied().collect();
    let events: Vec<_> = hist.events.iter().copied().collect();
    write_all(
        dir,
        &[
            ("history.csv", history_csv(&history, geo)),
            ("poincare.csv", poincare_csv(&section)),
            ("events.csv", events_csv(&events, geo)),
        ],
    )
    .map_err(|e| e.to_string())
}

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is compiled in; it cannot fail to parse, and if it did
        // the plots would only lack text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
    });
}

/// Draws the time history (window `window` ending at `now`), the phase
/// portrait (the last `trail` τ) and the Poincaré points into one PNG.
pub(crate) fn plots_png(path: &Path, hist: &RunHistory, now: f64, window: f64, trail: f64) -> Result<(), String> {
    register_font();
    let tmp = temp_beside(path).with_extension("png");
    let r = draw(&tmp, hist, now, window, trail)
        .and_then(|()| std::fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display())));
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r
}

fn range(values: impl Iterator<Item = f64>, min_span: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (-min_span, min_span);
    }
    let pad = 0.05 * (hi - lo).max(min_span);
    (lo - pad, hi + pad)
}

/// A panel's chart: plain f64 axes.
type Panel<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One of the three panels: a chart on `area` captioned `caption` over
/// `x` × `y`, its mesh drawn with the axes named `(x_desc, y_desc)`.
fn panel<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (Range<f64>, Range<f64>),
    (x_desc, y_desc): (&str, &str),
) -> Result<Panel<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d(x, y)?;
    chart.configure_mesh().x_desc(x_desc).y_desc(y_desc).draw()?;
    Ok(chart)
}

fn draw(file: &Path, hist: &RunHistory, now: f64, window: f64, trail: f64) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", file.display());
    let root = BitMapBackend::new(file, (1800, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let areas = root.split_evenly((1, 3));

    // Time history.
    let t0 = now - window;
    let window_samples: Vec<(f64, f64)> = hist
        .samples
        .iter()
        .filter(|s| s.tau >= t0)
        .map(|s| (s.tau, s.theta))
        .collect();
    let (y0, y1) = range(window_samples.iter().map(|p| p.1), 1.0);
    let mut chart = panel(&areas[0], "Θ(τ)", (t0..now.max(t0 + 1e-9), y0..y1), ("τ", "Θ")).map_err(|e| err(&e))?;
    chart
        .draw_series(LineSeries::new(window_samples, &BLUE))
        .map_err(|e| err(&e))?;

    // Phase portrait.
    let trail_pts: Vec<(f64, f64)> = hist
        .samples
        .iter()
        .filter(|s| s.tau >= now - trail)
        .map(|s| (s.theta, s.theta_dot))
        .collect();
    let (x0, x1) = range(trail_pts.iter().map(|p| p.0).chain([-1.0, 1.0]), 1.0);
    let (y0, y1) = range(trail_pts.iter().map(|p| p.1), 1.0);
    let mut chart = panel(&areas[1], "Phase portrait", (x0..x1, y0..y1), ("Θ", "Θ'")).map_err(|e| err(&e))?;
    chart
        .draw_series(LineSeries::new(trail_pts, &BLUE))
        .map_err(|e| err(&e))?;

    // Poincaré points, one dot per occupied pixel of a density grid (so a
    // million points export as fast as a thousand).
    let b = hist.section.bbox().unwrap_or([-1.0, 1.0, -1.0, 1.0]);
    let (x0, x1) = range([b[0], b[1]].into_iter(), 1e-3);
    let (y0, y1) = range([b[2], b[3]].into_iter(), 1e-3);
    let mut chart =
        panel(&areas[2], "Poincaré points", (x0..x1, y0..y1), ("Θ(τ_k)", "Θ'(τ_k)")).map_err(|e| err(&e))?;
    let (w, h) = (520usize, 500usize);
    let mut grid = DensityGrid::default();
    grid.update(&hist.section, [x0, x1, y0, y1], [w, h]);
    let dots = grid.counts.iter().enumerate().filter(|(_, c)| **c > 0).map(|(i, _)| {
        let (ix, iy) = (i % w, i / w);
        let x = x0 + (ix as f64 + 0.5) / w as f64 * (x1 - x0);
        let y = y1 - (iy as f64 + 0.5) / h as f64 * (y1 - y0);
        Pixel::new((x, y), BLACK)
    });
    chart.draw_series(dots).map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}
