//! # rocking
//!
//! An exact, event-driven simulator of a free-standing rigid block that
//! rocks, slides, slide-rocks, lifts off and tumbles on a base shaken
//! horizontally and vertically, after Jeong & Suzuki's *Chaotic rocking
//! vibration of a rigid block with sliding motion under two-dimensional
//! harmonic excitation* — with the paper's printed equations re-derived
//! (`docs/model.md`).
//!
//! ## Layers
//!
//! Dependencies point one way; each layer imports only those to its left
//! (as the `use crate::…` lines of each folder say):
//!
//! [`integrate`] → [`model`] → [`sim`] → [`analysis`] → [`io`] → [`plot`]
//! → (`bench`, [`reproduce`]) → (`cli`, `gui`)
//!
//! and the Python package (`python/`) sits on top, beside `cli`. One arrow
//! points back, in test code only: `sim`'s session tests load the shipped
//! presets through `io`. `tests/layers.rs` checks the order, and that no two
//! sibling files import from each other, from the source text.
//!
//! - [`integrate`]: methods only, knowing nothing of blocks — the steppers
//!   (DOP853, DOPRI5, Taylor, Ralston), root finding and the hybrid driver
//!   with its [`HybridSystem`](integrate::hybrid::HybridSystem) trait.
//! - [`model`]: equations only — geometry, modes, dynamics, impact laws,
//!   energy, the excitations (a record is a series of samples; reading
//!   files is [`io::record`]'s), and the block as a `HybridSystem`. It
//!   imports `integrate` for that trait, the driver's jump and error types
//!   and the Taylor method's largest order (which sizes the block's
//!   series), never a stepper.
//! - [`sim`]: the typed, validated [`Scenario`](sim::Scenario) and
//!   [`Param`](sim::Param), one run ([`sim::simulate`]), the simulation
//!   thread of the app ([`sim::runner`]) and the background-job type it and
//!   the app's panels share ([`sim::job`]).
//! - [`analysis`]: sections, classification, spectra, Lyapunov exponents,
//!   bifurcation diagrams and outcome maps, on scenarios varied through
//!   typed parameters; progress through a callback.
//! - [`io`]: the config file (TOML, presets, `--set`, `summary.json`) read
//!   into a scenario — the only place that knows the string keys —,
//!   records, and the output files written whole or not at all.
//! - [`plot`] draws figures from the analyses' results; `bench` measures
//!   the methods (work–precision) and [`reproduce`] recomputes the paper's
//!   figures and writes the report, both drawing through `plot`.
//! - `cli` (the `rocking` binary's commands) and `gui` (the desktop app,
//!   feature `gui`) sit on top.
//!
//! `cli` and `bench` are public only so that the binary, the benches and
//! the tests can reach them; they are not a library API and are hidden from
//! the docs.

pub mod analysis;
pub mod integrate;
pub mod io;
pub mod model;
pub mod plot;
pub mod reproduce;
pub mod sim;

/// The `rocking` binary's command line (for `src/main.rs` and the tests;
/// not a library API).
#[doc(hidden)]
pub mod cli;

/// The benchmark scenes of `rocking bench`, `cargo bench` and the examples
/// (not a library API).
#[doc(hidden)]
pub mod bench;

#[cfg(feature = "gui")]
pub mod gui;
