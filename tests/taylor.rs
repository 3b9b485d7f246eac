//! The Taylor method: the block's series (`model::series`) against the
//! vector field and against DOP853, mode by mode, and whole runs against
//! DOP853 at a tight tolerance.

mod common;

use common::{model, opts, run};
use rocking::integrate::hybrid::HybridSystem;
use rocking::integrate::{Dop853, Rhs, Stepper, Taylor, Tolerances};
use rocking::model::excitation::Excitation;
use rocking::model::system::N;
use rocking::model::{BlockSystem, Geometry, Harmonic, ImpactLaw, Mode, Sign};
use rocking::sim::Method;

/// One mode of the block as a plain ODE (no guards): what a stepper sees.
struct ModeField<'a> {
    sys: &'a BlockSystem,
    mode: Mode,
}

impl Rhs<N> for ModeField<'_> {
    fn eval(&self, t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
        self.sys.rhs(self.mode, t, y, dydt);
    }
    fn taylor(&self, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        self.sys.taylor(self.mode, t, y, order, c)
    }
}

/// A squat block (so slide-rock stays well posed) under a 2-D forcing with
/// separate frequencies and phases: every term of every series is exercised.
fn system() -> BlockSystem {
    let geo = Geometry::new(1.0, 2.0);
    let exc = Excitation::Harmonic(Harmonic {
        a_h: 0.8,
        a_v: 0.5,
        omega_h: 3.0,
        omega_v: 5.5,
        phase_h: 0.4,
        phase_v: -1.1,
        psi: geo.psi,
    });
    BlockSystem::new(model(1.0, 2.0, ImpactLaw::Ratio { r: 0.9 }, (0.5, 0.3), exc))
}

/// Every continuous mode, with a state inside it.
fn cases() -> Vec<(Mode, [f64; N])> {
    let (p, m) = (Sign::Pos, Sign::Neg);
    vec![
        (Mode::Rest, [0.0, 0.0, 0.1, 0.0, 0.2, 0.05]),
        (Mode::Slide { slip: p }, [0.0, 0.0, 0.1, 0.3, 0.2, 0.05]),
        (Mode::Slide { slip: m }, [0.0, 0.0, -0.1, -0.2, 0.2, 0.05]),
        (Mode::Rock { pivot: p }, [0.3, 0.4, 0.2, 0.1, 0.0, 0.0]),
        (Mode::Rock { pivot: m }, [-0.2, 0.5, -0.1, 0.05, 0.1, 0.0]),
        (Mode::SlideRock { pivot: p, slip: p }, [0.25, 0.3, 0.2, 0.4, 0.0, 0.1]),
        (Mode::SlideRock { pivot: p, slip: m }, [0.25, -0.3, 0.2, -0.4, 0.0, 0.1]),
        (Mode::SlideRock { pivot: m, slip: p }, [-0.3, 0.2, -0.2, 0.3, 0.0, 0.1]),
        (
            Mode::SlideRock { pivot: m, slip: m },
            [-0.3, -0.2, -0.2, -0.3, 0.0, 0.1],
        ),
    ]
}

#[test]
fn the_first_coefficient_is_the_vector_field() {
    let sys = system();
    for (mode, y) in cases() {
        let mut c = [[0.0; N]; 21];
        assert!(sys.taylor(mode, 1.7, &y, 20, &mut c), "{mode:?} has a series");
        let mut f = [0.0; N];
        sys.rhs(mode, 1.7, &y, &mut f);
        assert_eq!(c[0], y, "{mode:?}");
        for n in 0..N {
            // Rocking's X'' comes from X = X_pivot − s sin φ in the series and
            // from the Newton–Euler form in the vector field: round-off apart.
            assert!(
                (c[1][n] - f[n]).abs() <= 1e-14 * (1.0 + f[n].abs()),
                "{mode:?}, component {n}: {} against {}",
                c[1][n],
                f[n]
            );
        }
    }
}

#[test]
fn the_second_coefficient_is_half_the_derivative_of_the_field_along_the_flow() {
    // f(t + δ, y + δ f) − f(t − δ, y − δ f) ≈ 2δ y''(t): a check of every
    // component's second coefficient independent of the recurrences.
    let sys = system();
    for (mode, y) in cases() {
        let mut c = [[0.0; N]; 21];
        sys.taylor(mode, 0.9, &y, 20, &mut c);
        let mut f = [0.0; N];
        sys.rhs(mode, 0.9, &y, &mut f);
        let d = 1e-5;
        let (mut fp, mut fm) = ([0.0; N], [0.0; N]);
        sys.rhs(mode, 0.9 + d, &std::array::from_fn(|n| y[n] + d * f[n]), &mut fp);
        sys.rhs(mode, 0.9 - d, &std::array::from_fn(|n| y[n] - d * f[n]), &mut fm);
        for n in 0..N {
            let second = (fp[n] - fm[n]) / (4.0 * d);
            assert!(
                (c[2][n] - second).abs() < 1e-8,
                "{mode:?}, component {n}: {} against {second}",
                c[2][n]
            );
        }
    }
}

#[test]
fn every_mode_follows_a_tight_dop853_solve() {
    let sys = system();
    for (mode, y) in cases() {
        let f = ModeField { sys: &sys, mode };
        let tight = Tolerances {
            rtol: 1e-13,
            atol: 1e-15,
            ..Tolerances::default()
        };
        let mut d = Dop853::new(tight);
        d.restart(&f, 0.3, &y);
        while d.t() < 0.8 {
            d.step(&f, 0.8).unwrap();
        }
        for rtol in [1e-6, 1e-10] {
            let mut t = Taylor::new(Tolerances {
                rtol,
                atol: rtol * 1e-2,
                ..Tolerances::default()
            });
            t.restart(&f, 0.3, &y);
            while t.t() < 0.8 {
                t.step(&f, 0.8).unwrap();
            }
            assert_eq!(t.t(), 0.8);
            let err = (0..N).map(|n| (t.y()[n] - d.y()[n]).abs()).fold(0.0, f64::max);
            assert!(err < 100.0 * rtol, "{mode:?} at rtol {rtol}: error {err:e}");
            assert_eq!(t.stats().rejected, 0);
        }
    }
}

#[test]
fn a_periodic_run_with_impacts_agrees_with_dop853() {
    // The paper's Fig. 4 point Ω = 8, A_h = 2, A_v = 0.5, r = 0.925, to τ 200.
    let geo = Geometry::new(1.0, 4.0);
    let exc = common::harmonic(&geo, 2.0, 0.5, 8.0);
    let m = model(
        1.0,
        4.0,
        ImpactLaw::Ratio { r: 0.925 },
        (f64::INFINITY, f64::INFINITY),
        exc,
    );
    let mut o = opts(200.0, 1e-10, None);
    let reference = run(m.clone(), 0.0, 0.0, &o);
    o.method = Method::Taylor;
    let taylor = run(m, 0.0, 0.0, &o);
    assert_eq!(taylor.outcome, reference.outcome);
    assert_eq!(taylor.events.len(), reference.events.len());
    for (a, b) in taylor.events.iter().zip(&reference.events) {
        assert!((a.tau - b.tau).abs() < 1e-8, "event at {} against {}", a.tau, b.tau);
    }
    for (a, b) in taylor.section.iter().zip(&reference.section) {
        assert!((a.theta - b.theta).abs() < 1e-8 && (a.theta_dot - b.theta_dot).abs() < 1e-8);
    }
    // Fewer, longer steps, none rejected.
    assert!(taylor.stats.accepted < reference.stats.accepted);
    assert_eq!(taylor.stats.rejected, 0);
}

#[test]
fn a_pulse_has_no_series_and_is_stepped_by_dop853() {
    let geo = Geometry::new(1.0, 4.0);
    let sys = BlockSystem::new(model(
        1.0,
        4.0,
        ImpactLaw::Housner,
        (f64::INFINITY, f64::INFINITY),
        Excitation::Pulse(rocking::model::excitation::PulsePair {
            horizontal: rocking::model::excitation::Pulse::new(
                rocking::model::excitation::PulseShape::OneSine,
                3.0 * geo.psi,
                4.0,
            )
            .expect("a valid pulse"),
            vertical: None,
        }),
    ));
    let mut c = [[0.0; N]; 21];
    assert!(!sys.taylor(Mode::Rock { pivot: Sign::Pos }, 0.0, &[0.1; N], 20, &mut c));
}
