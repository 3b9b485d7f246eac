//! The section on the paper's comparative statements across figures: each
//! statement, the figures it compares, and the rule of [`super::claims`]
//! that checks it, as one table row.

use std::fmt::Write as _;

use super::Row;
use super::claims::{
    Check, Exponent, amplitude_decreasing, amplitude_larger, asymmetrical, best_exponent, chaotic_wider, check_verdict,
    inclined, intermittent, lambda_larger, not_computed, period_doubling, periodic_narrower, periodic_wider,
    tumbling_level, tumbling_narrower,
};
use crate::reproduce::Reproduction;
use crate::reproduce::diagrams::{Diagram, Shares};
use crate::reproduce::response::ResponseExample;
use crate::reproduce::variant::Variant;
use crate::sim::Outcome;

fn diag(rep: &Reproduction, n: u32) -> Option<&Diagram> {
    rep.diagram(n, Variant::Paper)
}

/// One statement's row, in the section's table and in the summary.
fn push_claim(out: &mut String, rows: &mut Vec<Row>, figs: &str, claim: &str, check: Check) {
    let verdict = check_verdict(&check);
    let ours = match check {
        Check::Done(text, _) | Check::Skip(text) => text,
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
    let share_check = |a: u32, b: u32, rule: fn(&Shares, &Shares) -> Check| match (pick(a), pick(b)) {
        (Some(x), Some(y)) => rule(&x.shares(), &y.shares()),
        _ => not_computed(),
    };
    for (a, b) in [(5, 3), (6, 4)] {
        let figs = format!("{a} vs {b}{label}");
        let c = share_check(a, b, periodic_wider);
        push_claim(out, rows, &figs, "periodic region wider at Ω = 10", c);
        let c = share_check(a, b, tumbling_narrower);
        push_claim(out, rows, &figs, "tumbling region narrower at Ω = 10", c);
    }
    for n in [3, 5] {
        let c = pick(n).map_or_else(not_computed, |d| intermittent(&d.responses()));
        push_claim(
            out,
            rows,
            &format!("{n}{label}"),
            "intermittency (periodic and chaotic values intermingled; read: at least 4 switches)",
            c,
        );
    }
    for n in [4, 6] {
        let c = pick(n).map_or_else(not_computed, |d| period_doubling(&d.responses()));
        push_claim(
            out,
            rows,
            &format!("{n}{label}"),
            "period doubling (1,1) → (1,2) → (1,4) → chaos (read: periods 1, 2, 4 in this order before two consecutive aperiodic or tumbled values)",
            c,
        );
    }
    for (a, b) in [(9, 3), (10, 3), (14, 6), (15, 6)] {
        let c = share_check(a, b, chaotic_wider);
        push_claim(
            out,
            rows,
            &format!("{a} vs {b}{label}"),
            "chaotic region wider with sliding",
            c,
        );
    }
    for (a, b) in [(10, 9), (15, 14)] {
        let figs = format!("{a} vs {b}{label}");
        let c = share_check(a, b, chaotic_wider);
        push_claim(out, rows, &figs, "lower friction: chaotic region expanded", c);
        let c = share_check(a, b, periodic_narrower);
        push_claim(out, rows, &figs, "lower friction: periodic region narrower", c);
    }
}

/// The section: the statements on the diagrams (as computed, and with the
/// paper's impact law), then those on the response examples.
pub(super) fn across_section(out: &mut String, rows: &mut Vec<Row>, rep: &Reproduction) {
    out.push_str("## Across figures\n\n");
    out.push_str("The paper's comparative statements, checked on our shares of values (periodic: any period or rest; chaotic region: chaotic or quasiperiodic values) and on the response examples. Rows marked *eqs. 17–27* use every diagram recomputed with the paper's own impact law (e = 0; Housner's law where the block cannot slide) instead of the preset's ratio r = 0.925.\n\n");
    out.push_str("| Figs. | the paper says | ours | verdict |\n|---|---|---|---|\n");
    diagram_claims(out, rows, &|n| diag(rep, n), "");
    diagram_claims(out, rows, &|n| rep.paper_law_diagram(n), " (eqs. 17–27)");
    let resp = |n: u32| rep.response(n);
    let amp = |r: &ResponseExample| r.max_abs_theta;
    let c = match (resp(7), resp(8)) {
        (Some(a), Some(b)) => amplitude_larger((amp(a), a.tumble_tau), (amp(b), b.tumble_tau)),
        _ => not_computed(),
    };
    push_claim(out, rows, "7 vs 8", "max amplitude larger at Ω = 8 than at Ω = 10", c);
    let c = resp(7).map_or_else(not_computed, |a| tumbling_level(amp(a), a.tumble_tau));
    push_claim(out, rows, "7", "reached a tumbling level (read: max |Θ| ≥ 0.9)", c);
    let c = match (resp(7), resp(12), resp(13)) {
        (Some(a), Some(b), Some(c)) => amplitude_decreasing([amp(a), amp(b), amp(c)]),
        _ => not_computed(),
    };
    push_claim(
        out,
        rows,
        "7, 12, 13",
        "lower friction (sliding): smaller max amplitude",
        c,
    );
    let lam = |r: &ResponseExample| -> Exponent<'static> {
        let l = best_exponent(r).map(|(l, w)| (l.largest_per_tau, if w.is_some() { " (transient)" } else { "" }));
        (r.figure, l)
    };
    let lam_claim = |a: Option<&ResponseExample>, b: &[Option<&ResponseExample>]| -> Check {
        let (Some(a), Some(bs)) = (a, b.iter().copied().collect::<Option<Vec<_>>>()) else {
            return not_computed();
        };
        let with: Vec<Exponent> = bs.iter().map(|r| lam(r)).collect();
        lambda_larger(lam(a), &with)
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
    let c = resp(18).map_or_else(not_computed, |r| inclined(r.poincare_mean));
    push_claim(
        out,
        rows,
        "18",
        "attractor inclined toward negative Θ' (read: mean Θ' of the Poincaré points < 0)",
        c,
    );
    let c = resp(7).map_or_else(not_computed, |r| {
        asymmetrical(r.poincare_mean, &r.poincare, matches!(r.long_outcome, Outcome::Tumbled))
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
