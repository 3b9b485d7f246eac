//! Dormand–Prince 5(4) with first-same-as-last, Shampine's 4th-order dense
//! output and Hairer's PI step-size controller.
//!
//! References:
//! - J. R. Dormand, P. J. Prince, "A family of embedded Runge–Kutta formulae",
//!   J. Comput. Appl. Math. 6 (1980) 19–26 (the tableau).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I*, 2nd ed., Springer 1993: §II.4 (error norm and initial step,
//!   the `HINIT` routine), §II.5 (tableau 5.2), §II.6 (dense output), and the
//!   code `dopri5.f` (controller with Lund stabilisation, `beta = 0.04`).
//! - scipy `integrate/_ivp/rk.py` (`RK45`), used as a cross-check.
//!
//! This file holds what is DOPRI5's own: the tableau, an attempt and the
//! continuous extension. The step loop, restarts and FSAL bookkeeping are
//! [`EmbeddedRk`]'s, the controller is in [`super::controller`]; both are
//! shared with [`super::dop853`], Hairer's other code with the same logic.

use super::controller::err_scale;
use super::embedded::{EmbeddedRk, Pair};
use super::stages::{all_finite, combine};
use super::stepper::{Rhs, StepError};

// ---------------------------------------------------------------------------
// The DOPRI5 tableau (Hairer–Nørsett–Wanner table II.5.2).
// ---------------------------------------------------------------------------

const STAGES: usize = 7;
const C: [f64; STAGES] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; STAGES - 1]; STAGES] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    // 5th-order weights b_j: the last row is the solution (FSAL).
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Error weights `b_j - b̂_j` (5th minus 4th order), Hairer's `E1..E7`.
const E: [f64; STAGES] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Shampine's dense-output coefficients (Hairer's `D1..D7`, `D2 = 0`).
const D: [f64; STAGES] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Dormand–Prince 5(4) stepper (Hairer's DOPRI5).
///
/// Adaptive, 5th order with a 4th-order embedded error estimate, 6 evaluations
/// of `f` per attempted step thanks to FSAL, and a 4th-order continuous
/// extension that costs nothing extra. Controller as in `dopri5.f`:
/// safety 0.9, step ratio in [0.2, 10], Lund stabilisation `beta = 0.04`.
/// The stage slots hold `k[0] = f(t_old, y_old)` and `k[6] = f(t, y)` once
/// a step has been taken.
pub type Dopri5<const N: usize> = EmbeddedRk<Dopri5Pair, N, STAGES>;

/// The DOPRI5 pair, for [`EmbeddedRk`].
#[derive(Clone, Copy, Debug)]
pub struct Dopri5Pair;

impl<const N: usize> Pair<N, STAGES> for Dopri5Pair {
    const NAME: &'static str = "dopri5";
    const ORDER: i32 = 5;
    // The last stage is `f(t + h, y_new)` (its row of `A` is the solution).
    const FSAL: usize = STAGES - 1;
    const FSAL_AFTER_TEST: bool = false;
    const RETRY_NON_FINITE: bool = false;
    // Hairer's defaults: SAFE = 0.9, FAC1 = 0.2, FAC2 = 10, BETA = 0.04,
    // EXPO1 = 0.2 - BETA * 0.75.
    const CONTROL: [f64; 5] = [0.9, 0.2, 10.0, 0.04, 0.2 - 0.04 * 0.75];

    /// The continuous extension needs the stages only.
    type Dense = ();

    fn new_dense() {}

    /// Fills `k[1..7]` and `y_new`, returns the error norm.
    fn attempt<F: Rhs<N>>(
        rk: &mut Dopri5<N>,
        f: &F,
        h: f64,
        t_new: f64,
        y_new: &mut [f64; N],
    ) -> Result<f64, StepError> {
        let t = rk.t;
        let mut ys = [0.0; N];
        for i in 1..STAGES {
            combine(&rk.y, h, &A[i][..i], &rk.k[..i], &mut ys);
            if !all_finite(&ys) {
                return Err(StepError::NonFinite { t });
            }
            // Stages with c = 1 use the exact end time, so that the FSAL
            // stage is f at the time the step reports.
            let ti = if C[i] == 1.0 { t_new } else { t + C[i] * h };
            rk.eval(f, ti, &ys, i);
            if !all_finite(&rk.k[i]) {
                return Err(StepError::NonFinite { t });
            }
        }
        *y_new = ys;
        let mut sum = 0.0;
        for n in 0..N {
            let mut e = 0.0;
            for (ej, kj) in E.iter().zip(&rk.k) {
                if *ej != 0.0 {
                    e += ej * kj[n];
                }
            }
            let sk = err_scale(&rk.tol, rk.y[n], y_new[n]);
            sum += (h * e / sk).powi(2);
        }
        Ok((sum / N.max(1) as f64).sqrt())
    }

    /// 4th-order dense output (Shampine 1986, Hairer's `CONTD5`). Never
    /// evaluates `f`.
    #[inline]
    fn dense_inside<F: Rhs<N>>(rk: &mut Dopri5<N>, _f: &F, theta: f64, out: &mut [f64; N], count: usize) {
        rk.interpolate_leading(theta, out, count);
    }
}

impl<const N: usize> Dopri5<N> {
    /// The continuous extension at `theta = (t - t_old) / h` in Hairer's
    /// form (`CONTD5`): `y_old + θ(Δ + (1-θ)(r3 + θ(r4 + (1-θ) r5)))`.
    /// (The stepper interpolates the leading components it is asked for;
    /// the tests look at the whole polynomial.)
    #[cfg(test)]
    fn interpolate(&self, theta: f64, out: &mut [f64; N]) {
        self.interpolate_leading(theta, out, N);
    }

    /// The continuous extension for the leading `count` components (the
    /// rest of `out` is left as it was).
    fn interpolate_leading(&self, theta: f64, out: &mut [f64; N], count: usize) {
        let h = self.h_used;
        let th1 = 1.0 - theta;
        let (k0, k6) = (&self.k[0], &self.k[STAGES - 1]);
        for n in 0..count.min(N) {
            let ydiff = self.y[n] - self.y_old[n];
            let bspl = h * k0[n] - ydiff;
            let r4 = ydiff - h * k6[n] - bspl;
            let mut d = 0.0;
            for (dj, kj) in D.iter().zip(&self.k) {
                if *dj != 0.0 {
                    d += dj * kj[n];
                }
            }
            let r5 = h * d;
            out[n] = self.y_old[n] + theta * (ydiff + th1 * (bspl + theta * (r4 + th1 * r5)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::stepper_checks::{self as checks, observed_orders};
    use super::*;

    checks::adaptive_stepper_tests!(Dopri5, "dopri5");

    #[test]
    fn local_and_dense_orders() {
        let (p_end, p_mid) = observed_orders(Dopri5::new, 0.2);
        eprintln!("dopri5 local order {p_end:.2}, dense order {p_mid:.2}");
        // Local error O(h^6) for a 5th-order method, O(h^5) for the
        // 4th-order interpolant.
        assert!((5.5..6.6).contains(&p_end), "end {p_end}");
        assert!((4.5..5.6).contains(&p_mid), "mid {p_mid}");
    }

    #[test]
    fn dense_matches_step_ends_and_closed_form() {
        let mut s = checks::oscillator_after_five_steps(Dopri5::new);
        checks::interpolant_meets_the_ends(&s.y_old, &s.y, |theta, p| s.interpolate(theta, p));
        let y_old = s.y_old;
        checks::dense_returns_the_step_ends(&mut s, &y_old);
        checks::dense_is_accurate_inside(&mut s);
    }
}
