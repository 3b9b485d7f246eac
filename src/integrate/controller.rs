//! Hairer's step-size control, shared by the embedded Runge–Kutta pairs
//! ([`Dopri5`](super::Dopri5), [`Dop853`](super::Dop853)): the PI controller
//! with Lund stabilisation, the initial step heuristic `HINIT`, the error
//! scale and the limits on a step.
//!
//! References:
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I*, 2nd ed., Springer 1993: §II.4 (error norm and initial
//!   step, the `HINIT` routine) and the codes `dopri5.f` and `dop853.f`
//!   (the controller; their parameters differ, the logic does not).
//! - K. Gustafsson, "Control theoretic techniques for stepsize selection in
//!   explicit Runge–Kutta methods", ACM TOMS 17 (1991) 533–554 (the PI
//!   part).
//!
//! Both methods are Hairer's codes with different tableaux: one copy of the
//! control keeps them from drifting apart.

use super::stages::all_finite;
use super::stepper::{Rhs, Tolerances};

/// Rejections in a row after which a step gives up. The controller shrinks
/// by at least `fac_min` per rejection, so 100 rejections mean a factor of
/// at least 1e-48 (DOP853) or 1e-70 (DOPRI5): the step underflowed in all but
/// name, or the error norm is NaN.
pub(super) const MAX_REJECTIONS: u32 = 100;

/// First step when `hinit` could not estimate one (its Euler probe met a
/// non-finite derivative): Hairer's own fallback in `HINIT`. The controller
/// grows it by up to `fac_max` per step.
pub(super) const H_FALLBACK: f64 = 1e-6;

/// Smallest step allowed at time `t`: 16 ulps of `max(|t|, 1)`, below which
/// `t + h` can no longer represent the stage times.
pub(super) fn h_min(t: f64) -> f64 {
    16.0 * f64::EPSILON * t.abs().max(1.0)
}

/// Error scale of one component, `atol + rtol * max(|y_old|, |y_new|)`
/// (Hairer). Only absolute values enter, so negating components of the state
/// leaves every step size bit-identical.
#[inline]
pub(super) fn err_scale(tol: &Tolerances, y_old: f64, y_new: f64) -> f64 {
    tol.atol + tol.rtol * y_old.abs().max(y_new.abs())
}

/// Hairer's initial step-size heuristic (`HINIT` in `dopri5.f`/`dop853.f`;
/// Hairer–Nørsett–Wanner §II.4): take `h0 = 0.01 ||y|| / ||f||`, estimate the
/// second derivative with one explicit Euler step, and choose `h` such that
/// `h^order * max(||f||, ||y''||) = 0.01`. Costs one evaluation of `f`.
///
/// Returns `None` when `f0` or the trial derivative is not finite, so the
/// caller does not store a meaningless estimate (the step then reports
/// [`StepError::NonFinite`](super::StepError::NonFinite)).
pub(super) fn hinit<const N: usize, F: Rhs<N>>(
    f: &F,
    t: f64,
    y: &[f64; N],
    f0: &[f64; N],
    order: i32,
    tol: &Tolerances,
    rhs_evals: &mut u64,
) -> Option<f64> {
    if !all_finite(f0) {
        return None;
    }
    // Hairer uses plain sums of squares here (no division by N).
    let mut dnf = 0.0;
    let mut dny = 0.0;
    for n in 0..N {
        let sk = tol.atol + tol.rtol * y[n].abs();
        dnf += (f0[n] / sk).powi(2);
        dny += (y[n] / sk).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(tol.h_max);

    let mut y1 = [0.0; N];
    for n in 0..N {
        y1[n] = y[n] + h * f0[n];
    }
    let mut f1 = [0.0; N];
    f.eval(t + h, &y1, &mut f1);
    *rhs_evals += 1;
    if !all_finite(&f1) {
        return None;
    }
    let mut der2 = 0.0;
    for n in 0..N {
        let sk = tol.atol + tol.rtol * y[n].abs();
        der2 += ((f1[n] - f0[n]) / sk).powi(2);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / f64::from(order))
    };
    let h = (100.0 * h).min(h1).min(tol.h_max);
    (h.is_finite() && h > 0.0).then_some(h)
}

/// Outcome of one error test.
#[derive(Clone, Copy, Debug)]
pub(super) struct Decision {
    /// The step passed the error test (`err <= 1`).
    pub(super) accept: bool,
    /// Next step size (after acceptance) or retry step size (after
    /// rejection), clipped by `fac_min`/`fac_max` but not by `h_max`.
    pub(super) h_new: f64,
}

/// Hairer's step-size controller (`dopri5.f`, `dop853.f`): a PI controller
/// ("Lund stabilisation", Gustafsson 1991) with
/// `h_new = h / clamp(err^expo / facold^beta / safety, 1/fac_max, 1/fac_min)`,
/// and after a rejection a pure I step that never grows `h`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Controller {
    safety: f64,
    fac_min: f64,
    fac_max: f64,
    beta: f64,
    /// Exponent of the I part, `1/q - beta * 0.75` (DOPRI5, q = 5) or
    /// `1/8 - beta * 0.2` (DOP853), as in Hairer's codes.
    expo: f64,
    /// Error of the last accepted step, floored at 1e-4 (Hairer's `FACOLD`).
    facold: f64,
}

impl Controller {
    /// The smallest step ratio a rejection can ask for (Hairer's `FAC1`).
    pub(super) fn fac_min(&self) -> f64 {
        self.fac_min
    }

    /// A controller with Hairer's parameter names.
    pub(super) const fn new(safety: f64, fac_min: f64, fac_max: f64, beta: f64, expo: f64) -> Self {
        Self {
            safety,
            fac_min,
            fac_max,
            beta,
            expo,
            facold: 1e-4,
        }
    }

    /// Forgets the error history, as at the start of an integration.
    pub(super) fn reset(&mut self) {
        self.facold = 1e-4;
    }

    /// Error test of a step of size `h` with error norm `err`.
    /// `after_reject` limits growth after a rejected attempt (Hairer's
    /// `REJECT` flag).
    pub(super) fn decide(&mut self, err: f64, h: f64, after_reject: bool) -> Decision {
        // `powf` was 3% of a sweep point; DOP853's exponent 1/8 and β = 0
        // have exact cheaper forms (three square roots, and 1).
        let fac11 = if self.expo == 0.125 {
            err.sqrt().sqrt().sqrt()
        } else {
            err.powf(self.expo)
        };
        if err <= 1.0 {
            let pi_part = if self.beta == 0.0 {
                1.0
            } else {
                self.facold.powf(self.beta)
            };
            let raw = fac11 / pi_part / self.safety;
            // `f64::max/min` return the non-NaN operand; `raw` is finite here.
            let fac = raw.min(1.0 / self.fac_min).max(1.0 / self.fac_max);
            let mut h_new = h / fac;
            if after_reject {
                h_new = h_new.min(h);
            }
            self.facold = err.max(1e-4);
            Decision { accept: true, h_new }
        } else {
            // A NaN error lands here; `min` then picks 1/fac_min, the
            // strongest allowed cut.
            let h_new = h / (1.0 / self.fac_min).min(fac11 / self.safety);
            Decision { accept: false, h_new }
        }
    }
}

/// Step size to propose after an accepted step of size `h` whose decision
/// was `d`.
///
/// When the step had been shortened to land on `t_stop` (`clamped`), the
/// controller's answer is relative to the short step: after a tiny clamped
/// step it would shrink the estimate by up to `fac_max` (and round-off in the
/// error of a tiny step keeps even the unclipped answer small). So if the
/// error allowed the step to grow, keep the larger of that and the proposal
/// from before the clamp, `h_proposed`, which rests on the error of a full
/// step; if the error asked for a smaller step, believe it. Hairer's codes
/// only clamp the last step, so they never face this; the hybrid driver
/// clamps at every output and event-check time.
pub(super) fn next_step_size(d: &Decision, h: f64, clamped: bool, h_proposed: f64, h_max: f64) -> f64 {
    let h_next = if clamped && d.h_new >= h {
        d.h_new.max(h_proposed)
    } else {
        d.h_new
    };
    h_next.min(h_max)
}
