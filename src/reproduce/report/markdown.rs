//! Small pieces of the report's markdown: numbers, lists and table cells
//! made from the results, shared by its sections.

use std::fmt::Write as _;

use crate::analysis::classify::Response;
use crate::analysis::lyapunov::Lyapunov;
use crate::analysis::orbit_diagram::{Continuation, ResponseRange};
use crate::plot::labels::grid_num;
use crate::reproduce::diagrams::{Diagram, RangeComparison, cascade, counts, counts_text, is_period_doubling, short};
use crate::reproduce::format::diagram_stem;
use crate::reproduce::paper::{PaperFigure, PaperRange};
use crate::reproduce::response::{ResponseExample, SpectrumData};

/// A share of `count` values as `n/count`.
pub(super) fn of(share: f64, count: usize) -> String {
    format!("{}/{count}", (share * count as f64).round())
}

/// A share as a whole percentage: `25 %`.
pub(super) fn pct(x: f64) -> String {
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

/// One range comparison in a cell: our run of the paper's mode, or the
/// share of matching values.
pub(super) fn range_cell(c: &RangeComparison, decimals: usize) -> String {
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

/// A Lyapunov result in words: both methods' exponents with their
/// errors, or why there is none.
pub(super) fn lyapunov_text(l: &Result<Lyapunov, String>) -> String {
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

/// The harmonics ω/Ω_h of the five strongest spectral peaks.
pub(super) fn peaks_text(s: &Result<SpectrumData, String>) -> String {
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

/// A response in words: `periodic, period 2 (1,2)`, `chaotic`, ….
pub(super) fn response_word(r: Response) -> String {
    match r {
        Response::Periodic { period } => format!("periodic, period {period} (1,{period})"),
        Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Rest | Response::Flight => {
            r.name().to_string()
        }
    }
}

/// The periodic cascade from the first value: `periods 1 → 2 → 4 (period
/// doubling)`, or `none`.
pub(super) fn cascade_text(values: &[(f64, Response)]) -> String {
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

/// The responses of an example's neighbouring runs: `8 runs: chaotic ×5, …`.
pub(super) fn neighbours_text(r: &ResponseExample) -> String {
    let counts = counts(r.neighbours.iter().copied());
    format!("{} runs: {}", r.neighbours.len(), counts_text(&counts))
}

/// One row of a variant table: the variant, its settings, a cell per paper
/// range, first tumble and all counts.
pub(super) fn variant_row(d: &Diagram, cmp: &[RangeComparison], dec: usize) -> String {
    // A variant without `--set` assignments changes how the values are
    // seeded, or nothing.
    let sets = if d.sets.is_empty() {
        match d.variant.continuation() {
            Continuation::Up => "`--continuation up`".to_string(),
            Continuation::Down => "`--continuation down`".to_string(),
            Continuation::None => "preset".to_string(),
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

/// Median of `v` (sorted copy); `None` if empty.
pub(super) fn median(v: &[f64]) -> Option<f64> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(s.len() / 2).copied()
}

/// The paper's statements about `f`, quoted.
pub(super) fn paper_statements(out: &mut String, f: &PaperFigure) {
    out.push_str("**The paper:**\n\n");
    for s in f.statements {
        let _ = writeln!(out, "> {s}\n");
    }
}

/// The head of a table with a column per paper range: the `first`
/// columns, `paper 0–0.84: (1,1)` and so on, then the `last` columns.
pub(super) fn range_columns(out: &mut String, first: &[&str], ranges: &[PaperRange], last: &[&str]) {
    let mut head = String::from("|");
    let mut rule = String::from("|");
    for c in first {
        let _ = write!(head, " {c} |");
        rule.push_str("---|");
    }
    for r in ranges {
        let _ = write!(head, " paper {}–{}: {} |", r.from, r.to, r.expect.label());
        rule.push_str("---|");
    }
    for c in last {
        let _ = write!(head, " {c} |");
        rule.push_str("---|");
    }
    let _ = writeln!(out, "{head}\n{rule}");
}
