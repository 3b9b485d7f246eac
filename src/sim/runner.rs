//! The simulation thread: owns a live run ([`Live`]: a block's or a
//! frame's [`Session`], or a stack's [`StackSession`]), paces it in real
//! time (or runs flat out), and streams its output over a bounded channel.
//!
//! The thread is a [`crate::sim::job::Job`] named `sim`: commands in,
//! updates out, joined when the [`SimHandle`] is dropped. It never names a
//! GUI toolkit: the consumer supplies a [`Waker`] (the app passes
//! `ctx.request_repaint()`), called after every burst of messages sent.
//!
//! # Channel policy (what happens when the consumer falls behind)
//!
//! - Commands go in over an unbounded channel: they are few and none may be
//!   lost.
//! - Updates go out over a bounded channel of [`UPDATE_CAPACITY`] messages.
//!   The thread never blocks on it (it sends with
//!   [`crate::sim::job::Link::try_send`]): when it is full, messages wait in
//!   the thread's outbox, where consecutive batches of the same run are
//!   merged.
//! - **Samples** (the live states) may be *dropped*: a merged batch keeps only
//!   its newest [`MAX_QUEUED_SAMPLES`] samples and counts the rest in
//!   [`Batch::dropped_samples`]. The consumer then shows a gap, never a lie.
//! - **Events and section (Poincaré) points are never dropped.** When more
//!   than [`MAX_QUEUED_EXACT`] of them wait in the outbox, the thread stops
//!   integrating (backpressure) until the consumer drains the channel, so
//!   memory stays bounded whatever the speed.
//! - `Started`, `Paused` and `Finished` messages are never dropped.
//! - Messages of a run that has been replaced are purged from the outbox:
//!   the consumer would drop them anyway ([`SimHandle::drain`] does).
//!
//! # Pacing
//!
//! At [`Speed::RealTime`]`(m)` the playhead advances `m · p` τ per wall-clock
//! second (1 physical second = p τ). The session integrates whole chunks
//! ahead of the playhead and releases what lies behind it every
//! [`TICK`]; if integration cannot keep up, the playhead waits for it
//! (the clock is re-anchored) rather than bursting to catch up. At
//! [`Speed::Max`] every chunk is released as soon as it is computed.
//! A paused thread blocks on its command channel and uses no CPU.

mod live;
mod outbox;
mod playhead;
mod session;
mod stack_session;
mod worker;

use std::time::{Duration, Instant};

pub use live::Live;
pub use outbox::{MAX_QUEUED_EXACT, MAX_QUEUED_SAMPLES};
pub use session::{LIVE_SAMPLE_DT, MAX_CHUNK, Session, Start, normalise_phase};
pub use stack_session::StackSession;

use super::job::Job;
pub use super::job::Waker;
use super::protocol::{Batch, RunEnd, RunId, SimCommand, SimUpdate, Speed, StartFrom};
use crate::sim::Scenario;

/// Capacity of the update channel, in messages. At one batch per
/// [`TICK`] this is about a second of output: enough to ride out a slow
/// frame without merging.
pub(crate) const UPDATE_CAPACITY: usize = 64;

/// Release period of the paced playback: one 60 Hz frame.
pub(crate) const TICK: Duration = Duration::from_micros(16_667);

/// How the thread failed to start.
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    /// The operating system refused the thread.
    #[error("could not start the simulation thread: {0}")]
    Spawn(#[from] std::io::Error),
}

/// The handle to the simulation thread. Dropping it shuts the thread down
/// and joins it.
pub struct SimHandle {
    job: Job<SimUpdate, SimCommand>,
    current: RunId,
}

impl SimHandle {
    /// Starts the thread on run 1 of `scenario`, at `speed`, paused if
    /// `paused`. `waker` is called after every burst of messages sent.
    pub fn spawn(scenario: Scenario, speed: Speed, paused: bool, waker: Waker) -> Result<Self, StartError> {
        let run = RunId(1);
        let job = Job::spawn("sim", UPDATE_CAPACITY, waker, move |link| {
            worker::Worker::new(link, scenario, speed, paused).run(run);
        })?;
        Ok(Self { job, current: run })
    }

    /// The run whose updates [`SimHandle::drain`] passes on.
    pub fn current_run(&self) -> RunId {
        self.current
    }

    fn next_run(&mut self) -> RunId {
        self.current = RunId(self.current.0 + 1);
        self.current
    }

    fn send(&self, cmd: SimCommand) {
        // A send fails only if the thread has exited, which it does only on
        // Shutdown (from Drop) or a panic; there is nothing to tell then.
        self.job.send(cmd);
    }
    /// Starts a new run of `scenario` from τ = 0; returns its id.
    pub fn set_params(&mut self, scenario: Scenario) -> RunId {
        self.set_params_from(scenario, StartFrom::Initial)
    }

    /// Starts a new run of `scenario` from τ = 0 or from the state shown
    /// now (`from`); returns its id.
    pub fn set_params_from(&mut self, scenario: Scenario, from: StartFrom) -> RunId {
        let run = self.next_run();
        self.send(SimCommand::SetParams {
            run,
            scenario: Box::new(scenario),
            from,
        });
        run
    }

    /// Takes stroboscopic section points at forcing phase `phase` (rad)
    /// from now on: a new run from the state shown now. Returns its id.
    pub fn set_section_phase(&mut self, phase: f64) -> RunId {
        let run = self.next_run();
        self.send(SimCommand::SetSectionPhase { run, phase });
        run
    }

    /// Restarts the current scenario from τ = 0; returns the new run's id.
    pub fn reset(&mut self) -> RunId {
        let run = self.next_run();
        self.send(SimCommand::Reset { run });
        run
    }

    /// Restarts from the state shown now with Θ + `eps`; returns the new id.
    pub fn reset_perturbed(&mut self, eps: f64) -> RunId {
        let run = self.next_run();
        self.send(SimCommand::ResetPerturbed { run, eps });
        run
    }

    /// Pauses.
    pub fn pause(&self) {
        self.send(SimCommand::Pause);
    }

    /// Resumes.
    pub fn resume(&self) {
        self.send(SimCommand::Resume);
    }

    /// While paused, advances by `tau`.
    pub fn step(&self, tau: f64) {
        self.send(SimCommand::Step { tau });
    }

    /// Sets the playback speed.
    pub fn set_speed(&self, speed: Speed) {
        self.send(SimCommand::SetSpeed(speed));
    }

    /// Runs `count` ghost copies perturbed by up to `eps`.
    pub fn set_ghosts(&self, count: usize, eps: f64) {
        self.send(SimCommand::SetGhosts { count, eps });
    }

    /// Receives updates for at most `budget` (and at most `max` messages),
    /// passing those of the current run to `f` and dropping stale ones.
    /// Returns how many were passed on.
    pub fn drain(&self, budget: Duration, max: usize, mut f: impl FnMut(SimUpdate)) -> usize {
        let start = Instant::now();
        let mut n = 0;
        for _ in 0..max {
            let Some(u) = self.job.try_recv() else { break };
            if u.run() == self.current {
                f(u);
                n += 1;
            }
            if start.elapsed() >= budget {
                break;
            }
        }
        n
    }

    /// Whether updates are waiting to be drained.
    pub fn has_pending(&self) -> bool {
        self.job.has_pending()
    }

    /// Waits up to `timeout` for the next update of any run (tests).
    pub fn recv_timeout(&self, timeout: Duration) -> Option<SimUpdate> {
        self.job.recv_timeout(timeout)
    }

    /// Whether the thread is still running.
    pub fn is_alive(&self) -> bool {
        !self.job.finished()
    }
}

impl Drop for SimHandle {
    fn drop(&mut self) {
        // The protocol's explicit end; the job's own Drop then disconnects
        // the commands (which also ends the thread) and joins it.
        self.send(SimCommand::Shutdown);
    }
}

/// Runs run `run` of `scenario` synchronously to `tau_end` (or its end) and
/// returns what the thread would have streamed: `Started`, one `Batch`,
/// and `Finished` if the run ended. For fixed streams (snapshots, tests).
pub fn record(run: RunId, scenario: &Scenario, tau_end: f64) -> Vec<SimUpdate> {
    let mut s = match Live::with_phase(run, scenario, Start::Initial, 0.0) {
        Ok(s) => s,
        Err(msg) => {
            return vec![SimUpdate::Finished {
                run,
                end: RunEnd::Failed(msg),
            }];
        }
    };
    let mut out = vec![SimUpdate::Started {
        run,
        info: Box::new(s.info().clone()),
    }];
    s.fill_to(tau_end);
    let mut batch = Batch::default();
    s.release(tau_end, &mut batch);
    out.push(SimUpdate::Batch { run, batch });
    if let Some(end) = s.end() {
        out.push(SimUpdate::Finished { run, end: end.clone() });
    }
    out
}
