//! One simulation run from an initial state to `tau_end` or a terminal mode.

use std::time::Instant;

use serde::Serialize;

use super::collect::{Collector, HistoryRow, Keep, SectionRow, Sink, Tallies};
use super::end_state::EndState;
pub use super::end_state::Outcome;
use super::method::{Method, StepperVisitor, with_stepper};
use crate::integrate::hybrid::{Advance, Driver, Limits, Outputs};
use crate::integrate::{StepStats, Stepper, Tolerances};
use crate::model::dynamics::Tilt;
use crate::model::system::{EventRecord, FRICTION_LOSS, ModelError, N, Tally, WORK, X};
use crate::model::{Mode, Model, Rocker, RockerVisitor, Sign, with_rocker};

/// Initial state (config `initial.*`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct InitialState {
    /// Θ at τ = 0.
    pub theta: f64,
    /// Θ' at τ = 0.
    pub theta_dot: f64,
    /// X' of the centre of mass at τ = 0. `None`: the value for which the
    /// contact corner does not slip (0 for a flat block).
    pub x_dot: Option<f64>,
}

/// Length of the legs, τ, in which a run with [`RunOptions::rest_after`]
/// advances past that time, checking for rest after each: short enough to
/// stop within a fraction of a second of coming to rest (τ = 1 is 1/p s,
/// 0.1–0.5 s for blocks of 0.1–5 m), long enough to cost nothing.
const REST_CHECK_TAU: f64 = 1.0;

/// How to run (config `run.*`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// End of the run, τ.
    pub tau_end: f64,
    /// Method.
    pub method: Method,
    /// Tolerances (and the fixed step for `ralston`).
    pub tol: Tolerances,
    /// Spacing of the time history; `None` keeps no history.
    pub output_dt: Option<f64>,
    /// Whether to take the stroboscopic section (harmonic excitation only).
    pub section: bool,
    /// Stop as soon as the block is at rest at or after this τ (a record's
    /// end: with the ground still, rest lasts for ever). `None`: run to
    /// `tau_end`.
    pub rest_after: Option<f64>,
    /// Loop bounds.
    pub limits: Limits,
}

/// The energy audit, per m g R (docs/model.md §8):
/// `final − initial = work_base − loss_friction − loss_impact + residual`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnergyAudit {
    /// Mechanical energy (kinetic + potential) at the start.
    pub initial: f64,
    /// Mechanical energy at the end.
    pub r#final: f64,
    /// Work done on the block by the base's pseudo-forces.
    pub work_base: f64,
    /// Energy dissipated by sliding friction.
    pub loss_friction: f64,
    /// Energy lost at impacts.
    pub loss_impact: f64,
    /// What the balance leaves unexplained (integration error).
    pub residual: f64,
    /// `|residual|` relative to the largest term of the balance.
    pub relative_residual: f64,
}

impl EnergyAudit {
    /// The audit of a run from energy `initial` to `r#final` with the base's
    /// work and the two losses: the residual, and it relative to the
    /// largest term.
    pub fn new(initial: f64, r#final: f64, work_base: f64, loss_friction: f64, loss_impact: f64) -> Self {
        let residual = (r#final - initial) - (work_base - loss_friction - loss_impact);
        let scale = initial
            .abs()
            .max(r#final.abs())
            .max(work_base.abs())
            .max(loss_friction.abs())
            .max(loss_impact.abs());
        Self {
            initial,
            r#final,
            work_base,
            loss_friction,
            loss_impact,
            residual,
            relative_residual: if scale > 0.0 { residual.abs() / scale } else { 0.0 },
        }
    }
}

/// Everything a run produces.
#[derive(Clone, Debug)]
pub struct RunResult {
    /// How it ended.
    pub outcome: Outcome,
    /// τ at which it ended (the tumble or flight time for those outcomes).
    pub tau_end: f64,
    /// τ of the tumble, if any.
    pub tumble_tau: Option<f64>,
    /// τ at which |θ| reached π/2 (only when `tumble_theta` >= π/(2ψ)).
    pub side_landing_tau: Option<f64>,
    /// τ of flight, if any.
    pub flight_tau: Option<f64>,
    /// Largest |Θ| reached.
    pub max_abs_theta: f64,
    /// Events in time order.
    pub events: Vec<EventRecord>,
    /// Stroboscopic section points.
    pub section: Vec<SectionRow>,
    /// Regular time history.
    pub history: Vec<HistoryRow>,
    /// Time spent in rest, slide, rock and slide-rock.
    pub mode_time: [f64; 4],
    /// The energy audit.
    pub energy: EnergyAudit,
    /// Stepper work counters.
    pub stats: StepStats,
    /// Wall time of the solver, s.
    pub wall_s: f64,
    /// Tallies of the model (impacts, flight violations).
    pub tally: Tally,
    /// Final mode.
    pub final_mode: Mode,
    /// Final state.
    pub final_state: [f64; N],
    /// What the run passed to its sink (counts) and tallied as it went.
    pub tallies: Tallies,
    /// Largest |sliding displacement| over the run, per R
    /// ([`Geometry::sliding`](crate::model::Geometry::sliding)).
    pub max_abs_sliding: f64,
    /// Sliding displacement at the end, per R (signed, +x to the right).
    pub final_sliding: f64,
}

impl RunResult {
    /// How it ended, in the engineer's words.
    pub fn end_state(&self) -> EndState {
        EndState::of(self.outcome)
    }

    /// τ of the event the run ended on (overturning or flight; the run's
    /// end if the event's own time was not kept), `None` for a run that
    /// ended at rest or moving.
    pub(crate) fn end_event_tau(&self) -> Option<f64> {
        match self.outcome {
            Outcome::Rest | Outcome::Running => None,
            Outcome::Tumbled => self.tumble_tau.or(Some(self.tau_end)),
            Outcome::Flight => self.flight_tau.or(Some(self.tau_end)),
        }
    }
}

/// Errors of a run.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The model or driver failed.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The initial state is not admissible.
    #[error("initial state: {0}")]
    Initial(&'static str),
}

/// The mode and full state a run starts in, before settling.
pub fn initial_mode(model: &Model, init: &InitialState) -> Result<(Mode, [f64; N]), SimError> {
    let geo = &model.geo;
    let mut y = [0.0; N];
    y[0] = init.theta;
    y[1] = init.theta_dot;
    let sliding_allowed = model.mu_s.is_finite();
    if init.theta == 0.0 && init.theta_dot == 0.0 {
        let x_dot = init.x_dot.unwrap_or(0.0);
        y[3] = x_dot;
        if x_dot == 0.0 {
            return Ok((Mode::Rest, y));
        }
        if !sliding_allowed {
            return Err(SimError::Initial(
                "initial.x_dot must be 0 for a flat block when friction is infinite (no sliding)",
            ));
        }
        return Ok((Mode::Slide { slip: Sign::of(x_dot) }, y));
    }
    let pivot = if init.theta != 0.0 {
        Sign::of(init.theta)
    } else {
        Sign::of(init.theta_dot)
    };
    let tilt = Tilt::new(geo, pivot, init.theta);
    // Tipped about its corner from the centred position, so the sliding
    // displacement starts at 0 (docs/model.md §1.7): X₀ = −U's tilt term.
    // Without this a block released tilted reported "sliding" of up to
    // B/2 before it had slid at all.
    y[2] = init.theta.signum() * (geo.sin_psi - (geo.psi * (1.0 - init.theta.abs())).sin());
    let stuck = tilt.c * geo.psi * init.theta_dot;
    let x_dot = init.x_dot.unwrap_or(stuck);
    y[3] = x_dot;
    let slip = x_dot - stuck;
    if slip == 0.0 {
        Ok((Mode::Rock { pivot }, y))
    } else if sliding_allowed {
        Ok((
            Mode::SlideRock {
                pivot,
                slip: Sign::of(slip),
            },
            y,
        ))
    } else {
        Err(SimError::Initial(
            "initial.x_dot must equal the no-slip value cos(ψ(1−|Θ|))·ψΘ' when friction is infinite",
        ))
    }
}

/// Runs `model` from `init` with `opts`, keeping every event, section
/// point and history row in the result.
pub fn simulate(model: Model, init: &InitialState, opts: &RunOptions) -> Result<RunResult, SimError> {
    let mut keep = Keep::default();
    let mut res = simulate_into(model, init, opts, &mut keep)?;
    res.events = keep.events;
    res.section = keep.section;
    res.history = keep.history;
    Ok(res)
}

/// Runs `model` from `init` with `opts`, passing events, section points
/// and history rows to `sink` as they are produced; the result's lists are
/// empty and its [`Tallies`] count what went to the sink. Memory does not
/// grow with the run's length unless the sink keeps what it is given.
pub fn simulate_into(
    model: Model,
    init: &InitialState,
    opts: &RunOptions,
    sink: &mut dyn Sink,
) -> Result<RunResult, SimError> {
    let (mode0, y0) = initial_mode(&model, init)?;
    /// The run, waiting for its stepper.
    struct Run<'a> {
        model: Model,
        mode0: Mode,
        y0: [f64; N],
        opts: &'a RunOptions,
        sink: &'a mut dyn Sink,
    }
    impl StepperVisitor for Run<'_> {
        type Output = Result<RunResult, SimError>;
        fn visit<S: Stepper<N> + Send + 'static>(self, stepper: S) -> Self::Output {
            /// The run with its stepper, waiting for the model's system.
            struct WithStepper<'a, S> {
                stepper: S,
                mode0: Mode,
                y0: [f64; N],
                opts: &'a RunOptions,
                sink: &'a mut dyn Sink,
            }
            impl<S: Stepper<N>> RockerVisitor for WithStepper<'_, S> {
                type Output = Result<RunResult, SimError>;
                fn visit<R: Rocker>(self, system: R) -> Self::Output {
                    run_with(self.stepper, system, self.mode0, self.y0, self.opts, self.sink)
                }
            }
            let next = WithStepper {
                stepper,
                mode0: self.mode0,
                y0: self.y0,
                opts: self.opts,
                sink: self.sink,
            };
            with_rocker(self.model, next)
        }
    }
    let run = Run {
        model,
        mode0,
        y0,
        opts,
        sink,
    };
    with_stepper(opts.method, opts.tol, run)
}

fn run_with<S: Stepper<N>, R: Rocker>(
    stepper: S,
    mut system: R,
    mode0: Mode,
    mut y0: [f64; N],
    opts: &RunOptions,
    sink: &mut dyn Sink,
) -> Result<RunResult, SimError> {
    let start = Instant::now();
    let section_period = if opts.section {
        system.params().excitation.forcing_period()
    } else {
        None
    };
    let mode0 = system.settle_mode(mode0, 0.0, &mut y0);
    let e0 = system.mechanical_energy(mode0, &y0);
    let outputs = Outputs {
        sample_dt: opts.output_dt,
        section_period,
    };
    let mut driver = Driver::new(stepper, system, mode0, 0.0, y0, opts.limits, outputs);
    let geometry = driver.system().params().geo;
    let mut obs = Collector {
        sink,
        keep_history: opts.output_dt.is_some(),
        geometry,
        mode: mode0,
        mode_since: 0.0,
        tallies: Tallies {
            max_abs_theta: y0[0].abs(),
            max_abs_sliding: geometry.sliding(y0[0], y0[X]).abs(),
            ..Tallies::default()
        },
    };
    match opts.rest_after {
        None => match section_period.filter(|_| obs.sink.watches()) {
            // Legs of one forcing period, each ending on a section time,
            // all with the run's end as horizon: the same steps as one
            // advance to `tau_end`, so a watched run that is not stopped
            // ends bit for bit as an unwatched one.
            Some(period) => {
                while driver.t() < opts.tau_end && !obs.sink.settled() {
                    let next = ((driver.t() / period).floor() + 1.0) * period;
                    let leg = driver.advance_past(next.min(opts.tau_end), opts.tau_end, &mut obs)?;
                    if matches!(leg, Advance::Terminal) {
                        break;
                    }
                }
            }
            None => {
                driver.advance(opts.tau_end, &mut obs)?;
            }
        },
        Some(rest_after) => {
            driver.advance(rest_after.min(opts.tau_end), &mut obs)?;
            // After the record the ground is still, so rest is for ever:
            // go on in short legs and stop at the first that ends at rest.
            while driver.t() < opts.tau_end
                && matches!(
                    driver.mode(),
                    Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. }
                )
            {
                driver.advance((driver.t() + REST_CHECK_TAU).min(opts.tau_end), &mut obs)?;
            }
        }
    }
    let wall_s = start.elapsed().as_secs_f64();

    let final_mode = driver.mode();
    let y = *driver.y();
    let t_final = driver.t();
    let system = driver.system();
    let tally = system.tallied();

    // Time per mode: the collector's sums up to the last event, plus the
    // mode the run ended in up to its end.
    let tallies = obs.tallies;
    let mut mode_time = tallies.mode_time;
    if obs.mode.index() < 4 {
        mode_time[obs.mode.index()] += (t_final - obs.mode_since).max(0.0);
    }
    let tumble_tau = tallies.tumble_tau;
    let side_landing_tau = if system.overturn_angle() >= system.params().geo.side_theta() {
        tumble_tau
    } else {
        None
    };
    let flight_tau = if final_mode == Mode::Flight {
        tallies.last_event_tau
    } else {
        None
    };
    let outcome = match final_mode {
        Mode::Tumbled => Outcome::Tumbled,
        Mode::Flight => Outcome::Flight,
        Mode::Rest => Outcome::Rest,
        Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. } => Outcome::Running,
    };

    let e_final = system.end_energy(final_mode, &y);
    let (work, friction, impact) = (y[WORK], y[FRICTION_LOSS], tally.impact_loss);
    let energy = EnergyAudit::new(e0, e_final, work, friction, impact);
    let max_abs_theta = tallies.max_abs_theta.max(tally.max_abs_theta).max(y[0].abs());
    let final_sliding = geometry.sliding(y[0], y[X]);
    let max_abs_sliding = tallies.max_abs_sliding.max(final_sliding.abs());
    let mut stats = driver.stepper().stats();
    stats.accepted = stats.accepted.max(driver.steps());
    Ok(RunResult {
        outcome,
        tau_end: t_final,
        tumble_tau,
        side_landing_tau,
        flight_tau,
        max_abs_theta,
        events: Vec::new(),
        section: Vec::new(),
        history: Vec::new(),
        mode_time,
        energy,
        stats,
        wall_s,
        tally,
        final_mode,
        final_state: y,
        tallies,
        max_abs_sliding,
        final_sliding,
    })
}
