//! The rocking frame: `columns` identical free-standing rectangular columns
//! under a rigid cap beam that rests on their top corners, the columns
//! rocking together (Makris & Vassiliou 2013, EESD, doi 10.1002/eqe.2222).
//! EQUATIONS ONLY, derived from the frame's own Lagrangian in
//! `docs/model.md` §16.
//!
//! Variables are the block's, for one column (τ = p t with the column's p,
//! Θ = θ/ψ with the column's slenderness ψ, X = x_G/R of the column's
//! centre), and the state is the block's `[Θ, Θ', X, X', W, D]`. Energies
//! and forces are per unit weight of one column (m_c g R and m_c g), with
//! its share `1/columns` of the beam.
//!
//! The columns rock on stuck corners: a frame does not slide (friction is
//! not a key of a frame; `docs/model.md` §16 says why).

mod system;
mod tangent;
#[cfg(test)]
mod tests;

pub use system::FrameSystem;
pub use tangent::{FRAME_COORDS, FRAME_DIM};

use super::ad::Scalar;
use super::dynamics::{Forcing, Tilt};
use super::geometry::{GAMMA, Geometry};
use super::mode::Sign;

/// What a frame adds to its columns' geometry (config `[frame]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Number of columns, ≥ 2.
    pub columns: u32,
    /// Mass of the cap beam over the columns' total mass, γ_b ≥ 0.
    pub beam_mass_ratio: f64,
}

impl Frame {
    /// κ = (1 + 2γ_b)/(1 + 3γ_b): the factor on a lone column's angular
    /// acceleration. The beam adds twice a column's lever arm to the
    /// moment (its support is twice as far from the pivot as the column's
    /// centre) and four times its arm squared to the inertia (docs/model.md
    /// §16.1), so a heavier beam makes the frame rock more slowly.
    pub fn kappa(&self) -> f64 {
        let g = self.beam_mass_ratio;
        (1.0 + 2.0 * g) / (1.0 + 3.0 * g)
    }

    /// The ratio of angular velocities across an impact in which every
    /// column's new pivot and the beam's new supports stick
    /// (docs/model.md §16.3):
    /// r = (1 − 1.5 sin²ψ + 3γ_b cos 2ψ)/(1 + 3γ_b), Housner's for γ_b = 0.
    /// It may be ≤ 0 for a squat column under a heavy beam (cos 2ψ < 0):
    /// the frame then comes to rest.
    pub fn restitution(&self, geo: &Geometry) -> f64 {
        let g = self.beam_mass_ratio;
        let cos_2psi = 1.0 - 2.0 * geo.sin_psi * geo.sin_psi;
        (geo.housner_r() + 3.0 * g * cos_2psi) / (1.0 + 3.0 * g)
    }

    /// Kinetic energy per m_c g R of the frame rocking at w = ψΘ':
    /// ½(1 + 3γ_b) w² (docs/model.md §16.2).
    pub fn kinetic(&self, w: f64) -> f64 {
        0.5 * (1.0 + 3.0 * self.beam_mass_ratio) * w * w
    }

    /// The weight the frame's centre of mass moves with, per column
    /// weight: the factor 1 + 2γ_b on the column's height and horizontal
    /// position in the potential energy and the base's work.
    pub fn lever(&self) -> f64 {
        1.0 + 2.0 * self.beam_mass_ratio
    }

    /// Where a column and the beam are when the columns of `geo` are
    /// turned by θ = `theta` rad (clockwise, on their right corners when
    /// positive): each body's rotation (rad) and its centre's displacement
    /// from where it stands at rest, horizontal and up (m). A column turns
    /// about its pivot, its centre moving by
    /// (s b (1 − cos θ) + h sin θ, b |sin θ| − h (1 − cos θ)) with s the
    /// pivot's side and b, h its half width and half height; the beam does
    /// not turn and its supports, the columns' opposite top corners, are
    /// twice as far from the pivots, so it moves by twice that
    /// (docs/model.md §16.1: it rises by 2R(cos(ψ − |θ|) − cos ψ)).
    pub fn bodies(&self, geo: &Geometry, theta: f64) -> [[f64; 3]; 2] {
        let (b, h) = (0.5 * geo.width, 0.5 * geo.height);
        let (sn, c) = theta.sin_cos();
        let dx = theta.signum() * b * (1.0 - c) + h * sn;
        let dy = b * sn.abs() - h * (1.0 - c);
        [[theta, dx, dy], [0.0, 2.0 * dx, 2.0 * dy]]
    }
}

/// Accelerations and contact forces of a rocking frame at one state (`S`:
/// `f64`, or a dual number for the tangent dynamics, `tangent.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameAccel<S = f64> {
    /// ψΘ'': the columns' angular acceleration, per p².
    pub wdd: S,
    /// X'': of a column's centre.
    pub x_ddot: S,
    /// Normal force at a column's base, per column weight: its own share
    /// and its share of the beam (≤ 0: the frame flies).
    pub base_normal: S,
    /// Normal force between the columns and the beam, per beam weight
    /// (≤ 0: the beam lifts off the columns).
    pub beam_normal: S,
}

/// The frame rocking about pivot side `pivot` with tilt `tilt` at
/// ψΘ' = `w` under `fo` (docs/model.md §16.1–16.2):
/// ψΘ'' = −κ (s b sin φ + a cos φ).
///
/// Written once over a generic [`Scalar`] (constants on the right, as
/// `model::ad` asks): over `f64` these are the operations of a run, over
/// dual numbers the frame's tangent dynamics.
#[inline]
pub fn rock<S: Scalar>(frame: &Frame, kappa: f64, pivot: Sign, tilt: Tilt<S>, w: S, fo: Forcing<S>) -> FrameAccel<S> {
    let s = pivot.value();
    let Tilt { sn, c } = tilt;
    let b = fo.b();
    let wdd = (b * s * sn + fo.a * c) * -kappa;
    let ww = w * w;
    // Y'' of a column's centre per p²R: (cos φ)'' = s sin φ ψΘ'' − cos φ w².
    let y_ddot = sn * s * wdd - c * ww;
    // The beam's supports move on circles of twice the radius (2R), so the
    // beam's vertical acceleration is twice a column centre's.
    let beam_normal = b + y_ddot * (2.0 * GAMMA);
    FrameAccel {
        wdd,
        x_ddot: c * wdd + sn * s * ww,
        base_normal: b + y_ddot * GAMMA + beam_normal * frame.beam_mass_ratio,
        beam_normal,
    }
}
