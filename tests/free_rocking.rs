//! Housner free rocking against an independent energy-conservation
//! quadrature of the exact nonlinear model, and against the linearised
//! slender-block closed form.

mod common;

use common::{model, opts, run};
use rocking::model::excitation::Excitation;
use rocking::model::{EventKind, Geometry, ImpactLaw};
// The quarter period by energy quadrature: computed without the integrator
// (substitution Θ = Θ₀(1 − v²) and composite Simpson; src/bench/quadrature.rs).
use rocking::bench::quadrature::quarter_period;

/// |w| = ψ|Θ'| at Θ = 0 after falling from rest at `theta0`:
/// ½w² = cos(ψ(1−Θ₀)) − cos ψ.
fn impact_speed(psi: f64, theta0: f64) -> f64 {
    (4.0 * (psi * (1.0 - 0.5 * theta0)).sin() * (0.5 * psi * theta0).sin()).sqrt()
}

/// Amplitude reached after leaving Θ = 0 with speed |w|.
fn amplitude(psi: f64, w: f64) -> f64 {
    1.0 - (psi.cos() + 0.5 * w * w).acos() / psi
}

#[test]
fn housner_free_rocking_matches_quadrature_to_1e9() {
    let (b, h) = (1.0, 4.0);
    let geo = Geometry::new(b, h);
    let psi = geo.psi;
    let r = geo.housner_r();
    let m = model(
        b,
        h,
        ImpactLaw::Housner,
        (f64::INFINITY, f64::INFINITY),
        Excitation::None,
    );
    let res = run(m, 0.5, 0.0, &opts(60.0, 1e-13, None));
    let impacts: Vec<_> = res.events.iter().filter(|e| e.kind == EventKind::Impact).collect();
    assert!(impacts.len() >= 10, "only {} impacts", impacts.len());

    let mut theta_k = 0.5;
    let mut tau = quarter_period(psi, theta_k);
    let mut sign = -1.0; // falls back from Θ > 0 towards Θ = 0
    let mut worst = (0.0f64, 0.0f64);
    for ev in impacts.iter().take(10) {
        let w_before = impact_speed(psi, theta_k);
        let w_after = r * w_before;
        let err_tau = (ev.tau - tau).abs();
        let err_vel = (ev.theta_dot_after - sign * w_after / psi).abs();
        worst = (worst.0.max(err_tau), worst.1.max(err_vel));
        assert!(
            err_tau <= 1e-9,
            "impact at {} vs quadrature {tau}: error {err_tau:e}",
            ev.tau
        );
        assert!(
            err_vel <= 1e-9,
            "post-impact Θ' {} vs {}: error {err_vel:e}",
            ev.theta_dot_after,
            sign * w_after / psi
        );
        assert!((ev.theta_dot_before - sign * w_before / psi).abs() <= 1e-9);
        theta_k = amplitude(psi, w_after);
        tau += 2.0 * quarter_period(psi, theta_k);
        sign = -sign;
    }
    eprintln!("worst |Δτ| = {:e}, worst |ΔΘ'| = {:e}", worst.0, worst.1);
}

#[test]
fn slender_limit_matches_linearised_closed_form() {
    // Θ'' = Θ − 1 for small ψ: τ_q = arccosh(1/(1 − Θ₀)); the exact model
    // differs by O(ψ²).
    let theta0 = 0.5;
    let closed = (1.0f64 / (1.0 - theta0)).acosh();
    let mut errors = Vec::new();
    for ratio in [0.02, 0.01] {
        let m = model(
            ratio,
            1.0,
            ImpactLaw::Housner,
            (f64::INFINITY, f64::INFINITY),
            Excitation::None,
        );
        let res = run(m, theta0, 0.0, &opts(3.0, 1e-12, None));
        let first = res
            .events
            .iter()
            .find(|e| e.kind == EventKind::Impact)
            .expect("an impact");
        errors.push(((first.tau - closed) / closed).abs());
    }
    assert!(errors[1] < 2e-5, "relative error {:e} at B/H = 0.01", errors[1]);
    // Halving ψ divides the error by about four.
    let ratio = errors[0] / errors[1];
    assert!((3.5..4.5).contains(&ratio), "error ratio {ratio} (errors {errors:?})");
}

#[test]
fn free_rocking_ends_at_rest_by_accumulation() {
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Housner,
        (f64::INFINITY, f64::INFINITY),
        Excitation::None,
    );
    let res = run(m, 0.3, 0.0, &opts(400.0, 1e-10, None));
    let last = res.events.last().expect("events");
    assert_eq!(last.kind, EventKind::Rest);
    assert_eq!(res.outcome, rocking::sim::Outcome::Rest);
    // Event times strictly increase, also across the accumulation point.
    for w in res.events.windows(2) {
        assert!(w[1].tau > w[0].tau, "{} !> {}", w[1].tau, w[0].tau);
    }
    // The accumulation time lies after the last impact and within one
    // geometric tail of it.
    let n = res.events.len();
    let before = &res.events[n - 2];
    assert!(last.tau > before.tau && last.tau - before.tau < 1e-3);
    // All energy above the resting level was lost at impacts.
    let e = res.energy;
    assert!((e.loss_impact - (e.initial - e.r#final)).abs() < 1e-9, "{e:?}");
}

#[test]
fn papers_ralston_method_converges_to_the_quadrature() {
    // The paper's method: fixed step 0.004, the step cut by 10 at a sign
    // change until |Θ| < 1e-6. Its impact times are second-order accurate
    // in the step; halving it cuts the error by about four.
    let (b, h) = (1.0, 4.0);
    let geo = Geometry::new(b, h);
    let first = quarter_period(geo.psi, 0.5);
    let mut errors = Vec::new();
    for step in [0.004, 0.002] {
        let m = model(
            b,
            h,
            ImpactLaw::Housner,
            (f64::INFINITY, f64::INFINITY),
            Excitation::None,
        );
        let mut o = opts(3.0, 1e-10, None);
        o.method = rocking::sim::Method::Ralston;
        o.tol.h_fixed = step;
        let res = run(m, 0.5, 0.0, &o);
        let ev = res
            .events
            .iter()
            .find(|e| e.kind == EventKind::Impact)
            .expect("an impact");
        errors.push((ev.tau - first).abs());
    }
    assert!(errors[0] < 1e-4, "Ralston at 0.004: impact time error {:e}", errors[0]);
    let ratio = errors[0] / errors[1];
    assert!(
        ratio > 2.5,
        "halving the step only cut the error by {ratio} ({errors:?})"
    );
    eprintln!("ralston first-impact errors at h = 0.004, 0.002: {errors:?}");
}
