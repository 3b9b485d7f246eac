//! Telling attractors apart by their section points, as a basin map needs:
//! two coexisting period-2 orbits are two attractors, not one class.
//!
//! A periodic attractor is identified by its cycle of k section points
//! (Θ, Θ', X'). Two cycles are the same attractor when they have the same
//! period and, for some cyclic shift s, every point of one lies within
//! [`MATCH_FRACTION`] of the amplitude of the other's shifted point, per
//! component: |a_i,d − b_(i+s) mod k,d| ≤ 10⁻²·max(A_d, B_d) + 10⁻⁹, where
//! A_d, B_d are the largest |p_d| of each cycle. The shift is needed
//! because a run may stop at any phase of its cycle. Converged cycles
//! agree to about 10⁻⁵ of their amplitude (the early stop's
//! [`SETTLE_FRACTION`](super::settle::SETTLE_FRACTION)) and a cycle from a
//! full run to the classifier's 10⁻³; distinct coexisting orbits (a
//! period-2 orbit and its mirror image, say) differ by a sizeable part of
//! their amplitude, so 10⁻² separates them with room on both sides.
//!
//! Attractors are numbered in order of discovery while a map is computed
//! (deterministic: cells are recorded in index order), and renumbered at
//! the end by the first cell, in row order, that reaches each, so that the
//! numbers do not depend on how the map was computed.

/// Relative distance within which two cycles are one attractor (module
/// docs).
pub(crate) const MATCH_FRACTION: f64 = 1e-2;

/// Absolute part of the match tolerance, for components that are zero
/// on both cycles (the slip velocity of a block that never slides).
const MATCH_FLOOR: f64 = 1e-9;

/// One periodic attractor.
#[derive(Clone, Debug, PartialEq)]
pub struct Attractor {
    /// Its number, from 1, in order of the first cell (row order) that
    /// reaches it.
    pub id: u32,
    /// Period, forcing cycles.
    pub period: u32,
    /// Its representative section point (Θ, Θ', X'): the point of the
    /// cycle with the largest Θ (then Θ'), the same whatever phase the
    /// cycle was recorded at.
    pub point: [f64; 3],
    /// The whole cycle, starting at `point`.
    pub cycle: Vec<[f64; 3]>,
    /// Cells of the map that reach it (computed or inherited).
    pub cells: usize,
}

/// The attractors found so far, in order of discovery.
#[derive(Clone, Debug, Default)]
pub struct Catalogue {
    cycles: Vec<Vec<[f64; 3]>>,
}

/// The cycle rotated to start at its representative point (largest Θ,
/// then largest Θ').
fn canonical(cycle: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let start = (0..cycle.len())
        .max_by(|&a, &b| {
            cycle[a][0]
                .total_cmp(&cycle[b][0])
                .then(cycle[a][1].total_cmp(&cycle[b][1]))
                .then(b.cmp(&a))
        })
        .unwrap_or(0);
    cycle[start..].iter().chain(&cycle[..start]).copied().collect()
}

/// Whether two cycles are one attractor (module docs).
pub(crate) fn same_attractor(a: &[[f64; 3]], b: &[[f64; 3]]) -> bool {
    let k = a.len();
    if k == 0 || k != b.len() {
        return false;
    }
    let mut amplitude = [0.0_f64; 3];
    for p in a.iter().chain(b) {
        for (m, x) in amplitude.iter_mut().zip(p) {
            *m = m.max(x.abs());
        }
    }
    let tol: [f64; 3] = std::array::from_fn(|d| MATCH_FRACTION * amplitude[d] + MATCH_FLOOR);
    (0..k).any(|s| {
        (0..k).all(|i| {
            let (p, q) = (&a[i], &b[(i + s) % k]);
            p.iter().zip(q).zip(&tol).all(|((x, y), t)| (x - y).abs() <= *t)
        })
    })
}

impl Catalogue {
    /// The discovery number (from 0) of the attractor with this cycle,
    /// adding it if it is new.
    pub(crate) fn identify(&mut self, cycle: &[[f64; 3]]) -> u32 {
        if let Some(i) = self.cycles.iter().position(|c| same_attractor(c, cycle)) {
            return i as u32;
        }
        self.cycles.push(canonical(cycle));
        (self.cycles.len() - 1) as u32
    }

    /// The cycles found so far, in discovery order (each from its point
    /// of largest Θ): what a later cell's run may stop on reaching
    /// ([`settle`](super::settle)).
    pub fn cycles(&self) -> &[Vec<[f64; 3]>] {
        &self.cycles
    }

    /// Attractors found.
    pub fn len(&self) -> usize {
        self.cycles.len()
    }

    /// Whether none was found.
    pub fn is_empty(&self) -> bool {
        self.cycles.is_empty()
    }

    /// The attractors numbered by first cell in row order: `labels` holds
    /// each cell's discovery number (or `None`). Returns the attractors and
    /// the map from discovery number to final id.
    pub fn numbered(&self, labels: &[Option<u32>]) -> (Vec<Attractor>, Vec<u32>) {
        let mut id = vec![0_u32; self.cycles.len()];
        let mut count = vec![0_usize; self.cycles.len()];
        let mut order = Vec::new();
        for &l in labels.iter().flatten() {
            let l = l as usize;
            if count[l] == 0 {
                order.push(l);
                id[l] = order.len() as u32;
            }
            count[l] += 1;
        }
        let attractors = order
            .iter()
            .map(|&l| {
                let cycle = self.cycles[l].clone();
                Attractor {
                    id: id[l],
                    period: cycle.len() as u32,
                    point: cycle[0],
                    cycle,
                    cells: count[l],
                }
            })
            .collect();
        (attractors, id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cycle_matches_itself_at_any_phase_and_not_its_mirror() {
        let orbit = vec![[0.3, -0.1, 0.02], [-0.2, 0.4, -0.05]];
        let shifted = vec![orbit[1], orbit[0]];
        assert!(same_attractor(&orbit, &shifted));
        let nudged: Vec<[f64; 3]> = orbit.iter().map(|p| [p[0] + 1e-5, p[1], p[2]]).collect();
        assert!(same_attractor(&orbit, &nudged), "agrees to 1e-5: one attractor");
        let mirror: Vec<[f64; 3]> = orbit.iter().map(|p| [-p[0], -p[1], -p[2]]).collect();
        assert!(!same_attractor(&orbit, &mirror), "a mirror orbit is another attractor");
        assert!(!same_attractor(&orbit, &orbit[..1]), "periods differ");
    }

    #[test]
    fn attractors_are_numbered_by_their_first_cell_in_row_order() {
        let a = vec![[0.5, 0.0, 0.0]];
        let b = vec![[-0.5, 0.0, 0.0]];
        let mut cat = Catalogue::default();
        // Discovered b first (a refined map computes cells out of row order).
        assert_eq!(cat.identify(&b), 0);
        assert_eq!(cat.identify(&a), 1);
        assert_eq!(cat.identify(&[[0.5 + 1e-7, 0.0, 0.0]]), 1);
        let labels = [None, Some(1), Some(0), Some(1)];
        let (attractors, id) = cat.numbered(&labels);
        assert_eq!(id, vec![2, 1]);
        assert_eq!(attractors[0].point, a[0]);
        assert_eq!((attractors[0].id, attractors[0].cells), (1, 2));
        assert_eq!((attractors[1].id, attractors[1].cells), (2, 1));
    }

    #[test]
    fn the_representative_point_is_the_largest_theta_whatever_the_phase() {
        let c = vec![[0.1, 0.0, 0.0], [0.4, 1.0, 0.0], [-0.3, 0.0, 0.0]];
        let r = canonical(&c);
        assert_eq!(r[0], [0.4, 1.0, 0.0]);
        assert_eq!(canonical(&[c[2], c[0], c[1]]), r);
    }
}
