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

use super::classify::{ClassifyOptions, Response};
use super::orbit_diagram::PlanError;
use super::steady::{LyapunovFn, SteadyError, Window, check_scenario, steady_response};
use super::{Progress, ProgressFn};
use crate::sim::{Param, Scenario};

/// Most points on one axis (a guard against a typo; 10⁴ × 10⁴ cells would
/// take weeks anyway).
pub const MAX_AXIS_POINTS: usize = 10_000;

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
    /// Validates an axis; errors name `flag` (e.g. `--x`).
    pub fn new(flag: &str, key: &str, from: f64, to: f64, n: usize) -> Result<Self, PlanError> {
        let bad = |what: String| Err(PlanError::flag(flag, format!("{key} {from} {to} {n}"), what));
        if !from.is_finite() || !to.is_finite() {
            return bad("A and B must be finite".into());
        }
        if n == 0 || n > MAX_AXIS_POINTS {
            return bad(format!("N must be in 1..={MAX_AXIS_POINTS}"));
        }
        let axis = Self {
            key: key.to_string(),
            from,
            to,
            n,
        };
        if n > 1 && from >= to {
            return bad("A must be < B when N > 1".into());
        }
        if n > 1 && (0..n - 1).any(|i| axis.value(i) >= axis.value(i + 1)) {
            return bad("the values must be distinct (A and B too close for N points)".into());
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
    /// Largest |Θ| over the run, transient included.
    pub max_abs_theta: f64,
    /// Largest Lyapunov exponent per unit τ, when a hook supplied it.
    pub lyapunov: Option<f64>,
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

    /// Makes and checks every cell's scenario before anything runs.
    pub fn check(&self) -> Result<(), MapError<SteadyError>> {
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

/// The outcome map of the block (module docs).
pub fn block_map(spec: &BlockMap<'_>, progress: &ProgressFn<'_>) -> Result<Vec<Cell>, MapError<SteadyError>> {
    spec.check()?;
    grid_map(spec.x, spec.y, progress, |x, y| {
        let cfg = spec.scenario(x, y)?;
        let s = steady_response(&cfg, &spec.window, &spec.classify, spec.lyapunov)?;
        Ok(Cell {
            x,
            y,
            response: s.response,
            max_abs_theta: s.max_abs_theta,
            lyapunov: s.lyapunov,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_end_exactly_at_to() {
        let a = Axis::new("--x", "excitation.a_h", 0.1, 0.7, 7).unwrap();
        assert_eq!(a.value(6), 0.7);
        assert_eq!(a.value(0), 0.1);
        assert_eq!(a.values().len(), 7);
        assert_eq!(Axis::new("--x", "k", 2.0, 5.0, 1).unwrap().values(), vec![2.0]);
        assert!(
            Axis::new("--y", "k", 1.0, 1.0, 3)
                .unwrap_err()
                .to_string()
                .starts_with("--y k")
        );
        assert!(Axis::new("--x", "k", 0.0, 1.0, 0).is_err());
        assert!(Axis::new("--x", "k", f64::INFINITY, 1.0, 2).is_err());
    }

    #[test]
    fn grid_map_is_row_major_and_reports_the_first_failure() {
        let x = Axis::new("--x", "a", 0.0, 2.0, 3).unwrap();
        let y = Axis::new("--y", "b", 10.0, 20.0, 2).unwrap();
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
