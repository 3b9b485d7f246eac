//! `report.md`: each recomputed figure beside the paper's statements about
//! it, with tables of paper against ours and a plain verdict per claim.
//!
//! Every number and every verdict in the report is computed from the
//! [`Reproduction`]; the only fixed prose is the method, the paper's quotes
//! ([`super::paper`]) and facts about the paper's printed equations that do
//! not depend on a run (docs/model.md §12). Verdict rules are stated in the
//! report next to the tables that use them.

use std::fmt::Write as _;

use super::diagrams::{
    Diagram, RangeComparison, cascade, compare_ranges, counts_text, intermittency_switches, is_period_doubling, short,
};
use super::format::{block_and_impact, diagram_stem, prefix, short_num, short_params};
use super::paper::{FIGURES, FigureKind, PaperFigure};
use super::response::{ResponseExample, SpectrumData, TransientExponent, TransientWindow};
use super::variant::Variant;
use super::{INVESTIGATED, Reproduction, SCANNED};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::{Lyapunov, LyapunovResult};
use crate::analysis::orbit_diagram::ResponseRange;
use crate::plot::labels::{grid_decimals, grid_num};
use crate::sim::Outcome;

/// One line of the summary table.
#[derive(Clone, Debug, PartialEq)]
struct Row {
    figure: String,
    claim: String,
    paper: String,
    ours: String,
    verdict: String,
}

/// The range tolerance for "about" in the paper's A_v ranges: 0.1, or one
/// grid step if coarser.
fn range_tol(step: f64) -> f64 {
    step.max(0.1)
}

/// A share of `count` values as `n/count`.
fn of(share: f64, count: usize) -> String {
    format!("{}/{count}", (share * count as f64).round())
}

fn pct(x: f64) -> String {
    format!("{:.0} %", 100.0 * x)
}

/// Our response ranges in one line: `0.00–0.84 (1,1); 0.86 (1,8); …`.
pub fn ranges_line(ranges: &[ResponseRange], decimals: usize) -> String {
    ranges
        .iter()
        .map(|r| {
            let span = if r.from == r.to {
                grid_num(r.from, decimals)
            } else {
                format!("{}–{}", grid_num(r.from, decimals), grid_num(r.to, decimals))
            };
            format!("{span} {}", short(r.response))
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn range_cell(c: &RangeComparison, decimals: usize) -> String {
    match c.run {
        Some((a, b)) => format!(
            "run {}–{}; {}/{} values",
            grid_num(a, decimals),
            grid_num(b, decimals),
            c.matching,
            c.total
        ),
        None => format!("{}/{} match ({})", c.matching, c.total, c.ours),
    }
}

fn lyapunov_result(l: &Result<Lyapunov, String>) -> Option<&LyapunovResult> {
    match l {
        Ok(Lyapunov::Exponents(r)) => Some(r),
        Ok(Lyapunov::None { .. }) | Err(_) => None,
    }
}

fn lyapunov_text(l: &Result<Lyapunov, String>) -> String {
    match l {
        Ok(Lyapunov::Exponents(r)) => {
            let mut s = format!(
                "tangent: {:.3} ± {:.3} per τ = {:.3} ± {:.3} per cycle",
                r.largest_per_tau, r.stderr, r.per_cycle, r.stderr_per_cycle
            );
            if let Some(c) = &r.check {
                let _ = write!(
                    s,
                    "; two trajectories: {:.3} ± {:.3} per τ (difference {:.4} ± {:.4})",
                    c.benettin_per_tau, c.benettin_stderr, c.difference, c.difference_stderr
                );
            }
            s
        }
        Ok(Lyapunov::None { no_exponent, tau, .. }) => {
            format!("no finite exponent: {} (τ = {tau:.1})", no_exponent.name())
        }
        Err(e) => format!("failed: {e}"),
    }
}

/// Whether a quoted exponent `paper` matches ours in one of the two units:
/// within 3 standard errors or 15 % of the paper's value, whichever is
/// larger (the paper gives two digits and no error bar).
fn lyapunov_verdict(paper: f64, r: &LyapunovResult) -> (String, bool) {
    let close = |ours: f64, err: f64| (ours - paper).abs() <= (3.0 * err).max(0.15 * paper.abs());
    let per_tau = close(r.largest_per_tau, r.stderr);
    let per_cycle = close(r.per_cycle, r.stderr_per_cycle);
    let sign = if r.largest_per_tau > 0.0 {
        "positive, as the paper's"
    } else {
        "not positive, unlike the paper's"
    };
    let text = match (per_tau, per_cycle) {
        (true, true) => format!("agrees (per τ and per cycle); {sign}"),
        (true, false) => format!("agrees per τ; {sign}"),
        (false, true) => format!("agrees per cycle; {sign}"),
        (false, false) => format!("differs in value in both units; {sign}"),
    };
    (text, per_tau || per_cycle)
}

fn peaks_text(s: &Result<SpectrumData, String>) -> String {
    match s {
        Ok(s) if s.peaks.is_empty() => "no peak".to_string(),
        Ok(s) => s
            .peaks
            .iter()
            .take(5)
            .map(|p| format!("{:.3}", p.harmonic))
            .collect::<Vec<_>>()
            .join(", "),
        Err(e) => format!("not computed: {e}"),
    }
}

fn response_word(r: Response) -> String {
    match r {
        Response::Periodic { period } => format!("periodic, period {period} (1,{period})"),
        Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Rest | Response::Flight => {
            r.name().to_string()
        }
    }
}

/// The report (module docs). `files` are the names written beside it,
/// `threads` the size of the pool it ran on.
pub fn report(rep: &Reproduction, files: &[String], threads: usize) -> String {
    let mut rows: Vec<Row> = Vec::new();
    let mut body = String::new();
    for f in FIGURES.iter().filter(|f| rep.options.wants(f.number)) {
        match f.kind {
            FigureKind::Bifurcation => diagram_section(&mut body, &mut rows, rep, f),
            FigureKind::Response => response_section(&mut body, &mut rows, rep, f),
        }
    }
    let mut investigation = String::new();
    for n in INVESTIGATED {
        investigation_section(&mut investigation, &mut rows, rep, n);
    }
    let mut across = String::new();
    across_section(&mut across, &mut rows, rep);
    let mut units = String::new();
    units_section(&mut units, rep);

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
    let count = |w: &str| rows.iter().filter(|r| r.verdict.starts_with(w)).count();
    let _ = writeln!(
        out,
        "- Of the {} rows of the summary table below, {} agree, {} agree partly and {} differ; the rest are observations without a verdict or findings of the investigation.",
        rows.len(),
        count("agrees"),
        count("partly"),
        count("differs")
    );
    for n in INVESTIGATED {
        let (Some(f), Some(d)) = (super::paper::figure(n), rep.diagram(n, Variant::Paper)) else {
            continue;
        };
        let dec = grid_decimals(d.settings.grid.from, d.settings.grid.step);
        let cmp = compare_ranges(&d.responses(), f.ranges, range_tol(d.settings.grid.step));
        let list = |v: super::diagrams::Verdict| -> Vec<String> {
            cmp.iter()
                .filter(|c| c.verdict == v)
                .map(|c| format!("{}–{} {}", c.from, c.to, c.paper))
                .collect()
        };
        let (agree, partly, differ) = (
            list(super::diagrams::Verdict::Agrees),
            list(super::diagrams::Verdict::Partly),
            list(super::diagrams::Verdict::Differs),
        );
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
                        .all(|c| c.verdict == super::diagrams::Verdict::Agrees)
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
            let within = checks
                .iter()
                .filter(|(d, e)| d.abs() <= 3.0 * e || d.abs() <= 0.01)
                .count();
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

fn diagram_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
    let _ = writeln!(out, "## Fig. {}: {}\n", f.number, f.caption);
    let Some(d) = rep.diagram(f.number, Variant::Paper) else {
        out.push_str("Not computed.\n\n");
        return;
    };
    let stem = diagram_stem(d);
    let _ = writeln!(
        out,
        "![Fig. {n} reproduced]({stem}bifurcation.png)\n\n(`{stem}bifurcation.svg`; data `{stem}classes.csv`, `{stem}points.csv`.)\n",
        n = f.number
    );
    out.push_str("**The paper:**\n\n");
    for s in f.statements {
        let _ = writeln!(out, "> {s}\n");
    }
    let dec = grid_decimals(d.settings.grid.from, d.settings.grid.step);
    let tol = range_tol(d.settings.grid.step);
    if !f.ranges.is_empty() {
        let cmp = compare_ranges(&d.responses(), f.ranges, tol);
        out.push_str("| A_v (paper) | paper | our responses in that range | our run of that mode | verdict |\n|---|---|---|---|---|\n");
        for c in &cmp {
            let run = c.run.map_or("—".to_string(), |(a, b)| {
                format!("{}–{}", grid_num(a, dec), grid_num(b, dec))
            });
            let _ = writeln!(
                out,
                "| {}–{} | {} | {} | {run} | {} |",
                c.from,
                c.to,
                c.paper,
                c.ours,
                c.verdict.word()
            );
            rows.push(Row {
                figure: f.number.to_string(),
                claim: format!("A_v {}–{}", c.from, c.to),
                paper: c.paper.clone(),
                ours: range_cell(c, dec),
                verdict: c.verdict.word().to_string(),
            });
        }
        let _ = writeln!(
            out,
            "\nVerdict rule: a periodic range *agrees* when our longest-overlapping run of that period starts and ends within ±{} of the paper's ends, and is reproduced *partly* when at least half of the values in the range have that period; a chaotic or mixed range agrees when at least 3/4 of its values match and partly when at least 1/4 do.\n",
            short_num(tol)
        );
    }
    let s = d.shares();
    let _ = writeln!(
        out,
        "**Ours** ({} values): {}.\n\nShares: periodic {}, chaotic or quasiperiodic {}, tumbled {}; first tumble at A_v = {}; periodic cascade from A_v = 0: {}; switches between periodic and aperiodic values: {}.\n",
        s.count,
        ranges_line(&d.ranges(), dec),
        pct(s.periodic),
        pct(s.aperiodic),
        pct(s.tumbled),
        d.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec)),
        cascade_text(&d.responses()),
        intermittency_switches(&d.responses())
    );
    if INVESTIGATED.contains(&f.number) {
        let _ = writeln!(
            out,
            "Where this differs from the paper, see [the investigation of Fig. {n}](#investigation-fig-{n}).\n",
            n = f.number
        );
    } else if let Some(v) = rep.paper_law_diagram(f.number) {
        let sv = v.shares();
        let _ = writeln!(
            out,
            "*{}* ([figure]({}bifurcation.png)): {}.\n\nShares: periodic {}, chaotic or quasiperiodic {}, tumbled {}.\n",
            v.variant.title(),
            diagram_stem(v),
            ranges_line(&v.ranges(), dec),
            pct(sv.periodic),
            pct(sv.aperiodic),
            pct(sv.tumbled)
        );
    }
    if f.number == SCANNED {
        scan_text(out, rows, rep, f);
    }
}

fn cascade_text(values: &[(f64, Response)]) -> String {
    let c = cascade(values);
    if c.is_empty() {
        return "none".to_string();
    }
    let list: Vec<String> = c.iter().map(|k| k.to_string()).collect();
    format!(
        "periods {}{}",
        list.join(" → "),
        if is_period_doubling(values) {
            " (period doubling)"
        } else {
            ""
        }
    )
}

fn scan_text(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
    let Some(scan) = rep.scan(f.number) else {
        return;
    };
    let Some(paper) = f.lyapunov else {
        return;
    };
    let mut ex = scan.exponents();
    ex.sort_by(f64::total_cmp);
    let _ = writeln!(
        out,
        "**Lyapunov exponents along our diagram** (tangent dynamics, τ {}–{}, for each of the {} chaotic or quasiperiodic values; {} have a finite exponent):\n",
        scan.window.0,
        scan.window.1,
        scan.points.len(),
        ex.len()
    );
    if ex.is_empty() {
        out.push_str("none.\n\n");
        rows.push(Row {
            figure: f.number.to_string(),
            claim: "an example's λ".to_string(),
            paper: format!("{paper}"),
            ours: "no aperiodic value with a finite exponent".to_string(),
            verdict: "differs".to_string(),
        });
        return;
    }
    let median = ex[ex.len() / 2];
    let (lo, hi) = (ex[0], ex[ex.len() - 1]);
    let per_cycle = |x: f64| x * scan.period;
    let near = |target: f64, conv: &dyn Fn(f64) -> f64| -> Vec<String> {
        scan.points
            .iter()
            .filter_map(|p| p.exponent.as_ref().ok().map(|e| (p.a_v, conv(e.0))))
            .filter(|(_, l)| (l - target).abs() <= 0.1 * target.abs().max(0.1))
            .map(|(a, _)| format!("{a:.2}"))
            .collect()
    };
    let near_tau = near(paper, &|x| x);
    let near_cycle = near(paper, &per_cycle);
    let _ = writeln!(
        out,
        "| | min | median | max |\n|---|---|---|---|\n| per τ | {lo:.3} | {median:.3} | {hi:.3} |\n| per cycle | {:.3} | {:.3} | {:.3} |\n",
        per_cycle(lo),
        per_cycle(median),
        per_cycle(hi)
    );
    let list = |v: &[String]| {
        if v.is_empty() { "none".to_string() } else { v.join(", ") }
    };
    let _ = writeln!(
        out,
        "The paper's 0.51 (A_v not given) lies within 10 % of our exponent at A_v = {} per τ, and at A_v = {} per cycle.\n",
        list(&near_tau),
        list(&near_cycle)
    );
    let inside = |a: f64, b: f64| paper >= a && paper <= b;
    let verdict = if inside(lo, hi) || inside(per_cycle(lo), per_cycle(hi)) {
        "agrees (within our range)"
    } else {
        "differs (outside our range)"
    };
    rows.push(Row {
        figure: f.number.to_string(),
        claim: "an example's λ (A_v not given)".to_string(),
        paper: format!("{paper}"),
        ours: format!(
            "{lo:.2}–{hi:.2} per τ, {:.2}–{:.2} per cycle over {} values",
            per_cycle(lo),
            per_cycle(hi),
            ex.len()
        ),
        verdict: verdict.to_string(),
    });
}

/// The exponent to compare with the paper's: the steady one, or else that
/// of the chaotic transient before a tumble, with its window `(from, to,
/// tumble τ)`.
fn best_exponent(r: &ResponseExample) -> Option<(&LyapunovResult, Option<TransientWindow>)> {
    if let Some(l) = lyapunov_result(&r.lyapunov) {
        return Some((l, None));
    }
    let t = r.transient_lyapunov.as_ref()?;
    lyapunov_result(&t.lyapunov).map(|l| (l, Some(t.window)))
}

fn neighbours_text(r: &ResponseExample) -> String {
    let counts = super::diagrams::counts(r.neighbours.iter().copied());
    format!("{} runs: {}", r.neighbours.len(), counts_text(&counts))
}

fn response_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
    let _ = writeln!(out, "## Fig. {}: {}\n", f.number, f.caption);
    let Some(r) = rep.response(f.number) else {
        out.push_str("Not computed.\n\n");
        return;
    };
    let p = prefix(f.number);
    let _ = writeln!(
        out,
        "(a) ![Fig. {n} (a) time history]({p}time_history.png)\n",
        n = f.number
    );
    if r.spectrum_paper.is_ok() {
        let _ = writeln!(
            out,
            "(b) ![Fig. {n} (b) spectrum, the paper's window]({p}spectrum_paper_window.png)\n",
            n = f.number
        );
    }
    if r.spectrum_long.is_ok() {
        let _ = writeln!(
            out,
            "(b) ![Fig. {n} (b) spectrum, a long window]({p}spectrum_long_window.png)\n",
            n = f.number
        );
    }
    let _ = writeln!(
        out,
        "(c) ![Fig. {n} (c) Poincaré map]({p}poincare.png)\n\n(SVG beside each PNG; the Poincaré points in `{p}poincare.csv`.)\n",
        n = f.number
    );
    out.push_str("**The paper:**\n\n");
    for s in f.statements {
        let _ = writeln!(out, "> {s}\n");
    }
    let _ = writeln!(
        out,
        "**Ours** ({}; {}):\n",
        short_params(&r.config, true),
        block_and_impact(&r.config)
    );
    out.push_str("| quantity | paper | ours | verdict |\n|---|---|---|---|\n");
    let fig = f.number.to_string();
    let terminal = matches!(r.long_outcome, Outcome::Tumbled | Outcome::Flight);
    // The class.
    let mut ours_class = format!(
        "{}{}",
        response_word(r.response),
        match (&r.lyapunov, r.response) {
            (Ok(Lyapunov::Exponents(_)), Response::Chaotic | Response::Quasiperiodic) => " (decided by λ)",
            _ => "",
        }
    );
    if terminal {
        let _ = write!(ours_class, " at τ = {:.1}", r.long_tau_end);
    }
    let (paper_class, class_verdict) = match f.chaotic {
        Some(true) => (
            "chaotic",
            if r.response == Response::Chaotic {
                "agrees"
            } else {
                "differs"
            },
        ),
        Some(false) => ("not chaotic", "—"),
        None => ("not stated", "—"),
    };
    let transient_note = match (r.response, lyapunov_result(&r.lyapunov)) {
        (Response::Periodic { .. }, Some(l)) if l.largest_per_tau > 0.01 => {
            " — yet λ > 0 over the Lyapunov window: the run rocks chaotically for a long time before it settles (a chaotic transient)"
        }
        _ => "",
    };
    let _ = writeln!(
        out,
        "| response at the end of the long run (τ {}–{}) | {paper_class} | {ours_class}{transient_note} | {class_verdict} |",
        short_num(r.end_from),
        short_num(r.long_tau_end)
    );
    if f.chaotic.is_some() {
        rows.push(Row {
            figure: fig.clone(),
            claim: "response (end of the long run)".to_string(),
            paper: paper_class.to_string(),
            ours: ours_class.clone(),
            verdict: class_verdict.to_string(),
        });
    }
    // The neighbours.
    if !r.neighbours.is_empty() {
        let chaotic = r.neighbours.iter().filter(|x| **x == Response::Chaotic).count();
        let verdict = match f.chaotic {
            Some(true) if 2 * chaotic >= r.neighbours.len() => "agrees (most are chaotic)",
            Some(true) if chaotic > 0 => "partly (some are chaotic)",
            Some(true) => "differs (none is chaotic)",
            Some(false) | None => "—",
        };
        let _ = writeln!(
            out,
            "| neighbouring runs A_v·(1 + k·10⁻⁹), τ {}–{} | {paper_class} | {} | {verdict} |",
            r.settings.transient,
            r.settings.history_end,
            neighbours_text(r)
        );
        if f.chaotic.is_some() {
            rows.push(Row {
                figure: fig.clone(),
                claim: "neighbouring runs (A_v·(1 + k·10⁻⁹))".to_string(),
                paper: paper_class.to_string(),
                ours: neighbours_text(r),
                verdict: verdict.to_string(),
            });
        }
    }
    // The run's end.
    let ended = match r.tumble_tau {
        Some(t) => format!("tumbled at τ = {t:.2}"),
        None => format!("{:?}", r.outcome).to_lowercase(),
    };
    let long_ended = format!(
        "{} at τ = {}",
        format!("{:?}", r.long_outcome).to_lowercase(),
        short_num(r.long_tau_end)
    );
    let _ = writeln!(
        out,
        "| end of the paper's run (τ 0–{}) / of the long run (τ 0–{}) | blank = tumbling | {ended} / {long_ended} | — |",
        r.settings.history_end, r.settings.long_end
    );
    // Amplitude.
    let steady = r.max_abs_theta_steady.map_or("—".to_string(), |m| format!("{m:.3}"));
    let amp = format!(
        "{:.3} over τ 0–{}; {steady} over τ {}–{}; {:.3} over the long run",
        r.max_abs_theta, r.settings.history_end, r.settings.transient, r.settings.history_end, r.long_max_abs_theta
    );
    match f.max_amplitude {
        Some(pa) => {
            let verdict = if (r.max_abs_theta - pa).abs() <= 0.1 {
                "agrees (±0.1)"
            } else {
                "differs"
            };
            let _ = writeln!(out, "| max \\|Θ\\| | about {pa} | {amp} | {verdict} |");
            rows.push(Row {
                figure: fig.clone(),
                claim: "max |Θ| (τ 0–800)".to_string(),
                paper: format!("about {pa}"),
                ours: format!("{:.3} (τ 600–800: {steady})", r.max_abs_theta),
                verdict: verdict.to_string(),
            });
        }
        None => {
            let _ = writeln!(out, "| max \\|Θ\\| | not quoted | {amp} | — |");
        }
    }
    // Lyapunov.
    let lt = lyapunov_text(&r.lyapunov);
    let quoted = f
        .lyapunov
        .map_or("not quoted".to_string(), |pl| format!("{pl} (units not stated)"));
    let main_verdict = match (f.lyapunov, lyapunov_result(&r.lyapunov)) {
        (Some(pl), Some(res)) => lyapunov_verdict(pl, res).0,
        (Some(_), None) => "differs (no steady exponent)".to_string(),
        (None, _) => "—".to_string(),
    };
    let _ = writeln!(
        out,
        "| largest Lyapunov exponent, τ {}–{} | {quoted} | {lt} | {main_verdict} |",
        r.settings.lyapunov_transient, r.settings.lyapunov_end
    );
    if let Some(TransientExponent {
        window: TransientWindow {
            from,
            to,
            tumble_tau: tumble,
        },
        lyapunov: l,
    }) = &r.transient_lyapunov
    {
        let v = match (f.lyapunov, lyapunov_result(l)) {
            (Some(pl), Some(res)) => lyapunov_verdict(pl, res).0,
            (Some(_), None) => "differs".to_string(),
            (None, _) => "—".to_string(),
        };
        let _ = writeln!(
            out,
            "| largest Lyapunov exponent of the chaotic transient, τ {from:.0}–{to:.0} (that run tumbles at τ = {tumble:.1}) | {quoted} | {} | {v} |",
            lyapunov_text(l)
        );
    }
    if let Some(pl) = f.lyapunov {
        let (ours, verdict) = match best_exponent(r) {
            Some((res, None)) => (
                format!("{:.3} per τ, {:.3} per cycle", res.largest_per_tau, res.per_cycle),
                lyapunov_verdict(pl, res).0,
            ),
            Some((res, Some(TransientWindow { from: a, to: b, .. }))) => (
                format!(
                    "chaotic transient before tumbling (τ {a:.0}–{b:.0}): {:.3} per τ, {:.3} per cycle",
                    res.largest_per_tau, res.per_cycle
                ),
                format!("{} (transient)", lyapunov_verdict(pl, res).0),
            ),
            None => (lt.clone(), "differs".to_string()),
        };
        rows.push(Row {
            figure: fig.clone(),
            claim: "largest Lyapunov exponent".to_string(),
            paper: format!("{pl}"),
            ours,
            verdict,
        });
    }
    if let Some((res, _)) = best_exponent(r) {
        let spectrum: Vec<String> = res
            .spectrum
            .iter()
            .zip(&res.spectrum_stderr)
            .map(|(l, e)| format!("{l:.3} ± {e:.3}"))
            .collect();
        let _ = writeln!(
            out,
            "| Lyapunov spectrum of (Θ, Θ', X') per τ | — | {}{} | — |",
            spectrum.join(", "),
            if res.collapsed > 0 {
                format!(
                    " and {} direction(s) at −∞ (slip velocity reset at sticking impacts)",
                    res.collapsed
                )
            } else {
                String::new()
            }
        );
    }
    let _ = writeln!(
        out,
        "| spectral peaks, ω/Ω_h, paper's window τ 12–28.4 | periodic: one line; chaotic: broadband | {} | — |",
        peaks_text(&r.spectrum_paper)
    );
    let _ = writeln!(
        out,
        "| spectral peaks, ω/Ω_h, τ {}–{}{} | — | {} | — |",
        short_num(r.steady_from),
        short_num(r.long_tau_end),
        if terminal { " (before the tumble)" } else { "" },
        peaks_text(&r.spectrum_long)
    );
    let mean = r
        .poincare_mean
        .map_or("—".to_string(), |(a, b)| format!("mean Θ = {a:.3}, mean Θ' = {b:.3}"));
    let _ = writeln!(
        out,
        "| Poincaré points from τ = {}{} | — | {} points; {mean} | — |",
        short_num(r.steady_from),
        if terminal { " to the tumble" } else { "" },
        r.poincare.len()
    );
    let _ = writeln!(
        out,
        "| impacts per forcing cycle; times N ≤ 0 (flight ignored) | — | {:.2}; {} | — |\n",
        r.impacts_per_cycle, r.flight_violations
    );
    variants_table(out, rows, rep, f, r);
}

/// The response example recomputed with other impact laws.
fn variants_table(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure, r: &ResponseExample) {
    let variants = rep.response_variants(f.number);
    if variants.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "**Impact-law variants** (the preset's `ratio` law with r = 0.925 replaced; labelled VARIANT, never a default). The response is classified from the end of a run to τ = {}, the exponent by tangent dynamics over τ {}–{} (or over the rocking before a tumble):\n",
        r.settings.long_end, r.settings.lyapunov_transient, r.settings.lyapunov_end
    );
    out.push_str(
        "| impact law | response at the end | max \\|Θ\\| (τ 0–800) | largest exponent per τ |\n|---|---|---|---|\n",
    );
    let exponent = |main: &Result<Lyapunov, String>, tr: &Option<TransientExponent>| match (lyapunov_result(main), tr) {
        (Some(l), _) => format!("{:.3} ± {:.3}", l.largest_per_tau, l.stderr),
        (
            None,
            Some(TransientExponent {
                window: TransientWindow { from: a, to: b, .. },
                lyapunov: t,
            }),
        ) => match lyapunov_result(t) {
            Some(l) => format!(
                "{:.3} ± {:.3} (transient, τ {a:.0}–{b:.0})",
                l.largest_per_tau, l.stderr
            ),
            None => lyapunov_text(t),
        },
        (None, None) => lyapunov_text(main),
    };
    let _ = writeln!(
        out,
        "| preset: ratio r = 0.925 | {} | {:.3} | {} |",
        response_word(r.response),
        r.max_abs_theta,
        exponent(&r.lyapunov, &r.transient_lyapunov)
    );
    let mut chaotic: Vec<String> = Vec::new();
    for v in &variants {
        let end = match v.tumble_tau {
            Some(t) => format!("tumbled at τ = {t:.1}"),
            None => response_word(v.response),
        };
        let _ = writeln!(
            out,
            "| {} (`{}`) | {end} | {:.3} | {} |",
            v.variant.title().trim_start_matches("VARIANT: "),
            v.sets.join("` `"),
            v.max_abs_theta,
            exponent(&v.lyapunov, &v.transient_lyapunov)
        );
        if v.response == Response::Chaotic {
            chaotic.push(v.variant.slug());
        }
    }
    out.push('\n');
    if f.chaotic == Some(true) {
        let ours: Vec<String> = variants
            .iter()
            .map(|v| format!("{}: {}", v.variant.slug(), short(v.response)))
            .collect();
        rows.push(Row {
            figure: f.number.to_string(),
            claim: "response with other impact laws (end of the long run)".to_string(),
            paper: "chaotic".to_string(),
            ours: ours.join("; "),
            verdict: if chaotic.is_empty() {
                "no variant is chaotic".to_string()
            } else {
                format!("chaotic with {}", chaotic.join(", "))
            },
        });
    }
}

/// Median of `v` (sorted copy); `None` if empty.
fn median(v: &[f64]) -> Option<f64> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(s.len() / 2).copied()
}

/// The variants of figure `n` against the preset, with findings.
fn investigation_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, n: u32) {
    let Some(f) = super::paper::figure(n) else {
        return;
    };
    let Some(base) = rep.diagram(n, Variant::Paper) else {
        return;
    };
    let variants: Vec<&Diagram> = std::iter::once(Variant::Paper)
        .chain(Variant::INVESTIGATION)
        .filter_map(|v| rep.diagram(n, v))
        .collect();
    if variants.len() < 2 {
        return;
    }
    let _ = writeln!(
        out,
        "<a id=\"investigation-fig-{n}\"></a>\n## Investigation: where Fig. {n} differs, and why\n"
    );
    let dec = grid_decimals(base.settings.grid.from, base.settings.grid.step);
    let tol = range_tol(base.settings.grid.step);
    out.push_str(
        "Each variant changes one thing through the configuration (the model's equations are never altered) and is labelled VARIANT in its figure; none is a default. ",
    );
    out.push_str("Cells give our run of the paper's mode (first–last A_v) or the share of matching values, and the verdict by the rules of the figure's section.\n\n");
    let mut head = String::from("| variant | settings |");
    let mut rule = String::from("|---|---|");
    for r in f.ranges {
        let _ = write!(head, " paper {}–{}: {} |", r.from, r.to, r.expect.label());
        rule.push_str("---|");
    }
    head.push_str(" first tumble | all values |");
    rule.push_str("---|---|");
    let _ = writeln!(out, "{head}\n{rule}");
    let mut last_range: Vec<(Variant, usize, usize, usize)> = Vec::new();
    let base_responses = base.responses();
    let mut identical: Vec<String> = Vec::new();
    for d in &variants {
        let cmp = compare_ranges(&d.responses(), f.ranges, tol);
        if d.variant != Variant::Paper && d.responses() == base_responses {
            identical.push(d.variant.title());
        }
        let _ = writeln!(out, "{}", variant_row(d, &cmp, dec));
        if let (Some(c), Some(pr)) = (cmp.last(), f.ranges.last()) {
            let tumbled = d
                .values
                .iter()
                .filter(|v| v.value >= pr.from - 1e-9 && v.value <= pr.to + 1e-9 && v.response == Response::Tumbled)
                .count();
            last_range.push((d.variant, c.matching, tumbled, c.total));
        }
    }
    out.push('\n');

    // Findings, computed.
    out.push_str("**Findings** (computed):\n\n");
    if let (Some(pr), Some(&(_, base_match, base_tumbled, total))) = (f.ranges.last(), last_range.first()) {
        let _ = writeln!(
            out,
            "- In the paper's last range, A_v {}–{} ({}), {total} values: the preset gives {base_match} matching values and {base_tumbled} tumbled, first tumble at A_v = {}.",
            pr.from,
            pr.to,
            pr.expect.label(),
            base.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec))
        );
        for &(v, m, t, _) in last_range.iter().skip(1) {
            let change = m as i64 - base_match as i64;
            let first = rep
                .diagram(n, v)
                .and_then(Diagram::first_tumble)
                .map_or("none".to_string(), |x| grid_num(x, dec));
            let _ = writeln!(
                out,
                "- {}: {m} match ({}{change} against the preset), {t} tumble, first tumble at A_v = {first}.",
                v.title(),
                if change >= 0 { "+" } else { "" }
            );
        }
        if !identical.is_empty() {
            let _ = writeln!(
                out,
                "- Identical, value by value, to the preset: {}. So these assumptions change nothing here{}.",
                identical.join("; "),
                if identical.iter().any(|t| t.contains("π/2")) {
                    " (in particular, every block that passes |Θ| = 1 goes on to fall on its side: the tumble criterion is not the cause)"
                } else {
                    ""
                }
            );
        }
        let best = last_range.iter().max_by_key(|x| x.1).copied();
        if let Some((v, m, _, _)) = best {
            let share = m as f64 / total.max(1) as f64;
            let explained = share >= 0.75;
            let _ = writeln!(
                out,
                "- The most matching values come from *{}* ({m}/{total}, {}). {}",
                v.title(),
                pct(share),
                if explained {
                    "This variant reproduces the paper's range by the verdict rule (3/4 of the values)."
                } else {
                    "No single variant reproduces the paper's range by the verdict rule (3/4 of the values), so none of these assumptions alone explains the difference."
                }
            );
            rows.push(Row {
                figure: format!("{n} (variants)"),
                claim: format!("which assumption explains A_v {}–{}", pr.from, pr.to),
                paper: pr.expect.label(),
                ours: format!("best: {} with {m}/{total}", v.slug()),
                verdict: if explained {
                    format!("explained by {}", v.slug())
                } else {
                    "not explained by any single variant".to_string()
                },
            });
        }
    }
    if let Some(times) = rep.tumbles(n)
        && !times.is_empty()
    {
        let taus: Vec<f64> = times.iter().map(|t| t.1).collect();
        let lo = taus.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = taus.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let late = taus.iter().filter(|t| **t > 100.0).count();
        let in_window = taus.iter().filter(|t| **t >= base.settings.window.transient).count();
        let _ = writeln!(
            out,
            "- When the preset's {} tumbled values tumble: τ = {lo:.1} to {hi:.1}, median {:.1}; {late} after τ = 100 (more than ~13 forcing cycles of rocking first) and {in_window} only inside the paper's sampling window (τ ≥ {}). {}",
            taus.len(),
            median(&taus).unwrap_or(0.0),
            base.settings.window.transient,
            if 2 * late >= taus.len() {
                "Most tumbles thus end a long stretch of rocking: a transient, not an immediate overturn. When that rocking is chaotic its length is sensitive to the smallest change (see the neighbouring runs below and those of Figs. 7 and 8), so a run of the paper's that happened to outlast τ = 800 would show chaos where ours tumbles."
            } else {
                "Most tumbles come early, within the first few excitation cycles."
            }
        );
    }
    if let (Some(surv), Some(pr)) = (rep.survivals(n), f.ranges.last())
        && !surv.is_empty()
    {
        let all: Vec<Response> = surv.iter().flat_map(|(_, r)| r.iter().copied()).collect();
        let still = all.iter().filter(|r| !r.is_terminal()).count();
        let chaotic = all.iter().filter(|r| **r == Response::Chaotic).count();
        let values_with_survivor = surv.iter().filter(|(_, r)| r.iter().any(|x| !x.is_terminal())).count();
        let _ = writeln!(
            out,
            "- Neighbouring runs of the {} tumbled values in A_v {}–{}: {} runs at A_v·(1 + k·10⁻⁹), k = 1 … {}: {} (still rocking at τ = {}: {still}, of them chaotic: {chaotic}; {values_with_survivor} of the {} values have at least one neighbour that does not tumble).",
            surv.len(),
            pr.from,
            pr.to,
            all.len(),
            surv.first().map_or(0, |s| s.1.len()),
            counts_text(&super::diagrams::counts(all.iter().copied())),
            base.settings.window.tau_end,
            surv.len()
        );
        rows.push(Row {
            figure: format!("{n} (neighbours)"),
            claim: format!(
                "tumbled values in A_v {}–{}: do runs differing in the 9th digit of A_v rock on?",
                pr.from, pr.to
            ),
            paper: pr.expect.label(),
            ours: format!(
                "{still} of {} rock on to τ = {}, {chaotic} chaotic",
                all.len(),
                base.settings.window.tau_end
            ),
            verdict: if 2 * still >= all.len() {
                "most rock on: a run of the paper's length could well show rocking here".to_string()
            } else if chaotic > 0 {
                format!(
                    "a few ({}) rock on chaotically: chance alone does not explain the paper's range",
                    pct(chaotic as f64 / all.len().max(1) as f64)
                )
            } else {
                "none rocks on".to_string()
            },
        });
    }
    if let Some(d) = rep.diagram(n, Variant::Ralston) {
        let not_p1 = |d: &Diagram| {
            d.values
                .iter()
                .filter(|v| v.value < 0.7 && !matches!(v.response, Response::Periodic { period: 1 }))
                .count()
        };
        let _ = writeln!(
            out,
            "- With the paper's fixed-step Ralston RK2, {} of the values below A_v = 0.7 are not classified period 1 (the preset's exact integration: {}). Presumably the fixed step's truncation error and its impact location (to |Θ| < 10⁻⁶ rather than to rounding) perturb every cycle slightly, so a response that the exact integration shows as one fixed point scatters by more than the classifier's 10⁻³ of the amplitude and reads as a higher period or chaos.",
            not_p1(d),
            not_p1(base)
        );
    }
    out.push('\n');
    ratio_scan_section(out, rows, rep, f, dec, tol);
    out.push_str(
        "**The paper's equations as printed.** Its eqs. 28–31 are the slide-rock equations (they carry μ_k, and eq. 30 has no horizontal-excitation term at all); the rocking equation with the pivot stuck, which a block without sliding obeys (Figs. 3–8), is not printed (docs/model.md §12, items 6 and 21). Run as printed for a block that does not slide, eq. 30 leaves a block started from rest at rest for every A_v (Θ = Θ' = 0 is its equilibrium and A_h does not enter), so it cannot be what produced Figs. 3–8. The printed equations that do act in these figures are the impact laws, and both readings are variants above: eq. 22 (Housner's r = 1 − 1.5 sin²ψ = 0.9118) and eq. 20 with the paper's e = 0.925 as printed (r = 1 − 1.5(1 + e) sin²ψ = 0.830).\n\n",
    );
}

/// One row of a variant table: the variant, its settings, a cell per paper
/// range, first tumble and all counts.
fn variant_row(d: &Diagram, cmp: &[RangeComparison], dec: usize) -> String {
    let sets = if d.sets.is_empty() {
        match d.variant {
            Variant::ContinuationUp => "`--continuation up`".to_string(),
            Variant::Paper
            | Variant::Ralston
            | Variant::Housner
            | Variant::PrintedEq20
            | Variant::TumbleAtSide
            | Variant::FlightStop
            | Variant::ImpulseLaw
            | Variant::ImpactRatio(_) => "preset".to_string(),
        }
    } else {
        d.sets.iter().map(|s| format!("`{s}`")).collect::<Vec<_>>().join(" ")
    };
    let mut line = format!(
        "| [{}]({}bifurcation.png) | {sets} |",
        d.variant.title(),
        diagram_stem(d)
    );
    for c in cmp {
        let _ = write!(line, " {} — {} |", range_cell(c, dec), c.verdict.word());
    }
    let _ = write!(
        line,
        " {} | {} |",
        d.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec)),
        counts_text(&d.counts())
    );
    line
}

/// The impact-ratio scan of figure `f`: one row per r, and whether any r
/// reproduces every range.
fn ratio_scan_section(
    out: &mut String,
    rows: &mut Vec<Row>,
    rep: &Reproduction,
    f: &PaperFigure,
    dec: usize,
    tol: f64,
) {
    let scan = rep.ratio_scan(f.number);
    if scan.len() < 3 {
        return;
    }
    let _ = writeln!(
        out,
        "**Impact-ratio scan.** The impact law is the one printed ingredient that changes the diagram, so the whole diagram was recomputed for r from {} to {} (the `ratio` law; for a block that does not slide Housner's law is the ratio law with r = 0.9118). Map: `{}impact_ratio_map.png`.\n",
        short_num(scan[0].0),
        short_num(scan[scan.len() - 1].0),
        prefix(f.number)
    );
    let mut head = String::from("| r |");
    let mut rule = String::from("|---|");
    for r in f.ranges {
        let _ = write!(head, " paper {}–{}: {} |", r.from, r.to, r.expect.label());
        rule.push_str("---|");
    }
    head.push_str(" first tumble | tumbled |");
    rule.push_str("---|---|");
    let _ = writeln!(out, "{head}\n{rule}");
    let mut all_agree: Vec<String> = Vec::new();
    let mut best: Option<(f64, usize)> = None;
    for (r, d) in &scan {
        let cmp = compare_ranges(&d.responses(), f.ranges, tol);
        let mut line = format!("| [{}]({}bifurcation.png) |", short_num(*r), diagram_stem(d));
        for c in &cmp {
            let _ = write!(line, " {} — {} |", range_cell(c, dec), c.verdict.word());
        }
        let tumbled = d.values.iter().filter(|v| v.response == Response::Tumbled).count();
        let _ = write!(
            line,
            " {} | {tumbled} |",
            d.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec))
        );
        let _ = writeln!(out, "{line}");
        let agree = cmp
            .iter()
            .filter(|c| c.verdict == super::diagrams::Verdict::Agrees)
            .count();
        if agree == cmp.len() {
            all_agree.push(short_num(*r));
        }
        if best.is_none_or(|b| agree > b.1) {
            best = Some((*r, agree));
        }
    }
    let verdict = if all_agree.is_empty() {
        format!(
            "No r in the scan reproduces every range; the most ranges ({} of {}) agree at r = {}.",
            best.map_or(0, |b| b.1),
            f.ranges.len(),
            best.map_or("—".to_string(), |b| short_num(b.0))
        )
    } else {
        format!("Every range agrees at r = {}.", all_agree.join(", "))
    };
    let _ = writeln!(out, "\n{verdict}\n");
    rows.push(Row {
        figure: format!("{} (r scan)", f.number),
        claim: "an impact ratio r that reproduces every range".to_string(),
        paper: "r = 0.925 (its e)".to_string(),
        ours: verdict.clone(),
        verdict: if all_agree.is_empty() {
            "none found".to_string()
        } else {
            format!("r = {}", all_agree.join(", "))
        },
    });
}

fn diag(rep: &Reproduction, n: u32) -> Option<&Diagram> {
    rep.diagram(n, Variant::Paper)
}

/// The outcome of checking one comparative statement.
enum Check {
    /// Checked: what we found and whether it agrees.
    Done(String, bool),
    /// Not checkable, and why.
    Skip(String),
}

fn not_computed() -> Check {
    Check::Skip("not computed (--only)".to_string())
}

fn push_claim(out: &mut String, rows: &mut Vec<Row>, figs: &str, claim: &str, check: Check) {
    let (ours, verdict) = match check {
        Check::Done(text, ok) => (text, if ok { "agrees" } else { "differs" }),
        Check::Skip(why) => (why, "—"),
    };
    let _ = writeln!(out, "| {figs} | {claim} | {ours} | {verdict} |");
    rows.push(Row {
        figure: figs.to_string(),
        claim: claim.to_string(),
        paper: "as stated".to_string(),
        ours,
        verdict: verdict.to_string(),
    });
}

/// The comparative statements about the diagrams, on the diagrams `pick`
/// gives; `label` marks the figures column (e.g. for the paper's impact
/// law).
fn diagram_claims<'a>(out: &mut String, rows: &mut Vec<Row>, pick: &dyn Fn(u32) -> Option<&'a Diagram>, label: &str) {
    let share_check = |a: u32, b: u32, f: &dyn Fn(&Diagram, &Diagram) -> Check| match (pick(a), pick(b)) {
        (Some(x), Some(y)) => f(x, y),
        _ => not_computed(),
    };
    for (a, b) in [(5, 3), (6, 4)] {
        let c = share_check(a, b, &|x, y| {
            let (sx, sy) = (x.shares(), y.shares());
            Check::Done(
                format!(
                    "periodic {} vs {}",
                    of(sx.periodic, sx.count),
                    of(sy.periodic, sy.count)
                ),
                sx.periodic > sy.periodic,
            )
        });
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "periodic region wider at Ω = 10",
            c,
        );
        let c = share_check(a, b, &|x, y| {
            let (sx, sy) = (x.shares(), y.shares());
            Check::Done(
                format!("tumbled {} vs {}", of(sx.tumbled, sx.count), of(sy.tumbled, sy.count)),
                sx.tumbled < sy.tumbled,
            )
        });
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "tumbling region narrower at Ω = 10",
            c,
        );
    }
    for n in [3, 5] {
        let c = pick(n).map_or_else(not_computed, |d| {
            let s = intermittency_switches(&d.responses());
            Check::Done(format!("{s} periodic↔aperiodic switches"), s >= 4)
        });
        push_claim(
            out,
            rows,
            &format!("{n}{label}"),
            "intermittency (periodic and chaotic values intermingled; read: at least 4 switches)",
            c,
        );
    }
    for n in [4, 6] {
        let c = pick(n).map_or_else(not_computed, |d| {
            let r = d.responses();
            Check::Done(cascade_text(&r), is_period_doubling(&r))
        });
        push_claim(
            out,
            rows,
            &format!("{n}{label}"),
            "period doubling (1,1) → (1,2) → (1,4) → chaos (read: periods 1, 2, 4 in this order before two consecutive aperiodic or tumbled values)",
            c,
        );
    }
    for (a, b) in [(9, 3), (10, 3), (14, 6), (15, 6)] {
        let c = share_check(a, b, &|x, y| {
            let (sx, sy) = (x.shares(), y.shares());
            Check::Done(
                format!(
                    "chaotic {} vs {}",
                    of(sx.aperiodic, sx.count),
                    of(sy.aperiodic, sy.count)
                ),
                sx.aperiodic > sy.aperiodic,
            )
        });
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "chaotic region wider with sliding",
            c,
        );
    }
    for (a, b) in [(10, 9), (15, 14)] {
        let c = share_check(a, b, &|x, y| {
            let (sx, sy) = (x.shares(), y.shares());
            Check::Done(
                format!(
                    "chaotic {} vs {}",
                    of(sx.aperiodic, sx.count),
                    of(sy.aperiodic, sy.count)
                ),
                sx.aperiodic > sy.aperiodic,
            )
        });
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "lower friction: chaotic region expanded",
            c,
        );
        let c = share_check(a, b, &|x, y| {
            let (sx, sy) = (x.shares(), y.shares());
            Check::Done(
                format!(
                    "periodic {} vs {}",
                    of(sx.periodic, sx.count),
                    of(sy.periodic, sy.count)
                ),
                sx.periodic < sy.periodic,
            )
        });
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "lower friction: periodic region narrower",
            c,
        );
    }
}

fn across_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction) {
    out.push_str("## Across figures\n\n");
    out.push_str("The paper's comparative statements, checked on our shares of values (periodic: any period or rest; chaotic region: chaotic or quasiperiodic values) and on the response examples. Rows marked *eqs. 17–27* use every diagram recomputed with the paper's own impact law (e = 0; Housner's law where the block cannot slide) instead of the preset's ratio r = 0.925.\n\n");
    out.push_str("| Figs. | the paper says | ours | verdict |\n|---|---|---|---|\n");
    diagram_claims(out, rows, &|n| diag(rep, n), "");
    diagram_claims(out, rows, &|n| rep.paper_law_diagram(n), " (eqs. 17–27)");
    let resp = |n: u32| rep.response(n);
    let amp = |r: &ResponseExample| r.max_abs_theta;
    let c = match (resp(7), resp(8)) {
        (Some(a), Some(b)) if a.tumble_tau.is_some() && b.tumble_tau.is_some() => Check::Skip(format!(
            "not comparable: both tumble (τ = {:.1} and {:.1}), so both reach |Θ| = 1",
            a.tumble_tau.unwrap_or(0.0),
            b.tumble_tau.unwrap_or(0.0)
        )),
        (Some(a), Some(b)) => Check::Done(format!("max |Θ| {:.3} vs {:.3}", amp(a), amp(b)), amp(a) > amp(b)),
        _ => not_computed(),
    };
    push_claim(out, rows, "7 vs 8", "max amplitude larger at Ω = 8 than at Ω = 10", c);
    let c = resp(7).map_or_else(not_computed, |a| {
        Check::Done(
            format!(
                "max |Θ| {:.3}{}",
                amp(a),
                a.tumble_tau
                    .map_or(String::new(), |t| format!(", tumbled at τ = {t:.1}"))
            ),
            amp(a) >= 0.9,
        )
    });
    push_claim(out, rows, "7", "reached a tumbling level (read: max |Θ| ≥ 0.9)", c);
    let c = match (resp(7), resp(12), resp(13)) {
        (Some(a), Some(b), Some(c)) => Check::Done(
            format!("max |Θ| {:.3} > {:.3} > {:.3}?", amp(a), amp(b), amp(c)),
            amp(a) > amp(b) && amp(b) > amp(c),
        ),
        _ => not_computed(),
    };
    push_claim(
        out,
        rows,
        "7, 12, 13",
        "lower friction (sliding): smaller max amplitude",
        c,
    );
    let lam = |r: &ResponseExample| {
        best_exponent(r).map(|(l, w)| (l.largest_per_tau, if w.is_some() { " (transient)" } else { "" }))
    };
    let lam_claim = |a: Option<&ResponseExample>, b: &[Option<&ResponseExample>]| -> Check {
        let (Some(a), Some(bs)) = (a, b.iter().copied().collect::<Option<Vec<_>>>()) else {
            return not_computed();
        };
        let Some((la, ta)) = lam(a) else {
            return Check::Skip(format!("Fig. {} has no exponent", a.figure));
        };
        let mut lb = Vec::new();
        for r in &bs {
            match lam(r) {
                Some(x) => lb.push(x),
                None => return Check::Skip(format!("Fig. {} has no exponent", r.figure)),
            }
        }
        let text = format!(
            "λ {la:.3}{ta} without sliding vs {} with (per τ)",
            lb.iter()
                .map(|(x, t)| format!("{x:.3}{t}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        Check::Done(text, lb.iter().all(|x| x.0 > la))
    };
    push_claim(
        out,
        rows,
        "7 vs 12, 13",
        "λ larger with sliding",
        lam_claim(resp(7), &[resp(12), resp(13)]),
    );
    push_claim(
        out,
        rows,
        "8 vs 19",
        "λ larger with sliding",
        lam_claim(resp(8), &[resp(19)]),
    );
    let c = resp(18).map_or_else(not_computed, |r| match r.poincare_mean {
        Some((_, b)) => Check::Done(format!("mean Θ' = {b:.3}"), b < 0.0),
        None => Check::Skip("no Poincaré points".to_string()),
    });
    push_claim(
        out,
        rows,
        "18",
        "attractor inclined toward negative Θ' (read: mean Θ' of the Poincaré points < 0)",
        c,
    );
    let c = resp(7).map_or_else(not_computed, |r| match r.poincare_mean {
        Some((m, _)) => {
            let top = r.poincare.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
            Check::Done(
                format!(
                    "mean Θ = {m:.3}, largest |Θ| {top:.3}{}",
                    if matches!(r.long_outcome, Outcome::Tumbled) {
                        " (points of the transient before the tumble)"
                    } else {
                        ""
                    }
                ),
                m.abs() > 0.05 * top,
            )
        }
        None => Check::Skip("no Poincaré points".to_string()),
    });
    push_claim(
        out,
        rows,
        "7",
        "attractor asymmetrical about Θ = 0 (read: |mean Θ| > 5 % of the largest |Θ| of the points)",
        c,
    );
    out.push('\n');
}

fn units_section(out: &mut String, rep: &Reproduction) {
    let quoted: Vec<(&PaperFigure, &ResponseExample, &LyapunovResult, bool)> = FIGURES
        .iter()
        .filter_map(|f| {
            f.lyapunov?;
            let r = rep.response(f.number)?;
            let (l, w) = best_exponent(r)?;
            Some((f, r, l, w.is_some()))
        })
        .collect();
    let Some(first) = quoted.first() else {
        return;
    };
    out.push_str("## Lyapunov exponents: which unit did the paper use?\n\n");
    let p = first.1.config.geometry().p;
    let _ = writeln!(
        out,
        "The paper quotes its exponents without a unit or a method. Ours are natural-log rates per unit τ = p t, per excitation cycle (× 2π/Ω_h) and per second (× p, with p = √(3g/4R) = {p:.3} 1/s). \"transient\" marks the exponent of the chaotic rocking before a tumble.\n"
    );
    out.push_str(
        "| Fig. | paper | ours per τ | per cycle | per second | two trajectories per τ |\n|---|---|---|---|---|---|\n",
    );
    let (mut near_tau, mut near_cycle, mut near_second) = (0, 0, 0);
    for (f, _, l, transient) in &quoted {
        let pl = f.lyapunov.unwrap_or(0.0);
        let per_s = l.largest_per_tau * p;
        let close = |x: f64| (x - pl).abs() <= 0.15 * pl.abs();
        near_tau += usize::from(close(l.largest_per_tau));
        near_cycle += usize::from(close(l.per_cycle));
        near_second += usize::from(close(per_s));
        let b = l.check.map_or("—".to_string(), |c| {
            format!("{:.3} ± {:.3}", c.benettin_per_tau, c.benettin_stderr)
        });
        let _ = writeln!(
            out,
            "| {}{} | {pl} | {:.3} ± {:.3} | {:.3} ± {:.3} | {per_s:.3} | {b} |",
            f.number,
            if *transient { " (transient)" } else { "" },
            l.largest_per_tau,
            l.stderr,
            l.per_cycle,
            l.stderr_per_cycle
        );
    }
    let _ = writeln!(
        out,
        "\nWithin 15 % of the paper's value: {near_tau} of {n} per τ, {near_cycle} of {n} per cycle, {near_second} of {n} per second.\n",
        n = quoted.len()
    );
    out.push_str("A unit explains the paper's exponents only if one column matches them all. The paper does not say how it computed its exponents (nor how it treated the impacts, across which a naive two-trajectory estimate is wrong), and its runs were shorter and fixed-step, so a quoted exponent may also differ for those reasons.\n\n");
}
