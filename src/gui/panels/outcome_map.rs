//! The outcome-map view: the steady response over two parameters (the
//! rocking literature's overturning map, e.g. A_h × Ω_h) or over the
//! initial state (Θ₀ × Θ'₀, a basin of attraction), computed in the
//! background on all cores and drawn level by level, coarse first and then
//! refined where classes meet. A click on a cell loads that scene.
//!
//! Contract:
//! - The view does no physics and no classification: the map is the
//!   analysis layer's map engine ([`MapRun`](crate::analysis::outcome_map::MapRun),
//!   the one `rocking map` and Python drive) with the fast plan, run by
//!   [`mapper`] on a named thread: each cell stops once its class is
//!   certain, and cells are computed coarse first and then where labels
//!   ([`Label`]: the exact class and, in a basin map, the attractor) meet.
//!   The finished map is `compute_map` with that plan, cell for cell.
//!   Cells inside a uniform block inherit its label without being
//!   computed; the panel says so, and counts them as done.
//! - Cells are coloured by their legend class ([`Slot`]); in a basin map
//!   (both keys initial-state keys) a periodic cell is coloured by its
//!   attractor instead, with the colours and legend text of `rocking
//!   map`'s figure, and the attractors numbered as it numbers them.
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

mod draw;
pub mod mapper;
mod queries;
mod slot;

pub use self::slot::{Slot, attractor_color};

use std::time::{Duration, Instant};

use egui::{Color32, TextureHandle, TextureOptions};
use egui_plot::PlotTransform;

use self::mapper::{Class, Mapper, Reply, Request};
use crate::analysis::attractor::Attractor;
use crate::analysis::classify::ClassifyOptions;
use crate::analysis::map_refine::Refiner;
use crate::analysis::outcome_map::{Axis, HALO, Label};
use crate::analysis::steady::Window;
use crate::gui::panels::bifurcation::SHORT_WINDOW;
use crate::gui::settings::Settings;
use crate::sim::{Param, Scenario};

/// The keys a map may vary: the excitation, friction and the initial
/// state. Geometry and the impact law change the block itself, and the
/// solver settings do not change the physics.
pub(crate) const PARAMS: [Param; 9] = [
    Param::Ah,
    Param::OmegaH,
    Param::Av,
    Param::OmegaV,
    Param::PhaseV,
    Param::MuS,
    Param::MuK,
    Param::Theta0,
    Param::ThetaDot0,
];

/// The config keys of [`PARAMS`] that `cfg` reads, as the axis menus list
/// them (a stack reads the excitation's only: [`Param::applies_to_stack`]).
pub fn keys(cfg: &Scenario) -> Vec<&'static str> {
    PARAMS
        .into_iter()
        .filter(|p| cfg.stack.is_none() || p.applies_to_stack())
        .map(Param::key)
        .collect()
}

/// Cells per axis to choose from. 128 is the default: fine enough to see
/// the structure of the overturning map.
pub(crate) const RESOLUTIONS: [usize; 4] = [32, 64, 128, 256];

/// Default cells per axis.
pub(crate) const DEFAULT_RESOLUTION: usize = 128;

/// Cells of the coarse level along the longer axis (at least): 17 × 17 at
/// 128, a first picture after about 2 % of the full map's work.
pub const COARSE: usize = 16;

/// The range a key is mapped over when chosen: |Θ₀| up to 0.9 (the
/// tumble angle is 1) and Θ'₀ within ±1 for a basin; 0 to twice the
/// current amplitude (0 to 1 at 0), where 0 is the unforced block; half to
/// one and a half times the current value for the others (0 to 1 at 0).
pub fn default_range(key: &str, current: f64) -> (f64, f64) {
    let current = if current.is_finite() { current } else { 0.0 };
    match crate::sim::catalogue::spec(key).and_then(|s| s.param) {
        Some(Param::Theta0) => (-0.9, 0.9),
        Some(Param::ThetaDot0) => (-1.0, 1.0),
        _ if current == 0.0 => (0.0, 1.0),
        Some(Param::Ah | Param::Av) => (0.0, 2.0 * current.abs()),
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
    /// The config key, one of [`keys`].
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
    /// The mirror of the engine's refinement, fed the engine's labels.
    refiner: Option<Refiner<Label>>,
    /// The exact class of each computed cell, as soon as it arrives
    /// (its label comes when its whole batch is recorded).
    responses: Vec<Option<Class>>,
    /// Whether the current map is a basin map (attractors told apart).
    basin: bool,
    /// A basin map's attractors so far, numbered as `rocking map` numbers
    /// them, and the number of each discovery number.
    attractors: (Vec<Attractor>, Vec<u32>),
    /// Cells drawn per attractor in the last picture (id, cells).
    attractor_counts: Vec<(u32, usize)>,
    /// Cells of the current map received, and how many of them stopped
    /// early.
    received: (usize, usize),
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
            responses: Vec::new(),
            basin: false,
            attractors: (Vec::new(), Vec::new()),
            attractor_counts: Vec::new(),
            received: (0, 0),
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
        self.responses.clear();
        self.basin = false;
        self.attractors = (Vec::new(), Vec::new());
        self.attractor_counts.clear();
        self.received = (0, 0);
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
                self.basin = req.is_basin();
                // The engine's refiner has this size, coarse level and halo.
                self.refiner = Some(Refiner::new(nx, ny, req.coarse, HALO));
                self.responses = vec![None; nx * ny];
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
                Reply::Cell {
                    index,
                    class,
                    stopped_early,
                    error,
                } => {
                    self.cells += 1;
                    self.level.1 += 1;
                    self.received.0 += 1;
                    self.received.1 += usize::from(stopped_early);
                    if let Some(slot) = self.responses.get_mut(index) {
                        *slot = Some(class);
                    }
                    if let Some(e) = error {
                        self.failed.push((index, e));
                    }
                    self.dirty = true;
                }
                Reply::Labels(labels) => {
                    for (index, label) in labels {
                        r.record(index, label);
                    }
                    self.dirty = true;
                }
                Reply::Attractors { attractors, ids } => {
                    self.attractors = (attractors, ids);
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

    /// Says so when the map's thread ended without finishing (it panicked:
    /// the panic hook has printed why), instead of showing it as still
    /// computing.
    fn check_alive(&mut self) {
        let died = self.mapper.as_ref().is_some_and(|m| m.finished() && !m.has_pending());
        if died && !self.done && self.invalid.is_none() {
            self.invalid = Some("the map stopped: its thread ended before the map was finished".into());
        }
    }

    /// Rebuilds the texture from the refiner's picture; a cell computed in
    /// the batch under way shows its own class before its label arrives
    /// (in a basin map only when not periodic: its attractor is not known
    /// yet).
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
        let mut by_attractor: Vec<(u32, usize)> = Vec::new();
        let mut pixels = vec![Color32::TRANSPARENT; nx * ny];
        for (c, label) in picture.iter().enumerate() {
            let (slot, attractor) = match (label, self.responses.get(c).copied().flatten()) {
                (_, Some(class)) if r.class(c).is_none() && !(self.basin && Slot::of(class).is_periodic()) => {
                    (Slot::of(class), None)
                }
                (Some(l), _) => (
                    Slot::of(l.response),
                    l.attractor.filter(|_| self.basin).map(|d| self.attractor_id(d)),
                ),
                (None, _) => continue,
            };
            counts[Slot::ALL.iter().position(|s| *s == slot).unwrap_or(0)] += 1;
            let color = match attractor {
                Some(id) => {
                    match by_attractor.iter_mut().find(|(a, _)| *a == id) {
                        Some((_, n)) => *n += 1,
                        None => by_attractor.push((id, 1)),
                    }
                    attractor_color(id)
                }
                None => slot.color(),
            };
            // Texture rows go down, the map's y goes up.
            let (i, j) = (c % nx, c / nx);
            pixels[(ny - 1 - j) * nx + i] = color;
        }
        by_attractor.sort_unstable();
        self.attractor_counts = by_attractor;
        self.counts = Slot::ALL.into_iter().zip(counts).filter(|(_, n)| *n > 0).collect();
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
        self.check_alive();
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
