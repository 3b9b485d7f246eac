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

/// A shipped record read in its unit, as the engineering commands read it.
fn shipped_record(name: &str, unit: rocking::model::units::AccelUnit) -> rocking::sim::scenario::Record {
    let path = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/")).join(name);
    let spec = rocking::io::record::RecordSpec::stated(unit);
    let loaded = rocking::io::record::read_record_as(&path, &spec).expect("shipped record");
    rocking::sim::scenario::Record {
        path,
        series: loaded.series,
        unit: loaded.unit,
        dt: None,
        crc32: loaded.crc32,
        channel: None,
    }
}

/// Issue 14's spectrum target (< 1 s on 2 cores): the rocking spectrum of
/// 200 block sizes (R = 0.05 … 10 m, B/H = 0.2, no sliding, Housner
/// impact) under El Centro 1940, on rayon's global pool (one thread per
/// core), no history, each run stopped at overturning or at rest.
#[divan::bench(sample_count = 10)]
fn rocking_spectrum_elcentro_200_sizes() {
    use rocking::analysis::engineering::Drive;
    use rocking::analysis::engineering::rocking_spectrum::{SizeAxis, SizeRange, SpectrumSpec, rocking_spectrum};
    let drive = Drive::Record(shipped_record(
        "elcentro-1940-ns.dat",
        rocking::model::units::AccelUnit::G,
    ));
    let base = rocking::sim::Scenario::default();
    let spec = SpectrumSpec {
        base: &base,
        drive: &drive,
        scale: 1.0,
        sizes: SizeRange::new(SizeAxis::HalfDiagonal, 0.05, 10.0, 200).expect("range"),
        b_over_h: vec![0.2],
        overturn: None,
    };
    black_box(rocking_spectrum(&spec, &rocking::analysis::silent).expect("runs"));
}

/// Issue 14's fragility target (< 2 s on 2 cores): El Centro 1940 and Kobe
/// 1995 scaled to 40 PGA levels (0.05 … 2 g) on 3 blocks (0.6 × 2.0,
/// 0.4 × 1.6, 1 × 3 m): 240 runs, then both lognormal fits per block.
#[divan::bench(sample_count = 10)]
fn fragility_2_records_40_levels_3_blocks() {
    use rocking::analysis::engineering::fragility::{FragilitySpec, SuiteRecord, fit_block, run_fragility, summarise};
    use rocking::analysis::engineering::{BlockSize, Drive};
    use rocking::model::units::AccelUnit;
    let records: Vec<SuiteRecord> = [
        ("elcentro-1940-ns.dat", AccelUnit::G),
        ("kobe-1995.dat", AccelUnit::MetresPerSecond2),
    ]
    .into_iter()
    .map(|(name, unit)| {
        let record = shipped_record(name, unit);
        let intensity = record.series.peaks(1.0).pga_g;
        SuiteRecord {
            drive: Drive::Record(record),
            intensity,
        }
    })
    .collect();
    let levels: Vec<f64> = (1..=40).map(|i| 0.05 * f64::from(i)).collect();
    let blocks = [(0.6, 2.0), (0.4, 1.6), (1.0, 3.0)].map(|(width_m, height_m)| BlockSize { width_m, height_m });
    let base = rocking::sim::Scenario::default();
    let spec = FragilitySpec {
        base: &base,
        records: &records,
        levels: &levels,
        blocks: &blocks,
        im: rocking::analysis::engineering::fragility::Intensity::Pga,
    };
    let indices: Vec<usize> = (0..spec.run_count()).collect();
    let runs = run_fragility(&spec, &indices, &rocking::analysis::silent).expect("runs");
    let counts = summarise(
        blocks.len(),
        levels.len(),
        0.5,
        runs.iter()
            .map(|r| (r.at.block, r.at.level, r.response.end, r.response.peak_theta_over_alpha)),
    );
    for c in &counts {
        black_box(fit_block(&levels, c));
    }
}

/// The periodic sweep point of [`periodic_sweep_point`] with the Taylor
/// method (order 28 at rtol 1e-10): the Taylor series' share of a run.
#[divan::bench(sample_count = 20)]
fn periodic_sweep_point_taylor() {
    let s = scene("periodic");
    let opts = RunOptions {
        tau_end: s.tau_end,
        method: Method::Taylor,
        tol: tolerances(),
        output_dt: None,
        section: true,
        rest_after: None,
        limits: Limits::default(),
    };
    black_box(simulate(s.model.clone(), &s.initial, &opts).expect("runs"));
}

/// The tangent Lyapunov spectrum (variational equations, saltation
/// matrices, QR) over τ 0–300 with 50 τ of transient: the Jacobians'
/// share of a run. `chaotic` rocks about stuck pivots, `sliding`
/// slide-rocks.
#[divan::bench(args = ["chaotic", "sliding"], sample_count = 10)]
fn lyapunov_tangent(name: &str) {
    use rocking::analysis::lyapunov::{LyapunovOptions, Method as LyapunovMethod, lyapunov};
    let s = scene(name);
    let opts = LyapunovOptions {
        method: LyapunovMethod::Tangent,
        transient_tau: 50.0,
        total_tau: 300.0,
        batches: 4,
        ..LyapunovOptions::default()
    };
    black_box(lyapunov(&s.model, &s.initial, &opts).expect("runs"));
}

/// [`taylor_series`] generated from the vector field over jets
/// (`model::series::generated`): the hand-written expansion's speed
/// against the one the equations give by themselves.
#[divan::bench(args = ["rock", "slide_rock"])]
fn taylor_series_generated(bencher: divan::Bencher, mode: &str) {
    let cfg = rocking::io::config::load(Some("default"), None, &[]).expect("default preset");
    let model = cfg.model().expect("model");
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
        assert!(rocking::model::series::generated::taylor(
            &model,
            mode,
            black_box(t),
            black_box(&y),
            order,
            &mut c
        ));
        black_box(&c);
    });
}

fn tangent_mode(mode: &str) -> Mode {
    match mode {
        "rock" => Mode::Rock { pivot: Sign::Pos },
        _ => Mode::SlideRock {
            pivot: Sign::Pos,
            slip: Sign::Neg,
        },
    }
}

/// The Jacobian of the vector field as the Lyapunov run calls it (the
/// hand-written partials of `model::variational`), forcing included.
#[divan::bench(args = ["rock", "slide_rock"])]
fn jacobian_hand(bencher: divan::Bencher, mode: &str) {
    use rocking::analysis::lyapunov::TangentSystem as _;
    let (sys, _, y) = rocking_state();
    let mode = tangent_mode(mode);
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        black_box(sys.jacobian(mode, black_box(t), black_box(&y)));
    });
}

/// [`jacobian_hand`] generated by dual numbers over the vector field
/// (`model::variational::generated`).
#[divan::bench(args = ["rock", "slide_rock"])]
fn jacobian_generated(bencher: divan::Bencher, mode: &str) {
    let (sys, _, y) = rocking_state();
    let mode = tangent_mode(mode);
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        let fo = sys.model.excitation.forcing(black_box(t));
        black_box(rocking::model::variational::generated::field_jacobian(
            &sys.model,
            mode,
            fo,
            black_box(&y),
        ));
    });
}

/// The gradient of rocking's normal-force guard (index 2), as the
/// saltation matrix needs it at every event: the hand-written partials of
/// `model::variational`, or dual numbers over the guards
/// (`model::variational::generated`).
#[divan::bench(args = ["hand", "generated"])]
fn guard_gradient(bencher: divan::Bencher, form: &str) {
    use rocking::model::variational;
    let (sys, mode, y) = rocking_state();
    let mut t = 0.0;
    bencher.bench_local(|| {
        t += 1e-3;
        let t = black_box(t);
        let fo = sys.model.excitation.forcing(t);
        let rate = rocking::model::dynamics::Forcing {
            a: 0.1 * t.cos(),
            av: 0.05 * t.cos(),
        };
        let g = if form == "hand" {
            variational::guard_gradient(&sys.model, mode, 2, fo, rate, black_box(&y))
        } else {
            variational::generated::guard_gradient(&sys.model, mode, 2, fo, rate, black_box(&y))
        };
        black_box(g);
    });
}
