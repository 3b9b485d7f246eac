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
//!
//! The equations are written once, over a generic [`Scalar`]: over `f64`
//! they are the vector field (the same operations as code written for
//! `f64`), over dual numbers its Jacobian (`variational`), over jets its
//! Taylor series (`series`). Constants multiply on the right (`sn * s`
//! for `s sin φ`), which has the bits of the left.

use super::ad::{Dual, Scalar};
use super::geometry::{GAMMA, Geometry};
use super::mode::{Mode, Sign};
use super::state::{N, THETA, THETA_DOT, X_DOT};

/// Base acceleration at one instant, per unit g (`S`: see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forcing<S = f64> {
    /// a_h/g.
    pub a: S,
    /// a_v/g (upward positive).
    pub av: S,
}

impl<S: Scalar> Forcing<S> {
    /// b = 1 + a_v/g: effective gravity per unit g.
    #[inline]
    pub fn b(&self) -> S {
        self.av + 1.0
    }
}

impl Forcing {
    /// This forcing as dual numbers of `D` directions whose last is time
    /// (τ), with `rate` (dτ of a/g and a_v/g) as its partials there: what a
    /// guard's time partial reads.
    #[inline]
    pub(crate) fn timed<const D: usize>(self, rate: Forcing) -> Forcing<Dual<D>> {
        let (mut a, mut av) = ([0.0; D], [0.0; D]);
        a[D - 1] = rate.a;
        av[D - 1] = rate.av;
        Forcing {
            a: Dual::with_partials(self.a, a),
            av: Dual::with_partials(self.av, av),
        }
    }
}

/// Accelerations and contact forces of one mode at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accel<S = f64> {
    /// Θ''.
    pub theta_ddot: S,
    /// X''.
    pub x_ddot: S,
    /// Normal force per unit weight, n = N/(mg).
    pub normal: S,
    /// Horizontal contact force on the block per unit weight, f = F/(mg).
    pub friction: S,
}

/// Angle quantities of a tilted block: φ = ψ(1 − sΘ) and its sine/cosine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tilt<S = f64> {
    /// sin φ.
    pub sn: S,
    /// cos φ.
    pub c: S,
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

impl<S: Scalar> Tilt<S> {
    /// [`Tilt::new`] of a generic Θ: the values are those of `Tilt::new`
    /// at Θ's value, the derivatives those of φ = ψ − sψΘ. Always inlined:
    /// over `f64` it must reduce to `Tilt::new` (the derivative part is dead
    /// code there), which the optimiser sees only inside the caller.
    #[inline(always)]
    pub fn of(geo: &Geometry, s: Sign, theta: S) -> Self {
        let value = Tilt::new(geo, s, theta.value());
        let phi = theta * -(s.value() * geo.psi) + geo.psi;
        let (sn, c) = phi.sin_cos_from(value.sn, value.c);
        Self { sn, c }
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
pub(crate) fn rock_at<S: Scalar>(geo: &Geometry, pivot: Sign, tilt: Tilt<S>, theta_dot: S, fo: Forcing<S>) -> Accel<S> {
    let (theta_ddot, x_ddot, wdd, ww) = rock_motion(geo, pivot, tilt, theta_dot, fo);
    let s = pivot.value();
    let Tilt { sn, c } = tilt;
    Accel {
        theta_ddot,
        x_ddot,
        normal: fo.b() + (sn * s * wdd - c * ww) * GAMMA,
        friction: fo.a + x_ddot * GAMMA,
    }
}

/// The motion part of [`rock_at`]: `(Θ'', X'', ψΘ'', w²)`, without the
/// contact forces (the vector field needs no more; a jet computes only
/// what it is asked for).
#[inline]
fn rock_motion<S: Scalar>(geo: &Geometry, pivot: Sign, tilt: Tilt<S>, theta_dot: S, fo: Forcing<S>) -> (S, S, S, S) {
    let s = pivot.value();
    let Tilt { sn, c } = tilt;
    let b = fo.b();
    let w = theta_dot * geo.psi;
    let wdd = -(b * s * sn + fo.a * c);
    let ww = w * w;
    (wdd * geo.inv_psi, c * wdd + sn * s * ww, wdd, ww)
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
pub(crate) fn slide_rock_at<S: Scalar>(
    geo: &Geometry,
    pivot: Sign,
    slip: Sign,
    mu_k: f64,
    tilt: Tilt<S>,
    theta_dot: S,
    fo: Forcing<S>,
) -> Accel<S> {
    let s = pivot.value();
    let sigma = slip.value();
    let Tilt { sn, c } = tilt;
    let b = fo.b();
    let w = theta_dot * geo.psi;
    let ww = w * w;
    let k = sn * s - c * (sigma * mu_k);
    let den = (sn * sn - sn * (s * sigma * mu_k) * c) * GAMMA + (1.0 - GAMMA);
    let wdd = -k * (b - c * GAMMA * ww) / den;
    let normal = b + (sn * s * wdd - c * ww) * GAMMA;
    let friction = normal * (-sigma * mu_k);
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
pub fn slide<S: Scalar>(slip: Sign, mu_k: f64, fo: Forcing<S>) -> Accel<S> {
    let b = fo.b();
    let friction = b * (-slip.value() * mu_k);
    Accel {
        theta_ddot: b.constant(0.0),
        x_ddot: (friction - fo.a) / GAMMA,
        normal: b,
        friction,
    }
}

/// Flat block stuck to the base: the base supplies f = a, n = b.
#[inline]
pub fn rest<S: Scalar>(fo: Forcing<S>) -> Accel<S> {
    Accel {
        theta_ddot: fo.a.constant(0.0),
        x_ddot: fo.a.constant(0.0),
        normal: fo.b(),
        friction: fo.a,
    }
}

/// The vector field of `mode`: `y' = [Θ', Θ'', X', X'', W', D']` with the
/// work rate of the base's pseudo-forces W' = −a X' − a_v ẏ (ẏ = s sin φ w,
/// the centre of mass's vertical velocity) and the friction dissipation
/// rate D' = −f (X' − cos φ w) (docs/model.md §8). Rest and the terminal
/// modes stand still.
#[inline(always)]
pub(crate) fn field<S: Scalar>(geo: &Geometry, mu_k: f64, mode: Mode, fo: Forcing<S>, y: &[S; N]) -> [S; N] {
    let zero = y[THETA].constant(0.0);
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => [zero; N],
        Mode::Slide { slip } => {
            let acc = slide(slip, mu_k, fo);
            [
                zero,
                zero,
                y[X_DOT],
                acc.x_ddot,
                -fo.a * y[X_DOT],
                -acc.friction * y[X_DOT],
            ]
        }
        Mode::Rock { pivot } => {
            let tilt = Tilt::of(geo, pivot, y[THETA]);
            let (theta_ddot, x_ddot, _, _) = rock_motion(geo, pivot, tilt, y[THETA_DOT], fo);
            let w = y[THETA_DOT] * geo.psi;
            let y_dot = tilt.sn * pivot.value() * w;
            [
                y[THETA_DOT],
                theta_ddot,
                y[X_DOT],
                x_ddot,
                -fo.a * y[X_DOT] - fo.av * y_dot,
                zero,
            ]
        }
        Mode::SlideRock { pivot, slip } => {
            let tilt = Tilt::of(geo, pivot, y[THETA]);
            let acc = slide_rock_at(geo, pivot, slip, mu_k, tilt, y[THETA_DOT], fo);
            let w = y[THETA_DOT] * geo.psi;
            let y_dot = tilt.sn * pivot.value() * w;
            let vp = y[X_DOT] - tilt.c * w;
            [
                y[THETA_DOT],
                acc.theta_ddot,
                y[X_DOT],
                acc.x_ddot,
                -fo.a * y[X_DOT] - fo.av * y_dot,
                -acc.friction * vp,
            ]
        }
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
pub fn restoring<S: Scalar>(geo: &Geometry, pivot: Sign, fo: Forcing<S>) -> S {
    fo.b() * geo.sin_psi + fo.a * pivot.value() * geo.cos_psi
}

/// The scene the tests of the equations and their derived forms share.
#[cfg(test)]
pub(crate) mod test_scene;

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
