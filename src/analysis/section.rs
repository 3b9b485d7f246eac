//! The stroboscopic (Poincaré) section: the state sampled once per forcing
//! period, at τ_k = 2πk/Ω_h (excitation phase 0, MODEL-DECISIONS), after a
//! transient.
//!
//! The hybrid driver takes section points from the dense output of the step
//! that contains them (the paper's fixed-step method: from a step landed on
//! the section time); a step ends at every event, so a section point is
//! never an interpolation across an impact. This module
//! - collects section points of any [`HybridSystem`](crate::integrate::hybrid::HybridSystem)
//!   run by the driver ([`Strobe`]);
//! - selects a block run's points after the transient ([`after_transient`])
//!   and gives the coordinates the classifier compares ([`block_coordinates`]);
//! - iterates a plain map ([`map_orbit`]), so that the classifier and the
//!   sweep machinery can be tested on maps with known answers.
//!
//! Contract: times and states are taken as given; the functions here never
//! produce NaN from finite input.

use crate::integrate::hybrid::Observer;
use crate::sim::SectionRow;

/// One section point of a generic hybrid system.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrobePoint<const N: usize> {
    /// Index k of the section time t_k = k·period (0 at t = 0).
    pub k: u64,
    /// Section time t_k, in the system's time unit.
    pub t: f64,
    /// State at t_k.
    pub y: [f64; N],
}

/// An [`Observer`] that keeps the section points at or after `transient`
/// and ignores samples and events (a Poincaré-only run keeps no history).
#[derive(Clone, Debug)]
pub struct Strobe<const N: usize> {
    transient: f64,
    points: Vec<StrobePoint<N>>,
}

impl<const N: usize> Strobe<N> {
    /// Collects section points with `t >= transient` (same time unit as the
    /// system's).
    pub fn new(transient: f64) -> Self {
        Self {
            transient,
            points: Vec::new(),
        }
    }

    /// The points collected so far, in time order.
    pub fn points(&self) -> &[StrobePoint<N>] {
        &self.points
    }

    /// The points, consuming the collector.
    pub fn into_points(self) -> Vec<StrobePoint<N>> {
        self.points
    }
}

impl<M, R, const N: usize> Observer<M, R, N> for Strobe<N> {
    fn sample(&mut self, _t: f64, _mode: M, _y: &[f64; N]) {}

    fn section(&mut self, k: u64, t: f64, _mode: M, y: &[f64; N]) {
        if t >= self.transient {
            self.points.push(StrobePoint { k, t, y: *y });
        }
    }

    fn event(&mut self, _t: f64, _before: M, _y_before: &[f64; N], _record: R) {}
}

/// The rows of a run's section at τ ≥ `transient` (rows are in time order,
/// as the driver emits them).
pub(crate) fn after_transient(rows: &[SectionRow], transient: f64) -> &[SectionRow] {
    let first = rows.partition_point(|r| r.tau < transient);
    rows.get(first..).unwrap_or(&[])
}

/// The coordinates the classifier compares for the block: (Θ, Θ', X').
///
/// X' is included so that a flat sliding block (Θ = Θ' = 0) is still told
/// apart by its slip velocity; X itself is left out because a sliding block
/// drifts, so X never repeats even when the motion is periodic.
pub(crate) fn block_coordinates(rows: &[SectionRow]) -> Vec<[f64; 3]> {
    rows.iter().map(|r| [r.theta, r.theta_dot, r.x_dot]).collect()
}

/// The orbit of the map `x ↦ map(x)` from `x0`: `transient` iterations are
/// discarded, the next `keep` iterates are returned. A map is its own
/// stroboscopic section, so this is the section of a discrete system.
pub fn map_orbit<const D: usize, F>(mut map: F, x0: [f64; D], transient: usize, keep: usize) -> Vec<[f64; D]>
where
    F: FnMut(&[f64; D]) -> [f64; D],
{
    let mut x = x0;
    for _ in 0..transient {
        x = map(&x);
    }
    let mut orbit = Vec::with_capacity(keep);
    for _ in 0..keep {
        x = map(&x);
        orbit.push(x);
    }
    orbit
}

/// How many section times τ_k = k·`period` lie in [`transient`, `tau_end`]
/// (0 for a non-positive period or an empty window).
pub(crate) fn points_in_window(period: f64, transient: f64, tau_end: f64) -> u64 {
    if period.is_nan() || period <= 0.0 || tau_end.is_nan() || transient.is_nan() || tau_end < transient {
        return 0;
    }
    let first = (transient.max(0.0) / period).ceil();
    let last = (tau_end / period).floor();
    if last >= first { (last - first) as u64 + 1 } else { 0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Mode, Sign};

    fn row(k: u64, tau: f64) -> SectionRow {
        SectionRow {
            k,
            tau,
            theta: k as f64,
            theta_dot: 0.0,
            x: 0.0,
            x_dot: 0.0,
            mode: Mode::Rock { pivot: Sign::Pos },
        }
    }

    #[test]
    fn after_transient_keeps_points_at_and_after_the_transient() {
        let rows: Vec<_> = (0..10).map(|k| row(k, k as f64 * 0.5)).collect();
        let kept = after_transient(&rows, 2.0);
        assert_eq!(kept.first().map(|r| r.k), Some(4));
        assert_eq!(kept.len(), 6);
        assert!(after_transient(&rows, 100.0).is_empty());
        assert_eq!(after_transient(&rows, -1.0).len(), 10);
    }

    #[test]
    fn map_orbit_discards_the_transient() {
        let orbit = map_orbit(|x: &[f64; 1]| [x[0] + 1.0], [0.0], 3, 2);
        assert_eq!(orbit, vec![[4.0], [5.0]]);
    }

    #[test]
    fn points_in_window_counts_inclusive_ends() {
        assert_eq!(points_in_window(1.0, 2.0, 5.0), 4);
        assert_eq!(points_in_window(1.0, 2.5, 5.0), 3);
        assert_eq!(points_in_window(1.0, 5.0, 2.0), 0);
        assert_eq!(points_in_window(0.0, 0.0, 2.0), 0);
        // The paper's window: tau 600..800 at Omega = 8 holds 255 points.
        let p = std::f64::consts::TAU / 8.0;
        assert_eq!(points_in_window(p, 600.0, 800.0), 255);
    }

    #[test]
    fn strobe_keeps_only_points_after_the_transient() {
        let mut s = Strobe::<2>::new(1.0);
        Observer::<(), (), 2>::section(&mut s, 0, 0.5, (), &[1.0, 2.0]);
        Observer::<(), (), 2>::section(&mut s, 1, 1.0, (), &[3.0, 4.0]);
        assert_eq!(s.points().len(), 1);
        assert_eq!(s.into_points()[0].y, [3.0, 4.0]);
    }
}
