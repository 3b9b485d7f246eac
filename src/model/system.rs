//! The block as a hybrid system: vector field per mode, guards, reset maps.
//!
//! State `y = [Θ, Θ', X, X', W, D]` (`state`); parameters [`Model`]
//! (`params`). The vector field and guards are here, the reset maps and the
//! consistency of a freshly entered mode in `reset`.
//!
//! Guard indices per mode (each guard is positive inside the mode):
//!
//! | mode | 0 | 1 | 2 | 3 | 4 | 5 |
//! |---|---|---|---|---|---|---|
//! | rest | flight b | uplift right κ₊ | uplift left κ₋ | slide +x μ_s b + a | slide −x μ_s b − a | |
//! | slide σ | stick σX' | flight b | | | | |
//! | rock s | impact sΘ | tumble Θ_t − sΘ | flight n | extremum sΘ' (observer) | slip μ_s n − sf | slip μ_s n + sf |
//! | slide-rock s,σ | impact sΘ | tumble Θ_t − sΘ | flight n | extremum sΘ' (observer) | stick σX_p' | |
//!
//! Slide guards exist only with finite friction. With `flight = ignore` the
//! flight guard only counts violations.

mod reset;

use std::cell::Cell;

pub(crate) use self::reset::{Settles, accumulated, rock_from_flat, uplift};
use super::ad::Scalar;
use super::dynamics::{self, Accel, Forcing, Tilt};
use super::energy;
use super::mode::{Mode, Sign};
use super::params::{FlightPolicy, Model};
// Re-exported: the driver, outputs, analyses, tests and benches index the
// state by these paths.
use super::excitation::Excitation;
pub use super::state::{FRICTION_LOSS, N, THETA, THETA_DOT, WORK, X, X_DOT};
use crate::integrate::StepError;
use crate::integrate::hybrid::{DriverError, HybridSystem, Jump, MAX_GUARDS};

/// The parts of [`HybridSystem`] the one-body models (the block, the
/// frame) share: their mode, record and error types, their terminal modes,
/// and the clock of the excitation in `self.model.excitation` (its
/// breakpoints and time scale, and a step cap at rest), and rest as the
/// mode that stands still.
macro_rules! one_body_system {
    () => {
        type Mode = $crate::model::mode::Mode;
        type Record = $crate::model::system::EventRecord;
        type Error = $crate::model::system::ModelError;

        fn is_terminal(&self, mode: $crate::model::mode::Mode) -> bool {
            mode.is_terminal()
        }

        fn next_breakpoint(&self, t: f64) -> Option<f64> {
            self.model.excitation.next_breakpoint(t)
        }

        fn time_scale(&self) -> f64 {
            self.model.excitation.time_scale()
        }

        /// At rest the field is zero whatever the state (`rhs` writes
        /// zeros for `Rest`).
        fn is_still(&self, mode: $crate::model::mode::Mode, _y: &[f64; $crate::model::system::N]) -> bool {
            mode == $crate::model::mode::Mode::Rest
        }

        fn step_cap(&self, mode: $crate::model::mode::Mode) -> f64 {
            // At rest the state does not move and every guard is a function
            // of the forcing alone; in the other modes the forcing drives
            // the state, whose error control resolves it.
            match mode {
                $crate::model::mode::Mode::Rest => self.model.excitation.time_scale(),
                _ => f64::INFINITY,
            }
        }
    };
}
pub(crate) use one_body_system;

/// Kind of event, as written in `events.csv`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// A corner leaves the base (rest/slide → rock/slide-rock).
    Uplift,
    /// Contact starts to slip (or reverses its slip).
    Slip,
    /// Slipping contact sticks.
    Stick,
    /// The lifted corner strikes the base at Θ = 0.
    Impact,
    /// The block comes to rest after an accumulation of impacts.
    Rest,
    /// |Θ| reached the tumble angle.
    Tumble,
    /// The normal force vanished.
    Flight,
}

impl EventKind {
    /// Name used in `events.csv`.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Uplift => "uplift",
            EventKind::Slip => "slip",
            EventKind::Stick => "stick",
            EventKind::Impact => "impact",
            EventKind::Rest => "rest",
            EventKind::Tumble => "tumble",
            EventKind::Flight => "flight",
        }
    }
}

/// One event, as reported to observers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventRecord {
    /// Time of the event (for `Rest` after accumulation, the accumulation
    /// time).
    pub tau: f64,
    /// What happened.
    pub kind: EventKind,
    /// Mode before.
    pub before: Mode,
    /// Mode after (after any immediate follow-up switch at the same instant).
    pub after: Mode,
    /// Θ at the event.
    pub theta: f64,
    /// Θ' just before.
    pub theta_dot_before: f64,
    /// Θ' just after.
    pub theta_dot_after: f64,
    /// X' just after.
    pub x_dot: f64,
    /// X at the event (positions do not jump, so before = after).
    pub x: f64,
}

impl EventRecord {
    /// The record of a switch at `t` from `before` with state `y` to
    /// `after` with state `yn`.
    pub(crate) fn switch(kind: EventKind, t: f64, before: Mode, after: Mode, y: &[f64; N], yn: &[f64; N]) -> Self {
        Self {
            tau: t,
            kind,
            before,
            after,
            theta: y[THETA],
            theta_dot_before: y[THETA_DOT],
            theta_dot_after: yn[THETA_DOT],
            x_dot: yn[X_DOT],
            x: yn[X],
        }
    }
}
/// Things the system tallies as it runs, beyond the state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Energy lost at impacts (and in summed accumulations), per m g R.
    pub impact_loss: f64,
    /// Times the normal force vanished while `flight = ignore`.
    pub flight_violations: u64,
    /// Largest |Θ| at an extremum.
    pub max_abs_theta: f64,
    /// Impacts.
    pub impacts: u64,
    /// Y' with which an impact threw the block off the base (flight by
    /// vertical restitution), kept for the final energy.
    pub lift_off_y_dot: Option<f64>,
}

/// The block as a [`HybridSystem`].
#[derive(Clone, Debug)]
pub struct BlockSystem {
    /// Parameters.
    pub model: Model,
    /// Tallies.
    pub tally: Tally,
    /// The forcing at the time of the last evaluation.
    last_forcing: LastForcing,
}

/// The forcing at the time of the last evaluation: the guards at a step's
/// end are evaluated at the time of its last (FSAL) right-hand side and
/// reuse its sine. Same bits either way. Kept by the block and the frame.
#[derive(Clone, Debug)]
pub(crate) struct LastForcing(Cell<(f64, Forcing)>);

impl LastForcing {
    /// Nothing remembered yet (no time equals NaN).
    pub(crate) fn new() -> Self {
        Self(Cell::new((f64::NAN, Forcing { a: 0.0, av: 0.0 })))
    }

    /// The forcing of `excitation` at `t`, remembered for the next call at
    /// the same `t`.
    #[inline]
    pub(crate) fn at(&self, excitation: &Excitation, t: f64) -> Forcing {
        let (tl, fl) = self.0.get();
        if tl.to_bits() == t.to_bits() {
            return fl;
        }
        let fo = excitation.forcing(t);
        self.0.set((t, fo));
        fo
    }
}

/// A jump of a one-body model (the block's, the frame's).
pub(crate) type ModelJump = Jump<Mode, EventRecord, N>;

/// A jump to `mode` at `t` with state `y`, recording `record` if any.
pub(crate) fn jump_to(mode: Mode, t: f64, y: [f64; N], record: Option<EventRecord>) -> ModelJump {
    Jump {
        mode,
        t,
        y,
        records: [record, None],
    }
}

/// Errors from the model side of a run.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// The driver failed. Shown with the block's own clock: the driver's
    /// independent variable is the dimensionless time τ, which a user
    /// reads as "τ" to a few decimals (the driver's message names a
    /// generic "t" with all 17 digits).
    #[error("{}", driver_message(.0))]
    Driver(#[from] DriverError),
}

/// `e` in the block's words: τ instead of the integrator's t, to four
/// decimals (a step or event is found to far better than that, but a
/// person reads where the run stopped, not its last bits).
fn driver_message(e: &DriverError) -> String {
    match *e {
        DriverError::Step(StepError::StepSizeUnderflow { t, h }) => {
            format!("step size underflow at τ = {t:.4} (h = {h:.1e})")
        }
        DriverError::Step(StepError::NonFinite { t }) => format!("non-finite state at τ = {t:.4}"),
        DriverError::TooManySteps { t, limit } => format!("more than {limit} steps by τ = {t:.4}"),
        DriverError::TooManyEvents { t, limit } => format!("more than {limit} events by τ = {t:.4}"),
        DriverError::TimeReversal { t } => format!("reset map moved time backwards at τ = {t:.4}"),
    }
}

impl BlockSystem {
    /// A system for `model` with zeroed tallies.
    pub fn new(model: Model) -> Self {
        Self {
            model,
            tally: Tally::default(),
            last_forcing: LastForcing::new(),
        }
    }

    /// The forcing at `t`, remembered for the next call at the same `t`.
    #[inline]
    fn forcing(&self, t: f64) -> Forcing {
        self.last_forcing.at(&self.model.excitation, t)
    }

    /// The effective tumble angle: `tumble_theta` capped at the side landing.
    pub(crate) fn tumble_angle(&self) -> f64 {
        tumble_angle(&self.model)
    }

    fn friction_finite(&self) -> bool {
        self.model.mu_s.is_finite()
    }

    fn stops_at_flight(&self) -> bool {
        self.model.flight == FlightPolicy::Stop
    }

    /// Accelerations and contact forces of `mode` at `(t, y)`.
    pub fn accel(&self, mode: Mode, t: f64, y: &[f64; N]) -> Accel {
        let fo = self.model.excitation.forcing(t);
        self.accel_with(mode, fo, y)
    }

    fn accel_with(&self, mode: Mode, fo: Forcing, y: &[f64; N]) -> Accel {
        accel_of(&self.model, mode, fo, y)
    }

    /// Normal and horizontal contact force per unit weight (what the app
    /// plots).
    pub(crate) fn base_forces(&self, mode: Mode, t: f64, y: &[f64; N]) -> (f64, f64) {
        let acc = self.accel(mode, t, y);
        (acc.normal, acc.friction)
    }

    /// Mechanical energy / (m g R) of `y` in `mode`.
    pub fn energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        energy::total(&self.model.geo, mode, y[THETA], y[THETA_DOT], y[X_DOT])
    }

    /// Mechanical energy at the end of a run: as [`energy`](Self::energy),
    /// except that a block thrown off the base by an impact keeps the
    /// vertical velocity it left with.
    pub(crate) fn final_energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        match (mode, self.tally.lift_off_y_dot) {
            (Mode::Flight, Some(y_dot)) => {
                let geo = &self.model.geo;
                energy::kinetic(geo, y[X_DOT], y_dot, y[THETA_DOT]) + geo.cos_psi
            }
            _ => self.energy(mode, y),
        }
    }
}

/// The effective tumble angle of `model`: `tumble_theta` capped at the side
/// landing.
pub(crate) fn tumble_angle(model: &Model) -> f64 {
    model.tumble_theta.min(model.geo.side_theta())
}

/// Accelerations and contact forces of `mode` at forcing `fo` and state `y`.
#[inline]
fn accel_of<S: Scalar>(model: &Model, mode: Mode, fo: Forcing<S>, y: &[S; N]) -> Accel<S> {
    let geo = &model.geo;
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => dynamics::rest(fo),
        Mode::Slide { slip } => dynamics::slide(slip, model.mu_k, fo),
        Mode::Rock { pivot } => dynamics::rock_at(geo, pivot, Tilt::of(geo, pivot, y[THETA]), y[THETA_DOT], fo),
        Mode::SlideRock { pivot, slip } => dynamics::slide_rock_at(
            geo,
            pivot,
            slip,
            model.mu_k,
            Tilt::of(geo, pivot, y[THETA]),
            y[THETA_DOT],
            fo,
        ),
    }
}

/// The guards of `mode` (the table in the module docs) at forcing `fo` and
/// state `y`, written once over a generic scalar: over `f64` for the
/// driver, over dual numbers for their gradients (`variational`). Returns
/// how many there are; `tumble` is [`tumble_angle`].
#[inline]
pub(crate) fn guard_values<S: Scalar>(
    model: &Model,
    tumble: f64,
    mode: Mode,
    fo: Forcing<S>,
    y: &[S; N],
    g: &mut [S; MAX_GUARDS],
) -> usize {
    let geo = &model.geo;
    let mu_s = model.mu_s;
    let friction_finite = mu_s.is_finite();
    match mode {
        Mode::Tumbled | Mode::Flight => 0,
        Mode::Rest => {
            let b = fo.b();
            // Flight first: when b reaches 0 the uplift guards κ = b sin ψ
            // ± a cos ψ may reach 0 at the same instant, and ties go to
            // the lowest index.
            g[0] = b;
            g[1] = dynamics::restoring(geo, Sign::Pos, fo);
            g[2] = dynamics::restoring(geo, Sign::Neg, fo);
            if friction_finite {
                g[3] = b * mu_s + fo.a;
                g[4] = b * mu_s - fo.a;
                5
            } else {
                3
            }
        }
        Mode::Slide { slip } => {
            g[0] = y[X_DOT] * slip.value();
            g[1] = fo.b();
            2
        }
        Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => {
            let s = pivot.value();
            let acc = accel_of(model, mode, fo, y);
            g[0] = y[THETA] * s;
            // tumble − sΘ, with the bits of the subtraction.
            g[1] = -(y[THETA] * s) + tumble;
            g[2] = acc.normal;
            g[3] = y[THETA_DOT] * s;
            match mode {
                Mode::SlideRock { slip, .. } => {
                    let c = Tilt::of(geo, pivot, y[THETA]).c;
                    let vp = y[X_DOT] - c * geo.psi * y[THETA_DOT];
                    g[4] = vp * slip.value();
                    5
                }
                _ if friction_finite => {
                    let f_side = acc.friction * s;
                    g[4] = acc.normal * mu_s - f_side;
                    g[5] = acc.normal * mu_s + f_side;
                    6
                }
                _ => 4,
            }
        }
    }
}

impl HybridSystem<N> for BlockSystem {
    one_body_system!();

    /// W and D: the vector field reads Θ, Θ' and X' only.
    const QUADRATURES: usize = 2;

    #[inline]
    fn rhs(&self, mode: Mode, t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        *dy = dynamics::field(&self.model.geo, self.model.mu_k, mode, self.forcing(t), y);
    }

    #[inline]
    fn taylor(&self, mode: Mode, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        super::series::taylor(&self.model, mode, t, y, order, c)
    }

    fn guards(&self, mode: Mode, t: f64, y: &[f64; N], g: &mut [f64; MAX_GUARDS]) -> usize {
        guard_values(&self.model, self.tumble_angle(), mode, self.forcing(t), y, g)
    }

    #[inline]
    fn guard(&self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> f64 {
        // The geometric guards of the rocking modes need neither the
        // forcing nor the contact forces; the same expressions as `guards`.
        match (mode, index) {
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 0) => pivot.value() * y[THETA],
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 1) => self.tumble_angle() - pivot.value() * y[THETA],
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 3) => pivot.value() * y[THETA_DOT],
            (Mode::SlideRock { pivot, slip }, 4) => {
                let vp = dynamics::pivot_slip_velocity(&self.model.geo, pivot, y[THETA], y[THETA_DOT], y[X_DOT]);
                slip.value() * vp
            }
            (Mode::Slide { slip }, 0) => slip.value() * y[X_DOT],
            _ => {
                let mut g = [0.0; MAX_GUARDS];
                self.guards(mode, t, y, &mut g);
                g[index]
            }
        }
    }

    /// The flight guard of rocking, n > 0, from a bound over the step: with
    /// |ψΘ''| ≤ b_max + a_max at every state and time, |Θ'| along the step
    /// is at most (|Θ'₀| + |Θ'₁| + h M)/2 (it can grow at rate M from either
    /// end), |Θ| at most (|Θ₀| + |Θ₁| + h V)/2 likewise, and
    /// [`dynamics::rock_normal_lower_bound`] bounds n over those states and
    /// every forcing the excitation can give. On the paper's scenes the
    /// bound is about 0.6 against n ≈ 0.9: long steps at loose tolerances
    /// then sample only the geometric guards, which need no forcing.
    fn guard_stays_positive(&self, mode: Mode, index: usize, h: f64, y0: &[f64; N], y1: &[f64; N]) -> bool {
        if !matches!(mode, Mode::Rock { .. }) || index != 2 {
            return false;
        }
        let Some((a_max, av_max)) = self.model.excitation.peak_accel() else {
            return false;
        };
        let geo = &self.model.geo;
        let m = (1.0 + av_max + a_max) * geo.inv_psi;
        let v = 0.5 * (y0[THETA_DOT].abs() + y1[THETA_DOT].abs() + h * m);
        let th = 0.5 * (y0[THETA].abs() + y1[THETA].abs() + h * v);
        // Far above round-off and the interpolant's error, far below the
        // bound's own slack.
        const MARGIN: f64 = 1e-3;
        dynamics::rock_normal_lower_bound(geo, th, v, a_max, 1.0 - av_max) > MARGIN
    }

    /// Θ for the impact and tumble guards, Θ and Θ' for the extremum and
    /// for every guard of rocking about a stuck corner (its forces, hence
    /// the flight and slip-onset guards, depend on the tilt and its rate
    /// alone: `dynamics::rock_at`); the rest read Θ, Θ', X and X' (through
    /// the forces, or the pivot's slip).
    fn guard_reads(&self, mode: Mode, index: usize) -> usize {
        match (mode, index) {
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 0 | 1) => THETA + 1,
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 3) => THETA_DOT + 1,
            (Mode::Rock { .. }, _) => THETA_DOT + 1,
            _ => N - Self::QUADRATURES,
        }
    }

    /// The guards `guard` evaluates without the forcing and the contact
    /// forces (its special cases).
    fn guard_is_cheap(&self, mode: Mode, index: usize) -> bool {
        matches!(
            (mode, index),
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 0 | 1 | 3)
                | (Mode::SlideRock { .. }, 4)
                | (Mode::Slide { .. }, 0)
        )
    }

    fn is_observer(&self, mode: Mode, index: usize) -> bool {
        match mode {
            Mode::Rock { .. } | Mode::SlideRock { .. } => index == 3 || (index == 2 && !self.stops_at_flight()),
            Mode::Rest => index == 0 && !self.stops_at_flight(),
            Mode::Slide { .. } => index == 1 && !self.stops_at_flight(),
            Mode::Tumbled | Mode::Flight => false,
        }
    }

    /// The extremum observer of rocking records the largest |Θ|: its root
    /// in `[ta, tb]`, where Θ' = 0, is within `M (tb − ta)²/2` of Θ at
    /// either end (Taylor's theorem with |Θ''| ≤ M = (b_max + a_max)/ψ, the
    /// bound of `guard_stays_positive`), so when that stays at or below the
    /// largest |Θ| so far the root cannot raise it and is not located (most
    /// extrema of a run that has settled into its range). Slide-rock, whose
    /// Θ'' has no such simple bound, and the flight observer always record.
    fn observer_may_record(&self, mode: Mode, index: usize, ta: f64, ya: &[f64; N], tb: f64, yb: &[f64; N]) -> bool {
        if !matches!(mode, Mode::Rock { .. }) || index != 3 {
            return true;
        }
        let Some((a_max, av_max)) = self.model.excitation.peak_accel() else {
            return true;
        };
        let m = (1.0 + av_max + a_max) * self.model.geo.inv_psi;
        let dt = tb - ta;
        // The samples are the dense output, within the tolerance of the
        // solution: a margin far above that.
        const MARGIN: f64 = 1e-6;
        let peak = ya[THETA].abs().max(yb[THETA].abs()) + 0.5 * m * dt * dt + MARGIN;
        !(peak.is_finite() && peak <= self.tally.max_abs_theta)
    }

    fn observe(&mut self, mode: Mode, index: usize, _t: f64, y: &[f64; N]) {
        match (mode, index) {
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 3) => {
                self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs());
            }
            _ => self.tally.flight_violations += 1,
        }
    }

    fn jump(&mut self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> Result<ModelJump, ModelError> {
        let mut yn = *y;
        let jump = match (mode, index) {
            (Mode::Rest, 1 | 2) => self.simple(EventKind::Uplift, mode, uplift(index, &mut yn), t, y, yn),
            (Mode::Rest, 0) | (Mode::Slide { .. }, 1) | (Mode::Rock { .. } | Mode::SlideRock { .. }, 2) => {
                self.simple(EventKind::Flight, mode, Mode::Flight, t, y, yn)
            }
            (Mode::Rest, _) => {
                let slip = if index == 3 { Sign::Pos } else { Sign::Neg };
                yn[X_DOT] = 0.0;
                self.simple(EventKind::Slip, mode, Mode::Slide { slip }, t, y, yn)
            }
            (Mode::Slide { .. }, _) => {
                yn[X_DOT] = 0.0;
                self.simple(EventKind::Stick, mode, Mode::Rest, t, y, yn)
            }
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 0) => self.impact(mode, pivot, t, y),
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 1) => {
                self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs());
                self.simple(EventKind::Tumble, mode, Mode::Tumbled, t, y, yn)
            }
            (Mode::Rock { pivot }, _) => {
                // Guard 4: s f reached μ_s n, friction pushes towards s, the
                // corner slips towards −s; guard 5 the other way.
                let slip = if index == 4 { pivot.flip() } else { pivot };
                self.simple(EventKind::Slip, mode, Mode::SlideRock { pivot, slip }, t, y, yn)
            }
            (Mode::SlideRock { pivot, .. }, _) => {
                let tilt = Tilt::new(&self.model.geo, pivot, y[THETA]);
                yn[X_DOT] = tilt.c * self.model.geo.psi * y[THETA_DOT];
                self.simple(EventKind::Stick, mode, Mode::Rock { pivot }, t, y, yn)
            }
            (Mode::Tumbled | Mode::Flight, _) => jump_to(mode, t, yn, None),
        };
        Ok(jump)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_run_says_where_in_tau_to_four_decimals() {
        let e = ModelError::from(DriverError::Step(StepError::NonFinite { t: 21.21694493994567 }));
        assert_eq!(e.to_string(), "non-finite state at τ = 21.2169");
        let e = ModelError::from(DriverError::Step(StepError::StepSizeUnderflow {
            t: 3.000_000_000_1,
            h: 1.234e-17,
        }));
        assert_eq!(e.to_string(), "step size underflow at τ = 3.0000 (h = 1.2e-17)");
        let e = ModelError::from(DriverError::TooManyEvents { t: 7.5, limit: 100 });
        assert_eq!(e.to_string(), "more than 100 events by τ = 7.5000");
    }
}
