//! The files of a whole fragility study (`runs.csv`, `fractions.csv`,
//! `fragility.json`, the figures), from one run or from merged shards.

use std::path::Path;

use serde_json::{Value as Json, json};

use super::Layout;
use crate::analysis::engineering::EndState;
use crate::analysis::engineering::fragility::{LevelSummary, fit_block, summarise};
use crate::analysis::engineering::lognormal::{FitError, LognormalFit};
use crate::cli::error::BatchError;
use crate::io::csv::{self, Num};
use crate::io::engineering_files::{FractionRow, FragilityRunRow, IncrementalRow};
use crate::plot::fragility::{FragilityCurve, FragilityFigure, FragilityPanel};
use crate::plot::incremental::{IncrementalCurve, IncrementalFigure, IncrementalPanel};
use crate::plot::labels::num;

/// Points of the fitted curve in `fragility.json` and the figure.
const BAND_POINTS: usize = 60;

/// Fit or error as JSON, with the band on a fine grid.
fn fit_json(fit: &Result<LognormalFit, FitError>, grid: &[f64]) -> Json {
    match fit {
        Ok(f) => {
            let mut j = serde_json::to_value(f).unwrap_or(Json::Null);
            j["band"] = json!(grid.iter().map(|&x| f.at(x)).collect::<Vec<_>>());
            j
        }
        Err(e) => json!({ "error": e.to_string() }),
    }
}

/// One-line text of a fit.
fn fit_text(fit: &Result<LognormalFit, FitError>, unit: &str) -> String {
    match fit {
        Ok(f) => format!(
            "median {:.4} {unit} (95 %: {:.4}–{:.4}), β {:.3} ({:.3}–{:.3})",
            f.median, f.median_ci95[0], f.median_ci95[1], f.beta, f.beta_ci95[0], f.beta_ci95[1]
        ),
        Err(e) => format!("no fit: {e}"),
    }
}

/// The whole study's files from all its rows (in run order), written into
/// `out`; returns the summary lines. `common` is `fragility.json` without
/// fits (shard null).
pub(super) fn write_whole(
    out: &Path,
    common: Json,
    layout: &Layout,
    rows: Vec<FragilityRunRow>,
) -> Result<Vec<String>, BatchError> {
    let (nl, nr) = (layout.levels.len(), layout.records);
    let counts: Vec<Vec<LevelSummary>> = summarise(
        layout.blocks.len(),
        nl,
        layout.threshold,
        rows.iter().map(|r| {
            let i = r.run as usize;
            let end = EndState::from_name(&r.end).unwrap_or(EndState::Moving);
            (i / (nl * nr), (i / nr) % nl, end, r.peak_theta_over_alpha.0)
        }),
    );
    let x_max = layout.levels.iter().copied().fold(0.0, f64::max);
    let grid: Vec<f64> = (1..=BAND_POINTS)
        .map(|k| 1.1 * x_max * k as f64 / BAND_POINTS as f64)
        .collect();
    let unit = layout.im.unit();
    let mut fraction_rows = Vec::new();
    let mut fits_json = Vec::new();
    let mut lines = Vec::new();
    let mut over_curves = Vec::new();
    let mut exceed_curves = Vec::new();
    for (b, (block, c)) in layout.blocks.iter().zip(&counts).enumerate() {
        let fits = fit_block(&layout.levels, c);
        for (&level, s) in layout.levels.iter().zip(c) {
            let over = fits.overturn.as_ref().ok().map(|f| f.at(level));
            let exceed = fits.exceed.as_ref().ok().map(|f| f.at(level));
            fraction_rows.push(FractionRow {
                block: b as u64,
                width_m: Num(block.width_m),
                height_m: Num(block.height_m),
                im: layout.im.column().to_string(),
                level: Num(level),
                runs: s.runs,
                overturned: s.overturned,
                flight: s.flight,
                exceeded: s.exceeded,
                fraction_overturned: s.fraction_overturned().map(Num),
                fraction_exceeded: s.fraction_exceeded().map(Num),
                fit_overturned: over.map(|p| Num(p.p)),
                fit_overturned_lo: over.map(|p| Num(p.lo)),
                fit_overturned_hi: over.map(|p| Num(p.hi)),
                fit_exceeded: exceed.map(|p| Num(p.p)),
                fit_exceeded_lo: exceed.map(|p| Num(p.lo)),
                fit_exceeded_hi: exceed.map(|p| Num(p.hi)),
            });
        }
        let name = layout.block_name(block);
        fits_json.push(json!({
            "block": b,
            "width_m": block.width_m,
            "height_m": block.height_m,
            "r_m": block.half_diagonal_m(),
            "alpha_rad": block.alpha(),
            "p_per_s": block.p_per_s(),
            "overturning": fit_json(&fits.overturn, &grid),
            "exceedance": fit_json(&fits.exceed, &grid),
        }));
        lines.push(format!("{name}: overturning {}", fit_text(&fits.overturn, unit)));
        lines.push(format!(
            "{name}: θ/α ≥ {} {}",
            num(layout.threshold),
            fit_text(&fits.exceed, unit)
        ));
        let observed = |f: fn(&LevelSummary) -> Option<f64>| -> Vec<(f64, f64)> {
            layout
                .levels
                .iter()
                .zip(c)
                .filter_map(|(&x, s)| f(s).map(|y| (x, y)))
                .collect()
        };
        let curve = |fit: &Result<LognormalFit, FitError>| match fit {
            Ok(f) => grid.iter().map(|&x| f.at(x)).collect(),
            Err(_) => Vec::new(),
        };
        over_curves.push(FragilityCurve {
            label: match &fits.overturn {
                Ok(f) => format!("{name}: median {:.3} {unit}, β {:.2}", f.median, f.beta),
                Err(_) => format!("{name}: no fit"),
            },
            observed: observed(LevelSummary::fraction_overturned),
            fitted: curve(&fits.overturn),
        });
        exceed_curves.push(FragilityCurve {
            label: match &fits.exceed {
                Ok(f) => format!("{name}: median {:.3} {unit}, β {:.2}", f.median, f.beta),
                Err(_) => format!("{name}: no fit"),
            },
            observed: observed(LevelSummary::fraction_exceeded),
            fitted: curve(&fits.exceed),
        });
    }
    let mut meta = common;
    meta["fits"] = Json::Array(fits_json);
    let fig = FragilityFigure {
        title: format!(
            "Fragility of free-standing blocks: {} records × {} levels",
            layout.records,
            layout.levels.len()
        ),
        subtitle: format!(
            "{}; markers: fraction of records, lines: lognormal MLE, shaded: 95 % band (Fisher information, delta method)",
            layout.conditions()
        ),
        x_label: layout.im.label_at(layout.sa_period),
        x_max: 1.1 * x_max,
        panels: vec![
            FragilityPanel {
                caption: "P(overturning)".into(),
                curves: over_curves,
            },
            FragilityPanel {
                caption: format!("P(peak θ/α ≥ {} or overturning)", num(layout.threshold)),
                curves: exceed_curves,
            },
        ],
    };
    let (incremental_rows, incremental_fig) = incremental(layout, &rows, layout.overturn_at);
    crate::cli::write::staged(out, |staging| {
        staging.text("runs.csv", &csv::to_string(rows))?;
        staging.text("fractions.csv", &csv::to_string(fraction_rows))?;
        staging.text("incremental.csv", &csv::to_string(incremental_rows))?;
        crate::cli::write::figure(staging, "incremental", &incremental_fig)?;
        staging.text("fragility.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
        crate::cli::write::figure(staging, "fragility", &fig)?;
        Ok(())
    })?;
    Ok(lines)
}

/// Each record's incremental curve for each block (its runs in increasing
/// level) from the study's rows (in run order: block, level, record), as
/// rows of `incremental.csv` and the figure; overturned runs are drawn at
/// `overturn_at` (θ/α).
fn incremental(
    layout: &Layout,
    rows: &[FragilityRunRow],
    overturn_at: f64,
) -> (Vec<IncrementalRow>, IncrementalFigure) {
    let (nl, nr) = (layout.levels.len(), layout.records);
    let at = |b: usize, l: usize, r: usize| rows.get((b * nl + l) * nr + r);
    let mut out = Vec::with_capacity(rows.len());
    let mut panels = Vec::with_capacity(layout.blocks.len());
    for (b, block) in layout.blocks.iter().enumerate() {
        let mut curves = Vec::with_capacity(nr);
        for r in 0..nr {
            let mut points = Vec::with_capacity(nl);
            let mut label = String::new();
            for l in 0..nl {
                let Some(row) = at(b, l, r) else { continue };
                label.clone_from(&row.record);
                let end = EndState::from_name(&row.end).unwrap_or(EndState::Moving);
                points.push((row.level.0, row.peak_theta_over_alpha.0, end));
                out.push(IncrementalRow {
                    block: b as u64,
                    width_m: row.width_m,
                    height_m: row.height_m,
                    record: row.record.clone(),
                    im: row.im.clone(),
                    level: row.level,
                    peak_theta_over_alpha: row.peak_theta_over_alpha,
                    end: row.end.clone(),
                });
            }
            curves.push(IncrementalCurve { label, points });
        }
        panels.push(IncrementalPanel {
            caption: layout.block_name(block),
            curves,
        });
    }
    let fig = IncrementalFigure {
        title: format!(
            "Incremental curves: peak rotation of each block under each of {} records",
            layout.records
        ),
        subtitle: format!(
            "{}; one line per record; cross: overturned (drawn at θ/α = {}), triangle: flight",
            layout.conditions(),
            num(overturn_at)
        ),
        y_label: layout.im.label_at(layout.sa_period),
        y_max: layout.levels.iter().copied().fold(0.0, f64::max),
        overturn_at,
        panels,
    };
    (out, fig)
}
