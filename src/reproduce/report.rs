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
    Diagram, RangeComparison, Variant, cascade, compare_ranges, counts_text, intermittency_switches,
    is_period_doubling, short,
};
use super::paper::{FIGURES, FigureKind, PaperFigure};
use super::response::{ResponseExample, SpectrumData};
use super::write::{block_and_impact, diagram_stem, prefix, short_num, short_params};
use super::{INVESTIGATED, Reproduction, SCANNED};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::{Lyapunov, LyapunovResult};
use crate::analysis::orbit_diagram::ResponseRange;
use crate::plot::labels::{grid_decimals, grid_num};

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
        Ok(Lyapunov::None {
            no_exponent, tau, ..
        }) => format!("no finite exponent: {} (τ = {tau:.1})", no_exponent.name()),
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
        "Written by `rocking reproduce` (rocking {}). Computation wall time: **{:.1} s** on {threads} worker thread(s); the command prints its total time, files included, when it ends.\n",
        env!("CARGO_PKG_VERSION"),
        rep.wall_s
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
        "- **Response examples**: (a) the time history of the paper's run (τ 0–{}, sampled every 0.004), shown from τ = {}; (b) the power spectrum of Θ (Hann taper, mean removed) over the paper's window, its samples 3000–7096, i.e. τ 12–28.4 inside the transient, and over a long window τ {}–{} of a longer run; (c) the Poincaré map (Θ, Θ') of that longer run at τ_k ≥ {}; and the largest Lyapunov exponent, computed two independent ways on one trajectory (tangent dynamics with saltation matrices at every impact and mode switch, and two trajectories renormalised on the stroboscopic section), over τ {}–{} with error bars from {} batch means, per unit τ and per excitation cycle. The response's class uses that exponent.",
        rs.history_end,
        rs.transient,
        rs.transient,
        rs.long_end,
        rs.transient,
        rs.lyapunov_transient,
        rs.lyapunov_end,
        rs.lyapunov_batches
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
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
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

fn response_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
    let _ = writeln!(out, "## Fig. {}: {}\n", f.number, f.caption);
    let Some(r) = rep.response(f.number) else {
        out.push_str("Not computed.\n\n");
        return;
    };
    let p = prefix(f.number);
    let _ = writeln!(out, "(a) ![Fig. {n} (a) time history]({p}time_history.png)\n", n = f.number);
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
    // The class.
    let ours_class = format!(
        "{}{}",
        response_word(r.response),
        match (&r.lyapunov, r.response) {
            (Ok(Lyapunov::Exponents(_)), Response::Chaotic | Response::Quasiperiodic) => " (decided by λ)",
            _ => "",
        }
    );
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
    let _ = writeln!(out, "| response (long run) | {paper_class} | {ours_class} | {class_verdict} |");
    if f.chaotic.is_some() {
        rows.push(Row {
            figure: fig.clone(),
            claim: "response".to_string(),
            paper: paper_class.to_string(),
            ours: ours_class.clone(),
            verdict: class_verdict.to_string(),
        });
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
        "| end of the paper's run (τ 0–{}) / of the long run | blank = tumbling | {ended} / {long_ended} | — |",
        r.settings.history_end
    );
    // Amplitude.
    let steady = r
        .max_abs_theta_steady
        .map_or("—".to_string(), |m| format!("{m:.3}"));
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
                claim: "max |Θ|".to_string(),
                paper: format!("about {pa}"),
                ours: format!("{:.3}", r.max_abs_theta),
                verdict: verdict.to_string(),
            });
        }
        None => {
            let _ = writeln!(out, "| max \\|Θ\\| | not quoted | {amp} | — |");
        }
    }
    // Lyapunov.
    let lt = lyapunov_text(&r.lyapunov);
    match (f.lyapunov, lyapunov_result(&r.lyapunov)) {
        (Some(pl), Some(res)) => {
            let (v, _) = lyapunov_verdict(pl, res);
            let _ = writeln!(out, "| largest Lyapunov exponent | {pl} (units not stated) | {lt} | {v} |");
            rows.push(Row {
                figure: fig.clone(),
                claim: "largest Lyapunov exponent".to_string(),
                paper: format!("{pl}"),
                ours: format!("{:.3} per τ, {:.3} per cycle", res.largest_per_tau, res.per_cycle),
                verdict: v,
            });
        }
        (Some(pl), None) => {
            let _ = writeln!(out, "| largest Lyapunov exponent | {pl} (units not stated) | {lt} | differs |");
            rows.push(Row {
                figure: fig.clone(),
                claim: "largest Lyapunov exponent".to_string(),
                paper: format!("{pl}"),
                ours: lt.clone(),
                verdict: "differs".to_string(),
            });
        }
        (None, _) => {
            let _ = writeln!(out, "| largest Lyapunov exponent | not quoted | {lt} | — |");
        }
    }
    if let Some(res) = lyapunov_result(&r.lyapunov) {
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
                format!(" and {} direction(s) at −∞ (slip velocity reset at sticking impacts)", res.collapsed)
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
        "| spectral peaks, ω/Ω_h, τ {}–{} | — | {} | — |",
        r.settings.transient,
        short_num(r.long_tau_end),
        peaks_text(&r.spectrum_long)
    );
    let mean = r
        .poincare_mean
        .map_or("—".to_string(), |(a, b)| format!("mean Θ = {a:.3}, mean Θ' = {b:.3}"));
    let _ = writeln!(
        out,
        "| Poincaré points after τ = {} | — | {} points; {mean} | — |",
        r.settings.transient,
        r.poincare.len()
    );
    let _ = writeln!(
        out,
        "| impacts per forcing cycle; times N ≤ 0 (flight ignored) | — | {:.2}; {} | — |\n",
        r.impacts_per_cycle, r.flight_violations
    );
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
    for d in &variants {
        let cmp = compare_ranges(&d.responses(), f.ranges, tol);
        let sets = if d.sets.is_empty() {
            match d.variant {
                Variant::ContinuationUp => "`--continuation up`".to_string(),
                Variant::Paper
                | Variant::Ralston
                | Variant::Housner
                | Variant::PrintedEq20
                | Variant::TumbleAtSide
                | Variant::FlightStop => "preset".to_string(),
            }
        } else {
            d.sets.iter().map(|s| format!("`{s}`")).collect::<Vec<_>>().join(" ")
        };
        let mut line = format!(
            "| [{}]({}bifurcation.png) | {sets} |",
            d.variant.title(),
            diagram_stem(d)
        );
        for c in &cmp {
            let _ = write!(line, " {} — {} |", range_cell(c, dec), c.verdict.word());
        }
        let _ = write!(
            line,
            " {} | {} |",
            d.first_tumble().map_or("none".to_string(), |v| grid_num(v, dec)),
            counts_text(&d.counts())
        );
        let _ = writeln!(out, "{line}");
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
    if let (Some(pr), Some(&(_, base_match, base_tumbled, total))) = (f.ranges.last(), last_range.first()) {
        let _ = writeln!(
            out,
            "**Findings** for the paper's last range, A_v {}–{} ({}), {total} values:\n",
            pr.from,
            pr.to,
            pr.expect.label()
        );
        let _ = writeln!(
            out,
            "- preset: {base_match} match the paper, {base_tumbled} tumble."
        );
        for &(v, m, t, _) in last_range.iter().skip(1) {
            let change = m as i64 - base_match as i64;
            let _ = writeln!(
                out,
                "- {}: {m} match ({}{change} against the preset), {t} tumble.",
                v.title(),
                if change >= 0 { "+" } else { "" }
            );
        }
        let best = last_range.iter().max_by_key(|x| x.1).copied();
        if let Some((v, m, _, _)) = best {
            let share = m as f64 / total.max(1) as f64;
            let explained = share >= 0.75;
            let _ = writeln!(
                out,
                "- The most matching values come from *{}* ({m}/{total}, {}). {}\n",
                v.title(),
                pct(share),
                if explained {
                    "This variant reproduces the paper's range by the verdict rule above."
                } else {
                    "No single variant reproduces the paper's range by the verdict rule above (3/4 of the values), so none of these assumptions alone explains the difference."
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
    if let Some(d) = rep.diagram(n, Variant::Ralston) {
        let low: Vec<&Response> = d
            .values
            .iter()
            .filter(|v| v.value < 0.7 && !matches!(v.response, Response::Periodic { period: 1 }))
            .map(|v| &v.response)
            .collect();
        let _ = writeln!(
            out,
            "With the paper's fixed-step Ralston RK2, {} of the values below A_v = 0.7 are not classified period 1 (the preset's exact integration: {}). Presumably the fixed step's truncation error and its impact location (to |Θ| < 10⁻⁶ rather than to rounding) perturb every cycle slightly, so a response that the exact integration shows as one fixed point scatters by more than the classifier's 10⁻³ of the amplitude and reads as a higher period or chaos.\n",
            low.len(),
            base.values
                .iter()
                .filter(|v| v.value < 0.7 && !matches!(v.response, Response::Periodic { period: 1 }))
                .count()
        );
    }
    out.push_str(
        "**The paper's equations as printed.** Its eqs. 28–31 are the slide-rock equations (they carry μ_k, and eq. 30 has no horizontal-excitation term at all); the rocking equation with the pivot stuck, which a block without sliding obeys (Figs. 3–8), is not printed (docs/model.md §12, items 6 and 21). Run as printed for a block that does not slide, eq. 30 leaves a block started from rest at rest for every A_v (Θ = Θ' = 0 is its equilibrium and A_h does not enter), so it cannot be what produced Figs. 3–8. The printed equations that do act in these figures are the impact laws, and both readings are variants above: eq. 22 (Housner's r = 1 − 1.5 sin²ψ = 0.9118) and eq. 20 with the paper's e = 0.925 as printed (r = 1 − 1.5(1 + e) sin²ψ = 0.830).\n\n",
    );
}

fn diag(rep: &Reproduction, n: u32) -> Option<&Diagram> {
    rep.diagram(n, Variant::Paper)
}

fn push_claim(out: &mut String, rows: &mut Vec<Row>, figs: &str, claim: &str, ours: Option<(String, bool)>) {
    let (ours, verdict) = match ours {
        Some((text, ok)) => (text, if ok { "agrees" } else { "differs" }),
        None => ("not computed (--only)".to_string(), "—"),
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

fn across_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction) {
    out.push_str("## Across figures\n\n");
    out.push_str("The paper's comparative statements, checked on our shares of values (periodic: any period or rest; chaotic region: chaotic or quasiperiodic values) and on the response examples.\n\n");
    out.push_str("| Figs. | the paper says | ours | verdict |\n|---|---|---|---|\n");
    let pair = |a: u32, b: u32| diag(rep, a).zip(diag(rep, b));
    for (a, b) in [(5, 3), (6, 4)] {
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}"),
            "periodic region wider at Ω = 10",
            pair(a, b).map(|(x, y)| {
                let (sx, sy) = (x.shares(), y.shares());
                (
                    format!("periodic {} vs {}", pct(sx.periodic), pct(sy.periodic)),
                    sx.periodic > sy.periodic,
                )
            }),
        );
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}"),
            "tumbling region narrower at Ω = 10",
            pair(a, b).map(|(x, y)| {
                let (sx, sy) = (x.shares(), y.shares());
                (
                    format!("tumbled {} vs {}", pct(sx.tumbled), pct(sy.tumbled)),
                    sx.tumbled < sy.tumbled,
                )
            }),
        );
    }
    for n in [3, 5] {
        push_claim(
            out,
            rows,
            &n.to_string(),
            "intermittency (periodic and chaotic values intermingled)",
            diag(rep, n).map(|d| {
                let s = intermittency_switches(&d.responses());
                (format!("{s} periodic↔aperiodic switches"), s >= 4)
            }),
        );
    }
    for n in [4, 6] {
        push_claim(
            out,
            rows,
            &n.to_string(),
            "period doubling (1,1) → (1,2) → (1,4) → chaos",
            diag(rep, n).map(|d| {
                let r = d.responses();
                (cascade_text(&r), is_period_doubling(&r))
            }),
        );
    }
    for (a, b) in [(9, 3), (10, 3), (14, 6), (15, 6)] {
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}"),
            "chaotic region wider with sliding",
            pair(a, b).map(|(x, y)| {
                let (sx, sy) = (x.shares(), y.shares());
                (
                    format!("chaotic {} vs {}", pct(sx.aperiodic), pct(sy.aperiodic)),
                    sx.aperiodic > sy.aperiodic,
                )
            }),
        );
    }
    for (a, b) in [(10, 9), (15, 14)] {
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}"),
            "lower friction: chaotic region expanded",
            pair(a, b).map(|(x, y)| {
                let (sx, sy) = (x.shares(), y.shares());
                (
                    format!("chaotic {} vs {}", pct(sx.aperiodic), pct(sy.aperiodic)),
                    sx.aperiodic > sy.aperiodic,
                )
            }),
        );
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}"),
            "lower friction: periodic region narrower",
            pair(a, b).map(|(x, y)| {
                let (sx, sy) = (x.shares(), y.shares());
                (
                    format!("periodic {} vs {}", pct(sx.periodic), pct(sy.periodic)),
                    sx.periodic < sy.periodic,
                )
            }),
        );
    }
    let resp = |n: u32| rep.response(n);
    let amp = |r: &ResponseExample| r.max_abs_theta;
    push_claim(
        out,
        rows,
        "7 vs 8",
        "max amplitude larger at Ω = 8 than at Ω = 10",
        resp(7).zip(resp(8)).map(|(a, b)| {
            (
                format!("max |Θ| {:.3} vs {:.3}", amp(a), amp(b)),
                amp(a) > amp(b),
            )
        }),
    );
    push_claim(
        out,
        rows,
        "7",
        "reached a tumbling level",
        resp(7).map(|a| {
            (
                format!("max |Θ| {:.3}{}", amp(a), if a.tumble_tau.is_some() { ", tumbled" } else { "" }),
                amp(a) >= 0.9,
            )
        }),
    );
    push_claim(
        out,
        rows,
        "7, 12, 13",
        "lower friction (sliding): smaller max amplitude",
        resp(7).zip(resp(12)).zip(resp(13)).map(|((a, b), c)| {
            (
                format!("max |Θ| {:.3} > {:.3} > {:.3}?", amp(a), amp(b), amp(c)),
                amp(a) > amp(b) && amp(b) > amp(c),
            )
        }),
    );
    let lam = |r: &ResponseExample| lyapunov_result(&r.lyapunov).map(|x| x.largest_per_tau);
    let lam_claim = |a: Option<&ResponseExample>, b: &[Option<&ResponseExample>]| -> Option<(String, bool)> {
        let la = lam(a?)?;
        let lb: Option<Vec<f64>> = b.iter().map(|r| r.and_then(lam)).collect();
        let lb = lb?;
        let text = format!(
            "λ {la:.3} without sliding vs {} with (per τ)",
            lb.iter().map(|x| format!("{x:.3}")).collect::<Vec<_>>().join(", ")
        );
        Some((text, lb.iter().all(|x| *x > la)))
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
    push_claim(
        out,
        rows,
        "18",
        "attractor inclined toward negative Θ' (read: mean Θ' of the Poincaré points < 0)",
        resp(18).and_then(|r| r.poincare_mean).map(|(_, b)| (format!("mean Θ' = {b:.3}"), b < 0.0)),
    );
    push_claim(
        out,
        rows,
        "7",
        "attractor asymmetrical about Θ = 0 (read: |mean Θ| > 5 % of the largest |Θ| of the points)",
        resp(7).and_then(|r| {
            let (m, _) = r.poincare_mean?;
            let top = r.poincare.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
            Some((format!("mean Θ = {m:.3}, largest |Θ| {top:.3}"), m.abs() > 0.05 * top))
        }),
    );
    out.push('\n');
}

fn units_section(out: &mut String, rep: &Reproduction) {
    let quoted: Vec<(&PaperFigure, &ResponseExample, &LyapunovResult)> = FIGURES
        .iter()
        .filter_map(|f| {
            let pl = f.lyapunov?;
            let _ = pl;
            let r = rep.response(f.number)?;
            Some((f, r, lyapunov_result(&r.lyapunov)?))
        })
        .collect();
    if quoted.is_empty() {
        return;
    }
    out.push_str("## Lyapunov exponents: which unit did the paper use?\n\n");
    out.push_str("The paper quotes its exponents without a unit or a method. Ours are natural-log rates per unit τ = p t, per excitation cycle (× 2π/Ω_h) and per second (× p, with p = √(3g/4R) = ");
    let p = quoted[0].1.config.geometry().p;
    let _ = writeln!(out, "{p:.3} 1/s).\n");
    out.push_str("| Fig. | paper | ours per τ | per cycle | per second | two trajectories per τ |\n|---|---|---|---|---|---|\n");
    let (mut near_tau, mut near_cycle, mut near_second) = (0, 0, 0);
    for (f, _, l) in &quoted {
        let pl = f.lyapunov.unwrap_or(0.0);
        let per_s = l.largest_per_tau * p;
        let close = |x: f64| (x - pl).abs() <= 0.15 * pl.abs();
        near_tau += usize::from(close(l.largest_per_tau));
        near_cycle += usize::from(close(l.per_cycle));
        near_second += usize::from(close(per_s));
        let b = l
            .check
            .map_or("—".to_string(), |c| format!("{:.3} ± {:.3}", c.benettin_per_tau, c.benettin_stderr));
        let _ = writeln!(
            out,
            "| {} | {pl} | {:.3} ± {:.3} | {:.3} ± {:.3} | {per_s:.3} | {b} |",
            f.number, l.largest_per_tau, l.stderr, l.per_cycle, l.stderr_per_cycle
        );
    }
    let _ = writeln!(
        out,
        "\nWithin 15 % of the paper's value: {near_tau} of {n} per τ, {near_cycle} of {n} per cycle, {near_second} of {n} per second. ",
        n = quoted.len()
    );
    out.push_str("A unit explains the paper's exponents only if one column matches them all. The paper does not say how it computed its exponents (nor how it treated the impacts, across which a naive two-trajectory estimate is wrong), and its runs were shorter and fixed-step, so a quoted exponent may also differ for those reasons.\n\n");
}
