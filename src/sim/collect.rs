//! The observer that gathers a run's outputs.

use crate::integrate::hybrid::Observer;
use crate::model::{Geometry, Mode};
use crate::model::system::{EventRecord, N, THETA, THETA_DOT, X, X_DOT};

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
    pub fn of_state(t: f64, mode: Mode, y: &[f64; N]) -> Self {
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
    pub fn of_state(k: u64, t: f64, mode: Mode, y: &[f64; N]) -> Self {
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

/// Collects samples, section points and events, and the time per mode.
#[derive(Debug, Default)]
pub(crate) struct Collector {
    pub history: Vec<HistoryRow>,
    pub section: Vec<SectionRow>,
    pub events: Vec<EventRecord>,
    pub keep_history: bool,
    pub max_abs_theta: f64,
    /// The block, for the sliding displacement.
    pub geometry: Option<Geometry>,
    /// Largest |sliding displacement| at an event, per R. Slip keeps one
    /// direction between events (a reversal is an event), so the sliding
    /// displacement is monotone between them and its extremes are at
    /// events or at the end: this, with the final value, is exact.
    pub max_abs_sliding: f64,
}

impl Observer<Mode, EventRecord, N> for Collector {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.max_abs_theta = self.max_abs_theta.max(y[THETA].abs());
        if self.keep_history {
            self.history.push(HistoryRow::of_state(t, mode, y));
        }
    }

    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        self.max_abs_theta = self.max_abs_theta.max(y[THETA].abs());
        self.section.push(SectionRow::of_state(k, t, mode, y));
    }

    fn event(&mut self, _t: f64, before: Mode, y_before: &[f64; N], record: EventRecord) {
        self.max_abs_theta = self.max_abs_theta.max(y_before[THETA].abs());
        if let Some(geo) = &self.geometry {
            let u = geo.sliding(before, y_before[THETA], y_before[X]);
            self.max_abs_sliding = self.max_abs_sliding.max(u.abs());
        }
        self.events.push(record);
    }
}
