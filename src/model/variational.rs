//! Variational (tangent) equations of the block: Jacobians of each mode's
//! vector field, gradients of the guards, and Jacobians of the reset maps.
//! EQUATIONS ONLY: no integrator. The saltation matrices built from these
//! live in `analysis::lyapunov`.
//!
//! # Tangent coordinates
//!
//! Exponents are measured in the reduced phase space `z = (Θ, Θ', X')`
//! ([`COORDS`] picks them out of the state `[Θ, Θ', X, X', W, D]`):
//! - `X` is left out because nothing depends on it (the vector fields,
//!   guards and resets are invariant under translation along the base).
//!   Its perturbation is carried along but never fed back, so its
//!   Lyapunov exponent is exactly 0; the cocycle is block-triangular and
//!   the other exponents are those of `z`.
//! - `W` and `D` are quadratures (energy audit), not state.
//!
//! Not every mode uses all of `z` ([`tangent_dim`]): rock keeps the pivot
//! stuck, so `X' = cos φ · ψΘ'` is slaved (2 free directions); slide has
//! `Θ = Θ' = 0` (1); rest has none (0); slide-rock is free (3). The reset
//! Jacobians project onto the tangent space of the mode entered, so a
//! direction that a mode does not have is annihilated in finite time
//! (exponent −∞), and the rock tangent flow keeps `δX' − ∂(c ψ Θ')·δz`
//! constant (because `X'' = d/dτ (c ψ Θ')` there), so a projected
//! perturbation stays on the constraint.
//!
//! # Accuracy
//!
//! The field's Jacobian and the guard gradients are hand-derived: faster
//! than the ones [`generated`] derives from `dynamics` and `system` by dual
//! numbers, and tested against them to round-off. Everything is analytic,
//! except the Jacobian of the impact laws other
//! than `ratio`: those laws are piecewise *linear* in the pre-impact
//! velocities `(w, X')`, so a central difference inside one branch is exact
//! up to round-off (relative error ~1e-10 with the step used here).
//!
//! Contract: matrices are row-major, `m[i][j] = ∂(out_i)/∂(z_j)`; inputs are
//! finite states of the given mode; outputs are finite for them.

use super::dynamics::{self, Forcing, Tilt};
use super::excitation::Excitation;
use super::geometry::{GAMMA, Geometry};
use super::impact::{self, ImpactLaw, PreImpact};
use super::mode::{Mode, Sign};
use super::params::Model;
use super::state::{N, THETA, THETA_DOT, X_DOT};

/// Dimension of the tangent coordinates `z = (Θ, Θ', X')`.
pub(crate) const DIM: usize = 3;

/// Indices of `z = (Θ, Θ', X')` in the state `[Θ, Θ', X, X', W, D]`.
pub(crate) const COORDS: [usize; DIM] = [THETA, THETA_DOT, X_DOT];

/// A `DIM × DIM` matrix, row-major.
pub(crate) type Matrix = [[f64; DIM]; DIM];

/// The identity matrix.
pub(crate) const IDENTITY: Matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// Gradient of one guard: `∂g/∂z` and the explicit time derivative `∂g/∂τ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GuardGradient {
    /// ∂g/∂(Θ, Θ', X').
    pub state: [f64; DIM],
    /// ∂g/∂τ at fixed state (through the base acceleration).
    pub time: f64,
}

/// Jacobian of a reset map restricted to `z`, composed with the
/// projections onto the tangent spaces of the modes left and entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResetJacobian {
    /// ∂z⁺/∂z⁻.
    pub matrix: Matrix,
    /// How many independent directions of `z` survive the event (its
    /// saltation matrix's rank): 3 for slip and stick switches, 2 through a
    /// sticking impact or into rock, 1 or 0 through a flat phase.
    pub dim: usize,
}

/// The reduced coordinates `z` of a full state (or of its rate).
#[inline]
pub fn coords(y: &[f64; N]) -> [f64; DIM] {
    [y[COORDS[0]], y[COORDS[1]], y[COORDS[2]]]
}

/// Number of free directions of `z` in `mode` (see the module docs).
pub fn tangent_dim(mode: Mode) -> usize {
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => 0,
        Mode::Slide { .. } => 1,
        Mode::Rock { .. } => 2,
        Mode::SlideRock { .. } => 3,
    }
}

/// Rate of change of the base acceleration, `(da/dτ, da_v/dτ)` per unit g,
/// for excitations whose derivative is known in closed form (harmonic, a
/// floor under harmonic ground motion, and none); `None` for pulses and
/// records.
pub(crate) fn forcing_rate(excitation: &Excitation, tau: f64) -> Option<Forcing> {
    match excitation {
        Excitation::None => Some(Forcing { a: 0.0, av: 0.0 }),
        Excitation::Harmonic(h) => Some(Forcing {
            a: h.a_h * h.psi * h.omega_h * (h.omega_h * tau + h.phase_h).cos(),
            av: h.a_v * h.psi * h.omega_v * (h.omega_v * tau + h.phase_v).cos(),
        }),
        Excitation::Floor(f) => f.accel_rate(tau).map(|(a, av)| Forcing { a, av }),
        Excitation::Pulse(_) | Excitation::Record(_) => None,
    }
}

/// Derivatives of a grounded tilted mode at one state, with respect to
/// `u = Θ` and `v = Θ'` (no mode depends on `X'`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Partials {
    /// w' = ψΘ'' and its partials.
    wdd: f64,
    wdd_u: f64,
    wdd_v: f64,
    /// ∂w'/∂τ per unit of db/dτ and of da/dτ: w'_τ = wdd_b·b' + wdd_a·a'.
    wdd_b: f64,
    wdd_a: f64,
    /// X'' and its partials.
    x_ddot_u: f64,
    x_ddot_v: f64,
    /// Normal force n and its partials.
    n_u: f64,
    n_v: f64,
    /// Horizontal contact force f and its partials.
    f_u: f64,
    f_v: f64,
}

/// Partials of rock about `pivot` (docs/model.md §3):
/// w' = −(s b sn + a c), X'' = c w' + s sn w², n = b + γ(s sn w' − c w²),
/// f = a + γ X''. With φ = ψ(1 − sΘ): ∂sn/∂Θ = −sψc, ∂c/∂Θ = sψ sn.
fn rock_partials(geo: &Geometry, pivot: Sign, theta: f64, theta_dot: f64, fo: Forcing) -> Partials {
    let s = pivot.value();
    let psi = geo.psi;
    let Tilt { sn, c } = Tilt::new(geo, pivot, theta);
    let b = fo.b();
    let w = psi * theta_dot;
    let ww = w * w;
    let wdd = -(s * b * sn + fo.a * c);
    let wdd_u = psi * (b * c - s * fo.a * sn);
    let x_ddot_u = s * psi * sn * wdd + c * wdd_u - psi * c * ww;
    let x_ddot_v = 2.0 * s * sn * w * psi;
    Partials {
        wdd,
        wdd_u,
        wdd_v: 0.0,
        wdd_b: -s * sn,
        wdd_a: -c,
        x_ddot_u,
        x_ddot_v,
        n_u: GAMMA * (-psi * c * wdd + s * sn * wdd_u - s * psi * sn * ww),
        n_v: -2.0 * GAMMA * c * w * psi,
        f_u: GAMMA * x_ddot_u,
        f_v: GAMMA * x_ddot_v,
    }
}

/// Partials of slide-rock about `pivot` slipping towards `slip`
/// (docs/model.md §4): w' = −k Q/D with k = s sn − σμ_k c,
/// Q = b − γ c w², D = (1−γ) + γ(sn² − sσμ_k sn c); n = b + γ(s sn w' − c w²);
/// f = −σμ_k n; X'' = (f − a)/γ.
fn slide_rock_partials(
    geo: &Geometry,
    pivot: Sign,
    slip: Sign,
    mu_k: f64,
    theta: f64,
    theta_dot: f64,
    fo: Forcing,
) -> Partials {
    let s = pivot.value();
    let sigma = slip.value();
    let psi = geo.psi;
    let Tilt { sn, c } = Tilt::new(geo, pivot, theta);
    let b = fo.b();
    let w = psi * theta_dot;
    let ww = w * w;
    let k = s * sn - sigma * mu_k * c;
    let k_u = -psi * (c + s * sigma * mu_k * sn);
    let den = (1.0 - GAMMA) + GAMMA * (sn * sn - s * sigma * mu_k * sn * c);
    let den_u = GAMMA * (-2.0 * s * psi * sn * c - sigma * mu_k * psi * (sn * sn - c * c));
    let q = b - GAMMA * c * ww;
    let q_u = -GAMMA * s * psi * sn * ww;
    let q_v = -2.0 * GAMMA * c * w * psi;
    let wdd = -k * q / den;
    let wdd_u = -(k_u * q + k * q_u) / den + k * q * den_u / (den * den);
    let wdd_v = -k * q_v / den;
    let n_u = GAMMA * (-psi * c * wdd + s * sn * wdd_u - s * psi * sn * ww);
    let n_v = GAMMA * (s * sn * wdd_v - 2.0 * c * w * psi);
    Partials {
        wdd,
        wdd_u,
        wdd_v,
        wdd_b: -k / den,
        wdd_a: 0.0,
        x_ddot_u: -sigma * mu_k * n_u / GAMMA,
        x_ddot_v: -sigma * mu_k * n_v / GAMMA,
        n_u,
        n_v,
        f_u: -sigma * mu_k * n_u,
        f_v: -sigma * mu_k * n_v,
    }
}

/// Partials of a tilted mode, `None` for the flat and terminal modes.
fn tilted_partials(model: &Model, mode: Mode, fo: Forcing, y: &[f64; N]) -> Option<(Sign, Partials)> {
    let geo = &model.geo;
    match mode {
        Mode::Rock { pivot } => Some((pivot, rock_partials(geo, pivot, y[THETA], y[THETA_DOT], fo))),
        Mode::SlideRock { pivot, slip } => Some((
            pivot,
            slide_rock_partials(geo, pivot, slip, model.mu_k, y[THETA], y[THETA_DOT], fo),
        )),
        Mode::Rest | Mode::Slide { .. } | Mode::Tumbled | Mode::Flight => None,
    }
}

/// Jacobian `∂(Θ', Θ'', X'')/∂(Θ, Θ', X')` of `mode`'s vector field at
/// forcing `fo` and state `y`. Flat and terminal modes have constant (or
/// zero) fields: their Jacobian is zero. No field depends on `X'`, so the
/// last column is always zero.
pub(crate) fn field_jacobian(model: &Model, mode: Mode, fo: Forcing, y: &[f64; N]) -> Matrix {
    match tilted_partials(model, mode, fo, y) {
        Some((_, p)) => {
            let psi = model.geo.psi;
            [
                [0.0, 1.0, 0.0],
                [p.wdd_u / psi, p.wdd_v / psi, 0.0],
                [p.x_ddot_u, p.x_ddot_v, 0.0],
            ]
        }
        None => [[0.0; DIM]; DIM],
    }
}

/// Gradient of guard `index` of `mode` (the table in `model::system`) at
/// forcing `fo`, forcing rate `rate` (from [`forcing_rate`]) and state `y`.
/// `None` for an index the mode does not have.
pub fn guard_gradient(
    model: &Model,
    mode: Mode,
    index: usize,
    fo: Forcing,
    rate: Forcing,
    y: &[f64; N],
) -> Option<GuardGradient> {
    let geo = &model.geo;
    let time_only = |time: f64| GuardGradient {
        state: [0.0; DIM],
        time,
    };
    match mode {
        Mode::Tumbled | Mode::Flight => None,
        // Every rest guard is a function of τ alone (b, κ±, μ_s b ± a).
        Mode::Rest => {
            let db = rate.av;
            let mu_s = model.mu_s;
            match index {
                0 => Some(time_only(db)),
                1 => Some(time_only(db * geo.sin_psi + rate.a * geo.cos_psi)),
                2 => Some(time_only(db * geo.sin_psi - rate.a * geo.cos_psi)),
                3 if mu_s.is_finite() => Some(time_only(mu_s * db + rate.a)),
                4 if mu_s.is_finite() => Some(time_only(mu_s * db - rate.a)),
                _ => None,
            }
        }
        Mode::Slide { slip } => match index {
            0 => Some(GuardGradient {
                state: [0.0, 0.0, slip.value()],
                time: 0.0,
            }),
            1 => Some(time_only(rate.av)),
            _ => None,
        },
        Mode::Rock { .. } | Mode::SlideRock { .. } => {
            let (pivot, p) = tilted_partials(model, mode, fo, y)?;
            let s = pivot.value();
            let Tilt { sn, c } = Tilt::new(geo, pivot, y[THETA]);
            let wdd_t = p.wdd_b * rate.av + p.wdd_a * rate.a;
            let n_t = rate.av + GAMMA * s * sn * wdd_t;
            let normal = GuardGradient {
                state: [p.n_u, p.n_v, 0.0],
                time: n_t,
            };
            match (mode, index) {
                (_, 0) => Some(GuardGradient {
                    state: [s, 0.0, 0.0],
                    time: 0.0,
                }),
                (_, 1) => Some(GuardGradient {
                    state: [-s, 0.0, 0.0],
                    time: 0.0,
                }),
                (_, 2) => Some(normal),
                (_, 3) => Some(GuardGradient {
                    state: [0.0, s, 0.0],
                    time: 0.0,
                }),
                (Mode::Rock { .. }, 4 | 5) if model.mu_s.is_finite() => {
                    // μ_s n ∓ s f, with f = a + γ X'' (rock).
                    let side = if index == 4 { -s } else { s };
                    let f_t = rate.a + GAMMA * c * wdd_t;
                    Some(GuardGradient {
                        state: [
                            model.mu_s * p.n_u + side * p.f_u,
                            model.mu_s * p.n_v + side * p.f_v,
                            0.0,
                        ],
                        time: model.mu_s * n_t + side * f_t,
                    })
                }
                (Mode::SlideRock { slip, .. }, 4) => {
                    // σ X_p' = σ(X' − c ψ Θ').
                    let sigma = slip.value();
                    let psi = geo.psi;
                    let w = psi * y[THETA_DOT];
                    Some(GuardGradient {
                        state: [-sigma * s * psi * sn * w, -sigma * c * psi, sigma],
                        time: 0.0,
                    })
                }
                _ => None,
            }
        }
    }
}

/// Projection of `z` onto the tangent space of `mode` at state `y`: what a
/// switch into `mode` does to a perturbation (rest pins everything, slide
/// pins Θ and Θ', rock slaves X' to c ψ Θ').
pub(crate) fn mode_projection(geo: &Geometry, mode: Mode, y: &[f64; N]) -> Matrix {
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => [[0.0; DIM]; DIM],
        Mode::Slide { .. } => [[0.0; DIM], [0.0; DIM], [0.0, 0.0, 1.0]],
        Mode::Rock { pivot } => {
            let Tilt { sn, c } = Tilt::new(geo, pivot, y[THETA]);
            let w = geo.psi * y[THETA_DOT];
            [
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [pivot.value() * geo.psi * sn * w, c * geo.psi, 0.0],
            ]
        }
        Mode::SlideRock { .. } => IDENTITY,
    }
}

/// Post-impact `(Θ', X')` and what kind of impact it was, exactly as
/// `BlockSystem`'s impact reset computes them (docs/model.md §7, §10).
#[derive(Clone, Copy, Debug, PartialEq)]
struct ImpactOutcome {
    theta_dot: f64,
    x_dot: f64,
    kind: ImpactKind,
}

/// The branch an impact law took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ImpactKind {
    /// The new pivot sticks.
    Stuck,
    /// The new pivot slips in this direction.
    Slipping(Sign),
    /// Both corners landed (flat landing).
    Flat,
    /// The post-impact rotation is below `zeno_eps`: the accumulation is
    /// summed and the block put flat.
    Accumulation,
}

fn impact_outcome(model: &Model, pivot: Sign, theta_dot: f64, x_dot: f64) -> ImpactOutcome {
    let geo = &model.geo;
    let w = geo.psi * theta_dot;
    let pre = PreImpact {
        striking: pivot.flip(),
        w,
        x_dot,
        y_dot: pivot.value() * geo.sin_psi * w,
    };
    let mut post = impact::apply_law(geo, &model.law, &pre);
    if impact::reverses(&pre, &post) {
        let (mu_s, mu_k) = match model.law {
            ImpactLaw::Impulse { mu_s, mu_k, .. } => (mu_s, mu_k),
            ImpactLaw::Housner | ImpactLaw::CornerMomentum | ImpactLaw::Ratio { .. } => (model.mu_s, model.mu_k),
        };
        post = impact::flat_landing(&pre, mu_s, mu_k);
    }
    let finite = model.mu_s.is_finite();
    let theta_dot_after = post.w / geo.psi;
    let (x_dot_after, kind) = if post.flat {
        match post.slip {
            Some(_) if finite => (post.x_dot, ImpactKind::Flat),
            _ => (0.0, ImpactKind::Flat),
        }
    } else {
        match post.slip {
            Some(slip) if finite => (post.x_dot, ImpactKind::Slipping(slip)),
            Some(_) | None => (geo.cos_psi * post.w, ImpactKind::Stuck),
        }
    };
    let kind = if kind != ImpactKind::Flat && theta_dot_after.abs() < model.zeno_eps {
        ImpactKind::Accumulation
    } else {
        kind
    };
    ImpactOutcome {
        theta_dot: theta_dot_after,
        x_dot: x_dot_after,
        kind,
    }
}

/// Jacobian of the impact reset `(Θ, Θ', X') ↦ (0, Θ'₊, X'₊)` of a block
/// rocking about `pivot`, and the branch taken. The `ratio` and `housner` laws are
/// differentiated analytically; the others by a central difference inside
/// the branch (they are piecewise linear in `(Θ', X')`, so it is exact up to
/// round-off).
fn impact_jacobian(model: &Model, pivot: Sign, theta_dot: f64, x_dot: f64) -> (Matrix, ImpactKind) {
    let geo = &model.geo;
    let centre = impact_outcome(model, pivot, theta_dot, x_dot);
    let mut m = [[0.0; DIM]; DIM];
    match centre.kind {
        ImpactKind::Accumulation => return (m, centre.kind),
        ImpactKind::Stuck | ImpactKind::Slipping(_) | ImpactKind::Flat => {}
    }
    // Housner's law is the ratio law with r = 1 − 1.5 sin²ψ; a negative r
    // (ψ > 54.7°) reverses the rotation into a flat landing, left to the
    // difference quotient below.
    let ratio = match model.law {
        ImpactLaw::Ratio { r } => Some(r),
        ImpactLaw::Housner if geo.housner_r() >= 0.0 => Some(geo.housner_r()),
        ImpactLaw::Housner | ImpactLaw::CornerMomentum | ImpactLaw::Impulse { .. } => None,
    };
    if let Some(r) = ratio {
        // Θ'₊ = r Θ'₋, X'₊ = cos ψ · ψ Θ'₊ (the new pivot sticks; no slip
        // branch and no reversal for r >= 0).
        m[1][1] = r;
        m[2][1] = geo.cos_psi * geo.psi * r;
        return (m, centre.kind);
    }
    let scale = theta_dot.abs().max(x_dot.abs()).max(f64::MIN_POSITIVE);
    let h = 1e-6 * scale;
    for (col, (dt, dx)) in [(1, (h, 0.0)), (2, (0.0, h))] {
        let plus = impact_outcome(model, pivot, theta_dot + dt, x_dot + dx);
        let minus = impact_outcome(model, pivot, theta_dot - dt, x_dot - dx);
        // One-sided where the branch changes within ±h (a measure-zero
        // boundary; the side of the centre point is the one taken).
        let (hi, lo, span) = match (plus.kind == centre.kind, minus.kind == centre.kind) {
            (true, true) | (false, false) => (plus, minus, 2.0 * h),
            (true, false) => (plus, centre, h),
            (false, true) => (centre, minus, h),
        };
        m[1][col] = (hi.theta_dot - lo.theta_dot) / span;
        m[2][col] = (hi.x_dot - lo.x_dot) / span;
    }
    (m, centre.kind)
}

fn mat_mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut out = [[0.0; DIM]; DIM];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..DIM).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

/// Jacobian of the reset of guard `index` of mode `before`, crossed at state
/// `y_before`, which left the block in mode `after` at state `y_after`
/// (after any immediate follow-up switch). It is the composition
/// `P_after · R · P_before` of the projections onto the modes' tangent
/// spaces ([`mode_projection`]) and the primary reset `R`: the impact law
/// for an impact, zero for a switch out of a flat mode (uplift and slip
/// from rest, stick of a flat slide: the switching time depends on τ alone
/// there), and the identity for slip and stick of a tilted block (the state
/// is continuous; stick's `X' = c ψ Θ'` is rock's projection).
///
/// An impact that starts an accumulation (post-impact |Θ'| below
/// `zeno_eps`) ends in a flat mode after a closed-form time skip: its
/// primary reset is taken as zero (Θ and Θ' are put to 0 exactly; the slip
/// velocity a slipping accumulation may leave is not differentiated). A
/// flat landing is differentiated like any impact (its Θ, Θ' rows are 0).
/// Both are reported with at most one surviving direction, and the
/// analysis then reports no finite exponent, so the accumulation's
/// approximation never reaches a reported number.
///
/// Only the action on the guard surface's tangent space matters to the
/// saltation matrix, so the natural extension off the surface used here is
/// as good as any.
pub fn reset_jacobian(
    model: &Model,
    before: Mode,
    index: usize,
    y_before: &[f64; N],
    after: Mode,
    y_after: &[f64; N],
) -> ResetJacobian {
    let geo = &model.geo;
    let (primary, primary_dim) = match (before, index) {
        (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 0) => {
            let (m, kind) = impact_jacobian(model, pivot, y_before[THETA_DOT], y_before[X_DOT]);
            let dim = match kind {
                ImpactKind::Slipping(_) => 3,
                ImpactKind::Stuck => 2,
                ImpactKind::Flat | ImpactKind::Accumulation => 1,
            };
            (m, dim)
        }
        (Mode::Rock { .. } | Mode::SlideRock { .. }, _) => (IDENTITY, DIM),
        (Mode::Rest | Mode::Slide { .. } | Mode::Tumbled | Mode::Flight, _) => ([[0.0; DIM]; DIM], 0),
    };
    let p_before = mode_projection(geo, before, y_before);
    let p_after = mode_projection(geo, after, y_after);
    let matrix = mat_mul(&p_after, &mat_mul(&primary, &p_before));
    let dim = tangent_dim(before).min(primary_dim).min(tangent_dim(after));
    ResetJacobian { matrix, dim }
}

/// Slip velocity of the pivot of a tilted mode (`None` for flat modes):
/// used to keep a displaced state in its slip direction.
pub(crate) fn slip_velocity(geo: &Geometry, mode: Mode, y: &[f64; N]) -> Option<f64> {
    match mode {
        Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => Some(dynamics::pivot_slip_velocity(
            geo,
            pivot,
            y[THETA],
            y[THETA_DOT],
            y[X_DOT],
        )),
        Mode::Rest | Mode::Slide { .. } | Mode::Tumbled | Mode::Flight => None,
    }
}

/// The same Jacobian and guard gradients generated by automatic
/// differentiation of the equations written once.
pub mod generated;

#[cfg(test)]
mod tests;
