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
//! This file also holds the machinery shared with [`super::dop853`]: the
//! controller, the initial step heuristic, the error scale and the stage
//! combination. Both methods are Hairer's codes with different tableaux, so
//! sharing keeps them from drifting apart.

use super::stepper::{Rhs, StepError, StepStats, Stepper, Tolerances};

// ---------------------------------------------------------------------------
// Shared machinery (also used by DOP853).
// ---------------------------------------------------------------------------

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

/// `out = y + h * sum_j w[j] * k[j]`, skipping zero weights (most tableau
/// entries are zero). The sum runs in stage order, so it is the same
/// arithmetic for a state and its mirror image.
#[inline]
pub(super) fn combine<const N: usize>(y: &[f64; N], h: f64, w: &[f64], k: &[[f64; N]], out: &mut [f64; N]) {
    // Stages outer, components inner: contiguous and vectorisable. Each
    // component still sums its stages in the same order, so the result is
    // bit-identical to the component-by-component loop.
    let mut acc = [0.0; N];
    for (wj, kj) in w.iter().zip(k) {
        if *wj != 0.0 {
            for (a, kn) in acc.iter_mut().zip(kj) {
                *a += wj * kn;
            }
        }
    }
    for ((o, yn), a) in out.iter_mut().zip(y).zip(acc) {
        *o = yn + h * a;
    }
}

/// [`combine`] for the first `m` components only (`m <= N`); the others
/// keep whatever `out` held. For stage states, whose trailing quadratures
/// no right-hand side reads ([`Rhs::QUADRATURES`]): `m` is a constant after
/// monomorphisation, so the loops are as tight as `combine`'s.
#[inline]
pub(super) fn combine_leading<const N: usize>(
    y: &[f64; N],
    h: f64,
    w: &[f64],
    k: &[[f64; N]],
    out: &mut [f64; N],
    m: usize,
) {
    let m = m.min(N);
    let mut acc = [0.0; N];
    for (wj, kj) in w.iter().zip(k) {
        if *wj != 0.0 {
            for (a, kn) in acc[..m].iter_mut().zip(&kj[..m]) {
                *a += wj * kn;
            }
        }
    }
    for ((o, yn), a) in out[..m].iter_mut().zip(&y[..m]).zip(&acc[..m]) {
        *o = yn + h * a;
    }
}

/// The cubic Hermite interpolant through `(t0, y0, f0)` and `(t0 + h, y1,
/// f1)` at `theta = (t - t0)/h`, in the Hermite basis:
/// `(1-θ)²(1+2θ) y0 + θ(1-θ)² h f0 + θ²(3-2θ) y1 + θ²(θ-1) h f1`.
/// The four weights are computed once and the components are a vectorisable
/// linear combination in a fixed order, so negating the state negates the
/// result bit for bit.
#[inline]
pub(super) fn hermite<const N: usize>(
    y0: &[f64; N],
    y1: &[f64; N],
    f0: &[f64; N],
    f1: &[f64; N],
    h: f64,
    theta: f64,
    out: &mut [f64; N],
) {
    hermite_leading(y0, y1, f0, f1, h, theta, out, N);
}

/// [`hermite`] for the leading `count` components (the rest of `out` is
/// left as it was).
#[inline]
#[allow(clippy::too_many_arguments)]
pub(super) fn hermite_leading<const N: usize>(
    y0: &[f64; N],
    y1: &[f64; N],
    f0: &[f64; N],
    f1: &[f64; N],
    h: f64,
    theta: f64,
    out: &mut [f64; N],
    count: usize,
) {
    let u = 1.0 - theta;
    let t2 = theta * theta;
    let w_y0 = u * u * (1.0 + 2.0 * theta);
    let w_f0 = h * theta * u * u;
    let w_y1 = t2 * (3.0 - 2.0 * theta);
    let w_f1 = -h * t2 * u;
    for n in 0..count.min(N) {
        out[n] = w_y0 * y0[n] + w_f0 * f0[n] + w_y1 * y1[n] + w_f1 * f1[n];
    }
}

/// The third-order term of [`hermite`] at the midpoint,
/// `(2(y1 - y0) - h(f0 + f1))/8` (see [`Stepper::hermite_spread`]).
#[inline]
pub(super) fn hermite_spread<const N: usize>(
    y0: &[f64; N],
    y1: &[f64; N],
    f0: &[f64; N],
    f1: &[f64; N],
    h: f64,
    out: &mut [f64; N],
) {
    for n in 0..N {
        out[n] = 0.125 * (2.0 * (y1[n] - y0[n]) - h * (f0[n] + f1[n]));
    }
}

/// `true` if every component is finite.
#[inline]
pub(super) fn all_finite<const N: usize>(v: &[f64; N]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Hairer's initial step-size heuristic (`HINIT` in `dopri5.f`/`dop853.f`;
/// Hairer–Nørsett–Wanner §II.4): take `h0 = 0.01 ||y|| / ||f||`, estimate the
/// second derivative with one explicit Euler step, and choose `h` such that
/// `h^order * max(||f||, ||y''||) = 0.01`. Costs one evaluation of `f`.
///
/// Returns `None` when `f0` or the trial derivative is not finite, so the
/// caller does not store a meaningless estimate (the step then reports
/// [`StepError::NonFinite`]).
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
#[derive(Clone, Debug)]
pub struct Dopri5<const N: usize> {
    tol: Tolerances,
    ctrl: Controller,
    t: f64,
    t_old: f64,
    y: [f64; N],
    y_old: [f64; N],
    /// Stages of the last accepted step; `k[0] = f(t_old, y_old)` and
    /// `k[6] = f(t, y)` once a step has been taken.
    k: [[f64; N]; STAGES],
    /// `k[6]` holds `f(t, y)` and must become `k[0]` before the next step.
    /// Deferred so that dense output still sees the old `k[0]`.
    fsal_pending: bool,
    /// A step has been taken since the last restart (dense output is valid).
    has_step: bool,
    /// `restart` has been called at least once.
    started: bool,
    /// Size of the last accepted step (the one dense output covers).
    h_used: f64,
    /// Proposed size of the next step; 0 until the first `hinit`.
    h_next: f64,
    /// The last accepted step size not shortened to land on a stop (or a
    /// shortened one, if larger): the largest step with evidence that the
    /// current solution allows it. 0 before the first step.
    h_trusted: f64,
    stats: StepStats,
}

impl<const N: usize> Dopri5<N> {
    /// A stepper with the given tolerances. Call [`Stepper::restart`] before
    /// the first step (a step without it starts from `t = 0`, `y = 0`).
    pub fn new(tol: Tolerances) -> Self {
        Self {
            tol,
            // Hairer's defaults: SAFE = 0.9, FAC1 = 0.2, FAC2 = 10, BETA = 0.04,
            // EXPO1 = 0.2 - BETA * 0.75.
            ctrl: Controller::new(0.9, 0.2, 10.0, 0.04, 0.2 - 0.04 * 0.75),
            t: 0.0,
            t_old: 0.0,
            y: [0.0; N],
            y_old: [0.0; N],
            k: [[0.0; N]; STAGES],
            fsal_pending: false,
            has_step: false,
            started: false,
            h_used: 0.0,
            h_next: 0.0,
            h_trusted: 0.0,
            stats: StepStats::default(),
        }
    }

    /// Evaluates `f` and counts it.
    fn eval<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N], i: usize) {
        f.eval(t, y, &mut self.k[i]);
        self.stats.rhs_evals += 1;
    }

    /// One attempt of size `h` ending at `t_new`: fills `k[1..7]` and
    /// `y_new`, returns the error norm.
    fn attempt<F: Rhs<N>>(&mut self, f: &F, h: f64, t_new: f64, y_new: &mut [f64; N]) -> Result<f64, StepError> {
        let t = self.t;
        let mut ys = [0.0; N];
        for i in 1..STAGES {
            combine(&self.y, h, &A[i][..i], &self.k[..i], &mut ys);
            if !all_finite(&ys) {
                return Err(StepError::NonFinite { t });
            }
            // Stages with c = 1 use the exact end time, so that the FSAL
            // stage is f at the time the step reports.
            let ti = if C[i] == 1.0 { t_new } else { t + C[i] * h };
            self.eval(f, ti, &ys, i);
            if !all_finite(&self.k[i]) {
                return Err(StepError::NonFinite { t });
            }
        }
        *y_new = ys;
        let mut sum = 0.0;
        for n in 0..N {
            let mut e = 0.0;
            for (ej, kj) in E.iter().zip(&self.k) {
                if *ej != 0.0 {
                    e += ej * kj[n];
                }
            }
            let sk = err_scale(&self.tol, self.y[n], y_new[n]);
            sum += (h * e / sk).powi(2);
        }
        Ok((sum / N.max(1) as f64).sqrt())
    }

    /// The continuous extension at `theta = (t - t_old) / h` in Hairer's
    /// form (`CONTD5`): `y_old + θ(Δ + (1-θ)(r3 + θ(r4 + (1-θ) r5)))`.
    fn interpolate(&self, theta: f64, out: &mut [f64; N]) {
        let h = self.h_used;
        let th1 = 1.0 - theta;
        let (k0, k6) = (&self.k[0], &self.k[STAGES - 1]);
        for n in 0..N {
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

impl<const N: usize> Stepper<N> for Dopri5<N> {
    fn name(&self) -> &'static str {
        "dopri5"
    }

    /// Starts at `(t, y)`: evaluates `f(t, y)` (discarding FSAL data) and, on
    /// the very first restart only, estimates the initial step with Hairer's
    /// `hinit` (one more evaluation). Later restarts keep the last step-size
    /// estimate: they follow impacts, where the time scale has not changed.
    fn restart<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N]) {
        self.t = t;
        self.t_old = t;
        self.y = *y;
        self.y_old = *y;
        self.eval(f, t, y, 0);
        self.fsal_pending = false;
        self.has_step = false;
        self.started = true;
        self.h_used = 0.0;
        // A reset (an impact, a stick–slip switch) starts a new solution.
        // The proposal carried over may have grown on a step whose error
        // estimate saw the smooth continuation of the old mode across the
        // event, which says nothing about the new one: start no larger than
        // the last step that passed. At loose tolerances this removes about
        // one rejected step per impact (see docs/performance.md).
        if self.h_trusted > 0.0 {
            self.h_next = self.h_next.min(self.h_trusted);
        }
        self.ctrl.reset();
        if self.h_next <= 0.0 {
            let (y0, f0) = (self.y, self.k[0]);
            if let Some(h) = hinit(f, t, &y0, &f0, 5, &self.tol, &mut self.stats.rhs_evals) {
                self.h_next = h;
            }
        }
    }

    fn step<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(StepError::StepSizeUnderflow {
                t: self.t,
                h: t_stop - self.t,
            });
        }
        if !self.started {
            let y = self.y;
            self.restart(f, self.t, &y);
        }
        if self.fsal_pending {
            self.k[0] = self.k[STAGES - 1];
            self.fsal_pending = false;
        }
        // The stages of the last step are being overwritten: until this step
        // is accepted, dense output only knows the current point (this
        // matters if the step fails).
        self.has_step = false;
        self.t_old = self.t;
        self.y_old = self.y;
        if !all_finite(&self.k[0]) || !all_finite(&self.y) {
            return Err(StepError::NonFinite { t: self.t });
        }
        let mut h = if self.h_next > 0.0 { self.h_next } else { H_FALLBACK };
        let mut after_reject = false;
        let mut rejections = 0;
        let mut y_new = [0.0; N];
        loop {
            let h_proposed = h;
            let h_cap = h.min(self.tol.h_max);
            let dist = t_stop - self.t;
            let (h_try, mut clamped) = if h_cap >= dist { (dist, true) } else { (h_cap, false) };
            if !clamped && (h_try.is_nan() || h_try < h_min(self.t)) {
                return Err(StepError::StepSizeUnderflow { t: self.t, h: h_try });
            }
            let mut t_new = if clamped { t_stop } else { self.t + h_try };
            if t_new >= t_stop {
                // Rounding of `t + h` reached t_stop: land on it exactly.
                t_new = t_stop;
                clamped = true;
            }
            let err = self.attempt(f, h_try, t_new, &mut y_new)?;
            let d = self.ctrl.decide(err, h_try, after_reject);
            if d.accept {
                self.h_next = next_step_size(&d, h_try, clamped, h_proposed, self.tol.h_max);
                self.t = t_new;
                self.y = y_new;
                self.h_used = h_try;
                self.h_trusted = if clamped { self.h_trusted.max(h_try) } else { h_try };
                self.fsal_pending = true;
                self.has_step = true;
                self.stats.accepted += 1;
                return Ok(());
            }
            self.stats.rejected += 1;
            rejections += 1;
            if rejections >= MAX_REJECTIONS {
                return Err(StepError::StepSizeUnderflow { t: self.t, h: d.h_new });
            }
            after_reject = true;
            h = d.h_new;
        }
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64; N] {
        &self.y
    }

    fn t_prev(&self) -> f64 {
        self.t_old
    }

    /// 4th-order dense output (Shampine 1986, Hairer's `CONTD5`). Returns the
    /// stored end states bit for bit at `t_prev()` and `t()`, and `y()` when
    /// no step has been taken since the last restart. Outside
    /// `[t_prev(), t()]` the polynomial extrapolates. Never evaluates `f`.
    fn dense<F: Rhs<N>>(&mut self, _f: &F, t: f64, out: &mut [f64; N]) {
        if !self.has_step || t == self.t {
            *out = self.y;
        } else if t == self.t_old {
            *out = self.y_old;
        } else {
            self.interpolate((t - self.t_old) / self.h_used, out);
        }
    }

    fn hermite(&self, t: f64, out: &mut [f64; N]) -> bool {
        if !self.has_step {
            return false;
        }
        // k[0] is f(t_old, y_old) until the next step moves the FSAL stage.
        let (f0, f1) = (&self.k[0], &self.k[STAGES - 1]);
        hermite(
            &self.y_old,
            &self.y,
            f0,
            f1,
            self.h_used,
            (t - self.t_old) / self.h_used,
            out,
        );
        true
    }

    fn hermite_spread(&self, out: &mut [f64; N]) -> bool {
        if !self.has_step {
            return false;
        }
        let (f0, f1) = (&self.k[0], &self.k[STAGES - 1]);
        hermite_spread(&self.y_old, &self.y, f0, f1, self.h_used, out);
        true
    }

    fn stats(&self) -> StepStats {
        self.stats
    }

    fn step_size(&self) -> f64 {
        self.h_next
    }
}

#[cfg(test)]
pub(super) mod tests {
    //! Test problems shared with the other methods' tests.

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

    /// The Hermite interpolant reproduces every cubic exactly (to
    /// round-off) from its end values and slopes, and is odd in the state.
    #[test]
    fn hermite_is_exact_for_cubics() {
        let p = |t: f64| 0.3 - 1.7 * t + 2.1 * t * t - 0.9 * t * t * t;
        let dp = |t: f64| -1.7 + 4.2 * t - 2.7 * t * t;
        let (t0, h) = (0.4, 0.7);
        let (y0, y1, f0, f1) = ([p(t0)], [p(t0 + h)], [dp(t0)], [dp(t0 + h)]);
        for k in 0..=20 {
            let theta = f64::from(k) / 20.0;
            let mut out = [0.0];
            hermite(&y0, &y1, &f0, &f1, h, theta, &mut out);
            assert!((out[0] - p(t0 + theta * h)).abs() < 1e-14, "θ = {theta}");
            let mut neg = [0.0];
            hermite(&[-y0[0]], &[-y1[0]], &[-f0[0]], &[-f1[0]], h, theta, &mut neg);
            assert_eq!(neg[0].to_bits(), (-out[0]).to_bits());
        }
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
