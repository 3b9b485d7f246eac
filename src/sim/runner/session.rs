//! One live run, advanced incrementally and without a thread: the
//! simulation the runner's thread owns, usable synchronously in tests and
//! for fixed streams.
//!
//! The run is integrated in *chunks* whose ends lie on a fixed τ grid (the
//! forcing period, split so that no chunk exceeds [`MAX_CHUNK`]). A chunk
//! ends with the step that reaches its end, taken whole
//! ([`Driver::advance_past`]), so chunk ends put no stops in the step
//! sequence: a live run with the same scenario follows the batch trajectory
//! bit for bit (up to the batch run's last step, shortened to end on its
//! τ_end), whatever the playback speed or pauses. (The paper's fixed-step
//! method stops on chunk ends, which are its section-time stops.) What a
//! chunk produces is queued here and *released* up to a τ chosen by the
//! caller (the playhead), which is how the thread paces output in real
//! time without putting step stops at wall-clock times.

use std::collections::VecDeque;

use crate::integrate::Stepper;
use crate::integrate::hybrid::{Advance, Driver, Limits, Observer, Outputs};
use crate::model::system::{EventRecord, ModelError, N, THETA, THETA_DOT, X, X_DOT};
use crate::model::{BlockSystem, Mode};
use crate::sim::Scenario;
use crate::sim::method::{StepperVisitor, with_stepper};
use crate::sim::protocol::{BaseMotion, Batch, GhostState, RunEnd, RunId, RunInfo, Sample};
use crate::sim::{HistoryRow, SectionRow};
use crate::sim::{InitialState, initial_mode};

/// Spacing of the live samples, τ. Fine enough that the paper's block
/// (p ≈ 1.9 s⁻¹) shows a new pose about 40 times a second at ×0.1 playback;
/// samples come from the dense output, so they add no step stops.
pub const LIVE_SAMPLE_DT: f64 = 0.005;

/// Longest chunk, τ: bounds the data produced ahead of the playhead.
pub const MAX_CHUNK: f64 = 1.0;

/// The driver of a live run, whatever its method: a trait object, so the
/// session and a hundred ghosts hold one pointer each. Dispatch is per
/// chunk and per output, not per step: the stepping inside
/// [`Driver::advance_past`] stays monomorphised.
trait LiveDriver: Send {
    fn t(&self) -> f64;
    fn y(&self) -> [f64; N];
    fn mode(&self) -> Mode;
    /// To `t_end` or past it, by whole steps ([`Driver::advance_past`]).
    fn advance(&mut self, t_end: f64, obs: &mut dyn Observer<Mode, EventRecord, N>) -> Result<Advance, ModelError>;
    /// Largest |Θ| the model found at its rocking peaks (between samples).
    fn peak_theta(&self) -> f64;
}

/// An observer behind a `dyn` pointer, for the generic driver.
struct Forward<'a>(&'a mut dyn Observer<Mode, EventRecord, N>);

impl Observer<Mode, EventRecord, N> for Forward<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.sample(t, mode, y);
    }
    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.section(k, t, mode, y);
    }
    fn event(&mut self, t: f64, before: Mode, y_before: &[f64; N], record: EventRecord) {
        self.0.event(t, before, y_before, record);
    }
}

impl<S: Stepper<N> + Send> LiveDriver for Driver<S, BlockSystem, N> {
    fn t(&self) -> f64 {
        Driver::t(self)
    }
    fn y(&self) -> [f64; N] {
        *Driver::y(self)
    }
    fn mode(&self) -> Mode {
        Driver::mode(self)
    }
    fn advance(&mut self, t_end: f64, obs: &mut dyn Observer<Mode, EventRecord, N>) -> Result<Advance, ModelError> {
        self.advance_past(t_end, &mut Forward(obs))
    }
    fn peak_theta(&self) -> f64 {
        self.system().tally.max_abs_theta
    }
}

type AnyDriver = Box<dyn LiveDriver>;

/// A live driver of `scenario`'s method.
fn live_driver(
    scenario: &Scenario,
    system: BlockSystem,
    mode: Mode,
    t0: f64,
    y0: [f64; N],
    outputs: Outputs,
) -> AnyDriver {
    /// The driver, waiting for its stepper.
    struct Make {
        system: BlockSystem,
        mode: Mode,
        t0: f64,
        y0: [f64; N],
        limits: Limits,
        outputs: Outputs,
    }
    impl StepperVisitor for Make {
        type Output = AnyDriver;
        fn visit<S: Stepper<N> + Send + 'static>(self, stepper: S) -> AnyDriver {
            Box::new(Driver::new(
                stepper,
                self.system,
                self.mode,
                self.t0,
                self.y0,
                self.limits,
                self.outputs,
            ))
        }
    }
    let opts = scenario.run_options();
    let make = Make {
        system,
        mode,
        t0,
        y0,
        limits: opts.limits,
        outputs,
    };
    with_stepper(opts.method, opts.tol, make)
}

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
    probe: &'a BlockSystem,
    base: &'a mut BaseMotion,
    queue: &'a mut Queue,
    peaks: &'a mut Peaks,
}

impl Observer<Mode, EventRecord, N> for MainSink<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.peaks.see(&self.probe.model.geo, y);
        let fo = self.probe.model.excitation.forcing(t);
        let base_x = self.base.advance(t, fo.a);
        let (normal, friction) = if mode.is_terminal() {
            (0.0, 0.0)
        } else {
            let acc = self.probe.accel(mode, t, y);
            (acc.normal, acc.friction)
        };
        self.queue.samples.push_back(Sample {
            state: HistoryRow::of_state(t, mode, y),
            a_h: fo.a,
            a_v: fo.av,
            base_x,
            normal,
            friction,
        });
    }

    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        self.queue.section.push_back(SectionRow::of_state(k, t, mode, y));
    }

    fn event(&mut self, _t: f64, _before: Mode, y_before: &[f64; N], record: EventRecord) {
        self.peaks.see(&self.probe.model.geo, y_before);
        self.queue.events.push_back(record);
    }
}

/// A ghost copy: its own driver, and its states on the sample grid.
struct Ghost {
    driver: AnyDriver,
    states: VecDeque<(f64, GhostState)>,
    /// Last released state.
    latest: GhostState,
    done: bool,
}

struct GhostSink<'a>(&'a mut VecDeque<(f64, GhostState)>);

impl Observer<Mode, EventRecord, N> for GhostSink<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.push_back((
            t,
            GhostState {
                theta: y[THETA],
                x: y[X],
                mode,
            },
        ));
    }
    fn section(&mut self, _k: u64, _t: f64, _mode: Mode, _y: &[f64; N]) {}
    fn event(&mut self, _t: f64, _before: Mode, _y_before: &[f64; N], _record: EventRecord) {}
}

/// The τ grid of chunk ends: each forcing period split into `parts`.
/// Period boundaries are computed as `k · period`, exactly as the driver
/// computes section times, so they coincide bit for bit.
#[derive(Clone, Copy, Debug)]
struct ChunkGrid {
    period: f64,
    parts: u64,
}

impl ChunkGrid {
    /// The `j`-th chunk end.
    fn end(&self, j: u64) -> f64 {
        let (k, i) = (j / self.parts, j % self.parts);
        let start = k as f64 * self.period;
        if i == 0 {
            start
        } else {
            start + i as f64 * (self.period / self.parts as f64)
        }
    }
}

/// Where a run starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Start {
    /// τ = 0 and the scenario's initial state.
    Initial,
    /// From the state `y` in `mode` at `tau`, with Θ increased by `eps`.
    Perturbed {
        /// τ to start at.
        tau: f64,
        /// State to start from.
        y: [f64; N],
        /// Its mode.
        mode: Mode,
        /// Added to Θ.
        eps: f64,
    },
}

/// The mode and state of a block restarted from `(mode, y)` with Θ + `eps`.
///
/// X' is kept where the contact slips, and recomputed as the no-slip value
/// where the pivot sticks (a perturbed Θ changes it), so the perturbed state
/// is admissible for the same contact.
fn perturbed_state(
    system: &mut BlockSystem,
    tau: f64,
    mode: Mode,
    y: &[f64; N],
    eps: f64,
) -> Result<(Mode, [f64; N]), String> {
    let theta = y[THETA] + eps;
    let tumble = system.tumble_angle();
    if !theta.is_finite() || theta.abs() >= tumble {
        return Err(format!(
            "perturbed Θ = {theta} is not inside the tumble angle ±{tumble}"
        ));
    }
    let keeps_slip = match mode {
        Mode::Slide { .. } | Mode::SlideRock { .. } => true,
        Mode::Rest | Mode::Rock { .. } | Mode::Tumbled | Mode::Flight => false,
    };
    let init = InitialState {
        theta,
        theta_dot: y[THETA_DOT],
        x_dot: keeps_slip.then_some(y[X_DOT]),
    };
    let (m, mut y0) = initial_mode(&system.model, &init).map_err(|e| e.to_string())?;
    y0[X] = y[X];
    let m = system.settle(m, tau, &mut y0);
    Ok((m, y0))
}

/// One live run.
pub struct Session {
    run: RunId,
    info: RunInfo,
    driver: AnyDriver,
    probe: BlockSystem,
    base: BaseMotion,
    queue: Queue,
    ghosts: Vec<Ghost>,
    grid: ChunkGrid,
    /// Index of the next chunk end on the grid.
    next_chunk: u64,
    /// How the run ended, once the driver stopped.
    ended: Option<RunEnd>,
    /// For a record run: its end, τ, after which rest ends the run
    /// ([`RunEnd::Rest`]).
    rest_after: Option<f64>,
    /// Extremes so far.
    peaks: Peaks,
    /// τ up to which output has been released.
    released: f64,
}

impl Session {
    /// Starts run `run` of `scenario` from `start`. Errors (a record file that
    /// cannot be read, an inadmissible start) are one-line messages.
    pub fn new(run: RunId, scenario: &Scenario, start: Start) -> Result<Self, String> {
        let model = scenario.model().map_err(|e| e.to_string())?;
        let section_period = model.excitation.forcing_period();
        let mut system = BlockSystem::new(model);
        let (tau0, mode0, y0) = match start {
            Start::Initial => {
                let (m, mut y) = initial_mode(&system.model, &scenario.initial).map_err(|e| e.to_string())?;
                let m = system.settle(m, 0.0, &mut y);
                (0.0, m, y)
            }
            Start::Perturbed { tau, y, mode, eps } => {
                let (m, y0) = perturbed_state(&mut system, tau, mode, &y, eps)?;
                (tau, m, y0)
            }
        };
        let grid = match section_period {
            Some(period) => ChunkGrid {
                period,
                parts: (period / MAX_CHUNK).ceil().max(1.0) as u64,
            },
            None => ChunkGrid {
                period: MAX_CHUNK,
                parts: 1,
            },
        };
        let mut next_chunk = 0;
        while grid.end(next_chunk) <= tau0 {
            next_chunk += 1;
        }
        let probe = system.clone();
        let base = BaseMotion::new(&system.model.excitation, tau0);
        let outputs = Outputs {
            sample_dt: Some(LIVE_SAMPLE_DT),
            section_period,
        };
        let geometry = system.model.geo;
        let mut peaks = Peaks::default();
        peaks.see(&geometry, &y0);
        let driver = live_driver(scenario, system, mode0, tau0, y0, outputs);
        Ok(Self {
            run,
            info: RunInfo {
                scenario: scenario.clone(),
                geometry,
                section_period,
                tau0,
                sample_dt: LIVE_SAMPLE_DT,
            },
            driver,
            probe,
            base,
            queue: Queue::default(),
            ghosts: Vec::new(),
            grid,
            next_chunk,
            ended: None,
            // Whatever `run.t_end` says: a live run ignores it, and rest after
            // the record lasts for ever.
            rest_after: scenario.record_end_tau(),
            peaks,
            released: tau0,
        })
    }

    /// The run's id.
    pub fn run(&self) -> RunId {
        self.run
    }

    /// What the run is about.
    pub fn info(&self) -> &RunInfo {
        &self.info
    }

    /// τ integrated so far (ahead of [`Session::released`] by at most a chunk
    /// once the caller has filled to the playhead).
    pub fn computed(&self) -> f64 {
        self.driver.t()
    }

    /// τ up to which output has been released.
    pub fn released(&self) -> f64 {
        self.released
    }

    /// Whether the driver has stopped (terminal mode or error).
    pub fn is_ended(&self) -> bool {
        self.ended.is_some()
    }

    /// How the run ended, once everything before the end has been released.
    pub fn end(&self) -> Option<&RunEnd> {
        let drained = self.queue.samples.is_empty() && self.queue.events.is_empty() && self.queue.section.is_empty();
        if drained { self.ended.as_ref() } else { None }
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
            None => (self.driver.t(), self.driver.mode(), self.driver.y()),
        }
    }

    /// Integrates chunk by chunk until `tau` is computed or the run ends.
    pub fn fill_to(&mut self, tau: f64) {
        while self.ended.is_none() && self.driver.t() < tau {
            self.advance_chunk();
        }
    }

    /// Integrates one chunk (to the next point of the chunk grid).
    pub fn advance_chunk(&mut self) {
        if self.ended.is_some() {
            return;
        }
        let t = self.driver.t();
        while self.grid.end(self.next_chunk) <= t {
            self.next_chunk += 1;
        }
        let t_end = self.grid.end(self.next_chunk);
        let mut sink = MainSink {
            probe: &self.probe,
            base: &mut self.base,
            queue: &mut self.queue,
            peaks: &mut self.peaks,
        };
        match self.driver.advance(t_end, &mut sink) {
            Ok(Advance::Reached) => {
                let t = self.driver.t();
                if self.rest_after.is_some_and(|end| t >= end) && self.driver.mode() == Mode::Rest {
                    self.ended = Some(RunEnd::Rest {
                        tau: t,
                        max_abs_theta: self.peaks.theta.max(self.driver.peak_theta()),
                        max_abs_sliding: self.peaks.sliding,
                    });
                }
            }
            Ok(Advance::Terminal) => {
                self.ended = Some(RunEnd::Terminal {
                    mode: self.driver.mode(),
                    tau: self.driver.t(),
                });
            }
            Err(e) => self.ended = Some(RunEnd::Failed(e.to_string())),
        }
        let t_ghost = self.driver.t();
        for g in self.ghosts.iter_mut().filter(|g| !g.done) {
            match g.driver.advance(t_ghost, &mut GhostSink(&mut g.states)) {
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
        let upto = if self.ended.is_some() {
            tau
        } else {
            tau.min(self.driver.t())
        };
        while self.queue.samples.front().is_some_and(|s| s.tau <= upto) {
            if let Some(s) = self.queue.samples.pop_front() {
                batch.samples.push(s);
            }
        }
        while self.queue.events.front().is_some_and(|e| e.tau <= upto) {
            if let Some(e) = self.queue.events.pop_front() {
                batch.events.push(e);
            }
        }
        while self.queue.section.front().is_some_and(|p| p.tau <= upto) {
            if let Some(p) = self.queue.section.pop_front() {
                batch.section.push(p);
            }
        }
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
        if upto > self.released {
            self.released = upto.min(self.driver.t());
        }
        batch.tau = self.released;
    }

    /// Replaces the ghosts with `count` copies started from the state shown
    /// at the playhead (`last_sample`), Θ perturbed by `eps·(k+1)/count`.
    pub fn set_ghosts(&mut self, count: usize, eps: f64, last_sample: Option<&Sample>) {
        self.ghosts.clear();
        if count == 0 {
            return;
        }
        let (tau, mode, y) = self.shown_state(last_sample);
        for k in 0..count {
            let delta = eps * (k as f64 + 1.0) / count as f64;
            let mut system = BlockSystem::new(self.probe.model.clone());
            let Ok((m, y0)) = perturbed_state(&mut system, tau, mode, &y, delta) else {
                continue;
            };
            let outputs = Outputs {
                sample_dt: Some(LIVE_SAMPLE_DT),
                section_period: None,
            };
            let mut driver = live_driver(&self.info.scenario, system, m, tau, y0, outputs);
            let mut states = VecDeque::new();
            // Bring the ghost level with the main trajectory's computed τ.
            let done = !matches!(
                driver.advance(self.driver.t(), &mut GhostSink(&mut states)),
                Ok(Advance::Reached)
            );
            self.ghosts.push(Ghost {
                latest: GhostState {
                    theta: y0[THETA],
                    x: y0[X],
                    mode: m,
                },
                driver,
                states,
                done,
            });
        }
    }

    /// A new run of the same scenario from the state shown at the playhead,
    /// with Θ + `eps`.
    pub fn perturbed(&self, run: RunId, eps: f64, last_sample: Option<&Sample>) -> Result<Session, String> {
        let (tau, mode, y) = self.shown_state(last_sample);
        Session::new(run, &self.info.scenario, Start::Perturbed { tau, y, mode, eps })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::simulate;

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
