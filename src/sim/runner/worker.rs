//! The simulation thread's loop: it waits for commands or for the next
//! tick, applies commands, integrates and releases output at the requested
//! speed (the pacing described in [`super`]), and flushes its outbox.

use std::time::{Duration, Instant};

use super::TICK;
use super::live::Live;
use super::outbox::Outbox;
use super::session::Start;
use crate::sim::Scenario;
use crate::sim::job::{Link, Stopped};
use crate::sim::protocol::{Batch, MAX_GHOSTS, RunEnd, RunId, Sample, SimCommand, SimUpdate, Speed, StartFrom};

/// Wall-clock time the thread integrates before it releases output at
/// [`Speed::Max`] (and the most it lets a paced tick overrun).
const WORK_SLICE: Duration = Duration::from_millis(12);

/// How long a thread whose outbox the channel refused waits before it
/// tries again: soon, but without spinning.
const RETRY: Duration = Duration::from_millis(4);

/// The thread's state.
pub(super) struct Worker {
    link: Link<SimUpdate, SimCommand>,
    outbox: Outbox,
    session: Option<Live>,
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
    /// Forcing phase of the stroboscopic section, rad, for every new run.
    section_phase: f64,
}

enum Flow {
    Continue,
    Stop,
}

impl Worker {
    pub(super) fn new(link: Link<SimUpdate, SimCommand>, scenario: Scenario, speed: Speed, paused: bool) -> Self {
        Self {
            link,
            outbox: Outbox::default(),
            session: None,
            last_sample: None,
            paused,
            speed,
            anchor: None,
            ghosts: (0, 0.0),
            deferred_finish: false,
            scenario,
            section_phase: 0.0,
        }
    }

    /// Runs until `Shutdown`, or until the handle is dropped.
    pub(super) fn run(mut self, run: RunId) {
        let scenario = self.scenario.clone();
        let phase = self.section_phase;
        self.start(run, |r| Live::with_phase(r, &scenario, Start::Initial, phase));
        loop {
            let flow = match self.wait() {
                Ok(Some(cmd)) => self.handle(cmd),
                Ok(None) => Flow::Continue,
                Err(Stopped) => Flow::Stop,
            };
            if let Flow::Stop = flow {
                return;
            }
            // Apply every command already waiting before doing work.
            loop {
                let flow = match self.link.try_command() {
                    Ok(Some(cmd)) => self.handle(cmd),
                    Ok(None) => break,
                    Err(Stopped) => Flow::Stop,
                };
                if let Flow::Stop = flow {
                    return;
                }
            }
            if !self.paused && !self.outbox.backpressured() {
                self.work();
            }
            self.outbox.flush(&self.link);
        }
    }

    /// Blocks until a command arrives or it is time to work again.
    fn wait(&mut self) -> Result<Option<SimCommand>, Stopped> {
        let idle = self.paused
            || self
                .session
                .as_ref()
                .is_none_or(|s| s.end().is_some() && self.deferred_finish);
        let timeout = if !self.outbox.is_empty() {
            Some(RETRY)
        } else if idle {
            None
        } else {
            match self.speed {
                Speed::Max => Some(Duration::ZERO),
                Speed::RealTime(_) => Some(TICK),
            }
        };
        match timeout {
            Some(d) if d.is_zero() => self.link.try_command(),
            t => self.link.next_command(t),
        }
    }

    fn handle(&mut self, cmd: SimCommand) -> Flow {
        match cmd {
            SimCommand::Shutdown => return Flow::Stop,
            SimCommand::SetParams { run, scenario, from } => {
                self.scenario = *scenario;
                self.restart(run, from);
            }
            SimCommand::SetSectionPhase { run, phase } => {
                self.section_phase = super::session::normalise_phase(phase);
                self.restart(run, StartFrom::Current);
            }
            SimCommand::Reset { run } => {
                self.restart(run, StartFrom::Initial);
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

    /// Starts run `run` of the configuration last asked for, at the
    /// current section phase, from `from`. A run that cannot continue from
    /// the current state (none shown, terminal, or not admissible under the
    /// new parameters) starts from the initial state instead: a drag across
    /// a value where the state is not admissible must not leave the user
    /// with a failed run.
    fn restart(&mut self, run: RunId, from: StartFrom) {
        let scenario = self.scenario.clone();
        let phase = self.section_phase;
        let continued = match (from, &self.session) {
            (StartFrom::Current, Some(s)) => s.continued(run, &scenario, phase, self.last_sample.as_ref()).ok(),
            _ => None,
        };
        self.start(run, |r| match continued {
            Some(s) => Ok(s),
            None => Live::with_phase(r, &scenario, Start::Initial, phase),
        });
    }

    /// Replaces the session with `make(run)`; a failure is reported as the
    /// new run's `Finished`.
    fn start(&mut self, run: RunId, make: impl FnOnce(RunId) -> Result<Live, String>) {
        self.outbox.purge_before(run);
        self.anchor = None;
        self.last_sample = None;
        self.deferred_finish = false;
        match make(run) {
            Ok(mut s) => {
                if self.ghosts.0 > 0 {
                    s.set_ghosts(self.ghosts.0, self.ghosts.1, None);
                }
                self.outbox.push(SimUpdate::Started {
                    run,
                    info: Box::new(s.info().clone()),
                });
                self.session = Some(s);
                if self.paused {
                    self.queue_first_frame();
                }
                self.queue_paused();
            }
            Err(msg) => {
                // Keep the old session's scenario for a later Reset, but it no
                // longer produces output under the new id.
                self.session = None;
                self.outbox.push(SimUpdate::Finished {
                    run,
                    end: RunEnd::Failed(msg),
                });
                self.deferred_finish = true;
            }
        }
    }

    fn queue_paused(&mut self) {
        if let Some(s) = &self.session {
            self.outbox.push(SimUpdate::Paused {
                run: s.run(),
                paused: self.paused,
                tau: s.released(),
            });
        }
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
            self.outbox.push(SimUpdate::Finished {
                run: s.run(),
                end: end.clone(),
            });
            self.deferred_finish = true;
        }
    }

    /// A paused run's first frame, so that the app shows the block where
    /// it starts (and the ghosts there) before the user presses Play.
    fn queue_first_frame(&mut self) {
        let Some(s) = self.session.as_mut() else { return };
        let mut batch = Batch::default();
        s.first_frame(&mut batch);
        if !batch.samples.is_empty() {
            self.queue_batch(batch);
        }
    }

    /// Queues `batch`, merging it into a waiting batch of the same run.
    fn queue_batch(&mut self, batch: Batch) {
        let Some(run) = self.session.as_ref().map(Live::run) else {
            return;
        };
        if let Some(last) = batch.samples.last() {
            self.last_sample = Some(*last);
        }
        self.outbox.push_batch(run, batch);
    }
}
