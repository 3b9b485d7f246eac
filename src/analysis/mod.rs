//! Analyses of the block's response: the stroboscopic (Poincaré) section,
//! the classification of a steady response, power spectra, bifurcation
//! (orbit) diagrams over one parameter and outcome maps over two.
//!
//! Contract:
//! - The numerical machinery (classification, spectra, sweeps over a grid)
//!   is generic: it works on plain point sets, sample vectors and closures,
//!   and is tested on systems with known answers (the logistic map, an
//!   irrational rotation, a linear forced oscillator, sums of sines).
//!   The block enters only through [`steady`], which runs one configuration
//!   and hands its section points to the classifier.
//! - Nothing here draws, writes files or names a GUI type.
//! - Sweeps are deterministic: the same inputs give bit-identical results
//!   for any number of threads (results are collected by index).
//! - Non-finite input is an error, never a NaN in a result.
//!
//! - Long analyses report progress through a callback ([`ProgressFn`]);
//!   they know no progress-bar library.
//!
//! Layers: `integrate → model → sim → analysis → io → …` (the crate docs
//! list them all): this layer imports `integrate`, `model` and `sim`, and
//! nothing to the right of it. A parameter is varied through a typed
//! [`Param`](crate::sim::Param), never by name.

pub mod attractor;
pub mod classify;
pub mod engineering;
pub mod field;
pub mod lyapunov;
pub mod map_refine;
pub mod orbit_diagram;
pub mod outcome_map;
pub mod section;
pub mod settle;
pub mod spectrum;
pub mod steady;

/// Progress of a long analysis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// The number of units of work (sweep values, map cells, figures), told
    /// once before the first is done.
    Total(u64),
    /// One more unit done (from any worker thread).
    Done,
}

/// A progress callback: the CLI draws a bar from it, the app a counter.
pub(crate) type ProgressFn<'a> = dyn Fn(Progress) + Sync + 'a;

/// The callback that ignores progress.
pub fn silent(_: Progress) {}
