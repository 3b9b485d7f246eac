//! The generic scalars against derivatives and series written out by hand.

use super::*;

/// A test function with every operation of the trait:
/// g(x, y) = sin x · y / (1 + x²) − 3y + cos x.
fn g<S: Scalar>(x: S, y: S) -> S {
    let (sn, cs) = x.sin_cos();
    sn * y / (x * x + 1.0) - y * 3.0 + cs
}

#[test]
fn dual_numbers_give_the_partial_derivatives_written_out_by_hand() {
    for (x, y) in [(0.3, -1.2), (-2.0, 0.7), (1.1, 4.0)] {
        let out = g(Dual::<2>::variable(x, 0), Dual::<2>::variable(y, 1));
        let (s, c, q) = (f64::sin(x), f64::cos(x), 1.0 + x * x);
        let gx = c * y / q - s * y * 2.0 * x / (q * q) - s;
        let gy = s / q - 3.0;
        assert_eq!(out.v, g(x, y), "the value is the f64 evaluation, bit for bit");
        // Round-off only: a few operations on numbers of order 1.
        assert!((out.d[0] - gx).abs() < 1e-14 * (1.0 + gx.abs()), "{} vs {gx}", out.d[0]);
        assert!((out.d[1] - gy).abs() < 1e-14 * (1.0 + gy.abs()), "{} vs {gy}", out.d[1]);
    }
}

/// Taylor coefficients of `y' = field(y)` to order `p` through `y0`.
fn expand<const L: usize>(y0: f64, p: usize, field: impl for<'t> Fn(Jet<'t, L>) -> Jet<'t, L>) -> Vec<f64> {
    let tape = Tape::<L>::new();
    let mut c = vec![y0];
    for k in 0..p {
        assert!(tape.begin(k));
        let y = tape.variable(c[k]);
        let f = field(y);
        c.push(f.coeff(k) / (k + 1) as f64);
    }
    c
}

#[test]
fn jets_expand_the_exponential_and_the_logistic_equation() {
    // y' = y, y(0) = 2: y_k = 2/k!.
    let c = expand::<30>(2.0, 25, |y| y);
    let mut fact = 1.0;
    for (k, ck) in c.iter().enumerate() {
        if k > 0 {
            fact *= k as f64;
        }
        assert!((ck - 2.0 / fact).abs() <= 1e-15 * (2.0 / fact), "order {k}: {ck}");
    }
    // y' = y(1 − y), y(0) = 1/2: y = 1/(1 + e^{−t}), whose series is
    // 1/2 + t/4 − t³/48 + t⁵/480 − 17t⁷/80640.
    let c = expand::<30>(0.5, 8, |y| y * (-y + 1.0));
    let want = [0.5, 0.25, 0.0, -1.0 / 48.0, 0.0, 1.0 / 480.0, 0.0, -17.0 / 80640.0];
    for (k, w) in want.iter().enumerate() {
        assert!((c[k] - w).abs() < 1e-15, "order {k}: {} vs {w}", c[k]);
    }
}

#[test]
fn a_quotient_of_jets_is_the_geometric_series_and_sine_the_closed_form() {
    let tape = Tape::<20>::new();
    let (a, w) = (0.4, 1.7);
    let mut line = [0.0; 20];
    line[0] = a;
    line[1] = w;
    let mut t = [0.0; 20];
    t[1] = 1.0;
    let (mut q, mut s, mut c) = (vec![], vec![], vec![]);
    for k in 0..20 {
        assert!(tape.begin(k));
        // 1/(1 − t) = Σ t^k, and sin, cos of a + w t.
        let tj = tape.known(&t);
        let one = tj.constant(1.0);
        q.push((one / (one - tj)).coeff(k));
        let (sn, cs) = tape.known(&line).sin_cos();
        s.push(sn.coeff(k));
        c.push(cs.coeff(k));
    }
    assert!(!tape.begin(20), "no pass beyond the tape's length");
    let mut scale = 1.0;
    for k in 0..20 {
        assert_eq!(q[k], 1.0, "order {k}");
        // w^k/k! · sin⁽ᵏ⁾(a): the derivatives cycle sin, cos, −sin, −cos.
        let ds = [a.sin(), a.cos(), -a.sin(), -a.cos()];
        let (ws, wc) = (scale * ds[k % 4], scale * ds[(k + 1) % 4]);
        assert!(
            (s[k] - ws).abs() < 1e-15 * (1.0 + ws.abs()),
            "sin order {k}: {} vs {ws}",
            s[k]
        );
        assert!(
            (c[k] - wc).abs() < 1e-15 * (1.0 + wc.abs()),
            "cos order {k}: {} vs {wc}",
            c[k]
        );
        scale *= w / (k + 1) as f64;
    }
}
