//! The rocking frame as a [`TangentSystem`]: its tangent coordinates
//! `z = (Θ, Θ')` and the Jacobians its equations generate
//! (`model/frame/tangent.rs`), for its whole spectrum by tangent dynamics
//! or its largest exponent by two trajectories.

use super::qr::Square;
use super::tangent::{Perturbable, TangentSystem};
use crate::model::dynamics::{Forcing, Tilt};
use crate::model::state::{N, THETA, THETA_DOT, X_DOT};
use crate::model::variational::forcing_rate;
use crate::model::{FRAME_DIM, FrameSystem, Mode};

impl Perturbable<N, FRAME_DIM> for FrameSystem {
    fn coords(&self, y: &[f64; N]) -> [f64; FRAME_DIM] {
        [y[THETA], y[THETA_DOT]]
    }

    /// Both while it rocks; none at rest or after it ended.
    fn tangent_dim(&self, mode: Mode) -> usize {
        FrameSystem::tangent_dim(mode)
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

impl TangentSystem<N, FRAME_DIM> for FrameSystem {
    fn jacobian(&self, mode: Mode, t: f64, y: &[f64; N]) -> Square<FRAME_DIM> {
        self.field_jacobian(mode, self.model.excitation.forcing(t), y)
    }

    /// `None` under a motion without a closed-form rate (pulses, records),
    /// as the block's: the tangent method needs the guards' time partials.
    fn guard_gradient(&self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> Option<([f64; FRAME_DIM], f64)> {
        let rate: Forcing = forcing_rate(&self.model.excitation, t)?;
        FrameSystem::guard_gradient(self, mode, index, self.model.excitation.forcing(t), rate, y)
    }

    fn reset_jacobian(
        &self,
        before: Mode,
        index: usize,
        y_before: &[f64; N],
        after: Mode,
        _y_after: &[f64; N],
    ) -> (Square<FRAME_DIM>, usize) {
        FrameSystem::reset_jacobian(self, before, index, y_before, after)
    }
}
