//! Hard cases for the event-driven integrator (issue 5), each a named test.

mod common;

use common::{harmonic, model, opts, run};
use rocking::integrate::hybrid::{Driver, Limits, Observer, Outputs};
use rocking::integrate::{Dop853, Tolerances};
use rocking::model::excitation::Excitation;
use rocking::model::system::{EventRecord, N};
use rocking::model::{BlockSystem, EventKind, Geometry, ImpactLaw, Mode};
use rocking::sim::{InitialState, Method, Outcome, initial_mode};

const NO_SLIDING: (f64, f64) = (f64::INFINITY, f64::INFINITY);

#[test]
fn zeno_accumulation_in_free_rocking() {
    for ratio in [0.05, 0.25, 1.0] {
        let m = model(ratio, 1.0, ImpactLaw::Housner, NO_SLIDING, Excitation::None);
        let res = run(m, 0.4, 0.0, &opts(2000.0, 1e-10, None));
        assert_eq!(res.outcome, Outcome::Rest, "B/H = {ratio}");
        let rest = res.events.last().expect("events");
        assert_eq!(rest.kind, EventKind::Rest);
        // Impacts up to the accumulation: the post-impact speed decays
        // geometrically by r from the first impact's, so the count is the
        // first n with |Θ'₁| rⁿ < zeno_eps.
        let r = Geometry::new(ratio, 1.0).housner_r();
        let first = res.events.iter().find(|e| e.kind == EventKind::Impact).expect("impact");
        let expected = ((1e-5 / first.theta_dot_after.abs()).ln() / r.ln()).ceil() + 1.0;
        let got = res.tally.impacts as f64;
        assert!(
            (got - expected).abs() <= 2.0,
            "B/H = {ratio}: {got} impacts, expected {expected}"
        );
        assert!(res.energy.relative_residual < 1e-8);
    }
}

#[test]
fn zeno_accumulation_under_weak_excitation() {
    // A_h ψ = 0.05 tan ψ: the base cannot lift the block from rest, and is
    // too weak to sustain rocking started by hand, which decays to rest
    // through an accumulation of impacts and stays there. (Stronger forcing
    // below the uplift level can sustain rocking: at 0.5 tan ψ it does.)
    let geo = Geometry::new(1.0, 4.0);
    let a_h = 0.05 * geo.tan_psi / geo.psi;
    let m = model(1.0, 4.0, ImpactLaw::Housner, NO_SLIDING, harmonic(&geo, a_h, 0.0, 3.0));
    let res = run(m, 0.3, 0.0, &opts(300.0, 1e-10, None));
    assert_eq!(res.outcome, Outcome::Rest);
    let rests: Vec<_> = res.events.iter().filter(|e| e.kind == EventKind::Rest).collect();
    assert_eq!(rests.len(), 1);
    assert_eq!(res.events.last().map(|e| e.kind), Some(EventKind::Rest));
    for w in res.events.windows(2) {
        assert!(w[1].tau > w[0].tau);
    }
}

#[test]
fn grazing_the_tumble_angle_from_either_side() {
    // Free rocking leaving Θ = 0 with ½w² = 1 − cos ψ just reaches |Θ| = 1
    // (the centre of mass over the pivot). A hair less: it falls back; a
    // hair more: it tumbles.
    let geo = Geometry::new(1.0, 4.0);
    let w_crit = (2.0 * (1.0 - geo.cos_psi)).sqrt();
    for (factor, tumbles) in [(1.0 - 1e-7, false), (1.0 + 1e-7, true)] {
        let m = model(1.0, 4.0, ImpactLaw::Housner, NO_SLIDING, Excitation::None);
        let res = run(m, 0.0, factor * w_crit / geo.psi, &opts(60.0, 1e-12, None));
        assert_eq!(
            res.outcome == Outcome::Tumbled,
            tumbles,
            "factor {factor}: {:?}",
            res.outcome
        );
        if !tumbles {
            assert!(
                res.max_abs_theta > 0.999 && res.max_abs_theta < 1.0,
                "peak {}",
                res.max_abs_theta
            );
            assert!(res.tally.impacts > 0);
        }
    }
}

#[test]
fn static_friction_equal_to_tan_psi() {
    // Sliding and uplift thresholds coincide: the block rocks (ties go to
    // uplift, which needs no slip), and stays consistent afterwards.
    let geo = Geometry::new(1.0, 4.0);
    let mu = geo.tan_psi;
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Housner,
        (mu, 0.8 * mu),
        harmonic(&geo, 2.0, 0.0, 4.0),
    );
    let res = run(m, 0.0, 0.0, &opts(100.0, 1e-10, Some(0.05)));
    assert_eq!(res.events.first().map(|e| e.kind), Some(EventKind::Uplift));
    common::assert_pivot_side(&res);
    assert!(res.energy.relative_residual < 1e-7, "{:?}", res.energy);
}

#[test]
fn near_flight_vertical_excitation() {
    // a_v/g reaches −(1 − 1e-9): the normal force nearly vanishes but the
    // block never leaves the base; at −(1 + 1e-9) it flies.
    let geo = Geometry::new(1.0, 4.0);
    for (level, flies) in [(1.0 - 1e-9, false), (1.0 + 1e-9, true)] {
        let m = model(
            1.0,
            4.0,
            ImpactLaw::Housner,
            NO_SLIDING,
            harmonic(&geo, 0.0, level / geo.psi, 2.0),
        );
        let res = run(m, 0.0, 0.0, &opts(10.0, 1e-11, None));
        assert_eq!(
            res.outcome == Outcome::Flight,
            flies,
            "level {level}: {:?}",
            res.outcome
        );
    }
}

#[test]
fn very_slender_and_square_blocks() {
    for ratio in [0.05, 1.0] {
        let geo = Geometry::new(ratio, 1.0);
        for (mu, law) in [
            (NO_SLIDING, ImpactLaw::Housner),
            ((0.3, 0.25), ImpactLaw::Housner),
            ((0.3, 0.25), ImpactLaw::CornerMomentum),
            (
                (0.3, 0.25),
                ImpactLaw::Impulse {
                    e: 0.0,
                    mu_s: 0.3,
                    mu_k: 0.25,
                },
            ),
        ] {
            let m = model(ratio, 1.0, law, mu, harmonic(&geo, 2.5, 1.0, 6.0));
            let res = run(m, 0.0, 0.0, &opts(200.0, 1e-10, Some(0.05)));
            common::assert_pivot_side(&res);
            assert!(
                res.energy.relative_residual < 1e-7,
                "B/H {ratio} {law:?}: {:?}",
                res.energy
            );
            for w in res.events.windows(2) {
                assert!(w[1].tau > w[0].tau);
            }
        }
    }
}

/// Keeps only the latest section point: memory stays constant however long
/// the run.
#[derive(Default)]
struct LastSection {
    first_steady: Option<[f64; 2]>,
    last: [f64; 2],
    count: u64,
    events: u64,
}

impl Observer<Mode, EventRecord, N> for LastSection {
    fn sample(&mut self, _t: f64, _m: Mode, _y: &[f64; N]) {}
    fn section(&mut self, k: u64, _t: f64, _m: Mode, y: &[f64; N]) {
        self.count += 1;
        self.last = [y[0], y[1]];
        if k == 1000 {
            self.first_steady = Some(self.last);
        }
    }
    fn event(&mut self, _t: f64, _m: Mode, _y: &[f64; N], _r: EventRecord) {
        self.events += 1;
    }
}

#[test]
fn million_tau_periodic_run_has_bounded_memory_and_no_drift() {
    // The paper's Fig. 4 conditions at A_v = 1 (period-1 rocking): after
    // 10⁶ τ the stroboscopic point is where it was at τ ≈ 785.
    let geo = Geometry::new(1.0, 4.0);
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Ratio { r: 0.925 },
        NO_SLIDING,
        harmonic(&geo, 3.0, 1.0, 8.0),
    );
    let period = m.excitation.forcing_period().expect("harmonic");
    let init = InitialState {
        theta: 0.0,
        theta_dot: 0.0,
        x_dot: None,
    };
    let (mode, y0) = initial_mode(&m, &init).expect("initial");
    let tol = Tolerances {
        rtol: 1e-10,
        atol: 1e-12,
        ..Tolerances::default()
    };
    let outputs = Outputs {
        sample_dt: None,
        section_period: Some(period),
    };
    let mut d = Driver::new(
        Dop853::new(tol),
        BlockSystem::new(m),
        mode,
        0.0,
        y0,
        Limits::default(),
        outputs,
    );
    let mut obs = LastSection::default();
    d.advance(1.0e6, &mut obs).expect("runs");
    let first = obs.first_steady.expect("steady point");
    let drift = ((obs.last[0] - first[0]).powi(2) + (obs.last[1] - first[1]).powi(2)).sqrt();
    assert!(obs.count > 1_270_000, "{} section points", obs.count);
    assert!(obs.events > 1_000_000);
    assert!(
        drift < 1e-8,
        "the periodic orbit drifted by {drift:e} (from {first:?} to {:?})",
        obs.last
    );
}

#[test]
fn papers_integrator_at_its_own_step_finds_the_same_orbit() {
    // Ralston RK2 at h = 0.004 with the paper's step cutting lands on the
    // same period-1 stroboscopic point as DOP853, to its O(h²) accuracy.
    let geo = Geometry::new(1.0, 4.0);
    let mk = || {
        model(
            1.0,
            4.0,
            ImpactLaw::Ratio { r: 0.925 },
            NO_SLIDING,
            harmonic(&geo, 3.0, 1.0, 8.0),
        )
    };
    let exact = run(mk(), 0.0, 0.0, &opts(800.0, 1e-11, None));
    let mut o = opts(800.0, 1e-11, None);
    o.method = Method::Ralston;
    let paper = run(mk(), 0.0, 0.0, &o);
    let (a, b) = (
        exact.section.last().expect("point"),
        paper.section.last().expect("point"),
    );
    assert_eq!(a.k, b.k);
    assert!(
        (a.theta - b.theta).abs() < 1e-3 && (a.theta_dot - b.theta_dot).abs() < 1e-3,
        "{a:?} vs {b:?}"
    );
}

#[test]
fn same_config_gives_bit_identical_results() {
    let geo = Geometry::new(1.0, 4.0);
    let mk = || model(1.0, 4.0, ImpactLaw::Housner, (0.4, 0.35), harmonic(&geo, 2.0, 2.5, 8.0));
    let a = run(mk(), 0.0, 0.0, &opts(300.0, 1e-10, Some(0.05)));
    let b = run(mk(), 0.0, 0.0, &opts(300.0, 1e-10, Some(0.05)));
    assert_eq!(a.events, b.events);
    assert_eq!(a.history, b.history);
    assert_eq!(a.section, b.section);
    assert_eq!(a.energy, b.energy);
}
