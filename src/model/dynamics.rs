//! Equations of motion of each contact mode, in normalised variables.
//!
//! Derivations: `docs/model.md` §3–6. Variables: τ = p t, Θ = θ/ψ,
//! X = x_G/R, w = ψΘ' = θ̇/p. Forcing per unit weight: `a = a_h/g`,
//! `b = 1 + a_v/g`. Contact forces per unit weight: `f = F/(mg)` (horizontal,
//! on the block), `n = N/(mg)`.
//!
//! Contract: every function is written as `sign × (mirror-symmetric terms)`,
//! so that mirroring the problem (Θ, X, a_h → −Θ, −X, −a_h, pivot and slip
//! flipped) negates the odd outputs and keeps the even ones **bit for bit**.
//! The functions use `u = sΘ` (not `|Θ|`) so they stay smooth slightly past
//! Θ = 0, where the integrator's stages and the root finder evaluate them.

use super::geometry::{GAMMA, Geometry};
use super::mode::Sign;

/// Base acceleration at one instant, per unit g.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forcing {
    /// a_h/g.
    pub a: f64,
    /// a_v/g (upward positive).
    pub av: f64,
}

impl Forcing {
    /// b = 1 + a_v/g: effective gravity per unit g.
    #[inline]
    pub fn b(&self) -> f64 {
        1.0 + self.av
    }
}

/// Accelerations and contact forces of one mode at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accel {
    /// Θ''.
    pub theta_ddot: f64,
    /// X''.
    pub x_ddot: f64,
    /// Normal force per unit weight, n = N/(mg).
    pub normal: f64,
    /// Horizontal contact force on the block per unit weight, f = F/(mg).
    pub friction: f64,
}

/// Angle quantities of a tilted block: φ = ψ(1 − sΘ) and its sine/cosine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tilt {
    /// sin φ.
    pub sn: f64,
    /// cos φ.
    pub c: f64,
}

/// Largest |θ| = |ψΘ| for which [`Tilt::new`] uses its series: there the
/// first omitted terms, θ¹⁵/15! and θ¹⁶/16!, are below 0.25 ulp.
const SERIES_LIMIT: f64 = 0.5;

/// sin θ and cos θ for |θ| <= [`SERIES_LIMIT`] by their Taylor series to
/// θ¹³ and θ¹⁴, as polynomials in z = θ² evaluated by Estrin's scheme
/// (pairs of terms, then pairs of pairs with z² and z⁴). The tilt lies on
/// the critical path of every stage of a step (stage state → tilt →
/// acceleration → next stage), so its latency, not its operation count, is
/// what costs: Estrin's tree is 6 operations deep where Horner's chain is
/// 14. The two series are independent and run side by side.
#[inline]
fn small_sin_cos(x: f64) -> (f64, f64) {
    let z = x * x;
    let z2 = z * z;
    let z4 = z2 * z2;
    // sin θ / θ = Σ (−z)^k / (2k+1)!, k = 0..6.
    let s01 = 1.0 - z * (1.0 / 6.0);
    let s23 = 1.0 / 120.0 - z * (1.0 / 5040.0);
    let s45 = 1.0 / 362_880.0 - z * (1.0 / 39_916_800.0);
    let s6 = 1.0 / 6_227_020_800.0;
    let sn = x * ((s01 + z2 * s23) + z4 * (s45 + z2 * s6));
    // cos θ = Σ (−z)^k / (2k)!, k = 0..7.
    let c01 = 1.0 - z * 0.5;
    let c23 = 1.0 / 24.0 - z * (1.0 / 720.0);
    let c45 = 1.0 / 40_320.0 - z * (1.0 / 3_628_800.0);
    let c67 = 1.0 / 479_001_600.0 - z * (1.0 / 87_178_291_200.0);
    let c = (c01 + z2 * c23) + z4 * (c45 + z2 * c67);
    (sn, c)
}

impl Tilt {
    /// Tilt about pivot `s` at angle `theta` (Θ).
    ///
    /// φ = ψ − θ with θ = ψ sΘ, so sin φ = sin ψ cos θ − cos ψ sin θ and
    /// cos φ = cos ψ cos θ + sin ψ sin θ, with sin ψ and cos ψ stored in the
    /// geometry and θ small for every block that rocks visibly. Both depend
    /// on sΘ only, so a state and its mirror image get the same bits. Beyond
    /// [`SERIES_LIMIT`] (squat blocks far over) the library's `sin_cos`.
    #[inline]
    pub fn new(geo: &Geometry, s: Sign, theta: f64) -> Self {
        let x = geo.psi * (s.value() * theta);
        if x.abs() <= SERIES_LIMIT {
            let (sx, cx) = small_sin_cos(x);
            Self {
                sn: geo.sin_psi * cx - geo.cos_psi * sx,
                c: geo.cos_psi * cx + geo.sin_psi * sx,
            }
        } else {
            let phi = geo.psi * (1.0 - s.value() * theta);
            let (sn, c) = phi.sin_cos();
            Self { sn, c }
        }
    }
}

/// Rocking about a stuck corner (not printed in the paper; docs/model.md §3):
/// ψΘ'' = −(s b sin φ + a cos φ).
#[inline]
pub fn rock(geo: &Geometry, pivot: Sign, theta: f64, theta_dot: f64, fo: Forcing) -> Accel {
    rock_at(geo, pivot, Tilt::new(geo, pivot, theta), theta_dot, fo)
}

/// [`rock`] with the tilt already computed.
#[inline]
pub(crate) fn rock_at(geo: &Geometry, pivot: Sign, tilt: Tilt, theta_dot: f64, fo: Forcing) -> Accel {
    let s = pivot.value();
    let Tilt { sn, c } = tilt;
    let b = fo.b();
    let w = geo.psi * theta_dot;
    let wdd = -(s * b * sn + fo.a * c);
    let ww = w * w;
    Accel {
        theta_ddot: wdd * geo.inv_psi,
        x_ddot: c * wdd + s * sn * ww,
        normal: b + GAMMA * (s * sn * wdd - c * ww),
        friction: fo.a + GAMMA * (c * wdd + s * sn * ww),
    }
}

/// A lower bound of the normal force n of [`rock_at`] over every state with
/// |Θ| ≤ `theta_max` and |Θ'| ≤ `theta_dot_max` and every forcing with
/// |a| ≤ `a_max` and b ≥ `b_min`; `−∞` when the tilt may pass π/2.
///
/// With ψΘ'' = −(s b sin φ + a cos φ), `rock_at`'s n = b + γ(s sin φ ψΘ'' −
/// cos φ w²) is n = b(1 − γ sin²φ) − γ s a sin φ cos φ − γ cos φ w²
/// (docs/model.md §3). For φ = ψ(1 − sΘ) in [0, π/2], 0 ≤ sin φ ≤
/// min(1, ψ(1 + |Θ|)) and 0 ≤ cos φ ≤ 1, and γ sin²φ ≤ γ < 1, so each term
/// is bounded by its worst case separately.
pub(crate) fn rock_normal_lower_bound(
    geo: &Geometry,
    theta_max: f64,
    theta_dot_max: f64,
    a_max: f64,
    b_min: f64,
) -> f64 {
    let phi_max = geo.psi * (1.0 + theta_max);
    let phi_min = geo.psi * (1.0 - theta_max);
    if !(phi_max <= std::f64::consts::FRAC_PI_2 && phi_min >= 0.0) || b_min <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let sn_max = phi_max.min(1.0);
    let w = geo.psi * theta_dot_max;
    b_min * (1.0 - GAMMA * sn_max * sn_max) - GAMMA * a_max * sn_max - GAMMA * w * w
}

/// Rocking about a corner that slips in direction `slip` against kinetic
/// friction `mu_k` (paper eqs. 9–10/30–31, corrected; docs/model.md §4):
/// ψΘ'' = −k (b − γ c w²)/((1−γ) + γ(sin²φ − sσμ_k sin φ cos φ)),
/// k = s sin φ − σ μ_k cos φ.
#[inline]
pub fn slide_rock(
    geo: &Geometry,
    pivot: Sign,
    slip: Sign,
    mu_k: f64,
    theta: f64,
    theta_dot: f64,
    fo: Forcing,
) -> Accel {
    slide_rock_at(geo, pivot, slip, mu_k, Tilt::new(geo, pivot, theta), theta_dot, fo)
}

/// [`slide_rock`] with the tilt already computed.
#[inline]
pub(crate) fn slide_rock_at(
    geo: &Geometry,
    pivot: Sign,
    slip: Sign,
    mu_k: f64,
    tilt: Tilt,
    theta_dot: f64,
    fo: Forcing,
) -> Accel {
    let s = pivot.value();
    let sigma = slip.value();
    let Tilt { sn, c } = tilt;
    let b = fo.b();
    let w = geo.psi * theta_dot;
    let ww = w * w;
    let k = s * sn - sigma * mu_k * c;
    let den = (1.0 - GAMMA) + GAMMA * (sn * sn - s * sigma * mu_k * sn * c);
    let wdd = -k * (b - GAMMA * c * ww) / den;
    let normal = b + GAMMA * (s * sn * wdd - c * ww);
    let friction = -sigma * mu_k * normal;
    Accel {
        theta_ddot: wdd / geo.psi,
        x_ddot: (friction - fo.a) / GAMMA,
        normal,
        friction,
    }
}

/// The slide-rock denominator D = (1−γ) + γ(sin²φ − sσμ_k sin φ cos φ).
/// Slide-rock is well posed only while D > 0 (docs/model.md §4.2).
#[inline]
pub(crate) fn slide_rock_denominator(geo: &Geometry, pivot: Sign, slip: Sign, mu_k: f64, theta: f64) -> f64 {
    let Tilt { sn, c } = Tilt::new(geo, pivot, theta);
    (1.0 - GAMMA) + GAMMA * (sn * sn - pivot.value() * slip.value() * mu_k * sn * c)
}

/// Flat block sliding in direction `slip`: X'' = −(σ μ_k b + a)/γ.
#[inline]
pub fn slide(slip: Sign, mu_k: f64, fo: Forcing) -> Accel {
    let b = fo.b();
    let friction = -slip.value() * mu_k * b;
    Accel {
        theta_ddot: 0.0,
        x_ddot: (friction - fo.a) / GAMMA,
        normal: b,
        friction,
    }
}

/// Flat block stuck to the base: the base supplies f = a, n = b.
#[inline]
pub fn rest(fo: Forcing) -> Accel {
    Accel {
        theta_ddot: 0.0,
        x_ddot: 0.0,
        normal: fo.b(),
        friction: fo.a,
    }
}

/// Slip velocity of the pivot corner, X_p' = X' − cos φ · w.
#[inline]
pub fn pivot_slip_velocity(geo: &Geometry, pivot: Sign, theta: f64, theta_dot: f64, x_dot: f64) -> f64 {
    let Tilt { c, .. } = Tilt::new(geo, pivot, theta);
    x_dot - c * geo.psi * theta_dot
}

/// Slip acceleration of the pivot corner, X_p'' = X'' − (c wdd + s sin φ w²),
/// used to check that a slip direction entered at zero slip velocity is
/// consistent.
#[inline]
pub fn pivot_slip_accel(geo: &Geometry, pivot: Sign, theta: f64, theta_dot: f64, acc: &Accel) -> f64 {
    let s = pivot.value();
    let Tilt { sn, c } = Tilt::new(geo, pivot, theta);
    let w = geo.psi * theta_dot;
    acc.x_ddot - (c * geo.psi * acc.theta_ddot + s * sn * w * w)
}

/// Lowest angular acceleration, on side `s`, of a flat block at rest that is
/// released: κ_s = b sin ψ + s a cos ψ = −s ψΘ''(Θ = 0). The base lifts the
/// block about corner `s` when κ_s < 0 (paper eq. 1 with |a_h| and a_v).
#[inline]
pub fn restoring(geo: &Geometry, pivot: Sign, fo: Forcing) -> f64 {
    fo.b() * geo.sin_psi + pivot.value() * fo.a * geo.cos_psi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilt_agrees_with_the_library_sine_and_cosine() {
        let mut worst = 0.0f64;
        for bh in [0.05, 0.1, 0.25, 0.5, 1.0] {
            let geo = Geometry::new(bh, 1.0);
            for i in -3000..=3000 {
                let theta = f64::from(i) / 2000.0;
                for s in [Sign::Pos, Sign::Neg] {
                    let t = Tilt::new(&geo, s, theta);
                    let (sn, c) = (geo.psi * (1.0 - s.value() * theta)).sin_cos();
                    // Absolute error: the values are at most 1 and enter the
                    // equations of motion linearly.
                    worst = worst.max((t.sn - sn).abs()).max((t.c - c).abs());
                    // Mirror image: pivot and Θ both flipped, same bits.
                    let m = Tilt::new(&geo, s.flip(), -theta);
                    assert_eq!((m.sn.to_bits(), m.c.to_bits()), (t.sn.to_bits(), t.c.to_bits()));
                }
            }
        }
        assert!(worst <= 4.0 * f64::EPSILON, "largest difference {worst:e}");
    }

    proptest::proptest! {
        /// The bound holds at every state and forcing inside its box,
        /// corners included (the extremes are where a bound fails first).
        #[test]
        fn the_normal_force_bound_holds_inside_its_box(
            bh in 0.05f64..1.0,
            theta_max in 0.0f64..1.0,
            theta_dot_max in 0.0f64..3.0,
            a_max in 0.0f64..1.5,
            av_max in 0.0f64..0.99,
            u in proptest::array::uniform4(-1.0f64..=1.0),
            corner in proptest::bool::ANY,
            pivot in proptest::bool::ANY,
        ) {
            let geo = Geometry::new(bh, 1.0);
            let b_min = 1.0 - av_max;
            let bound = rock_normal_lower_bound(&geo, theta_max, theta_dot_max, a_max, b_min);
            // Corners: every coordinate at an end of its range.
            let u = if corner { u.map(f64::signum) } else { u };
            let s = if pivot { Sign::Pos } else { Sign::Neg };
            let theta = s.value() * theta_max * u[0];
            let theta_dot = theta_dot_max * u[1];
            let fo = Forcing { a: a_max * u[2], av: av_max * u[3] };
            let n = rock(&geo, s, theta, theta_dot, fo).normal;
            proptest::prop_assert!(n >= bound - 1e-12, "n = {n} below the bound {bound}");
        }
    }

    #[test]
    fn the_normal_force_bound_is_tight_enough_to_use_on_the_papers_block() {
        // The paper's block (B/H = 1/4) under the periodic scene's forcing
        // (A_h = 2, A_v = 0.5 in units of ψ g), |Θ| ≤ 0.4, |Θ'| ≤ 1.2: the
        // bound must clear zero by far, or the driver gains nothing.
        let geo = Geometry::new(1.0, 4.0);
        let bound = rock_normal_lower_bound(&geo, 0.4, 1.2, 2.0 * geo.psi, 1.0 - 0.5 * geo.psi);
        assert!(bound > 0.5, "bound {bound}");
        // Past a tilt of π/2 there is no bound.
        assert_eq!(
            rock_normal_lower_bound(&Geometry::new(1.0, 1.0), 1.1, 0.0, 0.0, 1.0),
            f64::NEG_INFINITY
        );
    }
}
