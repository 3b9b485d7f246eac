//! The ghost copies' recent motion, one trail of (τ, Θ, Θ') per ghost, for
//! the phase portrait.
//!
//! The simulation thread sends only each ghost's latest state with every
//! batch (see [`crate::sim::protocol::Batch::ghosts`]), so a trail holds
//! one point per batch: about one per frame while playing. Contract:
//! - Storage is bounded: each trail keeps at most [`GHOST_TRAIL_POINTS`]
//!   points, the oldest going first (100 ghosts hold at most 9.8 MB).
//! - A batch with a different number of ghosts (the user changed the
//!   count) starts every trail over: the ghosts were started anew.
//! - NaN/inf: a ghost state with a non-finite Θ or Θ', or a batch with a
//!   non-finite τ, is not stored; points are added in increasing τ only.

use std::collections::VecDeque;

use crate::sim::protocol::GhostState;

/// Most points one ghost's trail keeps: 4096 batches, over a minute of
/// play at 60 frames per second, longer than the portrait's default 20 τ
/// trail at any speed up to 20×.
pub(crate) const GHOST_TRAIL_POINTS: usize = 4096;

/// One point of a ghost's trail.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GhostPoint {
    /// τ of the batch that carried it.
    pub tau: f64,
    /// Θ.
    pub theta: f64,
    /// Θ' = dΘ/dτ.
    pub theta_dot: f64,
}

/// The trails of the current ghosts, by ghost index.
#[derive(Clone, Debug, Default)]
pub struct GhostTrails {
    trails: Vec<VecDeque<GhostPoint>>,
    last_tau: Option<f64>,
}

impl GhostTrails {
    /// Adds the ghosts' states at `tau` (one batch's [`GhostState`]s, in
    /// ghost order).
    pub fn push(&mut self, tau: f64, ghosts: &[GhostState]) {
        if ghosts.len() != self.trails.len() {
            self.trails = vec![VecDeque::new(); ghosts.len()];
            self.last_tau = None;
        }
        if !tau.is_finite() || self.last_tau.is_some_and(|t| tau <= t) {
            return;
        }
        self.last_tau = Some(tau);
        for (trail, g) in self.trails.iter_mut().zip(ghosts) {
            if !(g.theta.is_finite() && g.theta_dot.is_finite()) {
                continue;
            }
            if trail.len() == GHOST_TRAIL_POINTS {
                trail.pop_front();
            }
            trail.push_back(GhostPoint {
                tau,
                theta: g.theta,
                theta_dot: g.theta_dot,
            });
        }
    }

    /// Forgets every trail (a new run, or new ghosts).
    pub fn clear(&mut self) {
        self.trails.clear();
        self.last_tau = None;
    }

    /// How many ghosts have a trail.
    pub fn len(&self) -> usize {
        self.trails.len()
    }

    /// Whether there are no ghosts.
    pub fn is_empty(&self) -> bool {
        self.trails.is_empty()
    }

    /// Ghost `k`'s trail, oldest first (empty past the last ghost).
    pub fn trail(&self, k: usize) -> std::collections::vec_deque::Iter<'_, GhostPoint> {
        const NONE: &VecDeque<GhostPoint> = &VecDeque::new();
        self.trails.get(k).unwrap_or(NONE).iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mode;

    fn ghost(theta: f64) -> GhostState {
        GhostState {
            theta,
            theta_dot: -theta,
            x: 0.0,
            mode: Mode::Rest,
        }
    }

    #[test]
    fn trails_keep_each_ghost_in_order_and_stay_bounded() {
        let mut t = GhostTrails::default();
        for k in 0..(GHOST_TRAIL_POINTS + 10) {
            t.push(k as f64, &[ghost(1.0), ghost(2.0)]);
        }
        assert_eq!(t.len(), 2);
        assert_eq!(t.trail(0).len(), GHOST_TRAIL_POINTS);
        assert_eq!(t.trail(1).next().map(|p| p.tau), Some(10.0));
        assert_eq!(t.trail(1).last().map(|p| (p.theta, p.theta_dot)), Some((2.0, -2.0)));
        assert_eq!(t.trail(2).len(), 0);
    }

    #[test]
    fn a_new_ghost_count_starts_over_and_bad_points_are_refused() {
        let mut t = GhostTrails::default();
        t.push(1.0, &[ghost(1.0), ghost(2.0)]);
        t.push(1.0, &[ghost(1.5), ghost(2.5)]);
        t.push(f64::NAN, &[ghost(1.5), ghost(2.5)]);
        t.push(2.0, &[ghost(f64::INFINITY), ghost(2.5)]);
        assert_eq!(t.trail(0).len(), 1, "same τ, NaN τ and inf Θ refused");
        assert_eq!(t.trail(1).len(), 2);
        t.push(3.0, &[ghost(0.0)]);
        assert_eq!(t.len(), 1);
        assert_eq!(t.trail(0).len(), 1);
        t.clear();
        assert!(t.is_empty());
    }
}
