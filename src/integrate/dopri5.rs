//! Dormand–Prince 5(4) with first-same-as-last, Shampine's 4th-order dense
//! output and Hairer's PI step-size controller.
//!
//! References:
//! - J. R. Dormand, P. J. Prince, "A family of embedded Runge–Kutta formulae",
//!   J. Comput. Appl. Math. 6 (1980) 19–26 (the tableau).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I*, 2nd ed., Springer 1993: §II.4 (error norm and initial step,
//!   the `HINIT` routine), §II.5 (tableau 5.2), §II.6 (dense output), and the
//!   code `dopri5.f` (controller with Lund stabilisation, `beta = 0.04`).
//! - scipy `integrate/_ivp/rk.py` (`RK45`), used as a cross-check.
//!
//! This file holds what is DOPRI5's own: the tableau, an attempt and the
//! continuous extension. The step loop, restarts and FSAL bookkeeping are
//! [`EmbeddedRk`]'s, the controller is in [`super::controller`]; both are
//! shared with [`super::dop853`], Hairer's other code with the same logic.

use super::controller::err_scale;
use super::embedded::{EmbeddedRk, Pair};
use super::stages::{all_finite, combine};
use super::stepper::{Rhs, StepError};

// ---------------------------------------------------------------------------
// The DOPRI5 tableau (Hairer–Nørsett–Wanner table II.5.2).
// ---------------------------------------------------------------------------

const STAGES: usize = 7;
const C: [f64; STAGES] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; STAGES - 1]; STAGES] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    // 5th-order weights b_j: the last row is the solution (FSAL).
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Error weights `b_j - b̂_j` (5th minus 4th order), Hairer's `E1..E7`.
const E: [f64; STAGES] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Shampine's dense-output coefficients (Hairer's `D1..D7`, `D2 = 0`).
const D: [f64; STAGES] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Dormand–Prince 5(4) stepper (Hairer's DOPRI5).
///
/// Adaptive, 5th order with a 4th-order embedded error estimate, 6 evaluations
/// of `f` per attempted step thanks to FSAL, and a 4th-order continuous
/// extension that costs nothing extra. Controller as in `dopri5.f`:
/// safety 0.9, step ratio in [0.2, 10], Lund stabilisation `beta = 0.04`.
/// The stage slots hold `k[0] = f(t_old, y_old)` and `k[6] = f(t, y)` once
/// a step has been taken.
pub type Dopri5<const N: usize> = EmbeddedRk<Dopri5Pair, N, STAGES>;

/// The DOPRI5 pair, for [`EmbeddedRk`].
#[derive(Clone, Copy, Debug)]
pub struct Dopri5Pair;

impl<const N: usize> Pair<N, STAGES> for Dopri5Pair {
    const NAME: &'static str = "dopri5";
    const ORDER: i32 = 5;
    // The last stage is `f(t + h, y_new)` (its row of `A` is the solution).
    const FSAL: usize = STAGES - 1;
    const FSAL_AFTER_TEST: bool = false;
    const RETRY_NON_FINITE: bool = false;
    // Hairer's defaults: SAFE = 0.9, FAC1 = 0.2, FAC2 = 10, BETA = 0.04,
    // EXPO1 = 0.2 - BETA * 0.75.
    const CONTROL: [f64; 5] = [0.9, 0.2, 10.0, 0.04, 0.2 - 0.04 * 0.75];

    /// The continuous extension needs the stages only.
    type Dense = ();

    fn new_dense() {}

    /// Fills `k[1..7]` and `y_new`, returns the error norm.
    fn attempt<F: Rhs<N>>(
        rk: &mut Dopri5<N>,
        f: &F,
        h: f64,
        t_new: f64,
        y_new: &mut [f64; N],
    ) -> Result<f64, StepError> {
        let t = rk.t;
        let mut ys = [0.0; N];
        for i in 1..STAGES {
            combine(&rk.y, h, &A[i][..i], &rk.k[..i], &mut ys);
            if !all_finite(&ys) {
                return Err(StepError::NonFinite { t });
            }
            // Stages with c = 1 use the exact end time, so that the FSAL
            // stage is f at the time the step reports.
            let ti = if C[i] == 1.0 { t_new } else { t + C[i] * h };
            rk.eval(f, ti, &ys, i);
            if !all_finite(&rk.k[i]) {
                return Err(StepError::NonFinite { t });
            }
        }
        *y_new = ys;
        let mut sum = 0.0;
        for n in 0..N {
            let mut e = 0.0;
            for (ej, kj) in E.iter().zip(&rk.k) {
                if *ej != 0.0 {
                    e += ej * kj[n];
                }
            }
            let sk = err_scale(&rk.tol, rk.y[n], y_new[n]);
            sum += (h * e / sk).powi(2);
        }
        Ok((sum / N.max(1) as f64).sqrt())
    }

    /// 4th-order dense output (Shampine 1986, Hairer's `CONTD5`). Never
    /// evaluates `f`.
    #[inline]
    fn dense_inside<F: Rhs<N>>(rk: &mut Dopri5<N>, _f: &F, theta: f64, out: &mut [f64; N], count: usize) {
        rk.interpolate_leading(theta, out, count);
    }
}

impl<const N: usize> Dopri5<N> {
    /// The continuous extension at `theta = (t - t_old) / h` in Hairer's
    /// form (`CONTD5`): `y_old + θ(Δ + (1-θ)(r3 + θ(r4 + (1-θ) r5)))`.
    /// (The stepper interpolates the leading components it is asked for;
    /// the tests look at the whole polynomial.)
    #[cfg(test)]
    fn interpolate(&self, theta: f64, out: &mut [f64; N]) {
        self.interpolate_leading(theta, out, N);
    }

    /// The continuous extension for the leading `count` components (the
    /// rest of `out` is left as it was).
    fn interpolate_leading(&self, theta: f64, out: &mut [f64; N], count: usize) {
        let h = self.h_used;
        let th1 = 1.0 - theta;
        let (k0, k6) = (&self.k[0], &self.k[STAGES - 1]);
        for n in 0..count.min(N) {
            let ydiff = self.y[n] - self.y_old[n];
            let bspl = h * k0[n] - ydiff;
            let r4 = ydiff - h * k6[n] - bspl;
            let mut d = 0.0;
            for (dj, kj) in D.iter().zip(&self.k) {
                if *dj != 0.0 {
                    d += dj * kj[n];
                }
            }
            let r5 = h * d;
            out[n] = self.y_old[n] + theta * (ydiff + th1 * (bspl + theta * (r4 + th1 * r5)));
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    //! Test problems shared with the other methods' tests.

    use super::super::stepper::{Stepper, Tolerances};
    use super::*;

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

    fn tol(rtol: f64, atol: f64) -> Tolerances {
        Tolerances {
            rtol,
            atol,
            ..Tolerances::default()
        }
    }

    #[test]
    fn decay_cosine_and_oscillator_match_closed_forms() {
        let tl = tol(1e-8, 1e-10);
        let mut s = Dopri5::new(tl);
        s.restart(&decay, 0.0, &[1.0]);
        s.step(&decay, 2.0).unwrap();
        while s.t() < 2.0 {
            s.step(&decay, 2.0).unwrap();
        }
        let e = norm_err(s.y(), &[(-2.0f64).exp()], &tl);
        assert!(e < 10.0, "decay: {e}");

        let mut s = Dopri5::new(tl);
        run(&mut s, &cosine, [0.0], 10.0, |t| [t.sin()]);
        let e = norm_err(s.y(), &[10.0f64.sin()], &tl);
        assert!(e < 10.0, "cosine: {e}");

        let mut s = Dopri5::new(tl);
        run(&mut s, &osc, [0.0, 1.0], 10.0, osc_exact);
        let e = norm_err(s.y(), &osc_exact(10.0), &tl);
        assert!(e < 100.0, "oscillator: {e}");
    }

    #[test]
    fn tight_tolerance_reaches_1e8_relative_over_20() {
        let mut s = Dopri5::new(tol(1e-10, 1e-10));
        let worst = run(&mut s, &osc, [0.0, 1.0], 20.0, osc_exact);
        assert!(worst < 1e-8, "worst relative error {worst:e}");
    }

    #[test]
    fn error_decreases_with_rtol() {
        let mut loose = Dopri5::new(tol(1e-6, 1e-6));
        let e6 = run(&mut loose, &osc, [0.0, 1.0], 20.0, osc_exact);
        let mut tight = Dopri5::new(tol(1e-10, 1e-10));
        let e10 = run(&mut tight, &osc, [0.0, 1.0], 20.0, osc_exact);
        eprintln!("dopri5 oscillator 0..20: rtol 1e-6 -> {e6:e}, 1e-10 -> {e10:e}");
        assert!(e6 / e10 > 1e3, "{e6:e} / {e10:e}");
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
    /// midpoint dense error.
    pub(crate) fn observed_orders<S: Stepper<2>>(mk: impl Fn(f64) -> S, h: f64) -> (f64, f64) {
        let (e1, m1) = one_step_errors(&mut mk(h), 0.3, h);
        let (e2, m2) = one_step_errors(&mut mk(h / 2.0), 0.3, h / 2.0);
        ((e1 / e2).log2(), (m1 / m2).log2())
    }

    #[test]
    fn local_and_dense_orders() {
        let mk = |h| {
            Dopri5::new(Tolerances {
                rtol: 1.0,
                atol: 1.0,
                h_max: h,
                h_fixed: 0.0,
            })
        };
        let (p_end, p_mid) = observed_orders(mk, 0.2);
        eprintln!("dopri5 local order {p_end:.2}, dense order {p_mid:.2}");
        // Local error O(h^6) for a 5th-order method, O(h^5) for the
        // 4th-order interpolant.
        assert!((5.5..6.6).contains(&p_end), "end {p_end}");
        assert!((4.5..5.6).contains(&p_mid), "mid {p_mid}");
    }

    #[test]
    fn dense_matches_step_ends_and_closed_form() {
        let mut s = Dopri5::new(tol(1e-6, 1e-6));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        for _ in 0..5 {
            s.step(&osc, 20.0).unwrap();
        }
        // The polynomial itself at θ = 0 and θ = 1 (dense() short-cuts there).
        let mut p = [0.0; 2];
        s.interpolate(0.0, &mut p);
        assert_rel_close(&p, &s.y_old, 1e-14);
        s.interpolate(1.0, &mut p);
        assert_rel_close(&p, &s.y, 1e-14);
        let mut out = [0.0; 2];
        s.dense(&osc, s.t(), &mut out);
        assert_eq!(&out, s.y());
        s.dense(&osc, s.t_prev(), &mut out);
        assert_eq!(out, s.y_old);
        // Interior points: as accurate as the step ends (loose tolerance).
        let (a, b) = (s.t_prev(), s.t());
        for i in 1..10 {
            let t = a + (b - a) * f64::from(i) / 10.0;
            s.dense(&osc, t, &mut out);
            let e = norm_err(&out, &osc_exact(t), &tol(1e-6, 1e-6));
            assert!(e < 10.0, "t = {t}: {e}");
        }
    }

    #[test]
    fn lands_exactly_on_t_stop() {
        let mut s = Dopri5::new(tol(1e-8, 1e-8));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        let stops = [0.1, 0.1 + 1e-13, 1.0 / 3.0, 2.7, 2.7 + f64::EPSILON * 4.0];
        for &ts in &stops {
            while s.t() < ts {
                s.step(&osc, ts).unwrap();
            }
            assert_eq!(s.t(), ts);
        }
        // A stop at or before t is a caller bug.
        assert!(matches!(s.step(&osc, s.t()), Err(StepError::StepSizeUnderflow { .. })));
    }

    #[test]
    fn restart_keeps_step_size_and_discards_fsal() {
        let mut s = Dopri5::new(tol(1e-8, 1e-8));
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

    #[test]
    fn nan_rhs_is_reported() {
        let bad = |t: f64, y: &[f64; 1], d: &mut [f64; 1]| {
            d[0] = if t > 0.5 { f64::NAN } else { -y[0] };
        };
        let mut s = Dopri5::new(Tolerances::default());
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
        let mut s = Dopri5::new(Tolerances::default());
        s.restart(&nan, 0.0, &[1.0]);
        assert!(matches!(s.step(&nan, 1.0), Err(StepError::NonFinite { .. })));
    }

    #[test]
    fn mirrored_state_gives_identical_steps() {
        let f = |t: f64, y: &[f64; 2], d: &mut [f64; 2]| {
            d[0] = y[1];
            d[1] = -y[0].sin() - 0.1 * y[1] + 0.5 * t.cos();
        };
        let fm = |t: f64, y: &[f64; 2], d: &mut [f64; 2]| {
            d[0] = y[1];
            d[1] = -y[0].sin() - 0.1 * y[1] - 0.5 * t.cos();
        };
        let mut a = Dopri5::new(Tolerances::default());
        let mut b = Dopri5::new(Tolerances::default());
        a.restart(&f, 0.0, &[0.3, 0.0]);
        b.restart(&fm, 0.0, &[-0.3, -0.0]);
        for _ in 0..50 {
            a.step(&f, 30.0).unwrap();
            b.step(&fm, 30.0).unwrap();
            assert_eq!(a.t(), b.t());
            assert_eq!(a.y()[0], -b.y()[0]);
            assert_eq!(a.y()[1], -b.y()[1]);
        }
    }

    #[test]
    fn clamped_step_keeps_estimate() {
        let mut s = Dopri5::new(tol(1e-8, 1e-8));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        for _ in 0..5 {
            s.step(&osc, 100.0).unwrap();
        }
        let h = s.step_size();
        let t = s.t();
        s.step(&osc, t + h * 1e-3).unwrap();
        assert_eq!(s.step_size(), h);
    }

    #[test]
    fn blow_up_is_an_error_not_a_hang() {
        // y' = y^2, y(0) = 1: y = 1 / (1 - t), singular at t = 1.
        let f = |_t: f64, y: &[f64; 1], d: &mut [f64; 1]| d[0] = y[0] * y[0];
        let mut s = Dopri5::new(Tolerances::default());
        s.restart(&f, 0.0, &[1.0]);
        let r = loop {
            if let Err(e) = s.step(&f, 2.0) {
                break e;
            }
        };
        eprintln!("dopri5 blow-up: {r:?} after {:?}", s.stats());
        assert!(s.t() < 1.1, "{}", s.t());
        assert!(
            matches!(r, StepError::StepSizeUnderflow { .. } | StepError::NonFinite { .. }),
            "{r:?}"
        );
    }
}
