//! The block, its contact with the base, and its impact law's coefficients.

use super::LawKind;
use crate::model::Geometry;

/// The block and its contact with the base.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Width B, m, > 0. Default 1 (the paper's).
    pub width: f64,
    /// Height H, m, > 0. Default 4 (the paper's).
    pub height: f64,
    /// Static friction coefficient μ_s ≥ 0, or infinite (no sliding, the
    /// paper's sec. 4.1; the default).
    pub mu_s: f64,
    /// Kinetic friction coefficient μ_k, 0 ≤ μ_k ≤ μ_s; `None`: μ_s.
    pub mu_k: Option<f64>,
}

impl Block {
    /// The block's geometry.
    pub fn geometry(&self) -> Geometry {
        Geometry::new(self.width, self.height)
    }

    /// μ_k, resolved.
    pub fn kinetic(&self) -> f64 {
        self.mu_k.unwrap_or(self.mu_s)
    }
}

/// The impact law and its coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct Impact {
    /// The law.
    pub law: LawKind,
    /// Ratio r of the ratio law, in [0, 1]; `None`: Housner's 1 − 1.5 sin²ψ
    /// (0 for blocks squat enough that it is negative).
    pub r: Option<f64>,
    /// Vertical restitution e of the impulse law, in [0, 1]. Default 0.
    pub e: f64,
    /// Static friction μ̄_s during impact; `None`: the block's μ_s (as in
    /// the paper).
    pub mu_s: Option<f64>,
    /// Kinetic friction μ̄_k during impact; `None`: min(μ_k, μ̄_s).
    pub mu_k: Option<f64>,
}
