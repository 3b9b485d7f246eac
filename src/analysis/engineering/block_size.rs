//! A rectangular block's size, m, and the quantities that follow from it.

/// A rectangular block, m.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BlockSize {
    /// Width B, m, > 0.
    pub width_m: f64,
    /// Height H, m, > 0.
    pub height_m: f64,
}

impl BlockSize {
    /// The block of half-diagonal `r_m` (m) and slenderness ratio
    /// `b_over_h` = B/H: B = 2R sin α, H = 2R cos α, α = atan(B/H).
    pub(crate) fn from_half_diagonal(r_m: f64, b_over_h: f64) -> Self {
        let alpha = b_over_h.atan();
        Self {
            width_m: 2.0 * r_m * alpha.sin(),
            height_m: 2.0 * r_m * alpha.cos(),
        }
    }

    /// The block of height `h_m` (m) and ratio `b_over_h` = B/H.
    pub(crate) fn from_height(h_m: f64, b_over_h: f64) -> Self {
        Self {
            width_m: b_over_h * h_m,
            height_m: h_m,
        }
    }

    /// Half-diagonal R = ½√(B²+H²), m.
    pub fn half_diagonal_m(&self) -> f64 {
        0.5 * self.width_m.hypot(self.height_m)
    }

    /// Slenderness angle α = atan(B/H), rad.
    pub fn alpha(&self) -> f64 {
        self.width_m.atan2(self.height_m)
    }

    /// Frequency parameter p = √(3g/(4R)), 1/s.
    pub fn p_per_s(&self) -> f64 {
        crate::model::Geometry::new(self.width_m, self.height_m).p
    }
}
