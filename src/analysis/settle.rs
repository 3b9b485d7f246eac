//! Early stopping of a steady-response run: a run ends as soon as its
//! class is certain, instead of running out its whole window.
//!
//! Run out in full, a map cell runs its transient and window (τ 0–800 by
//! default) whatever it does; most cells come to rest or settle onto a
//! periodic orbit long before. [`Settle`] watches a run's section points and events
//! and ends it (through [`Sink::settled`]) when one of these holds at a
//! section point τ_n:
//! - **Rest**: the block is at rest and has been since at least τ_n − T
//!   (T = 2π/Ω_h, no event in between). At rest the motion depends on
//!   the time alone (flat and stuck, whatever the state), so a base that
//!   did not lift or slide the block during one whole period never will
//!   when the forcing has period T: the run would end at rest with the
//!   same last event, which is exactly [`classify_run`]'s rest criterion.
//! - **Periodic, period k**: the last `2k + CONFIRM` recurrences of
//!   period k hold to [`SETTLE_FRACTION`] of the classifier's tolerance:
//!   |p_{j+k,d} − p_{j,d}| ≤ 10⁻²·(rel_tol·a_d + abs_tol) for each component
//!   d (a_d: the largest |p_d| over the points tested). The orbit has then
//!   converged a hundred times more tightly than the classifier needs,
//!   for at least two whole cycles of every point plus `CONFIRM` periods.
//!   To change the class later, the distance to the orbit would have to
//!   grow a hundredfold within the window, which needs an unstable orbit;
//!   a trajectory stays within 10⁻⁵ of an unstable one for that long only
//!   from a set of initial states of measure zero. The class is then read
//!   off the window's points as the full run would have them: the last
//!   cycle repeated over the window, classified by
//!   [`classify_points`] (so period k may still come out as a smaller
//!   period, when two of the cycle's points agree to the classifier's
//!   tolerance, as the full run would find).
//! - **A known attractor reached** (basin maps): the last `k + REACH_CONFIRM`
//!   section points follow, in order, the cycle of a periodic attractor
//!   already found in another cell of the same map (its k points, at
//!   some phase), each within the classifier's own tolerance of the
//!   cycle's point: |p_d − c_d| ≤ rel_tol·a_d + abs_tol (a_d: the largest
//!   |c_d| over the cycle). The known cycle is an attracting orbit (runs
//!   from other initial states converged onto it to 10⁻⁵ of its
//!   amplitude), and a trajectory that has stayed within 10⁻³ of its
//!   amplitude for a whole cycle and `REACH_CONFIRM` more forcing periods
//!   is in its basin (short of a chaotic transient shadowing the orbit
//!   that closely for that long, which a looser 1 % match was seen to
//!   let through): it converges onto that orbit, and the full run's
//!   window would show the same cycle. This is how Attractors.jl's
//!   recurrence method ends a run that enters a known attractor's
//!   neighbourhood; here it saves the tail of the approach from 10⁻³ to
//!   10⁻⁵ and the confirmation, about a third to a half of each periodic
//!   cell's run (docs/analysis.md).
//! - **A labelled basin entered** (basin maps over Θ₀ × Θ'₀): a section
//!   point is a state at the forcing's phase 0, as every cell's initial
//!   state is, so when the run rocks on its pivot without slipping (the
//!   cells' own initial condition, X' following Θ') at a point inside the
//!   map, its future is that of the cell it falls in, to within half a
//!   cell. When `BASIN_HITS` consecutive section points fall in cells
//!   already labelled with one periodic attractor (computed or inherited
//!   at the levels before), the run stops with that attractor: Attractors.jl
//!   labels a run that keeps hitting one basin the same way, with the
//!   same default count (`mx_chk_hit_bas = 10`). This is not a certainty
//!   in the strict sense of the criteria above: a cell label stands for
//!   states within half a cell, so where two basins are intertwined more
//!   finely than the grid, a run can be labelled with its neighbours'
//!   attractor; ten hits in a row in cells of one label make that rare,
//!   and docs/analysis.md gives the agreement measured against `--full`.
//!
//! Every other run (chaotic, quasiperiodic, slowly converging) runs its
//! whole window, and tumbling and flight end a run by themselves.
//!
//! Early stopping is used only when the forcing has period T exactly:
//! Ω_v = m·Ω_h for a whole m ≥ 1, or no vertical forcing. With another
//! Ω_v the section at T is not a Poincaré section of the forced system,
//! and neither criterion holds; such runs run their whole window.
//!
//! The watched run takes exactly the steps of the full one up to where it
//! stops ([`Sink::watches`]), so a run that does not stop is the full run,
//! bit for bit.

use std::collections::VecDeque;

use super::classify::{ClassifyOptions, Response, classify_points, classify_run};
use super::section::{after_transient, block_coordinates, points_in_window};
use super::steady::{LyapunovFn, SteadyError, Window, exponent_of, section_run};
use crate::model::Mode;
use crate::model::system::EventRecord;
use crate::sim::{HistoryRow, Scenario, SectionRow, Sink, simulate_into};

/// Fraction of the classifier's tolerance to which a periodic orbit must
/// have converged before its run stops (module docs): 10⁻², a hundred
/// times tighter than the class needs (10⁻⁵ of the amplitude), and still
/// far above the 10⁻¹² scatter of a converged orbit at the default
/// integration tolerance (so a converged orbit does reach it; a loose
/// tolerance whose scatter exceeds it only means the run is not stopped).
pub(crate) const SETTLE_FRACTION: f64 = 1e-2;

/// Recurrences beyond two whole cycles that must hold before a periodic
/// run stops: 8 forcing periods, a margin against a passing
/// near-recurrence of a chaotic transient.
pub(crate) const CONFIRM: usize = 8;

/// Section points beyond one whole cycle that must follow a known
/// attractor's cycle before a run stops on it (module docs): 4 forcing
/// periods. A trajectory near the orbit but leaving it would move away
/// within them; one converging onto it stays.
pub(crate) const REACH_CONFIRM: usize = 4;

/// Consecutive section points in cells labelled with one attractor after
/// which a basin map's run stops on it (module docs): 10, Attractors.jl's
/// default for the same test.
pub(crate) const BASIN_HITS: usize = 10;

/// The labels a basin map over Θ₀ × Θ'₀ has so far, for looking a
/// run's section points up in (module docs).
#[derive(Clone, Copy, Debug)]
pub struct BasinLookup<'a> {
    /// The Θ₀ axis: first value, last value, count (≥ 2).
    pub theta: (f64, f64, usize),
    /// The Θ'₀ axis.
    pub theta_dot: (f64, f64, usize),
    /// Whether Θ₀ is the map's x axis (else its y axis).
    pub theta_is_x: bool,
    /// Per cell, in row order (y outer): the attractor its label is (an
    /// index into the known cycles), or −1.
    pub labels: &'a [i64],
}

impl BasinLookup<'_> {
    /// The attractor of the cell (Θ, Θ') falls in, if labelled.
    fn label(&self, theta: f64, theta_dot: f64) -> Option<usize> {
        let index = |v: f64, (a, b, n): (f64, f64, usize)| {
            let i = ((v - a) / (b - a) * (n - 1) as f64).round();
            (i >= 0.0 && i < n as f64).then_some(i as usize)
        };
        let (i, j) = (index(theta, self.theta)?, index(theta_dot, self.theta_dot)?);
        let cell = if self.theta_is_x {
            j * self.theta.2 + i
        } else {
            i * self.theta_dot.2 + j
        };
        usize::try_from(*self.labels.get(cell)?).ok()
    }
}

/// Why a watched run stopped early.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// At rest for a whole forcing period at `tau`.
    Rest {
        /// τ of the section point where it was seen.
        tau: f64,
    },
    /// Converged onto a periodic orbit of period `k` at `tau`.
    Periodic {
        /// τ of the section point where it was seen.
        tau: f64,
        /// The orbit's last cycle of section points, (Θ, Θ', X'), oldest
        /// first: `k` points.
        cycle: Vec<[f64; 3]>,
    },
    /// Reached a periodic attractor already known at `tau`.
    Reached {
        /// τ of the section point where it was seen.
        tau: f64,
        /// The known attractor's cycle, in the run's phase: `k` points,
        /// the last one the point matched at `tau`.
        cycle: Vec<[f64; 3]>,
    },
}

/// The sink that watches a run (module docs).
#[derive(Debug)]
pub struct Settle<'a> {
    period: f64,
    opts: ClassifyOptions,
    /// The latest section points, newest last, at most `capacity`.
    recent: VecDeque<[f64; 3]>,
    capacity: usize,
    /// The largest |coordinate| of every point pushed so far: at least the
    /// amplitude of any range of `recent`, so the quick rejection of
    /// [`Settle::converged_period`] may use it without a pass over them.
    bound: [f64; 3],
    /// The latest event (the rest criterion reads its τ).
    last_event: Option<EventRecord>,
    verdict: Option<Verdict>,
    /// Every section point of the run, kept for the classifier when the
    /// run is not stopped (after the transient only).
    kept: Vec<SectionRow>,
    transient: f64,
    /// Cycles of the periodic attractors already known (basin maps).
    known: &'a [Vec<[f64; 3]>],
    /// Each known cycle's tolerance (the classifier's, of its amplitude),
    /// computed once.
    known_tol: Vec<[f64; 3]>,
    /// The basin map's labels so far, if its section points can be looked
    /// up in them.
    basins: Option<BasinLookup<'a>>,
    /// The attractor the latest section points' cells are labelled with,
    /// and how many in a row.
    hits: Option<(usize, usize)>,
}

impl<'a> Settle<'a> {
    /// A watcher for a run whose forcing has period `period` (τ), keeping
    /// the section points after `transient` for the full classification.
    pub fn new(period: f64, transient: f64, opts: ClassifyOptions) -> Self {
        let k_max = opts.k_max as usize;
        let capacity = 3 * k_max + CONFIRM;
        Self {
            period,
            opts,
            recent: VecDeque::with_capacity(capacity),
            capacity,
            bound: [0.0; 3],
            last_event: None,
            verdict: None,
            kept: Vec::new(),
            transient,
            known: &[],
            known_tol: Vec::new(),
            basins: None,
            hits: None,
        }
    }

    /// The same watcher, also stopping a run that reaches one of the
    /// `known` periodic attractors' cycles, or whose section points keep
    /// falling in cells of `basins` labelled with one of them (module
    /// docs).
    pub fn knowing(self, known: &'a [Vec<[f64; 3]>], basins: Option<BasinLookup<'a>>) -> Self {
        let known_tol = known
            .iter()
            .map(|cycle| {
                let mut amplitude = [0.0_f64; 3];
                for p in cycle {
                    for (a, x) in amplitude.iter_mut().zip(p) {
                        *a = a.max(x.abs());
                    }
                }
                std::array::from_fn(|d| self.opts.rel_tol * amplitude[d] + self.opts.abs_tol)
            })
            .collect();
        Self {
            known,
            known_tol,
            basins,
            ..self
        }
    }

    /// Why the run stopped, if it did.
    pub fn verdict(&self) -> Option<&Verdict> {
        self.verdict.as_ref()
    }

    /// The section points at τ ≥ the transient seen so far.
    pub fn kept(&self) -> &[SectionRow] {
        &self.kept
    }

    /// The smallest period k whose last `2k + CONFIRM` recurrences hold to
    /// [`SETTLE_FRACTION`] of the tolerance, if any.
    fn converged_period(&self) -> Option<usize> {
        converged_period(&self.recent, &self.bound, &self.opts)
    }
}

impl Settle<'_> {
    /// A known cycle the latest section points follow (module docs),
    /// rotated into the run's phase (its last point the newest's match).
    fn reached(&self) -> Option<Vec<[f64; 3]>> {
        let n = self.recent.len();
        let newest = self.recent.back()?;
        self.known.iter().zip(&self.known_tol).find_map(|(cycle, tol)| {
            let k = cycle.len();
            let m = k + REACH_CONFIRM;
            if k == 0 || n < m {
                return None;
            }
            let near = |p: &[f64; 3], c: &[f64; 3]| p.iter().zip(c).zip(tol).all(|((x, y), t)| (x - y).abs() <= *t);
            // The cycle's point the newest one matches, then the earlier
            // points against the cycle's earlier points, in order.
            let end = (0..k).find(|&e| {
                near(newest, &cycle[e]) && (1..m).all(|j| near(&self.recent[n - 1 - j], &cycle[(e + k * m - j) % k]))
            })?;
            Some((0..k).map(|i| cycle[(end + 1 + i) % k]).collect())
        })
    }
}

impl Sink for Settle<'_> {
    fn sample(&mut self, _row: &HistoryRow) {}

    fn section(&mut self, row: &SectionRow) {
        if row.tau >= self.transient {
            self.kept.push(*row);
        }
        if self.verdict.is_some() {
            return;
        }
        let since = self.last_event.map_or(0.0, |e| e.tau);
        if row.mode == Mode::Rest && since <= row.tau - self.period {
            self.verdict = Some(Verdict::Rest { tau: row.tau });
            return;
        }
        if self.recent.len() == self.capacity {
            self.recent.pop_front();
        }
        let point = [row.theta, row.theta_dot, row.x_dot];
        for (a, x) in self.bound.iter_mut().zip(&point) {
            *a = a.max(x.abs());
        }
        self.recent.push_back(point);
        if let Some(k) = self.converged_period() {
            let cycle = self.recent.range(self.recent.len() - k..).copied().collect();
            self.verdict = Some(Verdict::Periodic { tau: row.tau, cycle });
        } else if let Some(cycle) = self.reached() {
            self.verdict = Some(Verdict::Reached { tau: row.tau, cycle });
        } else if let Some(basins) = &self.basins {
            let label = match row.mode {
                Mode::Rock { .. } => basins.label(row.theta, row.theta_dot),
                _ => None,
            };
            self.hits = match (label, self.hits) {
                (Some(a), Some((b, n))) if a == b => Some((a, n + 1)),
                (Some(a), _) => Some((a, 1)),
                (None, _) => None,
            };
            if let Some((a, BASIN_HITS..)) = self.hits
                && let Some(cycle) = self.known.get(a)
            {
                self.verdict = Some(Verdict::Reached {
                    tau: row.tau,
                    cycle: cycle.clone(),
                });
            }
        }
    }

    fn event(&mut self, record: &EventRecord) {
        self.last_event = Some(*record);
    }

    fn watches(&self) -> bool {
        true
    }

    fn settled(&self) -> bool {
        self.verdict.is_some()
    }
}

/// The smallest period k whose last `2k + CONFIRM` recurrences among
/// `recent` (newest last; `bound` at least the largest |coordinate| among
/// them) hold to [`SETTLE_FRACTION`] of `opts`' tolerance, if any: the
/// periodic criterion of the module docs, for points of any dimension.
pub(crate) fn converged_period<const D: usize>(
    recent: &VecDeque<[f64; D]>,
    bound: &[f64; D],
    opts: &ClassifyOptions,
) -> Option<usize> {
    let n = recent.len();
    let newest = recent.back()?;
    // A quick rejection first: the newest pair against the tolerance of
    // the largest amplitude seen so far. That bounds the amplitude of
    // any range tested below, so a pair outside this looser tolerance
    // fails the exact test too, and most periods k fail here after
    // three comparisons instead of a pass over up to 3k + 8 points.
    let loose: [f64; D] = std::array::from_fn(|d| SETTLE_FRACTION * (opts.rel_tol * bound[d] + opts.abs_tol));
    (1..=opts.k_max as usize).find(|&k| {
        let pairs = 2 * k + CONFIRM;
        if n < pairs + k {
            return false;
        }
        let before = &recent[n - 1 - k];
        if newest
            .iter()
            .zip(before)
            .zip(&loose)
            .any(|((x, y), t)| (y - x).abs() > *t)
        {
            return false;
        }
        let first = n - pairs - k;
        let mut amplitude = [0.0_f64; D];
        for p in recent.range(first..) {
            for (a, x) in amplitude.iter_mut().zip(p) {
                *a = a.max(x.abs());
            }
        }
        let tol: [f64; D] = std::array::from_fn(|d| SETTLE_FRACTION * (opts.rel_tol * amplitude[d] + opts.abs_tol));
        // Newest pair first: a run that has not converged fails at once.
        (first..n - k).rev().all(|j| {
            let (a, b) = (&recent[j], &recent[j + k]);
            a.iter().zip(b).zip(&tol).all(|((x, y), t)| (y - x).abs() <= *t)
        })
    })
}

/// Whether a scenario's forcing has the section's period 2π/Ω_h exactly
/// (module docs): harmonic, and no vertical forcing or Ω_v a whole
/// multiple of Ω_h.
pub(crate) fn forcing_is_periodic(scenario: &Scenario) -> bool {
    let x = &scenario.excitation;
    if x.forcing_period().is_none() {
        return false;
    }
    if x.a_v == 0.0 {
        return true;
    }
    let m = x.omega_v() / x.omega_h;
    m >= 1.0 && m.fract() == 0.0
}

/// The steady response of one map cell, stopped as soon as it is certain.
#[derive(Clone, Debug, PartialEq)]
pub struct CellResponse {
    /// Its class.
    pub response: Response,
    /// Largest |Θ| over the part of the run computed.
    pub max_abs_theta: f64,
    /// Largest Lyapunov exponent per unit τ, when a hook supplied it.
    pub lyapunov: Option<f64>,
    /// The last cycle of a periodic response's section points
    /// (Θ, Θ', X'), `period` points; empty for the other classes.
    pub cycle: Vec<[f64; 3]>,
    /// τ at which the run stopped early; `None` when it ran its whole
    /// window (or ended by tumbling or flight).
    pub stopped_at: Option<f64>,
    /// Whether it stopped on reaching a periodic attractor already known
    /// (module docs).
    pub reached_known: bool,
    /// τ at which the class was certain: where the run stopped early, or
    /// where it ended (tumbling, flight, or the window's end for a run
    /// that ran out its window). A late one marks a cell whose fate took a
    /// long transient to show, which refinement does not trust its
    /// neighbours to share ([`map_refine`](super::map_refine)).
    pub settled_at: f64,
}

/// Runs `scenario` over `window` and classifies its steady response,
/// stopping as soon as the class is certain when `early` is set and the
/// forcing allows it (module docs), or on reaching one of the `known`
/// periodic attractors' cycles (a basin map's, found in other cells) or
/// their labelled cells in `basins`;
/// otherwise the full run of
/// [`steady_response`](super::steady::steady_response), with the same class.
pub fn cell_response(
    scenario: &Scenario,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
    early: bool,
    known: &[Vec<[f64; 3]>],
    basins: Option<BasinLookup<'_>>,
) -> Result<CellResponse, SteadyError> {
    let (cfg, model, period, run) = section_run(scenario, window)?;
    let mut watch = Settle::new(period, window.transient, *opts).knowing(known, basins);
    let mut res = if early && forcing_is_periodic(&cfg) {
        simulate_into(model, &cfg.initial, &run, &mut watch)?
    } else {
        // Unwatched: the same run, never stopped.
        struct Full<'a, 'b>(&'a mut Settle<'b>);
        impl Sink for Full<'_, '_> {
            fn sample(&mut self, _row: &HistoryRow) {}
            fn section(&mut self, row: &SectionRow) {
                if row.tau >= self.0.transient {
                    self.0.kept.push(*row);
                }
            }
            fn event(&mut self, record: &EventRecord) {
                self.0.last_event = Some(*record);
            }
        }
        simulate_into(model, &cfg.initial, &run, &mut Full(&mut watch))?
    };
    let (mut response, cycle, stopped_at) = match watch.verdict() {
        Some(Verdict::Rest { tau }) => (Response::Rest, Vec::new(), Some(*tau)),
        Some(Verdict::Periodic { tau, cycle } | Verdict::Reached { tau, cycle }) => {
            // The window's points as the full run would have them: those
            // already taken (a run may converge inside the window, after
            // points that had not), then the converged cycle repeated, the
            // next point being the one a period before it.
            let n = points_in_window(period, window.transient, window.tau_end) as usize;
            let mut points = block_coordinates(watch.kept());
            let k = cycle.len();
            for j in 0..n.max(opts.min_points()).saturating_sub(points.len()) {
                points.push(cycle[j % k]);
            }
            let response = classify_points(&points, None, opts)?;
            // The window's own period may differ from the converged one (a
            // window that began before the run converged): its cycle is the
            // window's last `period` points.
            let cycle = match response {
                Response::Periodic { period } => points[points.len() - period as usize..].to_vec(),
                _ => Vec::new(),
            };
            (response, cycle, Some(*tau))
        }
        None => {
            // The full run: classify it as `steady_response` does, from the
            // events' last τ and the points after the transient.
            res.events.extend(watch.last_event);
            res.section = watch.kept.clone();
            let response = classify_run(&res, period, window.transient, None, opts)?;
            let cycle = match response {
                Response::Periodic { period: k } => {
                    let rows = after_transient(&res.section, window.transient);
                    rows[rows.len() - k as usize..]
                        .iter()
                        .map(|r| [r.theta, r.theta_dot, r.x_dot])
                        .collect()
                }
                _ => Vec::new(),
            };
            (response, cycle, None)
        }
    };
    let exponent = exponent_of(lyapunov, response, &cfg)?;
    if exponent.is_some() && stopped_at.is_none() {
        response = classify_run(&res, period, window.transient, exponent, opts)?;
    }
    Ok(CellResponse {
        response,
        max_abs_theta: res.max_abs_theta,
        lyapunov: exponent,
        cycle,
        stopped_at,
        reached_known: matches!(watch.verdict(), Some(Verdict::Reached { .. })),
        settled_at: stopped_at.unwrap_or(res.tau_end),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Sign;

    /// A 3 × 2 map: Θ₀ ∈ {−0.2, 0, 0.2} along x, Θ'₀ ∈ {0, 1} along y;
    /// the cells' labels in row order (y outer).
    const LABELS: [i64; 6] = [0, -1, 1, 0, 0, 1];

    fn lookup(theta_is_x: bool) -> BasinLookup<'static> {
        let (t, d) = ((-0.2, 0.2, 3), (0.0, 1.0, 2));
        BasinLookup {
            theta: t,
            theta_dot: d,
            theta_is_x,
            labels: &LABELS,
        }
    }

    #[test]
    fn a_state_is_looked_up_in_the_nearest_cell_of_either_axis_order() {
        let l = lookup(true);
        // Θ = 0.19 is nearest 0.2 (column 2), Θ' = 0.4 nearest 0 (row 0).
        assert_eq!(l.label(0.19, 0.4), Some(1));
        assert_eq!(l.label(0.0, 0.4), None, "an unlabelled cell");
        assert_eq!(l.label(0.05, 0.9), Some(0), "row 1, column 1");
        assert_eq!(l.label(0.31, 0.0), None, "beyond half a cell past the last column");
        assert_eq!(l.label(-0.29, 1.49), Some(0), "within half a cell of the corner");
        // Θ₀ along y: 2 columns (Θ'), 3 rows (Θ): cell (Θ row 2, Θ' column 0).
        let labels = [0, -1, 1, 0, 1, 1];
        let swapped = BasinLookup {
            theta_is_x: false,
            labels: &labels,
            ..lookup(true)
        };
        assert_eq!(swapped.label(0.2, 0.0), Some(1));
        assert_eq!(swapped.label(-0.2, 1.0), None);
    }

    fn row(k: u64, theta: f64, theta_dot: f64, mode: Mode) -> SectionRow {
        SectionRow {
            k,
            tau: k as f64,
            theta,
            theta_dot,
            x: 0.0,
            x_dot: 0.0,
            mode,
        }
    }

    #[test]
    fn a_run_stops_after_ten_section_points_in_cells_of_one_attractor() {
        let known = vec![vec![[0.5, 0.5, 0.0]], vec![[0.7, 0.1, 0.0], [-0.7, 0.1, 0.0]]];
        let rock = Mode::Rock { pivot: Sign::Pos };
        let feed = |points: &[(f64, f64, Mode)]| {
            let mut s = Settle::new(1.0, 1e9, ClassifyOptions::default()).knowing(&known, Some(lookup(true)));
            for (k, &(t, d, m)) in points.iter().enumerate() {
                s.section(&row(k as u64, t, d, m));
            }
            s.verdict().cloned()
        };
        // Alternating between two cells of attractor 1 (far from its
        // cycle): stopped at the tenth, with attractor 1's cycle.
        let mut points: Vec<(f64, f64, Mode)> = (0..10)
            .map(|k| if k % 2 == 0 { (0.2, 0.0, rock) } else { (0.2, 1.0, rock) })
            .collect();
        assert_eq!(
            feed(&points),
            Some(Verdict::Reached {
                tau: 9.0,
                cycle: known[1].clone()
            })
        );
        // Nine, then one in a cell of another attractor: no verdict.
        points[9] = (-0.2, 0.0, rock);
        assert_eq!(feed(&points), None);
        // Ten, but one of them sliding (a state no cell starts in): none.
        points[9] = (0.2, 0.0, rock);
        points[4].2 = Mode::Slide { slip: Sign::Pos };
        assert_eq!(feed(&points), None);
    }
}
