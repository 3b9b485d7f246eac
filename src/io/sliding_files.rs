//! `sliding_spectrum.csv` of `rocking sliding-spectrum` (docs/engineering.md):
//! one row per block and friction coefficient, the slide-only block's rows
//! first, μ increasing. Columns with a physical unit name it (`_m`, `_s`);
//! empty cells mean "does not exist" (no residual after overturning), never
//! a NaN.

use serde::{Deserialize, Serialize};

use super::csv::{Num, Row};

/// A row of `sliding_spectrum.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct SlidingRow {
    /// Which block: `slide-only` (cannot rock: rigid-plastic sliding) or
    /// `block` (the given block, which may rock).
    pub block: String,
    /// Width B of the given block, m; empty for the slide-only block (its
    /// sliding depends on no size).
    pub width_m: Option<Num>,
    /// Height H of the given block, m; empty for the slide-only block.
    pub height_m: Option<Num>,
    /// Static friction coefficient μ_s (the spectrum's μ).
    pub mu: Num,
    /// Kinetic friction coefficient μ_k.
    pub mu_k: Num,
    /// How the run ended: rest, moving, overturned, flight.
    pub end: String,
    /// Largest |sliding displacement|, m (before overturning or flight when
    /// it ended so).
    pub peak_sliding_m: Num,
    /// Sliding displacement at the end, m, signed (+x to the right); empty
    /// when overturned or in flight.
    pub residual_sliding_m: Option<Num>,
    /// Peak |θ|/α (0 for the slide-only block).
    pub peak_theta_over_alpha: Num,
    /// Time of overturning, s; empty unless overturned.
    pub t_overturn_s: Option<Num>,
    /// Time the block left the ground, s; empty unless flight.
    pub t_flight_s: Option<Num>,
}

impl Row for SlidingRow {
    const HEADER: &'static [&'static str] = &[
        "block",
        "width_m",
        "height_m",
        "mu",
        "mu_k",
        "end",
        "peak_sliding_m",
        "residual_sliding_m",
        "peak_theta_over_alpha",
        "t_overturn_s",
        "t_flight_s",
    ];
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::csv::{header, header_of};

    #[test]
    fn the_header_is_the_row_fields() {
        let r = SlidingRow {
            block: "block".into(),
            width_m: Some(Num(0.4)),
            height_m: Some(Num(1.8)),
            mu: Num(0.2),
            mu_k: Num(0.2),
            end: "rest".into(),
            peak_sliding_m: Num(0.01),
            residual_sliding_m: Some(Num(-0.005)),
            peak_theta_over_alpha: Num(0.0),
            t_overturn_s: None,
            t_flight_s: None,
        };
        assert_eq!(header_of(&r), header::<SlidingRow>());
    }
}
