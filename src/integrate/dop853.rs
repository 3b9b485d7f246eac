//! DOP853: Dormand–Prince 8(5,3) with 7th-order dense output.
//!
//! References:
//! - P. J. Prince, J. R. Dormand, "High order embedded Runge–Kutta formulae",
//!   J. Comput. Appl. Math. 7 (1981) 67–75 (the 8th-order family).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I*, 2nd ed., Springer 1993, §II.10 and the code `dop853.f`:
//!   the 5th- and 3rd-order error estimators combined as
//!   `err = |h| e5² / sqrt(N (e5² + 0.01 e3²))`, the three extra stages of the
//!   dense output, and the controller (safety 0.9, step ratio in
//!   [1/3, 6], no Lund stabilisation).
//! - scipy `integrate/_ivp/rk.py` (`DOP853`) and `dop853_coefficients.py`,
//!   the source of the tableau in `dop853_tableau.rs`.
//!
//! The project's default method: at the tight tolerances the impact times need
//! (rtol 1e-10) it uses fewer evaluations than DOPRI5, and its dense output is
//! accurate enough for root finding to machine precision.

use super::controller::err_scale;
use super::dop853_tableau::{A, B, C, D, E3, E5, N_DENSE_ROWS, N_STAGES, N_STAGES_EXTENDED};
use super::embedded::{EmbeddedRk, Pair};
use super::stages::{all_finite, combine, combine_leading};
use super::stepper::{Rhs, StepError};

/// Index of the FSAL stage `f(t + h, y_new)`.
const FSAL: usize = N_STAGES;

/// Hairer's DOP853 stepper.
///
/// Adaptive, 8th order, 12 evaluations of `f` per accepted step (11 stages
/// plus the FSAL stage, which is evaluated only once the step is accepted),
/// 11 per rejected attempt, and 3 more the first time dense output is asked
/// for after a step. The stage slots are in the tableau's 0-based layout:
/// `k[0] = f(t_old, y_old)`, `k[12] = f(t, y)`, `k[13..16]` the extra
/// dense-output stages once computed.
pub type Dop853<const N: usize> = EmbeddedRk<Dop853Pair, N, N_STAGES_EXTENDED>;

/// The DOP853 pair, for [`EmbeddedRk`].
#[derive(Clone, Copy, Debug)]
pub struct Dop853Pair;

/// DOP853's dense output: the polynomial of the last step, built on the
/// first call that needs it.
#[derive(Clone, Debug)]
pub struct Dop853Dense<const N: usize> {
    /// Coefficients of the dense polynomial in scipy's `F` form, valid when
    /// `ready`.
    cont: [[f64; N]; 3 + N_DENSE_ROWS],
    /// The extra stages and `cont` have been computed for the last step.
    ready: bool,
    /// The extra stages are in place (a still step's zeros): `cont` needs
    /// no evaluation of `f`.
    extra: bool,
}

impl<const N: usize> Pair<N, N_STAGES_EXTENDED> for Dop853Pair {
    const NAME: &'static str = "dop853";
    const ORDER: i32 = 8;
    const FSAL: usize = FSAL;
    const FSAL_AFTER_TEST: bool = true;
    const RETRY_NON_FINITE: bool = true;
    // Hairer's defaults for DOP853: SAFE = 0.9, FAC1 = 0.333, FAC2 = 6,
    // BETA = 0, EXPO1 = 1/8 - BETA * 0.2 (no Lund stabilisation).
    const CONTROL: [f64; 5] = [0.9, 0.333, 6.0, 0.0, 1.0 / 8.0];

    type Dense = Dop853Dense<N>;

    fn new_dense() -> Dop853Dense<N> {
        Dop853Dense {
            cont: [[0.0; N]; 3 + N_DENSE_ROWS],
            ready: false,
            extra: false,
        }
    }

    #[inline]
    fn invalidate(dense: &mut Dop853Dense<N>) {
        dense.ready = false;
        dense.extra = false;
    }

    #[inline]
    fn attempt<F: Rhs<N>>(
        rk: &mut Dop853<N>,
        f: &F,
        h: f64,
        t_new: f64,
        y_new: &mut [f64; N],
    ) -> Result<f64, StepError> {
        rk.attempt(f, h, t_new, y_new)
    }

    /// The extra stages of a still step are zero, as its others are: its
    /// dense output, if asked for, is built from them without `f`.
    #[inline]
    fn still_dense(rk: &mut Dop853<N>) {
        rk.dense.extra = true;
    }

    /// 7th-order dense output. The first call after a step evaluates the
    /// three extra stages (counted in `rhs_evals`); later calls on the same
    /// step are free.
    #[inline]
    fn dense_inside<F: Rhs<N>>(rk: &mut Dop853<N>, f: &F, theta: f64, out: &mut [f64; N], count: usize) {
        if !rk.dense.ready {
            rk.prepare_dense(f);
        }
        rk.interpolate(theta, out, count);
    }
}

impl<const N: usize> Dop853<N> {
    /// One attempt of size `h` ending at `t_new`: fills `k[1..12]` and
    /// `y_new`, returns Hairer's combined error norm.
    fn attempt<F: Rhs<N>>(&mut self, f: &F, h: f64, t_new: f64, y_new: &mut [f64; N]) -> Result<f64, StepError> {
        let t = self.t;
        let mut ys = [0.0; N];
        // No finiteness test per stage: every stage has a non-zero weight in
        // a later stage, the solution or the error estimate (a tableau test
        // checks it), and `combine` skips zero weights (no 0·∞), so a
        // non-finite stage always shows in `y_new` or the error, which are
        // tested below.
        // Stage states need only the components `f` reads.
        let read = N - F::QUADRATURES.min(N);
        for i in 1..N_STAGES {
            combine_leading(&self.y, h, &A[i][..i], &self.k[..i], &mut ys, read);
            let ti = if C[i] == 1.0 { t_new } else { t + C[i] * h };
            self.eval(f, ti, &ys, i);
        }
        combine(&self.y, h, &B, &self.k[..N_STAGES], y_new);
        if !all_finite(y_new) {
            return Err(StepError::NonFinite { t });
        }
        // Stages outer, components inner (vectorisable, like `combine`);
        // each component sums its stages in the same order as before.
        let (mut e5, mut e3) = ([0.0; N], [0.0; N]);
        for ((kj, e5j), e3j) in self.k.iter().zip(&E5).zip(&E3) {
            if *e5j == 0.0 && *e3j == 0.0 {
                continue;
            }
            for n in 0..N {
                e5[n] += e5j * kj[n];
                e3[n] += e3j * kj[n];
            }
        }
        let (mut e5sq, mut e3sq) = (0.0, 0.0);
        for n in 0..N {
            // One division per component instead of two.
            let inv = 1.0 / err_scale(&self.tol, self.y[n], y_new[n]);
            e5sq += (e5[n] * inv).powi(2);
            e3sq += (e3[n] * inv).powi(2);
        }
        let mut deno = e5sq + 0.01 * e3sq;
        if deno <= 0.0 {
            deno = 1.0; // both estimates zero: err = 0 (Hairer)
        }
        let err = h.abs() * e5sq * (1.0 / (N.max(1) as f64 * deno)).sqrt();
        // NaN only comes from a non-finite stage; an infinite error from
        // finite stages is just a step far too large (rejected, cut).
        if err.is_nan() {
            return Err(StepError::NonFinite { t });
        }
        Ok(err)
    }

    /// Computes the three extra stages and the dense coefficients, once per
    /// step (scipy `_dense_output_impl`, Hairer's block after label 40).
    fn prepare_dense<F: Rhs<N>>(&mut self, f: &F) {
        let h = self.h_used;
        let mut ys = [0.0; N];
        let read = N - F::QUADRATURES.min(N);
        if !self.dense.extra {
            for s in FSAL + 1..N_STAGES_EXTENDED {
                combine_leading(&self.y_old, h, &A[s][..s], &self.k[..s], &mut ys, read);
                self.eval(f, self.t_old + C[s] * h, &ys, s);
            }
        }
        self.fill_cont();
    }

    /// The dense coefficients from the stages, extra ones included.
    fn fill_cont(&mut self) {
        let h = self.h_used;
        let (f_old, f_new) = (self.k[0], self.k[FSAL]);
        for n in 0..N {
            let dy = self.y[n] - self.y_old[n];
            self.dense.cont[0][n] = dy;
            self.dense.cont[1][n] = h * f_old[n] - dy;
            self.dense.cont[2][n] = 2.0 * dy - h * (f_new[n] + f_old[n]);
            for (r, drow) in D.iter().enumerate() {
                let mut s = 0.0;
                for (dj, kj) in drow.iter().zip(&self.k) {
                    if *dj != 0.0 {
                        s += dj * kj[n];
                    }
                }
                self.dense.cont[3 + r][n] = h * s;
            }
        }
        self.dense.ready = true;
    }

    /// The dense polynomial at `theta`, Horner-like in `θ` and `1 - θ`
    /// alternately: `y_old + θ(F0 + (1-θ)(F1 + θ(F2 + (1-θ)(F3 + ...))))`.
    fn interpolate(&self, theta: f64, out: &mut [f64; N], count: usize) {
        let th1 = 1.0 - theta;
        for n in 0..count.min(N) {
            let mut acc = 0.0;
            for (i, c) in self.dense.cont.iter().enumerate().rev() {
                acc += c[n];
                acc *= if i % 2 == 0 { theta } else { th1 };
            }
            out[n] = self.y_old[n] + acc;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::dopri5::Dopri5;
    use super::super::stepper::Stepper;
    use super::super::stepper_checks::{observed_orders, osc, osc_exact, run};
    use super::*;

    use super::super::stepper_checks::{self as checks, tol};

    checks::adaptive_stepper_tests!(Dop853, "dop853");

    #[test]
    fn local_and_dense_orders() {
        let (p_end, p_mid) = observed_orders(Dop853::new, 0.8);
        eprintln!("dop853 local order {p_end:.2}, dense order {p_mid:.2}");
        // Local error O(h^9) for the 8th-order solution, O(h^8) for the
        // 7th-order interpolant.
        assert!((8.4..9.8).contains(&p_end), "end {p_end}");
        assert!((7.4..8.8).contains(&p_mid), "mid {p_mid}");
    }

    #[test]
    fn dense_matches_step_ends_and_closed_form() {
        let mut s = checks::oscillator_after_five_steps(Dop853::new);
        let before = s.stats().rhs_evals;
        // End points: exact, and no extra stages needed.
        let y_old = s.y_old;
        checks::dense_returns_the_step_ends(&mut s, &y_old);
        assert_eq!(s.stats().rhs_evals, before);
        // Interior points: the extra stages cost 3 evaluations, once.
        checks::dense_is_accurate_inside(&mut s);
        assert_eq!(s.stats().rhs_evals, before + 3);
        // The polynomial itself at θ = 0 and θ = 1 (from those stages).
        checks::interpolant_meets_the_ends(&s.y_old, &s.y, |theta, p| s.interpolate(theta, p, 2));
        // A new step invalidates the extra stages.
        s.step(&osc, 20.0).unwrap();
        let before = s.stats().rhs_evals;
        let mut out = [0.0; 2];
        s.dense(&osc, 0.5 * (s.t_prev() + s.t()), &mut out);
        assert_eq!(s.stats().rhs_evals, before + 3);
    }

    #[test]
    fn leading_interpolants_equal_the_full_ones_and_leave_the_rest() {
        let f = |t: f64, y: &[f64; 3], d: &mut [f64; 3]| {
            d[0] = y[1];
            d[1] = -y[0] + 0.3 * t.sin();
            d[2] = y[0] * y[0];
        };
        let mut s = Dop853::new(tol(1e-9, 1e-9));
        s.restart(&f, 0.0, &[1.0, 0.0, 0.0]);
        s.step(&f, 10.0).unwrap();
        let t = 0.5 * (s.t_prev() + s.t());
        let (mut full, mut lead) = ([0.0; 3], [7.0; 3]);
        s.dense(&f, t, &mut full);
        s.dense_leading(&f, t, &mut lead, 2);
        assert_eq!(lead, [full[0], full[1], 7.0], "same bits, third untouched");
        let (mut full, mut lead) = ([0.0; 3], [7.0; 3]);
        assert!(s.hermite(t, &mut full) && s.hermite_leading(t, &mut lead, 2));
        assert_eq!(lead, [full[0], full[1], 7.0]);
        // At the step's ends, the stored states.
        s.dense_leading(&f, s.t(), &mut lead, 2);
        assert_eq!(lead[..2], s.y()[..2]);
    }

    #[test]
    fn fewer_evaluations_than_dopri5_at_tight_tolerance() {
        let tl = tol(1e-10, 1e-10);
        let mut a = Dop853::new(tl);
        run(&mut a, &osc, [0.0, 1.0], 20.0, osc_exact);
        let mut b = Dopri5::new(tl);
        run(&mut b, &osc, [0.0, 1.0], 20.0, osc_exact);
        let (na, nb) = (a.stats().rhs_evals, b.stats().rhs_evals);
        eprintln!("rhs evaluations over 0..20 at 1e-10: dop853 {na}, dopri5 {nb}");
        assert!(na < nb, "dop853 {na} vs dopri5 {nb}");
    }
}
