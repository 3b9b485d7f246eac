//! Bracketed root finding and minimisation on one variable, for locating
//! events on dense output.
//!
//! References:
//! - R. P. Brent, *Algorithms for Minimization without Derivatives*,
//!   Prentice-Hall 1973: ch. 4 (`zero`: bisection safeguarding secant and
//!   inverse quadratic interpolation) and ch. 5 (`localmin`: golden section
//!   with parabolic interpolation).
//! - scipy `optimize.brentq` (C `brentq.c`) and `optimize.fminbound`, the
//!   same algorithms, used as a cross-check.
//!
//! Both functions are deterministic and look at `g` only through the values
//! it returns: two problems whose `g` return bit-identical values (such as a
//! motion and its mirror image, with mirrored guards) give bit-identical
//! answers.

/// Why a root could not be found.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub(crate) enum RootError {
    /// The end values do not satisfy `g(a) > 0 >= g(b)` (a NaN fails too).
    #[error("root not bracketed: g({a}) = {ga:e}, g({b}) = {gb:e}")]
    NotBracketed {
        /// Left end of the interval.
        a: f64,
        /// Right end of the interval.
        b: f64,
        /// `g(a)`, which should be > 0.
        ga: f64,
        /// `g(b)`, which should be <= 0.
        gb: f64,
    },
    /// The iteration limit ran out, or `g` returned NaN inside the bracket.
    #[error("root finding did not converge in [{a}, {b}]")]
    NoConvergence {
        /// The end of the last bracket where `g > 0`.
        a: f64,
        /// The end of the last bracket where `g <= 0`.
        b: f64,
    },
}

/// Finds where `g` crosses from `> 0` to `<= 0` between `a` and `b`.
///
/// `ga = g(a)` and `gb = g(b)` are passed in because the caller has them
/// already; they must satisfy `ga > 0 && gb <= 0` (a guard is positive inside
/// its mode's domain, and an event is the first time it is not). Brent's
/// method keeps a bracket `[lo, hi]` with `g(lo) > 0 >= g(hi)` and stops when
/// `|hi - lo| <= xtol`, or when `lo` and `hi` are adjacent floats (so an
/// ulp-level `xtol` terminates too), or when `g` is exactly zero at an
/// iterate. It returns `(hi, g(hi))`: the event state is on the far side of
/// the surface, so the next mode starts outside the old domain and the same
/// guard cannot fire again at once.
///
/// `xtol` is absolute, in the units of the argument (time); the hybrid driver
/// passes `max(4 ε max(|a|, |b|), 1e-15)`. `max_iter` bounds the number of
/// evaluations of `g` (about 50 is plenty: the bisection safeguard
/// at least halves the bracket every few steps).
///
/// # Errors
/// [`RootError::NotBracketed`] if the end values do not bracket a crossing,
/// [`RootError::NoConvergence`] if `max_iter` evaluations did not suffice or
/// `g` returned NaN.
pub(crate) fn brent_root<G: FnMut(f64) -> f64>(
    mut g: G,
    a: f64,
    b: f64,
    ga: f64,
    gb: f64,
    xtol: f64,
    max_iter: u32,
) -> Result<(f64, f64), RootError> {
    if !(ga > 0.0 && gb <= 0.0) {
        return Err(RootError::NotBracketed { a, b, ga, gb });
    }
    if gb == 0.0 {
        return Ok((b, gb));
    }
    // Brent's names: `xb` is the best iterate, `xc` the contrapoint on the
    // other side of the crossing, `xa` the previous iterate; `d` is the last
    // step and `e` the one before, for the "is interpolation converging fast
    // enough" test.
    let (mut xa, mut fa) = (a, ga);
    let (mut xb, mut fb) = (b, gb);
    let (mut xc, mut fc) = (a, ga);
    let mut d = xb - xa;
    let mut e = d;
    let tol = 0.5 * xtol;
    let bracket = |xb: f64, fb: f64, xc: f64, fc: f64| {
        if fb > 0.0 { (xb, xc, fc) } else { (xc, xb, fb) }
    };
    for _ in 0..max_iter {
        if (fb > 0.0) == (fc > 0.0) {
            // The new iterate replaced the contrapoint's side: the previous
            // iterate is now the contrapoint.
            xc = xa;
            fc = fa;
            d = xb - xa;
            e = d;
        }
        if fc.abs() < fb.abs() {
            // Keep the smaller |g| as the best iterate.
            xa = xb;
            xb = xc;
            xc = xa;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let (lo, hi, ghi) = bracket(xb, fb, xc, fc);
        let m = 0.5 * (xc - xb);
        let mid = xb + m;
        if (hi - lo).abs() <= xtol || mid == xb || mid == xc {
            return Ok((hi, ghi));
        }

        if e.abs() < tol || fa.abs() <= fb.abs() {
            // Interpolation is not making progress: bisect.
            d = m;
            e = m;
        } else {
            let s = fb / fa;
            let (mut p, mut q);
            if xa == xc {
                // Secant (two distinct points).
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                // Inverse quadratic interpolation.
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (xb - xa) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            let e_old = e;
            e = d;
            if 2.0 * p < 3.0 * m * q - (tol * q).abs() && p < (0.5 * e_old * q).abs() {
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        }
        xa = xb;
        fa = fb;
        let mut x = if d.abs() > tol {
            xb + d
        } else if m > 0.0 {
            xb + tol
        } else {
            xb - tol
        };
        // At ulp-level tolerances `xb ± tol` may round back onto `xb` (or
        // past `xc`): fall back to the midpoint, which is strictly inside.
        let inside = if xb < xc { xb < x && x < xc } else { xc < x && x < xb };
        if !inside {
            x = mid;
        }
        let gx = g(x);
        if gx.is_nan() {
            let (lo, hi, _) = bracket(xb, fb, xc, fc);
            return Err(RootError::NoConvergence { a: lo, b: hi });
        }
        if gx == 0.0 {
            return Ok((x, gx));
        }
        xb = x;
        fb = gx;
    }
    // Classify the last iterate before reporting the bracket.
    if (fb > 0.0) == (fc > 0.0) {
        xc = xa;
        fc = fa;
    }
    let (lo, hi, _) = bracket(xb, fb, xc, fc);
    Err(RootError::NoConvergence { a: lo, b: hi })
}

/// Minimises `g` on `[a, b]` (either order) and returns `(argmin, min)`.
///
/// Brent's `localmin` (golden section safeguarding parabolic interpolation,
/// as in scipy's `fminbound`) finds an interior local minimum; the end points
/// are then compared as candidates too, since a guard's smallest value over a
/// step is often at an end. Ties go to the interior point, then to `a`.
///
/// `xtol` is the absolute tolerance on the argument (the search stops when
/// the bracket around the minimum is about `2 xtol` wide); unlike scipy it is
/// not widened by `sqrt(ε)|x|`, because `x` is a time whose origin is
/// arbitrary: only a few ulps of `|x|` are added, so that every trial point
/// differs from the last. `max_iter` bounds the evaluations in the interior
/// search (at least one); two more are spent on the end points.
pub(crate) fn brent_min<G: FnMut(f64) -> f64>(mut g: G, a: f64, b: f64, xtol: f64, max_iter: u32) -> (f64, f64) {
    let (a0, b0) = if a <= b { (a, b) } else { (b, a) };
    let (ga, gb) = (g(a0), g(b0));
    if a0 == b0 {
        return (a0, ga);
    }
    let (xm, fm) = localmin(&mut g, a0, b0, xtol, max_iter);
    let mut best = (xm, fm);
    if ga < best.1 {
        best = (a0, ga);
    }
    if gb < best.1 {
        best = (b0, gb);
    }
    best
}

/// Brent's `localmin` on `[a, b]`, `a < b` (scipy `_minimize_scalar_bounded`).
fn localmin<G: FnMut(f64) -> f64>(g: &mut G, mut a: f64, mut b: f64, xtol: f64, max_iter: u32) -> (f64, f64) {
    // (3 - sqrt 5) / 2, the golden-section fraction.
    let golden = 0.5 * (3.0 - 5.0_f64.sqrt());
    let tol_of = |x: f64| xtol / 3.0 + 2.0 * f64::EPSILON * x.abs();
    // x: best point; w: second best; v: previous w.
    let mut x = a + golden * (b - a);
    let mut fx = g(x);
    let (mut w, mut fw) = (x, fx);
    let (mut v, mut fv) = (x, fx);
    let mut d: f64 = 0.0;
    let mut e: f64 = 0.0;
    for _ in 1..max_iter {
        let xm = 0.5 * (a + b);
        let tol1 = tol_of(x);
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // Parabola through (x, fx), (w, fw), (v, fv).
            let mut r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            r = e;
            e = d;
            if p.abs() < (0.5 * q * r).abs() && p > q * (a - x) && p < q * (b - x) {
                golden_step = false;
                d = p / q;
                let u = x + d;
                // Do not evaluate too close to the ends.
                if u - a < tol2 || b - u < tol2 {
                    d = if xm >= x { tol1 } else { -tol1 };
                }
            }
        }
        if golden_step {
            e = if x >= xm { a - x } else { b - x };
            d = golden * e;
        }
        // Never step by less than tol1, so that u differs from x.
        let step = if d.abs() >= tol1 {
            d
        } else if d >= 0.0 {
            tol1
        } else {
            -tol1
        };
        let u = x + step;
        let fu = g(u);
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv) = (w, fw);
            (w, fw) = (x, fx);
            (x, fx) = (u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv) = (w, fw);
                (w, fw) = (u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The driver's tolerance for a bracket `[a, b]`.
    fn xtol_for(a: f64, b: f64) -> f64 {
        (4.0 * f64::EPSILON * a.abs().max(b.abs())).max(1e-15)
    }

    /// Runs `brent_root` recording every evaluation, and checks the
    /// contract: `g(hi) <= 0`, and, unless `g(hi)` is exactly zero, some
    /// evaluated point (or `a`) with `g > 0` lies within `xtol` (or one ulp,
    /// whichever is larger) to the left of `hi`.
    fn check_root(g: impl Fn(f64) -> f64, a: f64, b: f64, xtol: f64, max_iter: u32) -> (f64, usize) {
        let mut seen = vec![(a, g(a)), (b, g(b))];
        let (hi, ghi) = brent_root(
            |x| {
                let v = g(x);
                seen.push((x, v));
                v
            },
            a,
            b,
            g(a),
            g(b),
            xtol,
            max_iter,
        )
        .unwrap();
        assert!(ghi <= 0.0, "g(hi) = {ghi}");
        assert_eq!(ghi, g(hi));
        if ghi == 0.0 {
            // Exact zero: returned at once, whatever the bracket.
            return (hi, seen.len() - 2);
        }
        let lo = seen
            .iter()
            .filter(|(x, v)| *v > 0.0 && *x < hi)
            .map(|(x, _)| *x)
            .fold(f64::NEG_INFINITY, f64::max);
        let ulp = hi.abs() * f64::EPSILON;
        assert!(hi - lo <= xtol.max(ulp), "hi - lo = {:e} > xtol = {xtol:e}", hi - lo);
        (hi, seen.len() - 2)
    }

    #[test]
    fn cube_root_of_two() {
        // Positive inside (x below the root), crossing to <= 0.
        let g = |x: f64| 2.0 - x * x * x;
        let (hi, n) = check_root(g, 0.0, 2.0, 1e-14, 100);
        assert!((hi - 2.0f64.cbrt()).abs() < 1e-14, "{hi}");
        assert!(n < 20, "{n} evaluations");
    }

    #[test]
    fn near_double_root() {
        // Roots at 0.5 ± 1e-6: the bracket [0, 0.5] holds only the left one,
        // where the slope is tiny.
        let g = |x: f64| (x - 0.5) * (x - 0.5) - 1e-12;
        let (hi, _) = check_root(g, 0.0, 0.5, xtol_for(0.0, 0.5), 100);
        assert!((hi - (0.5 - 1e-6)).abs() < 1e-12, "{hi}");
        // A triple root: g = -(x - 1)^3. Interpolation is slow on multiple
        // roots, so Brent's safeguard bisects only every fourth evaluation or
        // so, and the bracket shrinks by about 2.5 per four: ~130 evaluations.
        let g = |x: f64| -(x - 1.0).powi(3);
        let (hi, n) = check_root(g, 0.0, 3.0, 1e-12, 300);
        assert!(n < 200, "{n}");
        assert!((hi - 1.0).abs() < 1e-4, "{hi}");
    }

    #[test]
    fn ulp_level_tolerance_terminates() {
        // g > 0 below the float r and g(r) = -1e-300: never exactly zero, so
        // the bracket test (not the exact-zero exit) must stop the search,
        // and the crossing lies between r's lower neighbour and r.
        let r = 100.3;
        let g = move |x: f64| (r - x) * (1.0 + x * x) - 1e-300;
        let (a, b) = (100.0, 101.0);
        let (hi, n) = check_root(g, a, b, xtol_for(a, b), 100);
        assert!(g(hi) < 0.0);
        assert!(hi >= r && hi - r <= xtol_for(a, b), "{hi} vs {r}");
        assert!(n < 60, "{n}");
        // xtol = 0: stops when lo and hi are adjacent floats, at r exactly.
        let (hi, n) = check_root(g, a, b, 0.0, 100);
        assert_eq!(hi, r);
        assert!(n < 60, "{n}");
    }

    #[test]
    fn exact_zero_returns_at_once() {
        let g = |x: f64| 1.0 - x;
        // The first iterate (secant) hits 1 exactly.
        let r = brent_root(g, 0.0, 2.0, 1.0, -1.0, 1e-15, 50).unwrap();
        assert_eq!(r, (1.0, 0.0));
        let r = brent_root(g, 0.0, 1.0, 1.0, 0.0, 1e-15, 50).unwrap();
        assert_eq!(r, (1.0, 0.0));
    }

    #[test]
    fn rejects_unbracketed_and_nan() {
        let g = |x: f64| x;
        for (ga, gb) in [(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0), (f64::NAN, -1.0)] {
            assert!(matches!(
                brent_root(g, 0.0, 1.0, ga, gb, 1e-12, 50),
                Err(RootError::NotBracketed { .. })
            ));
        }
        let nan = |_x: f64| f64::NAN;
        assert!(matches!(
            brent_root(nan, 0.0, 1.0, 1.0, -1.0, 1e-12, 50),
            Err(RootError::NoConvergence { .. })
        ));
        let slow = |x: f64| 0.5 - x;
        assert_eq!(
            brent_root(slow, 0.0, 1.0, 0.5, -0.5, 1e-12, 0),
            Err(RootError::NoConvergence { a: 0.0, b: 1.0 })
        );
    }

    #[test]
    fn identical_values_give_identical_answers() {
        // A guard and its mirror image (`x` ↦ `-x` in the state): the guard
        // values are the same function of time, computed from negated data.
        let g1 = |t: f64| 0.1 - (t.sin() * 0.7).abs();
        let g2 = |t: f64| 0.1 - (-(t.sin()) * 0.7).abs();
        let r1 = brent_root(g1, 0.0, 1.0, g1(0.0), g1(1.0), 1e-15, 100).unwrap();
        let r2 = brent_root(g2, 0.0, 1.0, g2(0.0), g2(1.0), 1e-15, 100).unwrap();
        assert_eq!(r1.0.to_bits(), r2.0.to_bits());
        let m1 = brent_min(g1, 0.0, 3.0, 1e-12, 100);
        let m2 = brent_min(g2, 0.0, 3.0, 1e-12, 100);
        assert_eq!(m1.0.to_bits(), m2.0.to_bits());
    }

    #[test]
    fn minimum_of_parabola() {
        let (x, v) = brent_min(|x| (x - 0.3) * (x - 0.3) + 1.0, 0.0, 1.0, 1e-10, 100);
        assert!((x - 0.3).abs() < 1e-8, "{x}");
        assert!((v - 1.0).abs() < 1e-15);
        // At a large time offset the tolerance stays absolute.
        let (x, _) = brent_min(|x| (x - 800.3) * (x - 800.3), 800.0, 801.0, 1e-10, 100);
        assert!((x - 800.3).abs() < 1e-7, "{x}");
    }

    #[test]
    fn minimum_at_an_end_point() {
        assert_eq!(brent_min(|x| x, 0.0, 1.0, 1e-10, 100), (0.0, 0.0));
        assert_eq!(brent_min(|x| -x, 0.0, 1.0, 1e-10, 100), (1.0, -1.0));
        // Reversed interval, minimum at an end.
        assert_eq!(brent_min(|x| (x - 2.0).powi(2), 1.0, 0.0, 1e-10, 100).0, 1.0);
        // An interior local minimum that is not the global one.
        let g = |x: f64| (3.0 * x).cos() + x;
        let (x, v) = brent_min(g, 0.0, 3.0, 1e-10, 100);
        let (ga, gb) = (g(0.0), g(3.0));
        assert!(v <= ga.min(gb), "{x} {v}");
    }
}
