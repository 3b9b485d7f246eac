//! The hybrid (event-driven) driver: step, detect, locate, reset, restart.
//!
//! This is the role of scipy's `solve_ivp` event handling and SciML's
//! continuous callbacks, written for piecewise-smooth systems with many modes.
//!
//! Contract with a [`HybridSystem`]:
//! - Each mode has up to [`MAX_GUARDS`] guard functions `g_i(t, y)`. The mode's
//!   domain is `{ g_i > 0 for all i }`; an event is a crossing of one guard
//!   from `> 0` to `<= 0`. Direction is therefore built into the sign of `g`.
//! - After every accepted step the driver evaluates the guards at the step's
//!   end and at its midpoint on the cheap cubic Hermite interpolant (no
//!   extra evaluations of `f`). Guards that stay positive there by more than
//!   [`SCREEN_MARGIN`] times their variation are cleared for the step; that
//!   is most steps, which then never build the high-order dense output.
//!   Otherwise it evaluates every guard at
//!   [`SUBINTERVALS`]` + 1` points of the dense output, looks for sign changes,
//!   and on sub-intervals where a guard stays positive but dips (the parabola
//!   through three samples has an interior minimum well below the samples)
//!   it minimises the guard on the dense output, so a shallow double crossing
//!   inside one step (grazing) is not missed.
//! - A guard that is `<= 0` at the start of a segment (on the surface just
//!   crossed, e.g. `Θ = 0` right after an impact) is *unarmed*: it cannot fire
//!   until it has been positive. If it starts at exactly `0` and goes negative
//!   within the first sub-interval, its maximum there is searched: a positive
//!   bump followed by a return is an event; no bump is not. This is the
//!   "no re-fire at the root just handled" rule (SciML `repeat_nudge`)
//!   without an arbitrary time nudge.
//! - The earliest root is solved by Brent's method on the dense output to
//!   `max(4 ε |t|, 1e-15)`; the state there goes to [`HybridSystem::jump`],
//!   which returns the new mode and state (possibly at a later time, for
//!   impact accumulation); the stepper is then restarted (FSAL invalidated).
//! - *Observer* guards are located the same way but cause no jump: the system
//!   is told the time and state (used for exact extrema of `|Θ|`).
//! - Steps are capped at the system's [`HybridSystem::step_cap`] of the
//!   mode (a block at rest: the forcing's time scale), so a guard that
//!   depends on time alone is sampled several times per radian.
//! - Section (strobe) points come from the dense output of the step that
//!   contains them, as regular samples do (no step stops on them: that cost
//!   one step per forcing period). A step ends at every event, so they are
//!   never interpolated across a jump. The paper's fixed-step method steps
//!   onto them instead.
//! - Every loop is bounded by [`Limits`]; exceeding a bound is a typed error.
//!
//! For the fixed-step `ralston` method (the paper's), events are located the
//! paper's way instead: a guard sign change at the end of a step undoes the
//! step and retries with the step divided by 10 until `|g| < 1e-6`.
//!
//! The driver's jobs, one file each: `driver` (the loop, steps without an
//! event, jumps), `screen` (which guards a step must sample, on the cheap
//! Hermite interpolant), `locate` (sampling, brackets and roots on the
//! dense output), `cutting` (the paper's step cutting) and `emit`
//! (samples and section points).

mod cutting;
mod driver;
mod emit;
mod locate;
mod screen;

use super::stepper::Rhs;

pub use cutting::PAPER_GUARD_TOL;
pub use driver::{Advance, Driver, DriverError, Limits, Outputs};
pub use screen::SCREEN_MARGIN;

/// Most guards a mode may have.
pub const MAX_GUARDS: usize = 17;

/// Sub-intervals per step at which guards are sampled on the dense output.
/// Eight keeps a DOP853 step's interior sample spacing well below the
/// curvature scale of the guards while costing only 7 dense evaluations.
pub(crate) const SUBINTERVALS: usize = 8;

/// What a system does at an event.
#[derive(Clone, Copy, Debug)]
pub struct Jump<M, R, const N: usize> {
    /// Mode after the event.
    pub mode: M,
    /// Time at which integration resumes (`>=` the event time; later only
    /// when an accumulation of impacts was summed in closed form).
    pub t: f64,
    /// State after the reset map.
    pub y: [f64; N],
    /// Records the system wants reported for this event, in time order
    /// (an impact followed by the accumulation point it starts).
    pub records: [Option<R>; 2],
}

/// A piecewise-smooth system with modes, guards and reset maps.
pub trait HybridSystem<const N: usize> {
    /// Discrete mode.
    type Mode: Copy + PartialEq + std::fmt::Debug;
    /// Event record handed to the [`Observer`].
    type Record;
    /// Error a reset map may return.
    type Error: From<DriverError>;

    /// How many trailing components of the state are pure quadratures that
    /// neither `rhs` nor the guards read (see [`Rhs::QUADRATURES`]); 0 by
    /// default. The driver samples guards on interpolants of the other
    /// components only (for the block, the energy audit's W and D).
    const QUADRATURES: usize = 0;

    /// Vector field of `mode`.
    fn rhs(&self, mode: Self::Mode, t: f64, y: &[f64; N], dydt: &mut [f64; N]);

    /// Taylor coefficients of the solution of `mode` through `(t, y)`, as
    /// [`Rhs::taylor`]; `false` (the default) where there is no series.
    fn taylor(&self, mode: Self::Mode, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        let _ = (mode, t, y, order, c);
        false
    }

    /// Writes the guard values of `mode` into `g` and returns how many there
    /// are (at most [`MAX_GUARDS`]).
    fn guards(&self, mode: Self::Mode, t: f64, y: &[f64; N], g: &mut [f64; MAX_GUARDS]) -> usize;

    /// The value of guard `index` alone. The root finder and the dip check
    /// call this many times per event, so a system can skip the work of the
    /// other guards; it must equal `guards(..)[index]` bit for bit.
    fn guard(&self, mode: Self::Mode, index: usize, t: f64, y: &[f64; N]) -> f64 {
        let mut g = [0.0; MAX_GUARDS];
        self.guards(mode, t, y, &mut g);
        g[index]
    }

    /// Whether [`guard`](Self::guard) evaluates guard `index` of `mode` at a
    /// fraction of the cost of [`guards`](Self::guards) (a guard on the
    /// state alone, say). Where a sample needs several guards and one is not
    /// cheap, the driver calls `guards` once instead of `guard` for each.
    /// `false` by default.
    fn guard_is_cheap(&self, _mode: Self::Mode, _index: usize) -> bool {
        false
    }

    /// How many leading components of the state guard `index` of `mode`
    /// reads (its samples and root iterations interpolate no more). By
    /// default every component but the quadratures.
    fn guard_reads(&self, _mode: Self::Mode, _index: usize) -> usize {
        N - Self::QUADRATURES.min(N)
    }

    /// Whether guard `index` of `mode` provably stays positive along a step
    /// of length `h` from state `y0` to `y1`: a bound from the system's own
    /// equations over the whole step (not from samples), so the driver need
    /// not sample the guard on the dense output. It must never hold for a
    /// step along which the guard reaches zero. `false` by default.
    fn guard_stays_positive(&self, _mode: Self::Mode, _index: usize, _h: f64, _y0: &[f64; N], _y1: &[f64; N]) -> bool {
        false
    }

    /// Whether the root of observer `index` of `mode`, bracketed between
    /// the states `ya` at `ta` and `yb` at `tb`, can change what the
    /// observer records: when it cannot, the driver does not locate it.
    /// The states are dense-output samples with the components the guards
    /// read ([`guard_reads`](HybridSystem::guard_reads)). `true` by default.
    fn observer_may_record(
        &self,
        _mode: Self::Mode,
        _index: usize,
        _ta: f64,
        _ya: &[f64; N],
        _tb: f64,
        _yb: &[f64; N],
    ) -> bool {
        true
    }

    /// Whether guard `index` of `mode` only observes (no jump).
    fn is_observer(&self, mode: Self::Mode, index: usize) -> bool;

    /// Called at the root of an observer guard.
    fn observe(&mut self, mode: Self::Mode, index: usize, t: f64, y: &[f64; N]);

    /// The reset map for guard `index` of `mode`, crossed at `(t, y)`.
    fn jump(
        &mut self,
        mode: Self::Mode,
        index: usize,
        t: f64,
        y: &[f64; N],
    ) -> Result<Jump<Self::Mode, Self::Record, N>, Self::Error>;

    /// Whether `mode` ends the run.
    fn is_terminal(&self, mode: Self::Mode) -> bool;

    /// The first time after `t` at which the vector field has a kink (a
    /// recorded ground motion's samples, a pulse's end). Steps stop there.
    fn next_breakpoint(&self, t: f64) -> Option<f64>;

    /// Shortest time scale of the explicit time dependence of the vector
    /// field and the guards (1/Ω for a harmonic forcing of frequency Ω);
    /// infinite by default. The cheap screening of a step (see [`screen`](screen::screen))
    /// is used only on steps no longer than this; longer steps get the full
    /// sampling on the dense output.
    fn time_scale(&self) -> f64 {
        f64::INFINITY
    }

    /// Whether the vector field of `mode` is exactly zero (every component,
    /// at every time) from the state `y`: a body at rest on its base, whose
    /// guards move with the forcing alone. The driver then steps without
    /// evaluating it ([`Stepper::step_still`]), with the same steps, state
    /// and outputs bit for bit. It must never hold where `rhs` would give a
    /// non-zero component (debug builds check it). `false` by default.
    fn is_still(&self, _mode: Self::Mode, _y: &[f64; N]) -> bool {
        false
    }

    /// Longest step in `mode`; infinite by default. A mode whose guards
    /// depend on time alone while its state does not move (a block at rest:
    /// the error control sees nothing, whatever the forcing does) must cap
    /// its steps at a fraction of the forcing's time scale, or a guard could
    /// pass through zero and back between two samples.
    fn step_cap(&self, _mode: Self::Mode) -> f64 {
        f64::INFINITY
    }
}

/// The vector field of one mode, as a stepper sees it.
struct Field<'a, Sys, M> {
    sys: &'a Sys,
    mode: M,
}

impl<Sys: HybridSystem<N>, const N: usize> Rhs<N> for Field<'_, Sys, Sys::Mode> {
    const QUADRATURES: usize = Sys::QUADRATURES;

    #[inline]
    fn eval(&self, t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
        self.sys.rhs(self.mode, t, y, dydt);
    }

    #[inline]
    fn taylor(&self, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        self.sys.taylor(self.mode, t, y, order, c)
    }
}

/// Receives what the driver produces.
pub trait Observer<M, R, const N: usize> {
    /// A state on the regular output grid.
    fn sample(&mut self, t: f64, mode: M, y: &[f64; N]);
    /// A point of the stroboscopic section, `k` counting from 0 at `t = 0`.
    fn section(&mut self, k: u64, t: f64, mode: M, y: &[f64; N]);
    /// An event, with the mode before it and the state just before the jump.
    fn event(&mut self, t: f64, before: M, y_before: &[f64; N], record: R);
}
