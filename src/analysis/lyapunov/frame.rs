//! The rocking frame as a [`Perturbable`] system, for its largest exponent
//! by two trajectories. Its tangent equations are not written, so it has
//! no spectrum.
//!
//! Tangent coordinates `z = (Θ, Θ')` of the columns (the frame has one
//! degree of freedom: its columns rock together on stuck corners, so the
//! columns' X' follows Θ' and X is neutral).

use super::tangent::Perturbable;
use crate::model::dynamics::Tilt;
use crate::model::state::{N, THETA, THETA_DOT, X_DOT};
use crate::model::{FrameSystem, Mode};

/// Number of tangent coordinates of a frame.
pub(crate) const FRAME_DIM: usize = 2;

impl Perturbable<N, FRAME_DIM> for FrameSystem {
    fn coords(&self, y: &[f64; N]) -> [f64; FRAME_DIM] {
        [y[THETA], y[THETA_DOT]]
    }

    /// Both while it rocks; none at rest or after it ended.
    fn tangent_dim(&self, mode: Mode) -> usize {
        match mode {
            Mode::Rock { .. } => 2,
            Mode::Rest | Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => 0,
        }
    }

    /// Θ and Θ' displaced, the columns' X' put back on the stuck-corner
    /// constraint `X' = cos φ · ψ Θ'` (as the block's rock), keeping the
    /// pivot's side (sΘ > 0).
    fn displaced(&self, mode: Mode, _t: f64, y: &[f64; N], dz: &[f64; FRAME_DIM]) -> Option<[f64; N]> {
        let Mode::Rock { pivot } = mode else {
            return None;
        };
        let geo = &self.model.geo;
        let mut yp = *y;
        yp[THETA] += dz[0];
        yp[THETA_DOT] += dz[1];
        let tilt = Tilt::new(geo, pivot, yp[THETA]);
        yp[X_DOT] = tilt.c * geo.psi * yp[THETA_DOT];
        (pivot.value() * yp[THETA] > 0.0).then_some(yp)
    }
}
