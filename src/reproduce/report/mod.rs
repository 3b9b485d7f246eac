//! `report.md`: each recomputed figure beside the paper's statements about
//! it, with tables of paper against ours and a plain verdict per claim.
//!
//! Every number and every verdict in the report is computed from the
//! [`Reproduction`]; the only fixed prose is the method, the paper's quotes
//! ([`super::paper`]) and facts about the paper's printed equations that do
//! not depend on a run (docs/model.md §12). Verdict rules are stated in the
//! report next to the tables that use them.
//!
//! The parts: the verdict rules (`claims`, with their tests in `tests`);
//! the sections on the bifurcation diagrams and their investigation
//! (`bifurcation`), on the response examples (`examples`) and on the
//! statements across figures (`across`); the small pieces of markdown they
//! share (`markdown`). Here: the summary table, the main findings and the
//! method.

mod across;
mod bifurcation;
mod claims;
mod examples;
mod markdown;
#[cfg(test)]
mod tests;

use std::fmt::Write as _;

use super::diagrams::{Verdict, compare_ranges, short};
use super::format::short_num;
use super::paper::{FIGURES, FigureKind};
use super::response::ResponseExample;
use super::variant::Variant;
use super::{INVESTIGATED, Reproduction};
use crate::analysis::classify::Response;
use crate::plot::labels::{grid_decimals, grid_num};
use crate::sim::Outcome;
use claims::{best_exponent, lyapunov_result, methods_agree, range_tol};
use markdown::median;
pub use markdown::ranges_line;

/// One line of the summary table.
#[derive(Clone, Debug, PartialEq)]
struct Row {
    figure: String,
    claim: String,
    paper: String,
    ours: String,
    verdict: String,
}

/// How many rows of the summary agree, agree partly and differ: by the
/// first word of the verdict, so a verdict with a reason in brackets
/// counts, and one without a verdict word ("—", "none found", an
/// investigation's finding) counts in none.
fn tally(rows: &[Row]) -> (usize, usize, usize) {
    let count = |w: &str| rows.iter().filter(|r| r.verdict.starts_with(w)).count();
    (count("agrees"), count("partly"), count("differs"))
}

/// The report (module docs). `files` are the names written beside it,
/// `threads` the size of the pool it ran on.
pub fn report(rep: &Reproduction, files: &[String], threads: usize) -> String {
    let mut rows: Vec<Row> = Vec::new();
    let mut body = String::new();
    for f in FIGURES.iter().filter(|f| rep.options.wants(f.number)) {
        match f.kind {
            FigureKind::Bifurcation => bifurcation::diagram_section(&mut body, &mut rows, rep, f),
            FigureKind::Response => examples::response_section(&mut body, &mut rows, rep, f),
        }
    }
    let mut investigation = String::new();
    for n in INVESTIGATED {
        bifurcation::investigation_section(&mut investigation, &mut rows, rep, n);
    }
    let mut across = String::new();
    across::across_section(&mut across, &mut rows, rep);
    let mut units = String::new();
    examples::units_section(&mut units, rep);

    let mut out = String::new();
    header(&mut out, rep, threads);
    findings(&mut out, rep, &rows);
    out.push_str("## Summary: the paper against ours\n\n");
    out.push_str(
        "One row per statement of the paper that a number can check. The verdict rules are given in the sections below.\n\n",
    );
    out.push_str("| Fig. | statement | paper | ours | verdict |\n|---|---|---|---|---|\n");
    for r in &rows {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} |",
            r.figure, r.claim, r.paper, r.ours, r.verdict
        );
    }
    out.push('\n');
    out.push_str(&body);
    out.push_str(&investigation);
    out.push_str(&across);
    out.push_str(&units);
    out.push_str("## Files\n\n");
    for name in files {
        let _ = writeln!(out, "- `{name}`");
    }
    out
}

/// The main findings, generated from the results (each sentence states
/// numbers computed here, so it changes with them).
fn findings(out: &mut String, rep: &Reproduction, rows: &[Row]) {
    out.push_str("## Main findings\n\n");
    let (agree, partly, differ) = tally(rows);
    let _ = writeln!(
        out,
        "- Of the {} rows of the summary table below, {} agree, {} agree partly and {} differ; the rest are observations without a verdict or findings of the investigation.",
        rows.len(),
        agree,
        partly,
        differ
    );
    for n in INVESTIGATED {
        let (Some(f), Some(d)) = (super::paper::figure(n), rep.diagram(n, Variant::Paper)) else {
            continue;
        };
        let dec = grid_decimals(d.settings.grid.from, d.settings.grid.step);
        let cmp = compare_ranges(&d.responses(), f.ranges, range_tol(d.settings.grid.step));
        let list = |v: Verdict| -> Vec<String> {
            cmp.iter()
                .filter(|c| c.verdict == v)
                .map(|c| format!("{}–{} {}", c.from, c.to, c.paper))
                .collect()
        };
        let (agree, partly, differ) = (list(Verdict::Agrees), list(Verdict::Partly), list(Verdict::Differs));
        let join = |v: &[String]| if v.is_empty() { "none".to_string() } else { v.join("; ") };
        let tumbled = d.values.iter().filter(|v| v.response == Response::Tumbled).count();
        let mut line = format!(
            "- **Fig. {n}**: the paper's A_v ranges that agree: {}; partly: {}; differ: {}. {tumbled} of {} values tumble (first at A_v = {})",
            join(&agree),
            join(&partly),
            join(&differ),
            d.values.len(),
            d.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec))
        );
        if let Some(t) = rep.tumbles(n)
            && !t.is_empty()
        {
            let taus: Vec<f64> = t.iter().map(|x| x.1).collect();
            let _ = write!(
                line,
                ", after a median of τ = {:.0} of rocking",
                median(&taus).unwrap_or(0.0)
            );
        }
        if let Some(sv) = rep.survivals(n) {
            let all: Vec<Response> = sv.iter().flat_map(|(_, r)| r.iter().copied()).collect();
            let chaotic = all.iter().filter(|r| **r == Response::Chaotic).count();
            let _ = write!(
                line,
                "; of {} runs that differ from those tumbled ones in the 9th digit of A_v, {} are chaotic at τ = {}",
                all.len(),
                chaotic,
                d.settings.window.tau_end
            );
        }
        line.push('.');
        let identical: Vec<String> = Variant::INVESTIGATION
            .iter()
            .filter_map(|v| rep.diagram(n, *v))
            .filter(|v| v.responses() == d.responses())
            .map(|v| v.variant.slug())
            .collect();
        if !identical.is_empty() {
            let _ = write!(
                line,
                " Changing {} leaves every value's class as it is.",
                identical.join(" or ")
            );
        }
        let scan = rep.ratio_scan(n);
        if scan.len() >= 3 {
            let tol = range_tol(d.settings.grid.step);
            let all_agree: Vec<String> = scan
                .iter()
                .filter(|(_, v)| {
                    compare_ranges(&v.responses(), f.ranges, tol)
                        .iter()
                        .all(|c| c.verdict == Verdict::Agrees)
                })
                .map(|(r, _)| short_num(*r))
                .collect();
            let no_tumble: Vec<String> = scan
                .iter()
                .filter(|(_, v)| v.first_tumble().is_none())
                .map(|(r, _)| short_num(*r))
                .collect();
            let _ = write!(
                line,
                " Over the impact-ratio scan (r = {} … {}), {}; the block never tumbles for r = {}.",
                short_num(scan[0].0),
                short_num(scan[scan.len() - 1].0),
                if all_agree.is_empty() {
                    "no r reproduces every range".to_string()
                } else {
                    format!("every range agrees at r = {}", all_agree.join(", "))
                },
                if no_tumble.is_empty() {
                    "none".to_string()
                } else {
                    no_tumble.join(", ")
                }
            );
        }
        let _ = writeln!(out, "{line}");
    }
    let examples: Vec<&ResponseExample> = FIGURES
        .iter()
        .filter(|f| f.chaotic == Some(true))
        .filter_map(|f| rep.response(f.number))
        .collect();
    if !examples.is_empty() {
        let ours: Vec<String> = examples
            .iter()
            .map(|r| match r.tumble_tau {
                Some(t) if matches!(r.long_outcome, Outcome::Tumbled) => format!("{} tumbled at τ = {t:.0}", r.figure),
                _ => format!("{} {}", r.figure, short(r.response)),
            })
            .collect();
        let neighbours: Vec<String> = examples
            .iter()
            .filter(|r| !r.neighbours.is_empty())
            .map(|r| {
                format!(
                    "{} {}/{}",
                    r.figure,
                    r.neighbours.iter().filter(|x| **x == Response::Chaotic).count(),
                    r.neighbours.len()
                )
            })
            .collect();
        let law: Vec<String> = examples
            .iter()
            .filter_map(|r| {
                let cfg = &r.config;
                let v = super::paper_law(cfg);
                rep.response_variants(r.figure)
                    .into_iter()
                    .find(|x| x.variant == v)
                    .map(|x| format!("{} {}", r.figure, short(x.response)))
            })
            .collect();
        let _ = writeln!(
            out,
            "- **Response examples the paper calls chaotic** (Figs. {}): ours, at the end of a run to τ = {}: {}. Neighbouring runs chaotic over the paper's window (τ {}–{}): {}. With the paper's own impact law (eqs. 17–27, e = 0; Housner's without sliding): {}.",
            examples
                .iter()
                .map(|r| r.figure.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            rep.response_settings.long_end,
            ours.join("; "),
            rep.response_settings.transient,
            rep.response_settings.history_end,
            neighbours.join(", "),
            if law.is_empty() {
                "not computed".to_string()
            } else {
                law.join("; ")
            }
        );
        let quoted: Vec<String> = FIGURES
            .iter()
            .filter_map(|f| {
                let pl = f.lyapunov?;
                let r = rep.response(f.number)?;
                let (l, w) = best_exponent(r)?;
                Some(format!(
                    "{} {pl} vs {:.2}{}",
                    f.number,
                    l.largest_per_tau,
                    if w.is_some() { " (transient)" } else { "" }
                ))
            })
            .collect();
        if !quoted.is_empty() {
            // The two methods against each other, on every exponent computed.
            let checks: Vec<(f64, f64)> = rep
                .responses
                .iter()
                .flat_map(|r| {
                    let tr = r.transient_lyapunov.as_ref().map(|t| &t.lyapunov);
                    [Some(&r.lyapunov), tr].into_iter().flatten()
                })
                .filter_map(|l| lyapunov_result(l).and_then(|x| x.check))
                .map(|c| (c.difference, c.difference_stderr))
                .collect();
            let within = checks.iter().filter(|(d, e)| methods_agree(*d, *e)).count();
            let _ = writeln!(
                out,
                "- **Lyapunov exponents**, paper vs ours per τ (tangent dynamics): {}. The two-trajectory estimate on the same trajectory is within 3 paired standard errors (or 0.01) of the tangent one in {within} of {} cases. See the unit table at the end.",
                quoted.join("; "),
                checks.len()
            );
        }
    }
    out.push('\n');
}

/// The title, timings and the method.
fn header(out: &mut String, rep: &Reproduction, threads: usize) {
    let g = rep.diagram_settings.grid;
    let w = rep.diagram_settings.window;
    let rs = rep.response_settings;
    let dec = grid_decimals(g.from, g.step);
    let _ = writeln!(
        out,
        "# Jeong & Suzuki, \"Chaotic rocking vibration of a rigid block with sliding motion under two-dimensional harmonic excitation\": Figs. 3–19 reproduced\n"
    );
    let _ = writeln!(
        out,
        "Written by `rocking reproduce` (rocking {}). Computation wall time: **{:.1} s** on {threads} worker thread(s) (summed wall times of the parts, which overlap: diagrams {:.1} s, response examples {:.1} s, then the Lyapunov scan and tumble times {:.1} s); the command prints its total time, files included, when it ends.\n",
        env!("CARGO_PKG_VERSION"),
        rep.wall_s,
        rep.part_s[0],
        rep.part_s[1],
        rep.part_s[2]
    );
    if rep.options.quick {
        out.push_str(
            "> **Quick mode** (`--quick`): a coarse A_v grid and short runs, for tests and a first look. The numbers below are NOT at the paper's resolution; run without `--quick` for the real comparison.\n\n",
        );
    }
    if let Some(only) = &rep.options.only {
        let list: Vec<String> = only.iter().map(|n| format!("Fig. {n}")).collect();
        let _ = writeln!(
            out,
            "> **Only** {} (`--only`): comparisons that need other figures are left out.\n",
            list.join(", ")
        );
    }
    out.push_str("## Method\n\n");
    let _ = writeln!(
        out,
        "- **Parameters** from the presets `fig3` … `fig19` (`assets/presets`): block B × H = 1 × 4 m, Ω_v = Ω_h, impact law `ratio` with r = 0.925 (the paper's e of its section 4.1, read as an angular-velocity ratio; MODEL-DECISIONS), start from rest, tumbled when |Θ| reaches 1, and `flight = \"ignore\"` (the grounded equations are integrated on, as the paper did; the times the normal force vanished are counted). Integrator DOP853, rtol 1e-10, atol 1e-12, every impact and mode switch located exactly."
    );
    let _ = writeln!(
        out,
        "- **Bifurcation diagrams**: A_v = {} … {} in steps of {} ({} values), each run from rest to τ = {}, Poincaré points Θ(τ_k) at τ_k = 2πk/Ω_h for {} ≤ τ_k ≤ {} (the paper's steps 150,000–200,000 of 0.004). Each value is classified (docs/analysis.md): period k ≤ 32 when the section points repeat to 10⁻³ of the amplitude (the paper's (1,k) mode); otherwise quasiperiodic or chaotic by the invariant-curve test; tumbled values are blank and shaded. Values run in parallel and are collected in order, so the output does not depend on the thread count.",
        grid_num(g.from, dec),
        grid_num(g.value(g.count.saturating_sub(1)), dec),
        g.step,
        g.count,
        w.tau_end,
        w.transient,
        w.tau_end
    );
    let _ = writeln!(
        out,
        "- **Response examples**: (a) the time history of the paper's run (τ 0–{}, sampled every 0.004), shown from τ = {}; (b) the power spectrum of Θ (Hann taper, mean removed) over the paper's window, its samples 3000–7096, i.e. τ 12–28.4 inside the transient, and over a long window τ {}–{} of a longer run; (c) the Poincaré map (Θ, Θ') of that longer run at τ_k ≥ {}; and the largest Lyapunov exponent, computed two independent ways on one trajectory (tangent dynamics with saltation matrices at every impact and mode switch, and two trajectories renormalised on the stroboscopic section), over τ {}–{} with error bars from {} batch means, per unit τ and per excitation cycle (if that run tumbles, also over the rocking before the tumble, labelled *transient*). The response is classified from the last {} τ of the long run, i.e. what it settles to; the exponent decides between chaotic and quasiperiodic. Because chaotic transients turned out to matter, {} **neighbouring runs** at A_v·(1 + k·10⁻⁹) are classified over the paper's window τ {}–{} as well: they show what a run of the paper's length sees at this A_v.",
        rs.history_end,
        rs.transient,
        rs.transient,
        rs.long_end,
        rs.transient,
        rs.lyapunov_transient,
        rs.lyapunov_end,
        rs.lyapunov_batches,
        rs.end_window,
        rs.neighbours,
        rs.transient,
        rs.history_end
    );
    out.push_str("- **Verdicts**: *agrees*, *partly* or *differs*, by the rules stated beside each table. \"About\" in the paper's A_v ranges is read as ±0.1 (or one grid step, if coarser).\n\n");
}
