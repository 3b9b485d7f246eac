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

use super::root::{brent_min, brent_root};
use super::stepper::{Rhs, StepError, Stepper};

/// Most guards a mode may have.
pub const MAX_GUARDS: usize = 8;

/// Sub-intervals per step at which guards are sampled on the dense output.
/// Eight keeps a DOP853 step's interior sample spacing well below the
/// curvature scale of the guards while costing only 7 dense evaluations.
pub const SUBINTERVALS: usize = 8;

/// Most offsets [`landing_near_surface_time`] looks at (halvings of half a
/// sample interval: 40 reach 1e-12 of it).
const SURFACE_PROBES: usize = 40;

/// Evenly spaced points at which [`landing_near_surface_time`] looks over
/// the first sample interval when its probes near the reset find nothing:
/// the hop it was added for (stress tier) landed 0.6 of the way through
/// the interval and was back above the surface by its end, 0.35 of it later.
const SURFACE_SCAN: usize = 16;

/// How deep behind its surface, relative to the guard's value two samples
/// after a reset, a probe must find it to count as a landing (1e-6: the
/// missed landing this catches dipped to 5.6e-3 of that value; round-off
/// noise right after a reset is far below it).
const LANDING_DEPTH: f64 = 1e-6;

/// How far behind its surface, in the guard's own units, a guard reset onto
/// it must be at the end of a step that took it straight there (every
/// sample behind, no bump above) for that to count as leaving at once
/// (see [`straight_behind_surface`]): far above the round-off of a reset
/// (1e-16 of state components of order 1), far below any motion that
/// matters (the case that needed it ended its step 2.8e-6 behind).
const BEHIND_FLOOR: f64 = 1e-12;

/// Margin of the cheap screening of a step: a guard is cleared without
/// dense output if its values at the ends and at the Hermite midpoint are
/// all above `SCREEN_MARGIN` times its variation between them. For a
/// resolved smooth guard (steps below the time scale, error control on the
/// state) the value between samples departs from them by a fraction of that
/// variation: at most 1/8 of it for a sinusoid sampled at its extremum.
pub const SCREEN_MARGIN: f64 = 1.0;

/// Guard tolerance of the paper's step-cutting event location (`|Θ| < 1e-6`).
pub const PAPER_GUARD_TOL: f64 = 1e-6;

/// Smallest step the paper's step cutting may reach before it accepts the
/// crossing anyway.
const PAPER_MIN_STEP: f64 = 1e-13;

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
    /// infinite by default. The cheap screening of a step (see [`screen`])
    /// is used only on steps no longer than this; longer steps get the full
    /// sampling on the dense output.
    fn time_scale(&self) -> f64 {
        f64::INFINITY
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

/// Loop bounds. Exceeding one is an error, never a hang.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Limits {
    /// Most accepted steps in one run. Default 10⁹: a 10⁶ τ run at the
    /// paper's fixed step 0.004 needs 2.5·10⁸.
    pub max_steps: u64,
    /// Most events in one run. Default 10⁸: a chaotic run makes about one
    /// impact per unit τ, so 10⁸ is far beyond any run this tool makes.
    pub max_events: u64,
    /// Whether a step may skip the dense output when the cheap screening on
    /// the Hermite interpolant clears every guard ([`screen`]). Default
    /// `true`. The screening must change nothing, bit for bit (a test runs
    /// thousands of random scenes both ways); `false` is there for that
    /// test.
    pub screening: bool,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_steps: 1_000_000_000,
            max_events: 100_000_000,
            screening: true,
        }
    }
}

/// Errors of the driver itself.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum DriverError {
    /// The stepper failed.
    #[error(transparent)]
    Step(#[from] StepError),
    /// More steps than [`Limits::max_steps`].
    #[error("more than {limit} steps by t = {t}")]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The limit.
        limit: u64,
    },
    /// More events than [`Limits::max_events`].
    #[error("more than {limit} events by t = {t}")]
    TooManyEvents {
        /// Time reached.
        t: f64,
        /// The limit.
        limit: u64,
    },
    /// A reset map returned a time before the event.
    #[error("reset map moved time backwards at t = {t}")]
    TimeReversal {
        /// Event time.
        t: f64,
    },
}

/// Regular output and stroboscopic section requested from the driver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    /// Spacing of regular samples; `None` for none (Poincaré-only runs keep
    /// no history).
    pub sample_dt: Option<f64>,
    /// Period of the stroboscopic section; `None` for none.
    pub section_period: Option<f64>,
}

/// How a call to [`Driver::advance`] ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Advance {
    /// Reached the requested time.
    Reached,
    /// Entered a terminal mode.
    Terminal,
}

/// The event-driven integrator: owns a stepper and a system.
pub struct Driver<S, Sys, const N: usize>
where
    Sys: HybridSystem<N>,
{
    stepper: S,
    system: Sys,
    mode: Sys::Mode,
    limits: Limits,
    outputs: Outputs,
    steps: u64,
    events: u64,
    /// Index of the next regular sample (`t = k · sample_dt`).
    next_sample: u64,
    /// Index of the next section point (`t = k · period`).
    next_section: u64,
    /// Guard values at the start of the current segment.
    g_start: [f64; MAX_GUARDS],
    n_guards: usize,
    /// Whether each guard has been positive since the last restart.
    armed: [bool; MAX_GUARDS],
    /// Steps cleared by the cheap screening (no dense output needed).
    screened: u64,
}

impl<S, Sys, const N: usize> Driver<S, Sys, N>
where
    S: Stepper<N>,
    Sys: HybridSystem<N>,
{
    /// Starts at `(t0, y0)` in `mode`. Section and sample indices start at the
    /// first grid points `>= t0`.
    pub fn new(
        mut stepper: S,
        system: Sys,
        mode: Sys::Mode,
        t0: f64,
        y0: [f64; N],
        limits: Limits,
        outputs: Outputs,
    ) -> Self {
        {
            let f = Field { sys: &system, mode };
            stepper.restart(&f, t0, &y0);
        }
        let first = |dt: Option<f64>| match dt {
            Some(dt) if dt > 0.0 => (t0 / dt).ceil().max(0.0) as u64,
            _ => 0,
        };
        let mut d = Self {
            stepper,
            system,
            mode,
            limits,
            outputs,
            steps: 0,
            events: 0,
            next_sample: first(outputs.sample_dt),
            next_section: first(outputs.section_period),
            g_start: [0.0; MAX_GUARDS],
            n_guards: 0,
            armed: [false; MAX_GUARDS],
            screened: 0,
        };
        d.refresh_guards();
        d
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.stepper.t()
    }
    /// Current state.
    pub fn y(&self) -> &[f64; N] {
        self.stepper.y()
    }
    /// Current mode.
    pub fn mode(&self) -> Sys::Mode {
        self.mode
    }
    /// The system.
    pub fn system(&self) -> &Sys {
        &self.system
    }
    /// The system, mutably (e.g. to change a parameter between calls).
    pub fn system_mut(&mut self) -> &mut Sys {
        &mut self.system
    }
    /// The stepper (for its statistics).
    pub fn stepper(&self) -> &S {
        &self.stepper
    }
    /// Accepted steps so far, as counted by the driver.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// Events so far.
    pub fn events(&self) -> u64 {
        self.events
    }
    /// Steps whose guards the cheap Hermite screening cleared, so that they
    /// needed no dense output.
    pub fn screened_steps(&self) -> u64 {
        self.screened
    }

    /// Restarts from a new state and mode (e.g. after the user edits it).
    pub fn reinit(&mut self, mode: Sys::Mode, t: f64, y: [f64; N]) {
        self.mode = mode;
        let sys = &self.system;
        let f = Field { sys, mode };
        self.stepper.restart(&f, t, &y);
        self.refresh_guards();
    }

    fn refresh_guards(&mut self) {
        let (t, y) = (self.stepper.t(), *self.stepper.y());
        self.n_guards = self.system.guards(self.mode, t, &y, &mut self.g_start);
        for i in 0..MAX_GUARDS {
            self.armed[i] = i < self.n_guards && self.g_start[i] > 0.0;
        }
    }

    /// Integrates until `t_end`, a terminal mode, or an error, reporting to
    /// `obs`. Can be called again with a later `t_end` to continue.
    pub fn advance<O>(&mut self, t_end: f64, obs: &mut O) -> Result<Advance, Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        self.advance_towards(t_end, t_end, obs)
    }

    /// Like [`advance`](Self::advance), except that a method with a dense
    /// output does not shorten a step to land on `t_end`: the step that
    /// reaches it is taken whole, with its outputs (samples, section points,
    /// its event), so the driver may stand past `t_end` afterwards. A run
    /// advanced so, in pieces of any size, takes the same steps as one
    /// advanced in a single call: the live session's chunks follow the batch
    /// run bit for bit up to its last step (the batch run's last step is the
    /// one shortened to end on its `τ_end`). The paper's fixed-step method
    /// steps onto `t_end`, as in `advance` (it stops on the section times
    /// too, which the live session's chunk ends are).
    pub fn advance_past<O>(&mut self, t_end: f64, obs: &mut O) -> Result<Advance, Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let horizon = if self.stepper.locates_by_root() {
            f64::INFINITY
        } else {
            t_end
        };
        self.advance_towards(t_end, horizon, obs)
    }

    /// Steps until `t_end` is reached, with steps that end on `horizon`
    /// (or before) rather than on `t_end`.
    fn advance_towards<O>(&mut self, t_end: f64, horizon: f64, obs: &mut O) -> Result<Advance, Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        self.emit_current(obs);
        loop {
            if self.system.is_terminal(self.mode) {
                return Ok(Advance::Terminal);
            }
            let t = self.stepper.t();
            if t >= t_end {
                return Ok(Advance::Reached);
            }
            if self.steps >= self.limits.max_steps {
                return Err(DriverError::TooManySteps {
                    t,
                    limit: self.limits.max_steps,
                }
                .into());
            }
            let t_stop = self.next_stop(t, horizon);
            if self.stepper.locates_by_root() {
                self.root_step(t_stop, obs)?;
            } else {
                self.cutting_step(t_stop, obs)?;
            }
        }
    }

    /// The next time a step must land on: the end, a section time or a kink.
    fn next_stop(&self, t: f64, t_end: f64) -> f64 {
        let mut stop = t_end;
        // Methods with a high-order dense output take section points from
        // it (`emit_sections_dense`), as scipy's `t_eval` and
        // DifferentialEquations.jl's `saveat` do: stopping on every section
        // time cost one extra step per forcing period, 7 % of a sweep
        // point's steps. The paper's fixed-step method steps onto them.
        if let Some(p) = self.outputs.section_period
            && !self.stepper.locates_by_root()
        {
            let ts = self.next_section as f64 * p;
            if ts > t && ts < stop {
                stop = ts;
            }
        }
        if let Some(tb) = self.system.next_breakpoint(t)
            && tb > t
            && tb < stop
        {
            stop = tb;
        }
        let cap = t + self.system.step_cap(self.mode);
        if cap > t && cap < stop {
            stop = cap;
        }
        stop
    }

    /// One step of an adaptive method, with events located by root finding.
    fn root_step<O>(&mut self, t_stop: f64, obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let n = self.n_guards;
        let mut g_end = [0.0; MAX_GUARDS];
        let need = {
            let sys = &self.system;
            let stepper = &mut self.stepper;
            let f = Field { sys, mode };
            let y0 = *stepper.y();
            stepper.step(&f, t_stop).map_err(DriverError::from)?;
            self.steps += 1;
            sys.guards(mode, stepper.t(), stepper.y(), &mut g_end);
            // Which guards need the dense output this step (see `screen`).
            if self.limits.screening {
                let mut need = screen(sys, mode, n, &*stepper, &self.armed, &self.g_start, &g_end);
                // A costly guard left over (a long step, which the cheap
                // screening does not look at) that the system can bound away
                // from zero over the whole step needs no samples either.
                let h = stepper.t() - stepper.t_prev();
                for i in 0..n {
                    if need[i]
                        && self.armed[i]
                        && self.g_start[i] > 0.0
                        && g_end[i] > 0.0
                        && !sys.guard_is_cheap(mode, i)
                        && sys.guard_stays_positive(mode, i, h, &y0, stepper.y())
                    {
                        need[i] = false;
                    }
                }
                need
            } else {
                [true; MAX_GUARDS]
            }
        };
        if need[..n].iter().any(|&x| x) {
            self.locate(&need, g_end, obs)
        } else {
            // Nothing can have happened: the common case, without building
            // the dense output.
            self.screened += 1;
            let armed = self.armed;
            self.accept(armed, g_end, obs);
            Ok(())
        }
    }

    /// The end of a step without an event: new guard values and arming,
    /// then the outputs due in the step.
    fn accept<O>(&mut self, armed: [bool; MAX_GUARDS], g_end: [f64; MAX_GUARDS], obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let t1 = self.stepper.t();
        self.armed = armed;
        self.emit_samples_dense(t1, obs);
        self.g_start = g_end;
        for i in 0..self.n_guards {
            if self.g_start[i] > 0.0 {
                self.armed[i] = true;
            } else if self.system.is_observer(mode, i) {
                // An observer re-arms only once it is positive again.
                self.armed[i] = false;
            }
        }
        self.emit_sections_dense(t1, true, obs);
    }

    /// Samples the guards in `need` on the dense output of the step just
    /// taken, locates the earliest crossing and the observers before it, and
    /// applies the event (or accepts the step if there is none).
    fn locate<O>(&mut self, need: &[bool; MAX_GUARDS], g_end: [f64; MAX_GUARDS], obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let n = self.n_guards;
        // Guards read no quadrature: samples interpolate the rest only.
        let reads = N - Sys::QUADRATURES.min(N);
        let mut armed = self.armed;
        // Observer roots before the event; their states are interpolated
        // after this block (no array of states to zero on every call).
        let mut observed = [None; MAX_GUARDS];
        let screening = self.limits.screening;
        let best = {
            let sys = &self.system;
            let stepper = &mut self.stepper;
            let f = Field { sys, mode };
            let t0 = stepper.t_prev();
            let t1 = stepper.t();
            // Guard samples on the dense output, for the guards that need it.
            let mut ts = [0.0; SUBINTERVALS + 1];
            let mut gs = [[0.0; MAX_GUARDS]; SUBINTERVALS + 1];
            ts[0] = t0;
            gs[0] = self.g_start;
            ts[SUBINTERVALS] = t1;
            gs[SUBINTERVALS] = g_end;
            // The sampled states (leading components), kept for the
            // observers' `observer_may_record`.
            let mut ys = [[0.0; N]; SUBINTERVALS + 1];
            // (The dense output returns the step's end states exactly.)
            stepper.dense(&f, t0, &mut ys[0]);
            ys[SUBINTERVALS] = *stepper.y();
            let all_at_once = several_costly(sys, mode, n, need);
            // The samples interpolate what the guards sampled read: Θ
            // alone for the block's impact and tumble guards, a quarter of
            // the dense output's work; all guards' reads when they are
            // evaluated together (Θ and Θ' for the block's rocking).
            let sample_reads = (0..n)
                .filter(|&i| all_at_once || need[i])
                .map(|i| sys.guard_reads(mode, i).min(reads))
                .max()
                .unwrap_or(reads);
            for j in 1..SUBINTERVALS {
                ts[j] = t0 + (t1 - t0) * (j as f64 / SUBINTERVALS as f64);
                let yj = &mut ys[j];
                stepper.dense_leading(&f, ts[j], yj, sample_reads);
                if all_at_once {
                    sys.guards(mode, ts[j], yj, &mut gs[j]);
                } else {
                    for i in (0..n).filter(|&i| need[i]) {
                        gs[j][i] = sys.guard(mode, i, ts[j], yj);
                    }
                }
            }

            // Earliest bracket per guard, then its root.
            let mut best: Option<(f64, usize)> = None;
            let mut roots = [None; MAX_GUARDS];
            for i in (0..n).filter(|&i| need[i]) {
                let reads_i = sys.guard_reads(mode, i).min(reads);
                let mut value = |tt: f64| {
                    let mut yy = [0.0; N];
                    stepper.dense_leading(&f, tt, &mut yy, reads_i);
                    sys.guard(mode, i, tt, &yy)
                };
                let Some((a, b)) = bracket(i, &ts, &gs, &mut armed[i], &mut value) else {
                    continue;
                };
                // An observer whose root cannot change its record is not
                // located (a bracket between two samples only). Part of the
                // screening: `tests/screening.rs` checks that it changes
                // no result.
                if screening
                    && sys.is_observer(mode, i)
                    && let (Some(ka), Some(kb)) = (ts.iter().position(|&x| x == a), ts.iter().position(|&x| x == b))
                    && !sys.observer_may_record(mode, i, a, &ys[ka], b, &ys[kb])
                {
                    continue;
                }
                // Bracket ends at samples have their values already (the
                // same bits: `guard` equals `guards`, and the dense output
                // returns the step's end states exactly); a dip's minimum
                // does not.
                let mut at = |x: f64| match ts.iter().position(|&tk| tk == x) {
                    Some(k) => gs[k][i],
                    None => value(x),
                };
                let ga = at(a);
                let gb = at(b);
                let root = if ga > 0.0 && gb <= 0.0 {
                    let xtol = (4.0 * f64::EPSILON * a.abs().max(b.abs())).max(1e-15);
                    match brent_root(&mut value, a, b, ga, gb, xtol, 200) {
                        Ok((r, _)) => r,
                        Err(_) => b,
                    }
                } else {
                    b
                };
                roots[i] = Some(root);
                if !sys.is_observer(mode, i) && best.is_none_or(|(tb, _)| root < tb) {
                    best = Some((root, i));
                }
            }
            // Observers located before the event (or anywhere, without one).
            let t_cut = best.map_or(t1, |(tb, _)| tb);
            for i in 0..n {
                if let Some(to) = roots[i]
                    && sys.is_observer(mode, i)
                    && to <= t_cut
                {
                    observed[i] = Some(to);
                }
            }
            best
        };
        for (i, to) in observed.iter().enumerate().take(n) {
            if let Some(to) = *to {
                let mut yo = [0.0; N];
                {
                    let f = Field {
                        sys: &self.system,
                        mode,
                    };
                    self.stepper.dense(&f, to, &mut yo);
                }
                self.system.observe(mode, i, to, &yo);
            }
        }

        match best {
            None => {
                self.accept(armed, g_end, obs);
                Ok(())
            }
            Some((t_ev, i)) => {
                let mut y_ev = [0.0; N];
                {
                    let sys = &self.system;
                    let f = Field { sys, mode };
                    self.stepper.dense(&f, t_ev, &mut y_ev);
                }
                self.emit_samples_dense(t_ev, obs);
                // A section time at the event itself reports the post-jump
                // state (`apply_jump`).
                self.emit_sections_dense(t_ev, false, obs);
                self.apply_jump(i, t_ev, y_ev, obs)
            }
        }
    }

    /// One step of the paper's fixed-step method, with events located by
    /// undoing the step and retrying with a step ten times smaller.
    fn cutting_step<O>(&mut self, t_stop: f64, obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let n = self.n_guards;
        let mut g1 = [0.0; MAX_GUARDS];
        loop {
            let sys = &self.system;
            let f = Field { sys, mode };
            self.stepper.step(&f, t_stop).map_err(DriverError::from)?;
            self.steps += 1;
            let t1 = self.stepper.t();
            let y1 = *self.stepper.y();
            sys.guards(mode, t1, &y1, &mut g1);
            // A guard that started on its surface (g = 0, just reset) and
            // ends the step behind it went out and back within the step: a
            // crossing too (after an impact with a tiny Θ', the block can
            // lift and fall back inside one fixed step).
            let crossing = (0..n).find(|&i| {
                !sys.is_observer(mode, i)
                    && ((self.armed[i] && g1[i] <= 0.0) || (self.g_start[i] == 0.0 && g1[i] < 0.0))
            });
            match crossing {
                Some(i) if g1[i].abs() >= PAPER_GUARD_TOL && self.stepper.step_size() > PAPER_MIN_STEP => {
                    if !self.stepper.undo_and_shrink(10.0) {
                        // A stepper that cannot undo: accept the crossing here.
                        return self.finish_cutting(i, t1, y1, obs);
                    }
                }
                Some(i) => return self.finish_cutting(i, t1, y1, obs),
                None => {
                    for (i, &gi) in g1.iter().enumerate().take(n) {
                        if self.system.is_observer(mode, i) && self.armed[i] && gi <= 0.0 {
                            self.system.observe(mode, i, t1, &y1);
                        }
                        if gi > 0.0 {
                            self.armed[i] = true;
                        } else if self.system.is_observer(mode, i) {
                            self.armed[i] = false;
                        }
                    }
                    self.g_start = g1;
                    self.emit_samples_dense(t1, obs);
                    self.emit_section_if_hit(t1, obs);
                    return Ok(());
                }
            }
        }
    }

    fn finish_cutting<O>(&mut self, i: usize, t1: f64, y1: [f64; N], obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        self.emit_samples_dense(t1, obs);
        self.stepper.reset_step_size();
        self.apply_jump(i, t1, y1, obs)
    }

    fn apply_jump<O>(&mut self, i: usize, t_ev: f64, y_ev: [f64; N], obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        self.events += 1;
        if self.events > self.limits.max_events {
            return Err(DriverError::TooManyEvents {
                t: t_ev,
                limit: self.limits.max_events,
            }
            .into());
        }
        let before = self.mode;
        let jump = self.system.jump(before, i, t_ev, &y_ev)?;
        if jump.t < t_ev {
            return Err(DriverError::TimeReversal { t: t_ev }.into());
        }
        for rec in jump.records.into_iter().flatten() {
            obs.event(t_ev, before, &y_ev, rec);
        }
        self.mode = jump.mode;
        // Outputs inside a closed-form skip (impact accumulation) see the
        // state the block is put in.
        if jump.t > t_ev {
            self.emit_constant(t_ev, jump.t, &jump.y, obs);
        }
        let mode = self.mode;
        let sys = &self.system;
        let f = Field { sys, mode };
        self.stepper.restart(&f, jump.t, &jump.y);
        self.refresh_guards();
        // A section time that coincides with the event (or was skipped over)
        // reports the post-jump state.
        self.emit_section_if_hit(jump.t, obs);
        Ok(())
    }

    /// Regular samples up to and including `t_to`, from the last step's
    /// dense output.
    fn emit_samples_dense<O>(&mut self, t_to: f64, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(dt) = self.outputs.sample_dt else {
            return;
        };
        let mode = self.mode;
        let sys = &self.system;
        let f = Field { sys, mode };
        let t_end = self.stepper.t();
        let mut y = [0.0; N];
        loop {
            let ts = self.next_sample as f64 * dt;
            if ts > t_to {
                break;
            }
            if ts == t_end {
                y = *self.stepper.y();
            } else {
                self.stepper.dense(&f, ts, &mut y);
            }
            obs.sample(ts, mode, &y);
            self.next_sample += 1;
        }
    }

    /// Section points in the last step up to `t_to` (included if
    /// `inclusive`), from its dense output; the step's end state bit for bit
    /// at its end. The dense output of DOP853 is of the method's accuracy
    /// (Hairer–Nørsett–Wanner II.6), so the points agree with stepping onto
    /// the section times to the tolerance (tested in `section_points_from_
    /// dense_output_match_stepping_onto_them`).
    fn emit_sections_dense<O>(&mut self, t_to: f64, inclusive: bool, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(p) = self.outputs.section_period else {
            return;
        };
        let mode = self.mode;
        let sys = &self.system;
        let f = Field { sys, mode };
        let t_end = self.stepper.t();
        let mut y = [0.0; N];
        loop {
            let ts = self.next_section as f64 * p;
            if ts > t_to || (ts == t_to && !inclusive) {
                break;
            }
            if ts == t_end {
                y = *self.stepper.y();
            } else {
                self.stepper.dense(&f, ts, &mut y);
            }
            obs.section(self.next_section, ts, mode, &y);
            self.next_section += 1;
        }
    }

    /// Outputs due exactly at the current time (the start of a run).
    fn emit_current<O>(&mut self, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let t = self.stepper.t();
        let y = *self.stepper.y();
        if let Some(dt) = self.outputs.sample_dt
            && self.next_sample as f64 * dt == t
        {
            obs.sample(t, self.mode, &y);
            self.next_sample += 1;
        }
        self.emit_section_if_hit(t, obs);
    }

    /// Samples and section points in `(t_from, t_to)` of a constant state.
    fn emit_constant<O>(&mut self, _t_from: f64, t_to: f64, y: &[f64; N], obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        if let Some(dt) = self.outputs.sample_dt {
            while (self.next_sample as f64 * dt) < t_to {
                obs.sample(self.next_sample as f64 * dt, self.mode, y);
                self.next_sample += 1;
            }
        }
        if let Some(p) = self.outputs.section_period {
            while (self.next_section as f64 * p) < t_to {
                obs.section(self.next_section, self.next_section as f64 * p, self.mode, y);
                self.next_section += 1;
            }
        }
    }

    /// Reports the section point if the current time is the next section time.
    fn emit_section_if_hit<O>(&mut self, t: f64, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(p) = self.outputs.section_period else {
            return;
        };
        let ts = self.next_section as f64 * p;
        if ts == t {
            let y = *self.stepper.y();
            obs.section(self.next_section, t, self.mode, &y);
            self.next_section += 1;
        } else if ts < t {
            // Only reachable if a jump moved time past a section time; those
            // points were emitted by `emit_constant`.
            while (self.next_section as f64 * p) < t {
                self.next_section += 1;
            }
        }
    }
}

/// The first landing of a guard that was reset onto its surface at `t0`,
/// is above it at `t1` and at `g_later` a sample later: offsets from `t0`
/// halving from `(t1 - t0)/2` down to the spacing of floats
/// ([`SURFACE_PROBES`] at most), then [`SURFACE_SCAN`] evenly spaced points
/// over `(t0, t1)`, give a bracket `(a, b)` with the guard above the
/// surface at `a` and clearly behind it at `b`, or `None`. Clearly
/// means below `-LANDING_DEPTH * g_later`: right after a reset the guard is
/// at round-off level, and a dip of that size is noise, not a landing (a
/// stick–slip reset would otherwise fire again and again at one instant).
/// Called only when `g_later > 3 g(t1)`, which a departure at a finite rate
/// (ratio about 2) does not give, but a short hop does, and a departure
/// from rest (ratio 4 to 8: uplifts, rare, and then nothing is found).
fn landing_near_surface_time<V: FnMut(f64) -> f64>(
    t0: f64,
    t1: f64,
    g_later: f64,
    value: &mut V,
) -> Option<(f64, f64)> {
    let depth = LANDING_DEPTH * g_later;
    let mut probes = [(0.0, 0.0); SURFACE_PROBES];
    let mut n = 0;
    let mut offset = 0.5 * (t1 - t0);
    while n < SURFACE_PROBES {
        let t = t0 + offset;
        if t <= t0 {
            break;
        }
        probes[n] = (t, value(t));
        n += 1;
        offset *= 0.5;
    }
    // The probes run backwards in time; the earliest landing wins.
    let near = probes[..n]
        .iter()
        .rev()
        .zip(probes[..n].iter().rev().skip(1))
        .find(|((_, ga), (_, gb))| *ga > 0.0 && *gb < -depth)
        .map(|((ta, _), (tb, _))| (*ta, *tb));
    if near.is_some() {
        return near;
    }
    // A hop that lands in the later half of the interval and leaves again
    // before its end is between the probes: look at evenly spaced points.
    let mut prev = (t0, 0.0);
    for k in 1..SURFACE_SCAN {
        let t = t0 + (t1 - t0) * (k as f64 / SURFACE_SCAN as f64);
        let g = value(t);
        if prev.1 > 0.0 && g < -depth {
            return Some((prev.0, t));
        }
        prev = (t, g);
    }
    None
}

/// The bracket of a guard that is exactly on its surface at `t0` (just
/// reset onto it) and behind it from then on, with no bump above it in
/// between (`g1` at `t1`, the first sample): `(t0, b)` with `b` the
/// earliest of the offsets halving from `t1 - t0` at which the guard is
/// still clearly behind the surface (deeper than [`LANDING_DEPTH`] of `g1`).
/// So the event falls soon after the reset, with the state hardly moved
/// behind the surface (for g ∝ −(τ − τ0)⁴, at 3 % of the sample interval
/// and 1e-6 of `g1`), yet late enough that what moved it there is no longer
/// at round-off level: at the reset itself the model resolves the new mode
/// from forces that are zero to round-off, and an event there would send
/// it back into the same mode, again and again.
///
/// Found by the extensive stress tier: a block at rest whose uplift moment
/// only touches zero (two-frequency forcing) is lifted at the tangency, and
/// then Θ ∝ −(τ − τ0)⁴: it never leaves its base. Without this the impact
/// guard, which starts on its surface, was never armed, and Θ went on
/// behind the pivot (−2.8e-6 at the end of the step). With it the block
/// lands at once (an impact at Θ' ≈ 0, so it is back at rest).
fn straight_behind_surface<V: FnMut(f64) -> f64>(t0: f64, t1: f64, g1: f64, value: &mut V) -> (f64, f64) {
    let depth = LANDING_DEPTH * g1.abs();
    let mut b = t1;
    let mut offset = 0.5 * (t1 - t0);
    for _ in 0..SURFACE_PROBES {
        let t = t0 + offset;
        if t <= t0 || value(t) >= -depth {
            break;
        }
        b = t;
        offset *= 0.5;
    }
    (t0, b)
}

/// Whether the samples `values` of a guard over a step (start, interior,
/// end, in time order) clear it for the step: all of one sign, `sign`
/// (+1 for an armed guard that must not fall to zero, −1 for an unarmed
/// one that must not rise above it), and farther from zero than
/// [`SCREEN_MARGIN`] times the largest change between neighbours plus
/// `slack`, the possible error of the samples.
#[inline]
fn clears(values: &[f64], sign: f64, slack: f64) -> bool {
    let mut nearest = f64::INFINITY;
    let mut largest_change = 0.0f64;
    for (j, &g) in values.iter().enumerate() {
        nearest = nearest.min(sign * g);
        if j > 0 {
            largest_change = largest_change.max((g - values[j - 1]).abs());
        }
    }
    nearest > 0.0 && nearest > SCREEN_MARGIN * largest_change + slack
}

/// How a guard is screened, by its state at the start of the step.
#[derive(Clone, Copy)]
enum Screening {
    /// Armed and positive: must stay positive.
    Positive,
    /// Unarmed and negative (an observer that fired, or a guard behind its
    /// surface): must stay negative, so it can neither arm nor fire.
    Negative,
    /// Just reset onto its surface (exactly 0): must leave it at once and
    /// stay positive. [`bracket`] arms such a guard at the first sample
    /// above zero and looks for a bump only if that sample is not above
    /// zero, so the screening asks the same of the first sample and the
    /// margin of the rest.
    FromSurface,
}

/// The [`Screening`] of a guard, or `None` when there is no cheap verdict
/// (the dense output decides).
#[inline]
fn screening_case(armed: bool, g_start: f64) -> Option<Screening> {
    if armed && g_start > 0.0 {
        Some(Screening::Positive)
    } else if !armed && g_start < 0.0 {
        Some(Screening::Negative)
    } else if !armed && g_start == 0.0 {
        Some(Screening::FromSurface)
    } else {
        None
    }
}

/// Whether the samples `values` (start, interior, end, in time order) clear
/// a guard screened as `case`.
#[inline]
fn cleared(values: &[f64], case: Screening, slack: f64) -> bool {
    match case {
        Screening::Positive => clears(values, 1.0, slack),
        Screening::Negative => clears(values, -1.0, slack),
        Screening::FromSurface => {
            // The first sample after the surface must be clearly above it
            // (a quarter of the largest change between the later samples),
            // and the later ones clear with the usual margin.
            let rest = &values[2..];
            let largest_change = rest.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
            values[1] > 0.25 * largest_change + slack && values[1] > 0.0 && clears(rest, 1.0, slack)
        }
    }
}

/// Which guards of the step just taken need the high-order dense output:
/// those that are not cleared on the cheap cubic Hermite interpolant.
///
/// First all guards are evaluated at the Hermite midpoint and tested on
/// (start, midpoint, end) with [`clears`]. The guards left are sampled alone
/// at the [`SUBINTERVALS`]` - 1` interior Hermite points (for guards on the
/// state alone that is a few flops each) and tested again on those samples.
/// The Hermite interpolant is accurate to O(h⁴), orders of magnitude below
/// the margin for a step that resolves the state (and steps are capped at
/// the system's time scale for guards that depend on time alone).
fn screen<Sys, S, const N: usize>(
    sys: &Sys,
    mode: Sys::Mode,
    n: usize,
    stepper: &S,
    armed: &[bool; MAX_GUARDS],
    g_start: &[f64; MAX_GUARDS],
    g_end: &[f64; MAX_GUARDS],
) -> [bool; MAX_GUARDS]
where
    Sys: HybridSystem<N>,
    S: Stepper<N>,
{
    let mut need = [true; MAX_GUARDS];
    let (t0, t1) = (stepper.t_prev(), stepper.t());
    let mut ym = [0.0; N];
    let tm = 0.5 * (t0 + t1);
    // Only a step that resolves the explicit time dependence is screened
    // (loose tolerances can take steps of several radians of forcing).
    // Guards read no quadrature: the interpolants skip them.
    let reads = N - Sys::QUADRATURES.min(N);
    if n == 0 || t1 - t0 > sys.time_scale() || !stepper.hermite_leading(tm, &mut ym, reads) {
        return need;
    }
    let mut gm = [0.0; MAX_GUARDS];
    sys.guards(mode, tm, &ym, &mut gm);
    // How far the Hermite values may be off, in each guard's own units: the
    // guards at the midpoint of the quadratic through y0, f0, y1 differ from
    // those of the cubic by about the cubic's third-order term, an
    // overestimate of its error. A guard whose values are not clear of zero
    // by more than that is left to the dense output (this is what catches a
    // guard of size 1e-8 on a step whose Hermite error is 1e-5).
    let mut spread = [0.0; N];
    if !stepper.hermite_spread(&mut spread) {
        return need;
    }
    let yq: [f64; N] = std::array::from_fn(|k| ym[k] - spread[k]);
    let mut gq = [0.0; MAX_GUARDS];
    sys.guards(mode, tm, &yq, &mut gq);
    let mut slack = [0.0; MAX_GUARDS];
    for i in 0..n {
        slack[i] = (gm[i] - gq[i]).abs();
        if !slack[i].is_finite() {
            return need;
        }
    }
    let mut rest = false;
    for i in 0..n {
        let Some(case) = screening_case(armed[i], g_start[i]) else {
            continue;
        };
        // A guard just reset onto its surface needs the finer look: three
        // samples say nothing about how it leaves the surface.
        if !matches!(case, Screening::FromSurface) && cleared(&[g_start[i], gm[i], g_end[i]], case, slack[i]) {
            need[i] = false;
        } else {
            rest = true;
        }
    }
    if !rest {
        return need;
    }
    // The finer look, on the Hermite interpolant.
    let mut ys = [[0.0; N]; SUBINTERVALS + 1];
    let mut ts = [0.0; SUBINTERVALS + 1];
    for j in 1..SUBINTERVALS {
        ts[j] = t0 + (t1 - t0) * (j as f64 / SUBINTERVALS as f64);
        stepper.hermite_leading(ts[j], &mut ys[j], reads);
    }
    // Guards still in question, and all of them per sample if that is
    // cheaper (see `several_costly`).
    let mut open = [false; MAX_GUARDS];
    for i in 0..n {
        open[i] = need[i] && screening_case(armed[i], g_start[i]).is_some();
    }
    let mut all = [[0.0; MAX_GUARDS]; SUBINTERVALS + 1];
    let all_at_once = several_costly(sys, mode, n, &open);
    if all_at_once {
        for j in 1..SUBINTERVALS {
            sys.guards(mode, ts[j], &ys[j], &mut all[j]);
        }
    }
    for i in 0..n {
        let Some(case) = screening_case(armed[i], g_start[i]) else {
            continue;
        };
        if !need[i] {
            continue;
        }
        let mut values = [0.0; SUBINTERVALS + 1];
        values[0] = g_start[i];
        values[SUBINTERVALS] = g_end[i];
        for j in 1..SUBINTERVALS {
            values[j] = if all_at_once {
                all[j][i]
            } else {
                sys.guard(mode, i, ts[j], &ys[j])
            };
        }
        if cleared(&values, case, slack[i]) {
            need[i] = false;
        }
    }
    need
}

/// Whether the guards marked in `need` are cheaper evaluated all at once by
/// [`HybridSystem::guards`] than one by one by [`HybridSystem::guard`]: when
/// at least two are wanted and one of them is not cheap (each costly
/// `guard` call costs about a `guards` call). Same values either way (the
/// contract of `guard`).
fn several_costly<Sys: HybridSystem<N>, const N: usize>(
    sys: &Sys,
    mode: Sys::Mode,
    n: usize,
    need: &[bool; MAX_GUARDS],
) -> bool {
    let wanted = (0..n).filter(|&i| need[i]).count();
    wanted >= 2 && (0..n).any(|i| need[i] && !sys.guard_is_cheap(mode, i))
}

/// The bracket `[a, b]` of the first crossing of guard `i` in one step, if
/// any, including dips between samples. `value` evaluates guard `i` on the
/// step's dense output.
fn bracket<V: FnMut(f64) -> f64>(
    i: usize,
    ts: &[f64; SUBINTERVALS + 1],
    gs: &[[f64; MAX_GUARDS]; SUBINTERVALS + 1],
    armed: &mut bool,
    value: &mut V,
) -> Option<(f64, f64)> {
    for j in 0..SUBINTERVALS {
        let (ga, gb) = (gs[j][i], gs[j + 1][i]);
        if !*armed {
            if ga > 0.0 {
                *armed = true;
            } else {
                if gb > 0.0 {
                    *armed = true;
                    // Reset onto the surface and above it at the next
                    // sample: usually a departure. But a hop shorter than a
                    // sample interval (the last one before an impact
                    // accumulation: Θ' = 1.4e-5 after the impact, back on
                    // the surface 1e-4 τ later, in an interval of 1.9e-3)
                    // lands and dips behind the surface in between, and the
                    // samples then start far from linearly. Only then, look
                    // closer (see `landing_near_surface_time`).
                    if ga == 0.0
                        && j + 2 <= SUBINTERVALS
                        && gs[j + 2][i] > 3.0 * gb
                        && let Some(b) = landing_near_surface_time(ts[j], ts[j + 1], gs[j + 2][i], value)
                    {
                        return Some(b);
                    }
                    continue;
                }
                // Starts on the surface and is behind it at the next sample:
                // a bump above zero in between is a real departure and return
                // (grazing right after a reset). No bump is no event.
                if ga == 0.0 {
                    let (tm, gm) = brent_min(|tt| -value(tt), ts[j], ts[j + 1], 0.0, 100);
                    if -gm > 0.0 && tm < ts[j + 1] {
                        return Some((tm, ts[j + 1]));
                    }
                    // No bump, and behind the surface all through the step:
                    // the state left the new mode's side at once, so the
                    // mode was never right and its guard fires now (see
                    // `straight_behind_surface`).
                    if gs[j + 1..].iter().all(|g| g[i] < 0.0) && gs[SUBINTERVALS][i] < -BEHIND_FLOOR {
                        return Some(straight_behind_surface(ts[j], ts[j + 1], gb, value));
                    }
                }
                continue;
            }
        }
        if ga > 0.0 && gb <= 0.0 {
            return Some((ts[j], ts[j + 1]));
        }
        // Dip check on the parabola through samples j, j+1, j+2.
        if j + 2 <= SUBINTERVALS {
            let gc = gs[j + 2][i];
            if ga > 0.0 && gb > 0.0 && gc > 0.0 {
                let curv = ga - 2.0 * gb + gc;
                if curv > 0.0 {
                    // Vertex offset from sample j+1, in sample spacings.
                    let u = 0.5 * (ga - gc) / curv;
                    let gmin = gb - 0.125 * (ga - gc) * (ga - gc) / curv;
                    let lowest = ga.min(gb).min(gc);
                    if u.abs() < 1.0 && gmin < 0.1 * lowest {
                        let (tm, gm) = brent_min(&mut *value, ts[j], ts[j + 2], 0.0, 100);
                        if gm <= 0.0 {
                            return Some((ts[j], tm));
                        }
                    }
                }
            }
        }
    }
    None
}
