//! The frame's tangent dynamics, generated from its equations (the vector
//! field and guards of `system.rs`, written once over a generic scalar) by
//! forward-mode automatic differentiation, and the Jacobian of its impact.
//! EQUATIONS ONLY: the saltation matrices and the QR renormalisation that
//! use them are `analysis::lyapunov`'s.
//!
//! Tangent coordinates `z = (Θ, Θ')` ([`FRAME_COORDS`]): the frame has one
//! degree of freedom, its columns rocking together on stuck corners, so the
//! columns' X' follows Θ' (`X' = cos φ · ψΘ'`) and X is neutral (nothing
//! depends on it; its exponent is 0). Rest and the terminal modes leave no
//! direction free.

use super::FrameSystem;
use crate::integrate::hybrid::MAX_GUARDS;
use crate::model::ad::Dual;
use crate::model::dynamics::Forcing;
use crate::model::mode::Mode;
use crate::model::state::{N, THETA, THETA_DOT};

/// Number of tangent coordinates of a frame.
pub const FRAME_DIM: usize = 2;

/// Indices of `z = (Θ, Θ')` in the state `[Θ, Θ', X, X', W, D]`.
pub const FRAME_COORDS: [usize; FRAME_DIM] = [THETA, THETA_DOT];

impl FrameSystem {
    /// Free directions of `z` in `mode`: both while the frame rocks.
    pub fn tangent_dim(mode: Mode) -> usize {
        match mode {
            Mode::Rock { .. } => FRAME_DIM,
            Mode::Rest | Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => 0,
        }
    }

    /// `∂(Θ', Θ'')/∂(Θ, Θ')` of `mode`'s vector field at forcing `fo` and
    /// state `y`, row-major. While the frame rocks its trace is 0 (Θ''
    /// reads Θ alone): the flow keeps phase-space area between impacts.
    pub fn field_jacobian(&self, mode: Mode, fo: Forcing, y: &[f64; N]) -> [[f64; FRAME_DIM]; FRAME_DIM] {
        let fo = Forcing {
            a: Dual::<FRAME_DIM>::constant(fo.a),
            av: Dual::constant(fo.av),
        };
        let dy = self.field(mode, fo, &Dual::seeded(y, &FRAME_COORDS));
        FRAME_COORDS.map(|i| dy[i].d)
    }

    /// Gradient of guard `index` of `mode`, `(∂g/∂z, ∂g/∂τ)`, at forcing
    /// `fo`, forcing rate `rate` (dτ of a/g and a_v/g) and state `y`;
    /// `None` for an index the mode does not have.
    pub fn guard_gradient(
        &self,
        mode: Mode,
        index: usize,
        fo: Forcing,
        rate: Forcing,
        y: &[f64; N],
    ) -> Option<([f64; FRAME_DIM], f64)> {
        // Directions: Θ, Θ', then τ.
        const T: usize = FRAME_DIM;
        let fo = fo.timed::<{ FRAME_DIM + 1 }>(rate);
        let mut g = [Dual::constant(0.0); MAX_GUARDS];
        let n = self.guard_values(mode, fo, &Dual::seeded(y, &FRAME_COORDS), &mut g);
        let d = g.get(index).filter(|_| index < n)?.d;
        Some(([d[0], d[1]], d[T]))
    }

    /// Jacobian of the reset of guard `index` of `before` at `y_before`,
    /// which ended in `after`, and how many directions survive it.
    ///
    /// The impact (`Rock`, guard 0) maps `(Θ, Θ')` to `(0, r Θ')`, with r
    /// the frame's ratio: both directions survive (the saltation matrix
    /// adds the one along the flow that the reset's Θ row drops). An
    /// accumulation (which a ratio r ≤ 0 always is: the frame lands flat)
    /// or a mode with no free direction ends them all. Every other event
    /// ends the frame's rocking (tumble, flight) or starts it from rest,
    /// where no direction was free.
    pub fn reset_jacobian(
        &self,
        before: Mode,
        index: usize,
        y_before: &[f64; N],
        after: Mode,
    ) -> ([[f64; FRAME_DIM]; FRAME_DIM], usize) {
        let none = ([[0.0; FRAME_DIM]; FRAME_DIM], 0);
        if !matches!((before, index), (Mode::Rock { .. }, 0)) || Self::tangent_dim(after) == 0 {
            return none;
        }
        let geo = &self.model.geo;
        let r = self.impact_ratio().max(0.0);
        // The same bits as the impact's test for an accumulation.
        let theta_dot = r * (geo.psi * y_before[THETA_DOT]) / geo.psi;
        if theta_dot.abs() < self.model.zeno_eps {
            return none;
        }
        ([[0.0, 0.0], [0.0, r]], FRAME_DIM)
    }
}

#[cfg(test)]
mod tests;
