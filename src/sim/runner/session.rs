//! One live run, advanced incrementally and without a thread: the
//! simulation the runner's thread owns, usable synchronously in tests and
//! for fixed streams.
//!
//! The run is integrated in *chunks* whose ends lie on a fixed τ grid (the
//! forcing period, split so that no chunk exceeds [`MAX_CHUNK`]). A chunk
//! ends with the step that reaches its end, taken whole
//! ([`Driver::advance_past`](crate::integrate::hybrid::Driver::advance_past)), and steps end on the batch run's end at the
//! latest, as the batch run's do, so chunk ends put no stops in the step
//! sequence: a live run with the same scenario follows the batch trajectory
//! bit for bit to the batch run's end, whatever the playback speed or
//! pauses. (The paper's fixed-step
//! method stops on chunk ends, which are its section-time stops.) What a
//! chunk produces is queued here and *released* up to a τ chosen by the
//! caller (the playhead), which is how the thread paces output in real
//! time without putting step stops at wall-clock times.
//!
//! # Section phase
//!
//! The stroboscopic section is taken at τ_k = (2πk + φ)/Ω_h. At φ = 0 (the
//! default) the driver takes the points from its dense output at k·period,
//! as the batch run does, bit for bit. At any other φ the driver takes no
//! section points: the chunk grid is shifted by φ/Ω_h so that every period
//! boundary is a section time, each chunk is advanced *onto* its end
//! ([`Driver::advance`](crate::integrate::hybrid::Driver::advance)), and the state there is the section point. Those
//! runs stop their steps on chunk ends (one extra stop per chunk, at most
//! one per τ), so they agree with a batch run to the tolerance rather than
//! bit for bit; the section points are the integrator's own states, not
//! interpolated.

use std::collections::VecDeque;

pub use super::playhead::LIVE_SAMPLE_DT;
use super::playhead::{Playhead, release_upto};
use crate::integrate::hybrid::{Advance, Observer, Outputs};
use crate::model::Mode;
use crate::model::system::{EventRecord, N, THETA, THETA_DOT, X, X_DOT};
use crate::sim::Scenario;
use crate::sim::initial_mode;
use crate::sim::protocol::{BaseMotion, Batch, GhostState, RunEnd, RunId, RunInfo, Sample};
use crate::sim::{HistoryRow, SectionRow};

mod driver;
mod ghosts;
mod grid;
mod start;

use driver::{AnyDriver, DriverStart, LiveSystem, live_system};
use ghosts::{Ghost, GhostSink};
use grid::ChunkGrid;
pub use grid::normalise_phase;
pub use start::Start;
use start::perturbed_state;

/// Longest chunk, τ: bounds the data produced ahead of the playhead.
pub const MAX_CHUNK: f64 = 1.0;

/// Output produced ahead of the playhead.
#[derive(Default)]
struct Queue {
    samples: VecDeque<Sample>,
    events: VecDeque<EventRecord>,
    section: VecDeque<SectionRow>,
}

/// The run's extremes so far, for [`RunEnd::Rest`]: tracked as the batch
/// run's collector tracks them (`sim::collect`), so the live answer and
/// the batch one agree.
#[derive(Clone, Copy, Debug, Default)]
struct Peaks {
    /// Largest |Θ| at samples and before events, units of ψ.
    theta: f64,
    /// Largest |sliding displacement| at samples and before events, per R.
    /// Slip keeps one direction between events, so with the values before
    /// events this is exact.
    sliding: f64,
}

impl Peaks {
    fn see(&mut self, geo: &crate::model::geometry::Geometry, y: &[f64; N]) {
        self.theta = self.theta.max(y[THETA].abs());
        self.sliding = self.sliding.max(geo.sliding(y[THETA], y[X]).abs());
    }
}

/// The main trajectory's observer: turns driver output into protocol data.
struct MainSink<'a> {
    probe: &'a dyn LiveSystem,
    base: &'a mut BaseMotion,
    queue: &'a mut Queue,
    peaks: &'a mut Peaks,
    /// τ of the latest event (where a block on a still base came to rest).
    last_event: &'a mut f64,
}

impl Observer<Mode, EventRecord, N> for MainSink<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.peaks.see(&self.probe.params().geo, y);
        let fo = self.probe.params().excitation.forcing(t);
        let base_x = self.base.advance(t, fo.a);
        let (normal, friction) = if mode.is_terminal() {
            (0.0, 0.0)
        } else {
            self.probe.contact_forces(mode, t, y)
        };
        self.queue.samples.push_back(Sample {
            state: HistoryRow::of_state(t, mode, y),
            a_h: fo.a,
            a_v: fo.av,
            base_x,
            normal,
            friction,
            stack: None,
        });
    }

    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        self.queue.section.push_back(SectionRow::of_state(k, t, mode, y));
    }

    fn event(&mut self, _t: f64, _before: Mode, y_before: &[f64; N], record: EventRecord) {
        *self.last_event = record.tau;
        self.peaks.see(&self.probe.params().geo, y_before);
        self.queue.events.push_back(record);
    }
}

/// One live run.
pub struct Session {
    pub(super) play: Playhead,
    driver: AnyDriver,
    probe: Box<dyn LiveSystem>,
    base: BaseMotion,
    queue: Queue,
    ghosts: Vec<Ghost>,
    grid: ChunkGrid,
    /// Index of the next chunk end on the grid.
    next_chunk: u64,
    /// For a record run: its end, τ, after which rest ends the run
    /// ([`RunEnd::Rest`]); on a still base (no excitation) its start.
    rest_after: Option<f64>,
    /// Extremes so far.
    peaks: Peaks,
    /// τ of the latest event of the main trajectory.
    last_event: f64,
    /// Whether the base never moves (no excitation): rest is then final.
    still_base: bool,
    /// Whether section points come from landing on chunk ends (a section
    /// phase other than 0) rather than from the driver.
    exact_sections: bool,
    /// Where the run started: τ, mode, state (the state shown until a
    /// sample is released).
    start: (f64, Mode, [f64; N]),
    /// Where the batch run of the same scenario ends its first advance, τ:
    /// `run.tau_end`, or a record's end. Steps end there at the latest, as
    /// the batch run's do, so the live run follows it bit for bit; past it,
    /// steps end on chunk ends. Never infinite: a block at rest on a still
    /// base has nothing that limits its step.
    batch_end: f64,
}

impl Session {
    /// Starts run `run` of `scenario` from `start`, with the section at
    /// phase 0. Errors (a record file that cannot be read, an inadmissible
    /// start) are one-line messages.
    pub fn new(run: RunId, scenario: &Scenario, start: Start) -> Result<Self, String> {
        Self::with_phase(run, scenario, start, 0.0)
    }

    /// As [`Session::new`], with stroboscopic section points at forcing
    /// phase `phase` (rad, taken modulo 2π): τ_k = (2πk + φ)/Ω_h.
    pub(crate) fn with_phase(run: RunId, scenario: &Scenario, start: Start, phase: f64) -> Result<Self, String> {
        let model = scenario.model().map_err(|e| e.to_string())?;
        let section_period = model.excitation.forcing_period();
        let phase = normalise_phase(phase);
        let omega_h = match &model.excitation {
            crate::model::Excitation::Harmonic(h) => Some(h.omega_h),
            _ => None,
        };
        // The offset is only meaningful with a section (harmonic forcing).
        let offset = match (section_period, omega_h) {
            (Some(period), Some(w)) if phase > 0.0 => (phase / w).min(period),
            _ => 0.0,
        };
        let exact_sections = offset > 0.0;
        let mut system = live_system(model);
        let (tau0, mode0, y0) = match start {
            Start::Initial => {
                let (m, mut y) = initial_mode(system.params(), &scenario.initial).map_err(|e| e.to_string())?;
                let m = system.settle_mode(m, 0.0, &mut y);
                (0.0, m, y)
            }
            Start::Perturbed { tau, y, mode, eps } => {
                let (m, y0) = perturbed_state(system.as_mut(), tau, mode, &y, eps)?;
                (tau, m, y0)
            }
        };
        let grid = match section_period {
            Some(period) => ChunkGrid {
                period,
                parts: (period / MAX_CHUNK).ceil().max(1.0) as u64,
                offset,
            },
            None => ChunkGrid {
                period: MAX_CHUNK,
                parts: 1,
                offset: 0.0,
            },
        };
        let mut next_chunk = 0;
        while grid.end(next_chunk) <= tau0 {
            next_chunk += 1;
        }
        let probe = system.boxed_clone();
        let base = BaseMotion::new(&system.params().excitation, tau0);
        let outputs = Outputs {
            sample_dt: Some(LIVE_SAMPLE_DT),
            section_period: if exact_sections { None } else { section_period },
        };
        let geometry = system.params().geo;
        let mut peaks = Peaks::default();
        peaks.see(&geometry, &y0);
        let from = DriverStart {
            mode: mode0,
            t0: tau0,
            y0,
        };
        let driver = system.into_driver(scenario, from, outputs);
        let still_base = scenario.excitation.kind == crate::sim::scenario::ExcitationKind::None;
        let section_phase = if exact_sections { phase } else { 0.0 };
        Ok(Self {
            play: Playhead::new(run, scenario, geometry, section_period, section_phase, tau0, None),
            driver,
            probe,
            base,
            queue: Queue::default(),
            ghosts: Vec::new(),
            grid,
            next_chunk,
            // Whatever `run.t_end` says: a live run ignores it, and rest after
            // the record lasts for ever. So does rest on a base that never
            // moves: a free-rocking block at rest ends the run there, and
            // the app keeps its picture (the spiral into the origin).
            rest_after: scenario.rest_after_tau().or(still_base.then_some(tau0)),
            last_event: tau0,
            still_base,
            peaks,
            exact_sections,
            start: (tau0, mode0, y0),
            batch_end: scenario
                .record_end_tau()
                .map_or(scenario.tau_end(), |end| end.min(scenario.tau_end())),
        })
    }

    /// The run's id.
    pub fn run(&self) -> RunId {
        self.play.run
    }

    /// What the run is about.
    pub fn info(&self) -> &RunInfo {
        &self.play.info
    }

    /// τ integrated so far (ahead of [`Session::released`] by at most a chunk
    /// once the caller has filled to the playhead).
    pub fn computed(&self) -> f64 {
        self.driver.t()
    }

    /// τ up to which output has been released.
    pub fn released(&self) -> f64 {
        self.play.released
    }

    /// Whether the driver has stopped (terminal mode or error).
    pub fn is_ended(&self) -> bool {
        self.play.ended.is_some()
    }

    /// How the run ended, once everything before the end has been released.
    pub fn end(&self) -> Option<&RunEnd> {
        let drained = self.queue.samples.is_empty() && self.queue.events.is_empty() && self.queue.section.is_empty();
        self.play.end(drained)
    }

    /// The current mode and state (at [`Session::computed`]).
    pub fn state(&self) -> (Mode, [f64; N]) {
        (self.driver.mode(), self.driver.y())
    }

    /// The last released sample's state (what the user sees), falling back
    /// to the integrator's state before any sample was released.
    fn shown_state(&self, last_sample: Option<&Sample>) -> (f64, Mode, [f64; N]) {
        match last_sample {
            Some(s) => {
                let mut y = self.driver.y();
                y[THETA] = s.theta;
                y[THETA_DOT] = s.theta_dot;
                y[X] = s.x;
                y[X_DOT] = s.x_dot;
                (s.tau, s.mode, y)
            }
            // Nothing released yet: the user still sees the start.
            None => self.start,
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

    /// Where the steps of a chunk from `t` to `t_end` end at the latest:
    /// the batch run's end while the run is before it, else the chunk's end.
    fn horizon(&self, t: f64, t_end: f64) -> f64 {
        if t < self.batch_end { self.batch_end } else { t_end }
    }

    /// Integrates one chunk (to the next point of the chunk grid).
    pub(crate) fn advance_chunk(&mut self) {
        if self.play.ended.is_some() {
            return;
        }
        let t = self.driver.t();
        while self.grid.end(self.next_chunk) <= t {
            self.next_chunk += 1;
        }
        let t_end = self.grid.end(self.next_chunk);
        let horizon = self.horizon(t, t_end);
        let mut sink = MainSink {
            probe: self.probe.as_ref(),
            base: &mut self.base,
            queue: &mut self.queue,
            peaks: &mut self.peaks,
            last_event: &mut self.last_event,
        };
        let advanced = if self.exact_sections {
            self.driver.advance_onto(t_end, &mut sink)
        } else {
            self.driver.advance(t_end, horizon, &mut sink)
        };
        match advanced {
            Ok(Advance::Reached) => {
                let t = self.driver.t();
                if self.exact_sections
                    && t == t_end
                    && let Some(k) = self.grid.section_index(self.next_chunk)
                {
                    let (mode, y) = (self.driver.mode(), self.driver.y());
                    self.queue.section.push_back(SectionRow::of_state(k, t, mode, &y));
                }
                if self.rest_after.is_some_and(|end| t >= end) && self.driver.mode() == Mode::Rest {
                    // On a still base the run ends when the block came to
                    // rest: a step at rest there reaches far past it (to the
                    // batch run's end), and the samples after it, all the
                    // same, would only delay the end by tens of seconds of
                    // playback. After a record, at the chunk end where rest
                    // was seen.
                    let tau = if self.still_base {
                        let rest_from = self.last_event.max(self.start.0);
                        self.queue.samples.retain(|s| s.tau <= rest_from + LIVE_SAMPLE_DT);
                        rest_from
                    } else {
                        t
                    };
                    self.play.ended = Some(RunEnd::Rest {
                        tau,
                        max_abs_theta: self.peaks.theta.max(self.driver.peak_theta()),
                        max_abs_sliding: self.peaks.sliding,
                    });
                }
            }
            Ok(Advance::Terminal) => {
                self.play.ended = Some(RunEnd::Terminal {
                    mode: self.driver.mode(),
                    tau: self.driver.t(),
                });
            }
            Err(e) => self.play.ended = Some(RunEnd::Failed(e.to_string())),
        }
        let t_ghost = self.driver.t();
        for g in self.ghosts.iter_mut().filter(|g| !g.done) {
            let horizon = self.batch_end.max(t_ghost);
            match g.driver.advance(t_ghost, horizon, &mut GhostSink(&mut g.states)) {
                Ok(Advance::Reached) => {}
                Ok(Advance::Terminal) | Err(_) => {
                    // A ghost that tumbles or fails freezes where it is: it
                    // is a picture of the spread of trajectories, not a run.
                    g.done = true;
                    let y = g.driver.y();
                    g.states.push_back((
                        g.driver.t(),
                        GhostState {
                            theta: y[THETA],
                            theta_dot: y[THETA_DOT],
                            x: y[X],
                            mode: g.driver.mode(),
                        },
                    ));
                }
            }
        }
    }

    /// Moves everything produced up to `tau` into `batch` (appending), and
    /// advances the playhead there. Ghost states: the latest at or before `tau`.
    pub fn release(&mut self, tau: f64, batch: &mut Batch) {
        let upto = self.play.release_limit(tau, self.driver.t());
        release_upto(&mut self.queue.samples, upto, |s| s.tau, |s| batch.samples.push(s));
        release_upto(&mut self.queue.events, upto, |e| e.tau, |e| batch.events.push(e));
        release_upto(&mut self.queue.section, upto, |p| p.tau, |p| batch.section.push(p));
        if !self.ghosts.is_empty() {
            batch.ghosts.clear();
            for g in &mut self.ghosts {
                while g.states.front().is_some_and(|(t, _)| *t <= upto) {
                    if let Some((_, s)) = g.states.pop_front() {
                        g.latest = s;
                    }
                }
                batch.ghosts.push(g.latest);
            }
        }
        self.play.move_to(upto, self.driver.t(), batch);
    }

    /// A new run of the same scenario from the state shown at the playhead,
    /// with Θ + `eps`, keeping this run's section phase.
    pub(crate) fn perturbed(&self, run: RunId, eps: f64, last_sample: Option<&Sample>) -> Result<Session, String> {
        let (tau, mode, y) = self.shown_state(last_sample);
        Session::with_phase(
            run,
            &self.play.info.scenario,
            Start::Perturbed { tau, y, mode, eps },
            self.play.info.section_phase,
        )
    }

    /// A new run of `scenario` (new parameters) from the state shown at the
    /// playhead, τ running on, with the section at `phase`. Refused (with
    /// the reason) if the state shown is terminal or not admissible under
    /// the new parameters (e.g. past the new tumble angle).
    pub fn continued(
        &self,
        run: RunId,
        scenario: &Scenario,
        phase: f64,
        last_sample: Option<&Sample>,
    ) -> Result<Session, String> {
        let (tau, mode, y) = self.shown_state(last_sample);
        if mode.is_terminal() {
            return Err(format!("the run has ended ({mode:?}): nothing to continue"));
        }
        Session::with_phase(run, scenario, Start::Perturbed { tau, y, mode, eps: 0.0 }, phase)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::{Method, Outcome, simulate};

    fn preset(name: &str) -> Scenario {
        crate::io::config::load(Some(name), None, &[]).expect("preset loads")
    }

    /// Runs `scenario` live, chunk by chunk, until it ends (at most `tau_max`).
    fn live_end(scenario: &Scenario, tau_max: f64) -> RunEnd {
        let mut s = Session::new(RunId(1), scenario, Start::Initial).expect("starts");
        s.fill_to(tau_max);
        let mut batch = Batch::default();
        s.release(f64::INFINITY, &mut batch);
        s.end().cloned().expect("the run ended")
    }

    #[test]
    fn a_record_run_at_rest_after_the_record_ends_with_the_batch_runs_peaks() {
        // El Centro: the statue rocks, comes to rest before the record ends,
        // and the live run stops at the first chunk end after the record.
        let sc = preset("elcentro-statue");
        let record_end = sc.record_end_tau().expect("a record");
        let RunEnd::Rest {
            tau,
            max_abs_theta,
            max_abs_sliding,
        } = live_end(&sc, 10.0 * record_end)
        else {
            panic!("the statue survives El Centro");
        };
        assert!(
            tau >= record_end && tau <= record_end + MAX_CHUNK + 1e-9,
            "stopped at τ = {tau}, record ends at {record_end}"
        );
        let batch = simulate(sc.model().expect("model"), &sc.initial, &sc.run_options()).expect("batch run");
        assert!(
            (max_abs_theta - batch.max_abs_theta).abs() <= 1e-9 * batch.max_abs_theta,
            "live {max_abs_theta} vs batch {}",
            batch.max_abs_theta
        );
        assert!(
            (max_abs_sliding - batch.max_abs_sliding).abs() <= 1e-9 + 1e-6 * batch.max_abs_sliding,
            "live {max_abs_sliding} vs batch {}",
            batch.max_abs_sliding
        );
    }

    /// Every preset's live run, with every method, reaches the batch run's
    /// end: the same tumble or flight at the same τ; for a record, the same
    /// survival; else the same events at the same τ, bit for bit (the live
    /// steps end on the batch run's end, as its do), and the same mode at
    /// the end. Free rocking failed here with a NaN at its impact
    /// accumulation (τ = 21.2): at rest on a still base, where nothing
    /// limits a Taylor step, the live run's step had no end.
    #[test]
    fn every_preset_live_ends_as_its_batch_run_with_every_method() {
        for name in crate::io::presets::names() {
            let base = preset(name);
            for method in [Method::Taylor, Method::Dop853, Method::Dopri5, Method::Ralston] {
                let mut sc = base.clone();
                sc.run.method = Some(method);
                // A stack runs in its own session, compared with its batch
                // run in `stack_session`'s tests.
                if sc.validate().is_err() || sc.stack.is_some() {
                    continue;
                }
                let what = format!("{name} with {method:?}");
                let opts = sc.run_options();
                let batch = simulate(sc.model().expect("model"), &sc.initial, &opts).expect("batch run");
                let mut live = Session::new(RunId(1), &sc, Start::Initial).expect("starts");
                // A record run stops at rest at a chunk end, the batch run
                // at the end of a leg of REST_CHECK_TAU: within a chunk.
                let unforced = sc.excitation.kind == crate::sim::scenario::ExcitationKind::None;
                let slack = if opts.rest_after.is_some() {
                    2.0 * MAX_CHUNK
                } else {
                    0.0
                };
                live.fill_to(batch.tau_end + slack);
                let mut out = Batch::default();
                live.release(batch.tau_end + slack, &mut out);
                match (batch.outcome, live.end()) {
                    (Outcome::Tumbled | Outcome::Flight, Some(RunEnd::Terminal { mode, tau })) => {
                        assert_eq!(*mode, batch.final_mode, "{what}");
                        assert_eq!(*tau, batch.tau_end, "{what}");
                    }
                    (Outcome::Rest, Some(RunEnd::Rest { tau, max_abs_theta, .. })) if opts.rest_after.is_some() => {
                        assert!(
                            (tau - batch.tau_end).abs() <= MAX_CHUNK + 1e-9,
                            "{what}: live rest at {tau}"
                        );
                        let peak = batch.max_abs_theta;
                        assert!(
                            (max_abs_theta - peak).abs() <= 1e-9 * peak,
                            "{what}: {max_abs_theta} vs {peak}"
                        );
                    }
                    (Outcome::Rest, Some(RunEnd::Rest { tau, max_abs_theta, .. })) if unforced => {
                        // On a still base the live run ends at the first
                        // chunk end at rest; the batch run goes on at rest
                        // to run.tau_end. Same impacts, same peak.
                        assert!(*tau <= batch.tau_end, "{what}: live rest at {tau}");
                        let rest_from = batch.events.last().map_or(0.0, |e| e.tau);
                        assert!(
                            *tau >= rest_from && *tau - rest_from <= MAX_CHUNK + 1e-9,
                            "{what}: live rest at {tau}, batch at rest from {rest_from}"
                        );
                        assert_eq!(*max_abs_theta, batch.max_abs_theta, "{what}");
                        assert_eq!(out.events.len(), batch.events.len(), "{what}: events live vs batch");
                        for (a, b) in out.events.iter().zip(&batch.events) {
                            assert!(a.tau == b.tau && a.kind == b.kind, "{what}: live {a:?}, batch {b:?}");
                        }
                    }
                    (Outcome::Rest | Outcome::Running, None) => {
                        let last = out.samples.last().expect("samples");
                        if method == Method::Ralston {
                            // The paper's fixed step stops on chunk ends,
                            // which are its section stops only when a
                            // forcing period is one chunk: the same end (at
                            // rest, or its fixed step chattering through
                            // an impact accumulation), by other steps.
                            let at_rest = last.state.mode == Mode::Rest;
                            assert_eq!(at_rest, batch.outcome == Outcome::Rest, "{what}");
                            continue;
                        }
                        assert_eq!(last.state.mode, batch.final_mode, "{what}");
                        let (n_live, n_batch) = (out.events.len(), batch.events.len());
                        assert_eq!(n_live, n_batch, "{what}: events live vs batch");
                        for (a, b) in out.events.iter().zip(&batch.events) {
                            assert!(a.tau == b.tau && a.kind == b.kind, "{what}: live {a:?}, batch {b:?}");
                        }
                    }
                    (outcome, end) => panic!("{what}: batch {outcome:?} at τ {}, live {end:?}", batch.tau_end),
                }
            }
        }
    }

    #[test]
    fn ghosts_set_on_a_block_at_rest_start_apart_once_it_lifts_off() {
        // The sensitive-dependence lesson: 20 ghosts within 1e-6 of a
        // block at rest on the default scene. A tilt of a block at rest
        // settles back to rest, so the ghosts must start where the block
        // lifts off, and keep their ε there.
        let sc = preset("default");
        let mut live = Session::new(RunId(1), &sc, Start::Initial).expect("starts");
        live.set_ghosts(20, 1e-6, None);
        live.fill_to(8.0);
        let mut out = Batch::default();
        live.release(8.0, &mut out);
        let block = out.samples.last().expect("samples");
        assert!(block.mode != Mode::Rest, "lifted off by τ = 8");
        assert_eq!(out.ghosts.len(), 20);
        let spread: Vec<f64> = out.ghosts.iter().map(|g| (g.theta - block.theta).abs()).collect();
        let least = spread.iter().copied().fold(f64::INFINITY, f64::min);
        let most = spread.iter().copied().fold(0.0, f64::max);
        assert!(
            least > 1e-9,
            "every ghost keeps its perturbation: least |ΔΘ| = {least:e}"
        );
        assert!(most < 1e-3, "and is still close to the block: {most:e}");
    }

    #[test]
    fn a_record_run_that_overturns_ends_terminal_not_at_rest() {
        let sc = preset("kobe-rack");
        let end = live_end(&sc, sc.record_end_tau().expect("a record"));
        assert!(
            matches!(
                end,
                RunEnd::Terminal {
                    mode: Mode::Tumbled,
                    ..
                }
            ),
            "{end:?}"
        );
    }

    /// Everything `scenario` produces live to `tau` with the section at `phase`.
    fn live_batch(scenario: &Scenario, phase: f64, tau: f64) -> Batch {
        let mut s = Session::with_phase(RunId(1), scenario, Start::Initial, phase).expect("starts");
        s.fill_to(tau);
        let mut batch = Batch::default();
        s.release(tau, &mut batch);
        batch
    }

    #[test]
    fn section_points_at_a_phase_lie_on_the_shifted_grid() {
        let sc = preset("default");
        let crate::model::Excitation::Harmonic(h) = sc.model().expect("model").excitation else {
            panic!("the default scene is harmonic");
        };
        let phi = 1.3;
        let batch = live_batch(&sc, phi, 50.0);
        // 50 τ at Ω_h = 8: 63 or 64 points.
        assert!(batch.section.len() >= 63, "{} points", batch.section.len());
        for (i, p) in batch.section.iter().enumerate() {
            assert_eq!(p.k, i as u64, "k counts from 0 at the first section time after τ = 0");
            let miss = h.omega_h * p.tau - phi - std::f64::consts::TAU * p.k as f64;
            assert!(miss.abs() <= 1e-12, "Ω τ_k − φ − 2πk = {miss:e} at k = {}", p.k);
        }
    }

    #[test]
    fn section_points_at_a_phase_are_the_trajectorys_states_there() {
        // The section point at τ_k is the state the run passes through at
        // τ_k: compared with the cubic Hermite interpolant (Θ and Θ') of the
        // phase-0 run's samples around it, away from events.
        let sc = preset("default");
        let at_zero = live_batch(&sc, 0.0, 20.0);
        let shifted = live_batch(&sc, 2.0, 20.0);
        let dt = LIVE_SAMPLE_DT;
        let mut checked = 0;
        for p in &shifted.section {
            let near_event = at_zero.events.iter().any(|e| (e.tau - p.tau).abs() < 2.0 * dt);
            let j = at_zero.samples.partition_point(|s| s.tau <= p.tau);
            if near_event || j == 0 || j >= at_zero.samples.len() {
                continue;
            }
            let (a, b) = (&at_zero.samples[j - 1], &at_zero.samples[j]);
            if a.mode != b.mode {
                continue;
            }
            let h = b.tau - a.tau;
            let s = (p.tau - a.tau) / h;
            let (h00, h10) = (2.0 * s.powi(3) - 3.0 * s * s + 1.0, s.powi(3) - 2.0 * s * s + s);
            let (h01, h11) = (-2.0 * s.powi(3) + 3.0 * s * s, s.powi(3) - s * s);
            let theta = h00 * a.theta + h10 * h * a.theta_dot + h01 * b.theta + h11 * h * b.theta_dot;
            assert!(
                (theta - p.theta).abs() < 1e-7,
                "Θ at τ = {}: section {} vs trajectory {theta}",
                p.tau,
                p.theta
            );
            checked += 1;
        }
        assert!(checked > 10, "only {checked} points away from events");
    }

    #[test]
    fn at_phase_zero_or_two_pi_the_section_is_the_batch_runs_bit_for_bit() {
        let sc = preset("default");
        let tau_end = 30.0;
        let opts = crate::sim::RunOptions {
            tau_end,
            ..sc.run_options()
        };
        let batch = simulate(sc.model().expect("model"), &sc.initial, &opts).expect("batch run");
        for phase in [0.0, std::f64::consts::TAU] {
            let live = live_batch(&sc, phase, tau_end - 1.0);
            assert!(live.section.len() > 30);
            for (a, b) in batch.section.iter().zip(&live.section) {
                assert_eq!(a.k, b.k);
                assert_eq!(a.tau.to_bits(), b.tau.to_bits());
                assert_eq!(a.theta.to_bits(), b.theta.to_bits(), "Θ at k = {}", a.k);
                assert_eq!(a.theta_dot.to_bits(), b.theta_dot.to_bits(), "Θ' at k = {}", a.k);
            }
        }
    }

    #[test]
    fn a_run_continued_with_new_parameters_starts_at_the_shown_state() {
        let sc = preset("default");
        let mut s = Session::new(RunId(1), &sc, Start::Initial).expect("starts");
        s.fill_to(10.0);
        let mut batch = Batch::default();
        s.release(7.0, &mut batch);
        let last = *batch.samples.last().expect("samples");
        let mut next_sc = sc.clone();
        next_sc.excitation.a_v += 0.1;
        let next = s.continued(RunId(2), &next_sc, 0.0, Some(&last)).expect("continues");
        assert_eq!(next.info().tau0, last.tau, "τ runs on");
        assert_eq!(next.info().scenario, next_sc);
        let (mode, y) = next.state();
        assert_eq!(mode, last.mode);
        assert_eq!(y[THETA], last.theta);
        assert_eq!(y[THETA_DOT], last.theta_dot);
    }

    #[test]
    fn a_harmonic_run_at_rest_goes_on() {
        // Rest ends only a record run: under harmonic shaking a block at
        // rest may be set rocking again at any time. A_h = 0.1 (0.1 ψ g)
        // is far below the uplift threshold, so the block stays flat.
        let sets = ["excitation.a_h=0.1".to_string(), "excitation.a_v=0".to_string()];
        let sc = crate::io::config::load(Some("default"), None, &sets).expect("valid");
        let mut s = Session::new(RunId(1), &sc, Start::Initial).expect("starts");
        s.fill_to(20.0);
        assert_eq!(s.state().0, Mode::Rest, "the block stays flat");
        assert!(!s.is_ended(), "a harmonic run at rest goes on");
    }
}
