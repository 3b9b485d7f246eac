//! The overturning map of a pulse (Makris & Roussos 2000; Zhang & Makris
//! 2001): for each ω_p/p, the smallest pulse amplitude a_p/(g tan α) that
//! overturns the block, and the safe windows above it.
//!
//! In these variables the response depends on the block only through its
//! slenderness α (and the impact law), not its size, so the map is drawn
//! for one B/H at a time. Amplitudes below 1 (a_p < g tan α) never lift a
//! block on a base shaken only horizontally, so the ladder of amplitudes
//! usually starts just above 1. The search is
//! [`overturn_scale::search`](super::overturn_scale::search); every
//! (shape, B/H, ω_p/p) runs in parallel and is collected by index.

use rayon::prelude::*;

use super::overturn_scale::{ScaleSearch, search};
use super::response::{BlockResponse, BlockSize, Drive, ResponseError, respond};
use crate::analysis::{Progress, ProgressFn};
use crate::sim::Scenario;
use crate::sim::scenario::ShapeKind;

/// Half-diagonal of the blocks the map runs, m. Any size gives the same
/// map (see the module docs); 1 m keeps p near 2.7/s.
pub(crate) const MAP_BLOCK_R_M: f64 = 1.0;

/// A pulse shape of the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PulseKind {
    /// Shape.
    pub shape: ShapeKind,
    /// n of type C_n (1 for the others).
    pub cycles: u32,
}

impl PulseKind {
    /// Output name: `one-sine`, `one-cosine`, `type-c1`, `type-c2`, ….
    pub fn name(self) -> String {
        match self.shape {
            ShapeKind::TypeC => format!("type-c{}", self.cycles),
            ShapeKind::OneSine | ShapeKind::OneCosine | ShapeKind::Rectangular | ShapeKind::HalfSine => {
                self.shape.name().to_string()
            }
        }
    }
}

/// What to compute.
#[derive(Clone, Debug)]
pub struct PulseMapSpec<'a> {
    /// Friction, impact law, tolerances, overturning angle.
    pub base: &'a Scenario,
    /// The pulses.
    pub pulses: Vec<PulseKind>,
    /// Slenderness ratios B/H.
    pub b_over_h: Vec<f64>,
    /// Frequencies ω_p/p, increasing.
    pub omega_ratios: Vec<f64>,
    /// Amplitudes a_p/(g tan α) stepped through, increasing, > 0.
    pub ladder: Vec<f64>,
    /// Relative tolerance of each boundary.
    pub rel_tol: f64,
}

/// One point of the map.
#[derive(Clone, Debug, PartialEq)]
pub struct PulseMapPoint {
    /// The pulse.
    pub pulse: PulseKind,
    /// B/H.
    pub b_over_h: f64,
    /// ω_p/p.
    pub omega_ratio: f64,
    /// The search over a_p/(g tan α).
    pub search: ScaleSearch<BlockResponse>,
}

/// A failed run of the map.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{pulse} pulse, B/H = {b_over_h}, omega_p/p = {omega_ratio}: {error}")]
pub struct PulseMapError {
    /// Pulse name.
    pub pulse: String,
    /// B/H.
    pub b_over_h: f64,
    /// ω_p/p.
    pub omega_ratio: f64,
    /// What failed.
    pub error: ResponseError,
}

/// The map's points in output order: pulse, then B/H, then ω_p/p.
pub fn pulse_map(spec: &PulseMapSpec<'_>, progress: &ProgressFn<'_>) -> Result<Vec<PulseMapPoint>, PulseMapError> {
    let mut cells = Vec::new();
    for &pulse in &spec.pulses {
        for &b_over_h in &spec.b_over_h {
            for &omega_ratio in &spec.omega_ratios {
                cells.push((pulse, b_over_h, omega_ratio));
            }
        }
    }
    progress(Progress::Total(cells.len() as u64));
    cells
        .par_iter()
        .map(|&(pulse, b_over_h, omega_ratio)| {
            let block = BlockSize::from_half_diagonal(MAP_BLOCK_R_M, b_over_h);
            let drive = Drive::NormalisedPulse {
                shape: pulse.shape,
                cycles: pulse.cycles,
                omega_ratio,
            };
            let found = search(&spec.ladder, spec.rel_tol, &|amplitude| {
                respond(spec.base, block, &drive, amplitude)
            })
            .map_err(|error| PulseMapError {
                pulse: pulse.name(),
                b_over_h,
                omega_ratio,
                error,
            })?;
            progress(Progress::Done);
            Ok(PulseMapPoint {
                pulse,
                b_over_h,
                omega_ratio,
                search: found,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::engineering::overturn_scale::ladder;

    #[test]
    fn the_minimum_overturning_amplitude_rises_with_frequency() {
        // As in Makris & Roussos 2000: for a slender block the one-sine
        // boundary rises from just above 1 at low ω_p/p to several g tan α
        // at ω_p/p = 6; the amplitude never falls below the uplift value 1.
        let base = Scenario::default();
        let spec = PulseMapSpec {
            base: &base,
            pulses: vec![PulseKind {
                shape: ShapeKind::OneSine,
                cycles: 1,
            }],
            b_over_h: vec![0.2],
            omega_ratios: vec![2.0, 6.0],
            ladder: ladder(0.25, 12.0).unwrap(),
            rel_tol: 1e-3,
        };
        let points = pulse_map(&spec, &crate::analysis::silent).unwrap();
        let first: Vec<f64> = points.iter().map(|p| p.search.first_failure.unwrap().0).collect();
        assert!(first[0] > 1.0 && first[0] < first[1], "{first:?}");
        assert_eq!(points[1].omega_ratio, 6.0);
        assert_eq!(
            PulseKind {
                shape: ShapeKind::TypeC,
                cycles: 2
            }
            .name(),
            "type-c2"
        );
    }
}
