//! Impact laws at Θ = 0: the lifted corner strikes the base.
//!
//! Derivation: `docs/model.md` §7. Velocities are normalised by R p
//! (X', Y') and angular velocity by p (w = ψΘ'). The striking corner is on
//! side `s'` (the old pivot's opposite); flat, it sits at R(s' sin ψ, −cos ψ)
//! from the centre of mass. An impulse π = P/(mRp) there changes
//! ΔX' = π_x, ΔY' = π_y, Δw = −3(s' sin ψ π_y + cos ψ π_x) (mR²/I_G = 3),
//! and the corner's velocity V_c = (X' − C w, Y' − s' S w) by
//! `M π` with M = [[1+3C², 3s'SC], [3s'SC, 1+3S²]], det M = 4.
//!
//! Every law returns the post-impact velocities and whether the new pivot
//! slips or leaves the base. Written as sign × symmetric terms, so mirrored
//! impacts give exactly mirrored results.

use super::geometry::Geometry;
use super::mode::Sign;

/// Which impact law (MODEL-DECISIONS "Impact at Θ = 0").
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImpactLaw {
    /// Housner's law as the literature states it (Housner 1963): Θ'₊ = r Θ'₋
    /// with r = 1 − 1.5 sin²ψ from the block's geometry, and the new pivot
    /// sticks, so any slip before the impact is stopped (docs/model.md §7.3).
    /// Identical to [`ImpactLaw::CornerMomentum`] when the block rocked
    /// without slip before the impact.
    Housner,
    /// Angular momentum about the striking corner is conserved, including
    /// the momentum of a pre-impact slip, and the new pivot sticks (the
    /// `impulse` law with e = 0 and no slip):
    /// w₊ = (1 − 1.5 sin²ψ) w₋ + ¾ cos ψ V_cx₋ (docs/model.md §7.3).
    CornerMomentum,
    /// Θ'₊ = r Θ'₋ with a given ratio, new pivot stuck. The paper's
    /// e = 0.925 (sec. 4.1) is this `r`.
    Ratio {
        /// Angular velocity ratio, in [0, 1].
        r: f64,
    },
    /// Impulse–momentum law (paper eqs. 17–27, Shenton–Jones type):
    /// vertical restitution `e` of the striking corner and Coulomb friction
    /// during the impact, which can make the corner slip.
    Impulse {
        /// Vertical restitution of the striking corner, in [0, 1].
        e: f64,
        /// Static friction coefficient at impact μ̄_s (`inf`: no slip).
        mu_s: f64,
        /// Kinetic friction coefficient at impact μ̄_k (<= μ̄_s).
        mu_k: f64,
    },
}

impl ImpactLaw {
    /// Config name: `housner`, `corner-momentum`, `ratio`, `impulse`.
    pub fn name(&self) -> &'static str {
        match self {
            ImpactLaw::Housner => "housner",
            ImpactLaw::CornerMomentum => "corner-momentum",
            ImpactLaw::Ratio { .. } => "ratio",
            ImpactLaw::Impulse { .. } => "impulse",
        }
    }
}

/// Velocities just before an impact (at Θ = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreImpact {
    /// Side of the striking corner, s' (the new pivot).
    pub striking: Sign,
    /// w = ψΘ' before.
    pub w: f64,
    /// X' before.
    pub x_dot: f64,
    /// Y' before (vertical velocity of G / R p).
    pub y_dot: f64,
}

/// Velocities just after an impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PostImpact {
    /// w = ψΘ' after.
    pub w: f64,
    /// X' after.
    pub x_dot: f64,
    /// Y' after.
    pub y_dot: f64,
    /// Slip direction of the new pivot after the impact (`None`: it sticks).
    pub slip: Option<Sign>,
    /// The striking corner leaves the base (vertical restitution e > 0).
    pub lifts_off: bool,
    /// Normalised impulse (π_x, π_y) at the striking corner.
    pub impulse: (f64, f64),
    /// Both bottom corners struck at once and the block landed flat
    /// (w = 0, Y' = 0); see [`flat_landing`].
    pub flat: bool,
}

/// Whether a tangential impulse `t` is inside the friction cone of normal
/// impulse `n >= 0` with coefficient `mu` (infinite `mu`: always, even for
/// `n = 0`, where `mu * n` would be NaN).
#[inline]
fn within_cone(t: f64, mu: f64, n: f64) -> bool {
    mu.is_infinite() || t.abs() <= mu * n
}

/// Velocity of the striking corner, (V_cx, V_cy).
#[inline]
pub fn corner_velocity(geo: &Geometry, pre: &PreImpact) -> (f64, f64) {
    let sp = pre.striking.value();
    (pre.x_dot - geo.cos_psi * pre.w, pre.y_dot - sp * geo.sin_psi * pre.w)
}

/// Applies impulse `(px, py)` at the striking corner.
#[inline]
fn apply(geo: &Geometry, pre: &PreImpact, px: f64, py: f64) -> (f64, f64, f64) {
    let sp = pre.striking.value();
    let (s, c) = (geo.sin_psi, geo.cos_psi);
    let w = pre.w - 3.0 * (sp * s * py + c * px);
    (w, pre.x_dot + px, pre.y_dot + py)
}

/// Impulse that changes the corner velocity by `(dvx, dvy)`: π = M⁻¹ ΔV.
#[inline]
fn stick_impulse(geo: &Geometry, sp: f64, dvx: f64, dvy: f64) -> (f64, f64) {
    let (s, c) = (geo.sin_psi, geo.cos_psi);
    let m_off = 3.0 * sp * s * c;
    let px = ((1.0 + 3.0 * s * s) * dvx - m_off * dvy) / 4.0;
    let py = ((1.0 + 3.0 * c * c) * dvy - m_off * dvx) / 4.0;
    (px, py)
}

/// The impulse law: vertical restitution `e`, friction `mu_s`/`mu_k` at the
/// striking corner. Sticks if the stick impulse lies in the static friction
/// cone; otherwise slips in the direction consistent with kinetic friction.
pub fn impulse_law(geo: &Geometry, pre: &PreImpact, e: f64, mu_s: f64, mu_k: f64) -> PostImpact {
    let sp = pre.striking.value();
    let (s, c) = (geo.sin_psi, geo.cos_psi);
    let (vcx, vcy) = corner_velocity(geo, pre);
    let dvy = -(1.0 + e) * vcy;
    let (px, py) = stick_impulse(geo, sp, -vcx, dvy);
    let lifts_off = e > 0.0;
    // The block after impulse (π_x, π_y), the new pivot slipping by `slip`.
    let post = |px: f64, py: f64, slip: Option<Sign>| {
        let (w, x_dot, y_dot) = apply(geo, pre, px, py);
        PostImpact {
            w,
            x_dot,
            y_dot,
            slip,
            lifts_off,
            impulse: (px, py),
            flat: false,
        }
    };
    if within_cone(px, mu_s, py) {
        return post(px, py, None);
    }
    // Slip: π_x = −σ μ_k π_y, with σ the sign of the corner's slip after
    // the impact. Friction opposes the slip the stick impulse prevented, so
    // try σ = −sign(π_x,stick) first, then the other direction.
    let first = Sign::of(-px);
    for sigma in [first, first.flip()] {
        let sg = sigma.value();
        // ΔV_cy = (1+3S²)π_y + 3s'SC π_x with π_x = −σ μ_k π_y.
        let den = (1.0 + 3.0 * s * s) - 3.0 * sp * s * c * sg * mu_k;
        // μ_k is finite here (μ_k <= μ_s and the stick impulse left the
        // finite cone), so `den` is a number; <= 0 would need μ_k > 4/3.
        if den <= 0.0 {
            continue;
        }
        let py = dvy / den;
        let px = -sg * mu_k * py;
        let vcx_after = vcx + (1.0 + 3.0 * c * c) * px + 3.0 * sp * s * c * py;
        if sg * vcx_after >= 0.0 {
            return post(px, py, if vcx_after == 0.0 { None } else { Some(sigma) });
        }
    }
    // No consistent slip direction (impossible for μ_k <= μ_s and a
    // physical geometry, kept as a safe fallback): the corner sticks.
    post(px, py, None)
}

/// The corner-momentum law: a perfectly plastic, sticking impact at the
/// striking corner (the impulse law with e = 0 and infinite friction), so
/// angular momentum about that corner is conserved, pre-impact slip
/// included. Without pre-impact slip it is Housner's law.
pub fn corner_momentum(geo: &Geometry, pre: &PreImpact) -> PostImpact {
    impulse_law(geo, pre, 0.0, f64::INFINITY, f64::INFINITY)
}

/// Housner's law as the literature uses it: w₊ = r w₋ with
/// r = 1 − 1.5 sin²ψ ([`Geometry::housner_r`]) and the new pivot stuck,
/// i.e. the ratio law with Housner's r. A pre-impact slip is stopped by
/// whatever horizontal impulse that takes (the law idealises the base as
/// rough enough). For ψ > 54.7° r < 0 and the law reverses the rotation,
/// which the caller resolves as a flat landing ([`reverses`]).
pub fn housner(geo: &Geometry, pre: &PreImpact) -> PostImpact {
    ratio(geo, pre, geo.housner_r())
}

/// The ratio law: w₊ = r w₋, new pivot stuck (X'₊ = cos ψ w₊,
/// Y'₊ = s' sin ψ w₊).
pub fn ratio(geo: &Geometry, pre: &PreImpact, r: f64) -> PostImpact {
    let sp = pre.striking.value();
    let w = r * pre.w;
    let x_dot = geo.cos_psi * w;
    let y_dot = sp * geo.sin_psi * w;
    PostImpact {
        w,
        x_dot,
        y_dot,
        slip: None,
        lifts_off: false,
        impulse: (x_dot - pre.x_dot, y_dot - pre.y_dot),
        flat: false,
    }
}

/// Whether a single-corner impact result would drive the old pivot into
/// the base: with the striking corner stuck, the old pivot's vertical
/// velocity after is 2 s' sin ψ w₊ (docs/model.md §7.5), so it penetrates
/// when s' w₊ < 0. This happens when a large slip velocity before the
/// impact reverses the rotation (the corner-momentum law with slip:
/// w₊ = (1 − 1.5 sin²ψ) w₋ + ¾ cos ψ V_cx₋), or when Housner's r < 0
/// (ψ > 54.7°).
pub(crate) fn reverses(pre: &PreImpact, post: &PostImpact) -> bool {
    !post.lifts_off && pre.striking.value() * post.w < 0.0
}

/// Both bottom corners strike at once, perfectly plastically: rotation and
/// vertical velocity stop (total vertical impulse π_y = −Y'₋), and the
/// horizontal velocity is stopped by friction if |X'₋| <= μ_s π_y, or
/// reduced by μ_k π_y otherwise (the block then slides flat).
pub(crate) fn flat_landing(pre: &PreImpact, mu_s: f64, mu_k: f64) -> PostImpact {
    let py = (-pre.y_dot).max(0.0);
    let (px, slip) = if within_cone(pre.x_dot, mu_s, py) {
        (-pre.x_dot, None)
    } else {
        let px = -pre.x_dot.signum() * mu_k * py;
        let after = pre.x_dot + px;
        (px, if after == 0.0 { None } else { Some(Sign::of(after)) })
    };
    PostImpact {
        w: 0.0,
        x_dot: pre.x_dot + px,
        y_dot: 0.0,
        slip,
        lifts_off: false,
        impulse: (px, py),
        flat: true,
    }
}

/// Applies `law`.
pub(crate) fn apply_law(geo: &Geometry, law: &ImpactLaw, pre: &PreImpact) -> PostImpact {
    match *law {
        ImpactLaw::Housner => housner(geo, pre),
        ImpactLaw::CornerMomentum => corner_momentum(geo, pre),
        ImpactLaw::Ratio { r } => ratio(geo, pre, r),
        ImpactLaw::Impulse { e, mu_s, mu_k } => impulse_law(geo, pre, e, mu_s, mu_k),
    }
}

/// When an impact accumulation that starts at τ with post-impact rate `v`
/// (|ψΘ'|) and ratio `r` ends, summed in closed form (docs/model.md §10):
/// Δτ = 2v(1/k₊ + r/k₋)/(1 − r²), with k the deceleration ψ|Θ''| on the
/// side it rocks to next (k₊) and the other (k₋); a later τ than `t` in
/// every case (the next float when Δτ vanishes in round-off).
pub(crate) fn accumulation_end(t: f64, v: f64, r: f64, k_next: f64, k_after: f64) -> f64 {
    let dt = if r < 1.0 {
        2.0 * v * (1.0 / k_next + r / k_after) / (1.0 - r * r)
    } else {
        2.0 * v / k_next
    };
    let t_acc = t + dt;
    if t_acc <= t { t.next_up() } else { t_acc }
}
