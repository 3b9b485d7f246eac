//! The seam between the models and the simulation: what a run, the live
//! session and the outputs need of a model whose state is the block's
//! `[Θ, Θ', X, X', W, D]` and whose modes are the block's ([`Mode`]). The
//! single block ([`BlockSystem`]) and the rocking frame ([`FrameSystem`])
//! implement it; `sim` is generic over it and chooses one per run with
//! [`with_rocker`], so each stays monomorphised (no dispatch per
//! right-hand side).

use super::frame::FrameSystem;
use super::mode::Mode;
use super::params::Model;
use super::state::N;
use super::system::{BlockSystem, EventRecord, ModelError, Tally};
use crate::integrate::hybrid::HybridSystem;

/// What the simulation asks of a model between steps; object-safe, so the
/// live session can hold any model behind a pointer.
pub trait RockerCore: Send {
    /// The parameters it was built from.
    fn params(&self) -> &Model;

    /// What it tallied so far.
    fn tallied(&self) -> Tally;

    /// Brings a freshly entered `mode` to a consistent one at `t`.
    fn settle_mode(&mut self, mode: Mode, t: f64, y: &mut [f64; N]) -> Mode;

    /// Mechanical energy of `y` in `mode`, in the model's energy unit.
    fn mechanical_energy(&self, mode: Mode, y: &[f64; N]) -> f64;

    /// Mechanical energy at a run's end (a terminal state may keep
    /// velocities the state vector does not hold).
    fn end_energy(&self, mode: Mode, y: &[f64; N]) -> f64;

    /// |Θ| at which the model counts as overturned.
    fn overturn_angle(&self) -> f64;

    /// Normal and horizontal contact force at the base, per unit weight,
    /// of a grounded `mode` at `(t, y)` (what the app plots).
    fn contact_forces(&self, mode: Mode, t: f64, y: &[f64; N]) -> (f64, f64);
}

/// A planar rocking model with the block's state and modes.
pub trait Rocker:
    RockerCore + HybridSystem<N, Mode = Mode, Record = EventRecord, Error = ModelError> + Clone + 'static
{
    /// A system for `model`, tallies zeroed.
    fn build(model: Model) -> Self;
}

/// What to do with the system of a model (a generic closure, which Rust
/// spells as a trait).
pub trait RockerVisitor {
    /// What the visit returns.
    type Output;

    /// Called once, with the system.
    fn visit<R: Rocker>(self, system: R) -> Self::Output;
}

/// Calls `visitor` with the system `model` describes: a frame's when it
/// has one, else the single block's.
pub fn with_rocker<V: RockerVisitor>(model: Model, visitor: V) -> V::Output {
    if model.frame.is_some() {
        visitor.visit(FrameSystem::build(model))
    } else {
        visitor.visit(BlockSystem::build(model))
    }
}

/// Both systems keep their parameters in `model`, their tallies in `tally`,
/// and name their own methods alike.
macro_rules! rocker {
    ($system:ty) => {
        impl RockerCore for $system {
            fn params(&self) -> &Model {
                &self.model
            }
            fn tallied(&self) -> Tally {
                self.tally
            }
            fn settle_mode(&mut self, mode: Mode, t: f64, y: &mut [f64; N]) -> Mode {
                self.settle(mode, t, y)
            }
            fn mechanical_energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
                self.energy(mode, y)
            }
            fn end_energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
                self.final_energy(mode, y)
            }
            fn overturn_angle(&self) -> f64 {
                self.tumble_angle()
            }
            fn contact_forces(&self, mode: Mode, t: f64, y: &[f64; N]) -> (f64, f64) {
                self.base_forces(mode, t, y)
            }
        }

        impl Rocker for $system {
            fn build(model: Model) -> Self {
                <$system>::new(model)
            }
        }
    };
}

rocker!(BlockSystem);
rocker!(FrameSystem);
