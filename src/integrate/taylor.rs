//! A Taylor-series method of high order, with DOP853 for the modes it has
//! no series for.
//!
//! References:
//! - À. Jorba, M. Zou, "A software package for the numerical integration of
//!   ODEs by means of high-order Taylor methods", Experimental Mathematics
//!   14 (2005) 99–117: the order `p ≈ −ln ε / 2` and the step from the last
//!   two coefficients, `h = min_k (ε/‖y_k‖)^{1/k}, k = p−1, p`, times
//!   `exp(−0.7/(p−1))`.
//! - F. Biscani, D. Izzo, "Revisiting high-order Taylor methods for
//!   astrodynamics and celestial mechanics", MNRAS 504 (2021) 2614 (heyoka):
//!   the same rule, with the polynomial itself as dense output.
//!
//! The right-hand side provides the Taylor coefficients of the solution at
//! the start of a step ([`Rhs::taylor`]), computed by the recurrences of
//! automatic differentiation; a step evaluates the polynomial. There is no
//! rejected step (the coefficients fix the step before it is taken) and the
//! dense output is the polynomial itself, exact to the step's tolerance and
//! free. Where [`Rhs::taylor`] returns `false` (the block's pulse and record
//! excitations) the step is DOP853's.

use super::dop853::Dop853;
use super::stepper::{Rhs, StepError, StepStats, Stepper, Tolerances, step_ends};

/// Highest order the stepper uses (the order for rtol 1e-14 is 28).
pub(crate) const MAX_ORDER: usize = 28;

/// Lowest order: below it the step from the coefficients is too short to
/// beat DOP853.
const MIN_ORDER: usize = 8;

/// The order for a tolerance: `⌈1.2 (−ln ε)⌉`, 28 (the highest) at rtol
/// 1e-10 and 23 at 1e-8. That is far above Jorba and Zou's `−ln ε / 2`
/// (12), which is the optimum for an analytic solution stepped freely: the
/// block's steps end at every impact (about every 0.4 τ in the paper's
/// periodic scene), so a longer series buys fewer steps between impacts.
/// On that scene at rtol 1e-10, orders 12, 14, 16, 18 and 20 take 13,493,
/// 9,312, 7,193, 6,161 and 5,149 steps; with the fused expansions of
/// `model::series`, orders 20 and 28 take the same time there (5,149 and
/// 4,075 steps), and on the app's default scene order 28 takes 95,000
/// steps to order 20's 139,000 and runs about 10 % faster, as does order
/// 23 against 16 at rtol 1e-8 (docs/performance.md). Higher orders (30–34)
/// take no fewer steps than the events allow and run slower.
pub fn order_for(rtol: f64) -> usize {
    let eps = rtol.clamp(1e-16, 1e-2);
    ((-1.2 * eps.ln()).ceil() as usize).clamp(MIN_ORDER, MAX_ORDER)
}

/// The Taylor stepper.
#[derive(Clone, Debug)]
pub struct Taylor<const N: usize> {
    tol: Tolerances,
    order: usize,
    /// Jorba and Zou's safety factor `exp(−0.7/(p−1))`.
    safety: f64,
    t: f64,
    t_old: f64,
    y: [f64; N],
    y_old: [f64; N],
    /// Taylor coefficients of the last step at `t_old`: `y(t_old + s) =
    /// Σ_k coef[k] s^k`, rows 0..=order.
    coef: [[f64; N]; MAX_ORDER + 1],
    /// The last step was a Taylor step (else DOP853's, in `fallback`).
    has_step: bool,
    /// The last step was DOP853's: dense output and Hermite data are its.
    on_fallback: bool,
    /// `fallback` has been restarted at the current state.
    fallback_synced: bool,
    fallback: Dop853<N>,
    h_used: f64,
    stats: StepStats,
}

impl<const N: usize> Taylor<N> {
    /// A stepper with the given tolerances, of order [`order_for`]`(rtol)`.
    pub fn new(tol: Tolerances) -> Self {
        Self::with_order(tol, order_for(tol.rtol))
    }

    /// A stepper of a chosen order (clamped to 2..=[`MAX_ORDER`]).
    pub(crate) fn with_order(tol: Tolerances, order: usize) -> Self {
        let order = order.clamp(2, MAX_ORDER);
        Self {
            tol,
            order,
            safety: (-0.7 / (order - 1) as f64).exp(),
            t: 0.0,
            t_old: 0.0,
            y: [0.0; N],
            y_old: [0.0; N],
            coef: [[0.0; N]; MAX_ORDER + 1],
            has_step: false,
            on_fallback: false,
            fallback_synced: false,
            fallback: Dop853::new(tol),
            h_used: 0.0,
            stats: StepStats::default(),
        }
    }

    /// The order of the series.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The step the coefficients allow (Jorba and Zou): for each of the last
    /// two orders k, the largest h with `|y_k,n| h^k ≤ atol + rtol |y_n|`
    /// in every component, the smaller of the two, times `exp(−0.7/(p−1))`.
    /// Infinite for a polynomial solution of lower degree (a block at rest).
    fn step_from_coefficients(&self) -> f64 {
        let p = self.order;
        let mut log_h = f64::INFINITY;
        for k in [p - 1, p] {
            let mut r: f64 = 0.0;
            for n in 0..N {
                let sk = self.tol.atol + self.tol.rtol * self.y[n].abs().max(self.y_old[n].abs());
                r = r.max(self.coef[k][n].abs() / sk);
            }
            if r > 0.0 {
                // r^(-1/k) by its logarithm: the smaller exponent gives the
                // smaller step, so one `exp` serves both orders.
                log_h = log_h.min(-r.ln() / k as f64);
            }
        }
        log_h.exp() * self.safety
    }

    /// The polynomial at offset `s` from `t_old`, leading `count` components.
    #[inline]
    fn eval_poly(&self, s: f64, out: &mut [f64; N], count: usize) {
        match count.min(N) {
            1 => self.estrin::<1>(s, out),
            2 => self.estrin::<2>(s, out),
            c if c <= 4 && N >= 4 => self.estrin::<4>(s, out),
            _ => self.estrin::<N>(s, out),
        }
    }

    /// Estrin's scheme for the leading `C` components: coefficients paired
    /// as `c_2i + c_2i+1 s`, the pairs paired with `s²`, those with `s⁴`,
    /// and so on. Horner's rule is one chain of `p` multiply–adds; this is
    /// a tree `⌈log₂(p+1)⌉` deep. A root search evaluates the polynomial
    /// once per iteration, each waiting on the last, so the depth is its
    /// cost (about a quarter of Horner's at order 28). The rounding error
    /// is of the same size as Horner's.
    #[inline]
    fn estrin<const C: usize>(&self, s: f64, out: &mut [f64; N]) {
        let len = self.order + 1;
        let mut buf = [[0.0; C]; (MAX_ORDER + 2) / 2];
        let mut m = len / 2;
        for (i, b) in buf.iter_mut().enumerate().take(m) {
            let (lo, hi) = (&self.coef[2 * i], &self.coef[2 * i + 1]);
            for n in 0..C {
                b[n] = lo[n] + hi[n] * s;
            }
        }
        if len % 2 == 1 {
            buf[m].copy_from_slice(&self.coef[len - 1][..C]);
            m += 1;
        }
        let mut x = s * s;
        while m > 1 {
            let half = m / 2;
            for i in 0..half {
                let (lo, hi) = (buf[2 * i], buf[2 * i + 1]);
                for n in 0..C {
                    buf[i][n] = lo[n] + hi[n] * x;
                }
            }
            if m % 2 == 1 {
                buf[half] = buf[m - 1];
                m = half + 1;
            } else {
                m = half;
            }
            x *= x;
        }
        out[..C].copy_from_slice(&buf[0]);
    }

    /// Its derivative at offset `s`, all components.
    fn eval_derivative(&self, s: f64, out: &mut [f64; N]) {
        let p = self.order as f64;
        let mut acc = self.coef[self.order].map(|c| p * c);
        for k in (1..self.order).rev() {
            let (row, kk) = (&self.coef[k], k as f64);
            for n in 0..N {
                acc[n] = acc[n] * s + kk * row[n];
            }
        }
        *out = acc;
    }

    /// Both ends and their derivatives, for the Hermite screening.
    fn ends(&self) -> ([f64; N], [f64; N]) {
        let mut f1 = [0.0; N];
        self.eval_derivative(self.h_used, &mut f1);
        (self.coef[1], f1)
    }

    /// One step; `still` (see [`Stepper::step_still`]) passes on to the
    /// fallback's step.
    fn step_either<F: Rhs<N>>(&mut self, f: &F, t_stop: f64, still: bool) -> Result<(), StepError> {
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(StepError::StepSizeUnderflow {
                t: self.t,
                h: t_stop - self.t,
            });
        }
        self.has_step = false;
        let order = self.order;
        if f.taylor(self.t, &self.y, order, &mut self.coef[..=order]) {
            self.stats.rhs_evals += 1;
            self.on_fallback = false;
            self.fallback_synced = false;
            if !self.coef[..=order].iter().all(|row| row.iter().all(|v| v.is_finite())) {
                return Err(StepError::NonFinite { t: self.t });
            }
            let h_allowed = self.step_from_coefficients().min(self.tol.h_max);
            let dist = t_stop - self.t;
            let (h, t_new) = if h_allowed >= dist {
                (dist, t_stop)
            } else {
                (h_allowed, self.t + h_allowed)
            };
            if h.is_nan() || h <= 0.0 || t_new <= self.t {
                return Err(StepError::StepSizeUnderflow { t: self.t, h });
            }
            let mut y_new = [0.0; N];
            self.eval_poly(h, &mut y_new, N);
            if !y_new.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFinite { t: self.t });
            }
            self.t_old = self.t;
            self.y_old = self.y;
            self.t = t_new;
            self.y = y_new;
            self.h_used = h;
            self.has_step = true;
            self.stats.accepted += 1;
            return Ok(());
        }
        // No series for this right-hand side: DOP853 takes the step.
        if !self.fallback_synced {
            let y = self.y;
            self.fallback.restart(f, self.t, &y);
            self.fallback_synced = true;
        }
        self.on_fallback = true;
        if still {
            self.fallback.step_still(f, t_stop)?;
        } else {
            self.fallback.step(f, t_stop)?;
        }
        self.t_old = self.fallback.t_prev();
        self.y_old = self.y;
        self.t = self.fallback.t();
        self.y = *self.fallback.y();
        self.h_used = self.t - self.t_old;
        self.has_step = true;
        Ok(())
    }
}

impl<const N: usize> Stepper<N> for Taylor<N> {
    fn name(&self) -> &'static str {
        "taylor"
    }

    /// Starts at `(t, y)`. Evaluates nothing: the coefficients belong to the
    /// step, and DOP853 is restarted only if a step needs it.
    fn restart<F: Rhs<N>>(&mut self, _f: &F, t: f64, y: &[f64; N]) {
        self.t = t;
        self.t_old = t;
        self.y = *y;
        self.y_old = *y;
        self.has_step = false;
        self.on_fallback = false;
        self.fallback_synced = false;
        self.h_used = 0.0;
    }

    fn step<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        self.step_either(f, t_stop, false)
    }

    /// The series of a still field is its constant state, and costs one
    /// forcing series; DOP853, where there is no series (a record), takes
    /// its still step.
    fn step_still<F: Rhs<N>>(&mut self, f: &F, t_stop: f64) -> Result<(), StepError> {
        self.step_either(f, t_stop, true)
    }

    step_ends!();

    /// The step's polynomial (or DOP853's dense output). The end states are
    /// returned bit for bit.
    fn dense<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N]) {
        self.dense_leading(f, t, out, N);
    }

    fn dense_leading<F: Rhs<N>>(&mut self, f: &F, t: f64, out: &mut [f64; N], count: usize) {
        if !self.has_step || t == self.t {
            out[..count].copy_from_slice(&self.y[..count]);
        } else if t == self.t_old {
            out[..count].copy_from_slice(&self.y_old[..count]);
        } else if self.on_fallback {
            self.fallback.dense_leading(f, t, out, count);
        } else {
            self.eval_poly(t - self.t_old, out, count);
        }
    }

    /// The screening interpolant: the polynomial itself, more accurate than
    /// the cubic the driver assumes (so its margin is conservative).
    fn hermite_leading(&self, t: f64, out: &mut [f64; N], count: usize) -> bool {
        if !self.has_step {
            return false;
        }
        if self.on_fallback {
            return self.fallback.hermite_leading(t, out, count);
        }
        if t == self.t {
            out[..count].copy_from_slice(&self.y[..count]);
        } else {
            self.eval_poly(t - self.t_old, out, count);
        }
        true
    }

    /// The cubic's third-order term from the polynomial's end slopes, as
    /// for the Runge–Kutta methods: an overestimate of the polynomial's
    /// error, which keeps the screening as conservative as theirs.
    fn hermite_spread(&self, out: &mut [f64; N]) -> bool {
        if !self.has_step {
            return false;
        }
        if self.on_fallback {
            return self.fallback.hermite_spread(out);
        }
        let (f0, f1) = self.ends();
        let h = self.h_used;
        for n in 0..N {
            out[n] = (2.0 * (self.y[n] - self.y_old[n]) - h * (f0[n] + f1[n])) / 8.0;
        }
        true
    }

    fn stats(&self) -> StepStats {
        let mut s = self.stats;
        s += self.fallback.stats();
        s
    }

    fn step_size(&self) -> f64 {
        self.h_used
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = y with its series: y_k = y_0 / k!.
    struct Growth;
    impl Rhs<1> for Growth {
        fn eval(&self, _t: f64, y: &[f64; 1], d: &mut [f64; 1]) {
            d[0] = y[0];
        }
        fn taylor(&self, _t: f64, y: &[f64; 1], order: usize, c: &mut [[f64; 1]]) -> bool {
            c[0] = *y;
            for k in 0..order {
                c[k + 1][0] = c[k][0] / (k + 1) as f64;
            }
            true
        }
    }

    /// The harmonic oscillator y'' = −y as a first-order system.
    struct Oscillator;
    impl Rhs<2> for Oscillator {
        fn eval(&self, _t: f64, y: &[f64; 2], d: &mut [f64; 2]) {
            *d = [y[1], -y[0]];
        }
        fn taylor(&self, _t: f64, y: &[f64; 2], order: usize, c: &mut [[f64; 2]]) -> bool {
            c[0] = *y;
            for k in 0..order {
                let kk = (k + 1) as f64;
                c[k + 1] = [c[k][1] / kk, -c[k][0] / kk];
            }
            true
        }
    }

    fn tol(rtol: f64) -> Tolerances {
        Tolerances {
            rtol,
            atol: rtol,
            ..Tolerances::default()
        }
    }

    #[test]
    fn exponential_growth_is_followed_to_the_tolerance() {
        for rtol in [1e-6, 1e-10, 1e-13] {
            let mut s = Taylor::new(tol(rtol));
            s.restart(&Growth, 0.0, &[1.0]);
            while s.t() < 5.0 {
                s.step(&Growth, 5.0).unwrap();
            }
            assert_eq!(s.t(), 5.0);
            let rel = (s.y()[0] / 5.0f64.exp() - 1.0).abs();
            // A global error of a few hundred local ones at most.
            assert!(rel < 300.0 * rtol, "rtol {rtol}: relative error {rel:e}");
            assert_eq!(s.stats().rejected, 0);
        }
    }

    #[test]
    fn an_oscillation_and_its_dense_output_stay_on_the_circle() {
        let mut s = Taylor::new(tol(1e-10));
        s.restart(&Oscillator, 0.0, &[0.0, 1.0]);
        let mut worst: f64 = 0.0;
        while s.t() < 20.0 {
            s.step(&Oscillator, 20.0).unwrap();
            let (a, b) = (s.t_prev(), s.t());
            for j in 0..=8 {
                let t = a + (b - a) * j as f64 / 8.0;
                let mut out = [0.0; 2];
                s.dense(&Oscillator, t, &mut out);
                worst = worst.max((out[0] - t.sin()).abs()).max((out[1] - t.cos()).abs());
            }
        }
        assert!(worst < 1e-8, "worst error {worst:e}");
        // About 6 steps per period at this tolerance, against DOP853's 13.
        assert!(s.stats().accepted < 40, "{} steps", s.stats().accepted);
    }

    #[test]
    fn a_step_lands_on_its_stop_bit_for_bit() {
        let mut s = Taylor::new(tol(1e-10));
        s.restart(&Oscillator, 0.0, &[0.0, 1.0]);
        s.step(&Oscillator, 0.1).unwrap();
        assert_eq!(s.t(), 0.1);
        let mut out = [0.0; 2];
        s.dense(&Oscillator, 0.1, &mut out);
        assert_eq!(out, *s.y());
    }

    #[test]
    fn without_a_series_the_step_is_dop853s() {
        let f = |_t: f64, y: &[f64; 1], d: &mut [f64; 1]| d[0] = -y[0];
        let mut s = Taylor::new(tol(1e-10));
        let mut d = Dop853::new(tol(1e-10));
        s.restart(&f, 0.0, &[1.0]);
        d.restart(&f, 0.0, &[1.0]);
        while d.t() < 3.0 {
            s.step(&f, 3.0).unwrap();
            d.step(&f, 3.0).unwrap();
            assert_eq!(s.t(), d.t());
            assert_eq!(s.y(), d.y());
        }
        assert_eq!(s.stats(), d.stats());
    }

    #[test]
    fn orders_follow_the_tolerance() {
        assert_eq!(order_for(1e-10), 28);
        assert_eq!(order_for(1e-8), 23);
        assert_eq!(order_for(1e-3), 9);
        assert!(order_for(1e-16) <= MAX_ORDER);
    }
}
