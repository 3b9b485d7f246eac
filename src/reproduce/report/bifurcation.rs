//! The sections on the bifurcation diagrams: each figure's diagram against
//! the paper's ranges (with the Lyapunov scan of Fig. 10), and the
//! investigation of a diagram that differs, with its variants and the
//! impact-ratio scan.

use std::fmt::Write as _;

use super::Row;
use super::claims::{explains, exponent_range_verdict, range_tol, ratio_scan_verdict, survival_verdict};
use super::markdown::{
    cascade_text, median, paper_statements, pct, range_cell, range_columns, ranges_line, variant_row,
};
use crate::analysis::classify::Response;
use crate::plot::labels::{grid_decimals, grid_num};
use crate::reproduce::diagrams::{Diagram, Verdict, compare_ranges, counts, counts_text, intermittency_switches};
use crate::reproduce::format::{diagram_stem, prefix, short_num};
use crate::reproduce::paper::{self, PaperFigure};
use crate::reproduce::variant::Variant;
use crate::reproduce::{INVESTIGATED, Reproduction, SCANNED};

/// The section of a bifurcation diagram: the figure, the paper's
/// statements, the table of its ranges against ours and our shares.
pub(super) fn diagram_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, f: &PaperFigure) {
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
    paper_statements(out, f);
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

/// The Lyapunov exponents along the diagram of `f`, against the exponent
/// the paper quotes without its A_v.
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
    let verdict = exponent_range_verdict(paper, lo, hi, scan.period);
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

/// The variants of figure `n` against the preset, with findings.
pub(super) fn investigation_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction, n: u32) {
    let Some(f) = paper::figure(n) else {
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
    range_columns(out, &["variant", "settings"], f.ranges, &["first tumble", "all values"]);
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
            let explained = explains(share);
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
            counts_text(&counts(all.iter().copied())),
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
            verdict: survival_verdict(still, chaotic, all.len()),
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
        "**Impact-ratio scan.** The impact law is the one printed ingredient that changes the diagram, so the whole diagram was recomputed for r from {} to {} (the `ratio` law; Housner's law is the ratio law with r = 0.9118, with or without sliding). Map: `{}impact_ratio_map.png`.\n",
        short_num(scan[0].0),
        short_num(scan[scan.len() - 1].0),
        prefix(f.number)
    );
    range_columns(out, &["r"], f.ranges, &["first tumble", "tumbled"]);
    let mut agreeing: Vec<(f64, usize)> = Vec::new();
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
        agreeing.push((*r, cmp.iter().filter(|c| c.verdict == Verdict::Agrees).count()));
    }
    let (verdict, found) = ratio_scan_verdict(&agreeing, f.ranges.len(), &short_num);
    let _ = writeln!(out, "\n{verdict}\n");
    rows.push(Row {
        figure: format!("{} (r scan)", f.number),
        claim: "an impact ratio r that reproduces every range".to_string(),
        paper: "r = 0.925 (its e)".to_string(),
        ours: verdict,
        verdict: found,
    });
}
