//! Householder QR of a small fixed-size matrix, without allocation.
//!
//! Used to re-orthonormalise the tangent vectors (the columns of Φ) and to
//! read off their growth factors `R_ii` (Benettin et al. 1980; Householder
//! rather than Gram–Schmidt so that `Q` stays orthogonal even when a column
//! is annihilated by a rank-deficient reset).

/// A `D × D` matrix, row-major; the tangent vectors are its columns.
pub type Square<const D: usize> = [[f64; D]; D];

/// The identity.
pub fn identity<const D: usize>() -> Square<D> {
    let mut m = [[0.0; D]; D];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    m
}

/// `a · b`.
pub fn mul<const D: usize>(a: &Square<D>, b: &Square<D>) -> Square<D> {
    let mut out = [[0.0; D]; D];
    for i in 0..D {
        for k in 0..D {
            let aik = a[i][k];
            for j in 0..D {
                out[i][j] += aik * b[k][j];
            }
        }
    }
    out
}

// Explicit row and column indices read like the algorithm (Golub & Van
// Loan, alg. 5.2.1); iterator chains over columns would not.
#[allow(clippy::needless_range_loop)]
/// `a = Q R` with orthonormal columns in `Q` and `R_ii >= 0`. Returns `Q`
/// and the diagonal of `R`. A column already zero below the diagonal is
/// left alone (its `R_ii` is its diagonal entry, possibly 0).
pub fn qr<const D: usize>(a: &Square<D>) -> (Square<D>, [f64; D]) {
    let mut r = *a;
    let mut q = identity::<D>();
    for k in 0..D {
        let norm = (k..D).map(|i| r[i][k] * r[i][k]).sum::<f64>().sqrt();
        if norm == 0.0 {
            continue;
        }
        // Reflect x = r[k.., k] onto −sign(x_k)‖x‖ e_k (no cancellation).
        let alpha = if r[k][k] > 0.0 { -norm } else { norm };
        let mut v = [0.0; D];
        for i in k..D {
            v[i] = r[i][k];
        }
        v[k] -= alpha;
        let v2 = (k..D).map(|i| v[i] * v[i]).sum::<f64>();
        if v2 == 0.0 {
            continue;
        }
        for j in k..D {
            let f = 2.0 * (k..D).map(|i| v[i] * r[i][j]).sum::<f64>() / v2;
            for i in k..D {
                r[i][j] -= f * v[i];
            }
        }
        for row in q.iter_mut() {
            let f = 2.0 * (k..D).map(|i| row[i] * v[i]).sum::<f64>() / v2;
            for i in k..D {
                row[i] -= f * v[i];
            }
        }
    }
    let mut diag = [0.0; D];
    for k in 0..D {
        if r[k][k] < 0.0 {
            for row in q.iter_mut() {
                row[k] = -row[k];
            }
        }
        diag[k] = r[k][k].abs();
    }
    (q, diag)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn qr_reconstructs_and_is_orthonormal() {
        let a = [[2.0, -1.0, 0.5], [0.3, 4.0, -2.0], [-1.0, 0.2, 1.5]];
        let (q, d) = qr(&a);
        let qtq = mul(&transpose(&q), &q);
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((qtq[i][j] - e).abs() < 1e-14);
            }
        }
        // R = Qᵀ A is upper triangular with the returned positive diagonal.
        let r = mul(&transpose(&q), &a);
        for i in 0..3 {
            assert!((r[i][i] - d[i]).abs() < 1e-13 && d[i] > 0.0);
            for j in 0..i {
                assert!(r[i][j].abs() < 1e-13);
            }
        }
        // |det A| = Π R_ii.
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        assert!((det.abs() - d.iter().product::<f64>()).abs() < 1e-12);
    }

    #[test]
    fn rank_deficient_input_keeps_q_orthonormal() {
        let a = [[1.0, 2.0, 0.0], [0.0, 0.0, 0.0], [3.0, 6.0, 0.0]];
        let (q, d) = qr(&a);
        assert!(d[1] < 1e-15 && d[2] < 1e-15);
        let qtq = mul(&transpose(&q), &q);
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((qtq[i][j] - e).abs() < 1e-14, "{qtq:?}");
            }
        }
        let (q0, d0) = qr(&[[0.0; 2]; 2]);
        assert_eq!(d0, [0.0, 0.0]);
        assert_eq!(q0, identity());
    }

    fn transpose<const D: usize>(a: &Square<D>) -> Square<D> {
        let mut t = [[0.0; D]; D];
        for i in 0..D {
            for j in 0..D {
                t[j][i] = a[i][j];
            }
        }
        t
    }
}
