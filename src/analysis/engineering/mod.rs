//! The engineer's analyses of a free-standing block under earthquakes and
//! pulses: rocking spectra, overturning scales, pulse overturning maps,
//! fragility curves and sliding spectra (docs/engineering.md).
//!
//! Contract:
//! - Each analysis is a set of independent runs of one block under one
//!   ground motion ([`response`]): physical inputs (metres, seconds, g),
//!   physical and normalised answers (θ/α, seconds).
//! - Runs go in parallel (rayon, over the caller's pool) and are collected
//!   by index: the results do not depend on the number of threads.
//! - Nothing here reads files, draws or parses flags; records arrive as
//!   [`Series`](crate::model::excitation::record::Series) inside a
//!   [`Record`](crate::sim::scenario::Record).
//! - What a study is asked is checked in [`request`] (and each spec's own
//!   `check`), with errors that name inputs by meaning, never a flag.
//! - No NaN leaves this module: a quantity that does not exist (no
//!   overturning, no fit) is `None` or an error that says why.

pub mod block_size;
pub mod fragility;
pub mod lognormal;
pub mod overturn_scale;
pub mod pulse_map;
pub mod request;
pub mod response;
pub mod rocking_spectrum;
pub mod sliding_spectrum;
pub mod stack_response;

pub use response::{BlockResponse, BlockSize, Drive, EndState};

/// A record of accelerations `a_g` (g) at times `t` (s), named `path`,
/// driving a test run.
#[cfg(test)]
pub(crate) fn test_record(path: &str, t: Vec<f64>, a_g: Vec<f64>) -> Drive {
    Drive::Record(crate::sim::scenario::Record {
        path: path.into(),
        series: crate::model::excitation::record::Series::new(t, a_g).unwrap(),
        unit: crate::model::units::AccelUnit::G,
        dt: None,
        crc32: 0,
        channel: None,
    })
}
