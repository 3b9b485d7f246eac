//! One live run of a stack of blocks (config `[[stack]]`), advanced chunk
//! by chunk as the block's [`super::session::Session`] is: the same chunk
//! grid, the same release up to the playhead, the same rest rule after a
//! record, so the thread paces, pauses, steps and restarts it the same way.
//!
//! Its driver runs [`StackSystem`] with the stepper the batch run takes
//! (`simulate_stack`: DOPRI5 for `dopri5`, DOP853 otherwise), and its steps
//! end on the batch run's end at the latest, as the block's do: a live run
//! follows `rocking --batch` of the same scene bit for bit up to there.
//!
//! What it streams: every sample carries the whole state
//! ([`StackFrame`]) with the top block in the block's fields (the app
//! shows whichever body the user picks); events come as
//! [`Batch::stack_events`], each with its interface. What it does not
//! do: ghosts, a perturbed restart or a restart from the state shown (a
//! stack starts from rest, as its batch run does); a section phase other
//! than 0.

use std::collections::VecDeque;

use crate::integrate::hybrid::{Advance, Driver, Limits, Observer, Outputs};
use crate::integrate::{Dop853, Dopri5, Stepper};
use crate::model::Geometry;
use crate::model::Mode;
use crate::model::excitation::Excitation;
use crate::model::stack::{MAX_BLOCKS, NS, StackEnd, StackError, StackEvent, StackMode, StackSystem, StackTally};
use crate::sim::protocol::{BaseMotion, Batch, RunEnd, RunId, Sample, StackFrame};
use crate::sim::{Method, Scenario, SectionRow};

use super::playhead::{Playhead, release_upto};
use super::session::{LIVE_SAMPLE_DT, MAX_CHUNK};

/// A stack's driver, whatever its stepper: dispatch per chunk, stepping
/// monomorphised inside.
trait StackDriver: Send {
    fn t(&self) -> f64;
    fn y(&self) -> [f64; NS];
    fn mode(&self) -> StackMode;
    fn tally(&self) -> StackTally;
    /// To `t_end` or past it, by whole steps that end on `horizon` at the
    /// latest.
    fn advance(
        &mut self,
        t_end: f64,
        horizon: f64,
        obs: &mut dyn Observer<StackMode, StackEvent, NS>,
    ) -> Result<Advance, StackError>;
}

/// An observer behind a `dyn` pointer, for the generic driver.
struct Forward<'a>(&'a mut dyn Observer<StackMode, StackEvent, NS>);

impl Observer<StackMode, StackEvent, NS> for Forward<'_> {
    fn sample(&mut self, t: f64, mode: StackMode, y: &[f64; NS]) {
        self.0.sample(t, mode, y);
    }
    fn section(&mut self, k: u64, t: f64, mode: StackMode, y: &[f64; NS]) {
        self.0.section(k, t, mode, y);
    }
    fn event(&mut self, t: f64, before: StackMode, y_before: &[f64; NS], record: StackEvent) {
        self.0.event(t, before, y_before, record);
    }
}

impl<S: Stepper<NS> + Send> StackDriver for Driver<S, StackSystem, NS> {
    fn t(&self) -> f64 {
        Driver::t(self)
    }
    fn y(&self) -> [f64; NS] {
        *Driver::y(self)
    }
    fn mode(&self) -> StackMode {
        Driver::mode(self)
    }
    fn tally(&self) -> StackTally {
        self.system().tally
    }
    fn advance(
        &mut self,
        t_end: f64,
        horizon: f64,
        obs: &mut dyn Observer<StackMode, StackEvent, NS>,
    ) -> Result<Advance, StackError> {
        self.advance_past(t_end, horizon, &mut Forward(obs))
    }
}

/// Output produced ahead of the playhead.
#[derive(Default)]
struct Queue {
    samples: VecDeque<Sample>,
    events: VecDeque<StackEvent>,
    section: VecDeque<(SectionRow, StackFrame)>,
}

/// Turns the driver's output into protocol data.
struct Sink<'a> {
    excitation: &'a Excitation,
    base: &'a mut BaseMotion,
    queue: &'a mut Queue,
    /// Blocks, and the bottom block (the stack's units).
    k: usize,
    geo: Geometry,
    last_event: &'a mut f64,
}

impl Observer<StackMode, StackEvent, NS> for Sink<'_> {
    fn sample(&mut self, t: f64, mode: StackMode, y: &[f64; NS]) {
        let fo = self.excitation.forcing(t);
        let base_x = self.base.advance(t, fo.a);
        let frame = StackFrame { tau: t, mode, y: *y };
        self.queue.samples.push_back(Sample {
            state: frame.body_row(self.k - 1, &self.geo),
            a_h: fo.a,
            a_v: fo.av,
            base_x,
            // A stack's contact forces are its faces' own; the scene does
            // not draw one block's force for them.
            normal: 0.0,
            friction: 0.0,
            stack: Some(frame),
        });
    }

    fn section(&mut self, k: u64, t: f64, mode: StackMode, y: &[f64; NS]) {
        let frame = StackFrame { tau: t, mode, y: *y };
        let row = frame.body_row(self.k - 1, &self.geo);
        let point = SectionRow {
            k,
            tau: t,
            theta: row.theta,
            theta_dot: row.theta_dot,
            x: 0.0,
            x_dot: 0.0,
            mode: row.mode,
        };
        self.queue.section.push_back((point, frame));
    }

    fn event(&mut self, _t: f64, _before: StackMode, _y_before: &[f64; NS], record: StackEvent) {
        *self.last_event = record.tau;
        self.queue.events.push_back(record);
    }
}

/// One live run of a stack.
pub struct StackSession {
    pub(super) play: Playhead,
    driver: Box<dyn StackDriver>,
    excitation: Excitation,
    base: BaseMotion,
    queue: Queue,
    /// Chunk ends: `j · chunk` (a forcing period split into equal parts
    /// of at most [`MAX_CHUNK`], or [`MAX_CHUNK`]).
    chunk: f64,
    period: Option<f64>,
    parts: u64,
    next_chunk: u64,
    /// For a record: its end, after which rest ends the run; on a still
    /// base, 0.
    rest_after: Option<f64>,
    still_base: bool,
    last_event: f64,
    /// Where the batch run's first advance ends: steps end there at the
    /// latest, as its do.
    batch_end: f64,
    k: usize,
    geo: Geometry,
}

impl StackSession {
    /// Starts run `run` of the stack of `scenario` from rest at τ = 0.
    /// Errors are one-line messages.
    pub fn new(run: RunId, scenario: &Scenario) -> Result<Self, String> {
        let geo = scenario
            .stack_geometry()
            .ok_or_else(|| "stack: its blocks do not stand on each other".to_string())?;
        let excitation = scenario.excitation().map_err(|e| e.to_string())?;
        let system = StackSystem::new(geo, excitation.clone(), scenario.run.zeno_eps);
        let mut y0 = [0.0; NS];
        let mode0 = system.settle(StackMode::REST, 0.0, &mut y0);
        let section_period = excitation.forcing_period();
        let opts = scenario.run_options();
        let outputs = Outputs {
            sample_dt: Some(LIVE_SAMPLE_DT),
            section_period,
        };
        // The batch run's steppers (`sim::stack_run`): DOPRI5's when asked,
        // else DOP853's.
        fn boxed<S: Stepper<NS> + Send + 'static>(
            stepper: S,
            system: StackSystem,
            (mode0, y0): (StackMode, [f64; NS]),
            limits: Limits,
            outputs: Outputs,
        ) -> Box<dyn StackDriver> {
            Box::new(Driver::new(stepper, system, mode0, 0.0, y0, limits, outputs))
        }
        let start = (mode0, y0);
        let driver = match opts.method {
            Method::Dopri5 => boxed(Dopri5::new(opts.tol), system, start, opts.limits, outputs),
            Method::Taylor | Method::Dop853 | Method::Ralston => {
                boxed(Dop853::new(opts.tol), system, start, opts.limits, outputs)
            }
        };
        let parts = section_period.map_or(1, |p| (p / MAX_CHUNK).ceil().max(1.0) as u64);
        let chunk = section_period.map_or(MAX_CHUNK, |p| p / parts as f64);
        let still_base = scenario.excitation.kind == crate::sim::scenario::ExcitationKind::None;
        let geometry = scenario.geometry();
        let base = BaseMotion::new(&excitation, 0.0);
        Ok(Self {
            play: Playhead::new(run, scenario, geometry, section_period, 0.0, 0.0, Some(geo)),
            driver,
            excitation,
            base,
            queue: Queue::default(),
            chunk,
            period: section_period,
            parts,
            next_chunk: 1,
            rest_after: scenario.record_end_tau().or(still_base.then_some(0.0)),
            still_base,
            last_event: 0.0,
            batch_end: scenario
                .record_end_tau()
                .map_or(scenario.tau_end(), |end| end.min(scenario.tau_end())),
            k: geo.k,
            geo: geometry,
        })
    }

    /// τ integrated so far.
    pub fn computed(&self) -> f64 {
        self.driver.t()
    }

    /// How the run ended, once everything before the end is released.
    pub fn end(&self) -> Option<&RunEnd> {
        let drained = self.queue.samples.is_empty() && self.queue.events.is_empty() && self.queue.section.is_empty();
        self.play.end(drained)
    }

    /// The contacts and state at [`StackSession::computed`].
    pub fn state(&self) -> (StackMode, [f64; NS]) {
        (self.driver.mode(), self.driver.y())
    }

    /// The `j`-th chunk end: a period boundary is `k · period` exactly, as
    /// the driver computes section times.
    fn chunk_end(&self, j: u64) -> f64 {
        match self.period {
            Some(period) => {
                let (k, i) = (j / self.parts, j % self.parts);
                let start = k as f64 * period;
                if i == 0 { start } else { start + i as f64 * self.chunk }
            }
            None => j as f64 * self.chunk,
        }
    }

    /// τ of the next sample not yet released.
    pub(crate) fn next_sample_tau(&self) -> Option<f64> {
        self.queue.samples.front().map(|s| s.tau)
    }

    /// Integrates chunk by chunk until `tau` is computed or the run ends.
    pub(crate) fn fill_to(&mut self, tau: f64) {
        while self.play.ended.is_none() && self.driver.t() < tau {
            self.advance_chunk();
        }
    }

    /// Integrates one chunk.
    pub(crate) fn advance_chunk(&mut self) {
        if self.play.ended.is_some() {
            return;
        }
        let t = self.driver.t();
        while self.chunk_end(self.next_chunk) <= t {
            self.next_chunk += 1;
        }
        let t_end = self.chunk_end(self.next_chunk);
        let horizon = if t < self.batch_end { self.batch_end } else { t_end };
        let mut sink = Sink {
            excitation: &self.excitation,
            base: &mut self.base,
            queue: &mut self.queue,
            k: self.k,
            geo: self.geo,
            last_event: &mut self.last_event,
        };
        match self.driver.advance(t_end, horizon, &mut sink) {
            Ok(Advance::Reached) => {
                let t = self.driver.t();
                if self.rest_after.is_some_and(|end| t >= end) && self.driver.mode().at_rest(self.k) {
                    // As the block's run: on a still base at once (from
                    // the last event), after a record at this chunk end.
                    let tau = if self.still_base {
                        let from = self.last_event;
                        self.queue.samples.retain(|s| s.tau <= from + LIVE_SAMPLE_DT);
                        from
                    } else {
                        t
                    };
                    let tally = self.driver.tally();
                    let peak = tally.max_phi[..self.k].iter().copied().fold(0.0, f64::max);
                    self.play.ended = Some(RunEnd::Rest {
                        tau,
                        max_abs_theta: peak / self.geo.psi,
                        max_abs_sliding: tally.max_slide / self.geo.r,
                    });
                }
            }
            Ok(Advance::Terminal) => {
                let mode = match self.driver.mode().end {
                    Some(StackEnd::Flight(_)) => Mode::Flight,
                    Some(StackEnd::Overturned(_)) | None => Mode::Tumbled,
                };
                self.play.ended = Some(RunEnd::Terminal {
                    mode,
                    tau: self.driver.t(),
                });
            }
            Err(e) => self.play.ended = Some(RunEnd::Failed(e.to_string())),
        }
    }

    /// Moves everything produced up to `tau` into `batch` and advances the
    /// playhead there.
    pub fn release(&mut self, tau: f64, batch: &mut Batch) {
        let upto = self.play.release_limit(tau, self.driver.t());
        release_upto(&mut self.queue.samples, upto, |s| s.tau, |s| batch.samples.push(s));
        release_upto(&mut self.queue.events, upto, |e| e.tau, |e| batch.stack_events.push(e));
        release_upto(
            &mut self.queue.section,
            upto,
            |(p, _)| p.tau,
            |(p, f)| {
                batch.section.push(p);
                batch.stack_section.push(f);
            },
        );
        self.play.move_to(upto, self.driver.t(), batch);
    }

    /// The largest |φ_j| so far of each block, rad (exact: the model's
    /// observers stop at each extremum).
    pub fn max_phi(&self) -> [f64; MAX_BLOCKS] {
        self.driver.tally().max_phi
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::stack::StackEventKind;
    use crate::sim::stack_run::simulate_stack;

    fn preset(name: &str) -> Scenario {
        crate::io::config::load(Some(name), None, &[]).expect("preset loads")
    }

    /// Every stack preset's live run ends as its batch run: the same
    /// events at the same τ (bit for bit: the live steps end on the batch
    /// run's end, as its do) up to the batch run's end, and the same
    /// overturning at the same τ.
    #[test]
    fn every_stack_preset_live_has_the_batch_runs_events() {
        for name in ["tombstone", "statue-on-pedestal", "stack-patterns"] {
            let sc = preset(name);
            let opts = sc.run_options();
            let geo = sc.stack_geometry().expect("a stack");
            let batch =
                simulate_stack(geo, sc.excitation().expect("excitation"), sc.run.zeno_eps, &opts).expect("batch run");
            let mut live = StackSession::new(RunId(1), &sc).expect("starts");
            let until = sc.record_end_tau().map_or(batch.tau_end, |e| e.min(batch.tau_end));
            live.fill_to(until);
            let mut out = Batch::default();
            live.release(until, &mut out);
            let batch_events: Vec<_> = batch.events.iter().filter(|e| e.tau <= until).collect();
            assert_eq!(out.stack_events.len(), batch_events.len(), "{name}");
            for (a, b) in out.stack_events.iter().zip(&batch_events) {
                assert!(
                    a.tau == b.tau && a.kind == b.kind && a.body == b.body,
                    "{name}: {a:?} vs {b:?}"
                );
            }
            if let Some((StackEnd::Overturned(i), tau)) = batch.end {
                let last = out.stack_events.last().expect("events");
                assert_eq!(
                    (last.kind, last.body, last.tau),
                    (StackEventKind::Overturn, i, tau),
                    "{name}"
                );
                assert!(
                    matches!(
                        live.end(),
                        Some(RunEnd::Terminal {
                            mode: Mode::Tumbled,
                            ..
                        })
                    ),
                    "{name}"
                );
            }
        }
    }
}
