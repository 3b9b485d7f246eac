//! The live run the thread owns: a block's or a frame's ([`Session`]) or
//! a stack's ([`StackSession`]). The worker drives either through the
//! same calls; what a stack does not do (ghosts, a perturbed restart, a
//! restart from the state shown) is refused with its reason, and the
//! worker then starts over from rest as it does for any refusal.

use super::playhead::Playhead;
use super::session::{Session, Start};
use super::stack_session::StackSession;
use crate::sim::Scenario;
use crate::sim::protocol::{Batch, RunEnd, RunId, RunInfo, Sample};

/// Why a stack refuses to go on from the state shown.
const STACK_STARTS_AT_REST: &str = "a stack starts from rest, as its batch run does: no perturbed or continued start";

/// One live run.
pub enum Live {
    /// A block or a frame.
    Block(Session),
    /// A stack of blocks.
    Stack(StackSession),
}

impl Live {
    /// Starts run `run` of `scenario` from `start` (a stack: from rest),
    /// with the block's section at `phase`.
    pub(crate) fn with_phase(run: RunId, scenario: &Scenario, start: Start, phase: f64) -> Result<Self, String> {
        if scenario.stack.is_some() {
            if start != Start::Initial {
                return Err(STACK_STARTS_AT_REST.to_string());
            }
            return StackSession::new(run, scenario).map(Live::Stack);
        }
        Session::with_phase(run, scenario, start, phase).map(Live::Block)
    }

    /// What either kind keeps alike.
    fn play(&self) -> &Playhead {
        match self {
            Live::Block(s) => &s.play,
            Live::Stack(s) => &s.play,
        }
    }

    /// The run's id.
    pub fn run(&self) -> RunId {
        self.play().run
    }

    /// What the run is about.
    pub fn info(&self) -> &RunInfo {
        &self.play().info
    }

    /// τ integrated so far.
    pub fn computed(&self) -> f64 {
        match self {
            Live::Block(s) => s.computed(),
            Live::Stack(s) => s.computed(),
        }
    }

    /// τ released so far.
    pub fn released(&self) -> f64 {
        self.play().released
    }

    /// Whether the driver stopped.
    pub(crate) fn is_ended(&self) -> bool {
        self.play().ended.is_some()
    }

    /// How the run ended, once all before it is released.
    pub fn end(&self) -> Option<&RunEnd> {
        match self {
            Live::Block(s) => s.end(),
            Live::Stack(s) => s.end(),
        }
    }

    /// Integrates one chunk.
    pub(crate) fn advance_chunk(&mut self) {
        match self {
            Live::Block(s) => s.advance_chunk(),
            Live::Stack(s) => s.advance_chunk(),
        }
    }

    /// Integrates until `tau` is computed or the run ends.
    pub(crate) fn fill_to(&mut self, tau: f64) {
        match self {
            Live::Block(s) => s.fill_to(tau),
            Live::Stack(s) => s.fill_to(tau),
        }
    }

    /// Releases everything up to `tau` into `batch`.
    pub fn release(&mut self, tau: f64, batch: &mut Batch) {
        match self {
            Live::Block(s) => s.release(tau, batch),
            Live::Stack(s) => s.release(tau, batch),
        }
    }

    /// Moves the run's first frame (the sample at its start, with a block's
    /// ghosts there) into `batch` without moving the playhead: a run started
    /// paused shows where it starts instead of an empty stage. Integrates
    /// one chunk ahead, which the run would do next anyway.
    pub(crate) fn first_frame(&mut self, batch: &mut Batch) {
        let released = self.released();
        if released > self.info().tau0 {
            return;
        }
        let next = match self {
            Live::Block(s) => s.next_sample_tau(),
            Live::Stack(s) => s.next_sample_tau(),
        };
        if !self.is_ended() && next.is_none_or(|tau| tau > released) {
            self.advance_chunk();
        }
        self.release(released, batch);
    }

    /// Ghost copies (a block's only; a stack has none).
    pub fn set_ghosts(&mut self, count: usize, eps: f64, last_sample: Option<&Sample>) {
        match self {
            Live::Block(s) => s.set_ghosts(count, eps, last_sample),
            Live::Stack(_) => {}
        }
    }

    /// A perturbed restart from the state shown (a block's only).
    pub(crate) fn perturbed(&self, run: RunId, eps: f64, last_sample: Option<&Sample>) -> Result<Live, String> {
        match self {
            Live::Block(s) => s.perturbed(run, eps, last_sample).map(Live::Block),
            Live::Stack(_) => Err(STACK_STARTS_AT_REST.to_string()),
        }
    }

    /// A run of new parameters from the state shown (a block's, and a
    /// block's scenario, only).
    pub fn continued(
        &self,
        run: RunId,
        scenario: &Scenario,
        phase: f64,
        last_sample: Option<&Sample>,
    ) -> Result<Live, String> {
        match self {
            Live::Block(s) if scenario.stack.is_none() => {
                s.continued(run, scenario, phase, last_sample).map(Live::Block)
            }
            Live::Block(_) | Live::Stack(_) => Err(STACK_STARTS_AT_REST.to_string()),
        }
    }
}
