//! The ghosts: perturbed copies of a live run, started where the block is shown (or where it lifts off), that picture the spread of trajectories.

use std::collections::VecDeque;

use super::driver::{AnyDriver, DriverStart, live_system};
use super::start::perturbed_state;
use super::{LIVE_SAMPLE_DT, MAX_CHUNK, Session};
use crate::integrate::hybrid::{Advance, Observer, Outputs};
use crate::model::Mode;
use crate::model::system::{EventRecord, N, THETA, THETA_DOT, X};
use crate::sim::protocol::{GhostState, Sample};

/// A ghost copy: its own driver, and its states on the sample grid.
pub(super) struct Ghost {
    pub(super) driver: AnyDriver,
    pub(super) states: VecDeque<(f64, GhostState)>,
    /// Last released state.
    pub(super) latest: GhostState,
    pub(super) done: bool,
}

pub(super) struct GhostSink<'a>(pub(super) &'a mut VecDeque<(f64, GhostState)>);

impl Observer<Mode, EventRecord, N> for GhostSink<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.push_back((
            t,
            GhostState {
                theta: y[THETA],
                theta_dot: y[THETA_DOT],
                x: y[X],
                mode,
            },
        ));
    }
    fn section(&mut self, _k: u64, _t: f64, _mode: Mode, _y: &[f64; N]) {}
    fn event(&mut self, _t: f64, _before: Mode, _y_before: &[f64; N], _record: EventRecord) {}
}

/// Keeps the first sample that is not at rest (where a block at rest
/// starts to move).
struct FirstMove(Option<(f64, Mode, [f64; N])>);

impl Observer<Mode, EventRecord, N> for FirstMove {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        if self.0.is_none() && mode != Mode::Rest {
            self.0 = Some((t, mode, *y));
        }
    }
    fn section(&mut self, _k: u64, _t: f64, _mode: Mode, _y: &[f64; N]) {}
    fn event(&mut self, _t: f64, _before: Mode, _y_before: &[f64; N], _record: EventRecord) {}
}

impl Session {
    /// Replaces the ghosts with `count` copies started from the state shown
    /// at the playhead (`last_sample`), Θ perturbed by `eps·(k+1)/count`.
    pub fn set_ghosts(&mut self, count: usize, eps: f64, last_sample: Option<&Sample>) {
        self.ghosts.clear();
        if count == 0 {
            return;
        }
        let shown = self.shown_state(last_sample);
        // A tilt given to a block at rest settles back to rest (the base
        // has not lifted it), and every copy would be the block itself:
        // the ghosts start where the block lifts off, perturbed there.
        let (tau, mode, y) = if shown.1 == Mode::Rest {
            self.lift_off_after(shown).unwrap_or(shown)
        } else {
            shown
        };
        for k in 0..count {
            let delta = eps * (k as f64 + 1.0) / count as f64;
            let mut system = live_system(self.probe.params().clone());
            let Ok((m, y0)) = perturbed_state(system.as_mut(), tau, mode, &y, delta) else {
                continue;
            };
            let outputs = Outputs {
                sample_dt: Some(LIVE_SAMPLE_DT),
                section_period: None,
            };
            let mut driver =
                system.into_driver(&self.play.info.scenario, DriverStart { mode: m, t0: tau, y0 }, outputs);
            let mut states = VecDeque::new();
            // Bring the ghost level with the main trajectory's computed τ.
            let done = self.driver.t() > tau
                && !matches!(
                    driver.advance(
                        self.driver.t(),
                        self.batch_end.max(self.driver.t()),
                        &mut GhostSink(&mut states),
                    ),
                    Ok(Advance::Reached)
                );
            // Until its own states come, a ghost is where the block is shown.
            let (_, shown_mode, shown_y) = shown;
            self.ghosts.push(Ghost {
                latest: GhostState {
                    theta: shown_y[THETA],
                    theta_dot: shown_y[THETA_DOT],
                    x: shown_y[X],
                    mode: shown_mode,
                },
                driver,
                states,
                done,
            });
        }
    }

    /// The first sample at which the block, at rest in `from`, moves: the
    /// same scenario run on from there until it leaves rest, within the
    /// batch run's end. `None` if it never does (a base too weak to lift
    /// it, or a still one).
    fn lift_off_after(&self, from: (f64, Mode, [f64; N])) -> Option<(f64, Mode, [f64; N])> {
        let (tau, mode, y) = from;
        let outputs = Outputs {
            sample_dt: Some(LIVE_SAMPLE_DT),
            section_period: None,
        };
        let system = live_system(self.probe.params().clone());
        let mut driver = system.into_driver(&self.play.info.scenario, DriverStart { mode, t0: tau, y0: y }, outputs);
        let mut moved = FirstMove(None);
        let mut t = tau;
        while t < self.batch_end {
            t = (t + MAX_CHUNK).min(self.batch_end);
            let reached = driver.advance(t, self.batch_end, &mut moved);
            if moved.0.is_some() {
                return moved.0;
            }
            if !matches!(reached, Ok(Advance::Reached)) {
                return None;
            }
        }
        None
    }
}
