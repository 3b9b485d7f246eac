//! The smallest amplitude that overturns a block, and the safe windows
//! above it.
//!
//! Overturning is not monotonic in amplitude: a block that overturns at
//! one scale of a record may survive a larger one (the overturning maps of
//! Makris & Roussos 2000 show such safe regions above the first boundary).
//! So the search never assumes monotonicity: it evaluates a grid of
//! amplitudes stepping up from zero, finds every change between safe and
//! failed along it, and refines each change by bisection to a relative
//! tolerance. Changes narrower than a grid step can be missed; the grid
//! step is the resolution, and it is written beside every result.
//!
//! Amplitude 0 is safe by definition (no motion). Grid points and
//! bisections of different changes are independent and run in parallel
//! (rayon); results are collected by index, so they do not depend on the
//! number of threads.

use rayon::prelude::*;

use super::response::{BlockResponse, EndState};

/// The outcome of one trial: whether the block failed (overturned, or left
/// the ground: a run that cannot be called safe).
pub trait Failing {
    /// True when the trial is not safe.
    fn fails(&self) -> bool;
}

impl Failing for bool {
    fn fails(&self) -> bool {
        *self
    }
}

impl Failing for BlockResponse {
    fn fails(&self) -> bool {
        matches!(self.end, EndState::Overturned | EndState::Flight)
    }
}

/// The amplitudes a search tries: `step, 2·step, …` up to `max` (within
/// a millionth of a step), each > 0.
pub fn ladder(step: f64, max: f64) -> Result<Vec<f64>, String> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(format!("step {step} must be a finite number > 0"));
    }
    if !(max >= step && max.is_finite()) {
        return Err(format!("largest value {max} must be finite and >= the step {step}"));
    }
    let n = (max / step + 1e-6).floor() as usize;
    if n > 100_000 {
        return Err(format!("{n} steps of {step} up to {max}: at most 100000"));
    }
    Ok((1..=n).map(|i| i as f64 * step).collect())
}

/// A range of amplitudes above the first failure where the block is safe:
/// safe at `from`, and failed again at `to` (`None`: still safe at the
/// largest amplitude tried).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SafeWindow {
    /// Lowest safe amplitude found (within the tolerance of the boundary).
    pub from: f64,
    /// First failed amplitude above it, or `None`.
    pub to: Option<f64>,
}

/// What the search found.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleSearch<S> {
    /// The smallest failing amplitude found and the trial there (`None`:
    /// safe over the whole grid).
    pub first_failure: Option<(f64, S)>,
    /// Safe windows above the first failure, increasing.
    pub safe_windows: Vec<SafeWindow>,
    /// Trials run.
    pub trials: usize,
}

/// A change of status between two amplitudes, refined.
#[derive(Clone, Copy, Debug)]
struct Change<S> {
    /// First amplitude with the new status.
    hi: f64,
    /// The trial at `hi`.
    at_hi: S,
    trials: usize,
}

/// Narrows `[lo, hi]` (status differs at the ends; `at_hi` the trial at
/// `hi`) until `hi − lo <= rel_tol·hi`.
fn bisect<S, E, F>(mut lo: f64, mut hi: f64, mut at_hi: S, rel_tol: f64, f: &F) -> Result<Change<S>, E>
where
    S: Failing + Copy,
    F: Fn(f64) -> Result<S, E>,
{
    let hi_fails = at_hi.fails();
    let mut trials = 0;
    while hi - lo > rel_tol * hi {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let s = f(mid)?;
        trials += 1;
        if s.fails() == hi_fails {
            hi = mid;
            at_hi = s;
        } else {
            lo = mid;
        }
    }
    Ok(Change { hi, at_hi, trials })
}

/// Searches `grid` (increasing, > 0) with the trial `f`, refining every
/// change of status to `rel_tol` (relative, > 0). See the module docs.
pub fn search<S, E, F>(grid: &[f64], rel_tol: f64, f: &F) -> Result<ScaleSearch<S>, E>
where
    S: Failing + Copy + Send + Sync,
    E: Send,
    F: Fn(f64) -> Result<S, E> + Sync,
{
    let trials: Vec<S> = grid.par_iter().map(|&a| f(a)).collect::<Result<_, E>>()?;
    // Brackets (lo, hi, trial at hi) where the status changes; 0 is safe.
    let mut brackets: Vec<(f64, f64, S)> = Vec::new();
    let mut previous = (0.0, false);
    for (&a, s) in grid.iter().zip(&trials) {
        if s.fails() != previous.1 {
            brackets.push((previous.0, a, *s));
        }
        previous = (a, s.fails());
    }
    let changes: Vec<Change<S>> = brackets
        .par_iter()
        .map(|&(lo, hi, at_hi)| bisect(lo, hi, at_hi, rel_tol, f))
        .collect::<Result<_, E>>()?;
    let mut out = ScaleSearch {
        first_failure: None,
        safe_windows: Vec::new(),
        trials: grid.len() + changes.iter().map(|c| c.trials).sum::<usize>(),
    };
    for c in &changes {
        if c.at_hi.fails() {
            match (&out.first_failure, out.safe_windows.last_mut()) {
                (None, _) => out.first_failure = Some((c.hi, c.at_hi)),
                (Some(_), Some(w)) => w.to = Some(c.hi),
                (Some(_), None) => {}
            }
        } else {
            out.safe_windows.push(SafeWindow { from: c.hi, to: None });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;

    /// Fails on [1.234, 2.5) and [3.75, ∞): one safe window between.
    fn synthetic(a: f64) -> Result<bool, ()> {
        Ok((1.234..2.5).contains(&a) || a >= 3.75)
    }

    #[test]
    fn ladder_steps_up_to_the_maximum() {
        assert_eq!(ladder(0.5, 2.0).unwrap(), vec![0.5, 1.0, 1.5, 2.0]);
        assert_eq!(ladder(0.1, 0.3).unwrap().len(), 3);
        assert!(ladder(0.0, 1.0).is_err());
        assert!(ladder(1.0, 0.5).is_err());
        assert!(ladder(f64::NAN, 1.0).is_err());
    }

    #[test]
    fn finds_the_first_failure_and_the_safe_window_above_it() {
        let grid = ladder(0.25, 5.0).unwrap();
        let s = search(&grid, 1e-6, &synthetic).unwrap();
        let (first, at) = s.first_failure.unwrap();
        assert!(at);
        assert!((first - 1.234).abs() <= 1e-6 * 1.234 && first >= 1.234, "{first}");
        assert_eq!(s.safe_windows.len(), 1);
        let w = s.safe_windows[0];
        assert!((w.from - 2.5).abs() <= 1e-6 * 2.5 && w.from >= 2.5, "{w:?}");
        let to = w.to.unwrap();
        assert!((to - 3.75).abs() <= 1e-6 * 3.75 && to >= 3.75, "{w:?}");
    }

    #[test]
    fn an_open_window_and_a_failure_below_the_first_step() {
        // Fails on (0.01, 0.3] only: below the first step, then safe to the end.
        let f = |a: f64| -> Result<bool, ()> { Ok(a > 0.01 && a <= 0.3) };
        let s = search(&ladder(0.2, 1.0).unwrap(), 1e-9, &f).unwrap();
        let first = s.first_failure.unwrap().0;
        assert!((first - 0.01).abs() < 1e-9, "{first}");
        assert_eq!(s.safe_windows.len(), 1);
        assert!((s.safe_windows[0].from - 0.3).abs() < 1e-9);
        assert_eq!(s.safe_windows[0].to, None);
    }

    #[test]
    fn never_failing_finds_nothing_and_runs_only_the_grid() {
        let count = AtomicUsize::new(0);
        let f = |_: f64| -> Result<bool, ()> {
            count.fetch_add(1, Ordering::Relaxed);
            Ok(false)
        };
        let s = search(&ladder(0.1, 1.0).unwrap(), 1e-3, &f).unwrap();
        assert_eq!(s.first_failure, None);
        assert!(s.safe_windows.is_empty());
        assert_eq!((s.trials, count.load(Ordering::Relaxed)), (10, 10));
    }

    #[test]
    fn an_error_is_passed_on() {
        let f = |a: f64| if a > 0.5 { Err("boom") } else { Ok(false) };
        assert_eq!(search(&ladder(0.25, 1.0).unwrap(), 1e-3, &f), Err("boom"));
    }
}
