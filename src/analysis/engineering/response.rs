//! One block (or one stack of blocks, scaled as a whole:
//! [`stack_response`](super::stack_response)) under one ground motion:
//! the run every engineering analysis is made of.
//!
//! Contract:
//! - The block is set by its width and height in metres ([`BlockSize`]);
//!   everything else (friction, impact law, tolerances, the overturning
//!   angle `run.tumble_theta`) comes from a base [`Scenario`].
//! - A run keeps no history (`run.output_dt = 0`) and stops by itself at
//!   overturning or flight; otherwise it lasts the whole motion and a
//!   free-vibration tail: for records the base's `run.tail_s` (default
//!   [`RECORD_TAIL_S`], 30 s; the run ends earlier once the block is at rest
//!   after the record), for pulses [`PULSE_TAIL_TAU`].
//! - Flight (the normal force would vanish) is reported as flight, never as
//!   safe or overturned.
//! - Every number in a [`BlockResponse`] is finite.

use super::stack_response::{respond_stack, scale_stack};
use crate::model::excitation::Excitation;
/// How a run ended, in the engineer's words: the core's one type.
pub use crate::sim::EndState;
use crate::sim::scenario::{ExcitationKind, RECORD_TAIL_S, Record, ShapeKind};
use crate::sim::stack_run::StackError;
use crate::sim::{Scenario, ScenarioError, SimError, simulate};

/// Free-vibration tail after a pulse, in τ (units of 1/p). A block released
/// near the overturning angle with a small velocity needs about
/// 2·ln(2/δ) in τ to fall back or over, δ its distance from |Θ| = 1; 50
/// covers δ down to 1e-10, far below any amplitude resolution of a search.
pub(crate) const PULSE_TAIL_TAU: f64 = 50.0;

/// A rectangular block, m.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BlockSize {
    /// Width B, m, > 0.
    pub width_m: f64,
    /// Height H, m, > 0.
    pub height_m: f64,
}

impl BlockSize {
    /// The block of half-diagonal `r_m` (m) and slenderness ratio
    /// `b_over_h` = B/H: B = 2R sin α, H = 2R cos α, α = atan(B/H).
    pub(crate) fn from_half_diagonal(r_m: f64, b_over_h: f64) -> Self {
        let alpha = b_over_h.atan();
        Self {
            width_m: 2.0 * r_m * alpha.sin(),
            height_m: 2.0 * r_m * alpha.cos(),
        }
    }

    /// The block of height `h_m` (m) and ratio `b_over_h` = B/H.
    pub(crate) fn from_height(h_m: f64, b_over_h: f64) -> Self {
        Self {
            width_m: b_over_h * h_m,
            height_m: h_m,
        }
    }

    /// Half-diagonal R = ½√(B²+H²), m.
    pub fn half_diagonal_m(&self) -> f64 {
        0.5 * self.width_m.hypot(self.height_m)
    }

    /// Slenderness angle α = atan(B/H), rad.
    pub fn alpha(&self) -> f64 {
        self.width_m.atan2(self.height_m)
    }

    /// Frequency parameter p = √(3g/(4R)), 1/s.
    pub fn p_per_s(&self) -> f64 {
        crate::model::Geometry::new(self.width_m, self.height_m).p
    }
}

/// The base motion of one run, before scaling.
#[derive(Clone, Debug, PartialEq)]
pub enum Drive {
    /// A recorded horizontal acceleration (times s, accelerations g),
    /// multiplied by the run's scale factor.
    Record(Record),
    /// A recorded horizontal and vertical pair (vertical positive upward),
    /// both multiplied by the run's one scale factor: scaling keeps the
    /// components' ratio as recorded, so a level set by the horizontal's
    /// intensity scales the vertical with it.
    Paired {
        /// The horizontal component.
        horizontal: Record,
        /// The vertical component, positive upward.
        vertical: Record,
    },
    /// An analytic pulse given in physical units: a_p·scale (g) at
    /// frequency ω_p (rad/s); its ω_p/p differs from block to block.
    PhysicalPulse {
        /// Shape.
        shape: ShapeKind,
        /// n of a type-C_n pulse (1 for the others).
        cycles: u32,
        /// Peak acceleration a_p at scale 1, g, > 0.
        a_p_g: f64,
        /// Pulse frequency ω_p, rad/s, > 0.
        omega_p: f64,
    },
    /// An analytic pulse given as the overturning maps do: the amplitude
    /// a_p/(g tan α) is the run's scale, the frequency ω_p/p is fixed, so
    /// the block's size does not matter (only its slenderness).
    NormalisedPulse {
        /// Shape.
        shape: ShapeKind,
        /// n of a type-C_n pulse (1 for the others).
        cycles: u32,
        /// ω_p/p, > 0.
        omega_ratio: f64,
    },
}

impl Drive {
    /// Its name for outputs: the (horizontal) record's file stem or the
    /// pulse shape.
    pub fn name(&self) -> String {
        match self {
            Drive::Record(r) | Drive::Paired { horizontal: r, .. } => r
                .path
                .file_stem()
                .map_or_else(|| r.path.display().to_string(), |s| s.to_string_lossy().into_owned()),
            Drive::PhysicalPulse { shape, .. } | Drive::NormalisedPulse { shape, .. } => shape.name().to_string(),
        }
    }
}

/// The time, s, of a run's end event (`t_end_event_s`) when the run
/// ended as `which`, else `None`: the outputs give each kind of end its
/// own column (`t_overturn_s`, `t_flight_s`).
pub fn end_time_as(end: EndState, t_end_event_s: Option<f64>, which: EndState) -> Option<f64> {
    if end == which { t_end_event_s } else { None }
}

/// The answer of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockResponse {
    /// How it ended.
    pub end: EndState,
    /// Peak rotation over the slenderness, max |θ|/α (= max |Θ|); at least
    /// `tumble_theta` when overturned.
    pub peak_theta_over_alpha: f64,
    /// Time of overturning or flight, s (from the start of the motion).
    pub t_end_event_s: Option<f64>,
    /// For a stack, the block (0 = bottom) whose lower face overturned or
    /// flew; `None` for a block and for a stack that stayed.
    pub body: Option<usize>,
}

/// A run that could not be made or failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ResponseError {
    /// The scenario built for the block is invalid.
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    /// The integration failed.
    #[error("{0}")]
    Sim(#[from] SimError),
    /// A stack's run failed or stopped at a slip it does not follow.
    #[error("{0}")]
    Stack(#[from] StackError),
}

/// The scenario of `size` under `drive` at `scale`, built from `base`: no
/// history, run length = motion + tail, from rest.
pub fn scenario_for(base: &Scenario, size: BlockSize, drive: &Drive, scale: f64) -> Result<Scenario, ScenarioError> {
    let mut s = base.clone();
    if s.stack.is_some() {
        scale_stack(&mut s, size)?;
    } else {
        s.block.width = size.width_m;
        s.block.height = size.height_m;
    }
    s.run.output_dt = 0.0;
    s.analyses.lyapunov = false;
    s.analyses.spectrum = false;
    s.initial.theta = 0.0;
    s.initial.theta_dot = 0.0;
    s.initial.x_dot = None;
    let geo = s.geometry();
    match drive {
        Drive::Record(record) => {
            s.excitation.kind = ExcitationKind::Record;
            s.excitation.record_h = Some(record.clone());
            s.excitation.record_v = None;
            s.excitation.scale_h = scale;
            // The whole record and the tail, even when the base config set
            // an explicit end: a spectrum never cuts a record short.
            s.run.record_tail_s = Some(s.run.record_tail_s.unwrap_or(RECORD_TAIL_S));
        }
        Drive::Paired { horizontal, vertical } => {
            s.excitation.kind = ExcitationKind::Record;
            s.excitation.record_h = Some(horizontal.clone());
            s.excitation.record_v = Some(vertical.clone());
            s.excitation.scale_h = scale;
            s.excitation.scale_v = scale;
            s.run.record_tail_s = Some(s.run.record_tail_s.unwrap_or(RECORD_TAIL_S));
        }
        Drive::PhysicalPulse {
            shape,
            cycles,
            a_p_g,
            omega_p,
        } => {
            set_pulse(&mut s, *shape, *cycles, scale * a_p_g / geo.psi, omega_p / geo.p)?;
        }
        Drive::NormalisedPulse {
            shape,
            cycles,
            omega_ratio,
        } => {
            // a_p/(g tan α) = scale, and the pulse amplitude key is in ψ g.
            set_pulse(&mut s, *shape, *cycles, scale * geo.tan_psi / geo.psi, *omega_ratio)?;
        }
    }
    s.validate()?;
    Ok(s)
}

/// Sets a horizontal pulse of amplitude `a_h` (units of ψ g) and frequency
/// `omega` (units of p), and the run length: the pulse and
/// [`PULSE_TAIL_TAU`].
fn set_pulse(s: &mut Scenario, shape: ShapeKind, cycles: u32, a_h: f64, omega: f64) -> Result<(), ScenarioError> {
    s.excitation.kind = ExcitationKind::Pulse;
    s.excitation.shape = shape;
    s.excitation.cycles = cycles;
    s.excitation.a_h = a_h;
    s.excitation.omega_h = omega;
    s.excitation.a_v = 0.0;
    let duration = match s.excitation()? {
        Excitation::Pulse(pair) => pair.horizontal.duration(),
        Excitation::None | Excitation::Harmonic(_) | Excitation::Record(_) | Excitation::Floor(_) => 0.0,
    };
    s.run.tau_end = duration + PULSE_TAIL_TAU;
    Ok(())
}

/// Runs `size` under `drive` at `scale` (see [`scenario_for`]).
pub(crate) fn respond(
    base: &Scenario,
    size: BlockSize,
    drive: &Drive,
    scale: f64,
) -> Result<BlockResponse, ResponseError> {
    let s = scenario_for(base, size, drive, scale)?;
    if s.stack.is_some() {
        return respond_stack(&s);
    }
    let p = s.geometry().p;
    let r = simulate(s.model()?, &s.initial, &s.run_options())?;
    let (end, event_tau) = (r.end_state(), r.end_event_tau());
    Ok(BlockResponse {
        end,
        peak_theta_over_alpha: r.max_abs_theta,
        t_end_event_s: event_tau.map(|tau| tau / p),
        body: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_from_half_diagonal_and_height() {
        let b = BlockSize::from_half_diagonal(1.0, 0.25);
        assert!((b.half_diagonal_m() - 1.0).abs() < 1e-15);
        assert!((b.width_m / b.height_m - 0.25).abs() < 1e-15);
        let h = BlockSize::from_height(2.0, 0.3);
        assert_eq!((h.width_m, h.height_m), (0.6, 2.0));
        assert!((h.alpha() - 0.3f64.atan()).abs() < 1e-15);
    }

    #[test]
    fn a_pulse_below_uplift_leaves_the_block_at_rest_and_a_strong_one_overturns_it() {
        let base = Scenario::default();
        let size = BlockSize::from_half_diagonal(1.0, 0.2);
        let drive = Drive::NormalisedPulse {
            shape: ShapeKind::OneSine,
            cycles: 1,
            omega_ratio: 3.0,
        };
        // a_p < g tan α: the block never lifts off (paper eq. 1).
        let calm = respond(&base, size, &drive, 0.99).unwrap();
        assert_eq!(calm.end, EndState::Rest);
        assert_eq!(calm.peak_theta_over_alpha, 0.0);
        let strong = respond(&base, size, &drive, 20.0).unwrap();
        assert_eq!(strong.end, EndState::Overturned);
        assert!(strong.peak_theta_over_alpha >= 1.0);
        let t = strong.t_end_event_s.unwrap();
        assert!(t > 0.0 && t < (std::f64::consts::TAU / 3.0 + PULSE_TAIL_TAU) / size.p_per_s());
    }
}
