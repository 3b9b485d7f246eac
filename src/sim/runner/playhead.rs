//! What a live run keeps that reads alike for a block's run and a stack's:
//! its id, what it is about, how it ended, and how far its output has been
//! released; and the release of a queue of output up to the playhead.

use std::collections::VecDeque;

use crate::model::geometry::Geometry;
use crate::model::stack::StackGeometry;
use crate::sim::Scenario;
use crate::sim::protocol::{Batch, RunEnd, RunId, RunInfo};

/// Spacing of the live samples, τ. Fine enough that the paper's block
/// (p ≈ 1.9 s⁻¹) shows a new pose about 40 times a second at ×0.1 playback;
/// samples come from the dense output, so they add no step stops.
pub const LIVE_SAMPLE_DT: f64 = 0.005;

/// A live run's id, description, end and playhead.
pub(crate) struct Playhead {
    /// The run's id.
    pub(crate) run: RunId,
    /// What the run is about.
    pub(crate) info: RunInfo,
    /// How the run ended, once the driver stopped.
    pub(crate) ended: Option<RunEnd>,
    /// τ up to which output has been released.
    pub(crate) released: f64,
}

impl Playhead {
    /// Run `run` of `scenario` (a stack's if `stack` is given), sampled
    /// every [`LIVE_SAMPLE_DT`], its section at `section_phase` (rad) of
    /// `section_period` (τ), starting at `tau0` with nothing released.
    pub(crate) fn new(
        run: RunId,
        scenario: &Scenario,
        geometry: Geometry,
        section_period: Option<f64>,
        section_phase: f64,
        tau0: f64,
        stack: Option<StackGeometry>,
    ) -> Self {
        Self {
            run,
            info: RunInfo {
                scenario: scenario.clone(),
                geometry,
                section_period,
                section_phase,
                tau0,
                sample_dt: LIVE_SAMPLE_DT,
                stack,
            },
            ended: None,
            released: tau0,
        }
    }

    /// How the run ended, once everything before the end is released
    /// (`drained`: nothing is left queued).
    pub(crate) fn end(&self, drained: bool) -> Option<&RunEnd> {
        if drained { self.ended.as_ref() } else { None }
    }

    /// How far a release to `tau` goes: all of it once the run has ended,
    /// else no further than `computed`, the τ integrated so far.
    pub(crate) fn release_limit(&self, tau: f64, computed: f64) -> f64 {
        if self.ended.is_some() { tau } else { tau.min(computed) }
    }

    /// Moves the playhead forward to `upto` (no further than `computed`)
    /// and dates `batch` with it.
    pub(crate) fn move_to(&mut self, upto: f64, computed: f64, batch: &mut Batch) {
        if upto > self.released {
            self.released = upto.min(computed);
        }
        batch.tau = self.released;
    }
}

/// Moves the items of `queue` at or before `upto` (in its time order, `tau`
/// of each) into `out`.
pub(crate) fn release_upto<T>(queue: &mut VecDeque<T>, upto: f64, tau: impl Fn(&T) -> f64, mut out: impl FnMut(T)) {
    while queue.front().is_some_and(|x| tau(x) <= upto) {
        if let Some(x) = queue.pop_front() {
            out(x);
        }
    }
}
