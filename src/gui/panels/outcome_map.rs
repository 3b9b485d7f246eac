//! The outcome-map view: the steady response over two parameters (the
//! rocking literature's overturning map, e.g. A_h × Ω_h) or over the
//! initial state (Θ₀ × Θ'₀, a basin of attraction), computed in the
//! background on all cores and drawn level by level, coarse first and then
//! refined where classes meet. A click on a cell loads that scene.
//!
//! Contract:
//! - The view does no physics and no classification: each cell is the
//!   analysis layer's steady response (run by [`mapper`] on a named
//!   thread), and which cells are computed is the analysis layer's
//!   refinement schedule ([`crate::analysis::map_refine`]). Cells inside a
//!   uniform block inherit its class without being computed; the panel
//!   says so.
//! - A map is computed for the scene's explicit keys with the two mapped
//!   keys free. It restarts when any other key of the scene changes, or
//!   when the axes, resolution or window change; setting a mapped key
//!   (a click on the map) only moves the crosshair. A restart cancels the
//!   old map and drops its channel, so nothing stale is drawn.
//! - Hidden, the view does no work: [`OutcomeMapView::hide`] cancels a
//!   running map, and none starts until the view is shown again (it then
//!   starts over).
//! - The map is one texture of one texel per cell, rebuilt at most once a
//!   frame when cells have arrived.

pub mod mapper;

use std::time::{Duration, Instant};

use egui::{Color32, TextureHandle, TextureOptions};
use egui_plot::{HLine, Plot, PlotBounds, PlotImage, PlotPoint, PlotTransform, VLine};

use self::mapper::{Class, Mapper, Reply, Request};
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::map_refine::{Refiner, Source};
use crate::analysis::outcome_map::Axis;
use crate::analysis::steady::Window;
use crate::gui::panels::bifurcation::{PAPER_WINDOW, SHORT_WINDOW};
use crate::gui::settings::Settings;
use crate::sim::{Param, Scenario};

/// The keys a map may vary: the excitation, friction and the initial
/// state. Geometry and the impact law change the block itself, and the
/// solver settings do not change the physics.
pub const KEYS: [&str; 9] = [
    "excitation.a_h",
    "excitation.omega_h",
    "excitation.a_v",
    "excitation.omega_v",
    "excitation.phase_v",
    "friction.static",
    "friction.kinetic",
    "initial.theta",
    "initial.theta_dot",
];

/// Cells per axis to choose from. 128 is the default: fine enough to see
/// the structure of the overturning map, a few minutes of all cores in a
/// release build for the default scene.
pub const RESOLUTIONS: [usize; 4] = [32, 64, 128, 256];

/// Default cells per axis.
pub const DEFAULT_RESOLUTION: usize = 128;

/// Cells of the coarse level along the longer axis (at least): 17 × 17 at
/// 128, a first picture after about 2 % of the full map's work.
pub const COARSE: usize = 16;

/// The classes the map tells apart, in legend order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Slot {
    /// At rest.
    Rest,
    /// Period 1.
    Period1,
    /// Period 2.
    Period2,
    /// Period k ≥ 3.
    PeriodK,
    /// Quasiperiodic.
    Quasiperiodic,
    /// Chaotic.
    Chaotic,
    /// Tumbled.
    Tumbled,
    /// Left the base.
    Flight,
    /// The run failed.
    Failed,
}

impl Slot {
    /// Every slot, in legend order.
    pub const ALL: [Slot; 9] = [
        Slot::Rest,
        Slot::Period1,
        Slot::Period2,
        Slot::PeriodK,
        Slot::Quasiperiodic,
        Slot::Chaotic,
        Slot::Tumbled,
        Slot::Flight,
        Slot::Failed,
    ];

    /// The slot of a cell's class.
    pub fn of(class: Class) -> Slot {
        match class {
            None => Slot::Failed,
            Some(Response::Rest) => Slot::Rest,
            Some(Response::Periodic { period: 1 }) => Slot::Period1,
            Some(Response::Periodic { period: 2 }) => Slot::Period2,
            Some(Response::Periodic { .. }) => Slot::PeriodK,
            Some(Response::Quasiperiodic) => Slot::Quasiperiodic,
            Some(Response::Chaotic) => Slot::Chaotic,
            Some(Response::Tumbled) => Slot::Tumbled,
            Some(Response::Flight) => Slot::Flight,
        }
    }

    /// Legend name.
    pub fn name(self) -> &'static str {
        match self {
            Slot::Rest => "rest",
            Slot::Period1 => "period 1",
            Slot::Period2 => "period 2",
            Slot::PeriodK => "period k ≥ 3",
            Slot::Quasiperiodic => "quasiperiodic",
            Slot::Chaotic => "chaotic",
            Slot::Tumbled => "tumbled",
            Slot::Flight => "flight",
            Slot::Failed => "failed",
        }
    }

    /// Fill colour: blues for the periodic family (darker for longer
    /// periods), green quasiperiodic, orange chaotic, grey rest, dark red
    /// tumbled (the overturned region, the map's point), purple flight.
    pub fn color(self) -> Color32 {
        match self {
            Slot::Rest => Color32::from_gray(150),
            Slot::Period1 => Color32::from_rgb(150, 200, 255),
            Slot::Period2 => Color32::from_rgb(80, 140, 235),
            Slot::PeriodK => Color32::from_rgb(35, 75, 170),
            Slot::Quasiperiodic => Color32::from_rgb(120, 220, 140),
            Slot::Chaotic => Color32::from_rgb(255, 170, 80),
            Slot::Tumbled => Color32::from_rgb(150, 30, 40),
            Slot::Flight => Color32::from_rgb(190, 110, 230),
            Slot::Failed => Color32::from_rgb(255, 60, 200),
        }
    }
}

/// The range a key is mapped over when chosen: |Θ₀| up to 0.9 (the
/// tumble angle is 1) and Θ'₀ within ±1 for a basin; 0 to twice the
/// current amplitude (0 to 1 at 0), where 0 is the unforced block; half to
/// one and a half times the current value for the others (0 to 1 at 0).
pub fn default_range(key: &str, current: f64) -> (f64, f64) {
    let current = if current.is_finite() { current } else { 0.0 };
    match key {
        "initial.theta" => (-0.9, 0.9),
        "initial.theta_dot" => (-1.0, 1.0),
        _ if current == 0.0 => (0.0, 1.0),
        "excitation.a_h" | "excitation.a_v" => (0.0, 2.0 * current.abs()),
        _ => {
            let (a, b) = (0.5 * current, 1.5 * current);
            (a.min(b), a.max(b))
        }
    }
}

/// The window each cell is run over: `base`, lengthened where needed so
/// that it holds enough section points to classify at the lowest Ω_h of
/// the map (the section period is 2π/Ω_h, so a map down to low Ω_h needs
/// longer runs).
pub fn window_for(base: Window, lowest_omega_h: f64) -> Window {
    if !(lowest_omega_h.is_finite() && lowest_omega_h > 0.0) {
        return base;
    }
    let need = (ClassifyOptions::default().min_points() as f64 + 1.0) * std::f64::consts::TAU / lowest_omega_h;
    Window {
        transient: base.transient,
        tau_end: base.tau_end.max(base.transient + need),
    }
}

/// One mapped axis as the user set it.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisChoice {
    /// The config key, one of [`KEYS`].
    pub key: String,
    /// First value (left or bottom edge's cell).
    pub from: f64,
    /// Last value.
    pub to: f64,
}

/// What a computed map depends on.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    table: toml::Table,
    origin: String,
    x: AxisChoice,
    y: AxisChoice,
    resolution: usize,
    window: Window,
}

/// The outcome-map view's state. The public fields are the map the view
/// computes; it starts a new map whenever they change.
pub struct OutcomeMapView {
    /// Horizontal axis.
    pub x: AxisChoice,
    /// Vertical axis.
    pub y: AxisChoice,
    /// Cells per axis.
    pub resolution: usize,
    /// Window of each run before lengthening for low Ω_h ([`window_for`]).
    pub window: Window,
    /// Cells of the coarse level (at least, along the longer axis).
    pub coarse: usize,
    /// Whether the ranges have been set (by the user, or from the scene
    /// the first time the view is shown).
    ranged: bool,
    edit: (AxisChoice, AxisChoice),
    key: Option<Key>,
    mapper: Option<Mapper>,
    retired: Vec<Mapper>,
    refiner: Option<Refiner<Class>>,
    axes: Option<(Axis, Axis)>,
    texture: Option<TextureHandle>,
    transform: Option<PlotTransform>,
    dirty: bool,
    counts: Vec<(Slot, usize)>,
    failed: Vec<(usize, String)>,
    invalid: Option<String>,
    level: (usize, usize, usize),
    done: bool,
    started: Option<Instant>,
    first_level: Option<Duration>,
    took: Option<Duration>,
    /// Maps started over the view's life (work counter).
    pub maps: u64,
    /// Cells received over the view's life (work counter).
    pub cells: u64,
}

impl Default for OutcomeMapView {
    fn default() -> Self {
        let axis = |key: &str| AxisChoice {
            key: key.to_string(),
            from: 0.0,
            to: 1.0,
        };
        let (x, y) = (axis("excitation.a_h"), axis("excitation.omega_h"));
        Self {
            edit: (x.clone(), y.clone()),
            x,
            y,
            resolution: DEFAULT_RESOLUTION,
            window: SHORT_WINDOW,
            coarse: COARSE,
            ranged: false,
            key: None,
            mapper: None,
            retired: Vec::new(),
            refiner: None,
            axes: None,
            texture: None,
            transform: None,
            dirty: false,
            counts: Vec::new(),
            failed: Vec::new(),
            invalid: None,
            level: (0, 0, 0),
            done: false,
            started: None,
            first_level: None,
            took: None,
            maps: 0,
            cells: 0,
        }
    }
}

/// The current value of `key` in `cfg`, if it is a finite number.
fn current_value(cfg: &Scenario, key: &str) -> Option<f64> {
    Param::ALL
        .into_iter()
        .find(|p| p.key() == key)
        .map(|p| p.get(cfg))
        .filter(|v| v.is_finite())
}

impl OutcomeMapView {
    /// Sets both axes (key, first and last value), as the controls do.
    pub fn set_axes(&mut self, x: (&str, f64, f64), y: (&str, f64, f64)) {
        let axis = |(key, from, to): (&str, f64, f64)| AxisChoice {
            key: key.to_string(),
            from,
            to,
        };
        self.x = axis(x);
        self.y = axis(y);
        self.edit = (self.x.clone(), self.y.clone());
        self.ranged = true;
    }

    /// Whether the current map has every level in.
    pub fn done(&self) -> bool {
        self.done
    }

    /// Why the current map was refused, if it was.
    pub fn invalid(&self) -> Option<&str> {
        self.invalid.as_deref()
    }

    /// Whether a map thread is still working.
    pub fn busy(&self) -> bool {
        self.mapper.as_ref().is_some_and(|m| !m.finished())
    }

    /// Map threads still running, cancelled ones included.
    pub fn threads(&self) -> usize {
        self.retired
            .iter()
            .chain(self.mapper.iter())
            .filter(|m| !m.finished())
            .count()
    }

    /// Cells drawn in the last picture, per class (classes with none left
    /// out), in legend order.
    pub fn drawn(&self) -> &[(Slot, usize)] {
        &self.counts
    }

    /// Cells of the current map computed so far, and its total cells.
    pub fn computed(&self) -> (usize, usize) {
        let total = self.axes.as_ref().map_or(0, |(x, y)| x.n * y.n);
        (self.refiner.as_ref().map_or(0, Refiner::computed), total)
    }

    /// Time from the start of the current map to its coarse level drawn
    /// complete, and to the whole map.
    pub fn timings(&self) -> (Option<Duration>, Option<Duration>) {
        (self.first_level, self.took)
    }

    /// The class of cell (i, j) of the current map (column i from the
    /// left, row j from the bottom), if known, and whether it was computed
    /// or inherited.
    pub fn cell(&self, i: usize, j: usize) -> Option<(Class, Source)> {
        let r = self.refiner.as_ref()?;
        let (x, y) = self.axes.as_ref()?;
        if i >= x.n || j >= y.n {
            return None;
        }
        let c = j * x.n + i;
        r.class(c).map(|k| (k, r.source(c)))
    }

    /// The values of cell (i, j): the pair of (key, value) a click on it
    /// loads.
    pub fn cell_values(&self, i: usize, j: usize) -> Option<[(String, f64); 2]> {
        let (x, y) = self.axes.as_ref()?;
        (i < x.n && j < y.n).then(|| [(x.key.clone(), x.value(i)), (y.key.clone(), y.value(j))])
    }

    /// Where the centre of cell (i, j) was drawn in the last frame, in
    /// screen points (for tests that click it).
    pub fn cell_position(&self, i: usize, j: usize) -> Option<egui::Pos2> {
        let t = self.transform.as_ref()?;
        let [(_, x), (_, y)] = self.cell_values(i, j)?;
        Some(t.position_from_point(&PlotPoint::new(x, y)))
    }

    /// Stops work while the view is hidden: a running map is cancelled and
    /// will start over when the view is shown again.
    pub fn hide(&mut self) {
        self.retired.retain(|m| !m.finished());
        if !self.done
            && let Some(m) = self.mapper.take()
        {
            m.cancel();
            self.retired.push(m);
            self.key = None;
        }
    }

    fn wanted(&self, settings: &Settings) -> Key {
        let mut table = settings.table.clone();
        for key in [&self.x.key, &self.y.key] {
            if let Some((section, name)) = key.split_once('.')
                && let Some(toml::Value::Table(t)) = table.get_mut(section)
            {
                t.remove(name);
            }
        }
        Key {
            table,
            origin: settings.origin.clone(),
            x: self.x.clone(),
            y: self.y.clone(),
            resolution: self.resolution,
            window: self.window,
        }
    }

    /// Sets the ranges around the scene's values (the first time the view
    /// is shown, or when a key is chosen).
    fn range_from(&mut self, cfg: &Scenario) {
        for a in [&mut self.x, &mut self.y] {
            (a.from, a.to) = default_range(&a.key, current_value(cfg, &a.key).unwrap_or(0.0));
        }
        self.edit = (self.x.clone(), self.y.clone());
        self.ranged = true;
    }

    fn restart(&mut self, key: Key, settings: &Settings, ctx: &egui::Context) {
        if let Some(old) = self.mapper.take() {
            old.cancel();
            self.retired.push(old);
        }
        self.refiner = None;
        self.axes = None;
        self.failed.clear();
        self.counts.clear();
        self.invalid = None;
        self.done = false;
        self.first_level = None;
        self.took = None;
        self.level = (0, 0, 0);
        self.dirty = true;
        self.key = Some(key);
        match self.request(settings) {
            Ok(req) => {
                let nx = req.x.n;
                let ny = req.y.n;
                self.axes = Some((req.x.clone(), req.y.clone()));
                self.refiner = Some(Refiner::new(nx, ny, req.coarse, mapper::HALO));
                let ctx = ctx.clone();
                match mapper::start(req, Box::new(move || ctx.request_repaint())) {
                    Ok(m) => {
                        self.mapper = Some(m);
                        self.maps += 1;
                        self.started = Some(Instant::now());
                    }
                    Err(e) => self.invalid = Some(e),
                }
            }
            Err(e) => self.invalid = Some(e),
        }
    }

    /// The request for the current settings, or why there is none.
    fn request(&self, settings: &Settings) -> Result<Request, String> {
        if self.x.key == self.y.key {
            return Err(format!("{}: the two axes must be different keys", self.y.key));
        }
        let n = self.resolution;
        let x = Axis::new("x", &self.x.key, self.x.from, self.x.to, n).map_err(|e| e.to_string())?;
        let y = Axis::new("y", &self.y.key, self.y.from, self.y.to, n).map_err(|e| e.to_string())?;
        if n < 2 {
            return Err(format!("resolution {n}: need at least 2 cells per axis"));
        }
        let param = |k: &str| crate::io::config::param(k).map_err(|e| e.to_string());
        let (x_param, y_param) = (param(&self.x.key)?, param(&self.y.key)?);
        let base = settings.resolve()?;
        let lowest = [(x_param, &x), (y_param, &y)]
            .into_iter()
            .find(|(p, _)| *p == Param::OmegaH)
            .map_or(base.excitation.omega_h, |(_, a)| a.from);
        Ok(Request {
            window: window_for(self.window, lowest),
            base,
            x_param,
            x,
            y_param,
            y,
            coarse: self.coarse,
        })
    }

    fn receive(&mut self) {
        let (Some(m), Some(r)) = (&self.mapper, &mut self.refiner) else {
            return;
        };
        for reply in m.drain() {
            match reply {
                Reply::Level { stride, cells } => {
                    // The mirror of the thread's schedule (module docs of
                    // `mapper`): the same classes give the same level.
                    if self.level.2 > 0 && self.first_level.is_none() {
                        self.first_level = self.started.map(|t| t.elapsed());
                    }
                    let mine = r.next_level().map_or(0, |v| v.len());
                    debug_assert_eq!(mine, cells, "the view's schedule follows the thread's");
                    self.level = (stride, 0, cells);
                    self.dirty = true;
                }
                Reply::Cell { index, class, error } => {
                    self.cells += 1;
                    self.level.1 += 1;
                    r.record(index, class);
                    if let Some(e) = error {
                        self.failed.push((index, e));
                    }
                    self.dirty = true;
                }
                Reply::Invalid(e) => self.invalid = Some(e),
                Reply::Done => {
                    // Advance the mirror past the last level.
                    while r.next_level().is_some() {}
                    self.first_level = self.first_level.or_else(|| self.started.map(|t| t.elapsed()));
                    self.done = true;
                    self.took = self.started.map(|t| t.elapsed());
                    self.dirty = true;
                }
            }
        }
    }

    /// Rebuilds the texture from the refiner's picture.
    fn repaint(&mut self, ctx: &egui::Context) {
        if !self.dirty {
            return;
        }
        self.dirty = false;
        let Some(r) = &self.refiner else {
            self.texture = None;
            return;
        };
        let (nx, ny) = (r.nx(), r.ny());
        let picture = r.picture();
        let mut counts = [0usize; Slot::ALL.len()];
        let mut pixels = vec![Color32::TRANSPARENT; nx * ny];
        for (c, class) in picture.iter().enumerate() {
            if let Some(class) = class {
                let slot = Slot::of(*class);
                counts[Slot::ALL.iter().position(|s| *s == slot).unwrap_or(0)] += 1;
                // Texture rows go down, the map's y goes up.
                let (i, j) = (c % nx, c / nx);
                pixels[(ny - 1 - j) * nx + i] = slot.color();
            }
        }
        self.counts = Slot::ALL
            .into_iter()
            .zip(counts)
            .filter(|(_, n)| *n > 0)
            .collect();
        let image = egui::ColorImage::new([nx, ny], pixels);
        if let Some(t) = self.texture.as_mut().filter(|t| t.size() == [nx, ny]) {
            t.set(image, TextureOptions::NEAREST);
        } else {
            self.texture = Some(ctx.load_texture("outcome map", image, TextureOptions::NEAREST));
        }
    }

    /// Draws the view for the scene `settings` (resolved to `cfg`),
    /// starting or restarting the map as needed. Returns the two (key,
    /// value) pairs of a clicked cell, for the app to load.
    pub fn show(&mut self, ui: &mut egui::Ui, settings: &Settings, cfg: &Scenario) -> Option<[(String, f64); 2]> {
        self.retired.retain(|m| !m.finished());
        if !self.ranged {
            self.range_from(cfg);
        }
        self.receive();
        self.controls(ui, cfg);
        let key = self.wanted(settings);
        if self.key.as_ref() != Some(&key) {
            self.restart(key, settings, ui.ctx());
        }
        self.repaint(ui.ctx());
        self.status(ui);
        self.legend(ui);
        self.plot(ui, cfg)
    }

    fn axis_controls(ui: &mut egui::Ui, name: &str, axis: &mut AxisChoice, cfg: &Scenario) {
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(name);
            let mut chosen = None;
            egui::ComboBox::from_id_salt(("outcome map axis", name))
                .selected_text(&axis.key)
                .show_ui(ui, |ui| {
                    for k in KEYS {
                        if ui.selectable_label(k == axis.key, k).clicked() {
                            chosen = Some(k);
                        }
                    }
                })
                .response
                .labelled_by(label.id)
                .on_hover_text(format!("The configuration key along the {name} axis"));
            if let Some(k) = chosen
                && k != axis.key
            {
                axis.key = k.to_string();
                (axis.from, axis.to) = default_range(k, current_value(cfg, k).unwrap_or(0.0));
            }
            let l = ui.label(format!("{name} from"));
            ui.add(egui::DragValue::new(&mut axis.from).speed(0.01))
                .labelled_by(l.id);
            let l = ui.label(format!("{name} to"));
            ui.add(egui::DragValue::new(&mut axis.to).speed(0.01))
                .labelled_by(l.id);
        });
    }

    fn controls(&mut self, ui: &mut egui::Ui, cfg: &Scenario) {
        ui.horizontal_wrapped(|ui| {
            if ui
                .button("A_h × Ω_h")
                .on_hover_text("The overturning map: horizontal amplitude against forcing frequency")
                .clicked()
            {
                self.edit.0.key = "excitation.a_h".into();
                self.edit.1.key = "excitation.omega_h".into();
                self.x = self.edit.0.clone();
                self.y = self.edit.1.clone();
                self.range_from(cfg);
            }
            if ui
                .button("Θ₀ × Θ'₀")
                .on_hover_text("The basin of attraction: where each initial state ends up")
                .clicked()
            {
                self.edit.0.key = "initial.theta".into();
                self.edit.1.key = "initial.theta_dot".into();
                self.x = self.edit.0.clone();
                self.y = self.edit.1.clone();
                self.range_from(cfg);
            }
            let l = ui.label("Cells");
            egui::ComboBox::from_id_salt("outcome map resolution")
                .selected_text(format!("{0} × {0}", self.resolution))
                .show_ui(ui, |ui| {
                    for n in RESOLUTIONS {
                        ui.selectable_value(&mut self.resolution, n, format!("{n} × {n}"));
                    }
                })
                .response
                .labelled_by(l.id)
                .on_hover_text("Cells per axis of the finest level");
            let run_label = ui.label("Run");
            let text = |w: Window| format!("τ {}–{}", w.transient, w.tau_end);
            egui::ComboBox::from_id_salt("outcome map window")
                .selected_text(text(self.window))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.window, SHORT_WINDOW, text(SHORT_WINDOW))
                        .on_hover_text("Interactive: a third of the paper's run per cell");
                    ui.selectable_value(&mut self.window, PAPER_WINDOW, text(PAPER_WINDOW))
                        .on_hover_text("The paper's: section points from τ 600 to 800");
                })
                .response
                .labelled_by(run_label.id)
                .on_hover_text(
                    "Section points are kept from the first τ to the second (longer where Ω_h is low, to hold enough points)",
                );
        });
        Self::axis_controls(ui, "x", &mut self.edit.0, cfg);
        Self::axis_controls(ui, "y", &mut self.edit.1, cfg);
        ui.horizontal(|ui| {
            if ui.button("Map").on_hover_text("Compute the map over these axes").clicked() {
                self.x = self.edit.0.clone();
                self.y = self.edit.1.clone();
                self.ranged = true;
            }
            if ui
                .button("Around the scene")
                .on_hover_text("Ranges around the scene's current values")
                .clicked()
            {
                self.x.key = self.edit.0.key.clone();
                self.y.key = self.edit.1.key.clone();
                self.range_from(cfg);
            }
        });
    }

    fn status(&self, ui: &mut egui::Ui) {
        let red = Color32::from_rgb(235, 90, 90);
        if let Some(e) = &self.invalid {
            ui.colored_label(red, e);
            return;
        }
        let (computed, total) = self.computed();
        let share = if total > 0 {
            100.0 * computed as f64 / total as f64
        } else {
            0.0
        };
        let line = if self.done {
            let took = self
                .took
                .map_or(String::new(), |t| format!(" in {:.1} s", t.as_secs_f64()));
            format!(
                "{n} × {n} cells{took}; {computed} computed ({share:.0} %), the rest refined where classes meet",
                n = self.resolution
            )
        } else {
            let (stride, got, of) = self.level;
            format!(
                "computing: level {stride} cells per block, {got} / {of}; {computed} of {total} cells computed so far"
            )
        };
        ui.horizontal_wrapped(|ui| {
            ui.label(line).on_hover_text(
                "Computed coarse first, then refined where classes meet: a cell whose surroundings at the level above \
                 all have one class inherits it without being run",
            );
            if let Some((_, e)) = self.failed.first() {
                ui.colored_label(red, format!("{} failed, first: {e}", self.failed.len()));
            }
        });
    }

    fn legend(&self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            for slot in Slot::ALL {
                let n = self.counts.iter().find(|(s, _)| *s == slot).map_or(0, |(_, n)| *n);
                if slot == Slot::Failed && n == 0 {
                    continue;
                }
                let (r, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
                ui.painter().rect_filled(r, 2.0, slot.color());
                let text = egui::RichText::new(slot.name());
                ui.label(if n > 0 { text } else { text.weak() });
            }
        });
    }

    fn plot(&mut self, ui: &mut egui::Ui, cfg: &Scenario) -> Option<[(String, f64); 2]> {
        let (x, y) = self.axes.clone()?;
        let cell_w = (x.to - x.from) / (x.n - 1) as f64;
        let cell_h = (y.to - y.from) / (y.n - 1) as f64;
        let (x0, x1) = (x.from - 0.5 * cell_w, x.to + 0.5 * cell_w);
        let (y0, y1) = (y.from - 0.5 * cell_h, y.to + 0.5 * cell_h);
        let current = (current_value(cfg, &x.key), current_value(cfg, &y.key));
        let texture = self.texture.as_ref().map(TextureHandle::id);
        let index = |p: PlotPoint| {
            let i = ((p.x - x.from) / cell_w).round();
            let j = ((p.y - y.from) / cell_h).round();
            (i >= 0.0 && j >= 0.0 && i < x.n as f64 && j < y.n as f64).then_some((i as usize, j as usize))
        };
        let resp = Plot::new("outcome map")
            .x_axis_label(x.key.as_str())
            .y_axis_label(y.key.as_str())
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .allow_boxed_zoom(false)
            .allow_double_click_reset(false)
            .show_grid(false)
            .show(ui, |plot_ui| {
                plot_ui.set_plot_bounds(PlotBounds::from_min_max([x0, y0], [x1, y1]));
                if let Some(t) = texture {
                    plot_ui.image(
                        PlotImage::new(
                            "map",
                            t,
                            PlotPoint::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)),
                            egui::vec2((x1 - x0) as f32, (y1 - y0) as f32),
                        )
                        .allow_hover(false),
                    );
                }
                let mark = Color32::from_rgb(255, 230, 60);
                if let Some(v) = current.0 {
                    plot_ui.vline(VLine::new("scene", v).color(mark).width(1.5));
                }
                if let Some(v) = current.1 {
                    plot_ui.hline(HLine::new("scene", v).color(mark).width(1.5));
                }
                plot_ui.pointer_coordinate()
            });
        self.transform = Some(resp.transform);
        let hovered = resp.inner.and_then(index);
        let clicked = resp.response.clicked();
        if let Some((i, j)) = hovered {
            let what = match self.cell(i, j) {
                Some((class, source)) => {
                    let how = match source {
                        Source::Computed => "computed",
                        Source::Inherited => "inherited: refined where classes meet",
                        Source::Unknown => "not yet known",
                    };
                    format!("{} ({how})", Slot::of(class).name())
                }
                None => "not yet computed".to_string(),
            };
            resp.response.on_hover_text(format!(
                "{} = {:.4}, {} = {:.4}: {what}\nclick to load this scene",
                x.key,
                x.value(i),
                y.key,
                y.value(j)
            ));
        }
        if clicked {
            hovered.and_then(|(i, j)| self.cell_values(i, j))
        } else {
            None
        }
    }
}

impl Drop for OutcomeMapView {
    fn drop(&mut self) {
        // Cancel everything first so the threads stop together, then join
        // (each Mapper joins its thread on drop).
        for m in self.retired.iter().chain(self.mapper.iter()) {
            m.cancel();
        }
    }
}
