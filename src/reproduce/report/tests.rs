//! The verdict rules of [`super::claims`] and the summary's count, each on
//! small made-up inputs that give every verdict the rule can give.

use super::claims::*;
use super::{Row, tally};
use crate::analysis::lyapunov::{LyapunovResult, Method};
use crate::reproduce::diagrams::Shares;
use crate::reproduce::fixtures::{C, P1, P2, P4, T, grid};

/// Exponents per τ and per cycle with their standard errors.
fn exponents(per_tau: f64, stderr: f64, per_cycle: f64, stderr_per_cycle: f64) -> LyapunovResult {
    LyapunovResult {
        method: Method::Tangent,
        largest_per_tau: per_tau,
        per_cycle,
        stderr,
        stderr_per_cycle,
        spectrum: vec![per_tau],
        spectrum_stderr: vec![stderr],
        collapsed: 0,
        convergence: Vec::new(),
        tau_start: 100.0,
        tau_end: 800.0,
        period: 0.785,
        renormalisations: 890,
        batches: 10,
        neutral: "X",
        check: None,
    }
}

fn shares(periodic: f64, aperiodic: f64, tumbled: f64) -> Shares {
    Shares {
        periodic,
        aperiodic,
        tumbled,
        flight: 0.0,
        count: 10,
    }
}

/// The text and verdict word of a check, or `None` if it was skipped.
fn done(c: &Check) -> Option<(&str, &str)> {
    match c {
        Check::Done(text, _) => Some((text.as_str(), check_verdict(c))),
        Check::Skip(_) => None,
    }
}

fn skipped(c: &Check) -> Option<&str> {
    match c {
        Check::Skip(why) => {
            assert_eq!(check_verdict(c), "—");
            Some(why.as_str())
        }
        Check::Done(..) => None,
    }
}

#[test]
fn about_in_a_range_is_a_tenth_or_one_grid_step() {
    assert_eq!(range_tol(0.02), 0.1);
    assert_eq!(range_tol(0.25), 0.25);
}

#[test]
fn a_quoted_exponent_agrees_in_either_unit() {
    let v = |r: &LyapunovResult| lyapunov_verdict(0.5, r);
    assert_eq!(
        v(&exponents(0.52, 0.01, 0.49, 0.01)),
        (
            "agrees (per τ and per cycle); positive, as the paper's".to_string(),
            true
        )
    );
    assert_eq!(
        v(&exponents(0.55, 0.01, 2.0, 0.01)),
        ("agrees per τ; positive, as the paper's".to_string(), true)
    );
    assert_eq!(
        v(&exponents(0.1, 0.01, 0.45, 0.01)),
        ("agrees per cycle; positive, as the paper's".to_string(), true)
    );
    assert_eq!(
        v(&exponents(0.1, 0.01, 0.2, 0.01)),
        (
            "differs in value in both units; positive, as the paper's".to_string(),
            false
        )
    );
    assert_eq!(
        v(&exponents(-0.1, 0.01, -0.08, 0.01)),
        (
            "differs in value in both units; not positive, unlike the paper's".to_string(),
            false
        )
    );
    // 15 % of 0.5 is 0.075: 0.58 is outside, unless the error bar is wide.
    assert!(!v(&exponents(0.58, 0.01, 2.0, 0.01)).1);
    assert!(v(&exponents(0.58, 0.03, 2.0, 0.01)).1);
}

#[test]
fn an_exponent_verdict_needs_both_exponents() {
    let ours = exponents(0.5, 0.01, 0.4, 0.01);
    assert_eq!(exponent_verdict(None, Some(&ours), "differs"), "—");
    assert_eq!(exponent_verdict(Some(0.5), None, "differs (none)"), "differs (none)");
    assert_eq!(
        exponent_verdict(Some(0.5), Some(&ours), "differs"),
        lyapunov_verdict(0.5, &ours).0
    );
    assert!(exponent_verdict(Some(0.5), Some(&ours), "differs").starts_with("agrees per τ"));
}

#[test]
fn nearness_for_the_unit_table_and_the_two_methods() {
    assert!(near_quoted(0.57, 0.5));
    assert!(near_quoted(-0.57, -0.5));
    assert!(!near_quoted(0.58, 0.5));
    assert!(methods_agree(0.02, 0.01));
    assert!(methods_agree(-0.05, 0.02));
    assert!(methods_agree(0.009, 0.0));
    assert!(!methods_agree(0.05, 0.01));
}

#[test]
fn an_exponent_without_its_a_v_agrees_inside_our_range() {
    assert_eq!(
        exponent_range_verdict(0.51, 0.2, 0.6, 0.785),
        "agrees (within our range)"
    );
    // Per cycle only: 0.49–0.63.
    assert_eq!(exponent_range_verdict(0.51, 0.7, 0.9, 0.7), "agrees (within our range)");
    assert_eq!(
        exponent_range_verdict(0.51, 0.7, 0.9, 2.0),
        "differs (outside our range)"
    );
}

#[test]
fn only_a_chaotic_example_has_a_class_verdict() {
    assert_eq!(class_verdict(Some(true), C), ("chaotic", "agrees"));
    assert_eq!(class_verdict(Some(true), P1), ("chaotic", "differs"));
    assert_eq!(class_verdict(Some(true), T), ("chaotic", "differs"));
    assert_eq!(class_verdict(Some(false), C), ("not chaotic", "—"));
    assert_eq!(class_verdict(None, C), ("not stated", "—"));
}

#[test]
fn neighbouring_runs_agree_when_most_are_chaotic() {
    assert_eq!(
        neighbours_verdict(Some(true), &[C, C, P1, T]),
        "agrees (most are chaotic)"
    );
    assert_eq!(
        neighbours_verdict(Some(true), &[C, P1, P1, T]),
        "partly (some are chaotic)"
    );
    assert_eq!(neighbours_verdict(Some(true), &[P1, T, T]), "differs (none is chaotic)");
    assert_eq!(neighbours_verdict(Some(false), &[C, C]), "—");
    assert_eq!(neighbours_verdict(None, &[C]), "—");
}

#[test]
fn an_amplitude_agrees_within_a_tenth() {
    assert_eq!(amplitude_verdict(0.6, 0.68), "agrees (±0.1)");
    assert_eq!(amplitude_verdict(0.6, 0.52), "agrees (±0.1)");
    assert_eq!(amplitude_verdict(0.6, 0.75), "differs");
}

#[test]
fn a_variant_explains_a_range_with_three_quarters() {
    assert!(explains(0.75));
    assert!(explains(1.0));
    assert!(!explains(0.74));
}

#[test]
fn tumbled_values_whose_neighbours_rock_on() {
    assert!(survival_verdict(5, 1, 10).starts_with("most rock on"));
    assert_eq!(
        survival_verdict(2, 1, 10),
        "a few (10 %) rock on chaotically: chance alone does not explain the paper's range"
    );
    assert_eq!(survival_verdict(0, 0, 10), "none rocks on");
}

#[test]
fn the_ratio_scan_names_every_r_that_reproduces_or_the_best() {
    let name = |r: f64| format!("{r}");
    assert_eq!(
        ratio_scan_verdict(&[(0.85, 1), (0.87, 3), (0.89, 3)], 3, &name),
        (
            "Every range agrees at r = 0.87, 0.89.".to_string(),
            "r = 0.87, 0.89".to_string()
        )
    );
    // The first of the best, not the last.
    assert_eq!(
        ratio_scan_verdict(&[(0.85, 1), (0.87, 2), (0.89, 2)], 3, &name),
        (
            "No r in the scan reproduces every range; the most ranges (2 of 3) agree at r = 0.87.".to_string(),
            "none found".to_string()
        )
    );
    assert_eq!(
        ratio_scan_verdict(&[], 3, &name).0,
        "No r in the scan reproduces every range; the most ranges (0 of 3) agree at r = —."
    );
}

#[test]
fn regions_are_compared_by_their_shares() {
    let (x, y) = (shares(0.5, 0.3, 0.2), shares(0.3, 0.3, 0.4));
    assert_eq!(done(&periodic_wider(&x, &y)), Some(("periodic 5/10 vs 3/10", "agrees")));
    assert_eq!(
        done(&periodic_wider(&y, &x)),
        Some(("periodic 3/10 vs 5/10", "differs"))
    );
    assert_eq!(done(&periodic_wider(&x, &x)).map(|d| d.1), Some("differs"));
    assert_eq!(
        done(&periodic_narrower(&y, &x)),
        Some(("periodic 3/10 vs 5/10", "agrees"))
    );
    assert_eq!(done(&periodic_narrower(&x, &y)).map(|d| d.1), Some("differs"));
    assert_eq!(
        done(&tumbling_narrower(&x, &y)),
        Some(("tumbled 2/10 vs 4/10", "agrees"))
    );
    assert_eq!(done(&tumbling_narrower(&y, &x)).map(|d| d.1), Some("differs"));
    // Equal shares are not wider or narrower.
    assert_eq!(done(&tumbling_narrower(&x, &x)).map(|d| d.1), Some("differs"));
    assert_eq!(done(&periodic_narrower(&x, &x)).map(|d| d.1), Some("differs"));
    let z = shares(0.2, 0.6, 0.2);
    assert_eq!(done(&chaotic_wider(&z, &x)), Some(("chaotic 6/10 vs 3/10", "agrees")));
    assert_eq!(done(&chaotic_wider(&x, &y)).map(|d| d.1), Some("differs"));
}

#[test]
fn intermittency_wants_four_switches() {
    let c = intermittent(&grid(&[P1, C, P1, C, P1]));
    assert_eq!(done(&c), Some(("4 periodic↔aperiodic switches", "agrees")));
    // Tumbled values are passed over, so they do not switch.
    let c = intermittent(&grid(&[P1, C, T, C, P1, C]));
    assert_eq!(done(&c), Some(("3 periodic↔aperiodic switches", "differs")));
}

#[test]
fn period_doubling_wants_periods_one_two_four() {
    let c = period_doubling(&grid(&[P1, P2, P4, C, C]));
    assert_eq!(done(&c), Some(("periods 1 → 2 → 4 (period doubling)", "agrees")));
    let c = period_doubling(&grid(&[P1, P2, C, C, P4]));
    assert_eq!(done(&c), Some(("periods 1 → 2", "differs")));
    let c = period_doubling(&grid(&[C, T, P1]));
    assert_eq!(done(&c), Some(("none", "differs")));
}

#[test]
fn amplitudes_are_compared_unless_both_tumble() {
    let c = amplitude_larger((0.8, None), (0.5, Some(100.0)));
    assert_eq!(done(&c), Some(("max |Θ| 0.800 vs 0.500", "agrees")));
    let c = amplitude_larger((0.5, Some(100.0)), (0.8, None));
    assert_eq!(done(&c).map(|d| d.1), Some("differs"));
    let c = amplitude_larger((1.0, Some(100.0)), (1.0, Some(250.5)));
    assert_eq!(
        skipped(&c),
        Some("not comparable: both tumble (τ = 100.0 and 250.5), so both reach |Θ| = 1")
    );
    let c = tumbling_level(0.95, Some(123.3));
    assert_eq!(done(&c), Some(("max |Θ| 0.950, tumbled at τ = 123.3", "agrees")));
    let c = tumbling_level(0.85, None);
    assert_eq!(done(&c), Some(("max |Θ| 0.850", "differs")));
    let c = amplitude_decreasing([0.9, 0.5, 0.3]);
    assert_eq!(done(&c), Some(("max |Θ| 0.900 > 0.500 > 0.300?", "agrees")));
    assert_eq!(
        done(&amplitude_decreasing([0.9, 0.3, 0.5])).map(|d| d.1),
        Some("differs")
    );
    assert_eq!(
        done(&amplitude_decreasing([0.5, 0.5, 0.3])).map(|d| d.1),
        Some("differs")
    );
}

#[test]
fn lambda_with_sliding_must_exceed_every_one_without() {
    let c = lambda_larger(
        (7, Some((0.1, ""))),
        &[(12, Some((0.2, " (transient)"))), (13, Some((0.3, "")))],
    );
    assert_eq!(
        done(&c),
        Some((
            "λ 0.100 without sliding vs 0.200 (transient), 0.300 with (per τ)",
            "agrees"
        ))
    );
    let c = lambda_larger((7, Some((0.25, ""))), &[(12, Some((0.2, ""))), (13, Some((0.3, "")))]);
    assert_eq!(done(&c).map(|d| d.1), Some("differs"));
    let c = lambda_larger((7, None), &[(12, Some((0.2, "")))]);
    assert_eq!(skipped(&c), Some("Fig. 7 has no exponent"));
    let c = lambda_larger((7, Some((0.1, ""))), &[(12, Some((0.2, ""))), (13, None)]);
    assert_eq!(skipped(&c), Some("Fig. 13 has no exponent"));
}

#[test]
fn the_attractor_shape_from_the_poincare_points() {
    assert_eq!(done(&inclined(Some((0.1, -0.2)))), Some(("mean Θ' = -0.200", "agrees")));
    assert_eq!(done(&inclined(Some((0.1, 0.2)))).map(|d| d.1), Some("differs"));
    assert_eq!(skipped(&inclined(None)), Some("no Poincaré points"));
    let points = [(0.5, 0.0), (-1.0, 0.3)];
    let c = asymmetrical(Some((0.06, 0.0)), &points, false);
    assert_eq!(done(&c), Some(("mean Θ = 0.060, largest |Θ| 1.000", "agrees")));
    let c = asymmetrical(Some((-0.04, 0.0)), &points, true);
    assert_eq!(
        done(&c),
        Some((
            "mean Θ = -0.040, largest |Θ| 1.000 (points of the transient before the tumble)",
            "differs"
        ))
    );
    assert_eq!(skipped(&asymmetrical(None, &points, false)), Some("no Poincaré points"));
}

#[test]
fn the_summary_counts_verdicts_by_their_first_word() {
    let rows: Vec<Row> = [
        "agrees",
        "agrees (±0.1)",
        "agrees per cycle; positive, as the paper's",
        "partly (some are chaotic)",
        "differs",
        "differs (outside our range)",
        "—",
        "none found",
        "r = 0.87",
        "not explained by any single variant",
    ]
    .iter()
    .map(|v| Row {
        figure: "4".to_string(),
        claim: "a claim".to_string(),
        paper: "as stated".to_string(),
        ours: "ours".to_string(),
        verdict: (*v).to_string(),
    })
    .collect();
    assert_eq!(tally(&rows), (3, 1, 2));
}
