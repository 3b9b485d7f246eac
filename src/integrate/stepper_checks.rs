//! The methods' shared test material: problems with closed forms, error
//! measures, and what every adaptive stepper must do, as checks generic
//! over the stepper: each method's tests run them on its own stepper
//! (`mk` builds one from tolerances), so DOPRI5 and DOP853 are held to the
//! same behaviour by one text; [`adaptive_stepper_tests`] writes the tests
//! that run them.

use super::stepper::{Rhs, StepError, Stepper, Tolerances};

/// `y' = -y`, `y(0) = 1`.
pub(crate) fn decay(_t: f64, y: &[f64; 1], d: &mut [f64; 1]) {
    d[0] = -y[0];
}
/// `y' = cos t`, `y(0) = 0`: `y = sin t`.
pub(crate) fn cosine(t: f64, _y: &[f64; 1], d: &mut [f64; 1]) {
    d[0] = t.cos();
}
/// `y1' = y2, y2' = -y1`, `y(0) = (0, 1)`: `y = (sin t, cos t)`.
pub(crate) fn osc(_t: f64, y: &[f64; 2], d: &mut [f64; 2]) {
    d[0] = y[1];
    d[1] = -y[0];
}
pub(crate) fn osc_exact(t: f64) -> [f64; 2] {
    [t.sin(), t.cos()]
}

/// Asserts `|a - b| <= rel * max(|b|, 1)` componentwise.
pub(crate) fn assert_rel_close<const N: usize>(a: &[f64; N], b: &[f64; N], rel: f64) {
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= rel * y.abs().max(1.0), "{a:?} vs {b:?}");
    }
}

/// Largest error over components, normalised by `atol + rtol |y|`.
pub(crate) fn norm_err<const N: usize>(y: &[f64; N], exact: &[f64; N], tol: &Tolerances) -> f64 {
    y.iter()
        .zip(exact)
        .map(|(a, b)| (a - b).abs() / (tol.atol + tol.rtol * b.abs()))
        .fold(0.0, f64::max)
}

/// Largest relative (to max(|exact|, 1)) error at the step ends over
/// `[0, t_end]`, stepping with `t_stop = t_end`.
pub(crate) fn run<const N: usize, S: Stepper<N>, F: Rhs<N>>(
    s: &mut S,
    f: &F,
    y0: [f64; N],
    t_end: f64,
    exact: impl Fn(f64) -> [f64; N],
) -> f64 {
    s.restart(f, 0.0, &y0);
    let mut worst: f64 = 0.0;
    while s.t() < t_end {
        s.step(f, t_end).unwrap();
        let ex = exact(s.t());
        for (a, b) in s.y().iter().zip(&ex) {
            worst = worst.max((a - b).abs() / b.abs().max(1.0));
        }
    }
    assert_eq!(s.t(), t_end, "must land exactly on t_end");
    worst
}

/// One step of size `h` from the exact state at `t0` (forced by `h_max`
/// and `t_stop`, tolerances loose enough to accept it): returns the local
/// error at the end and the dense error at the midpoint.
pub(crate) fn one_step_errors<S: Stepper<2>>(s: &mut S, t0: f64, h: f64) -> (f64, f64) {
    // Warm up so that the step-size estimate reaches h_max = h; restart
    // keeps it.
    s.restart(&osc, -100.0, &osc_exact(-100.0));
    for _ in 0..20 {
        s.step(&osc, 0.0).unwrap();
    }
    assert!(s.step_size() >= h);
    s.restart(&osc, t0, &osc_exact(t0));
    s.step(&osc, t0 + h).unwrap();
    assert_eq!(s.t(), t0 + h);
    let end = osc_exact(t0 + h);
    let e_end = (s.y()[0] - end[0]).hypot(s.y()[1] - end[1]);
    let tm = t0 + 0.5 * h;
    let mut ym = [0.0; 2];
    s.dense(&osc, tm, &mut ym);
    let mid = osc_exact(tm);
    let e_mid = (ym[0] - mid[0]).hypot(ym[1] - mid[1]);
    (e_end, e_mid)
}

/// Observed orders `log2(e(h) / e(h/2))` of the local end error and the
/// midpoint dense error of the stepper `mk` builds, each step forced to
/// its size by `h_max` under tolerances loose enough to accept it.
pub(crate) fn observed_orders<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S, h: f64) -> (f64, f64) {
    let forced = |h| {
        mk(Tolerances {
            rtol: 1.0,
            atol: 1.0,
            h_max: h,
            h_fixed: 0.0,
        })
    };
    let (e1, m1) = one_step_errors(&mut forced(h), 0.3, h);
    let (e2, m2) = one_step_errors(&mut forced(h / 2.0), 0.3, h / 2.0);
    ((e1 / e2).log2(), (m1 / m2).log2())
}

/// Tolerances `rtol`, `atol`, the rest default.
pub(crate) fn tol(rtol: f64, atol: f64) -> Tolerances {
    Tolerances {
        rtol,
        atol,
        ..Tolerances::default()
    }
}

/// Decay, cosine and the oscillator end within a few tolerances of their
/// closed forms (`mk1`, `mk2`: the stepper for one and two components).
pub(crate) fn closed_forms<S1: Stepper<1>, S2: Stepper<2>>(
    mk1: impl Fn(Tolerances) -> S1,
    mk2: impl Fn(Tolerances) -> S2,
) {
    let tl = tol(1e-8, 1e-10);
    let mut s = mk1(tl);
    run(&mut s, &decay, [1.0], 2.0, |t| [(-t).exp()]);
    let e = norm_err(s.y(), &[(-2.0f64).exp()], &tl);
    assert!(e < 10.0, "decay: {e}");

    let mut s = mk1(tl);
    run(&mut s, &cosine, [0.0], 10.0, |t| [t.sin()]);
    let e = norm_err(s.y(), &[10.0f64.sin()], &tl);
    assert!(e < 10.0, "cosine: {e}");

    let mut s = mk2(tl);
    run(&mut s, &osc, [0.0, 1.0], 10.0, osc_exact);
    let e = norm_err(s.y(), &osc_exact(10.0), &tl);
    assert!(e < 100.0, "oscillator: {e}");
}

/// At rtol = atol = 1e-10 the oscillator stays within 1e-8 relative over
/// τ 0–20.
pub(crate) fn tight_tolerance_reaches_1e8_relative_over_20<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) {
    let mut s = mk(tol(1e-10, 1e-10));
    let worst = run(&mut s, &osc, [0.0, 1.0], 20.0, osc_exact);
    assert!(worst < 1e-8, "worst relative error {worst:e}");
}

/// Four decades tighter tolerances give more than three decades smaller
/// errors (`name` labels the printed errors).
pub(crate) fn error_decreases_with_rtol<S: Stepper<2>>(name: &str, mk: impl Fn(Tolerances) -> S) {
    let mut loose = mk(tol(1e-6, 1e-6));
    let e6 = run(&mut loose, &osc, [0.0, 1.0], 20.0, osc_exact);
    let mut tight = mk(tol(1e-10, 1e-10));
    let e10 = run(&mut tight, &osc, [0.0, 1.0], 20.0, osc_exact);
    eprintln!("{name} oscillator 0..20: rtol 1e-6 -> {e6:e}, 1e-10 -> {e10:e}");
    assert!(e6 / e10 > 1e3, "{e6:e} / {e10:e}");
}

/// Steps land exactly on each stop, however close to the last; a stop at
/// or before the current time is a caller bug, refused.
pub(crate) fn lands_exactly_on_t_stop<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) {
    let mut s = mk(tol(1e-8, 1e-8));
    s.restart(&osc, 0.0, &[0.0, 1.0]);
    let stops = [0.1, 0.1 + 1e-13, 1.0 / 3.0, 2.7, 2.7 + f64::EPSILON * 4.0];
    for &ts in &stops {
        while s.t() < ts {
            s.step(&osc, ts).unwrap();
        }
        assert_eq!(s.t(), ts);
    }
    assert!(matches!(s.step(&osc, s.t()), Err(StepError::StepSizeUnderflow { .. })));
    assert!(matches!(
        s.step(&osc, s.t() - 1.0),
        Err(StepError::StepSizeUnderflow { .. })
    ));
}

/// A restart (after a reset map) keeps the step-size estimate, no larger
/// than the last step, and evaluates the new right-hand side afresh.
pub(crate) fn restart_keeps_step_size_and_discards_fsal<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) {
    let mut s = mk(tol(1e-8, 1e-8));
    s.restart(&osc, 0.0, &[0.0, 1.0]);
    // f(t0) + hinit's Euler probe.
    assert_eq!(s.stats().rhs_evals, 2);
    s.step(&osc, 1.0).unwrap();
    let h = s.step_size();
    // The step just taken was not shortened (t = 1 is far), so it is
    // the step the estimate may not exceed after a reset.
    let h_last = s.t() - s.t_prev();
    assert!(h > h_last, "the proposal grew on the smooth oscillator");
    let before = s.stats().rhs_evals;
    // A different right-hand side after the "reset map": y' = (1, 2).
    let g = |_t: f64, _y: &[f64; 2], d: &mut [f64; 2]| *d = [1.0, 2.0];
    s.restart(&g, s.t(), &[5.0, 5.0]);
    assert_eq!(s.stats().rhs_evals, before + 1, "no second hinit");
    assert_eq!(
        s.step_size(),
        h.min(h_last),
        "estimate kept, no larger than the last step"
    );
    let t0 = s.t();
    s.step(&g, t0 + 0.5).unwrap();
    let dt = s.t() - t0;
    // Exact for a constant field only if k[0] was re-evaluated with g.
    assert!((s.y()[0] - (5.0 + dt)).abs() < 1e-13);
    assert!((s.y()[1] - (5.0 + 2.0 * dt)).abs() < 1e-13);
}

/// A NaN from the right-hand side is an error, never a state, and leaves
/// a valid, degenerate dense interval at the last good time.
pub(crate) fn nan_rhs_is_reported<S: Stepper<1>>(mk: impl Fn(Tolerances) -> S) {
    let bad = |t: f64, y: &[f64; 1], d: &mut [f64; 1]| {
        d[0] = if t > 0.5 { f64::NAN } else { -y[0] };
    };
    let mut s = mk(Tolerances::default());
    s.restart(&bad, 0.0, &[1.0]);
    let r = loop {
        match s.step(&bad, 10.0) {
            Ok(()) => assert!(s.t() <= 0.5 + 1.0),
            Err(e) => break e,
        }
    };
    assert!(matches!(r, StepError::NonFinite { .. }), "{r:?}");
    // A failed step leaves a valid, degenerate dense interval at t.
    assert_eq!(s.t_prev(), s.t());
    let mut out = [0.0];
    s.dense(&bad, s.t() - 0.01, &mut out);
    assert_eq!(&out, s.y());

    let nan = |_t: f64, _y: &[f64; 1], d: &mut [f64; 1]| d[0] = f64::NAN;
    let mut s = mk(Tolerances::default());
    s.restart(&nan, 0.0, &[1.0]);
    assert!(matches!(s.step(&nan, 1.0), Err(StepError::NonFinite { .. })));
}

/// The mirrored problem (state and forcing negated) takes the same steps
/// and gives the negated states and dense output, bit for bit.
pub(crate) fn mirrored_state_gives_identical_steps_and_dense<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) {
    let f = |t: f64, y: &[f64; 2], d: &mut [f64; 2]| {
        d[0] = y[1];
        d[1] = -y[0].sin() - 0.1 * y[1] + 0.5 * t.cos();
    };
    let fm = |t: f64, y: &[f64; 2], d: &mut [f64; 2]| {
        d[0] = y[1];
        d[1] = -y[0].sin() - 0.1 * y[1] - 0.5 * t.cos();
    };
    let mut a = mk(Tolerances::default());
    let mut b = mk(Tolerances::default());
    a.restart(&f, 0.0, &[0.3, 0.0]);
    b.restart(&fm, 0.0, &[-0.3, -0.0]);
    let (mut ya, mut yb) = ([0.0; 2], [0.0; 2]);
    for _ in 0..50 {
        a.step(&f, 30.0).unwrap();
        b.step(&fm, 30.0).unwrap();
        assert_eq!(a.t(), b.t());
        assert_eq!(a.y()[0], -b.y()[0]);
        assert_eq!(a.y()[1], -b.y()[1]);
        let tm = 0.3 * a.t_prev() + 0.7 * a.t();
        a.dense(&f, tm, &mut ya);
        b.dense(&fm, tm, &mut yb);
        assert_eq!(ya[0], -yb[0]);
        assert_eq!(ya[1], -yb[1]);
    }
}

/// A step shortened to land on a near stop does not shrink the estimate
/// for the next.
pub(crate) fn clamped_step_keeps_estimate<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) {
    let mut s = mk(tol(1e-8, 1e-8));
    s.restart(&osc, 0.0, &[0.0, 1.0]);
    for _ in 0..5 {
        s.step(&osc, 100.0).unwrap();
    }
    let h = s.step_size();
    let t = s.t();
    s.step(&osc, t + h * 1e-3).unwrap();
    assert_eq!(s.step_size(), h);
}

/// A solution that blows up (y' = y², y(0) = 1: y = 1/(1 − t), singular
/// at t = 1) ends in an error near the singularity, not a hang.
pub(crate) fn blow_up_is_an_error_not_a_hang<S: Stepper<1>>(name: &str, mk: impl Fn(Tolerances) -> S) {
    let f = |_t: f64, y: &[f64; 1], d: &mut [f64; 1]| d[0] = y[0] * y[0];
    let mut s = mk(Tolerances::default());
    s.restart(&f, 0.0, &[1.0]);
    let r = loop {
        if let Err(e) = s.step(&f, 2.0) {
            break e;
        }
    };
    eprintln!("{name} blow-up: {r:?} after {:?}", s.stats());
    assert!(s.t() < 1.1, "{}", s.t());
    assert!(
        matches!(r, StepError::StepSizeUnderflow { .. } | StepError::NonFinite { .. }),
        "{r:?}"
    );
}

/// The stepper `mk` builds at rtol = atol = 1e-6, five steps into the
/// oscillator: a step to look at the dense output of.
pub(crate) fn oscillator_after_five_steps<S: Stepper<2>>(mk: impl Fn(Tolerances) -> S) -> S {
    let mut s = mk(tol(1e-6, 1e-6));
    s.restart(&osc, 0.0, &[0.0, 1.0]);
    for _ in 0..5 {
        s.step(&osc, 20.0).unwrap();
    }
    s
}

/// The dense output of the last step at its ends is its stored end states
/// bit for bit (`y_old`: the state at its start).
pub(crate) fn dense_returns_the_step_ends<S: Stepper<2>>(s: &mut S, y_old: &[f64; 2]) {
    let mut out = [0.0; 2];
    s.dense(&osc, s.t(), &mut out);
    assert_eq!(&out, s.y());
    s.dense(&osc, s.t_prev(), &mut out);
    assert_eq!(&out, y_old);
}

/// The interpolant of the last step itself (`interpolate(θ)`, which the
/// dense output short-cuts at the ends) meets the end states `y_old` and
/// `y` at θ = 0 and θ = 1 to round-off.
pub(crate) fn interpolant_meets_the_ends(y_old: &[f64; 2], y: &[f64; 2], interpolate: impl Fn(f64, &mut [f64; 2])) {
    let mut p = [0.0; 2];
    interpolate(0.0, &mut p);
    assert_rel_close(&p, y_old, 1e-14);
    interpolate(1.0, &mut p);
    assert_rel_close(&p, y, 1e-14);
}

/// Inside the last step of [`oscillator_after_five_steps`], the dense
/// output is as accurate as the step ends: within ten tolerances of the
/// closed form at nine interior points.
pub(crate) fn dense_is_accurate_inside<S: Stepper<2>>(s: &mut S) {
    let mut out = [0.0; 2];
    let (a, b) = (s.t_prev(), s.t());
    for i in 1..10 {
        let t = a + (b - a) * f64::from(i) / 10.0;
        s.dense(&osc, t, &mut out);
        let e = norm_err(&out, &osc_exact(t), &tol(1e-6, 1e-6));
        assert!(e < 10.0, "t = {t}: {e}");
    }
}

/// The tests of the checks above for the stepper type `$ty` (built by
/// `$ty::new` from tolerances), `$name` labelling what they print.
macro_rules! adaptive_stepper_tests {
    ($ty:ident, $name:literal) => {
        #[test]
        fn decay_cosine_and_oscillator_match_closed_forms() {
            $crate::integrate::stepper_checks::closed_forms($ty::new, $ty::new);
        }

        #[test]
        fn tight_tolerance_reaches_1e8_relative_over_20() {
            $crate::integrate::stepper_checks::tight_tolerance_reaches_1e8_relative_over_20($ty::new);
        }

        #[test]
        fn error_decreases_with_rtol() {
            $crate::integrate::stepper_checks::error_decreases_with_rtol($name, $ty::new);
        }

        #[test]
        fn lands_exactly_on_t_stop() {
            $crate::integrate::stepper_checks::lands_exactly_on_t_stop($ty::new);
        }

        #[test]
        fn restart_keeps_step_size_and_discards_fsal() {
            $crate::integrate::stepper_checks::restart_keeps_step_size_and_discards_fsal($ty::new);
        }

        #[test]
        fn nan_rhs_is_reported() {
            $crate::integrate::stepper_checks::nan_rhs_is_reported($ty::new);
        }

        #[test]
        fn mirrored_state_gives_identical_steps_and_dense() {
            $crate::integrate::stepper_checks::mirrored_state_gives_identical_steps_and_dense($ty::new);
        }

        #[test]
        fn clamped_step_keeps_estimate() {
            $crate::integrate::stepper_checks::clamped_step_keeps_estimate($ty::new);
        }

        #[test]
        fn blow_up_is_an_error_not_a_hang() {
            $crate::integrate::stepper_checks::blow_up_is_an_error_not_a_hang($name, $ty::new);
        }
    };
}
pub(crate) use adaptive_stepper_tests;
