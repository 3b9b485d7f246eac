//! Mechanical energy of the block in the base frame, per unit m g R.
//!
//! T = ½γ(X'² + Y'²) + (γ/6) w² (γ = R p²/g; I_G = mR²/3), V = Y = y_G/R.
//! The base's pseudo-forces do work at the rate −a X' − (a_v/g) Y' per unit
//! τ; friction dissipates −f X_p'. See docs/model.md §8.

use super::dynamics::Tilt;
use super::geometry::{GAMMA, Geometry};
use super::mode::{Mode, Sign};

/// Height Y = y_G/R and vertical velocity Y' of the centre of mass.
#[inline]
pub fn height(geo: &Geometry, mode: Mode, theta: f64, theta_dot: f64) -> (f64, f64) {
    match mode {
        Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => tilted_height(geo, pivot, theta, theta_dot),
        Mode::Rest | Mode::Slide { .. } => (geo.cos_psi, 0.0),
        Mode::Tumbled | Mode::Flight => {
            // Terminal states keep the geometry of the last contact: tilted
            // about the side Θ is on, or, at Θ = 0, about the side Θ' moves
            // to (the block left the base rotating); flat if neither.
            if theta != 0.0 {
                tilted_height(geo, Sign::of(theta), theta, theta_dot)
            } else if theta_dot != 0.0 {
                tilted_height(geo, Sign::of(theta_dot), theta, theta_dot)
            } else {
                (geo.cos_psi, 0.0)
            }
        }
    }
}

#[inline]
fn tilted_height(geo: &Geometry, pivot: Sign, theta: f64, theta_dot: f64) -> (f64, f64) {
    let Tilt { sn, c } = Tilt::new(geo, pivot, theta);
    (c, pivot.value() * sn * geo.psi * theta_dot)
}

/// Kinetic energy / (m g R).
#[inline]
pub fn kinetic(geo: &Geometry, x_dot: f64, y_dot: f64, theta_dot: f64) -> f64 {
    let w = geo.psi * theta_dot;
    0.5 * GAMMA * (x_dot * x_dot + y_dot * y_dot) + GAMMA / 6.0 * w * w
}

/// Total mechanical energy / (m g R) of a state `[Θ, Θ', X, X', ..]` in `mode`.
#[inline]
pub fn total(geo: &Geometry, mode: Mode, theta: f64, theta_dot: f64, x_dot: f64) -> f64 {
    let (y, y_dot) = height(geo, mode, theta, theta_dot);
    kinetic(geo, x_dot, y_dot, theta_dot) + y
}
