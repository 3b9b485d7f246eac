//! The driver: its state, the stepping loop, a step of an adaptive method
//! up to the screening, a step without an event, and jumps.

use super::screen::screen;
use super::{Field, HybridSystem, MAX_GUARDS, Observer};
use crate::integrate::stepper::{StepError, Stepper};

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
    /// Whether a step from a state where the system's field is zero
    /// ([`HybridSystem::is_still`]: a body at rest on its base) is taken
    /// without evaluating the field ([`Stepper::step_still`]). Default
    /// `true`. Like the screening it must change nothing, bit for bit
    /// (`tests/stack.rs` runs the stack presets both ways); `false` is
    /// there for that test.
    #[serde(default = "yes")]
    pub still: bool,
}

/// [`Limits::still`]'s default in a file written before it existed.
fn yes() -> bool {
    true
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_steps: 1_000_000_000,
            max_events: 100_000_000,
            screening: true,
            still: true,
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
    pub(super) stepper: S,
    pub(super) system: Sys,
    pub(super) mode: Sys::Mode,
    pub(super) limits: Limits,
    pub(super) outputs: Outputs,
    pub(super) steps: u64,
    pub(super) events: u64,
    /// Index of the next regular sample (`t = k · sample_dt`).
    pub(super) next_sample: u64,
    /// Index of the next section point (`t = k · period`).
    pub(super) next_section: u64,
    /// Guard values at the start of the current segment.
    pub(super) g_start: [f64; MAX_GUARDS],
    pub(super) n_guards: usize,
    /// Whether each guard has been positive since the last restart.
    pub(super) armed: [bool; MAX_GUARDS],
    /// Steps cleared by the cheap screening (no dense output needed).
    pub(super) screened: u64,
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
    pub(crate) fn system_mut(&mut self) -> &mut Sys {
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
    pub(crate) fn reinit(&mut self, mode: Sys::Mode, t: f64, y: [f64; N]) {
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
    /// output does not shorten a step to land on `t_end` but on `horizon`
    /// (when it is later; once past `horizon`, on `t_end` again): the step
    /// that reaches `t_end` is taken whole,
    /// with its outputs (samples, section points, its event), so the driver
    /// may stand past `t_end` afterwards. A run advanced so, in pieces of
    /// any size with one horizon, takes the same steps as one advanced to
    /// the horizon in a single call: the live session's chunks, with the
    /// batch run's end as horizon, follow the batch run bit for bit. The
    /// horizon must be finite: a step that no dynamics limits (a block at
    /// rest on a still base, whose Taylor series is its constant state)
    /// runs to it in one step. The paper's fixed-step method steps onto
    /// `t_end`, as in `advance` (it stops on the section times too, which
    /// the live session's chunk ends are).
    pub(crate) fn advance_past<O>(&mut self, t_end: f64, horizon: f64, obs: &mut O) -> Result<Advance, Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let horizon = if self.stepper.locates_by_root() { horizon } else { t_end };
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
            // Past the horizon (a chunk that ends after it), steps end on
            // `t_end` again.
            let t_stop = self.next_stop(t, if horizon > t { horizon } else { t_end });
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
            // A body at rest: the same step without evaluating the field.
            if self.limits.still && sys.is_still(mode, &y0) {
                debug_assert!(
                    {
                        let mut dy = [1.0; N];
                        sys.rhs(mode, stepper.t(), &y0, &mut dy);
                        dy.iter().all(|&d| d == 0.0)
                    },
                    "is_still holds where the field is not zero: {mode:?} at t = {}",
                    stepper.t()
                );
                stepper.step_still(&f, t_stop)
            } else {
                stepper.step(&f, t_stop)
            }
            .map_err(DriverError::from)?;
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
    pub(super) fn accept<O>(&mut self, armed: [bool; MAX_GUARDS], g_end: [f64; MAX_GUARDS], obs: &mut O)
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

    pub(super) fn apply_jump<O>(&mut self, i: usize, t_ev: f64, y_ev: [f64; N], obs: &mut O) -> Result<(), Sys::Error>
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
}
