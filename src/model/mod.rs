//! The block model: EQUATIONS ONLY. No integrator, threads, I/O or GUI types.
//!
//! Conventions (MODEL-DECISIONS): θ > 0 is a clockwise rotation about the
//! right bottom corner; τ = p t, Θ = θ/ψ, X = x_G/R; base accelerations
//! per unit g. Derivations and the paper's equation numbers: `docs/model.md`.

pub mod ad;
pub mod dynamics;
pub mod energy;
pub mod excitation;
pub mod frame;
pub mod geometry;
pub mod impact;
pub mod kinematics;
pub mod mode;
pub mod oscillator;
pub mod params;
pub mod rocker;
pub mod series;
pub mod stack;
pub mod state;
pub mod system;
pub mod units;
pub mod variational;

pub use excitation::{Excitation, Harmonic};
pub use frame::{FRAME_COORDS, FRAME_DIM, Frame, FrameSystem};
pub use geometry::Geometry;
pub use impact::ImpactLaw;
pub use mode::{Mode, Sign};
pub use params::{FlightPolicy, Model};
pub use rocker::{Rocker, RockerCore, RockerVisitor, with_rocker};
pub use system::{BlockSystem, EventKind, EventRecord};
