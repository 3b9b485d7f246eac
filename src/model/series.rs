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
//!
//! [`generated`] derives the same coefficients from `dynamics::field`
//! evaluated over jets; the hand-written expansions below are 5–8 times
//! faster (docs/model.md §17), so they are the ones used, and
//! `generated`'s tests check them against it.

use super::dynamics::Tilt;
use super::excitation::Excitation;
use super::geometry::{GAMMA, Geometry};
use super::mode::Mode;
use super::params::Model;
use super::state::{FRICTION_LOSS, N, THETA, THETA_DOT, WORK, X, X_DOT};

/// One more than the highest order with a series (rocking needs the tilt to
/// one order beyond the rest): 29, for the Taylor stepper's highest order
/// 28. Longer requests return `false`. The working series are arrays of
/// this length, zeroed on every expansion, so it is no longer than needed.
pub(crate) const MAX_ORDER: usize = crate::integrate::taylor::MAX_ORDER + 1;

/// Coefficients of one scalar series.
type Series = [f64; MAX_ORDER + 1];

/// `1/k` for k = 0..=MAX_ORDER + 1 (entry 0 unused): the recurrences divide
/// by the order at every step, and a division costs as much as a dozen
/// multiplications. The same bits as dividing at run time.
const INV: [f64; MAX_ORDER + 2] = {
    let mut t = [0.0; MAX_ORDER + 2];
    let mut k = 1;
    while k < MAX_ORDER + 2 {
        t[k] = 1.0 / k as f64;
        k += 1;
    }
    t
};

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

/// 1/γ.
const INV_GAMMA: f64 = 1.0 / GAMMA;

/// Index of coefficient 0 in a reversed series: `r[R - i] = y_i`.
///
/// Coefficient k of a product, `Σ_j x_j y_{k−j}`, walks `y` backwards; with
/// `y` also stored reversed it is the dot product of `x[lo..=k]` and
/// `r[R − k + lo..=R]`, two runs of ascending memory the compiler turns
/// into vector operations (the sums are most of an expansion's work).
const R: usize = MAX_ORDER;

/// `Σ_{j=lo..=k} x_j y_{k−j}` with `y` stored reversed in `yr` (see [`R`]).
#[inline(always)]
fn lagged(x: &Series, yr: &Series, k: usize, lo: usize) -> f64 {
    dot(&x[lo..=k], &yr[R - k + lo..=R])
}

/// `Σ_{j=0..=k} x_j y_{k−j}` (`y` reversed in `yr`), with the two terms that
/// read the newest coefficients, `x_0 y_k` and `x_k y_0`, added last.
///
/// An expansion is a chain from one order to the next; a sum that starts
/// from its newest terms waits for them before its first addition, while
/// one that ends with them can add up the older terms while the newest are
/// still being computed, and then waits only two operations.
#[inline(always)]
fn conv_newest_last(x: &Series, yr: &Series, k: usize) -> f64 {
    if k == 0 {
        return x[0] * yr[R];
    }
    dot(&x[1..k], &yr[R - k + 1..R]) + (x[0] * yr[R - k] + x[k] * yr[R])
}

/// `Σ_{j=1..=k} x_j y_{k−j}` (`y` reversed in `yr`), with the terms of the
/// newest `x_k` and `y_{k−1}` added last (see [`conv_newest_last`]).
#[inline(always)]
fn conv1_newest_last(x: &Series, yr: &Series, k: usize) -> f64 {
    if k == 1 {
        return x[1] * yr[R];
    }
    dot(&x[2..k], &yr[R - k + 2..R]) + (x[1] * yr[R - k + 1] + x[k] * yr[R])
}

/// The dot product of two slices of one length, with four partial sums side
/// by side (independent chains, paired into vector lanes).
#[inline(always)]
fn dot(x: &[f64], y: &[f64]) -> f64 {
    debug_assert_eq!(x.len(), y.len());
    let mut acc = [0.0; 4];
    let (xc, yc) = (x.chunks_exact(4), y.chunks_exact(4));
    let (xt, yt) = (xc.remainder(), yc.remainder());
    for (a, b) in xc.zip(yc) {
        for l in 0..4 {
            acc[l] += a[l] * b[l];
        }
    }
    for (l, (a, b)) in xt.iter().zip(yt).enumerate() {
        acc[l] += a * b;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// The series of `sin(Ω t + Φ)` about `t`, to `order`:
/// `Ω^k / k! · sin⁽ᵏ⁾(Ω t + Φ)`.
fn unit_sine_series(omega: f64, phase: f64, t: f64, order: usize, out: &mut Series) {
    let x = omega * t + phase;
    let (s0, c0) = (x.sin(), x.cos());
    let derivs = [s0, c0, -s0, -c0];
    let mut scale = 1.0;
    for (k, o) in out.iter_mut().enumerate().take(order + 1) {
        *o = scale * derivs[k % 4];
        scale *= omega * INV[k + 1];
    }
}

/// The forcing series `a = a_h/g` and `av = a_v/g` about `t`.
struct ForcingSeries {
    a: Series,
    av: Series,
    /// Both are multiples of one sine, `a = amp_h · unit` and `av = amp_v ·
    /// unit`: the paper's Ω_v = Ω_h and Φ_v = Φ_h, or no vertical forcing.
    /// A product with the forcing is then one sum, `unit · (amp_h y +
    /// amp_v z)`, instead of two.
    shared: bool,
    unit: Series,
    amp_h: f64,
    amp_v: f64,
}

impl ForcingSeries {
    /// No forcing.
    fn none() -> Self {
        let z = [0.0; MAX_ORDER + 1];
        Self {
            a: z,
            av: z,
            shared: true,
            unit: z,
            amp_h: 0.0,
            amp_v: 0.0,
        }
    }

    /// The series of `exc` about `t`, written in place (the struct is a few
    /// hundred bytes: no copies on the way out); `false` for an excitation
    /// without a closed form.
    fn fill(&mut self, exc: &Excitation, t: f64, order: usize) -> bool {
        let f = self;
        let z = [0.0; MAX_ORDER + 1];
        match exc {
            Excitation::None => {}
            Excitation::Harmonic(h) => {
                f.amp_h = h.a_h * h.psi;
                f.amp_v = h.a_v * h.psi;
                unit_sine_series(h.omega_h, h.phase_h, t, order, &mut f.unit);
                // Coefficient 0 of `a` is the bits of `Harmonic::accel`.
                for (a, u) in f.a.iter_mut().zip(&f.unit).take(order + 1) {
                    *a = f.amp_h * u;
                }
                if h.a_v == 0.0 {
                    f.amp_v = 0.0;
                } else if h.omega_v == h.omega_h && h.phase_v == h.phase_h {
                    for (av, u) in f.av.iter_mut().zip(&f.unit).take(order + 1) {
                        *av = f.amp_v * u;
                    }
                } else {
                    f.shared = false;
                    let mut unit_v = z;
                    unit_sine_series(h.omega_v, h.phase_v, t, order, &mut unit_v);
                    for (av, u) in f.av.iter_mut().zip(&unit_v).take(order + 1) {
                        *av = f.amp_v * u;
                    }
                }
            }
            Excitation::Pulse(_) | Excitation::Record(_) | Excitation::Floor(_) => return false,
        }
        true
    }

    /// Whether the base moves at all.
    fn forced(&self) -> bool {
        !self.shared || self.amp_h != 0.0 || self.amp_v != 0.0
    }
}

/// The sine and cosine of the tilt φ = ψ(1 − sΘ) as series, kept reversed
/// (see [`R`]) for the products that read them, and forward for the rest.
struct TiltSeries {
    /// `j φ_j`, forward.
    jph: Series,
    sn: Series,
    cs: Series,
    snr: Series,
    csr: Series,
}

impl TiltSeries {
    fn new(tilt: Tilt) -> Self {
        let z = [0.0; MAX_ORDER + 1];
        let mut t = Self {
            jph: z,
            sn: z,
            cs: z,
            snr: z,
            csr: z,
        };
        t.set(0, tilt.sn, tilt.c);
        t
    }

    #[inline(always)]
    fn set(&mut self, k: usize, sn: f64, cs: f64) {
        self.sn[k] = sn;
        self.cs[k] = cs;
        self.snr[R - k] = sn;
        self.csr[R - k] = cs;
    }

    /// Coefficient `k ≥ 1` from `k φ_k` and the lower ones, by `(sin φ)' =
    /// cos φ φ'` and `(cos φ)' = −sin φ φ'`. With φ = ψ(1 − sΘ) and
    /// `k Θ_k = Θ'_{k−1}`, `k φ_k = −ψ s Θ'_{k−1}`: the callers pass that,
    /// one multiplication after Θ' instead of four.
    #[inline(always)]
    fn step(&mut self, k: usize, jph_k: f64) {
        self.jph[k] = jph_k;
        let ds = conv1_newest_last(&self.jph, &self.csr, k);
        let dc = conv1_newest_last(&self.jph, &self.snr, k);
        let inv = INV[k];
        self.set(k, ds * inv, -dc * inv);
    }
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
    let mut f = ForcingSeries::none();
    if !f.fill(exc, t, order) {
        return false;
    }
    let c = &mut c[..=order];
    c[0] = *y;
    match mode {
        Mode::Rest | Mode::Tumbled | Mode::Flight => {
            for row in &mut c[1..] {
                *row = [0.0; N];
            }
        }
        Mode::Slide { slip } => slide(slip.value(), mu_k, &f.a, &f.av, c),
        Mode::Rock { pivot } => rock(geo, pivot.value(), Tilt::new(geo, pivot, y[THETA]), &f, c),
        Mode::SlideRock { pivot, slip } => slide_rock(
            geo,
            pivot.value(),
            slip.value(),
            mu_k,
            Tilt::new(geo, pivot, y[THETA]),
            &f,
            c,
        ),
    }
    true
}

/// Flat sliding: X'' = (f − a)/γ with f = −σ μ_k b; W' = −a X', D' = −f X'.
/// Θ and Θ' stay 0; the block's rarest mode, kept plain.
fn slide(sigma: f64, mu_k: f64, a: &Series, av: &Series, c: &mut [[f64; N]]) {
    let order = c.len() - 1;
    let mut fr = [0.0; MAX_ORDER + 1];
    let mut u = [0.0; MAX_ORDER + 1];
    u[0] = c[0][X_DOT];
    for k in 0..order {
        let b = if k == 0 { 1.0 + av[0] } else { av[k] };
        fr[k] = -sigma * mu_k * b;
        let xdd = (fr[k] - a[k]) * INV_GAMMA;
        let wdot = -conv(a, &u, k);
        let ddot = -conv(&fr, &u, k);
        let inv = INV[k + 1];
        u[k + 1] = xdd * inv;
        c[k + 1] = [0.0, 0.0, u[k] * inv, u[k + 1], wdot * inv, ddot * inv];
    }
}

/// Rocking about a stuck corner (`dynamics::rock_at`): ψΘ'' = −(s b sin φ +
/// a cos φ), W' = −a X' − a_v ẏ.
///
/// The centre of mass moves with the tilt alone: X = X_pivot − s sin φ and
/// Y = cos φ (per R), so X'' = cos φ ψΘ'' + s sin φ w² of `rock_at` is the
/// second derivative of −s sin φ, and ẏ = s sin φ w that of cos φ. Their
/// series are those of the tilt, with no products of their own.
///
/// With a shared forcing sine (`a = A e`, `a_v = B e`) the forcing terms of
/// ψΘ'' are one product, `e · m` with `m = A cos φ + s B sin φ`, and those
/// of W' one more, `e · (A X' + B ẏ)`.
fn rock(geo: &Geometry, sg: f64, tilt: Tilt, f: &ForcingSeries, c: &mut [[f64; N]]) {
    let order = c.len() - 1;
    let psi = geo.psi;
    let forced = f.forced();
    let mut tl = TiltSeries::new(tilt);
    // m = A cos φ + s B sin φ, reversed (shared forcing only).
    let mut mr = [0.0; MAX_ORDER + 1];
    let m_at = |tl: &TiltSeries, k: usize| f.amp_h * tl.cs[k] + sg * f.amp_v * tl.sn[k];
    mr[R] = m_at(&tl, 0);
    let mut th = [0.0; MAX_ORDER + 2];
    let mut v = [0.0; MAX_ORDER + 1];
    th[0] = c[0][THETA];
    v[0] = c[0][THETA_DOT];
    // Θ to order p + 1 (one beyond the rest: X' needs sin φ to p + 1).
    for k in 0..order {
        // ψΘ''_k = −(s sin φ_k + forcing_k).
        let forcing = if !forced {
            0.0
        } else if f.shared {
            // The newest m last (see `conv_newest_last`).
            (if k > 0 { lagged(&f.unit, &mr, k, 1) } else { 0.0 }) + f.unit[0] * mr[R - k]
        } else {
            lagged(&f.a, &tl.csr, k, 0) + sg * lagged(&f.av, &tl.snr, k, 0)
        };
        let wdd = -(sg * tl.sn[k] + forcing);
        let inv = INV[k + 1];
        th[k + 1] = v[k] * inv;
        v[k + 1] = wdd * geo.inv_psi * inv;
        tl.step(k + 1, -psi * sg * v[k]);
        mr[R - (k + 1)] = m_at(&tl, k + 1);
    }
    tl.step(order + 1, -psi * sg * v[order]);
    // X = X_pivot − s sin φ: X_k = −s sin φ_k (k ≥ 2), X'_k = (k+1) X_{k+1};
    // the state's own X and X' stay the constant terms. ẏ = (cos φ)':
    // ẏ_k = (k+1) cos φ_{k+1}. W' = −(a X' + a_v ẏ).
    let mut u = [0.0; MAX_ORDER + 1];
    let mut yd = [0.0; MAX_ORDER + 1];
    // Reversed: z = A X' + B ẏ (shared), or X' and ẏ apart.
    let (mut zr, mut ur, mut ydr) = ([0.0; MAX_ORDER + 1], [0.0; MAX_ORDER + 1], [0.0; MAX_ORDER + 1]);
    u[0] = c[0][X_DOT];
    for k in 0..order {
        if k > 0 {
            u[k] = -sg * (k + 1) as f64 * tl.sn[k + 1];
        }
        yd[k] = (k + 1) as f64 * tl.cs[k + 1];
        let wdot = if !forced {
            0.0
        } else if f.shared {
            zr[R - k] = f.amp_h * u[k] + f.amp_v * yd[k];
            -lagged(&f.unit, &zr, k, 0)
        } else {
            ur[R - k] = u[k];
            ydr[R - k] = yd[k];
            -(lagged(&f.a, &ur, k, 0) + lagged(&f.av, &ydr, k, 0))
        };
        let inv = INV[k + 1];
        let row = &mut c[k + 1];
        row[THETA] = th[k + 1];
        row[THETA_DOT] = v[k + 1];
        row[X] = if k == 0 { u[0] } else { -sg * tl.sn[k + 1] };
        row[X_DOT] = -sg * (k + 2) as f64 * tl.sn[k + 2];
        row[WORK] = wdot * inv;
        row[FRICTION_LOSS] = 0.0;
    }
}

/// Rocking about a slipping corner (`dynamics::slide_rock_at`):
/// ψΘ'' = −κ (b − γ cos φ w²)/D with κ = s sin φ − σ μ_k cos φ and
/// D = (1 − γ) + γ(sin²φ − sσμ_k sin φ cos φ); n = b + γ(s sin φ ψΘ'' −
/// cos φ w²), f = −σ μ_k n, X'' = (f − a)/γ, W' = −a X' − a_v ẏ,
/// D' = −f (X' − cos φ w).
///
/// With `t = sin φ − sσμ_k cos φ`: κ = s t and D = (1 − γ) + γ sin φ · t,
/// one product instead of two; with `P = cos φ Θ'`, cos φ w² = ψ² P Θ'
/// (and P gives the slip velocity's cos φ w too). Θ'' reads neither X'
/// nor the quadratures, so the first loop advances Θ alone and the second
/// the rest, whose sums do not wait on each other.
#[allow(clippy::too_many_arguments)]
fn slide_rock(geo: &Geometry, sg: f64, sigma: f64, mu_k: f64, tilt: Tilt, f: &ForcingSeries, c: &mut [[f64; N]]) {
    let order = c.len() - 1;
    let psi = geo.psi;
    let smu = sigma * mu_k;
    let z = [0.0; MAX_ORDER + 1];
    let mut tl = TiltSeries::new(tilt);
    // Forward and reversed as the products need them.
    let (mut tf, mut den, mut pf, mut cww, mut wdd) = (z, z, z, z, z);
    let (mut tr, mut numr, mut wddr, mut vr) = (z, z, z, z);
    let mut v = z;
    v[0] = c[0][THETA_DOT];
    vr[R] = v[0];
    let b = |k: usize| if k == 0 { 1.0 + f.av[0] } else { f.av[k] };
    // The quotient's one division, out of the loop.
    let mut inv_den0 = 0.0;
    for k in 0..order {
        tf[k] = tl.sn[k] - sg * smu * tl.cs[k];
        tr[R - k] = tf[k];
        den[k] = GAMMA * conv_newest_last(&tl.sn, &tr, k);
        if k == 0 {
            den[0] += 1.0 - GAMMA;
        }
        pf[k] = conv_newest_last(&tl.cs, &vr, k);
        cww[k] = psi * psi * conv_newest_last(&pf, &vr, k);
        numr[R - k] = b(k) - GAMMA * cww[k];
        // D · ψΘ'' = −κ · num, solved for the newest coefficient.
        let q = -sg * conv_newest_last(&tf, &numr, k) - if k > 0 { conv1_newest_last(&den, &wddr, k) } else { 0.0 };
        if k == 0 {
            inv_den0 = 1.0 / den[0];
        }
        wdd[k] = q * inv_den0;
        wddr[R - k] = wdd[k];
        let inv = INV[k + 1];
        let th_next = v[k] * inv;
        v[k + 1] = wdd[k] * geo.inv_psi * inv;
        vr[R - (k + 1)] = v[k + 1];
        c[k + 1][THETA] = th_next;
        c[k + 1][THETA_DOT] = v[k + 1];
        tl.step(k + 1, -psi * sg * v[k]);
    }
    // The rest, from Θ's series: n, f, X', ẏ = s ψ sin φ Θ', the slip
    // velocity X' − ψ P, and the two quadratures.
    let (mut fr, mut u) = (z, z);
    let (mut vpr, mut zr, mut ur, mut ydr) = (z, z, z, z);
    u[0] = c[0][X_DOT];
    for k in 0..order {
        let normal = b(k) + GAMMA * (sg * lagged(&tl.sn, &wddr, k, 0) - cww[k]);
        fr[k] = -smu * normal;
        let yd = sg * psi * lagged(&tl.sn, &vr, k, 0);
        vpr[R - k] = u[k] - psi * pf[k];
        let wdot = if f.shared {
            zr[R - k] = f.amp_h * u[k] + f.amp_v * yd;
            -lagged(&f.unit, &zr, k, 0)
        } else {
            ur[R - k] = u[k];
            ydr[R - k] = yd;
            -(lagged(&f.a, &ur, k, 0) + lagged(&f.av, &ydr, k, 0))
        };
        let ddot = -lagged(&fr, &vpr, k, 0);
        let inv = INV[k + 1];
        u[k + 1] = (fr[k] - f.a[k]) * (INV_GAMMA * inv);
        let row = &mut c[k + 1];
        row[X] = u[k] * inv;
        row[X_DOT] = u[k + 1];
        row[WORK] = wdot * inv;
        row[FRICTION_LOSS] = ddot * inv;
    }
}

/// The same coefficients generated from `dynamics::field` over jets.
pub mod generated;

/// The straightforward recurrences, one convolution per product and two
/// forcing series always apart: the oracle the fused expansions above are
/// tested against.
#[cfg(test)]
mod reference;

#[cfg(test)]
mod tests;
