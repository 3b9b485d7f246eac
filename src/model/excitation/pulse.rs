//! Analytic acceleration pulses used in rocking research to idealise
//! near-fault ground motion (Makris & Roussos 2000; Zhang & Makris 2001),
//! and the rectangular and half-sine pulses of the classical overturning
//! studies (Housner 1963; Shenton 1996).
//!
//! Contract:
//! - Units: time is the model's normalised time τ = p·t (p = sqrt(3 g / (4 R))
//!   in 1/s); the pulse frequency ω is given in units of p (radians per unit
//!   τ), so the period is T = 2π/ω in τ. Accelerations are fractions of g
//!   (a/g) and may be negative.
//! - The pulse starts at τ = 0 and lasts [`Pulse::duration`]; outside
//!   `[0, duration]` the acceleration is exactly 0 (ground at rest). The two
//!   ends are the only non-smooth points (kinks or jumps), listed by
//!   [`Pulse::breakpoints`] so that the integrator can stop on them.
//! - Errors: invalid parameters are rejected by [`Pulse::new`] with a
//!   [`PulseError`]; evaluation never fails or panics.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Largest number of main cycles `n` of a type-C pulse.
///
/// Near-fault records show at most a handful of main cycles; 20 is far beyond
/// that while keeping the phase root well separated from 0.
pub(crate) const MAX_TYPE_C_CYCLES: u32 = 20;

/// Shape of an analytic pulse, with ω the pulse frequency and T = 2π/ω its
/// period (both per unit τ).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PulseShape {
    /// Makris type-A pulse: one-sine acceleration a_p·sin(ωτ) for
    /// 0 <= τ <= T. Its ground velocity (a_p/ω)(1 − cos ωτ) is a one-sided
    /// forward pulse that returns to zero; the ground ends displaced by
    /// 2π a_p/ω².
    OneSine,
    /// Makris type-B pulse: one-cosine acceleration a_p·cos(ωτ) for
    /// 0 <= τ <= T. Its ground velocity (a_p/ω) sin ωτ is a forward-and-back
    /// pulse; both the final velocity and the final displacement are zero.
    OneCosine,
    /// Makris type-C_n pulse: a_p·cos(ωτ + φ) for
    /// 0 <= τ <= (n + 1/2 − φ/π)·T, with n main cycles. The phase
    /// φ ∈ (0, π/2) solves 2 cos φ = sin φ·((2n+1)π − 2φ), which makes the
    /// final ground velocity and displacement both zero (φ ≈ 0.0697π for
    /// n = 1, ≈ 0.0410π for n = 2). `n` must be in 1..=[`MAX_TYPE_C_CYCLES`].
    TypeC {
        /// Number of main cycles, 1..=[`MAX_TYPE_C_CYCLES`].
        n: u32,
    },
    /// Rectangular pulse: a constant a_p for 0 <= τ <= t_p with
    /// t_p = π/ω = T/2, the half-period convention of the half-sine below,
    /// so that a rectangular and a half-sine pulse of the same ω last
    /// equally long (ω is the frequency of the half-sine that fits the
    /// pulse, not a frequency of the rectangle itself). Housner's (1963)
    /// overturning study uses this shape. The ground ends moving at
    /// a_p t_p and displaced by a_p t_p²/2. Jumps at both ends.
    Rectangular,
    /// Half-sine pulse: a_p·sin(ωτ) for 0 <= τ <= π/ω = T/2, the usual
    /// idealisation of an impact or a single acceleration lobe. The ground
    /// ends moving at 2 a_p/ω and displaced by π a_p/ω². Kinks at both
    /// ends.
    HalfSine,
}

/// Why [`Pulse::new`] rejected its parameters.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum PulseError {
    /// ω is not a finite positive number, or so small that the pulse would
    /// never end.
    #[error("pulse frequency omega = {omega} (units of p) must be finite, > 0 and give a finite duration")]
    BadOmega {
        /// The frequency given, per unit τ.
        omega: f64,
    },
    /// The amplitude is NaN or infinite.
    #[error("pulse amplitude {amplitude} g must be finite")]
    BadAmplitude {
        /// The amplitude given, g.
        amplitude: f64,
    },
    /// A type-C pulse with a number of cycles outside 1..=20.
    #[error("type-C pulse needs 1 <= n <= {max} cycles, got {n}", max = MAX_TYPE_C_CYCLES)]
    BadCycles {
        /// The number of cycles given.
        n: u32,
    },
}

/// An analytic acceleration pulse in normalised time τ, starting at τ = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pulse {
    /// The pulse shape.
    shape: PulseShape,
    /// Peak acceleration a_p, g (negative flips the pulse).
    amplitude: f64,
    /// Pulse angular frequency ω, per unit τ (units of p).
    omega: f64,
    /// Phase φ, rad (0 for types A and B).
    phase: f64,
    /// Duration, τ.
    duration: f64,
}

impl Pulse {
    /// Builds a pulse of the given shape, peak acceleration `amplitude` (a_p,
    /// in g; may be negative) and angular frequency `omega` (ω, per unit τ,
    /// i.e. ω_p/p with ω_p in rad/s). For type C the phase φ is computed here,
    /// once, to within a few ulps.
    ///
    /// # Errors
    /// [`PulseError::BadOmega`] unless ω is finite, > 0 and gives a finite
    /// duration; [`PulseError::BadAmplitude`] unless a_p is finite;
    /// [`PulseError::BadCycles`] unless a type-C `n` is in
    /// 1..=[`MAX_TYPE_C_CYCLES`].
    pub fn new(shape: PulseShape, amplitude: f64, omega: f64) -> Result<Self, PulseError> {
        if !(omega.is_finite() && omega > 0.0) {
            return Err(PulseError::BadOmega { omega });
        }
        if !amplitude.is_finite() {
            return Err(PulseError::BadAmplitude { amplitude });
        }
        let period = 2.0 * PI / omega;
        let (phase, duration) = match shape {
            PulseShape::OneSine | PulseShape::OneCosine => (0.0, period),
            PulseShape::Rectangular | PulseShape::HalfSine => (0.0, 0.5 * period),
            PulseShape::TypeC { n } => {
                if !(1..=MAX_TYPE_C_CYCLES).contains(&n) {
                    return Err(PulseError::BadCycles { n });
                }
                let phase = type_c_phase(n);
                (phase, (f64::from(n) + 0.5 - phase / PI) * period)
            }
        };
        if !duration.is_finite() {
            return Err(PulseError::BadOmega { omega });
        }
        Ok(Self {
            shape,
            amplitude,
            omega,
            phase,
            duration,
        })
    }

    /// The pulse shape.
    pub fn shape(&self) -> PulseShape {
        self.shape
    }

    /// Peak acceleration a_p, g (may be negative).
    pub fn amplitude(&self) -> f64 {
        self.amplitude
    }

    /// Pulse angular frequency ω, per unit τ (units of p).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Pulse period T = 2π/ω, in τ.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }

    /// Phase φ in radians: the type-C root described in
    /// [`PulseShape::TypeC`], 0 for every other shape.
    pub fn phase(&self) -> f64 {
        self.phase
    }

    /// Duration of the pulse in τ: T for types A and B,
    /// (n + 1/2 − φ/π)·T for type C_n, T/2 = π/ω for the rectangular and
    /// half-sine pulses.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Ground acceleration at normalised time `tau`, in g: the pulse formula
    /// on the closed interval `[0, duration]`, 0 outside it (ground at rest),
    /// NaN for a NaN `tau` so that a bad time is caught downstream.
    pub fn accel(&self, tau: f64) -> f64 {
        if tau.is_nan() {
            return f64::NAN;
        }
        if !(0.0..=self.duration).contains(&tau) {
            return 0.0;
        }
        let arg = self.omega * tau;
        let shape = match self.shape {
            PulseShape::OneSine => arg.sin(),
            PulseShape::OneCosine => arg.cos(),
            PulseShape::TypeC { .. } => (arg + self.phase).cos(),
            PulseShape::Rectangular => 1.0,
            PulseShape::HalfSine => arg.sin(),
        };
        self.amplitude * shape
    }

    /// The non-smooth points of the acceleration, in τ: the start 0 and the
    /// end [`Pulse::duration`], where it has a kink (type A, half-sine) or a
    /// jump (types B and C, rectangular).
    pub(crate) fn breakpoints(&self) -> [f64; 2] {
        [0.0, self.duration]
    }
}

/// The type-C_n phase φ ∈ (0, π/2): the root of
/// f(φ) = 2 cos φ − sin φ·((2n+1)π − 2φ).
///
/// f(0) = 2 > 0, f(π/2) = −2nπ < 0 and f'(φ) = −cos φ·((2n+1)π − 2φ) < 0 on
/// (0, π/2), so the root is unique and bisection converges to it; it runs
/// until the bracket cannot shrink (adjacent floats), then returns the end
/// with the smaller residual.
fn type_c_phase(n: u32) -> f64 {
    let m = (2.0 * f64::from(n) + 1.0) * PI;
    let f = |phi: f64| 2.0 * phi.cos() - phi.sin() * (m - 2.0 * phi);
    let (mut lo, mut hi) = (0.0_f64, PI / 2.0);
    // 1100 halvings exhaust any f64 bracket; the loop breaks long before.
    for _ in 0..1100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if f(lo).abs() <= f(hi).abs() { lo } else { hi }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composite Simpson rule over [a, b] with `n` (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        assert!(n.is_multiple_of(2));
        let h = (b - a) / n as f64;
        let mut sum = f(a) + f(b);
        for k in 1..n {
            let weight = if k % 2 == 1 { 4.0 } else { 2.0 };
            sum += weight * f(a + k as f64 * h);
        }
        sum * h / 3.0
    }

    /// Final ground velocity and displacement (starting from rest) at the
    /// end of the pulse: v = ∫a, u = ∫(T_end − s) a(s) ds (Cauchy's formula
    /// for the double integral).
    fn final_velocity_displacement(pulse: &Pulse) -> (f64, f64) {
        let end = pulse.duration();
        let n = 200_000;
        let v = simpson(|s| pulse.accel(s), 0.0, end, n);
        let u = simpson(|s| (end - s) * pulse.accel(s), 0.0, end, n);
        (v, u)
    }

    fn shapes() -> Vec<PulseShape> {
        let mut shapes = vec![PulseShape::OneCosine];
        shapes.extend((1..=MAX_TYPE_C_CYCLES).map(|n| PulseShape::TypeC { n }));
        shapes
    }

    #[test]
    fn type_c_phase_values() {
        let phi1 = Pulse::new(PulseShape::TypeC { n: 1 }, 1.0, 1.0).unwrap().phase();
        let phi2 = Pulse::new(PulseShape::TypeC { n: 2 }, 1.0, 1.0).unwrap().phase();
        assert!((phi1 / PI - 0.0697).abs() < 5e-5, "{}", phi1 / PI);
        // The root of the defining equation for n = 2 is 0.04098π (Makris &
        // Roussos 2000 quote 0.0410π).
        assert!((phi2 / PI - 0.0410).abs() < 5e-5, "{}", phi2 / PI);
    }

    #[test]
    fn type_c_phase_solves_its_equation() {
        for n in 1..=MAX_TYPE_C_CYCLES {
            let phi = type_c_phase(n);
            assert!(phi > 0.0 && phi < PI / 2.0);
            let m = (2.0 * f64::from(n) + 1.0) * PI;
            let residual = 2.0 * phi.cos() - phi.sin() * (m - 2.0 * phi);
            let slope = phi.cos() * (m - 2.0 * phi);
            // Residual / slope bounds the distance to the exact root.
            assert!(residual.abs() / slope < 1e-15, "n = {n}: {residual:e}");
            // Newton from the returned value does not move it measurably.
            let newton = phi + residual / slope;
            assert!((newton - phi).abs() <= 4.0 * f64::EPSILON * phi, "n = {n}");
        }
        // The phase shrinks as the number of cycles grows.
        let phases: Vec<f64> = (1..=MAX_TYPE_C_CYCLES).map(type_c_phase).collect();
        assert!(phases.windows(2).all(|w| w[1] < w[0]));
    }

    #[test]
    fn type_b_and_c_end_at_rest_in_place() {
        for shape in shapes() {
            for &(amplitude, omega) in &[(0.5, 1.0), (-0.3, 2.5), (1.2, 7.0)] {
                let pulse = Pulse::new(shape, amplitude, omega).unwrap();
                let (v, u) = final_velocity_displacement(&pulse);
                assert!(v.abs() < 1e-8, "{shape:?} ω={omega}: v = {v:e}");
                assert!(u.abs() < 1e-8, "{shape:?} ω={omega}: u = {u:e}");
            }
        }
    }

    #[test]
    fn type_a_ends_at_rest_but_displaced() {
        for &(amplitude, omega) in &[(0.5, 1.0), (-0.3, 2.5), (1.2, 7.0)] {
            let pulse = Pulse::new(PulseShape::OneSine, amplitude, omega).unwrap();
            let (v, u) = final_velocity_displacement(&pulse);
            assert!(v.abs() < 1e-8, "ω={omega}: v = {v:e}");
            let expected = 2.0 * PI * amplitude / (omega * omega);
            assert!((u - expected).abs() < 1e-8, "ω={omega}: u = {u}");
            assert!(u.abs() > 0.01);
        }
    }

    #[test]
    fn zero_outside_the_pulse() {
        let more = [PulseShape::OneSine, PulseShape::Rectangular, PulseShape::HalfSine];
        for shape in more.into_iter().chain(shapes()) {
            let pulse = Pulse::new(shape, 0.7, 3.0).unwrap();
            let end = pulse.duration();
            for tau in [
                -1e9,
                -1.0,
                -1e-12,
                end + 1e-12,
                end * 1.5,
                1e12,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ] {
                assert_eq!(pulse.accel(tau), 0.0, "{shape:?} τ = {tau}");
            }
            assert!(pulse.accel(f64::NAN).is_nan());
        }
    }

    #[test]
    fn values_inside_and_at_the_ends() {
        let a = Pulse::new(PulseShape::OneSine, 0.4, 2.0).unwrap();
        assert_eq!(a.accel(0.0), 0.0);
        assert!((a.accel(PI / 4.0) - 0.4).abs() < 1e-15);
        assert!(a.accel(a.duration()).abs() < 1e-15);
        let b = Pulse::new(PulseShape::OneCosine, -0.4, 2.0).unwrap();
        assert_eq!(b.accel(0.0), -0.4);
        assert!((b.accel(b.duration()) + 0.4).abs() < 1e-15);
        let c = Pulse::new(PulseShape::TypeC { n: 1 }, 0.4, 2.0).unwrap();
        assert!((c.accel(0.0) - 0.4 * c.phase().cos()).abs() < 1e-15);
        // The end is symmetric: cos((2n+1)π − φ) = −cos φ.
        assert!((c.accel(c.duration()) + 0.4 * c.phase().cos()).abs() < 1e-14);
    }

    #[test]
    fn durations_periods_and_breakpoints() {
        let omega = 2.0;
        let period = PI;
        let a = Pulse::new(PulseShape::OneSine, 1.0, omega).unwrap();
        let b = Pulse::new(PulseShape::OneCosine, 1.0, omega).unwrap();
        assert_eq!(a.period(), period);
        assert_eq!(a.duration(), period);
        assert_eq!(b.duration(), period);
        assert_eq!(a.phase(), 0.0);
        assert_eq!(b.phase(), 0.0);
        assert_eq!(a.breakpoints(), [0.0, period]);
        for n in [1, 2, 5, 20] {
            let c = Pulse::new(PulseShape::TypeC { n }, 1.0, omega).unwrap();
            let expected = (f64::from(n) + 0.5 - c.phase() / PI) * period;
            assert!((c.duration() - expected).abs() < 1e-14);
            assert_eq!(c.breakpoints(), [0.0, c.duration()]);
            assert_eq!(c.shape(), PulseShape::TypeC { n });
        }
        assert_eq!(a.amplitude(), 1.0);
        assert_eq!(a.omega(), omega);
    }

    #[test]
    fn rectangular_and_half_sine_values_and_breakpoints() {
        for &(amplitude, omega) in &[(0.5, 1.0), (-0.3, 2.5), (1.2, 7.0)] {
            let half = PI / omega;
            let rect = Pulse::new(PulseShape::Rectangular, amplitude, omega).unwrap();
            let sine = Pulse::new(PulseShape::HalfSine, amplitude, omega).unwrap();
            for p in [&rect, &sine] {
                assert_eq!(p.duration(), half, "{:?}", p.shape());
                assert_eq!(p.period(), 2.0 * half);
                assert_eq!(p.phase(), 0.0);
                assert_eq!(p.breakpoints(), [0.0, half]);
                assert_eq!(p.accel(-1e-12), 0.0);
                assert_eq!(p.accel(half.next_up()), 0.0);
            }
            // The rectangle is a_p on the whole closed interval, ends
            // included (the integrator stops on both).
            for tau in [0.0, 0.3 * half, half] {
                assert_eq!(rect.accel(tau), amplitude);
            }
            assert_eq!(sine.accel(0.0), 0.0);
            assert!((sine.accel(0.5 * half) - amplitude).abs() < 1e-15);
            assert!((sine.accel(0.25 * half) - amplitude * (PI / 4.0).sin()).abs() < 1e-15);
            assert!(sine.accel(half).abs() < 1e-15);
        }
    }

    #[test]
    fn rectangular_and_half_sine_final_ground_motion() {
        for &(amplitude, omega) in &[(0.5, 1.0), (-0.3, 2.5), (1.2, 7.0)] {
            let t_p = PI / omega;
            let rect = Pulse::new(PulseShape::Rectangular, amplitude, omega).unwrap();
            let (v, u) = final_velocity_displacement(&rect);
            // Simpson is exact for the constant and the linear integrand;
            // what is left is the round-off of a 200 001-term sum
            // (~n ε |v| ≈ 1e-11).
            assert!((v - amplitude * t_p).abs() < 1e-10, "ω={omega}: v = {v}");
            assert!((u - 0.5 * amplitude * t_p * t_p).abs() < 1e-10, "ω={omega}: u = {u}");
            let sine = Pulse::new(PulseShape::HalfSine, amplitude, omega).unwrap();
            let (v, u) = final_velocity_displacement(&sine);
            assert!((v - 2.0 * amplitude / omega).abs() < 1e-8, "ω={omega}: v = {v}");
            assert!(
                (u - PI * amplitude / (omega * omega)).abs() < 1e-8,
                "ω={omega}: u = {u}"
            );
        }
    }

    #[test]
    fn new_rejects_bad_parameters() {
        use PulseShape::*;
        for omega in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-320] {
            assert!(matches!(
                Pulse::new(OneSine, 1.0, omega),
                Err(PulseError::BadOmega { .. })
            ));
        }
        for amplitude in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(matches!(
                Pulse::new(OneCosine, amplitude, 1.0),
                Err(PulseError::BadAmplitude { .. })
            ));
        }
        assert_eq!(
            Pulse::new(TypeC { n: 0 }, 1.0, 1.0),
            Err(PulseError::BadCycles { n: 0 })
        );
        assert_eq!(
            Pulse::new(TypeC { n: 21 }, 1.0, 1.0),
            Err(PulseError::BadCycles { n: 21 })
        );
        assert_eq!(
            PulseError::BadCycles { n: 21 }.to_string(),
            "type-C pulse needs 1 <= n <= 20 cycles, got 21"
        );
        assert!(Pulse::new(TypeC { n: 20 }, -2.0, 0.01).is_ok());
        assert!(Pulse::new(OneSine, 0.0, 1.0).is_ok());
    }
}
