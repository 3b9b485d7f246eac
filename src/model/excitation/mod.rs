//! Base excitations: harmonic (2-D, separate frequencies and phases),
//! analytic pulses, and recorded ground motion.
//!
//! Contract: [`Excitation::forcing`] returns the base acceleration at
//! normalised time τ per unit g, `(a_h/g, a_v/g)`, finite for every finite τ.
//! Kinks of the input (a pulse's ends, a record's samples) are reported by
//! [`Excitation::next_breakpoint`] so the integrator steps onto them instead
//! of across them.

pub mod floor;
pub mod pulse;
pub mod record;

use super::dynamics::Forcing;
pub use floor::{FloorExcitation, FloorMode, FloorPeaks};
pub use pulse::{Pulse, PulseShape};
pub use record::{RecordExcitation, Series};

/// 2-D harmonic excitation (MODEL-DECISIONS; paper eqs. 34–35 with τ):
/// `a_h/g = A_h ψ sin(Ω_h τ + Φ_h)`, `a_v/g = A_v ψ sin(Ω_v τ + Φ_v)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Harmonic {
    /// A_h: horizontal amplitude in units of ψ g (1 = the static uplift
    /// level of a slender block).
    pub a_h: f64,
    /// A_v: vertical amplitude in units of ψ g.
    pub a_v: f64,
    /// Ω_h: horizontal angular frequency in units of p.
    pub omega_h: f64,
    /// Ω_v: vertical angular frequency in units of p.
    pub omega_v: f64,
    /// Φ_h: horizontal phase, rad.
    pub phase_h: f64,
    /// Φ_v: vertical phase, rad.
    pub phase_v: f64,
    /// ψ, rad: the amplitudes are in units of ψ g.
    pub psi: f64,
}

impl Harmonic {
    /// `(a_h/g, a_v/g)` at τ.
    #[inline]
    pub fn accel(&self, tau: f64) -> (f64, f64) {
        let sh = (self.omega_h * tau + self.phase_h).sin();
        // The paper's Ω_v = Ω_h, Φ_v = Φ_h shares one sine (the same value
        // bit for bit), and no vertical excitation needs none: sines are a
        // third of a step's cost.
        let sv = if self.a_v == 0.0 {
            0.0
        } else if self.omega_v == self.omega_h && self.phase_v == self.phase_h {
            sh
        } else {
            (self.omega_v * tau + self.phase_v).sin()
        };
        (self.a_h * self.psi * sh, self.a_v * self.psi * sv)
    }
}

/// A horizontal and an optional vertical pulse of the same shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PulsePair {
    /// Horizontal pulse (amplitude in g).
    pub horizontal: Pulse,
    /// Vertical pulse (amplitude in g), if any.
    pub vertical: Option<Pulse>,
}

/// The base motion.
#[derive(Clone, Debug, PartialEq)]
pub enum Excitation {
    /// The base does not move (free rocking).
    None,
    /// 2-D harmonic.
    Harmonic(Harmonic),
    /// Analytic pulse(s).
    Pulse(PulsePair),
    /// Recorded ground motion.
    Record(Box<RecordExcitation>),
    /// A record or harmonic ground motion filtered through a building to
    /// the floor the block stands on (horizontal only).
    Floor(Box<FloorExcitation>),
}

impl Excitation {
    /// Base acceleration per unit g at τ.
    #[inline]
    pub fn forcing(&self, tau: f64) -> Forcing {
        let (a, av) = match self {
            Excitation::None => (0.0, 0.0),
            Excitation::Harmonic(h) => h.accel(tau),
            Excitation::Pulse(p) => (p.horizontal.accel(tau), p.vertical.map_or(0.0, |v| v.accel(tau))),
            Excitation::Record(r) => r.accel(tau),
            Excitation::Floor(f) => f.accel(tau),
        };
        Forcing { a, av }
    }

    /// The first τ' > τ at which the acceleration has a kink or jump.
    pub fn next_breakpoint(&self, tau: f64) -> Option<f64> {
        match self {
            Excitation::None | Excitation::Harmonic(_) => None,
            Excitation::Pulse(p) => {
                let mut best: Option<f64> = None;
                let v = p.vertical.map(|v| v.breakpoints());
                for tb in p.horizontal.breakpoints().into_iter().chain(v.into_iter().flatten()) {
                    if tb > tau && best.is_none_or(|b| tb < b) {
                        best = Some(tb);
                    }
                }
                best
            }
            Excitation::Record(r) => r.next_breakpoint(tau),
            Excitation::Floor(f) => f.next_breakpoint(tau),
        }
    }

    /// Shortest time scale of the forcing, τ: 1/Ω for the fastest harmonic
    /// component with a non-zero amplitude, 1/ω for a pulse; infinite for
    /// none. The event driver caps its steps at this while the block is at
    /// rest, so that guards that depend on the forcing alone (uplift and
    /// slip from rest) are sampled several times per radian of forcing
    /// phase, and screens steps cheaply only when they are no longer than
    /// this. A record is linear between its samples, and steps stop at every
    /// sample, so it needs neither; a floor oscillates inside a sample
    /// interval, so its time scale is 1/ω of its fastest mode (in τ).
    pub(crate) fn time_scale(&self) -> f64 {
        let inv = |omega: f64| if omega > 0.0 { 1.0 / omega } else { f64::INFINITY };
        match self {
            Excitation::None | Excitation::Record(_) => f64::INFINITY,
            Excitation::Harmonic(h) => {
                let th = if h.a_h != 0.0 { inv(h.omega_h) } else { f64::INFINITY };
                let tv = if h.a_v != 0.0 { inv(h.omega_v) } else { f64::INFINITY };
                th.min(tv)
            }
            Excitation::Pulse(p) => inv(p.horizontal.omega()),
            Excitation::Floor(f) => f.time_scale(),
        }
    }

    /// The largest |a_h/g| and |a_v/g| the excitation ever reaches, where
    /// that is known in closed form (none, harmonic, and a floor under
    /// harmonic ground motion, where it is a bound); `None` otherwise.
    /// Used to bound contact forces over a step.
    pub fn peak_accel(&self) -> Option<(f64, f64)> {
        match self {
            Excitation::None => Some((0.0, 0.0)),
            Excitation::Harmonic(h) => Some(((h.a_h * h.psi).abs(), (h.a_v * h.psi).abs())),
            Excitation::Pulse(_) | Excitation::Record(_) => None,
            Excitation::Floor(f) => f.peak_accel(),
        }
    }

    /// Period of the stroboscopic section, 2π/Ω_h, for harmonic excitation.
    pub fn forcing_period(&self) -> Option<f64> {
        match self {
            Excitation::Harmonic(h) if h.omega_h > 0.0 => Some(std::f64::consts::TAU / h.omega_h),
            Excitation::Floor(f) => f.forcing_period(),
            Excitation::None | Excitation::Harmonic(_) | Excitation::Pulse(_) | Excitation::Record(_) => None,
        }
    }
}
