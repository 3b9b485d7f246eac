//! The observer that gathers a run's outputs.

use crate::integrate::hybrid::Observer;
use crate::model::system::{EventRecord, N, THETA, THETA_DOT, X, X_DOT};
use crate::model::{EventKind, Geometry, Mode};

/// One row of the regular time history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistoryRow {
    /// τ.
    pub tau: f64,
    /// Θ.
    pub theta: f64,
    /// Θ'.
    pub theta_dot: f64,
    /// X.
    pub x: f64,
    /// X'.
    pub x_dot: f64,
    /// Mode.
    pub mode: Mode,
}

/// One point of the stroboscopic (Poincaré) section at τ_k = 2πk/Ω_h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionRow {
    /// k.
    pub k: u64,
    /// τ_k.
    pub tau: f64,
    /// Θ(τ_k).
    pub theta: f64,
    /// Θ'(τ_k).
    pub theta_dot: f64,
    /// X(τ_k).
    pub x: f64,
    /// X'(τ_k).
    pub x_dot: f64,
    /// Mode at τ_k.
    pub mode: Mode,
}

impl HistoryRow {
    /// The row of state `y` in `mode` at τ = `t`.
    pub(crate) fn of_state(t: f64, mode: Mode, y: &[f64; N]) -> Self {
        Self {
            tau: t,
            theta: y[THETA],
            theta_dot: y[THETA_DOT],
            x: y[X],
            x_dot: y[X_DOT],
            mode,
        }
    }
}

impl SectionRow {
    /// Section point `k` of state `y` in `mode` at τ = `t`.
    pub(crate) fn of_state(k: u64, t: f64, mode: Mode, y: &[f64; N]) -> Self {
        let r = HistoryRow::of_state(t, mode, y);
        Self {
            k,
            tau: r.tau,
            theta: r.theta,
            theta_dot: r.theta_dot,
            x: r.x,
            x_dot: r.x_dot,
            mode,
        }
    }
}

/// Where a run's outputs go as they are produced: kept in memory
/// ([`Keep`], what [`simulate`](super::simulate) returns), or written out
/// as they come (the batch run's files), so that a run's memory does not
/// grow with its length.
pub trait Sink {
    /// A state on the regular output grid (only when the run keeps a
    /// history, `RunOptions::output_dt`).
    fn sample(&mut self, row: &HistoryRow);
    /// A point of the stroboscopic section.
    fn section(&mut self, row: &SectionRow);
    /// An event.
    fn event(&mut self, record: &EventRecord);
    /// Whether this sink may end the run before `tau_end`: a run whose sink
    /// watches advances one forcing period at a time (taking exactly the
    /// steps of an uninterrupted run) and asks [`settled`](Self::settled)
    /// after each. Only runs with a section are watched.
    fn watches(&self) -> bool {
        false
    }
    /// Whether the run can end now, its fate being certain (asked after
    /// each forcing period when the sink [`watches`](Self::watches)).
    fn settled(&self) -> bool {
        false
    }
}

/// The sink that keeps everything in memory.
#[derive(Debug, Default)]
pub struct Keep {
    /// The history.
    pub history: Vec<HistoryRow>,
    /// The section points.
    pub section: Vec<SectionRow>,
    /// The events.
    pub events: Vec<EventRecord>,
}

impl Sink for Keep {
    fn sample(&mut self, row: &HistoryRow) {
        self.history.push(*row);
    }

    fn section(&mut self, row: &SectionRow) {
        self.section.push(*row);
    }

    fn event(&mut self, record: &EventRecord) {
        self.events.push(*record);
    }
}

/// What a run tallies as it goes, whatever its sink keeps: enough for the
/// summary without the event list.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tallies {
    /// Events passed on.
    pub events: u64,
    /// Section points passed on.
    pub section: u64,
    /// History rows passed on.
    pub history: u64,
    /// Largest |Θ| seen at samples, section points and events.
    pub max_abs_theta: f64,
    /// Largest |sliding displacement| at an event, per R. Slip keeps one
    /// direction between events (a reversal is an event), so the sliding
    /// displacement is monotone between them and its extremes are at
    /// events or at the end: this, with the final value, is exact.
    pub max_abs_sliding: f64,
    /// τ of the first tumble event.
    pub tumble_tau: Option<f64>,
    /// τ of the last event into rest.
    pub last_rest_tau: Option<f64>,
    /// τ of the last event.
    pub last_event_tau: Option<f64>,
    /// Time in rest, slide, rock and slide-rock up to the last event.
    pub mode_time: [f64; 4],
}

/// Passes samples, section points and events to a sink and keeps the
/// tallies.
pub(crate) struct Collector<'a> {
    pub sink: &'a mut dyn Sink,
    pub keep_history: bool,
    /// The block, for the sliding displacement.
    pub geometry: Geometry,
    /// The mode since the last event, and when it began.
    pub mode: Mode,
    pub mode_since: f64,
    pub tallies: Tallies,
}

impl Observer<Mode, EventRecord, N> for Collector<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        let t_ = &mut self.tallies;
        t_.max_abs_theta = t_.max_abs_theta.max(y[THETA].abs());
        if self.keep_history {
            t_.history += 1;
            self.sink.sample(&HistoryRow::of_state(t, mode, y));
        }
    }

    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        let t_ = &mut self.tallies;
        t_.max_abs_theta = t_.max_abs_theta.max(y[THETA].abs());
        t_.section += 1;
        self.sink.section(&SectionRow::of_state(k, t, mode, y));
    }

    fn event(&mut self, _t: f64, _before: Mode, y_before: &[f64; N], record: EventRecord) {
        let t_ = &mut self.tallies;
        t_.max_abs_theta = t_.max_abs_theta.max(y_before[THETA].abs());
        let u = self.geometry.sliding(y_before[THETA], y_before[X]);
        t_.max_abs_sliding = t_.max_abs_sliding.max(u.abs());
        if self.mode.index() < 4 {
            t_.mode_time[self.mode.index()] += record.tau - self.mode_since;
        }
        self.mode = record.after;
        self.mode_since = record.tau;
        t_.events += 1;
        t_.last_event_tau = Some(record.tau);
        if record.kind == EventKind::Tumble && t_.tumble_tau.is_none() {
            t_.tumble_tau = Some(record.tau);
        }
        if record.after == Mode::Rest {
            t_.last_rest_tau = Some(record.tau);
        }
        self.sink.event(&record);
    }
}
