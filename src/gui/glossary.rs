//! The paper's symbols in one sentence each, with this block's numbers:
//! shown on hover over the status bar's symbol line and the units switch,
//! and listed in Help ▸ Symbols. A newcomer meets Θ, τ, ψ and p on every
//! axis; the sentences say what they mean in degrees and seconds.

use crate::model::geometry::Geometry;

/// `(symbol, sentence)` for Θ, τ, ψ and p, with `geo`'s values.
pub fn entries(geo: &Geometry) -> [(&'static str, String); 4] {
    let psi_deg = geo.psi.to_degrees();
    [
        (
            "Θ",
            format!(
                "Θ = θ/ψ is the rotation θ as a fraction of the slenderness angle ψ: at Θ = ±1 the centre of mass is above a corner and the block tips over (here Θ = 1 is {psi_deg:.2}°)."
            ),
        ),
        (
            "τ",
            format!(
                "τ = p·t is time in units of 1/p, the block's own time scale, so blocks of any size can be compared (here 1 τ = {:.3} s).",
                1.0 / geo.p
            ),
        ),
        (
            "ψ",
            format!(
                "ψ = atan(B/H) is the slenderness angle (α in engineering texts): how far the block can tilt before it falls (here {psi_deg:.2}°, B/H = {:.3}).",
                geo.width / geo.height
            ),
        ),
        (
            "p",
            format!(
                "p = sqrt(3g/4R) is the block's frequency parameter, R its half-diagonal: a bigger block has a smaller p and rocks more slowly (here p = {:.3} 1/s, R = {:.3} m).",
                geo.p, geo.r
            ),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's 1 m × 4 m block: ψ = atan(1/4) = 14.04°, R = √4.25/… =
    /// 2.062 m, p = √(3·9.81/(4·2.062)) = 1.889 1/s, 1 τ = 0.529 s.
    #[test]
    fn the_sentences_carry_the_blocks_numbers() {
        let e = entries(&Geometry::new(1.0, 4.0));
        assert!(e[0].1.contains("14.04°"), "{}", e[0].1);
        assert!(e[1].1.contains("1 τ = 0.529 s"), "{}", e[1].1);
        assert!(e[2].1.contains("B/H = 0.250"), "{}", e[2].1);
        assert!(
            e[3].1.contains("p = 1.88") && e[3].1.contains("R = 2.062 m"),
            "{}",
            e[3].1
        );
    }
}
