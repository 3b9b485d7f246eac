//! Taylor coefficients of the block's motion in each mode, for the Taylor
//! method (`integrate::taylor`).
//!
//! The coefficients come from the equations of `dynamics` by the recurrences
//! of automatic differentiation (Moore; Jorba and Zou 2005): every product
//! of two series is a convolution, the tilt's sine and cosine follow from
//! `(sin φ)' = cos φ φ'` and `(cos φ)' = −sin φ φ'`, the slide-rock quotient
//! from `den · q = num`, and the harmonic forcing's series is known in
//! closed form. With `y_k` the coefficients of `y(t + s) = Σ y_k s^k`, a
//! first-order equation `y' = g` gives `y_{k+1} = g_k / (k + 1)`.
//!
//! Only the harmonic excitation (and none) has a closed-form series; pulses
//! and records return `false`, and the method takes DOP853 steps there.
//! `tests/taylor.rs` checks every mode against DOP853.

use super::dynamics::Tilt;
use super::excitation::Excitation;
use super::geometry::{GAMMA, Geometry};
use super::mode::Mode;
use super::system::{FRICTION_LOSS, Model, N, THETA, THETA_DOT, WORK, X, X_DOT};

/// Highest order with a series (longer requests return `false`).
pub const MAX_ORDER: usize = 32;

/// Coefficients of one scalar series.
type Series = [f64; MAX_ORDER + 1];

/// `Σ_{j=0..=k} a_j b_{k−j}`: coefficient k of the product of two series.
///
/// Four partial sums side by side: a single running sum is a chain of
/// dependent additions, and the expansion is made of these sums.
#[inline]
fn conv(a: &Series, b: &Series, k: usize) -> f64 {
    let mut acc = [0.0; 4];
    let mut j = 0;
    while j + 4 <= k + 1 {
        for l in 0..4 {
            acc[l] += a[j + l] * b[k - j - l];
        }
        j += 4;
    }
    while j <= k {
        acc[0] += a[j] * b[k - j];
        j += 1;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// The series of `amp · sin(Ω t + Φ)` about `t`, to `order`:
/// `amp Ω^k / k! · sin⁽ᵏ⁾(Ω t + Φ)`. Coefficient 0 is the bits of
/// `Harmonic::accel`.
fn sine_series(amp: f64, omega: f64, phase: f64, t: f64, order: usize, out: &mut Series) {
    let x = omega * t + phase;
    let (s0, c0) = (x.sin(), x.cos());
    let derivs = [s0, c0, -s0, -c0];
    let mut scale = amp;
    for (k, o) in out.iter_mut().enumerate().take(order + 1) {
        *o = scale * derivs[k % 4];
        scale *= omega / (k + 1) as f64;
    }
}

/// The forcing series `a = a_h/g` and `av = a_v/g` about `t`; `false` for
/// an excitation without a closed form.
fn forcing_series(exc: &Excitation, t: f64, order: usize, a: &mut Series, av: &mut Series) -> bool {
    match exc {
        Excitation::None => true,
        Excitation::Harmonic(h) => {
            sine_series(h.a_h * h.psi, h.omega_h, h.phase_h, t, order, a);
            if h.a_v != 0.0 {
                sine_series(h.a_v * h.psi, h.omega_v, h.phase_v, t, order, av);
            }
            true
        }
        Excitation::Pulse(_) | Excitation::Record(_) => false,
    }
}

/// Working series of one expansion.
struct Work {
    th: Series,
    v: Series,
    x: Series,
    u: Series,
    w: Series,
    d: Series,
}

impl Work {
    fn new(y: &[f64; N]) -> Self {
        let mut s = Self {
            th: [0.0; MAX_ORDER + 1],
            v: [0.0; MAX_ORDER + 1],
            x: [0.0; MAX_ORDER + 1],
            u: [0.0; MAX_ORDER + 1],
            w: [0.0; MAX_ORDER + 1],
            d: [0.0; MAX_ORDER + 1],
        };
        s.th[0] = y[THETA];
        s.v[0] = y[THETA_DOT];
        s.x[0] = y[X];
        s.u[0] = y[X_DOT];
        s.w[0] = y[WORK];
        s.d[0] = y[FRICTION_LOSS];
        s
    }

    fn write(&self, order: usize, c: &mut [[f64; N]]) {
        for (k, row) in c.iter_mut().enumerate().take(order + 1) {
            row[THETA] = self.th[k];
            row[THETA_DOT] = self.v[k];
            row[X] = self.x[k];
            row[X_DOT] = self.u[k];
            row[WORK] = self.w[k];
            row[FRICTION_LOSS] = self.d[k];
        }
    }
}

/// The sine and cosine of the tilt φ = ψ(1 − sΘ), coefficient `k ≥ 1`,
/// from `jph[j] = j φ_j` and the lower coefficients.
#[inline]
fn tilt_step(jph: &Series, sn: &mut Series, cs: &mut Series, k: usize) {
    let (mut ds, mut dc) = ([0.0; 2], [0.0; 2]);
    let mut j = 1;
    while j + 2 <= k + 1 {
        for l in 0..2 {
            ds[l] += jph[j + l] * cs[k - j - l];
            dc[l] += jph[j + l] * sn[k - j - l];
        }
        j += 2;
    }
    if j <= k {
        ds[0] += jph[j] * cs[k - j];
        dc[0] += jph[j] * sn[k - j];
    }
    let (ds, dc) = (ds[0] + ds[1], dc[0] + dc[1]);
    let inv = 1.0 / k as f64;
    sn[k] = ds * inv;
    cs[k] = -dc * inv;
}

/// Writes the Taylor coefficients of the block in `mode` through `(t, y)`
/// into `c[0..=order]`. `false` if the excitation has no series or the
/// order is above [`MAX_ORDER`].
pub fn taylor(model: &Model, mode: Mode, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
    let (geo, mu_k, exc) = (&model.geo, model.mu_k, &model.excitation);
    // One order is kept in reserve: rocking needs the tilt to order + 1.
    if order >= MAX_ORDER || c.len() < order + 1 {
        return false;
    }
    let mut a = [0.0; MAX_ORDER + 1];
    let mut av = [0.0; MAX_ORDER + 1];
    if !forcing_series(exc, t, order, &mut a, &mut av) {
        return false;
    }
    let mut s = Work::new(y);
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => {}
        Mode::Slide { slip } => slide(slip.value(), mu_k, &a, &av, order, &mut s),
        Mode::Rock { pivot } => rock(
            geo,
            pivot.value(),
            Tilt::new(geo, pivot, y[THETA]),
            &a,
            &av,
            order,
            &mut s,
        ),
        Mode::SlideRock { pivot, slip } => slide_rock(
            geo,
            pivot.value(),
            slip.value(),
            mu_k,
            Tilt::new(geo, pivot, y[THETA]),
            &a,
            &av,
            order,
            &mut s,
        ),
    }
    s.write(order, c);
    true
}

/// Flat sliding: X'' = (f − a)/γ with f = −σ μ_k b; W' = −a X', D' = −f X'.
fn slide(sigma: f64, mu_k: f64, a: &Series, av: &Series, order: usize, s: &mut Work) {
    let mut fr = [0.0; MAX_ORDER + 1];
    for k in 0..order {
        let b = if k == 0 { 1.0 + av[0] } else { av[k] };
        fr[k] = -sigma * mu_k * b;
        let xdd = (fr[k] - a[k]) / GAMMA;
        let wdot = -conv(a, &s.u, k);
        let ddot = -conv(&fr, &s.u, k);
        let inv = 1.0 / (k + 1) as f64;
        s.x[k + 1] = s.u[k] * inv;
        s.u[k + 1] = xdd * inv;
        s.w[k + 1] = wdot * inv;
        s.d[k + 1] = ddot * inv;
    }
}

/// Rocking about a stuck corner (`dynamics::rock_at`): ψΘ'' = −(s b sin φ +
/// a cos φ), W' = −a X' − a_v ẏ.
///
/// The centre of mass moves with the tilt alone: X = X_pivot − s sin φ and
/// Y = cos φ (per R), so X'' = cos φ ψΘ'' + s sin φ w² of `rock_at` is the
/// second derivative of −s sin φ, and ẏ = s sin φ w that of cos φ. Their
/// series are those of the tilt, with no products of their own.
fn rock(geo: &Geometry, sg: f64, tilt: Tilt, a: &Series, av: &Series, order: usize, s: &mut Work) {
    let psi = geo.psi;
    let vertical = av[..=order].iter().any(|&v| v != 0.0);
    let mut sn = [0.0; MAX_ORDER + 1];
    let mut cs = [0.0; MAX_ORDER + 1];
    let mut jph = [0.0; MAX_ORDER + 1];
    sn[0] = tilt.sn;
    cs[0] = tilt.c;
    // Θ to order p + 1 (one beyond the rest: X' needs sin φ to p + 1).
    for k in 0..=order {
        if k > 0 {
            jph[k] = -(k as f64) * psi * sg * s.th[k];
            tilt_step(&jph, &mut sn, &mut cs, k);
        }
        if k == order {
            break;
        }
        let bsn = if vertical { conv(av, &sn, k) + sn[k] } else { sn[k] };
        let wdd = -(sg * bsn + conv(a, &cs, k));
        let inv = 1.0 / (k + 1) as f64;
        s.th[k + 1] = s.v[k] * inv;
        s.v[k + 1] = wdd * geo.inv_psi * inv;
    }
    let p1 = order + 1;
    let th_next = s.v[order] / p1 as f64;
    jph[p1] = -(p1 as f64) * psi * sg * th_next;
    tilt_step(&jph, &mut sn, &mut cs, p1);
    // X = X_pivot − s sin φ: X_k = −s sin φ_k (k ≥ 2), X'_k = (k+1) X_{k+1};
    // the state's own X and X' stay the constant terms.
    s.x[1] = s.u[0];
    for (x, sn_k) in s.x[2..=order].iter_mut().zip(&sn[2..=order]) {
        *x = -sg * sn_k;
    }
    for k in 1..=order {
        s.u[k] = -sg * (k + 1) as f64 * sn[k + 1];
    }
    // ẏ = (cos φ)': ẏ_k = (k+1) cos φ_{k+1}.
    let mut yd = [0.0; MAX_ORDER + 1];
    if vertical {
        for k in 0..order {
            yd[k] = (k + 1) as f64 * cs[k + 1];
        }
    }
    for k in 0..order {
        let mut wdot = -conv(a, &s.u, k);
        if vertical {
            wdot -= conv(av, &yd, k);
        }
        s.w[k + 1] = wdot / (k + 1) as f64;
    }
}

/// Rocking about a slipping corner (`dynamics::slide_rock_at`):
/// ψΘ'' = −κ (b − γ cos φ w²)/D with κ = s sin φ − σ μ_k cos φ and
/// D = (1 − γ) + γ(sin²φ − sσμ_k sin φ cos φ); n = b + γ(s sin φ ψΘ'' −
/// cos φ w²), f = −σ μ_k n, X'' = (f − a)/γ, W' = −a X' − a_v ẏ,
/// D' = −f (X' − cos φ w).
#[allow(clippy::too_many_arguments)]
fn slide_rock(
    geo: &Geometry,
    sg: f64,
    sigma: f64,
    mu_k: f64,
    tilt: Tilt,
    a: &Series,
    av: &Series,
    order: usize,
    s: &mut Work,
) {
    let psi = geo.psi;
    let mut b = *av;
    b[0] += 1.0;
    let z = [0.0; MAX_ORDER + 1];
    let (mut sn, mut cs, mut jph) = (z, z, z);
    let (mut kap, mut den, mut num, mut wdd) = (z, z, z, z);
    let (mut ww, mut cww, mut fr, mut yd, mut vp) = (z, z, z, z, z);
    sn[0] = tilt.sn;
    cs[0] = tilt.c;
    for k in 0..order {
        if k > 0 {
            jph[k] = -(k as f64) * psi * sg * s.th[k];
            tilt_step(&jph, &mut sn, &mut cs, k);
        }
        kap[k] = sg * sn[k] - sigma * mu_k * cs[k];
        den[k] = GAMMA * (conv(&sn, &sn, k) - sg * sigma * mu_k * conv(&sn, &cs, k));
        if k == 0 {
            den[0] += 1.0 - GAMMA;
        }
        ww[k] = psi * psi * conv(&s.v, &s.v, k);
        cww[k] = conv(&cs, &ww, k);
        num[k] = b[k] - GAMMA * cww[k];
        // den · wdd = −κ · num, solved for the newest coefficient.
        let mut q = -conv(&kap, &num, k);
        for j in 1..=k {
            q -= den[j] * wdd[k - j];
        }
        wdd[k] = q / den[0];
        let normal = b[k] + GAMMA * (sg * conv(&sn, &wdd, k) - cww[k]);
        fr[k] = -sigma * mu_k * normal;
        let xdd = (fr[k] - a[k]) / GAMMA;
        yd[k] = sg * psi * conv(&sn, &s.v, k);
        vp[k] = s.u[k] - psi * conv(&cs, &s.v, k);
        let wdot = -conv(a, &s.u, k) - conv(av, &yd, k);
        let ddot = -conv(&fr, &vp, k);
        let inv = 1.0 / (k + 1) as f64;
        s.th[k + 1] = s.v[k] * inv;
        s.v[k + 1] = wdd[k] / psi * inv;
        s.x[k + 1] = s.u[k] * inv;
        s.u[k + 1] = xdd * inv;
        s.w[k + 1] = wdot * inv;
        s.d[k + 1] = ddot * inv;
    }
}
