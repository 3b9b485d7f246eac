//! The messages between the simulation thread ([`super::runner`]) and its
//! user (the desktop app, or a test).
//!
//! Contract:
//! - Every update carries the [`RunId`] of the run that produced it. A run is
//!   one continuous trajectory: a reset, new parameters (from τ = 0 or
//!   from the state shown), a new section phase or a perturbed restart
//!   start a new run with a new id, so data of a run that was replaced can
//!   be recognised and dropped.
//! - Within one run, updates arrive in the order they were produced, and the
//!   samples, events and section points inside a [`Batch`] are in time order
//!   and continue those of the previous batch of the same run.
//! - Every number in an update is finite: a run whose state turns
//!   non-finite ends with [`SimUpdate::Finished`] carrying the error instead.
//! - The end of a run is an explicit [`SimUpdate::Finished`] message, never
//!   just silence or a closed channel.
//! - Units are the normalised ones of MODEL-DECISIONS (τ = p t, Θ = θ/ψ,
//!   X = x/R, accelerations per unit g) unless a field says metres.
//!
//! This module knows nothing of windows; the app turns these into pictures.

use super::{EndState, HistoryRow, Scenario};
use crate::model::geometry::Geometry;
use crate::model::stack::{
    Contact, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, Slip, StackEnd, StackEvent, StackGeometry, StackMode,
};
use crate::model::system::EventRecord;
use crate::model::{Mode, Sign, energy, kinematics};

/// Identifies one run (one continuous trajectory). Ids increase by one with
/// every new run started through one [`super::runner::SimHandle`]; the first
/// run has id 1, so `RunId(0)` never names a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RunId(pub u64);

/// How fast the simulation runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Speed {
    /// A multiple of real time in the block's physical seconds
    /// (1 s = p τ). Clamped to [[`Speed::MIN_MULTIPLE`], [`Speed::MAX_MULTIPLE`]].
    RealTime(f64),
    /// As fast as the thread can integrate.
    Max,
}

impl Speed {
    /// Slowest playback, ×0.1: slow enough to follow one impact of the
    /// paper's block by eye.
    pub(crate) const MIN_MULTIPLE: f64 = 0.1;
    /// Fastest paced playback, ×1000; beyond that use [`Speed::Max`].
    pub(crate) const MAX_MULTIPLE: f64 = 1000.0;
}

impl Default for Speed {
    /// Real time: what a lecture audience expects to see.
    fn default() -> Self {
        Speed::RealTime(1.0)
    }
}

/// Where a run with new parameters starts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum StartFrom {
    /// τ = 0 and the configuration's initial state: the run the batch CLI
    /// computes for the same configuration.
    #[default]
    Initial,
    /// The state shown now (the last sample released: Θ, Θ', X, X', the
    /// mode) at the τ shown now, so the forcing phase runs on without a
    /// jump: what DynamicalSystems.jl's interactive apps do when a
    /// parameter is dragged, and what lets the eye follow an attractor as
    /// it changes. Falls back to [`StartFrom::Initial`] when there is no
    /// state to continue (the run ended, or never started) or the state is
    /// not admissible under the new parameters.
    Current,
}

/// Commands to the simulation thread.
#[derive(Clone, Debug)]
pub(crate) enum SimCommand {
    /// Start a new run with this configuration, from τ = 0 and its initial
    /// state or from the state shown now (`from`). The run's `run.tau_end`
    /// is ignored: a live run goes on until it reaches a terminal mode or
    /// is replaced.
    SetParams {
        /// Id of the new run.
        run: RunId,
        /// The validated configuration.
        scenario: Box<Scenario>,
        /// Where the new run starts.
        from: StartFrom,
    },
    /// Take stroboscopic section points at forcing phase `phase` from now
    /// on, τ_k = (2πk + φ)/Ω_h: a new run of the same configuration from
    /// the state shown now (as [`StartFrom::Current`]), so the motion goes
    /// on and only the section changes. The phase is kept for later runs.
    SetSectionPhase {
        /// Id of the new run.
        run: RunId,
        /// φ, rad; taken modulo 2π.
        phase: f64,
    },
    /// Restart the current configuration from τ = 0.
    Reset {
        /// Id of the new run.
        run: RunId,
    },
    /// Restart from the current time and state, with Θ increased by
    /// `eps` (units of ψ). Shows sensitive dependence on initial conditions.
    ResetPerturbed {
        /// Id of the new run.
        run: RunId,
        /// Perturbation of Θ.
        eps: f64,
    },
    /// Stop advancing (the thread then sleeps until the next command).
    Pause,
    /// Continue advancing.
    Resume,
    /// While paused: advance by `tau` (> 0) and stay paused.
    Step {
        /// How far, in τ.
        tau: f64,
    },
    /// Change the playback speed.
    SetSpeed(Speed),
    /// Run `count` ghost copies (0 = none, at most [`MAX_GHOSTS`]) from the
    /// current state with Θ perturbed by `eps · (k + 1)/count`, k = 0..count.
    SetGhosts {
        /// How many.
        count: usize,
        /// Largest perturbation of Θ.
        eps: f64,
    },
    /// End the thread. Sent by the handle's `Drop`.
    Shutdown,
}

/// Most ghost copies: the 1–100.
pub(crate) const MAX_GHOSTS: usize = 100;

/// One state on the regular output grid — the batch run's history row —
/// with what the scene needs to draw it without doing any mechanics. Its
/// state's fields read through it (`sample.theta`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// τ, Θ, Θ', X (centre of mass relative to the base, per R), X' and
    /// the contact mode.
    pub state: HistoryRow,
    /// Base acceleration a_h/g.
    pub a_h: f64,
    /// Base acceleration a_v/g.
    pub a_v: f64,
    /// Base displacement per R (see [`BaseMotion`]).
    pub base_x: f64,
    /// Normal contact force per unit weight, N/(mg); 0 in terminal modes.
    pub normal: f64,
    /// Horizontal contact force on the block per unit weight, F/(mg).
    pub friction: f64,
    /// A stack's whole state (`None` for a block or a frame): `state`
    /// then holds one body's rotation ([`StackFrame::body_row`]).
    pub stack: Option<StackFrame>,
}

/// A stack's state at one τ: every interface's contact and every
/// relative rotation and rate, as the core integrates them
/// (docs/model.md §18.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackFrame {
    /// τ.
    pub tau: f64,
    /// The contacts, and how the run ended if it did.
    pub mode: StackMode,
    /// `[q_1 … q_K, q_1' … q_K', W]`, padded ([`crate::model::stack::NS`]).
    pub y: [f64; NS],
}

impl StackFrame {
    /// Block `j`'s absolute rotation φ_j (rad, clockwise) and its rate
    /// (rad per τ): the sums of the relative rotations at and below it.
    pub fn body(&self, j: usize) -> (f64, f64) {
        let j = j.min(MAX_BLOCKS - 1);
        (0..=j).fold((0.0, 0.0), |(p, w), i| (p + self.y[i], w + self.y[MAX_BLOCKS + i]))
    }

    /// Block `j` as a block's history row, so the plots built for one
    /// block show it: Θ = φ_j/ψ and Θ' = φ_j'/ψ with `geo` the bottom
    /// block's (a stack's amplitude and length units, so the units switch
    /// turns them into the body's degrees), X such that the plots' sliding
    /// displacement ([`Geometry::sliding`] × R) is the stack's slip on its
    /// floor u, which carries every block, X' = u' per R, and the mode of
    /// its lower face: closed as rest (glued faces too), open as rocking on
    /// that corner, sliding on the floor as the block's slide or
    /// slide-rock, or the run's end.
    pub(crate) fn body_row(&self, j: usize, geo: &Geometry) -> HistoryRow {
        let psi = geo.psi;
        let (phi, omega) = self.body(j);
        let mode = match self.mode.end {
            Some(StackEnd::Overturned(_)) => Mode::Tumbled,
            Some(StackEnd::Flight(_)) => Mode::Flight,
            None => face_mode(self.mode.contacts[j.min(MAX_BLOCKS - 1)], face_slip(&self.mode, j)),
        };
        let theta = phi / psi;
        // The inverse of Geometry::sliding: the rocking part it adds for a
        // tilted block, taken off so that it reads u alone.
        let rocking = if theta == 0.0 {
            0.0
        } else {
            theta.signum() * ((psi * (1.0 - theta.abs())).sin() - geo.sin_psi)
        };
        HistoryRow {
            tau: self.tau,
            theta,
            theta_dot: omega / psi,
            x: self.y[SLIDE] / geo.r - rocking,
            x_dot: self.y[SLIDE_RATE] / geo.r,
            mode,
        }
    }

    /// Whether every number is finite.
    pub fn is_finite(&self) -> bool {
        self.tau.is_finite() && self.y.iter().all(|v| v.is_finite())
    }
}

/// The block's mode a face's contact (and, for the base face, its `slip`)
/// is drawn and plotted as: closed as rest, rocking on a corner as the
/// block's rocking on that corner, and a sliding base face as the block's
/// slide or slide-rock.
pub(crate) fn face_mode(c: Contact, slip: Slip) -> Mode {
    let sign = |s: f64| if s > 0.0 { Sign::Pos } else { Sign::Neg };
    match (c, slip) {
        (Contact::Closed, Slip::Stuck) => Mode::Rest,
        (c, Slip::Stuck) => Mode::Rock { pivot: sign(c.sign()) },
        (Contact::Closed, s) => Mode::Slide { slip: sign(s.sign()) },
        (c, s) => Mode::SlideRock {
            pivot: sign(c.sign()),
            slip: sign(s.sign()),
        },
    }
}

/// Block `j`'s lower face's slip in `mode`: the base face's for the
/// bottom block; upper faces do not slide.
pub(crate) fn face_slip(mode: &StackMode, j: usize) -> Slip {
    if j == 0 { mode.slip } else { Slip::Stuck }
}

/// Samples the tests of the scene, the plots and the outbox draw from.
#[cfg(test)]
impl Sample {
    /// `state` on a base that does not move, pressed with normal force
    /// `normal` (N/(mg)) and no friction.
    pub(crate) fn still(state: HistoryRow, normal: f64) -> Sample {
        Sample {
            state,
            a_h: 0.0,
            a_v: 0.0,
            base_x: 0.0,
            normal,
            friction: 0.0,
            stack: None,
        }
    }

    /// A block flat and still in `mode` at `tau`, pressed with `normal`.
    pub(crate) fn flat(tau: f64, mode: Mode, normal: f64) -> Sample {
        let state = HistoryRow {
            tau,
            theta: 0.0,
            theta_dot: 0.0,
            x: 0.0,
            x_dot: 0.0,
            mode,
        };
        Sample::still(state, normal)
    }
}

impl std::ops::Deref for Sample {
    type Target = HistoryRow;

    fn deref(&self) -> &HistoryRow {
        &self.state
    }
}

/// A point of the stroboscopic (Poincaré) section, τ_k = (2πk + φ)/Ω_h
/// ([`RunInfo::section_phase`] is φ; 0 unless asked for): the
/// batch run's [`SectionRow`] (one type for both; this is the name the
/// protocol has always used).
pub use super::SectionRow as SectionPoint;

/// The latest state of one ghost copy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GhostState {
    /// Θ.
    pub theta: f64,
    /// Θ' = dΘ/dτ (the phase portrait draws each ghost's (Θ, Θ')).
    pub theta_dot: f64,
    /// X (relative to the base), per R.
    pub x: f64,
    /// Mode.
    pub mode: Mode,
}

/// What a run is about: sent once when it starts.
#[derive(Clone, Debug, PartialEq)]
pub struct RunInfo {
    /// The configuration being run.
    pub scenario: Scenario,
    /// The block's geometry (for the scene and the τ ↔ seconds conversion).
    pub geometry: Geometry,
    /// Period of the stroboscopic section, τ; `None` without harmonic
    /// excitation (then no section points come).
    pub section_period: Option<f64>,
    /// Forcing phase φ ∈ [0, 2π) of the section, rad: points at
    /// τ_k = (2πk + φ)/Ω_h. 0 (today's τ_k = k·period) unless the user
    /// chose another ([`SimCommand::SetSectionPhase`]).
    pub section_phase: f64,
    /// τ at which the run starts (0, or the τ shown when a run was
    /// continued from the current state or restarted perturbed).
    pub tau0: f64,
    /// Spacing of the samples, τ.
    pub sample_dt: f64,
    /// A stack's shape (`None` for a block or a frame): its samples carry
    /// a [`StackFrame`] and its events come as [`Batch::stack_events`].
    pub stack: Option<StackGeometry>,
}

/// A batch of output of one run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Batch {
    /// Samples on the regular grid, in time order. May have gaps where the
    /// consumer fell behind (see `dropped_samples`).
    pub samples: Vec<Sample>,
    /// Events in time order. Never dropped.
    pub events: Vec<EventRecord>,
    /// Section points in time order. Never dropped.
    pub section: Vec<SectionPoint>,
    /// A stack's events (uplift, impact, close, flight, overturning, each
    /// with its interface), in time order. Never dropped.
    pub stack_events: Vec<StackEvent>,
    /// A stack's section points, in time order (`section` holds them as
    /// the top block's). Never dropped.
    pub stack_section: Vec<StackFrame>,
    /// Latest state of each ghost copy (live view only: older ghost states
    /// are not kept).
    pub ghosts: Vec<GhostState>,
    /// Samples of this run dropped since the previous batch because the
    /// consumer fell behind.
    pub dropped_samples: u64,
    /// τ reached by the run when the batch was sent.
    pub tau: f64,
}

impl Batch {
    /// Whether the batch carries no data.
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
            && self.events.is_empty()
            && self.section.is_empty()
            && self.ghosts.is_empty()
            && self.stack_events.is_empty()
    }
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum RunEnd {
    /// Reached a terminal mode (tumbled or flight) at `tau`.
    Terminal {
        /// The terminal mode.
        mode: Mode,
        /// When.
        tau: f64,
    },
    /// A record run at rest after its record ended (at a chunk end, at most
    /// [`super::runner::MAX_CHUNK`] τ after it came to rest): the ground is
    /// still from then on, so the block stays at rest for ever, and the
    /// run stops as the batch run does ([`super::RunOptions::rest_after`]).
    /// The block survived the record.
    Rest {
        /// When the run stopped, τ.
        tau: f64,
        /// Largest |Θ| of the run, units of ψ (at samples, events and the
        /// model's rocking peaks, as the batch run's `max_abs_theta`).
        max_abs_theta: f64,
        /// Largest |sliding displacement| of the run, per R
        /// ([`Geometry::sliding`], docs/model.md §1.6).
        max_abs_sliding: f64,
    },
    /// The integration failed; the message names the cause.
    Failed(String),
}

impl RunEnd {
    /// How the run ended, in the engineer's words, and when (τ): `None`
    /// for a run that failed, or that stopped in a mode that is neither
    /// terminal nor rest (which the thread does not send).
    pub fn end_state(&self) -> Option<(EndState, f64)> {
        match *self {
            RunEnd::Terminal {
                mode: Mode::Tumbled,
                tau,
            } => Some((EndState::Overturned, tau)),
            RunEnd::Terminal {
                mode: Mode::Flight,
                tau,
            } => Some((EndState::Flight, tau)),
            RunEnd::Terminal {
                mode: Mode::Rest | Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. },
                ..
            }
            | RunEnd::Failed(_) => None,
            RunEnd::Rest { tau, .. } => Some((EndState::Rest, tau)),
        }
    }
}

/// Updates from the simulation thread.
#[derive(Clone, Debug, PartialEq)]
pub enum SimUpdate {
    /// A run started.
    Started {
        /// Its id.
        run: RunId,
        /// What it runs.
        info: Box<RunInfo>,
    },
    /// Output of a run.
    Batch {
        /// The run.
        run: RunId,
        /// The data.
        batch: Batch,
    },
    /// The thread paused (after a `Pause` or a completed `Step`) or resumed.
    Paused {
        /// The run.
        run: RunId,
        /// Whether it is paused now.
        paused: bool,
        /// τ reached.
        tau: f64,
    },
    /// A run ended; no more batches of it follow.
    Finished {
        /// The run.
        run: RunId,
        /// How.
        end: RunEnd,
    },
}

impl SimUpdate {
    /// The run the update belongs to.
    pub fn run(&self) -> RunId {
        match self {
            SimUpdate::Started { run, .. }
            | SimUpdate::Batch { run, .. }
            | SimUpdate::Paused { run, .. }
            | SimUpdate::Finished { run, .. } => *run,
        }
    }
}

/// The base's horizontal displacement, per R, from the excitation.
///
/// For harmonic excitation it is the periodic solution of
/// `U'' = (a_h/g)/γ` (γ = R p²/g = 3/4), `U = −A_h ψ sin(Ω_h τ + Φ_h)/(γ Ω_h²)`:
/// the base oscillates about a fixed point. For pulses and records the
/// runner integrates the acceleration samples with the trapezoidal rule from
/// rest, which is exact to the sampling of the display and is only drawn,
/// never fed back into the mechanics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum BaseMotion {
    /// The base stays put.
    Fixed,
    /// Closed form: amplitude `A_h ψ/(γ Ω_h²)` per R, frequency, phase.
    Harmonic {
        /// Amplitude per R.
        amplitude: f64,
        /// Ω_h.
        omega: f64,
        /// Φ_h.
        phase: f64,
    },
    /// Trapezoidal integration of the samples.
    Integrated {
        /// τ of the last sample.
        tau: f64,
        /// a_h/g at the last sample.
        a: f64,
        /// U' at the last sample.
        velocity: f64,
        /// U at the last sample.
        displacement: f64,
    },
}

impl BaseMotion {
    /// The motion of `excitation`, starting at rest at τ = `tau0`.
    pub fn new(excitation: &crate::model::Excitation, tau0: f64) -> Self {
        use crate::model::Excitation as E;
        match excitation {
            E::None => BaseMotion::Fixed,
            E::Harmonic(h) => BaseMotion::Harmonic {
                amplitude: h.a_h * h.psi / (crate::model::geometry::GAMMA * h.omega_h * h.omega_h),
                omega: h.omega_h,
                phase: h.phase_h,
            },
            E::Pulse(_) | E::Record(_) | E::Floor(_) => BaseMotion::Integrated {
                tau: tau0,
                a: excitation.forcing(tau0).a,
                velocity: 0.0,
                displacement: 0.0,
            },
        }
    }

    /// Displacement per R at `tau`, given `a` = a_h/g there. Calls must come
    /// in increasing `tau` for the integrated kind.
    pub fn advance(&mut self, tau: f64, a: f64) -> f64 {
        match self {
            BaseMotion::Fixed => 0.0,
            BaseMotion::Harmonic {
                amplitude,
                omega,
                phase,
            } => -*amplitude * (*omega * tau + *phase).sin(),
            BaseMotion::Integrated {
                tau: t0,
                a: a0,
                velocity,
                displacement,
            } => {
                let dt = tau - *t0;
                if dt > 0.0 {
                    let gamma = crate::model::geometry::GAMMA;
                    let v1 = *velocity + 0.5 * (*a0 + a) / gamma * dt;
                    *displacement += 0.5 * (*velocity + v1) * dt;
                    *velocity = v1;
                    *t0 = tau;
                    *a0 = a;
                }
                *displacement
            }
        }
    }
}

/// Where to draw the block: the pose of a rigid rectangle, in metres, in
/// the frame of the base's rest position (x to the right, y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Centre of mass, horizontal, m (base displacement included).
    pub x: f64,
    /// Centre of mass, height above the base, m.
    pub y: f64,
    /// Rotation θ = ψΘ, rad, clockwise positive (MODEL-DECISIONS).
    pub angle: f64,
    /// The corner in contact, if the block is tilted: horizontal position, m,
    /// and which corner.
    pub pivot: Option<(f64, Sign)>,
    /// Base displacement, m.
    pub base_x: f64,
}

/// The pose of a block of geometry `geo` in state (`theta`, `x`, `mode`)
/// on a base displaced by `base_x` (per R). Uses the model's own height
/// of the centre of mass, so the drawing and the mechanics agree.
pub fn pose(geo: &Geometry, theta: f64, x: f64, mode: Mode, base_x: f64) -> Pose {
    let (height, _) = energy::height(geo, mode, theta, 0.0);
    let tilted = theta != 0.0;
    let pivot = tilted.then(|| {
        let s = Sign::of(theta);
        (
            (base_x + x + kinematics::corner_offset(geo, s.value(), theta)) * geo.r,
            s,
        )
    });
    Pose {
        x: (base_x + x) * geo.r,
        y: height * geo.r,
        angle: geo.psi * theta,
        pivot,
        base_x: base_x * geo.r,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_end_reads_as_the_engineers_end_state_with_its_time() {
        let at = |mode| RunEnd::Terminal { mode, tau: 3.5 }.end_state();
        assert_eq!(at(Mode::Tumbled), Some((EndState::Overturned, 3.5)));
        assert_eq!(at(Mode::Flight), Some((EndState::Flight, 3.5)));
        assert_eq!(at(Mode::Rock { pivot: Sign::Pos }), None);
        let rest = RunEnd::Rest {
            tau: 9.0,
            max_abs_theta: 0.2,
            max_abs_sliding: 0.0,
        };
        assert_eq!(rest.end_state(), Some((EndState::Rest, 9.0)));
        assert_eq!(RunEnd::Failed("x".into()).end_state(), None);
    }

    #[test]
    fn flat_block_stands_on_its_base() {
        let geo = Geometry::new(1.0, 4.0);
        let p = pose(&geo, 0.0, 0.25, Mode::Rest, 0.5);
        assert!((p.y - 2.0).abs() < 1e-12, "centre of mass at H/2, got {}", p.y);
        assert!((p.x - 0.75 * geo.r).abs() < 1e-12);
        assert_eq!(p.pivot, None);
    }

    #[test]
    fn pivot_corner_stays_on_the_base_line_for_any_tilt() {
        // The lower corner on the pivot side must be at (pivot_x, 0): rotate
        // the corner's offset from the centre by θ clockwise and compare.
        let geo = Geometry::new(1.0, 4.0);
        for &theta in &[0.3, -0.7, 0.99] {
            let mode = Mode::Rock { pivot: Sign::of(theta) };
            let p = pose(&geo, theta, 0.1, mode, 0.0);
            let (px, side) = p.pivot.expect("tilted");
            let (hw, hh) = (0.5 * geo.width * side.value(), -0.5 * geo.height);
            let (s, c) = p.angle.sin_cos();
            // Clockwise rotation by θ: (x, y) → (x cos θ + y sin θ, −x sin θ + y cos θ).
            let cx = p.x + hw * c + hh * s;
            let cy = p.y - hw * s + hh * c;
            assert!((cx - px).abs() < 1e-12, "corner x {cx} vs pivot {px}");
            assert!(cy.abs() < 1e-12, "corner height {cy}");
        }
    }

    #[test]
    fn harmonic_base_displacement_has_the_excitation_as_second_derivative() {
        let h = crate::model::Harmonic {
            a_h: 2.0,
            a_v: 0.0,
            omega_h: 8.0,
            omega_v: 8.0,
            phase_h: 0.3,
            phase_v: 0.0,
            psi: 0.245,
        };
        let ex = crate::model::Excitation::Harmonic(h);
        let mut m = BaseMotion::new(&ex, 0.0);
        let (tau, d) = (1.234, 1e-4);
        let u = |m: &mut BaseMotion, t: f64| m.advance(t, ex.forcing(t).a);
        let second = (u(&mut m, tau + d) - 2.0 * u(&mut m, tau) + u(&mut m, tau - d)) / (d * d);
        let want = ex.forcing(tau).a / crate::model::geometry::GAMMA;
        assert!((second - want).abs() < 1e-5 * want.abs().max(1.0), "{second} vs {want}");
    }

    #[test]
    fn integrated_base_displacement_of_constant_acceleration_is_a_parabola() {
        let mut m = BaseMotion::Integrated {
            tau: 0.0,
            a: 0.3,
            velocity: 0.0,
            displacement: 0.0,
        };
        let mut u = 0.0;
        for k in 1..=100 {
            u = m.advance(k as f64 * 0.01, 0.3);
        }
        let want = 0.5 * 0.3 / crate::model::geometry::GAMMA;
        assert!((u - want).abs() < 1e-12, "{u} vs {want}");
    }
}
