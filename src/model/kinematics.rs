//! Where the block's corners are: positions that follow from its geometry
//! and state alone (docs/model.md §1.4), for whatever draws or lays out a
//! block. Positions are per R unless a name says metres; Θ is the rotation
//! per ψ and X the centre's horizontal position per R (model conventions).

use super::geometry::Geometry;

/// Horizontal distance from the centre of mass to the bottom corner on
/// side `side` (+1 right, −1 left) at rotation Θ, per R:
/// `side · sin(ψ(1 − |Θ|))` (docs/model.md §1.4: X_p = X + s·sin(ψ(1 − |Θ|))
/// for the corner the block pivots on, `side = sign Θ`).
pub(crate) fn corner_offset(geo: &Geometry, side: f64, theta: f64) -> f64 {
    side * (geo.psi * (1.0 - theta.abs())).sin()
}

/// X of the centre of mass, per R, after the block turned from
/// (`theta0`, `x0`) to rotation `theta` about its bottom corner on side
/// `side`, that corner held fixed on the base (rotations of one sign, the
/// side's): a rigid turn, no mechanics.
pub fn turned_about_corner(geo: &Geometry, side: f64, theta0: f64, x0: f64, theta: f64) -> f64 {
    let corner = x0 + corner_offset(geo, side, theta0);
    corner - corner_offset(geo, side, theta)
}

/// Half the vertical extent of the block turned by `angle` rad, m:
/// ½(B|sin θ| + H|cos θ|), how far its highest corner is above its centre.
pub fn half_height_turned_m(geo: &Geometry, angle: f64) -> f64 {
    let (sin, cos) = angle.sin_cos();
    0.5 * (geo.width * sin.abs() + geo.height * cos.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The block's four corners, m, relative to its centre, turned by θ
    /// clockwise: (x, y) → (x cos θ + y sin θ, −x sin θ + y cos θ). Written
    /// here from the rectangle, not from the code under test.
    fn corners(geo: &Geometry, angle: f64) -> [(f64, f64); 4] {
        let (s, c) = angle.sin_cos();
        let (hw, hh) = (0.5 * geo.width, 0.5 * geo.height);
        [(-hw, -hh), (hw, -hh), (hw, hh), (-hw, hh)].map(|(x, y)| (x * c + y * s, -x * s + y * c))
    }

    /// Tolerance: a few roundings of numbers of order 1 m (the block is
    /// 1 m × 4 m): 1e-12 m is far above them and far below anything drawn.
    const TOL: f64 = 1e-12;

    #[test]
    fn the_corner_offset_is_where_the_turned_rectangle_puts_its_pivot_corner() {
        let geo = Geometry::new(1.0, 4.0);
        for theta in [0.3, -0.7, 0.99, -1.4] {
            let side: f64 = if theta > 0.0 { 1.0 } else { -1.0 };
            // The bottom corner on side `side` is corner 1 (right) or 0 (left).
            let (cx, _) = corners(&geo, geo.psi * theta)[if side > 0.0 { 1 } else { 0 }];
            let got = corner_offset(&geo, side, theta) * geo.r;
            assert!((got - cx).abs() < TOL, "Θ = {theta}: {got} vs {cx}");
        }
    }

    #[test]
    fn a_turn_about_a_corner_keeps_that_corner_where_it_was() {
        let geo = Geometry::new(1.0, 4.0);
        let (theta0, x0) = (0.8, 0.05);
        for theta in [0.8, 1.0, 2.0, geo.side_theta()] {
            let x = turned_about_corner(&geo, 1.0, theta0, x0, theta);
            let before = x0 * geo.r + corners(&geo, geo.psi * theta0)[1].0;
            let after = x * geo.r + corners(&geo, geo.psi * theta)[1].0;
            assert!(
                (after - before).abs() < TOL,
                "Θ = {theta}: corner moved {}",
                after - before
            );
        }
        // On its side, the centre lies H/2 beyond the corner.
        let x = turned_about_corner(&geo, 1.0, theta0, x0, geo.side_theta());
        let corner = x0 * geo.r + corners(&geo, geo.psi * theta0)[1].0;
        assert!((x * geo.r - corner - 2.0).abs() < TOL);
    }

    #[test]
    fn the_half_height_reaches_the_highest_corner() {
        let geo = Geometry::new(1.0, 4.0);
        for angle in [0.0, 0.2, -0.5, 1.2, std::f64::consts::FRAC_PI_2] {
            let top = corners(&geo, angle).iter().map(|c| c.1).fold(f64::MIN, f64::max);
            let got = half_height_turned_m(&geo, angle);
            assert!((got - top).abs() < TOL, "θ = {angle}: {got} vs {top}");
        }
    }
}
