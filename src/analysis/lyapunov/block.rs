//! The block as a [`TangentSystem`]: tangent coordinates `z = (Θ, Θ', X')`
//! and the analytic Jacobians of `model::variational`.

use super::qr::Square;
use super::tangent::{Perturbable, TangentSystem};
use crate::model::dynamics::{Forcing, Tilt};
use crate::model::system::{N, THETA, THETA_DOT, X_DOT};
use crate::model::variational::{self, DIM};
use crate::model::{BlockSystem, Mode};

impl Perturbable<N, DIM> for BlockSystem {
    fn coords(&self, y: &[f64; N]) -> [f64; DIM] {
        variational::coords(y)
    }

    fn tangent_dim(&self, mode: Mode) -> usize {
        variational::tangent_dim(mode)
    }

    /// Rock: Θ, Θ' displaced, X' put back on the stuck-pivot constraint.
    /// Slide-rock: all three, keeping the slip direction. Slide: X' only.
    /// The displaced state must stay on the mode's side of the impact
    /// surface (sΘ > 0) and keep its slip direction.
    fn displaced(&self, mode: Mode, _t: f64, y: &[f64; N], dz: &[f64; DIM]) -> Option<[f64; N]> {
        let geo = &self.model.geo;
        let mut yp = *y;
        match mode {
            Mode::Rest | Mode::Tumbled | Mode::Flight => return None,
            Mode::Slide { slip } => {
                yp[X_DOT] += dz[2];
                if slip.value() * yp[X_DOT] <= 0.0 {
                    return None;
                }
            }
            Mode::Rock { pivot } => {
                yp[THETA] += dz[0];
                yp[THETA_DOT] += dz[1];
                let tilt = Tilt::new(geo, pivot, yp[THETA]);
                yp[X_DOT] = tilt.c * geo.psi * yp[THETA_DOT];
                if pivot.value() * yp[THETA] <= 0.0 {
                    return None;
                }
            }
            Mode::SlideRock { pivot, slip } => {
                yp[THETA] += dz[0];
                yp[THETA_DOT] += dz[1];
                yp[X_DOT] += dz[2];
                let vp = variational::slip_velocity(geo, mode, &yp)?;
                if pivot.value() * yp[THETA] <= 0.0 || slip.value() * vp <= 0.0 {
                    return None;
                }
            }
        }
        Some(yp)
    }
}

impl TangentSystem<N, DIM> for BlockSystem {
    fn jacobian(&self, mode: Mode, t: f64, y: &[f64; N]) -> Square<DIM> {
        let fo = self.model.excitation.forcing(t);
        variational::field_jacobian(&self.model, mode, fo, y)
    }

    fn guard_gradient(&self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> Option<([f64; DIM], f64)> {
        let fo = self.model.excitation.forcing(t);
        let rate: Forcing = variational::forcing_rate(&self.model.excitation, t)?;
        variational::guard_gradient(&self.model, mode, index, fo, rate, y).map(|g| (g.state, g.time))
    }

    fn reset_jacobian(
        &self,
        before: Mode,
        index: usize,
        y_before: &[f64; N],
        after: Mode,
        y_after: &[f64; N],
    ) -> (Square<DIM>, usize) {
        let r = variational::reset_jacobian(&self.model, before, index, y_before, after, y_after);
        (r.matrix, r.dim)
    }
}
