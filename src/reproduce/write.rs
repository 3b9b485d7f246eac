//! The files of a reproduction: figures (PNG and SVG), CSV tables,
//! `reproduce.json` and `report.md`, written through a [`Sink`].
//!
//! File names are flat and sort by figure: `fig04_bifurcation.png`,
//! `fig04_variant_ralston_bifurcation.svg`, `fig07_time_history.png`, …
//! CSV numbers are written in their shortest round-trip form, so the files
//! are a function of the computation alone.

use std::path::PathBuf;

use serde_json::{Value as Json, json};

use super::diagrams::{Diagram, compare_ranges, counts_text};
use super::format::{block_and_impact, diagram_stem, prefix, short_num, short_params};
use super::paper;
use super::report;
use super::response::{ResponseExample, SpectrumData};
use super::variant::Variant;
use super::{ReproduceError, Reproduction};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::Lyapunov;
use crate::analysis::orbit_diagram::Continuation;
use crate::io::config::to_json;
use crate::io::csv::{self, Num, Row};
use crate::io::output_error::OutputError;
use crate::io::sweep_files::point_rows;
use crate::plot::Figure;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::labels::{grid_decimals, grid_num, num, param_label};
use crate::plot::outcome_map::{MapColouring, OutcomeMapFigure};
use crate::plot::poincare::PoincareFigure;
use crate::plot::spectrum::SpectrumFigure;
use crate::plot::time_history::TimeHistoryFigure;
use crate::sim::Outcome;

/// Where the files go: an output directory that is committed at the end.
pub trait Sink {
    /// Writes the text file `name`.
    fn text(&mut self, name: &str, text: &str) -> Result<(), OutputError>;
    /// The path at which the binary file `name` is to be written.
    fn path(&mut self, name: &str) -> PathBuf;
}

/// Highest harmonic ω/Ω_h shown in the spectra (the forcing frequency
/// and its first harmonics, where the paper's spectra have their lines).
pub(crate) const MAX_HARMONIC: f64 = 5.0;

/// A row of a diagram's `classes.csv` (no Lyapunov column: the paper's
/// diagrams are computed without exponents).
#[derive(serde::Serialize)]
struct DiagramClassRow {
    value: Num,
    outcome: &'static str,
    period: Option<u32>,
    max_abs_theta: Num,
}

impl Row for DiagramClassRow {
    const HEADER: &'static [&'static str] = &["value", "outcome", "period", "max_abs_theta"];
}

/// A row of a response example's `poincare.csv`.
#[derive(serde::Serialize)]
struct ThetaRow {
    theta: Num,
    theta_dot: Num,
}

impl Row for ThetaRow {
    const HEADER: &'static [&'static str] = &["theta", "theta_dot"];
}

/// `classes.csv` of a diagram: `value,outcome,period,max_abs_theta`.
pub(crate) fn classes_csv(d: &Diagram) -> String {
    csv::to_string(d.values.iter().map(|v| DiagramClassRow {
        value: Num(v.value),
        outcome: v.response.name(),
        period: v.response.period(),
        max_abs_theta: Num(v.max_abs_theta),
    }))
}

/// `points.csv` of a diagram: `value,k,tau,theta,theta_dot`.
pub(crate) fn points_csv(d: &Diagram) -> String {
    csv::to_string(point_rows(&d.values))
}

fn bifurcation_figure<'a>(
    d: &Diagram,
    values: &'a [(f64, Response)],
    points: &'a [(f64, f64)],
) -> BifurcationFigure<'a> {
    let g = d.settings.grid;
    let w = d.settings.window;
    let dec = grid_decimals(g.from, g.step);
    let seeding = match d.variant.continuation() {
        Continuation::Up => "continuation upwards",
        Continuation::Down => "continuation downwards",
        Continuation::None => "each value from rest",
    };
    // Variants name the change in the title and the parameters below it;
    // the preset names the parameters in the title (a line must fit 1200 px).
    let (title, first) = if d.variant == Variant::Paper {
        (
            format!(
                "Fig. {} reproduced: bifurcation diagram ({})",
                d.figure,
                short_params(&d.config, false)
            ),
            block_and_impact(&d.config),
        )
    } else {
        (
            format!("Fig. {} VARIANT: {}", d.figure, d.variant.short_label()),
            format!(
                "{}; B × H = {} × {} m",
                short_params(&d.config, false),
                num(d.config.block.width),
                num(d.config.block.height)
            ),
        )
    };
    let subtitle = format!(
        "{first}; Θ at τ_k = 2πk/Ω_h, {} ≤ τ_k ≤ {}; A_v = {} … {} step {}; {seeding}",
        num(w.transient),
        num(w.tau_end),
        grid_num(g.from, dec),
        grid_num(g.value(g.count.saturating_sub(1)), dec),
        num(g.step),
    );
    BifurcationFigure {
        title,
        subtitle,
        x_label: param_label(super::diagrams::PARAM),
        y_label: crate::plot::labels::section_theta(&crate::sim::Scenario::default()),
        values,
        points,
        step: g.step,
    }
}

fn write_figure<F: Figure>(
    sink: &mut dyn Sink,
    stem: &str,
    fig: &F,
    names: &mut Vec<String>,
) -> Result<(), ReproduceError> {
    let png = format!("{stem}.png");
    fig.write_png(&sink.path(&png))?;
    let svg = format!("{stem}.svg");
    sink.text(&svg, &fig.to_svg()?)?;
    names.push(png);
    names.push(svg);
    Ok(())
}

fn write_diagram(sink: &mut dyn Sink, d: &Diagram, names: &mut Vec<String>) -> Result<(), ReproduceError> {
    let stem = diagram_stem(d);
    let values = d.responses();
    let points: Vec<(f64, f64)> = d
        .values
        .iter()
        .flat_map(|v| v.points.iter().map(move |p| (v.value, p.theta)))
        .collect();
    write_figure(
        sink,
        &format!("{stem}bifurcation"),
        &bifurcation_figure(d, &values, &points),
        names,
    )?;
    let classes = format!("{stem}classes.csv");
    sink.text(&classes, &classes_csv(d))?;
    names.push(classes);
    if d.variant == Variant::Paper {
        let pts = format!("{stem}points.csv");
        sink.text(&pts, &points_csv(d))?;
        names.push(pts);
    }
    Ok(())
}

/// The impact-ratio scan of figure `n` as an outcome map over A_v × r
/// (`figNN_impact_ratio_map`), if at least three ratios were computed.
fn write_ratio_map(
    sink: &mut dyn Sink,
    rep: &Reproduction,
    n: u32,
    names: &mut Vec<String>,
) -> Result<(), ReproduceError> {
    let scan = rep.ratio_scan(n);
    let Some((_, first)) = scan.first() else {
        return Ok(());
    };
    if scan.len() < 3 {
        return Ok(());
    }
    let x: Vec<f64> = first.values.iter().map(|v| v.value).collect();
    let y: Vec<f64> = scan.iter().map(|s| s.0).collect();
    if scan.iter().any(|(_, d)| d.values.len() != x.len()) {
        return Err(ReproduceError::Figure {
            figure: n,
            what: "impact-ratio map".to_string(),
            error: "the diagrams of the scan have different grids".to_string(),
        });
    }
    let cells: Vec<(Response, Option<f64>)> = scan
        .iter()
        .flat_map(|(_, d)| d.values.iter().map(|v| (v.response, None)))
        .collect();
    let w = first.settings.window;
    let fig = OutcomeMapFigure {
        title: format!(
            "Fig. {n} VARIANTS: response over A_v × impact ratio r ({})",
            short_params(&first.config, false)
        ),
        subtitle: format!(
            "B × H = {} × {} m, ratio impact law (0.925 = preset, 0.9118 = Housner, 0.830 = eq. 20 as printed); Θ at τ_k for {} ≤ τ_k ≤ {}, from rest",
            num(first.config.block.width),
            num(first.config.block.height),
            num(w.transient),
            num(w.tau_end)
        ),
        x_label: param_label(super::diagrams::PARAM),
        y_label: "r, angular-velocity ratio at impact".to_string(),
        x: &x,
        y: &y,
        cells: &cells,
        colouring: MapColouring::Outcome,
        basins: None,
    };
    write_figure(sink, &format!("{}impact_ratio_map", prefix(n)), &fig, names)
}

fn spectrum_figure<'a>(r: &ResponseExample, s: &'a SpectrumData, which: &str) -> SpectrumFigure<'a> {
    SpectrumFigure {
        title: format!("Fig. {} (b) reproduced: power spectrum of Θ, {which}", r.figure),
        subtitle: format!(
            "{}; τ {} – {} ({} samples, Δτ = {}), Hann taper, mean removed",
            short_params(&r.config, true),
            short_num(s.tau_from),
            short_num(s.tau_to),
            s.samples,
            num(s.dt)
        ),
        harmonic: &s.harmonic,
        psd: &s.psd,
        peaks: &s.peaks,
        max_harmonic: MAX_HARMONIC,
    }
}

fn write_response(sink: &mut dyn Sink, r: &ResponseExample, names: &mut Vec<String>) -> Result<(), ReproduceError> {
    let stem = prefix(r.figure);
    let params = short_params(&r.config, true);
    let (tau, theta): (Vec<f64>, Vec<f64>) = r.history.iter().copied().unzip();
    let span = match (tau.first(), tau.last()) {
        (Some(a), Some(b)) => format!("τ {} – {}", short_num(*a), short_num(*b)),
        _ => "no samples".to_string(),
    };
    let ended = match r.tumble_tau {
        Some(t) => format!("; tumbled at τ = {t:.2}"),
        None => String::new(),
    };
    let th = TimeHistoryFigure {
        title: format!("Fig. {} (a) reproduced: time history Θ(τ) ({params})", r.figure),
        subtitle: format!(
            "{}; {span} of the run from rest, sampled every {}{ended}",
            block_and_impact(&r.config),
            num(super::response::HISTORY_DT)
        ),
        tau: &tau,
        theta: &theta,
        tumble_theta: Some(r.config.run.tumble_theta),
    };
    write_figure(sink, &format!("{stem}time_history"), &th, names)?;
    if let Ok(s) = &r.spectrum_paper {
        let fig = spectrum_figure(r, s, "the paper's window (its samples 3000–7096)");
        write_figure(sink, &format!("{stem}spectrum_paper_window"), &fig, names)?;
    }
    if let Ok(s) = &r.spectrum_long {
        let fig = spectrum_figure(r, s, "a long window after the transient");
        write_figure(sink, &format!("{stem}spectrum_long_window"), &fig, names)?;
    }
    let terminal = matches!(r.long_outcome, Outcome::Tumbled | Outcome::Flight);
    let pm = PoincareFigure {
        title: format!("Fig. {} (c) reproduced: Poincaré map ({params})", r.figure),
        subtitle: format!(
            "(Θ, Θ') at τ_k = 2πk/Ω_h, {} ≤ τ_k ≤ {}: {} points{}",
            short_num(r.steady_from),
            short_num(r.long_tau_end),
            r.poincare.len(),
            if terminal {
                format!(" of the rocking before the block tumbles at τ = {:.1}", r.long_tau_end)
            } else {
                String::new()
            }
        ),
        points: &r.poincare,
    };
    write_figure(sink, &format!("{stem}poincare"), &pm, names)?;
    let text = csv::to_string(r.poincare.iter().map(|&(theta, theta_dot)| ThetaRow {
        theta: Num(theta),
        theta_dot: Num(theta_dot),
    }));
    let name = format!("{stem}poincare.csv");
    sink.text(&name, &text)?;
    names.push(name);
    Ok(())
}

/// The JSON summary of a Lyapunov result.
pub(crate) fn lyapunov_json(l: &Result<Lyapunov, String>) -> Json {
    match l {
        Ok(l) => l.summary(),
        Err(e) => json!({ "error": e }),
    }
}

fn reproduction_json(rep: &Reproduction) -> Json {
    let diagrams: Vec<Json> = rep
        .diagrams
        .iter()
        .map(|d| {
            let fig = paper::figure(d.figure);
            let step = d.settings.grid.step;
            let comparison = fig.map(|f| compare_ranges(&d.responses(), f.ranges, step.max(0.1)));
            json!({
                "figure": d.figure,
                "variant": d.variant,
                "sets": d.sets,
                "continuation": d.variant.continuation(),
                "counts": counts_text(&d.counts()),
                "shares": d.shares(),
                "first_tumble": d.first_tumble(),
                "ranges": d.ranges().iter().map(|r| json!({
                    "from": r.from, "to": r.to, "outcome": r.response.name(), "period": r.response.period(),
                })).collect::<Vec<_>>(),
                "paper_comparison": comparison,
                "config": to_json(&d.config),
            })
        })
        .collect();
    let responses: Vec<Json> = rep
        .responses
        .iter()
        .map(|r| {
            let peaks = |s: &Result<SpectrumData, String>| match s {
                Ok(s) => json!({
                    "tau_from": s.tau_from, "tau_to": s.tau_to, "samples": s.samples, "dt": s.dt,
                    "peaks_harmonic": s.peaks.iter().map(|p| p.harmonic).collect::<Vec<_>>(),
                }),
                Err(e) => json!({ "error": e }),
            };
            json!({
                "figure": r.figure,
                "outcome": r.outcome,
                "tumble_tau": r.tumble_tau,
                "max_abs_theta": r.max_abs_theta,
                "max_abs_theta_steady": r.max_abs_theta_steady,
                "flight_violations": r.flight_violations,
                "impacts_per_cycle": r.impacts_per_cycle,
                "long_outcome": r.long_outcome,
                "long_tau_end": r.long_tau_end,
                "long_max_abs_theta": r.long_max_abs_theta,
                "poincare_points": r.poincare.len(),
                "poincare_mean": r.poincare_mean,
                "response": r.response.to_string(),
                "spectrum_paper_window": peaks(&r.spectrum_paper),
                "spectrum_long_window": peaks(&r.spectrum_long),
                "lyapunov": lyapunov_json(&r.lyapunov),
                "transient_lyapunov": r.transient_lyapunov.as_ref().map(|t| json!({
                    "window": t.window, "lyapunov": lyapunov_json(&t.lyapunov),
                })),
                "steady_from": r.steady_from,
                "neighbours": r.neighbours.iter().map(|x| x.to_string()).collect::<Vec<_>>(),
                "config": to_json(&r.config),
            })
        })
        .collect();
    let scans: Vec<Json> = rep
        .scans
        .iter()
        .map(|s| {
            json!({
                "figure": s.figure,
                "window": s.window,
                "period": s.period,
                "points": s.points.iter().map(|p| match &p.exponent {
                    Ok((l, e)) => json!({ "a_v": p.a_v, "class": p.response.name(), "largest_per_tau": l, "stderr": e }),
                    Err(why) => json!({ "a_v": p.a_v, "class": p.response.name(), "no_exponent": why }),
                }).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "command": "rocking reproduce",
        "version": env!("CARGO_PKG_VERSION"),
        "quick": rep.options.quick,
        "only": rep.options.only,
        "diagram_settings": rep.diagram_settings,
        "response_settings": rep.response_settings,
        "diagrams": diagrams,
        "responses": responses,
        "scans": scans,
        "response_variants": rep.response_variants.iter().map(|v| json!({
            "figure": v.figure,
            "variant": v.variant,
            "sets": v.sets,
            "max_abs_theta": v.max_abs_theta,
            "tumble_tau": v.tumble_tau,
            "end_from": v.end_from,
            "long_tau_end": v.long_tau_end,
            "response": v.response.to_string(),
            "lyapunov": lyapunov_json(&v.lyapunov),
            "transient_lyapunov": v.transient_lyapunov.as_ref().map(|t| json!({
                "window": t.window, "lyapunov": lyapunov_json(&t.lyapunov),
            })),
        })).collect::<Vec<_>>(),
        "tumbled_neighbours": rep.survivals.iter().map(|(n, s)| json!({
            "figure": n,
            "values": s.iter().map(|(a, r)| json!({
                "a_v": a,
                "responses": r.iter().map(|x| x.to_string()).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "tumble_times": rep.tumbles.iter().map(|(n, t)| json!({ "figure": n, "a_v_tau": t })).collect::<Vec<_>>(),
        "units": "tau = p t, theta = θ/ψ; lyapunov per unit τ (natural log), per_cycle = per τ × 2π/Ω_h",
    })
}

/// Writes every file of `rep` into `sink`, `report.md` last. `wall_s` is
/// the wall time to state in the report (the caller's measurement).
/// Returns the names written.
pub(crate) fn write_all(
    rep: &Reproduction,
    sink: &mut dyn Sink,
    threads: usize,
) -> Result<Vec<String>, ReproduceError> {
    let mut names = Vec::new();
    for d in &rep.diagrams {
        write_diagram(sink, d, &mut names)?;
    }
    for n in super::INVESTIGATED {
        write_ratio_map(sink, rep, n, &mut names)?;
    }
    for r in &rep.responses {
        write_response(sink, r, &mut names)?;
    }
    let json =
        serde_json::to_string_pretty(&reproduction_json(rep)).map_err(|e| ReproduceError::Json(e.to_string()))?;
    sink.text("reproduce.json", &(json + "\n"))?;
    names.push("reproduce.json".to_string());
    names.push("report.md".to_string());
    let text = report::report(rep, &names, threads);
    sink.text("report.md", &text)?;
    Ok(names)
}
