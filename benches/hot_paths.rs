//! `cargo bench`: the hot paths of a sweep point, timed by divan.
//!
//! The work–precision study of whole methods is `rocking bench`; this file
//! times the pieces it is made of, so a change to one of them shows up as a
//! number: one periodic sweep point (issue 5's < 10 ms target), the
//! right-hand side, one DOP853 step with and without dense output, and the
//! guard evaluation the event detection calls after every step.

use std::hint::black_box;

use rocking::bench::scenes;
use rocking::integrate::hybrid::{HybridSystem, Limits, MAX_GUARDS};
use rocking::integrate::{Dop853, Stepper, Tolerances};
use rocking::model::system::N;
use rocking::model::{BlockSystem, Mode, Sign};
use rocking::sim::{Method, RunOptions, simulate};

fn main() {
    divan::main();
}

fn tolerances() -> Tolerances {
    Tolerances {
        rtol: 1e-10,
        atol: 1e-12,
        h_max: f64::INFINITY,
        h_fixed: 0.004,
    }
}

fn scene(name: &str) -> rocking::bench::Scene {
    scenes().into_iter().find(|s| s.name == name).expect("scene exists")
}

/// One sweep point of the paper: the periodic scene (Ω = 8, A_h = 2,
/// A_v = 0.5, r = 0.925), τ 0–800, rtol 1e-10, section only, no history.
#[divan::bench(sample_count = 20)]
fn periodic_sweep_point() {
    let s = scene("periodic");
    let opts = RunOptions {
        tau_end: s.tau_end,
        method: Method::Dop853,
        tol: tolerances(),
        output_dt: None,
        section: true,
        rest_after: None,
        limits: Limits::default(),
    };
    black_box(simulate(s.model.clone(), &s.initial, &opts).expect("runs"));
}

/// The chaotic scene over τ 0–15 with a history every 0.02 (what the GUI
/// and `--batch` keep).
#[divan::bench(sample_count = 20)]
fn chaotic_with_history() {
    let s = scene("chaotic");
    let opts = RunOptions {
        tau_end: s.tau_end,
        method: Method::Dop853,
        tol: tolerances(),
        output_dt: Some(0.02),
        section: true,
        rest_after: None,
        limits: Limits::default(),
    };
    black_box(simulate(s.model.clone(), &s.initial, &opts).expect("runs"));
}

fn rocking_state() -> (BlockSystem, Mode, [f64; N]) {
    let s = scene("periodic");
    let sys = BlockSystem::new(s.model);
    (sys, Mode::Rock { pivot: Sign::Pos }, [0.3, -0.7, 0.0, 0.0, 0.0, 0.0])
}

/// The vector field of the rocking mode (with the harmonic forcing).
#[divan::bench]
fn rhs_rock(bencher: divan::Bencher) {
    let (sys, mode, y) = rocking_state();
    let mut dy = [0.0; N];
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        sys.rhs(mode, black_box(t), black_box(&y), &mut dy);
        black_box(dy);
    });
}

/// All guards of the rocking mode at one state.
#[divan::bench]
fn guards_rock(bencher: divan::Bencher) {
    let (sys, mode, y) = rocking_state();
    let mut g = [0.0; MAX_GUARDS];
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        black_box(sys.guards(mode, black_box(t), black_box(&y), &mut g));
    });
}

/// One accepted DOP853 step of the rocking mode, and the same step followed
/// by one dense-output evaluation (which costs three more right-hand sides
/// the first time in a step).
#[divan::bench(args = [false, true])]
fn dop853_step(bencher: divan::Bencher, with_dense: bool) {
    let (sys, mode, y0) = rocking_state();
    let f = |t: f64, y: &[f64; N], dy: &mut [f64; N]| sys.rhs(mode, t, y, dy);
    let mut stepper = Dop853::<N>::new(tolerances());
    stepper.restart(&f, 0.0, &y0);
    // Settle the step size first, so each sample is a typical step.
    for _ in 0..5 {
        stepper.step(&f, 1e9).expect("steps");
    }
    let mut out = [0.0; N];
    bencher.bench_local(|| {
        let t0 = stepper.t();
        if t0 > 0.5 {
            stepper.restart(&f, 0.0, &y0);
        }
        stepper.step(&f, 1e9).expect("steps");
        if with_dense {
            let tm = 0.5 * (stepper.t_prev() + stepper.t());
            stepper.dense(&f, tm, &mut out);
            black_box(out);
        }
    });
}

/// The harmonic forcing at one time (one sine: Ω_v = Ω_h).
#[divan::bench]
fn forcing_harmonic(bencher: divan::Bencher) {
    let (sys, _, _) = rocking_state();
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 0.0137;
        if t > 800.0 {
            t = 0.0;
        }
        black_box(sys.model.excitation.forcing(black_box(t)));
    });
}

/// The tilt (sin and cos of the angle of the diagonal to the base).
#[divan::bench]
fn tilt(bencher: divan::Bencher) {
    let (sys, _, _) = rocking_state();
    let mut theta = 0.0;
    bencher.bench_local(|| {
        theta += 0.0137;
        if theta > 1.0 {
            theta = -1.0;
        }
        black_box(rocking::model::dynamics::Tilt::new(
            &sys.model.geo,
            Sign::Pos,
            black_box(theta),
        ));
    });
}

/// The Taylor coefficients of one step at rtol 1e-10 (order 28), rocking
/// and slide-rocking, under the default scene's forcing (Ω_v = Ω_h, one
/// phase): the Taylor method's cost per step.
#[divan::bench(args = ["rock", "slide_rock"])]
fn taylor_series(bencher: divan::Bencher, mode: &str) {
    let cfg = rocking::io::config::load(Some("default"), None, &[]).expect("default preset");
    let sys = BlockSystem::new(cfg.model().expect("model"));
    let mode = match mode {
        "rock" => Mode::Rock { pivot: Sign::Pos },
        _ => Mode::SlideRock {
            pivot: Sign::Pos,
            slip: Sign::Neg,
        },
    };
    let y = [0.05, -0.2, 0.0, 0.01, 0.0, 0.0];
    let order = rocking::integrate::taylor::order_for(1e-10);
    let mut c = vec![[0.0; N]; order + 1];
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        assert!(sys.taylor(mode, black_box(t), black_box(&y), order, &mut c));
        black_box(&c);
    });
}
