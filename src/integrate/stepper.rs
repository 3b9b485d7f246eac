//! The stepper interface shared by every method.

/// Right-hand side of the ODE `dy/dt = f(t, y)`.
///
/// Implemented for every `Fn(f64, &[f64; N], &mut [f64; N])`, so a closure
/// that captures the current hybrid mode can be passed directly.
pub trait Rhs<const N: usize> {
    /// How many trailing components of `y` are pure quadratures, `y_i' =
    /// g_i(t, y)` with no `g` reading any of them (the block's work and
    /// friction-loss audits). A Runge–Kutta stepper then forms its stage
    /// states for the leading components only; the solution and the error
    /// estimate still cover all. 0 by default: every component is read.
    const QUADRATURES: usize = 0;

    /// Writes `f(t, y)` into `dydt`.
    fn eval(&self, t: f64, y: &[f64; N], dydt: &mut [f64; N]);

    /// The Taylor coefficients of the solution through `(t, y)`: writes
    /// `c[k]` with `y(t + s) = Σ_k c[k] s^k` for `k = 0..=order` (so `c[0] =
    /// y`, `c[1] = f(t, y)`), `c.len() == order + 1`. Returns `false` if
    /// this right-hand side has no series (then `c` is unspecified and the
    /// [Taylor](super::taylor) method steps with DOP853). By default none.
    fn taylor(&self, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        let _ = (t, y, order, c);
        false
    }
}

impl<const N: usize, F> Rhs<N> for F
where
    F: Fn(f64, &[f64; N], &mut [f64; N]),
{
    #[inline]
    fn eval(&self, t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
        self(t, y, dydt)
    }
}

/// Error tolerances and step limits of an adaptive method.
///
/// The local error of each component is measured against
/// `atol + rtol * max(|y_old|, |y_new|)` (Hairer–Nørsett–Wanner, scipy
/// `compute_error`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance. Default 1e-10: tight enough that impact times are
    /// resolved far below the paper's 1e-6 while a 800 τ run stays in
    /// milliseconds.
    pub rtol: f64,
    /// Absolute tolerance, in the units of each state component. Default 1e-12.
    pub atol: f64,
    /// Largest step allowed, in units of the independent variable. Default
    /// `f64::INFINITY`; the hybrid driver caps it so that interior guard
    /// samples stay dense enough.
    pub h_max: f64,
    /// Fixed step for fixed-step methods (Ralston). Default 0.004, the paper's
    /// normalised sampling time.
    pub h_fixed: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            h_max: f64::INFINITY,
            h_fixed: 0.004,
        }
    }
}

/// Work counters, as in ode-solvers and scipy's `nfev`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct StepStats {
    /// Right-hand-side evaluations, including those spent on dense output.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps (error too large, or undone by the driver).
    pub rejected: u64,
}

impl std::ops::AddAssign for StepStats {
    fn add_assign(&mut self, o: Self) {
        self.rhs_evals += o.rhs_evals;
        self.accepted += o.accepted;
        self.rejected += o.rejected;
    }
}

/// Why a step could not be taken.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StepError {
    /// The controller asked for a step below the round-off limit of `t`.
    #[error("step size underflow at t = {t} (h = {h:e})")]
    StepSizeUnderflow {
        /// Time at which the step could not be taken.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },
    /// The right-hand side or the new state contained NaN or infinity.
    #[error("non-finite state at t = {t}")]
    NonFinite {
        /// Time at the start of the failed step.
        t: f64,
    },
}

/// The [`Stepper`] accessors of a stepper that keeps its last step's end
/// in `t` and `y` and its start in `t_old` (each of ours does).
macro_rules! step_ends {
    () => {
        fn t(&self) -> f64 {
            self.t
        }

        fn y(&self) -> &[f64; N] {
            &self.y
        }

        fn t_prev(&self) -> f64 {
            self.t_old
        }
    };
}
pub(crate) use step_ends;

/// A one-step method with dense output over its last step.
///
/// Usage: [`restart`](Stepper::restart) at `(t0, y0)`, then call
/// [`step`](Stepper::step) repeatedly. After each step, [`dense`](Stepper::dense)
/// interpolates on `[t_prev(), t()]`. After the hybrid driver applies a reset
/// map it calls `restart` again with the new state: this discards FSAL data
/// (the derivative of the old mode is wrong for the new one) but keeps the
/// last step-size estimate.
pub trait Stepper<const N: usize> {
    /// Short method name as used in configs: `dop853`, `dopri5`, `ralston`.
    fn name(&self) -> &'static str;

    /// Starts from `(t, y)`, discarding FSAL and dense data.
    fn restart<F: Rhs<N>>(&mut self, f: &F, t: f64, y: &[f64; N]);

    /// Takes one accepted step that ends at or before `t_stop`, landing
    /// exactly on `t_stop` (bit for bit) when the step would pass it.
    fn step<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError>;

    /// [`step`](Stepper::step) where `f` is known to be exactly zero
    /// along the step ([`HybridSystem::is_still`](super::hybrid::HybridSystem::is_still)):
    /// the same step, state, step-size control and dense output bit for
    /// bit, without evaluating `f`. By default, `step`.
    fn step_still<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        self.step(f, t_stop)
    }

    /// Time at the end of the last step (the current time).
    fn t(&self) -> f64;
    /// State at the end of the last step.
    fn y(&self) -> &[f64; N];
    /// Time at the start of the last step.
    fn t_prev(&self) -> f64;

    /// High-order dense output at `t` in `[t_prev(), t()]`. May evaluate
    /// `f` (DOP853 needs three extra stages, computed once per step).
    fn dense<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N]);

    /// [`dense`](Stepper::dense) for the leading `count` components only;
    /// the rest of `out` is left as it was. The driver samples guards so,
    /// and guards read no quadrature ([`Rhs::QUADRATURES`]): a third less
    /// interpolation for the block. By default, all components.
    fn dense_leading<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N], count: usize) {
        let _ = count;
        self.dense(f, t, out);
    }

    /// [`hermite`](Stepper::hermite) for the leading `count` components
    /// only, as [`dense_leading`](Stepper::dense_leading): what a stepper
    /// with such data implements (the driver screens the guards' leading
    /// components). By default it has none.
    fn hermite_leading(&self, _t: f64, _out: &mut [f64; N], _count: usize) -> bool {
        false
    }

    /// The cubic Hermite interpolant of the last step at `t`, built from the
    /// end states and their derivatives only (no evaluation of `f`, no
    /// extra stages): the driver screens guards with it before it pays for
    /// the high-order dense output. Accurate to O(h⁴), not to the
    /// tolerance. Returns `false` if the stepper has no such data (then the
    /// driver uses [`dense`](Stepper::dense)). All components of
    /// [`hermite_leading`](Stepper::hermite_leading).
    fn hermite(&self, t: f64, out: &mut [f64; N]) -> bool {
        self.hermite_leading(t, out, N)
    }

    /// A conservative estimate of the error of [`hermite`](Stepper::hermite)
    /// at the step's midpoint: the cubic's own third-order term there,
    /// `(2(y1 - y0) - h(f0 + f1))/8`, i.e. how far it is from the quadratic
    /// through `y0`, `f0`, `y1`. That is O(h³) while the cubic's error is
    /// O(h⁴), so it overestimates it by about 8/(ωh) for a solution of
    /// frequency ω. Returns `false` without such data.
    fn hermite_spread(&self, _out: &mut [f64; N]) -> bool {
        false
    }

    /// Cut the last step short at `t_cut` in `[t_prev(), t()]`: the current
    /// state becomes the dense output there. Used at events.
    fn truncate<F: Rhs<N>>(&mut self, f: &F, t_cut: f64) {
        let mut y = [0.0; N];
        self.dense(f, t_cut, &mut y);
        self.restart(f, t_cut, &y);
    }

    /// Work counters since construction.
    fn stats(&self) -> StepStats;

    /// `true` if events are located by root finding on dense output; `false`
    /// for the paper's method, which locates them by undoing the step and
    /// retrying with a step cut by ten ([`undo_and_shrink`](Stepper::undo_and_shrink)).
    fn locates_by_root(&self) -> bool {
        true
    }

    /// Undoes the last step and divides the step size by `factor`. Only
    /// fixed-step methods support it; adaptive ones return `false`.
    fn undo_and_shrink(&mut self, _factor: f64) -> bool {
        false
    }

    /// Current step size (the next step's, for fixed-step methods).
    fn step_size(&self) -> f64;

    /// Puts a fixed-step method back to its nominal step after the driver has
    /// handled an event located by step cutting. No-op for adaptive methods.
    fn reset_step_size(&mut self) {}
}
