//! The parameters of a run: what the block is, what it stands on, and how
//! the run treats flight and impact accumulation.

use super::excitation::Excitation;
use super::frame::Frame;
use super::geometry::Geometry;
use super::impact::ImpactLaw;

/// What happens when the normal force vanishes (MODEL-DECISIONS "Flight").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlightPolicy {
    /// Stop the run and report flight (default).
    Stop,
    /// Keep integrating the grounded equations, as the paper did, and count
    /// the violations.
    Ignore,
}

/// Physical parameters of a run, normalised (MODEL-DECISIONS).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Block geometry.
    pub geo: Geometry,
    /// Static friction coefficient μ_s (`inf`: no sliding).
    pub mu_s: f64,
    /// Kinetic friction coefficient μ_k (<= μ_s).
    pub mu_k: f64,
    /// Impact law.
    pub law: ImpactLaw,
    /// Base motion.
    pub excitation: Excitation,
    /// |Θ| at which the block counts as tumbled (default 1; capped at the
    /// side-landing angle π/(2ψ)).
    pub tumble_theta: f64,
    /// What to do at flight.
    pub flight: FlightPolicy,
    /// Post-impact |Θ'| below which an impact accumulation is summed in
    /// closed form and the block put to rest (default 1e-5).
    pub zeno_eps: f64,
    /// A rocking frame of columns of `geo` under a cap beam; `None`: the
    /// single block.
    pub frame: Option<Frame>,
}
