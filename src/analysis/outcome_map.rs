//! Outcome maps: a 2-D sweep over two configuration keys, each cell
//! classified as rest, period k, quasiperiodic, chaotic, tumbled or flight
//! (and, when a hook supplies it, given its largest Lyapunov exponent).
//! This is how the rocking literature presents overturning (e.g. A_h × Ω).
//!
//! Contract:
//! - Axis values are `from + i·(to − from)/(n − 1)`, i = 0 … n−1, computed
//!   from i; the last is exactly `to`. A one-point axis is just `from`.
//! - Cells are ordered row by row: y outer (increasing), x inner
//!   (increasing), the order of `map.csv`.
//! - Every cell starts from the configuration's initial state; cells run in
//!   parallel on the current rayon pool and are collected by index, so the
//!   result is bit-identical for any number of threads.

use rayon::prelude::*;

use super::attractor::{Attractor, Catalogue};
use super::classify::{ClassifyOptions, Response};
use super::map_refine::Refiner;
use super::orbit_diagram::{AxisRule, PlanError};
use super::settle::{BasinLookup, CellResponse, cell_response};
use super::steady::{LyapunovFn, SteadyError, Window, check_scenario, check_stack_study, stack_cell};
use super::{Progress, ProgressFn};
use crate::sim::{Param, Scenario};

/// Most points on one axis (a guard against a typo; 10⁴ × 10⁴ cells would
/// take weeks anyway).
pub(crate) const MAX_AXIS_POINTS: usize = 10_000;

/// One axis of a map: what it is called and its values.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Axis {
    /// Its name as the user gave it (for a block map, the parameter's
    /// config key, e.g. `excitation.a_h`).
    pub key: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of values, ≥ 1.
    pub n: usize,
}

impl Axis {
    /// Validates an axis. `name` is how the caller's surface names the
    /// axis (the CLI its flag `--x`, Python its keyword `x`, the app `x`):
    /// an error carries it as given, with the axis as given after it.
    pub fn new(name: &str, key: &str, from: f64, to: f64, n: usize) -> Result<Self, PlanError> {
        let bad = |rule| {
            Err(PlanError::Axis {
                name: name.to_string(),
                given: format!("{key} {from} {to} {n}"),
                rule,
            })
        };
        if !from.is_finite() || !to.is_finite() {
            return bad(AxisRule::NotFinite);
        }
        if n == 0 || n > MAX_AXIS_POINTS {
            return bad(AxisRule::Count(MAX_AXIS_POINTS));
        }
        let axis = Self {
            key: key.to_string(),
            from,
            to,
            n,
        };
        if n > 1 && from >= to {
            return bad(AxisRule::Order);
        }
        if n > 1 && (0..n - 1).any(|i| axis.value(i) >= axis.value(i + 1)) {
            return bad(AxisRule::NotDistinct);
        }
        Ok(axis)
    }

    /// Value `i` (increasing in i).
    pub fn value(&self, i: usize) -> f64 {
        if self.n <= 1 {
            self.from
        } else if i + 1 == self.n {
            self.to
        } else {
            self.from + i as f64 * (self.to - self.from) / (self.n - 1) as f64
        }
    }

    /// All values in order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.n).map(|i| self.value(i)).collect()
    }
}

/// A failed cell: the first in row order.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("cell x = {x}, y = {y}: {error}")]
pub struct MapError<E: std::fmt::Display> {
    /// x value.
    pub x: f64,
    /// y value.
    pub y: f64,
    /// The error.
    pub error: E,
}

/// Runs `f(x, y)` for every cell, in parallel, and returns the results in
/// row order (y outer, x inner). `progress` is told the number of cells,
/// then once per cell done.
pub fn grid_map<T, E, F>(x: &Axis, y: &Axis, progress: &ProgressFn<'_>, f: F) -> Result<Vec<T>, MapError<E>>
where
    F: Fn(f64, f64) -> Result<T, E> + Sync,
    T: Send,
    E: Send + std::fmt::Display,
{
    progress(Progress::Total((x.n * y.n) as u64));
    let results: Vec<Result<T, MapError<E>>> = (0..x.n * y.n)
        .into_par_iter()
        .map(|c| {
            let (xv, yv) = (x.value(c % x.n), y.value(c / x.n));
            let r = f(xv, yv).map_err(|error| MapError { x: xv, y: yv, error });
            progress(Progress::Done);
            r
        })
        .collect();
    results.into_iter().collect()
}

/// One cell of an outcome map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// x value.
    pub x: f64,
    /// y value.
    pub y: f64,
    /// The steady response.
    pub response: Response,
    /// Largest |Θ| over the run, transient included (over the part run,
    /// for a run stopped early); `None` for a cell that inherited its
    /// class without being run.
    pub max_abs_theta: Option<f64>,
    /// Largest Lyapunov exponent per unit τ, when a hook supplied it.
    pub lyapunov: Option<f64>,
    /// The periodic attractor reached, numbered from 1 (basin maps only).
    pub attractor: Option<u32>,
    /// Whether the cell was run (otherwise it inherited its class from a
    /// uniform neighbourhood while the map was refined).
    pub computed: bool,
}

/// What a block outcome map needs.
#[derive(Clone, Copy)]
pub struct BlockMap<'a> {
    /// The scenario the two parameters are set in.
    pub base: &'a Scenario,
    /// The parameter along the horizontal axis.
    pub x_param: Param,
    /// Horizontal axis.
    pub x: &'a Axis,
    /// The parameter along the vertical axis.
    pub y_param: Param,
    /// Vertical axis.
    pub y: &'a Axis,
    /// Transient and end of each run.
    pub window: Window,
    /// Classifier thresholds.
    pub classify: ClassifyOptions,
    /// Largest Lyapunov exponent per configuration, if available (the
    /// cells are then coloured by it on request).
    pub lyapunov: Option<&'a LyapunovFn<'a>>,
}

impl BlockMap<'_> {
    /// The scenario of cell (x, y), validated.
    pub fn scenario(&self, x: f64, y: f64) -> Result<Scenario, SteadyError> {
        Ok(Param::apply(self.base, &[(self.x_param, x), (self.y_param, y)])?)
    }

    /// The response of cell (x, y), its run stopped as soon as its class
    /// is certain when `early`, or on reaching one of the `known` cycles
    /// ([`cell_response`]). The one function every driver of a map runs
    /// per cell, wherever the cell runs.
    pub fn cell(
        &self,
        x: f64,
        y: f64,
        early: bool,
        known: &[Vec<[f64; 3]>],
        basins: Option<BasinLookup<'_>>,
    ) -> Result<CellResponse, SteadyError> {
        let cfg = self.scenario(x, y)?;
        if cfg.stack.is_some() {
            return stack_cell(&cfg, &self.window, &self.classify, self.lyapunov, early);
        }
        cell_response(&cfg, &self.window, &self.classify, self.lyapunov, early, known, basins)
    }

    /// The basin labels `labels` (one per cell, row order: an attractor's
    /// index into the known cycles, or −1) as a run looks its section
    /// points up in them: only for a basin map over Θ₀ × Θ'₀ whose cells
    /// start without slipping (`initial.x_dot` unset), the state a rocking
    /// section point is in ([`settle`](super::settle)).
    pub fn basin_lookup<'b>(&self, labels: &'b [i64]) -> Option<BasinLookup<'b>> {
        let theta_is_x = match (self.x_param, self.y_param) {
            (Param::Theta0, Param::ThetaDot0) => true,
            (Param::ThetaDot0, Param::Theta0) => false,
            _ => return None,
        };
        let (t, d) = if theta_is_x { (self.x, self.y) } else { (self.y, self.x) };
        let ok = self.base.initial.x_dot.is_none() && t.n >= 2 && d.n >= 2 && labels.len() == t.n * d.n;
        ok.then_some(BasinLookup {
            theta: (t.value(0), t.value(t.n - 1), t.n),
            theta_dot: (d.value(0), d.value(d.n - 1), d.n),
            theta_is_x,
            labels,
        })
    }

    /// Makes and checks every cell's scenario before anything runs.
    pub fn check(&self) -> Result<(), MapError<SteadyError>> {
        check_stack_study(self.base, &[self.x_param, self.y_param], false).map_err(|error| MapError {
            x: self.x.value(0),
            y: self.y.value(0),
            error,
        })?;
        for yv in self.y.values() {
            for xv in self.x.values() {
                let cfg = self
                    .scenario(xv, yv)
                    .map_err(|error| MapError { x: xv, y: yv, error })?;
                check_scenario(&cfg, &self.window, &self.classify).map_err(|error| MapError { x: xv, y: yv, error })?;
            }
        }
        Ok(())
    }
}

/// The outcome map of the block, every cell run over its whole window
/// (module docs): [`compute_map`] with [`MapPlan::FULL`].
pub fn block_map(spec: &BlockMap<'_>, progress: &ProgressFn<'_>) -> Result<Vec<Cell>, MapError<SteadyError>> {
    Ok(compute_map(spec, MapPlan::FULL, progress)?.cells)
}

/// How a map is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct MapPlan {
    /// Stop each cell's run as soon as its class is certain
    /// ([`settle`](super::settle)).
    pub early_stop: bool,
    /// Compute a coarse lattice first and then only where classes meet
    /// ([`map_refine`](super::map_refine)): at least this many cells along
    /// the longer axis at the coarse level. `None`: every cell.
    pub coarse: Option<usize>,
}

/// Cells of the coarse level along the longer axis (at least): 32 costs
/// about 1,000 runs whatever the resolution. An island that no lattice
/// cell of a level touches and that no boundary seen at the level above
/// comes near (within the halo) is missed; on the fig3 A_h × Ω_h map at
/// 200 × 200 (a map with many one-cell islands), coarse 32 with halo 2
/// ran 17,530 cells and agreed with `--full` on 99.62 % of the cells,
/// against 18,340 runs and 99.46 % with coarse 64 and halo 1.
pub const COARSE_CELLS: usize = 32;

/// Lattice lines around a cell that must agree before it inherits their
/// class: 2 catches boundaries that bulge between lattice lines and most
/// one-cell islands next to a boundary (see [`COARSE_CELLS`]).
pub(crate) const HALO: usize = 2;

impl MapPlan {
    /// Every cell computed over its whole window: the reference, kept for
    /// checking and for papers (`--full`).
    pub const FULL: Self = Self {
        early_stop: false,
        coarse: None,
    };

    /// The fast plan: early stopping and refinement from
    /// [`COARSE_CELLS`].
    pub const FAST: Self = Self {
        early_stop: true,
        coarse: Some(COARSE_CELLS),
    };
}

/// What a cell is told apart by while a map is refined: its class and,
/// in a basin map, which periodic attractor it reached (discovery number).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Label {
    /// The class; `None` for a cell whose run failed (a class of its own,
    /// so that its neighbours are computed).
    pub response: Option<Response>,
    /// The periodic attractor, in a basin map.
    pub attractor: Option<u32>,
}

/// A whole map, with how it was computed.
#[derive(Clone, Debug, PartialEq)]
pub struct OutcomeMap {
    /// Every cell in row order.
    pub cells: Vec<Cell>,
    /// The periodic attractors of a basin map (none for a parameter map),
    /// numbered as the cells' `attractor`.
    pub attractors: Vec<Attractor>,
    /// Cells whose run was computed (the rest inherited their class).
    pub computed: usize,
    /// Computed cells whose run stopped early.
    pub stopped_early: usize,
    /// Those of them that stopped on reaching an attractor found in
    /// another cell (basin maps).
    pub reached_known: usize,
}

/// A map being computed: hands out batches of cells, takes their results,
/// and puts the map together. The CLI, Python (local and on a Dask
/// cluster) and the app all drive this one engine; they differ only in
/// where a batch's cells run.
pub struct MapRun<'a> {
    spec: BlockMap<'a>,
    plan: MapPlan,
    basin: bool,
    refiner: Option<Refiner<Label>>,
    full_done: bool,
    results: Vec<Option<CellResponse>>,
    labels: Vec<Option<u32>>,
    catalogue: Catalogue,
    /// See [`basin_labels`](Self::basin_labels).
    basin_labels: Option<Vec<i64>>,
}

impl<'a> MapRun<'a> {
    /// A run of `spec` with `plan`. Cells are refined only without
    /// Lyapunov exponents (an inherited cell has none), and attractors are
    /// told apart when both axes are initial-state keys (a basin map: the
    /// same system in every cell).
    pub fn new(spec: BlockMap<'a>, plan: MapPlan) -> Self {
        let basin = spec.x_param.is_initial_state() && spec.y_param.is_initial_state();
        let refiner = match (plan.coarse, spec.lyapunov) {
            (Some(coarse), None) => Some(Refiner::new(spec.x.n, spec.y.n, coarse, HALO)),
            _ => None,
        };
        let n = spec.x.n * spec.y.n;
        Self {
            spec,
            plan,
            basin,
            refiner,
            full_done: false,
            results: vec![None; n],
            labels: vec![None; n],
            catalogue: Catalogue::default(),
            basin_labels: None,
        }
    }

    /// The map's specification.
    pub fn spec(&self) -> &BlockMap<'a> {
        &self.spec
    }

    /// Cells in the map.
    pub fn len(&self) -> usize {
        self.results.len()
    }

    /// Whether the map has no cell (never: an axis has at least one value).
    pub fn is_empty(&self) -> bool {
        self.results.is_empty()
    }

    /// Whether attractors are told apart (a basin map).
    pub fn is_basin(&self) -> bool {
        self.basin
    }

    /// The (x, y) values of cell `index` (row order).
    pub fn xy(&self, index: usize) -> (f64, f64) {
        let nx = self.spec.x.n;
        (self.spec.x.value(index % nx), self.spec.y.value(index / nx))
    }

    /// The next batch of cells to compute (indices, increasing), with the
    /// number of cells that inherited their class on the way; `None` when
    /// the map is complete.
    pub fn next_batch(&mut self) -> Option<(Vec<usize>, usize)> {
        match &mut self.refiner {
            None if self.full_done => None,
            None => {
                self.full_done = true;
                Some(((0..self.results.len()).collect(), 0))
            }
            Some(r) => {
                let before = r.computed() + r.inherited();
                let todo = r.next_level()?;
                let inherited = r.computed() + r.inherited() - before;
                if self.basin && self.plan.early_stop {
                    let labels = (0..self.results.len())
                        .map(|i| r.class(i).and_then(|l| l.attractor).map_or(-1, i64::from))
                        .collect();
                    self.basin_labels = Some(labels);
                }
                Some((todo, inherited))
            }
        }
    }

    /// Computes cell `index` (any thread; pure): its run stops on
    /// reaching one of the [`known`](Self::known) attractors too.
    pub fn compute(&self, index: usize) -> Result<CellResponse, SteadyError> {
        let (x, y) = self.xy(index);
        let basins = self.basin_labels.as_deref().and_then(|l| self.spec.basin_lookup(l));
        self.spec.cell(x, y, self.plan.early_stop, self.known(), basins)
    }

    /// Per cell, the attractor (index into [`known`](Self::known)) its
    /// label is at the levels before the batch last handed out (computed
    /// or inherited), −1 where none: what a run of a basin map with
    /// refinement and early stopping looks its section points up in
    /// ([`BlockMap::basin_lookup`]); `None` for other maps.
    pub fn basin_labels(&self) -> Option<&[i64]> {
        self.basin_labels.as_deref()
    }

    /// The cycles a cell's run may stop on reaching: in a basin map with
    /// early stopping, the periodic attractors found at the levels
    /// recorded so far (fixed while a batch runs, so a cell's result does
    /// not depend on the order or the threads the batch runs on); none
    /// otherwise.
    pub fn known(&self) -> &[Vec<[f64; 3]>] {
        if self.basin && self.plan.early_stop {
            self.catalogue.cycles()
        } else {
            &[]
        }
    }

    /// Records a batch's results (in any order); attractors are identified
    /// in index order, so the numbering does not depend on the order.
    pub fn record(&mut self, mut batch: Vec<(usize, CellResponse)>) {
        batch.sort_by_key(|(i, _)| *i);
        for (index, cell) in batch {
            let attractor = match (self.basin, cell.response) {
                (true, Response::Periodic { period }) => {
                    let k = period as usize;
                    Some(self.catalogue.identify(&cell.cycle[cell.cycle.len() - k..]))
                }
                _ => None,
            };
            self.labels[index] = attractor;
            if let Some(r) = &mut self.refiner {
                r.record(
                    index,
                    Label {
                        response: Some(cell.response),
                        attractor,
                    },
                );
            }
            self.results[index] = Some(cell);
        }
    }

    /// The class of cell `index` so far (computed or inherited).
    pub fn label(&self, index: usize) -> Option<Label> {
        match &self.refiner {
            Some(r) => r.class(index),
            None => self.results[index].as_ref().map(|c| Label {
                response: Some(c.response),
                attractor: self.labels[index],
            }),
        }
    }

    /// Records that cell `index` could not be computed (the app shows such
    /// cells and goes on; the CLI stops at the first).
    pub fn record_failed(&mut self, index: usize) {
        if let Some(r) = &mut self.refiner {
            r.record(
                index,
                Label {
                    response: None,
                    attractor: None,
                },
            );
        }
    }

    /// The attractors found so far, numbered as [`finish`](Self::finish)
    /// would number them from the cells known so far (by first cell in row
    /// order), and the number of each discovery number (a [`Label`]'s
    /// `attractor`, index into the second vector). After the last batch
    /// these are `finish`'s attractors. Empty for a parameter map.
    pub fn attractors(&self) -> (Vec<Attractor>, Vec<u32>) {
        let labels: Vec<Option<u32>> = (0..self.results.len())
            .map(|index| self.label(index).and_then(|l| l.attractor))
            .collect();
        self.catalogue.numbered(&labels)
    }

    /// Lattice stride of the batch last handed out (1 when every cell is
    /// computed at once).
    pub fn stride(&self) -> usize {
        self.refiner.as_ref().and_then(Refiner::stride).unwrap_or(1)
    }

    /// The refinement state, for a view that draws the map as it fills
    /// (`None` when every cell is computed at once).
    pub fn refiner(&self) -> Option<&Refiner<Label>> {
        self.refiner.as_ref()
    }

    /// The finished map. Cells never computed nor inherited (a map whose
    /// batches were not all recorded) are an error naming the first.
    pub fn finish(self) -> Result<OutcomeMap, MapError<SteadyError>> {
        let mut labels = Vec::with_capacity(self.results.len());
        let mut classes = Vec::with_capacity(self.results.len());
        for index in 0..self.results.len() {
            let Some(Label {
                response: Some(response),
                attractor,
            }) = self.label(index)
            else {
                let (x, y) = self.xy(index);
                return Err(MapError {
                    x,
                    y,
                    error: SteadyError::Unfinished,
                });
            };
            labels.push(attractor);
            classes.push(response);
        }
        let (attractors, ids) = self.catalogue.numbered(&labels);
        let mut computed = 0;
        let mut stopped_early = 0;
        let mut reached_known = 0;
        let cells = (0..self.results.len())
            .map(|index| {
                let (x, y) = self.xy(index);
                let result = self.results[index].as_ref();
                computed += usize::from(result.is_some());
                stopped_early += usize::from(result.is_some_and(|c| c.stopped_at.is_some()));
                reached_known += usize::from(result.is_some_and(|c| c.reached_known));
                Cell {
                    x,
                    y,
                    response: classes[index],
                    max_abs_theta: result.map(|c| c.max_abs_theta),
                    lyapunov: result.and_then(|c| c.lyapunov),
                    attractor: labels[index].map(|l| ids[l as usize]),
                    computed: result.is_some(),
                }
            })
            .collect();
        Ok(OutcomeMap {
            cells,
            attractors,
            computed,
            stopped_early,
            reached_known,
        })
    }
}

/// Computes the map of `spec` with `plan` on the current rayon pool.
/// `progress` is told the number of cells, then once per cell computed
/// or inherited. The result is the same for any number of threads.
pub fn compute_map(
    spec: &BlockMap<'_>,
    plan: MapPlan,
    progress: &ProgressFn<'_>,
) -> Result<OutcomeMap, MapError<SteadyError>> {
    spec.check()?;
    let mut run = MapRun::new(*spec, plan);
    progress(Progress::Total(run.len() as u64));
    while let Some((cells, inherited)) = run.next_batch() {
        for _ in 0..inherited {
            progress(Progress::Done);
        }
        let results: Vec<Result<(usize, CellResponse), MapError<SteadyError>>> = cells
            .par_iter()
            .map(|&index| {
                let r = run.compute(index).map(|c| (index, c)).map_err(|error| {
                    let (x, y) = run.xy(index);
                    MapError { x, y, error }
                });
                progress(Progress::Done);
                r
            })
            .collect();
        let batch = results.into_iter().collect::<Result<Vec<_>, _>>()?;
        run.record(batch);
    }
    run.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_end_exactly_at_to() {
        let a = Axis::new("x", "excitation.a_h", 0.1, 0.7, 7).unwrap();
        assert_eq!(a.value(6), 0.7);
        assert_eq!(a.value(0), 0.1);
        assert_eq!(a.values().len(), 7);
        assert_eq!(Axis::new("x", "k", 2.0, 5.0, 1).unwrap().values(), vec![2.0]);
        let rule = |e: PlanError| match e {
            PlanError::Axis { rule, .. } => rule,
            other => panic!("not an axis error: {other}"),
        };
        assert_eq!(rule(Axis::new("y", "k", 1.0, 1.0, 3).unwrap_err()), AxisRule::Order);
        assert_eq!(
            rule(Axis::new("x", "k", 0.0, 1.0, 0).unwrap_err()),
            AxisRule::Count(MAX_AXIS_POINTS)
        );
        assert_eq!(
            rule(Axis::new("x", "k", f64::INFINITY, 1.0, 2).unwrap_err()),
            AxisRule::NotFinite
        );
        // 1 and its successor: no room for a third value between them.
        let next = f64::from_bits(1f64.to_bits() + 1);
        assert_eq!(
            rule(Axis::new("x", "k", 1.0, next, 3).unwrap_err()),
            AxisRule::NotDistinct
        );
        // The caller's name for the axis, then the axis as given.
        assert_eq!(
            Axis::new("y", "k", 1.0, 1.0, 3).unwrap_err().to_string(),
            "y k 1 1 3: A must be < B when N > 1"
        );
    }

    #[test]
    fn grid_map_is_row_major_and_reports_the_first_failure() {
        let x = Axis::new("x", "a", 0.0, 2.0, 3).unwrap();
        let y = Axis::new("y", "b", 10.0, 20.0, 2).unwrap();
        let cells = grid_map(&x, &y, &super::super::silent, |a, b| Ok::<_, String>((a, b))).unwrap();
        assert_eq!(
            cells,
            vec![
                (0.0, 10.0),
                (1.0, 10.0),
                (2.0, 10.0),
                (0.0, 20.0),
                (1.0, 20.0),
                (2.0, 20.0)
            ]
        );
        let e = grid_map(&x, &y, &super::super::silent, |a, b| {
            if a >= 1.0 && b > 15.0 { Err("no") } else { Ok(()) }
        })
        .unwrap_err();
        assert_eq!((e.x, e.y), (1.0, 20.0));
    }
}
