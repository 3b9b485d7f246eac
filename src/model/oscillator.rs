//! The exact linear oscillator: a single-degree-of-freedom system of
//! circular frequency ω and damping ratio ζ < 1 under a ground acceleration
//! a(t), ü + 2ζωu̇ + ω²u = −a(t), u the displacement relative to the ground.
//!
//! Contract:
//! - Units: any one time unit (seconds for records, τ for the model's
//!   harmonic excitation); ω in radians per that unit, accelerations in any
//!   unit (g in this crate), displacements and velocities in that unit times
//!   the time unit squared and to the first power. Nothing here converts.
//! - Exact: for a ground acceleration that is linear between samples the
//!   response inside an interval is the closed form (Nigam & Jennings 1969;
//!   Chopra, *Dynamics of Structures*, §5.2): a particular solution linear
//!   in time plus the damped free vibration that matches the state at the
//!   interval's start. Under a harmonic ground acceleration from rest it is
//!   the steady state plus the transient, in closed form. No time stepping
//!   with truncation error: the only errors are rounding.
//! - Before a record's first sample and after its last the ground is at rest
//!   (as in [`Series`]); the oscillator then starts from rest, or rings down.
//! - Finite in, finite out: no NaN for finite inputs (ω > 0, 0 ≤ ζ < 1 are
//!   the caller's to check: [`Oscillator::new`] refuses the rest).

use super::excitation::record::Series;

/// An oscillator of circular frequency ω and damping ratio ζ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillator {
    /// ω, rad per time unit, > 0.
    omega: f64,
    /// ζ, fraction of critical, in [0, 1).
    zeta: f64,
}

/// The response of an oscillator at one instant: relative displacement,
/// velocity and acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response {
    /// Relative displacement u.
    pub u: f64,
    /// Relative velocity u̇.
    pub u_dot: f64,
    /// Relative acceleration ü (the absolute acceleration is a + ü).
    pub u_ddot: f64,
}

/// A free damped vibration e^{−σs}(x cos ω_d s + …) that starts from
/// displacement `x0` and velocity `y0` at s = 0: the homogeneous part of
/// the response inside one interval.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Free {
    x0: f64,
    y0: f64,
}

impl Oscillator {
    /// The oscillator of period `period` (time units, > 0 and finite) and
    /// damping ratio `zeta` (in [0, 1)); `None` otherwise (ζ ≥ 1 has no
    /// damped frequency, the closed forms here being those of the
    /// underdamped oscillator, which every building is).
    pub fn new(period: f64, zeta: f64) -> Option<Self> {
        let omega = std::f64::consts::TAU / period;
        (period > 0.0 && omega.is_finite() && omega > 0.0 && (0.0..1.0).contains(&zeta)).then_some(Self { omega, zeta })
    }

    /// ω, rad per time unit.
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// ζ.
    pub fn zeta(&self) -> f64 {
        self.zeta
    }

    /// The same oscillator in a time unit `new_units_per_old` times finer
    /// (τ = p t: an oscillator in s becomes one in τ with p, ω_τ = ω_s / p).
    pub(crate) fn rescaled(&self, new_units_per_old: f64) -> Self {
        Self {
            omega: self.omega / new_units_per_old,
            zeta: self.zeta,
        }
    }

    /// σ = ζω, the decay rate.
    fn sigma(&self) -> f64 {
        self.zeta * self.omega
    }

    /// ω_d = ω √(1 − ζ²), the damped frequency.
    fn omega_d(&self) -> f64 {
        self.omega * (1.0 - self.zeta * self.zeta).sqrt()
    }

    /// The linear particular solution α + βs under a ground acceleration
    /// a0 + k s: β = −k/ω², α = −(a0 + 2ζωβ)/ω² (it has ü = 0).
    fn particular(&self, a0: f64, k: f64) -> (f64, f64) {
        let w2 = self.omega * self.omega;
        let beta = -k / w2;
        let alpha = -(a0 + 2.0 * self.sigma() * beta) / w2;
        (alpha, beta)
    }

    /// Displacement, velocity and acceleration of a free vibration at s.
    fn free_at(&self, f: Free, s: f64) -> Response {
        let (sigma, wd) = (self.sigma(), self.omega_d());
        let e = (-sigma * s).exp();
        let (sn, cs) = (wd * s).sin_cos();
        let u = e * (f.x0 * cs + (f.y0 + sigma * f.x0) / wd * sn);
        let u_dot = e * (f.y0 * cs - (self.omega * self.omega * f.x0 + sigma * f.y0) / wd * sn);
        Response {
            u,
            u_dot,
            u_ddot: -2.0 * sigma * u_dot - self.omega * self.omega * u,
        }
    }

    /// The response a time `s` ≥ 0 into an interval that starts in state
    /// (`u0`, `u_dot0`) under the ground acceleration `a0 + k s`: exact.
    pub(crate) fn linear_at(&self, u0: f64, u_dot0: f64, a0: f64, k: f64, s: f64) -> Response {
        let (alpha, beta) = self.particular(a0, k);
        let h = self.free_at(
            Free {
                x0: u0 - alpha,
                y0: u_dot0 - beta,
            },
            s,
        );
        Response {
            u: h.u + alpha + beta * s,
            u_dot: h.u_dot + beta,
            u_ddot: h.u_ddot,
        }
    }

    /// The response to the harmonic ground acceleration
    /// `a(t) = amplitude · sin(Ω t + phase)` from rest at t = 0: the steady
    /// state (the ground's sinusoid times the transfer function
    /// −1/(ω² − Ω² + 2iζωΩ)) plus the free vibration that cancels it at
    /// t = 0. Exact; evaluate it with [`HarmonicResponse::at`].
    pub fn harmonic(&self, amplitude: f64, big_omega: f64, phase: f64) -> HarmonicResponse {
        let at0 = self.steady_state(amplitude, big_omega, phase, 0.0);
        HarmonicResponse {
            osc: *self,
            amplitude,
            big_omega,
            phase,
            transient: Free {
                x0: -at0.u,
                y0: -at0.u_dot,
            },
        }
    }

    /// The steady state under `amplitude · sin(Ω t + phase)`: u = Im[U
    /// e^{i(Ωt+φ)}] with U = −amplitude / (ω² − Ω² + 2iζωΩ).
    fn steady_state(&self, amplitude: f64, big_omega: f64, phase: f64, t: f64) -> Response {
        let (dr, di) = (
            self.omega * self.omega - big_omega * big_omega,
            2.0 * self.sigma() * big_omega,
        );
        let d2 = dr * dr + di * di;
        // U = −A (dr − i di)/|D|².
        let (ur, ui) = (-amplitude * dr / d2, amplitude * di / d2);
        let (sn, cs) = (big_omega * t + phase).sin_cos();
        // Im[(ur + i ui)(cs + i sn)] = ur sn + ui cs.
        let im = |r: f64, i: f64| r * sn + i * cs;
        Response {
            u: im(ur, ui),
            u_dot: im(-big_omega * ui, big_omega * ur),
            u_ddot: im(-big_omega * big_omega * ur, -big_omega * big_omega * ui),
        }
    }

    /// The steady-state amplitude of the absolute acceleration a + ü per
    /// unit ground amplitude at forcing frequency Ω (the transmissibility
    /// √(ω⁴ + (2ζωΩ)²) / √((ω² − Ω²)² + (2ζωΩ)²)).
    pub fn transmissibility(&self, big_omega: f64) -> f64 {
        let w2 = self.omega * self.omega;
        let c = 2.0 * self.sigma() * big_omega;
        ((w2 * w2 + c * c) / ((w2 - big_omega * big_omega).powi(2) + c * c)).sqrt()
    }

    /// √(c² + d²) for the acceleration of a free vibration written as
    /// e^{−σs}(c cos ω_d s + d sin ω_d s): c = ü(0), d = (ü'(0) + σ ü(0))/ω_d.
    fn free_accel_amplitude(&self, f: Free) -> f64 {
        let (sigma, wd, w2) = (self.sigma(), self.omega_d(), self.omega * self.omega);
        let a0 = -2.0 * sigma * f.y0 - w2 * f.x0;
        // ü' = −2σ ü − ω² u̇ at s = 0.
        let j0 = -2.0 * sigma * a0 - w2 * f.y0;
        let d = (j0 + sigma * a0) / wd;
        a0.hypot(d)
    }
}

/// The response of an oscillator to a harmonic ground acceleration from
/// rest at t = 0 ([`Oscillator::harmonic`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HarmonicResponse {
    osc: Oscillator,
    amplitude: f64,
    big_omega: f64,
    phase: f64,
    /// The free vibration that starts at t = 0 with minus the steady
    /// state's displacement and velocity.
    transient: Free,
}

impl HarmonicResponse {
    /// The response at `t` ≥ 0; at rest (all zero) for t < 0.
    pub fn at(&self, t: f64) -> Response {
        if t < 0.0 {
            return Response {
                u: 0.0,
                u_dot: 0.0,
                u_ddot: 0.0,
            };
        }
        let ss = self.osc.steady_state(self.amplitude, self.big_omega, self.phase, t);
        let tr = self.osc.free_at(self.transient, t);
        Response {
            u: ss.u + tr.u,
            u_dot: ss.u_dot + tr.u_dot,
            u_ddot: ss.u_ddot + tr.u_ddot,
        }
    }

    /// The oscillator.
    pub fn oscillator(&self) -> Oscillator {
        self.osc
    }

    /// The steady-state relative acceleration ü as a complex amplitude
    /// (re, im) per unit ground amplitude: ü_ss = Im[Ü e^{i(Ωt+φ)}] with
    /// Ü = Ω²/(ω² − Ω² + 2iζωΩ).
    pub(crate) fn steady_accel_ratio(&self) -> (f64, f64) {
        let w2 = self.osc.omega * self.osc.omega;
        let o2 = self.big_omega * self.big_omega;
        let (dr, di) = (w2 - o2, 2.0 * self.osc.sigma() * self.big_omega);
        let d2 = dr * dr + di * di;
        (o2 * dr / d2, -o2 * di / d2)
    }

    /// A bound on the transient's |ü| for every t ≥ 0: the amplitude
    /// √(c² + d²) of e^{−σt}(c cos ω_d t + d sin ω_d t), with e^{−σt} ≤ 1.
    pub(crate) fn transient_accel_bound(&self) -> f64 {
        self.osc.free_accel_amplitude(self.transient)
    }
}

/// The exact response of one oscillator to a piecewise-linear ground
/// acceleration ([`Series`], times in s and accelerations in g, times a
/// scale factor), with its state at every sample.
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseResponse {
    osc: Oscillator,
    /// Sample times, s.
    times: Vec<f64>,
    /// Ground acceleration at the samples, scaled.
    accel: Vec<f64>,
    /// u at each sample.
    u: Vec<f64>,
    /// u̇ at each sample.
    u_dot: Vec<f64>,
}

impl PiecewiseResponse {
    /// The response of `osc` (ω in rad/s) to `scale` times `series`, from
    /// rest before the first sample (where the ground may jump to its first
    /// value; u and u̇ do not jump).
    pub fn new(osc: Oscillator, series: &Series, scale: f64) -> Self {
        let times = series.times_s().to_vec();
        let accel: Vec<f64> = series.accel_g().iter().map(|a| a * scale).collect();
        let mut u = Vec::with_capacity(times.len());
        let mut u_dot = Vec::with_capacity(times.len());
        let (mut x, mut v) = (0.0, 0.0);
        u.push(x);
        u_dot.push(v);
        for (t, a) in times.windows(2).zip(accel.windows(2)) {
            let h = t[1] - t[0];
            let r = osc.linear_at(x, v, a[0], (a[1] - a[0]) / h, h);
            (x, v) = (r.u, r.u_dot);
            u.push(x);
            u_dot.push(v);
        }
        Self {
            osc,
            times,
            accel,
            u,
            u_dot,
        }
    }

    /// The oscillator.
    pub fn oscillator(&self) -> Oscillator {
        self.osc
    }

    /// Sample times, s.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// u at each sample.
    pub fn u(&self) -> &[f64] {
        &self.u
    }

    /// u̇ at each sample.
    pub(crate) fn u_dot(&self) -> &[f64] {
        &self.u_dot
    }

    /// The interval holding `t`: `Some(i)` for t in [t_i, t_{i+1}), and for
    /// the last sample itself the interval that ends there (where the
    /// ground still has its last value, as [`Series::accel_at`] says); the
    /// last index after the last sample; `None` before the first.
    pub fn interval(&self, t: f64) -> Option<usize> {
        let i = self.times.partition_point(|&ti| ti <= t);
        if i == self.times.len() && self.times.last() == Some(&t) {
            return i.checked_sub(2);
        }
        i.checked_sub(1)
    }

    /// The ground acceleration a0 at the start of interval `i` and its
    /// slope k over it (0 after the last sample, where the ground is at rest
    /// and a0 = 0).
    fn ground(&self, i: usize) -> (f64, f64) {
        match (self.times.get(i..i + 2), self.accel.get(i..i + 2)) {
            (Some(t), Some(a)) => (a[0], (a[1] - a[0]) / (t[1] - t[0])),
            _ => (0.0, 0.0),
        }
    }

    /// The response at `t` (s) in interval `i` (see
    /// [`PiecewiseResponse::interval`]), in closed form; at rest before
    /// the first sample.
    pub(crate) fn at_in(&self, i: Option<usize>, t: f64) -> Response {
        let Some(i) = i else {
            return Response {
                u: 0.0,
                u_dot: 0.0,
                u_ddot: 0.0,
            };
        };
        let (a0, k) = self.ground(i);
        let (u0, v0, t0) = (
            self.u.get(i).copied().unwrap_or(0.0),
            self.u_dot.get(i).copied().unwrap_or(0.0),
            self.times.get(i).copied().unwrap_or(0.0),
        );
        self.osc.linear_at(u0, v0, a0, k, t - t0)
    }

    /// The response at `t` (s).
    pub fn at(&self, t: f64) -> Response {
        self.at_in(self.interval(t), t)
    }

    /// The largest |u| over continuous time up to the last sample: at the
    /// samples and at every zero of u̇ inside an interval. Inside an
    /// interval u̇ = β + e^{−σs} R cos(ω_d s − φ), whose derivative ü is a
    /// damped sinusoid with zeros π/ω_d apart in closed form; between two of
    /// them u̇ is monotone and has at most one zero, found by bisection to
    /// rounding (the error in u is then of second order).
    pub(crate) fn max_abs_u(&self) -> f64 {
        let mut peak = self.u.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
        let wd = self.osc.omega_d();
        for i in 0..self.times.len().saturating_sub(1) {
            let (Some(&t0), Some(&t1)) = (self.times.get(i), self.times.get(i + 1)) else {
                continue;
            };
            let h = t1 - t0;
            let at = |s: f64| self.at_in(Some(i), t0 + s);
            // Zeros of ü inside (0, h): ü = e^{−σs}(c cos ω_d s + d sin ω_d s)
            // vanishes where ω_d s = atan2(c, −d) + nπ.
            let start = at(0.0);
            let (a0, k) = self.ground(i);
            let beta = self.osc.particular(a0, k).1;
            let (sigma, w2) = (self.osc.sigma(), self.osc.omega * self.osc.omega);
            // ü = e^{−σs}(c cos ω_d s + d sin ω_d s) with c = ü(0) and
            // d = (ü'(0) + σc)/ω_d, ü' = −2σü − ω²(u̇ − β) (the free part's).
            let c = start.u_ddot;
            let d = (-2.0 * sigma * c - w2 * (start.u_dot - beta) + sigma * c) / wd;
            // c cos x + d sin x = R cos(x − φ), φ = atan2(d, c): zero at
            // x = φ + π/2 + nπ.
            let phi0 = d.atan2(c) + std::f64::consts::FRAC_PI_2;
            let mut cuts = vec![0.0];
            let mut x = phi0.rem_euclid(std::f64::consts::PI);
            while x / wd < h {
                if x > 0.0 {
                    cuts.push(x / wd);
                }
                x += std::f64::consts::PI;
            }
            cuts.push(h);
            for w in cuts.windows(2) {
                let (mut lo, mut hi) = (w[0], w[1]);
                let (vlo, vhi) = (at(lo).u_dot, at(hi).u_dot);
                if vlo == 0.0 || vhi == 0.0 || (vlo < 0.0) == (vhi < 0.0) {
                    continue;
                }
                let lo_neg = vlo < 0.0;
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if (at(mid).u_dot < 0.0) == lo_neg {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                peak = peak.max(at(lo).u.abs()).max(at(hi).u.abs());
            }
        }
        peak
    }
}

/// Sa(T, ζ): the pseudo-spectral acceleration ω² max|u| of `scale` times
/// the record `series` (g), for an oscillator of period `period_s` (s) and
/// damping ratio `zeta`, with the maximum taken over continuous time up to
/// the record's last sample (the record is linear between samples, and the
/// response to it exact). In g. `None` for a period or damping
/// [`Oscillator::new`] refuses.
pub fn pseudo_acceleration(series: &Series, scale: f64, period_s: f64, zeta: f64) -> Option<f64> {
    let osc = Oscillator::new(period_s, zeta)?;
    let r = PiecewiseResponse::new(osc, series, scale);
    Some(osc.omega * osc.omega * r.max_abs_u())
}

/// The largest |f(s)| over [0, h] for a smooth f whose second derivative is
/// bounded on [s0, s1] by `m2(s0, s1)`, to a relative `rel` of the answer:
/// branch and bound on the linear-interpolation error bound
/// |f − interpolant| ≤ M₂ w²/8, starting from the known lower bound `best`.
/// Pieces whose bound cannot beat the best found are dropped; the rest are
/// halved (at most 2⁶⁰ times).
pub(crate) fn max_abs_smooth(f: impl Fn(f64) -> f64, m2: impl Fn(f64, f64) -> f64, h: f64, best: f64, rel: f64) -> f64 {
    let mut best = best.max(f(0.0).abs()).max(f(h).abs());
    let mut stack = vec![(0.0, h, f(0.0).abs(), f(h).abs(), 0_u32)];
    while let Some((s0, s1, f0, f1, depth)) = stack.pop() {
        let w = s1 - s0;
        let bound = f0.max(f1) + m2(s0, s1) * w * w / 8.0;
        if bound <= best * (1.0 + rel) || depth >= 60 {
            continue;
        }
        let mid = 0.5 * (s0 + s1);
        if mid <= s0 || mid >= s1 {
            continue;
        }
        let fm = f(mid).abs();
        best = best.max(fm);
        stack.push((s0, mid, f0, fm, depth + 1));
        stack.push((mid, s1, fm, f1, depth + 1));
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_vibration_satisfies_its_equation_and_its_start() {
        // Checked against the equation itself by central differences.
        let osc = Oscillator::new(0.7, 0.05).unwrap();
        let at = |s: f64| osc.linear_at(0.3, -1.1, 0.4, 2.0, s);
        let r0 = at(0.0);
        assert!((r0.u - 0.3).abs() < 1e-15 && (r0.u_dot + 1.1).abs() < 1e-14);
        for &s in &[0.01, 0.13, 0.5] {
            let e = 1e-5;
            let fd = (at(s + e).u_dot - at(s - e).u_dot) / (2.0 * e);
            let r = at(s);
            assert!((fd - r.u_ddot).abs() < 1e-6, "{fd} {}", r.u_ddot);
            let w = osc.omega();
            let resid = r.u_ddot + 2.0 * 0.05 * w * r.u_dot + w * w * r.u + 0.4 + 2.0 * s;
            assert!(resid.abs() < 1e-10, "{resid}");
        }
    }

    #[test]
    fn refuses_periods_and_dampings_without_a_damped_oscillation() {
        assert!(Oscillator::new(0.0, 0.05).is_none());
        assert!(Oscillator::new(-1.0, 0.05).is_none());
        assert!(Oscillator::new(1.0, 1.0).is_none());
        assert!(Oscillator::new(1.0, -0.1).is_none());
        assert!(Oscillator::new(f64::NAN, 0.05).is_none());
        assert!(Oscillator::new(1.0, 0.0).is_some());
    }
}
