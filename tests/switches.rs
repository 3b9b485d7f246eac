//! Mode switches: uplift thresholds, mirror symmetry, passivity, slip and
//! stick, and flight.

mod common;

use common::{harmonic, model, opts, run};
use rocking::model::excitation::Excitation;
use rocking::model::{EventKind, Geometry, ImpactLaw, Mode, Sign};
use rocking::sim::Outcome;

#[test]
fn uplift_at_tan_psi_without_vertical_excitation() {
    let geo = Geometry::new(1.0, 4.0);
    for a_h in [1.5, -2.0, 3.0] {
        let m = model(
            1.0,
            4.0,
            ImpactLaw::Housner,
            (f64::INFINITY, f64::INFINITY),
            harmonic(&geo, a_h, 0.0, 3.0),
        );
        let res = run(m, 0.0, 0.0, &opts(3.0, 1e-12, None));
        let up = res.events.first().expect("an uplift");
        assert_eq!(up.kind, EventKind::Uplift);
        let a = a_h * geo.psi * (3.0 * up.tau).sin();
        assert!(
            (a.abs() - geo.tan_psi).abs() <= 1e-9,
            "|a_h|/g = {} vs tan ψ = {}",
            a.abs(),
            geo.tan_psi
        );
        // A base accelerating to +x tips the block to θ < 0.
        let pivot = if a > 0.0 { Sign::Neg } else { Sign::Pos };
        assert_eq!(up.after, Mode::Rock { pivot });
    }
}

#[test]
fn uplift_at_tan_psi_times_g_plus_av_with_vertical_excitation() {
    let geo = Geometry::new(1.0, 3.0);
    for (a_h, a_v, omega_v, phase_v) in [(2.0, 1.5, 3.0, 0.0), (2.5, -2.0, 7.0, 1.0), (3.0, 2.5, 1.3, 2.0)] {
        let exc = Excitation::Harmonic(rocking::model::Harmonic {
            a_h,
            a_v,
            omega_h: 3.0,
            omega_v,
            phase_h: 0.0,
            phase_v,
            psi: geo.psi,
        });
        let m = model(
            1.0,
            3.0,
            ImpactLaw::Housner,
            (f64::INFINITY, f64::INFINITY),
            exc.clone(),
        );
        let res = run(m, 0.0, 0.0, &opts(3.0, 1e-12, None));
        let up = res.events.first().expect("an uplift");
        assert_eq!(up.kind, EventKind::Uplift);
        let fo = exc.forcing(up.tau);
        let threshold = geo.tan_psi * (1.0 + fo.av);
        assert!(
            (fo.a.abs() - threshold).abs() <= 1e-9,
            "|a_h|/g = {} vs tan ψ (1 + a_v/g) = {threshold}",
            fo.a.abs()
        );
    }
}

/// Every output of a run and of its mirror image (a_h → −a_h) agree with
/// Θ, Θ', X, X' negated, bit for bit.
fn assert_mirrored(a: &rocking::sim::RunResult, b: &rocking::sim::RunResult) {
    assert_eq!(a.events.len(), b.events.len());
    for (x, y) in a.events.iter().zip(&b.events) {
        assert_eq!(x.tau, y.tau);
        assert_eq!(x.kind, y.kind);
        assert_eq!(x.before.name(), y.before.name());
        assert_eq!(x.after.name(), y.after.name());
        assert_eq!(x.theta, -y.theta);
        assert_eq!(x.theta_dot_before, -y.theta_dot_before);
        assert_eq!(x.theta_dot_after, -y.theta_dot_after);
        assert_eq!(x.x_dot, -y.x_dot);
    }
    assert_eq!(a.history.len(), b.history.len());
    for (x, y) in a.history.iter().zip(&b.history) {
        assert_eq!(
            (x.tau, x.theta, x.theta_dot, x.x, x.x_dot),
            (y.tau, -y.theta, -y.theta_dot, -y.x, -y.x_dot)
        );
        assert_eq!(x.mode.name(), y.mode.name());
    }
    assert_eq!(a.section.len(), b.section.len());
    for (x, y) in a.section.iter().zip(&b.section) {
        assert_eq!(
            (x.tau, x.theta, x.theta_dot, x.x, x.x_dot),
            (y.tau, -y.theta, -y.theta_dot, -y.x, -y.x_dot)
        );
    }
    assert_eq!(a.max_abs_theta, b.max_abs_theta);
    assert_eq!(a.energy, b.energy);
    assert_eq!(a.mode_time, b.mode_time);
    assert_eq!(a.stats, b.stats);
}

#[test]
fn mirror_symmetry_is_exact() {
    let geo = Geometry::new(1.0, 4.0);
    let cases = [
        // No sliding, ratio law (the paper's Fig. 7).
        (
            ImpactLaw::Ratio { r: 0.925 },
            (f64::INFINITY, f64::INFINITY),
            2.0,
            2.5,
            8.0,
        ),
        // Sliding, Housner law (Fig. 12 conditions).
        (ImpactLaw::Housner, (0.4, 0.35), 2.0, 2.5, 8.0),
        // Sliding with slip during impacts.
        (
            ImpactLaw::Impulse {
                e: 0.0,
                mu_s: 0.3,
                mu_k: 0.25,
            },
            (0.3, 0.25),
            3.0,
            2.0,
            10.0,
        ),
    ];
    for (law, mu, a_h, a_v, omega) in cases {
        let plus = run(
            model(1.0, 4.0, law, mu, harmonic(&geo, a_h, a_v, omega)),
            0.0,
            0.0,
            &opts(150.0, 1e-10, Some(0.05)),
        );
        let minus = run(
            model(1.0, 4.0, law, mu, harmonic(&geo, -a_h, a_v, omega)),
            0.0,
            0.0,
            &opts(150.0, 1e-10, Some(0.05)),
        );
        assert!(plus.tally.impacts > 10, "{law:?}: too few impacts to test");
        assert_mirrored(&plus, &minus);
    }
}

/// SplitMix64: a small deterministic generator for random scenes.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

#[test]
fn passivity_without_excitation() {
    let mut rng = Rng(7);
    let mut checked = 0;
    for case in 0..1500 {
        let ratio = rng.range(0.05, 1.0);
        let geo = Geometry::new(ratio, 1.0);
        let mu = match case % 3 {
            0 => (f64::INFINITY, f64::INFINITY),
            _ => {
                let s = rng.range(0.0, 1.2);
                (s, s * rng.range(0.5, 1.0))
            }
        };
        let law = match case % 4 {
            0 => ImpactLaw::CornerMomentum,
            1 => ImpactLaw::Housner,
            2 => ImpactLaw::Impulse {
                e: 0.0,
                mu_s: mu.0,
                mu_k: mu.1,
            },
            _ => ImpactLaw::Ratio { r: rng.range(0.0, 1.0) },
        };
        // The ratio law, and Housner's law (a ratio law), are passive only
        // when the corner cannot slip before the impact (docs/model.md
        // §7.3–7.4).
        let mu = if matches!(law, ImpactLaw::Ratio { .. } | ImpactLaw::Housner) {
            (f64::INFINITY, f64::INFINITY)
        } else {
            mu
        };
        let theta0 = rng.range(-0.95, 0.95);
        let theta_dot0 = rng.range(-0.5, 0.5);
        let mut m = model(ratio, 1.0, law, mu, Excitation::None);
        m.tumble_theta = geo.side_theta();
        m.flight = rocking::model::FlightPolicy::Ignore;
        let res = run(m.clone(), theta0, theta_dot0, &opts(15.0, 1e-10, Some(0.01)));
        common::assert_pivot_side(&res);
        let sys = rocking::model::BlockSystem::new(m);
        let e0 = res.energy.initial;
        let tol = 1e-8 * e0.abs().max(1.0);
        for row in &res.history {
            let y = [row.theta, row.theta_dot, row.x, row.x_dot, 0.0, 0.0];
            let e = sys.energy(row.mode, &y);
            assert!(
                e <= e0 + tol,
                "case {case}: energy rose from {e0} to {e} at τ = {} ({law:?}, μ = {mu:?})",
                row.tau
            );
        }
        assert!(
            res.energy.loss_impact >= -tol && res.energy.loss_friction >= -tol,
            "case {case}: {:?}",
            res.energy
        );
        assert!(res.energy.work_base == 0.0);
        assert!(res.energy.relative_residual < 1e-7, "case {case}: {:?}", res.energy);
        checked += 1;
    }
    assert_eq!(checked, 1500);
}

#[test]
fn slide_rock_starts_when_friction_runs_out_and_energy_closes() {
    let geo = Geometry::new(1.0, 4.0);
    let m = model(1.0, 4.0, ImpactLaw::Housner, (0.4, 0.35), harmonic(&geo, 2.0, 2.5, 8.0));
    let res = run(m, 0.0, 0.0, &opts(200.0, 1e-11, Some(0.01)));
    common::assert_pivot_side(&res);
    assert!(
        res.events
            .iter()
            .any(|e| e.kind == EventKind::Slip && e.after.name() == "slide-rock")
    );
    assert!(res.events.iter().any(|e| e.kind == EventKind::Stick));
    assert!(res.mode_time[3] > 0.0 && res.mode_time[2] > 0.0);
    assert!(res.energy.loss_friction > 0.0);
    assert!(res.energy.relative_residual < 1e-8, "{:?}", res.energy);
    for w in res.events.windows(2) {
        assert!(w[1].tau > w[0].tau);
    }
}

#[test]
fn flat_sliding_block_slides_then_sticks() {
    // μ_s = 0.1 < tan ψ = 0.25: the block slides flat before it could tip.
    let geo = Geometry::new(1.0, 4.0);
    let m = model(1.0, 4.0, ImpactLaw::Housner, (0.1, 0.08), harmonic(&geo, 0.6, 0.0, 2.0));
    let res = run(m, 0.0, 0.0, &opts(20.0, 1e-11, None));
    let slip = res.events.first().expect("slip");
    assert_eq!(slip.kind, EventKind::Slip);
    assert_eq!(slip.after.name(), "slide");
    let fo = harmonic(&geo, 0.6, 0.0, 2.0).forcing(slip.tau);
    assert!((fo.a.abs() - 0.1).abs() < 1e-9, "slip at |a| = {}", fo.a.abs());
    assert!(
        res.events
            .iter()
            .any(|e| e.kind == EventKind::Stick && e.after == Mode::Rest)
    );
    assert!(res.mode_time[0] > 0.0 && res.mode_time[1] > 0.0 && res.mode_time[2] == 0.0);
}

#[test]
fn strong_vertical_excitation_ends_in_flight() {
    let geo = Geometry::new(1.0, 4.0);
    // a_v/g = A_v ψ sin: A_v ψ > 1 lifts the block off the base.
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Housner,
        (f64::INFINITY, f64::INFINITY),
        harmonic(&geo, 0.0, 5.0, 4.0),
    );
    let res = run(m, 0.0, 0.0, &opts(10.0, 1e-10, None));
    assert_eq!(res.outcome, Outcome::Flight);
    let ev = res.events.last().expect("flight event");
    assert_eq!(ev.kind, EventKind::Flight);
    let fo = harmonic(&geo, 0.0, 5.0, 4.0).forcing(ev.tau);
    assert!((1.0 + fo.av).abs() < 1e-9);
}

#[test]
fn strong_excitation_tumbles_the_block() {
    let geo = Geometry::new(1.0, 4.0);
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Housner,
        (f64::INFINITY, f64::INFINITY),
        harmonic(&geo, 6.0, 0.0, 1.0),
    );
    let res = run(m, 0.0, 0.0, &opts(50.0, 1e-10, None));
    assert_eq!(res.outcome, Outcome::Tumbled);
    let t = res.tumble_tau.expect("tumble time");
    assert_eq!(res.events.last().map(|e| e.kind), Some(EventKind::Tumble));
    assert!((res.max_abs_theta - 1.0).abs() < 1e-12 && t > 0.0);
}
