//! Block geometry and the constants derived from it.

/// Standard gravity, m/s². Used only to convert normalised results to
/// physical units (and recorded ground motion to τ).
pub const G: f64 = 9.81;

/// γ = mR²/I_O = 3/4 for a rectangular block (paper eq. 13). It also equals
/// R p²/g, which is why it appears wherever a normalised acceleration meets
/// a force per unit weight.
pub(crate) const GAMMA: f64 = 0.75;

/// A rectangular block of width `B` and height `H` (metres), with the
/// quantities of MODEL-DECISIONS "Conventions and units".
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Width B, m.
    pub width: f64,
    /// Height H, m.
    pub height: f64,
    /// Slenderness ψ = atan(B/H), rad.
    pub psi: f64,
    /// 1/ψ: the rocking equations divide by ψ in every evaluation, and a
    /// division is several times slower than a multiplication.
    pub inv_psi: f64,
    /// sin ψ.
    pub sin_psi: f64,
    /// cos ψ.
    pub cos_psi: f64,
    /// tan ψ = B/H.
    pub tan_psi: f64,
    /// Half-diagonal R = ½√(B²+H²), m.
    pub r: f64,
    /// Frequency parameter p = √(3g/(4R)), 1/s: τ = p t.
    pub p: f64,
}

impl Geometry {
    /// Geometry of a `width` × `height` block (metres, both > 0).
    pub fn new(width: f64, height: f64) -> Self {
        let psi = width.atan2(height);
        let (sin_psi, cos_psi) = psi.sin_cos();
        let r = 0.5 * width.hypot(height);
        Self {
            width,
            height,
            psi,
            inv_psi: 1.0 / psi,
            sin_psi,
            cos_psi,
            tan_psi: width / height,
            r,
            p: (3.0 * G / (4.0 * r)).sqrt(),
        }
    }

    /// Housner's coefficient r = 1 − 1.5 sin²ψ: the ratio of angular
    /// velocities across an impact that conserves angular momentum about
    /// the striking corner, for a block rocking without slip.
    pub fn housner_r(&self) -> f64 {
        1.0 - 1.5 * self.sin_psi * self.sin_psi
    }

    /// The sliding displacement per R (docs/model.md §1.7): where the
    /// middle of the block's base would be, relative to the base's origin,
    /// if the block were tipped back flat about its pivot,
    /// `U = X + s(sin(ψ(1 − |Θ|)) − sin ψ)` with the pivot side
    /// `s = sign Θ` (MODEL-DECISIONS), and `U = X` when flat (Θ = 0, where
    /// both corners give the same value). Rocking about a sticking pivot
    /// leaves it unchanged; only slip moves it, and it is continuous across
    /// impacts. Holds in every mode, the terminal ones included.
    pub fn sliding(&self, theta: f64, x: f64) -> f64 {
        if theta == 0.0 {
            return x;
        }
        x + theta.signum() * ((self.psi * (1.0 - theta.abs())).sin() - self.sin_psi)
    }

    /// Height the lifted corner reaches at rotation |Θ|, m: B·sin(ψ|Θ|)
    /// (to the block lying on its side, |θ| = π/2).
    pub(crate) fn uplift_m(&self, abs_theta: f64) -> f64 {
        self.width * (self.psi * abs_theta).min(std::f64::consts::FRAC_PI_2).sin()
    }

    /// |Θ| at which the block lies on its side (|θ| = π/2).
    pub fn side_theta(&self) -> f64 {
        std::f64::consts::FRAC_PI_2 / self.psi
    }
}
