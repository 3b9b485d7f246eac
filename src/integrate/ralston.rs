//! Ralston's second-order Runge–Kutta method with a fixed step: the method
//! of the 1998 paper this project reproduces, kept to compare against it.
//!
//! References:
//! - A. Ralston, "Runge–Kutta methods with minimum error bounds",
//!   Math. Comp. 16 (1962) 431–437: the 2-stage method with `a21 = 2/3`,
//!   `b = (1/4, 3/4)`, which minimises the bound on the local truncation error
//!   among 2nd-order 2-stage methods.
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I*, 2nd ed., Springer 1993, §II.6: cubic Hermite
//!   interpolation as a continuous extension.
//!
//! Events are not located by root finding but the paper's way: the driver
//! undoes a step that crossed a guard and retries with the step cut by ten
//! ([`Stepper::undo_and_shrink`]), then puts the step back with
//! [`Ralston::reset_step`] after handling the event.

use super::controller::h_min;
use super::stages::{all_finite, combine};
use super::stepper::{Rhs, StepError, StepStats, Stepper, Tolerances, step_ends};

/// Ralston's node and weights.
const A21: f64 = 2.0 / 3.0;
const B1: f64 = 1.0 / 4.0;
const B2: f64 = 3.0 / 4.0;

/// Ralston's 2nd-order method with a fixed step `Tolerances::h_fixed`.
///
/// Two evaluations of `f` per step: the second stage and `f` at the new
/// point, which serves both the Hermite dense output and, first-same-as-last,
/// as the first stage of the next step. No error control: `rtol` and `atol`
/// are ignored; `h_max` still caps the step.
#[derive(Clone, Debug)]
pub struct Ralston<const N: usize> {
    tol: Tolerances,
    /// Current step (`h_fixed`, or less after `undo_and_shrink`).
    h: f64,
    t: f64,
    t_old: f64,
    y: [f64; N],
    y_old: [f64; N],
    /// `f(t, y)`.
    f: [f64; N],
    /// `f(t_old, y_old)`.
    f_old: [f64; N],
    /// Size of the last step (the one dense output covers).
    h_used: f64,
    /// A step has been taken since the last restart or undo.
    has_step: bool,
    /// `restart` has been called at least once.
    started: bool,
    stats: StepStats,
}

impl<const N: usize> Ralston<N> {
    /// A stepper that steps by `tol.h_fixed` (default 0.004, the paper's
    /// normalised sampling time). Call [`Stepper::restart`] before the first
    /// step (a step without it starts from `t = 0`, `y = 0`).
    pub fn new(tol: Tolerances) -> Self {
        Self {
            tol,
            h: tol.h_fixed,
            t: 0.0,
            t_old: 0.0,
            y: [0.0; N],
            y_old: [0.0; N],
            f: [0.0; N],
            f_old: [0.0; N],
            h_used: 0.0,
            has_step: false,
            started: false,
            stats: StepStats::default(),
        }
    }

    /// Puts the step back to `h_fixed` after `undo_and_shrink` cut it; the
    /// driver calls it once the event has been handled.
    pub(crate) fn reset_step(&mut self) {
        self.h = self.tol.h_fixed;
    }

    /// Cubic Hermite interpolation on the last step at `theta`, written like
    /// the first three terms of DOP853's dense output:
    /// `y_old + θ(Δ + (1-θ)(h f_old - Δ + θ(2Δ - h(f_old + f))))`.
    fn interpolate(&self, theta: f64, out: &mut [f64; N]) {
        let h = self.h_used;
        let th1 = 1.0 - theta;
        for (n, o) in out.iter_mut().enumerate() {
            let dy = self.y[n] - self.y_old[n];
            let c1 = h * self.f_old[n] - dy;
            let c2 = 2.0 * dy - h * (self.f_old[n] + self.f[n]);
            *o = self.y_old[n] + theta * (dy + th1 * (c1 + theta * c2));
        }
    }
}

impl<const N: usize> Stepper<N> for Ralston<N> {
    fn name(&self) -> &'static str {
        "ralston"
    }

    /// Starts at `(t, y)` and evaluates `f(t, y)`. Keeps the current step
    /// size; see [`Ralston::reset_step`].
    fn restart<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N]) {
        self.t = t;
        self.t_old = t;
        self.y = *y;
        self.y_old = *y;
        f.eval(t, y, &mut self.f);
        self.stats.rhs_evals += 1;
        self.f_old = self.f;
        self.h_used = 0.0;
        self.has_step = false;
        self.started = true;
    }

    fn step<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        let t = self.t;
        if t_stop.is_nan() || t_stop <= t {
            return Err(StepError::StepSizeUnderflow { t, h: t_stop - t });
        }
        if !self.started {
            let y = self.y;
            self.restart(f, t, &y);
        }
        if !all_finite(&self.f) || !all_finite(&self.y) {
            return Err(StepError::NonFinite { t });
        }
        let h_cap = self.h.min(self.tol.h_max);
        let dist = t_stop - t;
        let (h, clamped) = if h_cap >= dist { (dist, true) } else { (h_cap, false) };
        if !clamped && (h.is_nan() || h < h_min(t)) {
            return Err(StepError::StepSizeUnderflow { t, h });
        }
        let t_new = if clamped { t_stop } else { (t + h).min(t_stop) };

        let mut ys = [0.0; N];
        combine(&self.y, h, &[A21], core::slice::from_ref(&self.f), &mut ys);
        let mut k2 = [0.0; N];
        f.eval(t + A21 * h, &ys, &mut k2);
        let mut y_new = [0.0; N];
        combine(&self.y, h, &[B1, B2], &[self.f, k2], &mut y_new);
        let mut f_new = [0.0; N];
        f.eval(t_new, &y_new, &mut f_new);
        self.stats.rhs_evals += 2;
        if !all_finite(&k2) || !all_finite(&y_new) || !all_finite(&f_new) {
            return Err(StepError::NonFinite { t });
        }
        self.t_old = t;
        self.y_old = self.y;
        self.f_old = self.f;
        self.t = t_new;
        self.y = y_new;
        self.f = f_new;
        self.h_used = h;
        self.has_step = true;
        self.stats.accepted += 1;
        Ok(())
    }

    step_ends!();

    /// Cubic Hermite dense output from `y` and `f` at both ends (3rd-order
    /// interpolation, more than the method's 2nd order needs). Returns the end
    /// states bit for bit at `t_prev()` and `t()`. Never evaluates `f`.
    fn dense<F: Rhs<N>>(&mut self, _f: &F, t: f64, out: &mut [f64; N]) {
        if !self.has_step || t == self.t {
            *out = self.y;
        } else if t == self.t_old {
            *out = self.y_old;
        } else {
            self.interpolate((t - self.t_old) / self.h_used, out);
        }
    }

    fn stats(&self) -> StepStats {
        self.stats
    }

    fn locates_by_root(&self) -> bool {
        false
    }

    /// Restores `(t, y, f)` from before the last step exactly and divides the
    /// step by `factor`; the undone step moves from `accepted` to `rejected`.
    /// With no step to undo (just after a restart or another undo) it only
    /// shrinks the step. Returns `false`, changing nothing, unless `factor` is
    /// finite and positive.
    fn undo_and_shrink(&mut self, factor: f64) -> bool {
        if !(factor.is_finite() && factor > 0.0) {
            return false;
        }
        if self.has_step {
            self.t = self.t_old;
            self.y = self.y_old;
            self.f = self.f_old;
            self.h_used = 0.0;
            self.has_step = false;
            self.stats.accepted = self.stats.accepted.saturating_sub(1);
            self.stats.rejected += 1;
        }
        self.h /= factor;
        true
    }

    /// The step the next `step` will take (before clamping to `t_stop`).
    fn step_size(&self) -> f64 {
        self.h
    }

    /// Same as [`Ralston::reset_step`]: back to `h_fixed`.
    fn reset_step_size(&mut self) {
        self.reset_step();
    }
}

#[cfg(test)]
mod tests {
    use super::super::stepper_checks as checks;
    use super::super::stepper_checks::{cosine, decay, osc, osc_exact, run};
    use super::*;

    fn fixed(h: f64) -> Tolerances {
        Tolerances {
            h_fixed: h,
            ..Tolerances::default()
        }
    }

    #[test]
    fn default_step_is_the_papers() {
        let s = Ralston::<1>::new(Tolerances::default());
        assert_eq!(s.step_size(), 0.004);
        assert!(!s.locates_by_root());
    }

    #[test]
    fn decay_cosine_and_oscillator_match_closed_forms() {
        // Global error of a 2nd-order method at h = 1/256 ~ 0.004: ~1e-5 or
        // less. (A power of two, so that 10 is reached in exactly 2560 steps.)
        let h = 1.0 / 256.0;
        let mut s = Ralston::new(fixed(h));
        let e = run(&mut s, &decay, [1.0], 2.0, |t| [(-t).exp()]);
        assert!(e < 1e-5, "decay: {e:e}");
        let mut s = Ralston::new(fixed(h));
        let e = run(&mut s, &cosine, [0.0], 10.0, |t| [t.sin()]);
        assert!(e < 1e-5, "cosine: {e:e}");
        let mut s = Ralston::new(fixed(h));
        let e = run(&mut s, &osc, [0.0, 1.0], 10.0, osc_exact);
        assert!(e < 1e-4, "oscillator: {e:e}");
        assert_eq!(s.stats().accepted, 2560);
        assert_eq!(s.stats().rhs_evals, 1 + 2 * 2560);
    }

    #[test]
    fn halving_the_step_divides_the_error_by_four() {
        let err = |h: f64| {
            let mut s = Ralston::new(fixed(h));
            s.restart(&osc, 0.0, &[0.0, 1.0]);
            while s.t() < 10.0 {
                s.step(&osc, 10.0).unwrap();
            }
            let ex = osc_exact(10.0);
            (s.y()[0] - ex[0]).hypot(s.y()[1] - ex[1])
        };
        let (e1, e2, e3) = (err(0.02), err(0.01), err(0.005));
        let (r1, r2) = (e1 / e2, e2 / e3);
        eprintln!("ralston oscillator t=10: {e1:e} {e2:e} {e3:e}, ratios {r1:.3} {r2:.3}");
        assert!((3.5..4.5).contains(&r1), "{r1}");
        assert!((3.5..4.5).contains(&r2), "{r2}");
    }

    #[test]
    fn dense_matches_ends_and_is_third_order_locally() {
        let mut s = Ralston::new(fixed(0.1));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        s.step(&osc, 1.0).unwrap();
        s.step(&osc, 1.0).unwrap();
        checks::interpolant_meets_the_ends(&s.y_old, &s.y, |theta, p| s.interpolate(theta, p));
        let y_old = s.y_old;
        checks::dense_returns_the_step_ends(&mut s, &y_old);

        // Local errors over one step from the exact state: end O(h^3),
        // midpoint O(h^3) too (Hermite's own error is O(h^4)).
        let one = |h: f64| {
            let mut s = Ralston::new(fixed(h));
            s.restart(&osc, 0.3, &osc_exact(0.3));
            s.step(&osc, 10.0).unwrap();
            let mut m = [0.0; 2];
            s.dense(&osc, 0.3 + 0.5 * h, &mut m);
            let ex = osc_exact(0.3 + 0.5 * h);
            (m[0] - ex[0]).hypot(m[1] - ex[1])
        };
        let p_mid = (one(0.1) / one(0.05)).log2();
        eprintln!("ralston dense (midpoint, one step) order {p_mid:.2}");
        assert!((2.6..3.6).contains(&p_mid), "{p_mid}");
    }

    #[test]
    fn lands_exactly_on_t_stop() {
        let mut s = Ralston::new(fixed(0.004));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        for &ts in &[0.01, 0.0101, 1.0 / 3.0] {
            while s.t() < ts {
                s.step(&osc, ts).unwrap();
            }
            assert_eq!(s.t(), ts);
        }
        // Clamping does not change the fixed step.
        assert_eq!(s.step_size(), 0.004);
    }

    #[test]
    fn undo_and_shrink_restores_exactly() {
        let mut s = Ralston::new(fixed(0.004));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        for _ in 0..7 {
            s.step(&osc, 1.0).unwrap();
        }
        let (t0, y0) = (s.t(), *s.y());
        s.step(&osc, 1.0).unwrap();
        assert!(s.undo_and_shrink(10.0));
        assert_eq!(s.t(), t0);
        assert_eq!(s.y(), &y0);
        assert_eq!(s.step_size(), 0.004 / 10.0);
        assert_eq!(s.stats().accepted, 7);
        assert_eq!(s.stats().rejected, 1);
        // The retry takes the smaller step and matches a fresh run with it.
        let h = s.step_size();
        s.step(&osc, 1.0).unwrap();
        assert_eq!(s.t(), t0 + h);
        let mut fresh = Ralston::new(fixed(0.004 / 10.0));
        fresh.restart(&osc, t0, &y0);
        fresh.step(&osc, 1.0).unwrap();
        assert_eq!(s.y(), fresh.y());
        s.reset_step();
        assert_eq!(s.step_size(), 0.004);
        // The trait's hook, which the hybrid driver calls, does the same.
        assert!(s.undo_and_shrink(10.0));
        Stepper::reset_step_size(&mut s);
        assert_eq!(s.step_size(), 0.004);
        assert!(!s.undo_and_shrink(0.0));
        assert!(!s.undo_and_shrink(f64::NAN));
    }

    #[test]
    fn restart_discards_fsal() {
        let mut s = Ralston::new(fixed(0.01));
        s.restart(&osc, 0.0, &[0.0, 1.0]);
        s.step(&osc, 1.0).unwrap();
        let g = |_t: f64, _y: &[f64; 2], d: &mut [f64; 2]| *d = [1.0, 2.0];
        s.restart(&g, s.t(), &[5.0, 5.0]);
        s.step(&g, 1.0).unwrap();
        assert!((s.y()[0] - 5.01).abs() < 1e-14);
        assert!((s.y()[1] - 5.02).abs() < 1e-14);
    }

    #[test]
    fn nan_rhs_is_reported() {
        let nan = |_t: f64, _y: &[f64; 1], d: &mut [f64; 1]| d[0] = f64::NAN;
        let mut s = Ralston::new(Tolerances::default());
        s.restart(&nan, 0.0, &[1.0]);
        assert!(matches!(s.step(&nan, 1.0), Err(StepError::NonFinite { .. })));
        let bad = |t: f64, y: &[f64; 1], d: &mut [f64; 1]| {
            d[0] = if t > 0.1 { f64::NAN } else { -y[0] };
        };
        let mut s = Ralston::new(Tolerances::default());
        s.restart(&bad, 0.0, &[1.0]);
        let r = loop {
            if let Err(e) = s.step(&bad, 1.0) {
                break e;
            }
        };
        assert!(matches!(r, StepError::NonFinite { .. }));
    }
}
