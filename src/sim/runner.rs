//! The simulation thread: owns a live run ([`Session`]), paces it in real
//! time (or runs flat out), and streams its output over a bounded channel.
//!
//! It never names a GUI toolkit: the consumer supplies a [`Waker`] (the app
//! passes `ctx.request_repaint()`), called after every message sent.
//!
//! # Channel policy (what happens when the consumer falls behind)
//!
//! - Commands go in over an unbounded channel: they are few and none may be
//!   lost.
//! - Updates go out over a bounded channel of [`UPDATE_CAPACITY`] messages.
//!   The thread never blocks on it: when it is full, messages wait in the
//!   thread's outbox, where consecutive batches of the same run are merged.
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

mod session;

use std::collections::VecDeque;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, TrySendError};

pub use session::{LIVE_SAMPLE_DT, MAX_CHUNK, Session, Start};

use super::protocol::{Batch, MAX_GHOSTS, RunEnd, RunId, Sample, SimCommand, SimUpdate, Speed};
use crate::sim::Scenario;

/// Wakes the consumer after a message is sent (the app's repaint request).
pub type Waker = Box<dyn Fn() + Send + Sync>;

/// Capacity of the update channel, in messages. At one batch per
/// [`TICK`] this is about a second of output: enough to ride out a slow
/// frame without merging.
pub const UPDATE_CAPACITY: usize = 64;

/// Most samples a merged batch in the outbox keeps (the newest). 2¹⁶
/// samples are 328 τ at [`LIVE_SAMPLE_DT`], more than the time-history
/// window shows.
pub const MAX_QUEUED_SAMPLES: usize = 1 << 16;

/// Events plus section points in the outbox beyond which the thread stops
/// integrating until the consumer catches up (about 10 MB).
pub const MAX_QUEUED_EXACT: usize = 1 << 17;

/// Release period of the paced playback: one 60 Hz frame.
pub const TICK: Duration = Duration::from_micros(16_667);

/// Wall-clock time the thread integrates before it releases output at
/// [`Speed::Max`] (and the most it lets a paced tick overrun).
const WORK_SLICE: Duration = Duration::from_millis(12);

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
    commands: Sender<SimCommand>,
    updates: Receiver<SimUpdate>,
    thread: Option<JoinHandle<()>>,
    current: RunId,
}

impl SimHandle {
    /// Starts the thread on run 1 of `scenario`, at `speed`, paused if
    /// `paused`. `waker` is called after every message sent.
    pub fn spawn(scenario: Scenario, speed: Speed, paused: bool, waker: Waker) -> Result<Self, StartError> {
        let (cmd_tx, cmd_rx) = crossbeam_channel::unbounded();
        let (up_tx, up_rx) = crossbeam_channel::bounded(UPDATE_CAPACITY);
        let run = RunId(1);
        let worker = Worker {
            commands: cmd_rx,
            out: up_tx,
            waker,
            outbox: VecDeque::new(),
            session: None,
            last_sample: None,
            paused,
            speed,
            anchor: None,
            ghosts: (0, 0.0),
            deferred_finish: false,
            scenario: scenario.clone(),
        };
        let thread = std::thread::Builder::new()
            .name("sim".into())
            .spawn(move || worker.run(run))?;
        Ok(Self {
            commands: cmd_tx,
            updates: up_rx,
            thread: Some(thread),
            current: run,
        })
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
        let _ = self.commands.send(cmd);
    }

    /// Starts a new run of `scenario` from τ = 0; returns its id.
    pub fn set_params(&mut self, scenario: Scenario) -> RunId {
        let run = self.next_run();
        self.send(SimCommand::SetParams {
            run,
            scenario: Box::new(scenario),
        });
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
            let Ok(u) = self.updates.try_recv() else { break };
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
        !self.updates.is_empty()
    }

    /// Waits up to `timeout` for the next update of any run (tests).
    pub fn recv_timeout(&self, timeout: Duration) -> Option<SimUpdate> {
        self.updates.recv_timeout(timeout).ok()
    }

    /// Whether the thread is still running.
    pub fn is_alive(&self) -> bool {
        self.thread.as_ref().is_some_and(|t| !t.is_finished())
    }
}

impl Drop for SimHandle {
    fn drop(&mut self) {
        let _ = self.commands.send(SimCommand::Shutdown);
        if let Some(t) = self.thread.take() {
            // A panic in the thread has already been printed by the panic
            // hook; joining only reaps it.
            let _ = t.join();
        }
    }
}

/// The thread's state.
struct Worker {
    commands: Receiver<SimCommand>,
    out: Sender<SimUpdate>,
    waker: Waker,
    /// Messages not yet accepted by the channel, in order.
    outbox: VecDeque<SimUpdate>,
    session: Option<Session>,
    /// The last sample released: the state the user sees.
    last_sample: Option<Sample>,
    paused: bool,
    speed: Speed,
    /// Wall clock and playhead τ at the last (re)start of paced playback.
    anchor: Option<(Instant, f64)>,
    /// Ghost count and ε, re-applied to every new run.
    ghosts: (usize, f64),
    /// Whether the current run ended and its `Finished` message was queued.
    deferred_finish: bool,
    /// The configuration last asked for (what `Reset` restarts, even when
    /// it failed to start).
    scenario: Scenario,
}

enum Flow {
    Continue,
    Stop,
}

impl Worker {
    fn run(mut self, run: RunId) {
        let scenario = self.scenario.clone();
        self.start(run, |r| Session::new(r, &scenario, Start::Initial));
        loop {
            let flow = match self.wait() {
                Some(cmd) => self.handle(cmd),
                None => Flow::Continue,
            };
            if let Flow::Stop = flow {
                return;
            }
            // Apply every command already waiting before doing work.
            while let Ok(cmd) = self.commands.try_recv() {
                if let Flow::Stop = self.handle(cmd) {
                    return;
                }
            }
            if !self.paused && !self.backpressured() {
                self.work();
            }
            self.flush();
        }
    }

    /// Blocks until a command arrives or it is time to work again.
    fn wait(&mut self) -> Option<SimCommand> {
        let idle = self.paused
            || self
                .session
                .as_ref()
                .is_none_or(|s| s.end().is_some() && self.deferred_finish);
        let timeout = if !self.outbox.is_empty() {
            // Channel full: retry soon, but do not spin.
            Some(Duration::from_millis(4))
        } else if idle {
            None
        } else {
            match self.speed {
                Speed::Max => Some(Duration::ZERO),
                Speed::RealTime(_) => Some(TICK),
            }
        };
        match timeout {
            None => self.commands.recv().ok().or(Some(SimCommand::Shutdown)),
            Some(d) if d.is_zero() => self.commands.try_recv().ok(),
            Some(d) => match self.commands.recv_timeout(d) {
                Ok(c) => Some(c),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => Some(SimCommand::Shutdown),
            },
        }
    }

    fn handle(&mut self, cmd: SimCommand) -> Flow {
        match cmd {
            SimCommand::Shutdown => return Flow::Stop,
            SimCommand::SetParams { run, scenario } => {
                self.scenario = *scenario;
                let scenario = self.scenario.clone();
                self.start(run, |r| Session::new(r, &scenario, Start::Initial));
            }
            SimCommand::Reset { run } => {
                let scenario = self.scenario.clone();
                self.start(run, |r| Session::new(r, &scenario, Start::Initial));
            }
            SimCommand::ResetPerturbed { run, eps } => {
                let last = self.last_sample;
                let next = match &self.session {
                    Some(s) => s.perturbed(run, eps, last.as_ref()),
                    None => Err("nothing to perturb: the last run did not start".to_string()),
                };
                self.start(run, |_| next);
            }
            SimCommand::Pause => {
                self.paused = true;
                self.anchor = None;
                self.queue_paused();
            }
            SimCommand::Resume => {
                self.paused = false;
                self.anchor = None;
                self.queue_paused();
            }
            SimCommand::Step { tau } => {
                if tau > 0.0 && tau.is_finite() {
                    self.step(tau);
                }
            }
            SimCommand::SetSpeed(speed) => {
                self.speed = match speed {
                    Speed::RealTime(m) if m.is_finite() => {
                        Speed::RealTime(m.clamp(Speed::MIN_MULTIPLE, Speed::MAX_MULTIPLE))
                    }
                    Speed::RealTime(_) | Speed::Max => Speed::Max,
                };
                self.anchor = None;
            }
            SimCommand::SetGhosts { count, eps } => {
                self.ghosts = (count.min(MAX_GHOSTS), eps);
                let last = self.last_sample;
                if let Some(s) = self.session.as_mut() {
                    s.set_ghosts(self.ghosts.0, eps, last.as_ref());
                }
            }
        }
        Flow::Continue
    }

    /// Replaces the session with `make(run)`; a failure is reported as the
    /// new run's `Finished`.
    fn start(&mut self, run: RunId, make: impl FnOnce(RunId) -> Result<Session, String>) {
        self.outbox.retain(|u| u.run() >= run);
        self.anchor = None;
        self.last_sample = None;
        self.deferred_finish = false;
        match make(run) {
            Ok(mut s) => {
                if self.ghosts.0 > 0 {
                    s.set_ghosts(self.ghosts.0, self.ghosts.1, None);
                }
                self.outbox.push_back(SimUpdate::Started {
                    run,
                    info: Box::new(s.info().clone()),
                });
                self.session = Some(s);
                self.queue_paused();
            }
            Err(msg) => {
                // Keep the old session's scenario for a later Reset, but it no
                // longer produces output under the new id.
                self.session = None;
                self.outbox.push_back(SimUpdate::Finished {
                    run,
                    end: RunEnd::Failed(msg),
                });
                self.deferred_finish = true;
            }
        }
    }

    fn queue_paused(&mut self) {
        if let Some(s) = &self.session {
            self.outbox.push_back(SimUpdate::Paused {
                run: s.run(),
                paused: self.paused,
                tau: s.released(),
            });
        }
    }

    fn backpressured(&self) -> bool {
        let exact: usize = self
            .outbox
            .iter()
            .map(|u| match u {
                SimUpdate::Batch { batch, .. } => batch.events.len() + batch.section.len(),
                SimUpdate::Started { .. } | SimUpdate::Paused { .. } | SimUpdate::Finished { .. } => 0,
            })
            .sum();
        exact > MAX_QUEUED_EXACT
    }

    /// Integrates and releases according to the speed.
    fn work(&mut self) {
        let Some(s) = self.session.as_mut() else { return };
        if s.end().is_some() {
            self.finish();
            return;
        }
        let start = Instant::now();
        let mut batch = Batch::default();
        match self.speed {
            Speed::Max => {
                while !s.is_ended() && start.elapsed() < WORK_SLICE {
                    s.advance_chunk();
                }
                s.release(f64::INFINITY, &mut batch);
            }
            Speed::RealTime(m) => {
                let rate = m * s.info().geometry.p;
                let now = Instant::now();
                let (t0, tau0) = *self.anchor.get_or_insert((now, s.released()));
                let mut target = tau0 + now.duration_since(t0).as_secs_f64() * rate;
                while !s.is_ended() && s.computed() < target && start.elapsed() < WORK_SLICE {
                    s.advance_chunk();
                }
                if !s.is_ended() && s.computed() < target {
                    // Integration is slower than the requested speed: hold
                    // the playhead at what is computed and restart the clock
                    // there, instead of bursting later.
                    target = s.computed();
                    self.anchor = Some((Instant::now(), target));
                }
                s.release(target, &mut batch);
            }
        }
        self.queue_batch(batch);
        if self.session.as_ref().is_some_and(|s| s.end().is_some()) {
            self.finish();
        }
    }

    /// Advances the playhead by `tau` while paused (or running).
    fn step(&mut self, tau: f64) {
        let Some(s) = self.session.as_mut() else { return };
        let target = s.released() + tau;
        s.fill_to(target);
        let mut batch = Batch::default();
        s.release(target, &mut batch);
        self.anchor = None;
        self.queue_batch(batch);
        if self.session.as_ref().is_some_and(|s| s.end().is_some()) {
            self.finish();
        }
        self.queue_paused();
    }

    fn finish(&mut self) {
        if self.deferred_finish {
            return;
        }
        if let Some(s) = &self.session
            && let Some(end) = s.end()
        {
            self.outbox.push_back(SimUpdate::Finished {
                run: s.run(),
                end: end.clone(),
            });
            self.deferred_finish = true;
        }
    }

    /// Queues `batch`, merging it into a waiting batch of the same run.
    fn queue_batch(&mut self, batch: Batch) {
        let Some(run) = self.session.as_ref().map(Session::run) else {
            return;
        };
        if let Some(last) = batch.samples.last() {
            self.last_sample = Some(*last);
        }
        if batch.is_empty() {
            return;
        }
        if let Some(SimUpdate::Batch { run: r, batch: waiting }) = self.outbox.back_mut()
            && *r == run
        {
            merge(waiting, batch);
            return;
        }
        self.outbox.push_back(SimUpdate::Batch { run, batch });
    }

    /// Sends what the channel accepts, in order; wakes the consumer once.
    fn flush(&mut self) {
        let mut sent = false;
        while let Some(u) = self.outbox.pop_front() {
            match self.out.try_send(u) {
                Ok(()) => sent = true,
                Err(TrySendError::Full(u)) => {
                    self.outbox.push_front(u);
                    break;
                }
                Err(TrySendError::Disconnected(_)) => {
                    // The consumer is gone; Shutdown follows from Drop.
                    self.outbox.clear();
                    break;
                }
            }
        }
        if sent {
            (self.waker)();
        }
    }
}

/// Appends `next` to `waiting`, keeping at most [`MAX_QUEUED_SAMPLES`]
/// samples (the newest) and counting the dropped ones.
fn merge(waiting: &mut Batch, next: Batch) {
    waiting.samples.extend(next.samples);
    let excess = waiting.samples.len().saturating_sub(MAX_QUEUED_SAMPLES);
    if excess > 0 {
        waiting.samples.drain(..excess);
        waiting.dropped_samples += excess as u64;
    }
    waiting.dropped_samples += next.dropped_samples;
    waiting.events.extend(next.events);
    waiting.section.extend(next.section);
    if !next.ghosts.is_empty() {
        waiting.ghosts = next.ghosts;
    }
    waiting.tau = next.tau;
}

/// Runs run `run` of `scenario` synchronously to `tau_end` (or its end) and
/// returns what the thread would have streamed: `Started`, one `Batch`,
/// and `Finished` if the run ended. For fixed streams (snapshots, tests).
pub fn record(run: RunId, scenario: &Scenario, tau_end: f64) -> Vec<SimUpdate> {
    let mut s = match Session::new(run, scenario, Start::Initial) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(tau: f64) -> Sample {
        Sample {
            tau,
            theta: 0.0,
            theta_dot: 0.0,
            x: 0.0,
            x_dot: 0.0,
            mode: crate::model::Mode::Rest,
            a_h: 0.0,
            a_v: 0.0,
            base_x: 0.0,
            normal: 1.0,
            friction: 0.0,
        }
    }

    #[test]
    fn merging_keeps_the_newest_samples_and_counts_the_dropped() {
        let mut a = Batch {
            samples: (0..MAX_QUEUED_SAMPLES).map(|k| sample(k as f64)).collect(),
            ..Batch::default()
        };
        let b = Batch {
            samples: (0..10).map(|k| sample((MAX_QUEUED_SAMPLES + k) as f64)).collect(),
            tau: 7.0,
            ..Batch::default()
        };
        merge(&mut a, b);
        assert_eq!(a.samples.len(), MAX_QUEUED_SAMPLES);
        assert_eq!(a.dropped_samples, 10);
        assert_eq!(a.samples[0].tau, 10.0);
        assert_eq!(a.samples.last().map(|s| s.tau), Some((MAX_QUEUED_SAMPLES + 9) as f64));
        assert_eq!(a.tau, 7.0);
    }
}
