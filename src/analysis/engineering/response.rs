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

pub use super::block_size::BlockSize;
use super::stack_response::scale_stack;
use crate::model::excitation::Excitation;
/// How a run ended, in the engineer's words: the core's one type.
pub use crate::sim::EndState;
use crate::sim::scenario::{ExcitationKind, RECORD_TAIL_S, Record, ShapeKind};
use crate::sim::stack_run::{StackError, simulate_stack};
use crate::sim::{Scenario, ScenarioError, SimError, simulate};

/// Free-vibration tail after a pulse, in τ (units of 1/p). A block released
/// near the overturning angle with a small velocity needs about
/// 2·ln(2/δ) in τ to fall back or over, δ its distance from |Θ| = 1; 50
/// covers δ down to 1e-10, far below any amplitude resolution of a search.
pub(crate) const PULSE_TAIL_TAU: f64 = 50.0;

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
pub(crate) fn end_time_as(end: EndState, t_end_event_s: Option<f64>, which: EndState) -> Option<f64> {
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

/// The answer of the stack of the checked scenario `s`: it ends as the
/// first body to overturn or fly ends it; its peak rotation is that of
/// the block that turned most over its own slenderness
/// ([`StackRun::most_turned`](crate::sim::stack_run::StackRun::most_turned)).
fn respond_stack(s: &Scenario) -> Result<BlockResponse, ResponseError> {
    let geo = s
        .stack_geometry()
        .ok_or_else(|| ScenarioError::new("stack", "its blocks do not stand on each other"))?;
    let run = simulate_stack(geo, s.excitation()?, s.run.zeno_eps, &s.run_options())?;
    let p = s.geometry().p;
    let event = run.end.map(|(end, tau)| (end.body(), tau / p));
    Ok(BlockResponse {
        end: EndState::of(run.outcome),
        peak_theta_over_alpha: run.most_turned().2,
        t_end_event_s: event.map(|(_, t)| t),
        body: event.map(|(j, _)| j),
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

    /// A stack of three `0.4 × 0.5` m blocks, the upper two glued on.
    fn glued_column() -> Scenario {
        let block = |glued| crate::model::stack::StackBlock {
            glued,
            ..crate::model::stack::StackBlock::new(0.4, 0.5, 0.0)
        };
        let mut s = Scenario::default();
        s.block.width = 0.4;
        s.block.height = 0.5;
        s.stack = Some(vec![block(false), block(true), block(true)]);
        s
    }

    #[test]
    fn a_glued_stack_of_one_width_answers_as_the_block_of_its_height() {
        // Three glued 0.4 × 0.5 m blocks but the bottom face free: the
        // 0.4 × 1.5 m block, under a one-sine pulse that rocks it and one
        // that overturns it. The block's answer is its own code's
        // (`respond` without a stack); τ units differ (the stack's are its
        // bottom block's), so times agree to the integrator's tolerance.
        let stack = glued_column();
        let size = BlockSize {
            width_m: 0.4,
            height_m: 1.5,
        };
        for (a_p_g, want) in [(0.45, EndState::Rest), (3.0, EndState::Overturned)] {
            let drive = Drive::PhysicalPulse {
                shape: ShapeKind::OneSine,
                cycles: 1,
                a_p_g,
                omega_p: std::f64::consts::TAU / 0.5,
            };
            let one = respond(&Scenario::default(), size, &drive, 1.0).unwrap();
            let three = respond(&stack, size, &drive, 1.0).unwrap();
            assert_eq!((one.end, three.end), (want, want), "{one:?} {three:?}");
            // The glued blocks' own slenderness is atan(0.4/0.5), the
            // whole block's atan(0.4/1.5): the peak rotations agree once
            // each is brought back to radians.
            let (alpha_one, alpha_part) = ((0.4f64 / 1.5).atan(), 0.8f64.atan());
            let (rad_one, rad_three) = (
                one.peak_theta_over_alpha * alpha_one,
                three.peak_theta_over_alpha * alpha_part,
            );
            if want == EndState::Rest {
                assert!(rad_one > 0.01, "it rocks: {rad_one}");
                assert!((rad_one - rad_three).abs() < 1e-10, "{rad_one} vs {rad_three}");
            } else {
                let (t1, t3) = (one.t_end_event_s.unwrap(), three.t_end_event_s.unwrap());
                assert!((t1 - t3).abs() < 1e-10, "{t1} vs {t3}");
                assert_eq!(three.body, Some(0));
            }
            assert_eq!(one.body, None);
        }
    }
}
