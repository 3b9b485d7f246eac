//! QR re-orthonormalisation of the tangent vectors on nalgebra's
//! fixed-size matrices, and the conversions between those and the arrays
//! of the [`TangentSystem`](super::TangentSystem) interface.
//!
//! The QR re-orthonormalises the tangent vectors (the columns of Φ) and
//! reads off their growth factors `R_ii` (Benettin et al. 1980). It is
//! Householder, not Gram–Schmidt, so that `Q` stays orthogonal even when a
//! column is annihilated by a rank-deficient reset: nalgebra skips the
//! reflection of a column that is zero from the diagonal down, which
//! leaves that column of `Q` a unit vector orthogonal to the others.

use nalgebra::{Const, DimMin, SMatrix, SVector};

/// A `D × D` matrix, row-major (`m[row][column]`); the tangent vectors are
/// its columns. The array form of the [`TangentSystem`](super::TangentSystem)
/// interface (and of `model::variational`, which builds the block's
/// matrices); the machinery converts it to a `Matrix` at the boundary.
pub type Square<const D: usize> = [[f64; D]; D];

/// A `D × D` matrix as the machinery computes with it.
pub(crate) type Matrix<const D: usize> = SMatrix<f64, D, D>;

/// A vector of `D` tangent coordinates.
pub(crate) type Vector<const D: usize> = SVector<f64, D>;

/// The [`Matrix`] of a row-major [`Square`].
pub fn matrix<const D: usize>(a: &Square<D>) -> Matrix<D> {
    Matrix::from_fn(|i, j| a[i][j])
}

/// The row-major [`Square`] of a [`Matrix`].
pub(crate) fn square<const D: usize>(m: &Matrix<D>) -> Square<D> {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// `a = Q R` with orthonormal columns in `Q` and `R_ii >= 0`. Returns `Q`
/// and the diagonal of `R`. A column that is zero from the diagonal down
/// gets no reflection and `R_ii = 0`.
///
/// The bound holds for every `D` up to 127 (nalgebra's `DimMin` goes
/// through typenum); a caller generic in `D` must repeat it.
pub(crate) fn qr_matrix<const D: usize>(a: &Matrix<D>) -> (Matrix<D>, Vector<D>)
where
    Const<D>: DimMin<Const<D>, Output = Const<D>>,
{
    let qr = a.qr();
    // nalgebra's `r()` puts |R_ii| on the diagonal and `q()` flips the
    // matching columns of Q, so A = Q R holds with R_ii >= 0: log R_ii is
    // the growth of the i-th direction, whatever the reflections' signs.
    (qr.q(), qr.r().diagonal())
}

/// `qr_matrix` on the array form, for callers of the array interface.
pub fn qr<const D: usize>(a: &Square<D>) -> (Square<D>, [f64; D])
where
    Const<D>: DimMin<Const<D>, Output = Const<D>>,
{
    let (q, r) = qr_matrix(&matrix(a));
    (square(&q), r.into())
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

    fn identity<const D: usize>() -> Square<D> {
        square(&Matrix::identity())
    }

    fn mul<const D: usize>(a: &Square<D>, b: &Square<D>) -> Square<D> {
        square(&(matrix(a) * matrix(b)))
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
