//! Bifurcation (orbit) diagrams: sweep one parameter over a grid, and for
//! each value collect the Poincaré points after a transient and classify
//! the response.
//!
//! The machinery is generic: [`sweep`] runs any closure
//! `value, seed → (result, next seed)` over a [`Plan`], so it is tested on
//! the logistic map as well as used on the block ([`block_sweep`]).
//!
//! Every sweep documents, in its [`Plan`] and the block's
//! [`Window`]:
//! - **values**: `from + i·step` for i = 0, 1, … while the value is below
//!   `to` plus half a step (so `to` is included despite rounding), computed
//!   from i, never accumulated, and exact on the decimal grid the user
//!   typed: with `from` 0 and `step` 0.1 the value "0.3" is the double
//!   nearest 0.3 (what `--set …=0.3` runs), not 3 × 0.1 =
//!   0.30000000000000004;
//! - **transient and samples**: for the block, section points at
//!   τ_k = 2πk/Ω_h with transient ≤ τ_k ≤ tau_end (the paper: 600–800);
//! - **seeding**: without continuation every value starts from the
//!   configuration's own initial state (the paper: from rest), and values
//!   run in parallel on the current rayon pool, results collected by index,
//!   so the output is bit-identical for any number of threads. With
//!   continuation (`up` or `down`) each value starts from the previous
//!   value's last section point (excitation phase 0, so the restart at
//!   τ = 0 is in phase; exact when Ω_v is a multiple of Ω_h), which follows
//!   one attractor through hysteresis; the values are then necessarily
//!   computed one after another, in increasing (`up`) or decreasing
//!   (`down`) order. After a tumbled or flight value, the next value starts
//!   again from the configuration's initial state;
//! - **sharding**: `Shard { index: K, count: N }` computes the values whose
//!   index i satisfies i mod N = K, K counted from 0 (as Slurm's
//!   `--array=0-(N-1)` numbers its tasks). Shards cannot be combined with
//!   continuation, whose values depend on each other.
//!
//! Results are always returned in increasing index (value) order, whatever
//! the direction of computation.

use rayon::prelude::*;

use super::classify::{ClassifyOptions, Response};
use super::field::{FieldNames, OwnNames, StudyField};
use super::steady::{LyapunovFn, SteadyError, Window, check_scenario, check_stack_study, steady_response};
use super::{Progress, ProgressFn};
use crate::sim::{InitialState, Param, Scenario, SectionRow};

/// Most values one sweep may have (a guard against a step typed too small).
pub(crate) const MAX_VALUES: usize = 10_000_000;

/// The values of a sweep: `from + i·step` for every i with
/// `from + i·step < to + step/2`, so `to` is included despite rounding (and
/// a last value less than half a step beyond `to` is too).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Grid {
    /// First value.
    pub from: f64,
    /// Last value (included within half a step).
    pub to: f64,
    /// Spacing, > 0.
    pub step: f64,
    /// Number of values.
    pub count: usize,
    /// `from` and `step` as integers over 10^places, when both are short
    /// decimals (as typed): the values are then computed in decimal.
    #[serde(skip)]
    decimal: Option<Decimal>,
}

/// `from` = `first`·10^−places and `step` = `step`·10^−places exactly as
/// decimals (their shortest round-trip forms).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Decimal {
    first: i128,
    step: i128,
    places: usize,
}

/// Most decimal places a grid is computed in: beyond it the values are
/// `from + i·step` in binary (a step like 1/3 has no short decimal form).
const MAX_PLACES: usize = 15;

impl Decimal {
    /// The decimal form of `from` and `step` with the fewest places that
    /// both round-trip, if there is one within [`MAX_PLACES`] and the
    /// integers stay well inside i128.
    fn of(from: f64, step: f64) -> Option<Self> {
        let places = (0..=MAX_PLACES).find(|&d| {
            let round_trips = |x: f64| format!("{x:.d$}").parse::<f64>().ok() == Some(x);
            round_trips(from) && round_trips(step)
        })?;
        let scaled = |x: f64| -> Option<i128> {
            let text = format!("{x:.places$}").replace('.', "");
            text.parse::<i128>().ok().filter(|n| n.unsigned_abs() < 1u128 << 100)
        };
        Some(Self {
            first: scaled(from)?,
            step: scaled(step)?,
            places,
        })
    }

    /// Value `i`: the double nearest the decimal (first + i·step)·10^−places.
    fn value(&self, i: usize) -> f64 {
        let n = self.first + i as i128 * self.step;
        format!("{n}e-{}", self.places).parse().unwrap_or(f64::NAN)
    }
}

/// Errors in a sweep's or map's definition, naming the input at fault by
/// meaning ([`StudyField`], or the caller's name of a map axis);
/// [`PlanError::render`] words them for a surface.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.render(&OwnNames))]
pub enum PlanError {
    /// A grid value is not allowed.
    Grid {
        /// `From`, `To` or `Step`.
        field: StudyField,
        /// Its value.
        value: f64,
        /// What is wrong with it.
        rule: GridRule,
    },
    /// A shard that is not `K/N` with 0 ≤ K < N.
    Shard {
        /// The shard as given.
        text: String,
        /// What is wrong with it.
        rule: ShardRule,
    },
    /// A map axis that is not allowed.
    Axis {
        /// The axis as its caller names it (the CLI `--x`, Python `x`).
        name: String,
        /// Its key, first and last value and count, as given.
        given: String,
        /// What is wrong with it.
        rule: AxisRule,
    },
    /// Shards of a continuation sweep, whose values depend on each other.
    ShardedContinuation(Continuation),
}

/// Why a [`Grid`] value is refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GridRule {
    /// Not finite.
    NotFinite,
    /// The step is not finite or not > 0.
    NotPositive,
    /// `to` is below `from` (the value here).
    BelowFrom(f64),
    /// The step gives more than [`MAX_VALUES`] values.
    TooMany,
    /// The step is below the values' resolution: values `index − 1` and
    /// `index` are both `value`.
    BelowResolution {
        /// The later of the two equal values' index.
        index: usize,
        /// Their value.
        value: f64,
    },
}

/// Why a [`Shard`] is refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShardRule {
    /// No `/`.
    NotKOverN,
    /// K or N is not a non-negative integer.
    NotIntegers,
    /// N = 0.
    NoShards,
    /// K ≥ N (the N here).
    IndexTooLarge(usize),
}

/// Why a map axis is refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisRule {
    /// A or B is not finite.
    NotFinite,
    /// N is 0 or above the most points an axis takes (given).
    Count(usize),
    /// A ≥ B with N > 1.
    Order,
    /// A and B too close for N distinct values.
    NotDistinct,
}

impl PlanError {
    /// The one-line message with the inputs named by `names`.
    pub fn render(&self, names: &impl FieldNames) -> String {
        match self {
            PlanError::Grid { field, value, rule } => {
                // Debug formatting: 1.5e-16 as written, not as 0.00000000000000015.
                let given = names.valued(*field, &format!("{value:?}"));
                let what = match *rule {
                    GridRule::NotFinite => "must be finite".to_string(),
                    GridRule::NotPositive => "must be finite and > 0".to_string(),
                    GridRule::BelowFrom(from) => {
                        format!("must be >= {}", names.valued(StudyField::From, &from.to_string()))
                    }
                    GridRule::TooMany => format!("gives more than {MAX_VALUES} values"),
                    GridRule::BelowResolution { index, value } => format!(
                        "is below the resolution of the values near {value:?}: values {} and {index} are both {value:?}",
                        index.saturating_sub(1)
                    ),
                };
                format!("{given}: {what}")
            }
            PlanError::Shard { text, rule } => {
                let what = match *rule {
                    ShardRule::NotKOverN => "expected K/N, e.g. 0/4 (K counts from 0)".to_string(),
                    ShardRule::NotIntegers => "expected K/N with non-negative integers, e.g. 0/4".to_string(),
                    ShardRule::NoShards => "N must be >= 1".to_string(),
                    ShardRule::IndexTooLarge(count) => {
                        format!("K must be < N (K counts from 0: 0..={})", count.saturating_sub(1))
                    }
                };
                format!("{}: {what}", names.valued(StudyField::Shard, text))
            }
            PlanError::Axis { name, given, rule } => {
                let what = match rule {
                    AxisRule::NotFinite => "A and B must be finite".to_string(),
                    AxisRule::Count(max) => format!("N must be in 1..={max}"),
                    AxisRule::Order => "A must be < B when N > 1".to_string(),
                    AxisRule::NotDistinct => "the values must be distinct (A and B too close for N points)".to_string(),
                };
                format!("{name} {given}: {what}")
            }
            PlanError::ShardedContinuation(c) => format!(
                "{} cannot be combined with {}: each value is seeded from the previous one, so the values cannot be split",
                names.name(StudyField::Shard),
                names.valued(StudyField::Continuation, c.name())
            ),
        }
    }
}

impl Grid {
    /// Validates and counts the values.
    pub fn new(from: f64, to: f64, step: f64) -> Result<Self, PlanError> {
        let bad = |field, value, rule| Err(PlanError::Grid { field, value, rule });
        if !from.is_finite() {
            return bad(StudyField::From, from, GridRule::NotFinite);
        }
        if !to.is_finite() {
            return bad(StudyField::To, to, GridRule::NotFinite);
        }
        if !step.is_finite() || step <= 0.0 {
            return bad(StudyField::Step, step, GridRule::NotPositive);
        }
        if to < from {
            return bad(StudyField::To, to, GridRule::BelowFrom(from));
        }
        // The last index is the largest i with from + i·step < to + step/2.
        let n = ((to - from) / step - 0.5).ceil().max(0.0);
        if n.partial_cmp(&(MAX_VALUES as f64)) != Some(std::cmp::Ordering::Less) {
            return bad(StudyField::Step, step, GridRule::TooMany);
        }
        let count = n as usize + 1;
        let grid = Self {
            from,
            to,
            step,
            count,
            decimal: Decimal::of(from, step),
        };
        // Distinct values are needed to tell them apart in the outputs: every
        // value must exceed the one before it once rounded to an f64 (a step
        // near the values' resolution rounds some pairs together).
        if let Some(index) = (1..count).find(|&i| grid.value(i) <= grid.value(i - 1)) {
            let value = grid.value(index);
            return bad(StudyField::Step, step, GridRule::BelowResolution { index, value });
        }
        Ok(grid)
    }

    /// Value `i`: `from + i·step`, on the typed decimal grid when there is
    /// one (module docs).
    pub fn value(&self, i: usize) -> f64 {
        match self.decimal {
            Some(d) => d.value(i),
            None => self.from + i as f64 * self.step,
        }
    }

    /// All values in order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.count).map(|i| self.value(i)).collect()
    }
}

/// How each value is seeded (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Continuation {
    /// Every value from the configuration's initial state, in parallel.
    None,
    /// Each value from the previous (smaller) value's final section state.
    Up,
    /// Each value from the previous (larger) value's final section state.
    Down,
}

impl Continuation {
    /// Name used on the command line and in `sweep.json`.
    pub fn name(self) -> &'static str {
        match self {
            Continuation::None => "none",
            Continuation::Up => "up",
            Continuation::Down => "down",
        }
    }
}

/// One shard of a sweep: the values with index ≡ `index` (mod `count`),
/// `index` counted from 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shard {
    /// K, 0 ≤ K < N.
    pub index: usize,
    /// N ≥ 1.
    pub count: usize,
}

impl Shard {
    /// Parses `K/N` (0 ≤ K < N).
    pub fn parse(text: &str) -> Result<Self, PlanError> {
        let bad = |rule| {
            Err(PlanError::Shard {
                text: text.to_string(),
                rule,
            })
        };
        let Some((k, n)) = text.split_once('/') else {
            return bad(ShardRule::NotKOverN);
        };
        let (Ok(index), Ok(count)) = (k.trim().parse::<usize>(), n.trim().parse::<usize>()) else {
            return bad(ShardRule::NotIntegers);
        };
        if count == 0 {
            return bad(ShardRule::NoShards);
        }
        if index >= count {
            return bad(ShardRule::IndexTooLarge(count));
        }
        Ok(Self { index, count })
    }
}

/// What a sweep computes: its values, seeding and shard.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Plan {
    /// The values.
    pub grid: Grid,
    /// Seeding.
    pub continuation: Continuation,
    /// Only this shard's values, if set.
    pub shard: Option<Shard>,
}

impl Plan {
    /// A plan; sharding a continuation sweep is an error.
    pub fn new(grid: Grid, continuation: Continuation, shard: Option<Shard>) -> Result<Self, PlanError> {
        if shard.is_some() && continuation != Continuation::None {
            return Err(PlanError::ShardedContinuation(continuation));
        }
        Ok(Self {
            grid,
            continuation,
            shard,
        })
    }

    /// The indices this plan computes, increasing.
    pub fn indices(&self) -> Vec<usize> {
        match self.shard {
            None => (0..self.grid.count).collect(),
            Some(s) => (s.index..self.grid.count).step_by(s.count).collect(),
        }
    }
}

/// One computed value of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Computed<T> {
    /// Index in the grid.
    pub index: usize,
    /// The value.
    pub value: f64,
    /// What the closure returned for it.
    pub result: T,
}

/// A failed value of a sweep: the first failure in index order (or in
/// computation order with continuation).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("value {value}: {error}")]
pub struct SweepError<E: std::fmt::Display> {
    /// Index in the grid.
    pub index: usize,
    /// The value.
    pub value: f64,
    /// The closure's error.
    pub error: E,
}

/// Runs `f(value, seed)` for every value of `plan` and returns the results in
/// increasing index order. `f` returns its result and the seed for the next
/// value (used only with continuation). `progress` is told the number of
/// values first, then once per value done (pass [`super::silent`] for
/// nothing).
pub fn sweep<T, S, E, F>(plan: &Plan, progress: &ProgressFn<'_>, f: F) -> Result<Vec<Computed<T>>, SweepError<E>>
where
    F: Fn(f64, Option<&S>) -> Result<(T, Option<S>), E> + Sync,
    T: Send,
    S: Send,
    E: Send + std::fmt::Display,
{
    let indices = plan.indices();
    progress(Progress::Total(indices.len() as u64));
    let grid = plan.grid;
    let run_one = |i: usize, seed: Option<&S>| {
        let value = grid.value(i);
        let out = f(value, seed).map_err(|error| SweepError { index: i, value, error });
        progress(Progress::Done);
        out.map(|(result, next)| {
            (
                Computed {
                    index: i,
                    value,
                    result,
                },
                next,
            )
        })
    };
    match plan.continuation {
        Continuation::None => {
            let results: Vec<_> = indices.par_iter().map(|&i| run_one(i, None)).collect();
            results.into_iter().map(|r| r.map(|(c, _)| c)).collect()
        }
        Continuation::Up | Continuation::Down => {
            let mut order = indices;
            if plan.continuation == Continuation::Down {
                order.reverse();
            }
            let mut out = Vec::with_capacity(order.len());
            let mut seed: Option<S> = None;
            for i in order {
                let (c, next) = run_one(i, seed.as_ref())?;
                seed = next;
                out.push(c);
            }
            if plan.continuation == Continuation::Down {
                out.reverse();
            }
            Ok(out)
        }
    }
}

/// A run of consecutive values with the same response, for summaries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResponseRange {
    /// First value of the run.
    pub from: f64,
    /// Last value of the run.
    pub to: f64,
    /// Its response.
    pub response: Response,
}

/// Groups consecutive `(value, response)` pairs with equal responses.
pub(crate) fn response_ranges(values: &[(f64, Response)]) -> Vec<ResponseRange> {
    let mut out: Vec<ResponseRange> = Vec::new();
    for &(value, response) in values {
        match out.last_mut() {
            Some(last) if last.response == response => last.to = value,
            _ => out.push(ResponseRange {
                from: value,
                to: value,
                response,
            }),
        }
    }
    out
}

/// One value of a block's bifurcation diagram.
#[derive(Clone, Debug, PartialEq)]
pub struct BifurcationValue {
    /// The parameter value.
    pub value: f64,
    /// The steady response.
    pub response: Response,
    /// Largest |Θ| over the run, transient included.
    pub max_abs_theta: f64,
    /// Largest Lyapunov exponent per unit τ, when available.
    pub lyapunov: Option<f64>,
    /// Section points after the transient (none for tumbled or flight).
    pub points: Vec<SectionRow>,
}

/// What a block sweep needs besides its plan.
#[derive(Clone, Copy)]
pub struct BlockSweep<'a> {
    /// The scenario the parameter is set in.
    pub base: &'a Scenario,
    /// The parameter swept.
    pub param: Param,
    /// Transient and end of each run.
    pub window: Window,
    /// Classifier thresholds.
    pub classify: ClassifyOptions,
    /// Largest Lyapunov exponent per scenario, if available.
    pub lyapunov: Option<&'a LyapunovFn<'a>>,
}

impl BlockSweep<'_> {
    /// The scenario of `value`, validated.
    pub fn scenario(&self, value: f64) -> Result<Scenario, SteadyError> {
        Ok(Param::apply(self.base, &[(self.param, value)])?)
    }

    /// Makes and checks every value's scenario before anything runs, so
    /// that an out-of-range value, a non-harmonic excitation or a window
    /// too short is reported at once.
    pub fn scenarios(&self, plan: &Plan) -> Result<Vec<Scenario>, SweepError<SteadyError>> {
        let continued = plan.continuation != Continuation::None;
        check_stack_study(self.base, &[self.param], continued).map_err(|error| SweepError {
            index: 0,
            value: plan.grid.value(0),
            error,
        })?;
        plan.indices()
            .into_iter()
            .map(|i| {
                let value = plan.grid.value(i);
                let fail = |error| SweepError { index: i, value, error };
                let s = self.scenario(value).map_err(fail)?;
                check_scenario(&s, &self.window, &self.classify).map_err(fail)?;
                Ok(s)
            })
            .collect()
    }
}

/// The bifurcation diagram of the block over `plan` (module docs).
pub fn block_sweep(
    spec: &BlockSweep<'_>,
    plan: &Plan,
    progress: &ProgressFn<'_>,
) -> Result<Vec<BifurcationValue>, SweepError<SteadyError>> {
    spec.scenarios(plan)?;
    let computed = sweep(plan, progress, |value, seed: Option<&InitialState>| {
        let cfg = spec.scenario(value)?;
        let cfg = match seed {
            Some(s) => cfg.seeded(s),
            None => cfg,
        };
        let s = steady_response(&cfg, &spec.window, &spec.classify, spec.lyapunov)?;
        let next = s.seed;
        Ok((
            BifurcationValue {
                value,
                response: s.response,
                max_abs_theta: s.max_abs_theta,
                lyapunov: s.lyapunov,
                points: s.points,
            },
            next,
        ))
    })?;
    Ok(computed.into_iter().map(|c| c.result).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_includes_to_within_half_a_step() {
        let g = Grid::new(0.0, 3.0, 0.02).unwrap();
        assert_eq!(g.count, 151);
        assert_eq!(g.value(150), 150.0 * 0.02);
        assert_eq!(Grid::new(0.0, 1.0, 0.3).unwrap().count, 4);
        // Exactly half a step beyond `to` is out; less than half a step is in.
        assert_eq!(Grid::new(0.0, 1.0, 0.4).unwrap().count, 3);
        assert_eq!(Grid::new(0.0, 1.0, 0.6).unwrap().count, 3);
        assert_eq!(Grid::new(0.0, 0.3, 1.0).unwrap().count, 1);
        assert_eq!(Grid::new(1.0, 1.0, 0.5).unwrap().count, 1);
        let field = |e: PlanError| match e {
            PlanError::Grid { field, rule, .. } => (field, rule),
            other => panic!("not a grid error: {other}"),
        };
        assert_eq!(
            field(Grid::new(0.0, 1.0, 0.0).unwrap_err()),
            (StudyField::Step, GridRule::NotPositive)
        );
        assert_eq!(
            field(Grid::new(1.0, 0.0, 0.1).unwrap_err()),
            (StudyField::To, GridRule::BelowFrom(1.0))
        );
        assert_eq!(
            field(Grid::new(f64::NAN, 0.0, 0.1).unwrap_err()),
            (StudyField::From, GridRule::NotFinite)
        );
        // (2e20 − 1e20)/1 = 1e20 values, far above MAX_VALUES.
        assert!(1e20 > MAX_VALUES as f64);
        assert_eq!(
            field(Grid::new(1e20, 2e20, 1.0).unwrap_err()),
            (StudyField::Step, GridRule::TooMany)
        );
        assert_eq!(
            Grid::new(1.0, 0.0, 0.1).unwrap_err().to_string(),
            "to = 0.0: must be >= from = 1"
        );
    }

    #[test]
    fn values_lie_on_the_typed_decimal_grid() {
        let g = Grid::new(0.0, 3.0, 0.02).unwrap();
        // 115 × 0.02 = 2.3000000000000003 in binary; the typed grid means 2.3.
        assert_eq!(g.value(115), 2.3);
        assert_ne!(115.0 * 0.02, 2.3);
        let g = Grid::new(-1.25, 1.0, 0.05).unwrap();
        assert_eq!(g.value(0), -1.25);
        assert_eq!(g.value(31), 0.3);
        assert_eq!(g.value(g.count - 1), 1.0);
        // No short decimal form: the binary values, still from i.
        let third = 1.0 / 3.0;
        let g = Grid::new(0.0, 1.0, third).unwrap();
        assert_eq!(g.value(2), 2.0 * third);
    }

    #[test]
    fn shards_partition_the_indices() {
        let g = Grid::new(0.0, 1.0, 0.1).unwrap();
        let mut all: Vec<usize> = (0..3)
            .flat_map(|k| {
                Plan::new(g, Continuation::None, Some(Shard { index: k, count: 3 }))
                    .unwrap()
                    .indices()
            })
            .collect();
        all.sort_unstable();
        assert_eq!(all, (0..11).collect::<Vec<_>>());
        assert_eq!(Shard::parse("1/4").unwrap(), Shard { index: 1, count: 4 });
        for (bad, rule) in [
            ("4/4", ShardRule::IndexTooLarge(4)),
            ("1", ShardRule::NotKOverN),
            ("a/2", ShardRule::NotIntegers),
            ("0/0", ShardRule::NoShards),
            ("-1/3", ShardRule::NotIntegers),
        ] {
            assert_eq!(
                Shard::parse(bad),
                Err(PlanError::Shard {
                    text: bad.to_string(),
                    rule
                }),
                "{bad}"
            );
        }
        assert_eq!(
            Plan::new(g, Continuation::Up, Some(Shard { index: 0, count: 2 })),
            Err(PlanError::ShardedContinuation(Continuation::Up))
        );
    }

    #[test]
    fn continuation_passes_seeds_in_sweep_order() {
        let g = Grid::new(0.0, 4.0, 1.0).unwrap();
        let bar = super::super::silent;
        let f = |v: f64, seed: Option<&Vec<f64>>| -> Result<(Vec<f64>, Option<Vec<f64>>), String> {
            let mut seen = seed.cloned().unwrap_or_default();
            seen.push(v);
            Ok((seen.clone(), Some(seen)))
        };
        let up = sweep(&Plan::new(g, Continuation::Up, None).unwrap(), &bar, f).unwrap();
        assert_eq!(up[4].result, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
        let down = sweep(&Plan::new(g, Continuation::Down, None).unwrap(), &bar, f).unwrap();
        assert_eq!(down[0].result, vec![4.0, 3.0, 2.0, 1.0, 0.0]);
        assert_eq!(down.iter().map(|c| c.index).collect::<Vec<_>>(), vec![0, 1, 2, 3, 4]);
        let none = sweep(&Plan::new(g, Continuation::None, None).unwrap(), &bar, f).unwrap();
        assert_eq!(none[3].result, vec![3.0]);
    }

    #[test]
    fn the_first_failure_in_index_order_is_reported() {
        let g = Grid::new(0.0, 9.0, 1.0).unwrap();
        let plan = Plan::new(g, Continuation::None, None).unwrap();
        let e = sweep(&plan, &super::super::silent, |v, _: Option<&()>| {
            if v >= 3.0 {
                Err(format!("bad {v}"))
            } else {
                Ok(((), None))
            }
        })
        .unwrap_err();
        assert_eq!((e.index, e.error.as_str()), (3, "bad 3"));
        assert_eq!(e.to_string(), "value 3: bad 3");
    }

    #[test]
    fn ranges_group_equal_neighbours() {
        let p1 = Response::Periodic { period: 1 };
        let p2 = Response::Periodic { period: 2 };
        let r = response_ranges(&[(0.0, p1), (0.1, p1), (0.2, p2), (0.3, Response::Tumbled), (0.4, p2)]);
        assert_eq!(r.len(), 4);
        assert_eq!((r[0].from, r[0].to, r[0].response), (0.0, 0.1, p1));
        assert_eq!((r[3].from, r[3].to), (0.4, 0.4));
    }
}
