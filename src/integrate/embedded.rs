//! One adaptive stepper for the embedded Runge–Kutta pairs: Hairer's step
//! loop, first-same-as-last bookkeeping, restarts and the interpolants that
//! need only the step's ends, written once for [`Dopri5`](super::Dopri5) and
//! [`Dop853`](super::Dop853).
//!
//! What differs between the pairs is behind [`Pair`]: the stages and error
//! norm of an attempt, the dense output, the controller's parameters, and
//! two policies (where the FSAL stage is evaluated, and whether a stage that
//! leaves the domain of `f` is a step too large). Each pair is a zero-sized
//! marker type and [`EmbeddedRk`] is monomorphised per pair and per `N`, so
//! the policies are constants and the hooks are direct calls: the same
//! machine code as one stepper written out per method.

use std::fmt::Debug;

use super::controller::{Controller, H_FALLBACK, MAX_REJECTIONS, h_min, hinit, next_step_size};
use super::stages::{all_finite, hermite_leading, hermite_spread};
use super::stepper::{Rhs, StepError, StepStats, Stepper, Tolerances, step_ends};

/// An embedded explicit Runge–Kutta pair with first-same-as-last: what
/// [`EmbeddedRk`] needs to know of one method. `N` is the state size, `S`
/// the number of stage slots the method stores (its stages, the FSAL stage
/// and any extra dense-output stages).
pub trait Pair<const N: usize, const S: usize>: Sized {
    /// Short method name as used in configs.
    const NAME: &'static str;
    /// Order of the solution, for the initial step heuristic (`hinit`).
    const ORDER: i32;
    /// Index of the FSAL stage `f(t + h, y_new)` in the stage slots; it
    /// becomes stage 0 of the next step.
    const FSAL: usize;
    /// Whether the FSAL stage is evaluated after the error test, for an
    /// accepted step only (DOP853, whose FSAL stage is not one of the
    /// attempt's), rather than as the attempt's last stage (DOPRI5).
    const FSAL_AFTER_TEST: bool;
    /// Whether an attempt whose stages left the domain where `f` is finite
    /// is taken for a step too large and retried with the hardest cut, as
    /// Hairer's codes treat a NaN error (DOP853), rather than reported as
    /// [`StepError::NonFinite`] at once (DOPRI5).
    const RETRY_NON_FINITE: bool;
    /// Hairer's controller parameters `SAFE`, `FAC1`, `FAC2`, `BETA` and
    /// `EXPO1` (see [`Controller`]).
    const CONTROL: [f64; 5];

    /// Dense-output data beyond the stages (`()` for none).
    type Dense: Clone + Debug;

    /// The dense data of a stepper that has taken no step.
    fn new_dense() -> Self::Dense;

    /// Marks the dense data stale: a new step or a restart.
    #[inline]
    fn invalidate(_dense: &mut Self::Dense) {}

    /// One attempt of size `h` from `(rk.t, rk.y)` ending at `t_new`: fills
    /// the stages, writes the solution into `y_new` and returns the error
    /// norm (at most 1 passes).
    fn attempt<F: Rhs<N>>(
        rk: &mut EmbeddedRk<Self, N, S>,
        f: &F,
        h: f64,
        t_new: f64,
        y_new: &mut [f64; N],
    ) -> Result<f64, StepError>;

    /// Readies the dense data of a step taken by
    /// [`step_still`](Stepper::step_still), whose stages are all zero,
    /// without evaluating `f`: what the first dense call would compute from
    /// zero stages. Nothing by default (a dense output from the stages
    /// alone needs nothing more).
    #[inline]
    fn still_dense(_rk: &mut EmbeddedRk<Self, N, S>) {}

    /// The dense output at `theta = (t - t_prev) / h` strictly inside the
    /// last step, the leading `count` components (the rest of `out` is left
    /// as it was). May evaluate `f` (extra stages).
    fn dense_inside<F: Rhs<N>>(rk: &mut EmbeddedRk<Self, N, S>, f: &F, theta: f64, out: &mut [f64; N], count: usize);
}

/// An adaptive stepper with the pair `P`: Hairer's `dopri5.f` and
/// `dop853.f` share this loop, and so do [`Dopri5`](super::Dopri5) and
/// [`Dop853`](super::Dop853), which are this type for their pairs.
#[derive(Clone, Debug)]
pub struct EmbeddedRk<P: Pair<N, S>, const N: usize, const S: usize> {
    pub(super) tol: Tolerances,
    pub(super) ctrl: Controller,
    pub(super) t: f64,
    pub(super) t_old: f64,
    pub(super) y: [f64; N],
    pub(super) y_old: [f64; N],
    /// Stages of the last accepted step: `k[0] = f(t_old, y_old)` and
    /// `k[P::FSAL] = f(t, y)` once a step has been taken.
    pub(super) k: [[f64; N]; S],
    /// The pair's own dense-output data.
    pub(super) dense: P::Dense,
    /// `k[P::FSAL]` holds `f(t, y)` and must become `k[0]` before the next
    /// step. Deferred so that dense output still sees the old `k[0]`.
    pub(super) fsal_pending: bool,
    /// A step has been taken since the last restart (dense output is valid).
    pub(super) has_step: bool,
    /// `restart` has been called at least once.
    pub(super) started: bool,
    /// Size of the last accepted step (the one dense output covers).
    pub(super) h_used: f64,
    /// Proposed size of the next step; 0 until the first `hinit`.
    pub(super) h_next: f64,
    /// The last accepted step size not shortened to land on a stop (or a
    /// shortened one, if larger): the largest step with evidence that the
    /// current solution allows it. 0 before the first step.
    pub(super) h_trusted: f64,
    pub(super) stats: StepStats,
}

impl<P: Pair<N, S>, const N: usize, const S: usize> EmbeddedRk<P, N, S> {
    /// A stepper with the given tolerances. Call [`Stepper::restart`] before
    /// the first step (a step without it starts from `t = 0`, `y = 0`).
    pub fn new(tol: Tolerances) -> Self {
        let [safety, fac_min, fac_max, beta, expo] = P::CONTROL;
        Self {
            tol,
            ctrl: Controller::new(safety, fac_min, fac_max, beta, expo),
            t: 0.0,
            t_old: 0.0,
            y: [0.0; N],
            y_old: [0.0; N],
            k: [[0.0; N]; S],
            dense: P::new_dense(),
            fsal_pending: false,
            has_step: false,
            started: false,
            h_used: 0.0,
            h_next: 0.0,
            h_trusted: 0.0,
            stats: StepStats::default(),
        }
    }

    /// Evaluates `f` into stage `i` and counts it.
    #[inline]
    pub(super) fn eval<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N], i: usize) {
        f.eval(t, y, &mut self.k[i]);
        self.stats.rhs_evals += 1;
    }

    /// One step of Hairer's loop; `still`: `f` is zero along it (see
    /// [`Stepper::step_still`]), so the attempt is written down instead of
    /// evaluated, with the values the stages would give bit for bit: zero
    /// stages, `y + h·0`, error 0.
    fn step_either<F: Rhs<N>>(&mut self, f: &F, t_stop: f64, still: bool) -> Result<(), StepError> {
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
            self.k[0] = self.k[P::FSAL];
            self.fsal_pending = false;
        }
        // The stages of the last step are being overwritten: until this step
        // is accepted, dense output only knows the current point (this
        // matters if the step fails).
        self.has_step = false;
        self.t_old = self.t;
        self.y_old = self.y;
        P::invalidate(&mut self.dense);
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
            // A stage that left the domain where `f` is finite (the block's
            // slide-rock near its Painlevé limit, where the denominator D
            // falls to zero just beyond the state) is a step too large, as
            // Hairer's codes treat a NaN error: cut it hard and retry. Only
            // when that does not help is the state reported non-finite.
            let attempt = if still {
                self.k[1..].iter_mut().for_each(|k| *k = [0.0; N]);
                for (n, yn) in y_new.iter_mut().zip(&self.y) {
                    // (`combine` adds h times a sum from +0: -0 becomes +0.)
                    *n = yn + 0.0;
                }
                Ok(0.0)
            } else {
                P::attempt(self, f, h_try, t_new, &mut y_new)
            };
            let err = match attempt {
                Ok(err) => err,
                Err(e @ StepError::NonFinite { .. }) if P::RETRY_NON_FINITE => {
                    if rejections + 1 >= MAX_REJECTIONS || h_try * self.ctrl.fac_min() < h_min(self.t) {
                        return Err(e);
                    }
                    f64::NAN
                }
                Err(e) => return Err(e),
            };
            let d = self.ctrl.decide(err, h_try, after_reject);
            if d.accept {
                if P::FSAL_AFTER_TEST && !still {
                    // The FSAL stage is needed only by an accepted step
                    // (Hairer evaluates it after the error test too).
                    self.eval(f, t_new, &y_new, P::FSAL);
                    if !all_finite(&self.k[P::FSAL]) {
                        return Err(StepError::NonFinite { t: self.t });
                    }
                }
                self.h_next = next_step_size(&d, h_try, clamped, h_proposed, self.tol.h_max);
                self.t = t_new;
                self.y = y_new;
                self.h_used = h_try;
                self.h_trusted = if clamped { self.h_trusted.max(h_try) } else { h_try };
                self.fsal_pending = true;
                self.has_step = true;
                self.stats.accepted += 1;
                if still {
                    P::still_dense(self);
                }
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
}

impl<P: Pair<N, S>, const N: usize, const S: usize> Stepper<N> for EmbeddedRk<P, N, S> {
    fn name(&self) -> &'static str {
        P::NAME
    }

    /// Starts at `(t, y)`: evaluates `f(t, y)` (discarding FSAL and dense
    /// data) and, on the very first restart only, estimates the initial step
    /// with Hairer's `hinit` (one more evaluation). Later restarts keep the
    /// last step-size estimate: they follow impacts, where the time scale
    /// has not changed.
    fn restart<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N]) {
        self.t = t;
        self.t_old = t;
        self.y = *y;
        self.y_old = *y;
        self.eval(f, t, y, 0);
        self.fsal_pending = false;
        P::invalidate(&mut self.dense);
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
            if let Some(h) = hinit(f, t, &y0, &f0, P::ORDER, &self.tol, &mut self.stats.rhs_evals) {
                self.h_next = h;
            }
        }
    }

    fn step<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        self.step_either(f, t_stop, false)
    }

    fn step_still<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        self.step_either(f, t_stop, true)
    }

    step_ends!();

    /// The pair's dense output. Returns the stored end states bit for bit at
    /// `t_prev()` and `t()` without evaluating anything, and `y()` when no
    /// step has been taken since the last restart. Outside
    /// `[t_prev(), t()]` the polynomial extrapolates.
    fn dense<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N]) {
        if !self.has_step || t == self.t {
            *out = self.y;
        } else if t == self.t_old {
            *out = self.y_old;
        } else {
            P::dense_inside(self, f, (t - self.t_old) / self.h_used, out, N);
        }
    }

    fn dense_leading<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N], count: usize) {
        if !self.has_step || t == self.t {
            out[..count].copy_from_slice(&self.y[..count]);
        } else if t == self.t_old {
            out[..count].copy_from_slice(&self.y_old[..count]);
        } else {
            P::dense_inside(self, f, (t - self.t_old) / self.h_used, out, count);
        }
    }

    fn hermite_leading(&self, t: f64, out: &mut [f64; N], count: usize) -> bool {
        if !self.has_step {
            return false;
        }
        // k[0] is f(t_old, y_old) until the next step moves the FSAL stage.
        let (f0, f1) = (&self.k[0], &self.k[P::FSAL]);
        let theta = (t - self.t_old) / self.h_used;
        hermite_leading(&self.y_old, &self.y, f0, f1, self.h_used, theta, out, count);
        true
    }

    fn hermite_spread(&self, out: &mut [f64; N]) -> bool {
        if !self.has_step {
            return false;
        }
        let (f0, f1) = (&self.k[0], &self.k[P::FSAL]);
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
