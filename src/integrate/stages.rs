//! Stage arithmetic shared by the Runge–Kutta methods: linear combinations
//! of stages, the cubic Hermite interpolant the driver screens guards with,
//! and the finiteness test.
//!
//! Every sum runs in a fixed order over stages and components, so the same
//! inputs give the same bits whichever method calls it, and negating the
//! state negates the result bit for bit (the mirror tests of the steppers).

/// `out = y + h * sum_j w[j] * k[j]`, skipping zero weights (most tableau
/// entries are zero). The sum runs in stage order, so it is the same
/// arithmetic for a state and its mirror image.
#[inline]
pub(super) fn combine<const N: usize>(y: &[f64; N], h: f64, w: &[f64], k: &[[f64; N]], out: &mut [f64; N]) {
    // Stages outer, components inner: contiguous and vectorisable. Each
    // component still sums its stages in the same order, so the result is
    // bit-identical to the component-by-component loop.
    let mut acc = [0.0; N];
    for (wj, kj) in w.iter().zip(k) {
        if *wj != 0.0 {
            for (a, kn) in acc.iter_mut().zip(kj) {
                *a += wj * kn;
            }
        }
    }
    for ((o, yn), a) in out.iter_mut().zip(y).zip(acc) {
        *o = yn + h * a;
    }
}

/// [`combine`] for the first `m` components only (`m <= N`); the others
/// keep whatever `out` held. For stage states, whose trailing quadratures
/// no right-hand side reads ([`Rhs::QUADRATURES`](super::Rhs::QUADRATURES)): `m` is a constant after
/// monomorphisation, so the loops are as tight as `combine`'s.
#[inline]
pub(super) fn combine_leading<const N: usize>(
    y: &[f64; N],
    h: f64,
    w: &[f64],
    k: &[[f64; N]],
    out: &mut [f64; N],
    m: usize,
) {
    let m = m.min(N);
    let mut acc = [0.0; N];
    for (wj, kj) in w.iter().zip(k) {
        if *wj != 0.0 {
            for (a, kn) in acc[..m].iter_mut().zip(&kj[..m]) {
                *a += wj * kn;
            }
        }
    }
    for ((o, yn), a) in out[..m].iter_mut().zip(&y[..m]).zip(&acc[..m]) {
        *o = yn + h * a;
    }
}

/// The cubic Hermite interpolant through `(t0, y0, f0)` and `(t0 + h, y1,
/// f1)` at `theta = (t - t0)/h`, in the Hermite basis:
/// `(1-θ)²(1+2θ) y0 + θ(1-θ)² h f0 + θ²(3-2θ) y1 + θ²(θ-1) h f1`,
/// for the leading `count` components (the rest of `out` is left as it
/// was; `N` for all). The four weights are computed once and the
/// components are a vectorisable linear combination in a fixed order, so
/// negating the state negates the result bit for bit.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(super) fn hermite_leading<const N: usize>(
    y0: &[f64; N],
    y1: &[f64; N],
    f0: &[f64; N],
    f1: &[f64; N],
    h: f64,
    theta: f64,
    out: &mut [f64; N],
    count: usize,
) {
    let u = 1.0 - theta;
    let t2 = theta * theta;
    let w_y0 = u * u * (1.0 + 2.0 * theta);
    let w_f0 = h * theta * u * u;
    let w_y1 = t2 * (3.0 - 2.0 * theta);
    let w_f1 = -h * t2 * u;
    for n in 0..count.min(N) {
        out[n] = w_y0 * y0[n] + w_f0 * f0[n] + w_y1 * y1[n] + w_f1 * f1[n];
    }
}

/// The third-order term of [`hermite`] at the midpoint,
/// `(2(y1 - y0) - h(f0 + f1))/8` (see
/// [`Stepper::hermite_spread`](super::Stepper::hermite_spread)).
#[inline]
pub(super) fn hermite_spread<const N: usize>(
    y0: &[f64; N],
    y1: &[f64; N],
    f0: &[f64; N],
    f1: &[f64; N],
    h: f64,
    out: &mut [f64; N],
) {
    for n in 0..N {
        out[n] = 0.125 * (2.0 * (y1[n] - y0[n]) - h * (f0[n] + f1[n]));
    }
}

/// `true` if every component is finite.
#[inline]
pub(super) fn all_finite<const N: usize>(v: &[f64; N]) -> bool {
    v.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hermite interpolant reproduces every cubic exactly (to
    /// round-off) from its end values and slopes, and is odd in the state.
    #[test]
    fn hermite_is_exact_for_cubics() {
        let p = |t: f64| 0.3 - 1.7 * t + 2.1 * t * t - 0.9 * t * t * t;
        let dp = |t: f64| -1.7 + 4.2 * t - 2.7 * t * t;
        let (t0, h) = (0.4, 0.7);
        let (y0, y1, f0, f1) = ([p(t0)], [p(t0 + h)], [dp(t0)], [dp(t0 + h)]);
        for k in 0..=20 {
            let theta = f64::from(k) / 20.0;
            let mut out = [0.0];
            hermite_leading(&y0, &y1, &f0, &f1, h, theta, &mut out, 1);
            assert!((out[0] - p(t0 + theta * h)).abs() < 1e-14, "θ = {theta}");
            let mut neg = [0.0];
            hermite_leading(&[-y0[0]], &[-y1[0]], &[-f0[0]], &[-f1[0]], h, theta, &mut neg, 1);
            assert_eq!(neg[0].to_bits(), (-out[0]).to_bits());
        }
    }
}
