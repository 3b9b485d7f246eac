//! The straightforward recurrences, one convolution per product and two
//! forcing series always apart: the oracle the fused expansions of
//! `series` are tested against.

use super::*;

pub struct Work {
    pub th: Series,
    pub v: Series,
    pub x: Series,
    pub u: Series,
    pub w: Series,
    pub d: Series,
}

impl Work {
    pub fn new(y: &[f64; N]) -> Self {
        // Each series starts at the state's component; the rest is computed.
        let series = |c: f64| {
            let mut s = [0.0; MAX_ORDER + 1];
            s[0] = c;
            s
        };
        Self {
            th: series(y[THETA]),
            v: series(y[THETA_DOT]),
            x: series(y[X]),
            u: series(y[X_DOT]),
            w: series(y[WORK]),
            d: series(y[FRICTION_LOSS]),
        }
    }

    pub fn row(&self, k: usize) -> [f64; N] {
        [self.th[k], self.v[k], self.x[k], self.u[k], self.w[k], self.d[k]]
    }
}

fn tilt_step(jph: &Series, sn: &mut Series, cs: &mut Series, k: usize) {
    let (mut ds, mut dc) = (0.0, 0.0);
    for j in 1..=k {
        ds += jph[j] * cs[k - j];
        dc += jph[j] * sn[k - j];
    }
    sn[k] = ds / k as f64;
    cs[k] = -dc / k as f64;
}

/// Rocking about a stuck corner (`dynamics::rock_at`): ψΘ'' = −(s b sin φ +
/// a cos φ), W' = −a X' − a_v ẏ.
///
/// The centre of mass moves with the tilt alone: X = X_pivot − s sin φ and
/// Y = cos φ (per R), so X'' = cos φ ψΘ'' + s sin φ w² of `rock_at` is the
/// second derivative of −s sin φ, and ẏ = s sin φ w that of cos φ. Their
/// series are those of the tilt, with no products of their own.
pub fn rock(geo: &Geometry, sg: f64, tilt: Tilt, a: &Series, av: &Series, order: usize, s: &mut Work) {
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
pub fn slide_rock(
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
