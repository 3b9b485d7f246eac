//! The bifurcation view: Θ at the Poincaré section against one swept
//! parameter, computed in the background on all cores and drawn as the
//! values arrive, with the scene's current value marked.
//!
//! Contract:
//! - The view does no physics: the sweep is the analysis layer's
//!   ([`crate::analysis::orbit_diagram`]), run by [`sweeper`] on a named
//!   thread; this module only decides what to compute and draws it.
//! - A sweep is computed for the scene's explicit keys with the swept key
//!   free. It restarts when any other key of the scene changes, when the
//!   range, resolution or window changes, or after a zoom; setting the swept
//!   key itself only moves the marker. A restart cancels the old sweep and
//!   drops its channel, so nothing stale is drawn. While a pointer button
//!   is held (a slider of another key being dragged), the restart waits for
//!   the release: a sweep started and cancelled on every core each frame
//!   would only slow the live run being dragged.
//! - The current run's value of the swept key is marked by a labelled
//!   vertical line, so the live run can be placed on the diagram.
//! - Dragging a rectangle on the plot zooms into it: the same number of
//!   values over the narrower range, i.e. a finer step. Double-click (or
//!   "Full range") goes back.
//! - Hidden, the view does no work: [`BifurcationView::hide`] cancels a
//!   running sweep, and none starts until the view is shown again (it then
//!   starts over).
//! - Points are decimated to the plot's pixels before drawing: per value at
//!   most one point per pixel row.

mod plot;
pub mod sweeper;

use std::time::{Duration, Instant};

use egui::Color32;
use egui_plot::PlotPoint;

use self::sweeper::{Column, MAX_VALUES, Reply, Request, Sweeper};
use crate::analysis::classify::Response;
use crate::analysis::orbit_diagram::Grid;
use crate::analysis::steady::Window;
use crate::gui::settings::Settings;
use crate::sim::{Param, Scenario};

/// The interactive window: transient 200 τ, end 300 τ. At Ω_h = 8 that is
/// 128 section points per value (the classifier needs 64), and a third of
/// the paper's run time per value.
pub const SHORT_WINDOW: Window = Window {
    transient: 200.0,
    tau_end: 300.0,
};

/// The paper's window: section points for 600 ≤ τ ≤ 800.
pub(crate) const PAPER_WINDOW: Window = Window {
    transient: 600.0,
    tau_end: 800.0,
};

/// Default number of values: the paper's grid, 0 to 3 in steps of 0.02.
pub(crate) const DEFAULT_COUNT: usize = 151;

/// The swept key the view opens on (the paper's bifurcation figures).
pub(crate) const DEFAULT_PARAM: &str = "excitation.a_v";

/// What a computed sweep depends on.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    table: toml::Table,
    origin: String,
    param: String,
    from: f64,
    to: f64,
    count: usize,
    window: Window,
}

impl Key {
    /// Whether `other` asks for the same sweep of another scene (only the
    /// scene's keys differ).
    fn same_sweep(&self, other: &Key) -> bool {
        self.param == other.param
            && self.from == other.from
            && self.to == other.to
            && self.count == other.count
            && self.window == other.window
    }
}

/// The bifurcation view's state. The public fields are the sweep the view
/// computes; the view starts a new sweep whenever they change.
pub struct BifurcationView {
    /// The swept key, `section.key`.
    pub param: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of values (2 to [`MAX_VALUES`]).
    pub count: usize,
    /// Transient and end of each run, τ.
    pub window: Window,
    edit: (f64, f64, usize),
    key: Option<Key>,
    sweeper: Option<Sweeper>,
    retired: Vec<Sweeper>,
    columns: Vec<Column>,
    failed: Vec<(f64, String)>,
    invalid: Option<String>,
    expected: usize,
    done: bool,
    started: Option<Instant>,
    took: Option<Duration>,
    y_zoom: Option<[f64; 2]>,
    drag_from: Option<PlotPoint>,
    /// Sweeps started over the view's life (work counter).
    pub sweeps: u64,
    /// Values received over the view's life (work counter).
    pub values: u64,
    /// Points drawn in the last frame, after decimation.
    pub drawn: usize,
}

impl Default for BifurcationView {
    fn default() -> Self {
        let (from, to) = default_range(DEFAULT_PARAM, 0.0);
        Self {
            param: DEFAULT_PARAM.to_string(),
            from,
            to,
            count: DEFAULT_COUNT,
            window: SHORT_WINDOW,
            edit: (from, to, DEFAULT_COUNT),
            key: None,
            sweeper: None,
            retired: Vec::new(),
            columns: Vec::new(),
            failed: Vec::new(),
            invalid: None,
            expected: 0,
            done: false,
            started: None,
            took: None,
            y_zoom: None,
            drag_from: None,
            sweeps: 0,
            values: 0,
            drawn: 0,
        }
    }
}

/// The range a key is swept over when chosen: the paper's 0–3 for A_v,
/// otherwise half to one and a half times the current value (0–1 at 0).
pub fn default_range(param: &str, current: f64) -> (f64, f64) {
    if param == DEFAULT_PARAM {
        (0.0, 3.0)
    } else if current == 0.0 || !current.is_finite() {
        (0.0, 1.0)
    } else {
        let (a, b) = (0.5 * current, 1.5 * current);
        (a.min(b), a.max(b))
    }
}

/// The numeric keys a sweep may vary, with their current values in `cfg`
/// (infinite for `inf`). Solver settings are left out: the window replaces
/// the run's end, and the others do not change the physics. A stack's are
/// its excitation's ([`Param::applies_to_stack`]).
pub(crate) fn sweepable(cfg: &Scenario) -> Vec<(String, f64)> {
    Param::ALL
        .into_iter()
        .filter(|p| !p.key().starts_with("run."))
        .filter(|p| *p != Param::XDot0 || cfg.initial.x_dot.is_some())
        .filter(|p| cfg.stack.is_none() || p.applies_to_stack())
        .map(|p| (p.key().to_string(), p.get(cfg)))
        .collect()
}

/// The current value of `param` in `cfg`, if it is a finite number.
fn current_value(cfg: &Scenario, param: &str) -> Option<f64> {
    sweepable(cfg)
        .into_iter()
        .find(|(k, _)| k == param)
        .map(|(_, v)| v)
        .filter(|v| v.is_finite())
}

/// The key's name without its section (`excitation.a_v` → `a_v`).
fn short_name(param: &str) -> &str {
    param.split_once('.').map_or(param, |(_, name)| name)
}

impl BifurcationView {
    /// Values received for the current sweep.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Whether the current sweep has sent every value.
    pub fn done(&self) -> bool {
        self.done
    }

    /// Wall-clock time of the last complete sweep.
    pub fn took(&self) -> Option<Duration> {
        self.took
    }

    /// Why the current sweep was refused, if it was.
    pub fn invalid(&self) -> Option<&str> {
        self.invalid.as_deref()
    }

    /// Whether a sweep thread is still working.
    pub fn busy(&self) -> bool {
        self.sweeper.as_ref().is_some_and(|s| !s.finished())
    }

    /// Sweep threads still running, cancelled ones included.
    pub fn threads(&self) -> usize {
        self.retired
            .iter()
            .chain(self.sweeper.iter())
            .filter(|s| !s.finished())
            .count()
    }

    /// Number of values the current sweep computes.
    pub fn expected(&self) -> usize {
        self.expected
    }

    /// Stops work while the view is hidden: a running sweep is cancelled and
    /// will start over when the view is shown again.
    pub fn hide(&mut self) {
        self.retired.retain(|s| !s.finished());
        if !self.done
            && let Some(s) = self.sweeper.take()
        {
            s.cancel();
            self.retired.push(s);
            self.key = None;
        }
    }

    fn wanted(&self, settings: &Settings) -> Key {
        let mut table = settings.table.clone();
        if let Some((section, name)) = self.param.split_once('.')
            && let Some(toml::Value::Table(t)) = table.get_mut(section)
        {
            t.remove(name);
        }
        Key {
            table,
            origin: settings.origin.clone(),
            param: self.param.clone(),
            from: self.from,
            to: self.to,
            count: self.count,
            window: self.window,
        }
    }

    fn restart(&mut self, key: Key, settings: &Settings, ctx: &egui::Context) {
        if let Some(old) = self.sweeper.take() {
            old.cancel();
            self.retired.push(old);
        }
        self.columns.clear();
        self.failed.clear();
        self.invalid = None;
        self.done = false;
        self.took = None;
        self.expected = 0;
        let grid = if !(self.from.is_finite() && self.to.is_finite() && self.from < self.to) {
            Err(format!(
                "From {} / To {}: need From < To, both finite",
                self.from, self.to
            ))
        } else if !(2..=MAX_VALUES).contains(&self.count) {
            Err(format!("Values {}: must be 2 to {MAX_VALUES}", self.count))
        } else {
            let step = (self.to - self.from) / (self.count - 1) as f64;
            Grid::new(self.from, self.to, step).map_err(|e| e.to_string())
        };
        self.key = Some(key);
        let grid = match grid {
            Ok(g) => g,
            Err(e) => {
                self.invalid = Some(e);
                return;
            }
        };
        self.expected = grid.count;
        let base = settings.resolve();
        let param = crate::io::config::param(&self.param).map_err(|e| e.to_string());
        let (base, param) = match (base, param) {
            (Ok(b), Ok(p)) => (b, p),
            (Err(e), _) | (_, Err(e)) => {
                self.invalid = Some(e);
                return;
            }
        };
        let req = Request {
            base,
            param,
            grid,
            window: self.window,
        };
        let ctx = ctx.clone();
        match sweeper::start(req, Box::new(move || ctx.request_repaint())) {
            Ok(s) => {
                self.sweeper = Some(s);
                self.sweeps += 1;
                self.started = Some(Instant::now());
            }
            Err(e) => self.invalid = Some(e),
        }
    }

    fn receive(&mut self) {
        let Some(s) = &self.sweeper else { return };
        for reply in s.drain() {
            match reply {
                Reply::Value(c) => {
                    self.values += 1;
                    self.columns.push(c);
                }
                Reply::Failed { value, error } => self.failed.push((value, error)),
                Reply::Invalid(e) => self.invalid = Some(e),
                Reply::Done => {
                    self.done = true;
                    self.took = self.started.map(|t| t.elapsed());
                }
            }
        }
    }

    /// Sets the swept range to the rectangle between `a` and `b` (plot
    /// coordinates) at the same number of values.
    fn zoom(&mut self, a: PlotPoint, b: PlotPoint) {
        let (x0, x1) = (a.x.min(b.x), a.x.max(b.x));
        let (y0, y1) = (a.y.min(b.y), a.y.max(b.y));
        if x1 - x0 <= 1e-9 * (1.0 + x0.abs()) || y1 - y0 <= 0.0 {
            return;
        }
        self.from = x0;
        self.to = x1;
        self.y_zoom = Some([y0, y1]);
        self.edit = (x0, x1, self.count);
    }

    fn full_range(&mut self, cfg: &Scenario) {
        let (from, to) = default_range(&self.param, current_value(cfg, &self.param).unwrap_or(0.0));
        self.from = from;
        self.to = to;
        self.y_zoom = None;
        self.edit = (from, to, self.count);
    }

    /// Draws the view for the scene `settings` (resolved to `cfg`),
    /// starting or restarting the sweep as needed.
    pub fn show(&mut self, ui: &mut egui::Ui, settings: &Settings, cfg: &Scenario) {
        self.retired.retain(|s| !s.finished());
        self.receive();
        self.controls(ui, cfg);
        let key = self.wanted(settings);
        if self.key.as_ref() != Some(&key) {
            let dragging = ui.input(|i| i.pointer.any_down()) && self.key.as_ref().is_some_and(|k| k.same_sweep(&key));
            if !dragging {
                self.restart(key, settings, ui.ctx());
            }
        }
        self.status(ui);
        self.plot(ui, cfg);
    }

    fn controls(&mut self, ui: &mut egui::Ui, cfg: &Scenario) {
        ui.horizontal_wrapped(|ui| {
            let label = ui.label("Sweep");
            let keys = sweepable(cfg);
            let mut chosen = None;
            egui::ComboBox::from_id_salt("bifurcation param")
                .selected_text(&self.param)
                .show_ui(ui, |ui| {
                    for (k, _) in &keys {
                        if ui.selectable_label(*k == self.param, k).clicked() {
                            chosen = Some(k.clone());
                        }
                    }
                })
                .response
                .labelled_by(label.id)
                .on_hover_text("The configuration key swept along the horizontal axis");
            if let Some(k) = chosen
                && k != self.param
            {
                self.param = k;
                self.full_range(cfg);
            }
            let run_label = ui.label("Run");
            let text = |w: Window| format!("τ {}–{}", w.transient, w.tau_end);
            egui::ComboBox::from_id_salt("bifurcation window")
                .selected_text(text(self.window))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.window, SHORT_WINDOW, text(SHORT_WINDOW))
                        .on_hover_text("Interactive: a third of the paper's run per value");
                    ui.selectable_value(&mut self.window, PAPER_WINDOW, text(PAPER_WINDOW))
                        .on_hover_text("The paper's: section points from τ 600 to 800");
                })
                .response
                .labelled_by(run_label.id)
                .on_hover_text("Section points are kept from the first τ to the second");
        });
        ui.horizontal_wrapped(|ui| {
            let l = ui.label("From");
            ui.add(egui::DragValue::new(&mut self.edit.0).speed(0.01))
                .labelled_by(l.id);
            let l = ui.label("To");
            ui.add(egui::DragValue::new(&mut self.edit.1).speed(0.01))
                .labelled_by(l.id);
            let l = ui.label("Values");
            ui.add(egui::DragValue::new(&mut self.edit.2).range(2..=MAX_VALUES))
                .labelled_by(l.id)
                .on_hover_text("Number of parameter values, evenly spaced, ends included");
            if ui.button("Compute").on_hover_text("Sweep this range").clicked() {
                (self.from, self.to, self.count) = self.edit;
                self.y_zoom = None;
            }
            if ui
                .button("Full range")
                .on_hover_text("Back to the key's default range (or double-click the plot)")
                .clicked()
            {
                self.full_range(cfg);
            }
        });
    }

    fn status(&self, ui: &mut egui::Ui) {
        let red = Color32::from_rgb(235, 90, 90);
        if let Some(e) = &self.invalid {
            ui.colored_label(red, e);
            return;
        }
        let mut line = if self.done {
            let took = self
                .took
                .map_or(String::new(), |t| format!(" in {:.1} s", t.as_secs_f64()));
            format!("{} values{took}", self.expected)
        } else {
            format!(
                "computing: {} / {} values",
                self.columns.len() + self.failed.len(),
                self.expected
            )
        };
        let tumbled = self.columns.iter().filter(|c| c.response == Response::Tumbled).count();
        if tumbled > 0 {
            line.push_str(&format!(", {tumbled} tumbled (blank)"));
        }
        ui.horizontal_wrapped(|ui| {
            ui.label(line);
            if let Some((v, e)) = self.failed.first() {
                ui.colored_label(red, format!("{} failed, first at {v}: {e}", self.failed.len()));
            }
        });
    }
}

impl Drop for BifurcationView {
    fn drop(&mut self) {
        // Cancel everything first so the threads stop together, then join
        // (each Sweeper joins its thread on drop).
        for s in self.retired.iter().chain(self.sweeper.iter()) {
            s.cancel();
        }
    }
}
