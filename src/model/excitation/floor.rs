//! Floor motion: the block stands on a floor of a linear building, and
//! feels the ground motion filtered through the building's modes.
//!
//! Contract:
//! - The floor's absolute horizontal acceleration is
//!   a_f = a_g + Σ_k Γ_kφ_k ü_k (docs/model.md, "Floor motion"), ü_k the
//!   relative acceleration of mode k, a single-degree-of-freedom oscillator
//!   (period T_k, damping ζ_k) under the ground acceleration a_g, and
//!   Γ_kφ_k its participation at the floor. With one mode and Γφ = 1 this is
//!   the classic a_f = −2ζωu̇ − ω²u.
//! - Exact: under a record (linear between samples) each mode's response is
//!   the closed form of [`PiecewiseResponse`]; under harmonic ground motion
//!   the closed-form steady state plus transient from rest at τ = 0
//!   ([`HarmonicResponse`]). The building and the block start at rest
//!   together.
//! - The vertical component passes unfiltered: a building's vertical
//!   (axial) modes are an order of magnitude stiffer than its lateral ones
//!   (periods of a few hundredths of a second), so a floor moves vertically
//!   with the ground over the frequencies of ground shaking.
//! - Units: as the rest of the excitation, τ and g. Records are filtered in
//!   seconds (the record's time) and read at t = τ/p.
//! - Pulses are not filtered: the config refuses `[floor]` with a pulse.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::Harmonic;
use super::record::RecordExcitation;
use crate::model::oscillator::{HarmonicResponse, Oscillator, PiecewiseResponse, max_abs_smooth};

/// One building mode seen from the floor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorMode {
    /// The mode's oscillator: period in s (ω in rad/s).
    pub oscillator: Oscillator,
    /// Γφ, its participation at the floor (dimensionless).
    pub participation: f64,
}

/// What the floor filters.
#[derive(Clone, Debug, PartialEq)]
enum Ground {
    /// A record, each mode's response at every sample.
    Record {
        record: Box<RecordExcitation>,
        modes: Vec<(PiecewiseResponse, f64)>,
        fast: Box<FastRecord>,
    },
    /// Harmonic ground motion; each mode's closed form in τ.
    Harmonic {
        harmonic: Harmonic,
        modes: Vec<(HarmonicResponse, f64)>,
    },
}

/// The floor acceleration under a record, tabulated for evaluation: on
/// interval i, a_f(s) = a_g(s) + Σ_k e^{−σ_k s}(c_ki cos ω_dk s + d_ki sin
/// ω_dk s), the modes' free parts with Γφ folded in (their particular
/// parts have ü = 0). The same closed form as [`PiecewiseResponse::at_in`],
/// with the per-call divisions and the second search of the record done
/// once: the integrator evaluates the forcing at every stage of every step.
#[derive(Debug)]
struct FastRecord {
    /// Sample times, s.
    times: Vec<f64>,
    /// Scaled ground acceleration at the samples, g.
    accel: Vec<f64>,
    /// Per mode: σ, ω_d and the coefficients per interval.
    modes: Vec<ModeTable>,
    /// The number of samples at or before the last time asked for: the
    /// integrator asks at the stages of one step, then of the next, so the
    /// answer is this or the next one far more often than not, and checking
    /// them first saves the binary search (whose dependent loads are most of
    /// a record's forcing cost). Only a hint: every use checks it, so any
    /// value is safe, and relaxed ordering suffices when threads share it.
    hint: AtomicUsize,
}

/// One mode's free-vibration coefficients on every sample interval.
#[derive(Clone, Debug, PartialEq)]
struct ModeTable {
    /// σ = ζω, 1/s.
    sigma: f64,
    /// ω_d = ω√(1 − ζ²), rad/s.
    wd: f64,
    /// (Γφ c, Γφ d) per interval; the last entry is the ring-down after
    /// the last sample.
    coef: Vec<(f64, f64)>,
}

impl Clone for FastRecord {
    fn clone(&self) -> Self {
        Self {
            times: self.times.clone(),
            accel: self.accel.clone(),
            modes: self.modes.clone(),
            hint: AtomicUsize::new(self.hint.load(Ordering::Relaxed)),
        }
    }
}

impl PartialEq for FastRecord {
    /// The same tables; the search hint is no part of the value.
    fn eq(&self, other: &Self) -> bool {
        self.times == other.times && self.accel == other.accel && self.modes == other.modes
    }
}

impl FastRecord {
    /// The number of samples at or before `t` (`partition_point(t_i <= t)`),
    /// trying the hint and the sample after it before a binary search.
    #[inline]
    fn count_at_or_before(&self, t: f64) -> usize {
        let n = self.times.len();
        let fits = |c: usize| {
            (c == 0 || self.times.get(c - 1).is_some_and(|&ti| ti <= t))
                && (c == n || self.times.get(c).is_some_and(|&ti| ti > t))
        };
        let h = self.hint.load(Ordering::Relaxed);
        let c = if fits(h) {
            h
        } else if h < n && fits(h + 1) {
            h + 1
        } else {
            self.times.partition_point(|&ti| ti <= t)
        };
        self.hint.store(c, Ordering::Relaxed);
        c
    }

    fn new(responses: &[(PiecewiseResponse, f64)], record: &RecordExcitation) -> Self {
        let series = record.horizontal();
        let times = series.times_s().to_vec();
        let accel: Vec<f64> = series.accel_g().iter().map(|a| a * record.scale_h()).collect();
        let n = times.len();
        let modes = responses
            .iter()
            .map(|(r, gamma)| {
                let osc = r.oscillator();
                let (w, z) = (osc.omega(), osc.zeta());
                let (sigma, wd) = (z * w, w * (1.0 - z * z).sqrt());
                let coef = (0..n)
                    .map(|i| {
                        let (u, v) = (
                            r.u().get(i).copied().unwrap_or(0.0),
                            r.u_dot().get(i).copied().unwrap_or(0.0),
                        );
                        let k = match (times.get(i..i + 2), accel.get(i..i + 2)) {
                            (Some(t), Some(a)) => (a[1] - a[0]) / (t[1] - t[0]),
                            _ => 0.0,
                        };
                        let a0 = if i + 1 < n {
                            accel.get(i).copied().unwrap_or(0.0)
                        } else {
                            0.0
                        };
                        // The free part's start: u − α, u̇ − β (Oscillator::particular).
                        let beta = -k / (w * w);
                        let alpha = -(a0 + 2.0 * sigma * beta) / (w * w);
                        let (x0, y0) = (u - alpha, v - beta);
                        let c = -2.0 * sigma * y0 - w * w * x0;
                        let d = (-2.0 * sigma * c - w * w * y0 + sigma * c) / wd;
                        (gamma * c, gamma * d)
                    })
                    .collect();
                ModeTable { sigma, wd, coef }
            })
            .collect();
        Self {
            times,
            accel,
            modes,
            hint: AtomicUsize::new(0),
        }
    }

    /// a_f/g at `t` s: 0 before the first sample, the ground at rest and the
    /// building ringing down after the last.
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        let n = self.times.len();
        if t.is_nan() {
            return f64::NAN;
        }
        let mut i = self.count_at_or_before(t);
        if i == 0 {
            return 0.0;
        }
        // The last sample belongs to the interval that ends there
        // (PiecewiseResponse::interval).
        if i == n && self.times.last() == Some(&t) {
            i -= 1;
        }
        let i = i - 1;
        let (Some(&t0), Some(&a0)) = (self.times.get(i), self.accel.get(i)) else {
            return 0.0;
        };
        // The same interpolation as Series::accel_at.
        let a_g = match (self.times.get(i + 1), self.accel.get(i + 1)) {
            (Some(&t1), Some(&a1)) => a0 + (a1 - a0) * ((t - t0) / (t1 - t0)),
            _ => 0.0,
        };
        let s = t - t0;
        let mut rel = 0.0;
        for m in &self.modes {
            if let Some(&(c, d)) = m.coef.get(i) {
                let (sn, cs) = (m.wd * s).sin_cos();
                rel += (-m.sigma * s).exp() * (c * cs + d * sn);
            }
        }
        a_g + rel
    }
}

/// A ground motion filtered through a building to one of its floors.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorExcitation {
    ground: Ground,
    /// The modes, periods in s, as given.
    modes: Vec<FloorMode>,
    /// The block's frequency parameter p, 1/s (τ = p t).
    p: f64,
}

/// The peak absolute acceleration and velocity of the floor.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FloorPeaks {
    /// Peak floor acceleration, g.
    pub pga_g: f64,
    /// Peak floor velocity, m/s.
    pub pgv_m_s: f64,
}

/// Relative accuracy of the floor peaks (branch and bound in
/// [`max_abs_smooth`]): far below any digit an engineer quotes, far above
/// rounding.
const PEAK_REL: f64 = 1e-12;

impl FloorExcitation {
    /// The floor of a building with `modes` under a record.
    pub fn record(record: RecordExcitation, modes: Vec<FloorMode>) -> Self {
        let p = record.p_per_s();
        let responses: Vec<(PiecewiseResponse, f64)> = modes
            .iter()
            .map(|m| {
                (
                    PiecewiseResponse::new(m.oscillator, record.horizontal(), record.scale_h()),
                    m.participation,
                )
            })
            .collect();
        let fast = Box::new(FastRecord::new(&responses, &record));
        Self {
            ground: Ground::Record {
                record: Box::new(record),
                modes: responses,
                fast,
            },
            p,
            modes,
        }
    }

    /// The floor of a building with `modes` under harmonic ground motion
    /// (Ω_h in units of p, whose value `p_per_s`, 1/s, converts the modes'
    /// periods from s to τ).
    pub fn harmonic(harmonic: Harmonic, modes: Vec<FloorMode>, p_per_s: f64) -> Self {
        let responses = modes
            .iter()
            .map(|m| {
                let osc = m.oscillator.rescaled(p_per_s);
                (
                    osc.harmonic(harmonic.a_h * harmonic.psi, harmonic.omega_h, harmonic.phase_h),
                    m.participation,
                )
            })
            .collect();
        Self {
            ground: Ground::Harmonic {
                harmonic,
                modes: responses,
            },
            modes,
            p: p_per_s,
        }
    }

    /// The modes.
    pub fn modes(&self) -> &[FloorMode] {
        &self.modes
    }

    /// The record under the building, if it is one.
    pub fn record_ground(&self) -> Option<&RecordExcitation> {
        match &self.ground {
            Ground::Record { record, .. } => Some(record),
            Ground::Harmonic { .. } => None,
        }
    }

    /// `(a_f/g, a_v/g)` at τ: the floor's horizontal acceleration and the
    /// ground's vertical one.
    #[inline]
    pub fn accel(&self, tau: f64) -> (f64, f64) {
        match &self.ground {
            Ground::Record { record, fast, .. } => {
                let a_v = match record.vertical() {
                    Some(_) => record.accel(tau).1,
                    None => 0.0,
                };
                (fast.accel(tau / record.p_per_s()), a_v)
            }
            Ground::Harmonic { harmonic, modes } => {
                let (a_g, a_v) = harmonic.accel(tau);
                let rel: f64 = modes.iter().map(|(r, gamma)| gamma * r.at(tau).u_ddot).sum();
                (a_g + rel, a_v)
            }
        }
    }

    /// d(a_f/g)/dτ and d(a_v/g)/dτ for harmonic ground motion, in closed
    /// form (ü' = −ȧ_g − 2ζωü − ω²u̇ for each mode); `None` under a record.
    pub fn accel_rate(&self, tau: f64) -> Option<(f64, f64)> {
        match &self.ground {
            Ground::Record { .. } => None,
            Ground::Harmonic { harmonic: h, modes } => {
                let rate_g = h.a_h * h.psi * h.omega_h * (h.omega_h * tau + h.phase_h).cos();
                let rate_v = h.a_v * h.psi * h.omega_v * (h.omega_v * tau + h.phase_v).cos();
                let rel: f64 = modes
                    .iter()
                    .map(|(r, gamma)| {
                        if tau < 0.0 {
                            return 0.0;
                        }
                        let osc = r.oscillator();
                        let w = osc.omega();
                        let x = r.at(tau);
                        // ü + 2ζωu̇ + ω²u = −a_g, differentiated.
                        gamma * (-rate_g - 2.0 * osc.zeta() * w * x.u_ddot - w * w * x.u_dot)
                    })
                    .sum();
                Some((rate_g + rel, rate_v))
            }
        }
    }

    /// The first τ' > τ at which the floor acceleration has a kink: the
    /// record's samples (the floor's acceleration is smooth inside a sample
    /// interval, and its slope changes at every sample with the ground's);
    /// none for harmonic ground motion.
    pub fn next_breakpoint(&self, tau: f64) -> Option<f64> {
        match &self.ground {
            Ground::Record { record, .. } => record.next_breakpoint(tau),
            Ground::Harmonic { .. } => None,
        }
    }

    /// Shortest time scale, τ: 1/ω of the fastest mode, in τ, and the
    /// harmonic's own.
    pub(crate) fn time_scale(&self) -> f64 {
        let modes = self
            .modes
            .iter()
            .fold(f64::INFINITY, |m, mode| m.min(self.p / mode.oscillator.omega()));
        match &self.ground {
            Ground::Record { .. } => modes,
            Ground::Harmonic { harmonic, .. } => modes.min(super::Excitation::Harmonic(*harmonic).time_scale()),
        }
    }

    /// A bound on |a_f/g| and |a_v/g| for every τ, for harmonic ground
    /// motion: the steady-state amplitude |A_h ψ (1 + Σ Γ Ü_k)| plus each
    /// mode's transient bound; `None` under a record.
    pub fn peak_accel(&self) -> Option<(f64, f64)> {
        match &self.ground {
            Ground::Record { .. } => None,
            Ground::Harmonic { harmonic: h, modes } => {
                let (mut re, mut im) = (1.0, 0.0);
                let mut transient = 0.0;
                for (r, gamma) in modes {
                    let (ur, ui) = r.steady_accel_ratio();
                    re += gamma * ur;
                    im += gamma * ui;
                    transient += gamma.abs() * r.transient_accel_bound();
                }
                let amp = (h.a_h * h.psi).abs() * re.hypot(im);
                // Before τ = 0 the building is at rest and the floor moves
                // with the ground, whose amplitude is |A_h ψ|.
                Some((amp.max((h.a_h * h.psi).abs()) + transient, (h.a_v * h.psi).abs()))
            }
        }
    }

    /// The stroboscopic period, 2π/Ω_h, for harmonic ground motion (the
    /// transient decays; the steady state has the ground's period).
    pub fn forcing_period(&self) -> Option<f64> {
        match &self.ground {
            Ground::Record { .. } => None,
            Ground::Harmonic { harmonic, .. } => super::Excitation::Harmonic(*harmonic).forcing_period(),
        }
    }

    /// The τ after which the floor's |a_f| stays below `level_g` for ever,
    /// given that the ground is at rest from `end_tau` on: each mode then
    /// rings down as e^{−ζωt} times its acceleration amplitude at the
    /// record's end, and the sum stays below `level_g` once every mode's
    /// share is below `level_g` divided by the number of modes. `end_tau`
    /// for harmonic ground (which never stops) or a zero level.
    pub(crate) fn quiet_after(&self, end_tau: f64, level_g: f64) -> f64 {
        let Ground::Record { modes, .. } = &self.ground else {
            return end_tau;
        };
        if level_g <= 0.0 || modes.is_empty() {
            return end_tau;
        }
        let t_end = end_tau / self.p;
        let share = level_g / modes.len() as f64;
        let mut quiet_s = t_end;
        for (r, gamma) in modes {
            let osc = r.oscillator();
            let x = r.at(t_end);
            let (w, z) = (osc.omega(), osc.zeta());
            let (sigma, wd) = (z * w, w * (1.0 - z * z).sqrt());
            // Free vibration (ground at rest): ü(0) = c, ü'(0) = −2σc − ω²u̇.
            let c = x.u_ddot;
            let d = (-2.0 * sigma * c - w * w * x.u_dot + sigma * c) / wd;
            let amp = gamma.abs() * c.hypot(d);
            if amp > share {
                quiet_s = quiet_s.max(t_end + (amp / share).ln() / sigma);
            }
        }
        quiet_s * self.p
    }

    /// The floor's peak acceleration (g) and velocity (m/s) over
    /// continuous time, from τ = 0 to `tau_end`, the velocity integrated
    /// exactly from rest (v_f = v_g + Σ Γ u̇_k, v_g the exact integral of
    /// the piecewise-linear or harmonic ground). Found by branch and bound on
    /// each sample interval (or, for harmonic ground, on pieces of 1/8 of
    /// the fastest period up to τ_end or until the transients are below
    /// 1e-14 of the ground's amplitude and two forcing periods more, which
    /// then repeat for ever) with the closed-form bounds on the
    /// second derivative, to a relative 1e-12: exact in the engineer's sense,
    /// not a maximum over samples.
    pub fn peaks(&self, tau_end: f64) -> FloorPeaks {
        let g = crate::model::geometry::G;
        let p_per_s = self.p;
        match &self.ground {
            Ground::Record { record, modes, .. } => {
                let series = record.horizontal();
                let scale = record.scale_h();
                let (times, acc) = (series.times_s(), series.accel_g());
                let t_end = (tau_end / p_per_s).max(series.duration_s());
                let (mut pga, mut pgv) = (0.0_f64, 0.0_f64);
                // Bounds on |d^n ü_h/ds^n| over a piece starting s0 into the
                // interval that starts in state i: e^{−σ s0} R ω^n per mode.
                let mut v_g = 0.0; // ground velocity at the sample, g·s
                let n = times.len();
                for i in 0..n {
                    let Some(&t0) = times.get(i) else { continue };
                    let (h, a0, k) = match (times.get(i + 1), acc.get(i), acc.get(i + 1)) {
                        (Some(&t1), Some(&a0), Some(&a1)) => (t1 - t0, scale * a0, scale * (a1 - a0) / (t1 - t0)),
                        // After the last sample: the ground at rest (a jump
                        // to 0 there), the building ringing down to t_end.
                        _ => ((t_end - t0).max(0.0), 0.0, 0.0),
                    };
                    if h <= 0.0 {
                        continue;
                    }
                    let amps: Vec<(f64, f64, f64)> = modes
                        .iter()
                        .map(|(r, gamma)| {
                            let osc = r.oscillator();
                            let x = r.at_in(Some(i), t0);
                            // The free part's acceleration amplitude, from
                            // ü(0) and ü'(0) = −2σü − ω²(u̇ − β).
                            let w = osc.omega();
                            let sigma = osc.zeta() * w;
                            let beta = -k / (w * w);
                            let c = x.u_ddot;
                            let wd = w * (1.0 - osc.zeta() * osc.zeta()).sqrt();
                            let d = (-2.0 * sigma * c - w * w * (x.u_dot - beta) + sigma * c) / wd;
                            (gamma.abs() * c.hypot(d), sigma, w)
                        })
                        .collect();
                    let bound = |order: i32, s0: f64| -> f64 {
                        amps.iter()
                            .map(|(r, sigma, w)| r * (-sigma * s0).exp() * w.powi(order))
                            .sum()
                    };
                    let v0 = v_g;
                    let accel = |s: f64| {
                        let t = t0 + s;
                        a0 + k * s
                            + modes
                                .iter()
                                .map(|(r, gamma)| gamma * r.at_in(Some(i), t).u_ddot)
                                .sum::<f64>()
                    };
                    let velocity = |s: f64| {
                        let t = t0 + s;
                        v0 + a0 * s
                            + 0.5 * k * s * s
                            + modes
                                .iter()
                                .map(|(r, gamma)| gamma * r.at_in(Some(i), t).u_dot)
                                .sum::<f64>()
                    };
                    pga = max_abs_smooth(accel, |s0, _| bound(2, s0), h, pga, PEAK_REL);
                    pgv = max_abs_smooth(velocity, |s0, _| k.abs() + bound(1, s0), h, pgv, PEAK_REL);
                    v_g += a0 * h + 0.5 * k * h * h;
                }
                FloorPeaks {
                    pga_g: pga,
                    pgv_m_s: pgv * g,
                }
            }
            Ground::Harmonic { harmonic: hm, modes } => {
                // In τ: v in g/p, so m/s = v·g/p.
                let amp = hm.a_h * hm.psi;
                let (w, ph) = (hm.omega_h, hm.phase_h);
                let fastest = modes.iter().fold(w, |m, (r, _)| m.max(r.oscillator().omega()));
                // Once every transient is below 1e-14 of the ground's
                // amplitude the motion repeats with the ground's period, so
                // two more periods hold every later peak: a long run costs
                // no more than that.
                let settle = modes.iter().fold(0.0_f64, |m, (r, gamma)| {
                    let osc = r.oscillator();
                    let sigma = osc.zeta() * osc.omega();
                    let ratio = gamma.abs() * r.transient_accel_bound() / (1e-14 * amp.abs()).max(f64::MIN_POSITIVE);
                    if ratio > 1.0 && sigma > 0.0 {
                        m.max(ratio.ln() / sigma)
                    } else {
                        m
                    }
                });
                let horizon = if w > 0.0 {
                    tau_end.min(settle + 2.0 * std::f64::consts::TAU / w)
                } else {
                    tau_end
                };
                let piece = std::f64::consts::FRAC_PI_4 / fastest;
                let count = (horizon / piece).ceil().max(1.0);
                let piece = horizon / count;
                let accel =
                    |tau: f64| hm.accel(tau).0 + modes.iter().map(|(r, gamma)| gamma * r.at(tau).u_ddot).sum::<f64>();
                // v_g from rest at τ = 0: (A/Ω)(cos φ − cos(Ωτ + φ)).
                let velocity = |tau: f64| {
                    amp / w * (ph.cos() - (w * tau + ph).cos())
                        + modes.iter().map(|(r, gamma)| gamma * r.at(tau).u_dot).sum::<f64>()
                };
                let bound = |order: i32| -> f64 {
                    let mut b = amp.abs() * w.powi(order);
                    for (r, gamma) in modes {
                        let (ur, ui) = r.steady_accel_ratio();
                        let wm = r.oscillator().omega();
                        b += gamma.abs()
                            * (amp.abs() * ur.hypot(ui) * w.powi(order) + r.transient_accel_bound() * wm.powi(order));
                    }
                    b
                };
                let (b1, b2) = (bound(1), bound(2));
                let (mut pga, mut pgv) = (0.0_f64, 0.0_f64);
                let mut k = 0.0;
                while k < count {
                    let t0 = k * piece;
                    pga = max_abs_smooth(|s| accel(t0 + s), |_, _| b2, piece, pga, PEAK_REL);
                    pgv = max_abs_smooth(|s| velocity(t0 + s), |_, _| b1, piece, pgv, PEAK_REL);
                    k += 1.0;
                }
                FloorPeaks {
                    pga_g: pga,
                    pgv_m_s: pgv * g / p_per_s,
                }
            }
        }
    }
}
