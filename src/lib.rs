//! # rocking
//!
//! An exact, event-driven simulator of a free-standing rigid block that
//! rocks, slides, slide-rocks, lifts off and tumbles on a base shaken
//! horizontally and vertically, after Jeong & Suzuki's *Chaotic rocking
//! vibration of a rigid block with sliding motion under two-dimensional
//! harmonic excitation* — with the paper's printed equations re-derived
//! (`docs/model.md`).
//!
//! Layers point one way: [`model`] (equations) → [`integrate`] (methods,
//! knows nothing of blocks) → [`sim`] (runs a model with a method) →
//! [`io`] and the `rocking` binary.

pub mod analysis;
pub mod bench;
pub mod integrate;
pub mod io;
pub mod model;
pub mod plot;
pub mod reproduce;
pub mod sim;

pub mod cli;
#[cfg(feature = "gui")]
pub mod gui;
