//! The app: state, the message loop with the simulation thread, and the
//! layout of the panels.
//!
//! Contract: the app does no mechanics. Everything it shows comes from the
//! simulation thread's updates ([`crate::sim::protocol`]), filtered by run
//! id; it only stores (bounded), decimates and draws them. Updates are
//! drained in [`eframe::App::logic`] under a time budget. The app repaints
//! when the thread wakes it or while an impact flash fades, so a paused app
//! with no input does no work at all.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::gui::history::RunHistory;
use crate::gui::panels::bifurcation::BifurcationView;
use crate::gui::panels::lyapunov::LyapunovView;
use crate::gui::panels::params::{self, Edits};
use crate::gui::panels::plots::{self, HistoryView, PhaseView, PoincareView, SpectrumView};
use crate::gui::panels::scene::{self, Camera, SceneInput};
use crate::gui::settings::Settings;
use crate::gui::{block_view, export};
use crate::model::{EventKind, Mode};
use crate::sim::Scenario;
use crate::sim::protocol::{GhostState, MAX_GHOSTS, RunEnd, RunId, RunInfo, SimUpdate, Speed};
use crate::sim::runner::SimHandle;

/// Time per frame the app spends receiving updates: leaves most of a 60 Hz
/// frame to layout and drawing (rerun's `receive_messages` budget).
const DRAIN_BUDGET: Duration = Duration::from_millis(8);

/// How long an impact flash lasts, s of wall-clock time.
const FLASH_S: f64 = 0.18;

/// Where the app's data comes from.
enum Link {
    /// A simulation thread.
    Live(SimHandle),
    /// A fixed list of updates (snapshots and tests): commands only change
    /// the app's own state.
    Fixed { pending: VecDeque<SimUpdate>, run: RunId },
}

/// Which panels are shown. A hidden panel is not laid out and does no work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Show {
    /// The parameter panel.
    pub params: bool,
    /// The block scene.
    pub scene: bool,
    /// The phase portrait.
    pub phase: bool,
    /// The Poincaré points.
    pub poincare: bool,
    /// The time history.
    pub history: bool,
    /// The power spectrum of Θ.
    pub spectrum: bool,
    /// The bifurcation diagram. Off at start: its sweep keeps every core
    /// busy for seconds, which a lecture projector opening the app on the
    /// live block should not pay for unasked.
    pub bifurcation: bool,
    /// The running largest Lyapunov exponent. Off at start, like the
    /// bifurcation diagram: it keeps a core busy for seconds.
    pub lyapunov: bool,
}

impl Default for Show {
    fn default() -> Self {
        Self {
            params: true,
            scene: true,
            phase: true,
            poincare: true,
            history: true,
            spectrum: true,
            bifurcation: false,
            lyapunov: false,
        }
    }
}

/// A message in the status bar.
#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    /// Text, one line.
    pub text: String,
    /// Whether it reports a refusal or failure.
    pub error: bool,
}

/// The desktop app.
pub struct RockingApp {
    link: Link,
    settings: Settings,
    config: Scenario,
    edits: Edits,
    info: Option<RunInfo>,
    hist: RunHistory,
    ghosts: Vec<GhostState>,
    tau: f64,
    paused: bool,
    end: Option<RunEnd>,
    speed: f64,
    max_speed: bool,
    eps: f64,
    ghost_count: usize,
    ghost_eps: f64,
    /// Panels shown.
    pub show: Show,
    forces: bool,
    phase: PhaseView,
    poincare: PoincareView,
    history_view: HistoryView,
    spectrum: SpectrumView,
    bifurcation: BifurcationView,
    lyapunov: LyapunovView,
    camera: Camera,
    flash_at: Option<f64>,
    message: Option<Message>,
    gpu: bool,
    frame_ms: f32,
    frame_interval_ms: f32,
    last_shown: Option<crate::sim::protocol::Sample>,
}

impl RockingApp {
    /// The app on `settings` (resolved to `config`), with a simulation
    /// thread started at `speed`, paused if `paused`.
    pub fn live(
        cc: &eframe::CreationContext<'_>,
        settings: Settings,
        config: Scenario,
        speed: Speed,
        paused: bool,
    ) -> Self {
        let ctx = cc.egui_ctx.clone();
        let waker = Box::new(move || ctx.request_repaint());
        let mut message = None;
        let link = match SimHandle::spawn(config.clone(), speed, paused, waker) {
            Ok(h) => Link::Live(h),
            Err(e) => {
                message = Some(Message {
                    text: e.to_string(),
                    error: true,
                });
                Link::Fixed {
                    pending: VecDeque::new(),
                    run: RunId(1),
                }
            }
        };
        let mut app = Self::base(cc, link, settings, config);
        app.paused = paused;
        match speed {
            Speed::RealTime(m) => app.speed = m,
            Speed::Max => app.max_speed = true,
        }
        app.message = message;
        app
    }

    /// The app fed a fixed list of updates instead of a thread (for
    /// deterministic snapshots and tests).
    pub fn with_stream(
        cc: &eframe::CreationContext<'_>,
        settings: Settings,
        config: Scenario,
        updates: Vec<SimUpdate>,
    ) -> Self {
        let run = updates.first().map_or(RunId(1), SimUpdate::run);
        let link = Link::Fixed {
            pending: updates.into(),
            run,
        };
        let mut app = Self::base(cc, link, settings, config);
        app.paused = true;
        app
    }

    fn base(cc: &eframe::CreationContext<'_>, link: Link, settings: Settings, config: Scenario) -> Self {
        let gpu = match cc.wgpu_render_state.as_ref() {
            Some(rs) => {
                block_view::install(rs);
                true
            }
            None => false,
        };
        Self {
            link,
            settings,
            config,
            edits: Edits::default(),
            info: None,
            hist: RunHistory::default(),
            ghosts: Vec::new(),
            tau: 0.0,
            paused: false,
            end: None,
            speed: 1.0,
            max_speed: false,
            eps: 1e-6,
            ghost_count: 0,
            ghost_eps: 1e-3,
            show: Show::default(),
            forces: false,
            phase: PhaseView::default(),
            poincare: PoincareView::default(),
            history_view: HistoryView::default(),
            spectrum: SpectrumView::default(),
            bifurcation: BifurcationView::default(),
            lyapunov: LyapunovView::default(),
            camera: Camera::default(),
            flash_at: None,
            message: None,
            gpu,
            frame_ms: 0.0,
            frame_interval_ms: 0.0,
            last_shown: None,
        }
    }

    // ---- Queries (for tests and the status bar) ----

    /// Whether the scene is drawn by the wgpu pipeline.
    pub fn gpu(&self) -> bool {
        self.gpu
    }
    /// Whether the contact force and friction cone are drawn.
    pub fn forces_shown(&self) -> bool {
        self.forces
    }
    /// The playhead, τ.
    pub fn tau(&self) -> f64 {
        self.tau
    }
    /// Whether paused.
    pub fn paused(&self) -> bool {
        self.paused
    }
    /// The configuration of the scene (what the panel shows).
    pub fn config(&self) -> &Scenario {
        &self.config
    }
    /// What the current run is running, once it has started.
    pub fn run_info(&self) -> Option<&RunInfo> {
        self.info.as_ref()
    }
    /// The current run.
    pub fn run_id(&self) -> RunId {
        match &self.link {
            Link::Live(h) => h.current_run(),
            Link::Fixed { run, .. } => *run,
        }
    }
    /// What the app keeps of the run.
    pub fn history(&self) -> &RunHistory {
        &self.hist
    }
    /// How the run ended, if it has.
    pub fn end(&self) -> Option<&RunEnd> {
        self.end.as_ref()
    }
    /// The status-bar message.
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }
    /// Work done by each plot so far: (phase trail points, Poincaré points
    /// binned, time-history points, spectra computed). A hidden plot's
    /// count stays put.
    pub fn plot_work(&self) -> (u64, u64, u64, u64) {
        (
            self.phase.work,
            self.poincare.grid.work,
            self.history_view.work,
            self.spectrum.work,
        )
    }
    /// The bifurcation view (its sweep settings are public fields).
    pub fn bifurcation(&self) -> &BifurcationView {
        &self.bifurcation
    }
    /// The bifurcation view, to change its sweep.
    pub fn bifurcation_mut(&mut self) -> &mut BifurcationView {
        &mut self.bifurcation
    }
    /// The Lyapunov view.
    pub fn lyapunov(&self) -> &LyapunovView {
        &self.lyapunov
    }
    /// CPU time of the last frame's app code (layout and data), ms.
    pub fn frame_ms(&self) -> f32 {
        self.frame_ms
    }

    /// Adds section points directly (measurements of the plot with many
    /// points in a fixed stream).
    pub fn push_section_points(&mut self, points: impl IntoIterator<Item = crate::sim::protocol::SectionPoint>) {
        for p in points {
            self.hist.push_section(p);
        }
    }

    // ---- Actions ----

    /// Plays or pauses.
    pub fn toggle_pause(&mut self) {
        self.paused = !self.paused;
        if let Link::Live(h) = &self.link {
            if self.paused { h.pause() } else { h.resume() }
        }
    }

    /// Advances one forcing period (or 0.5 τ without one) and stays paused.
    pub fn step(&mut self) {
        if !self.paused {
            self.toggle_pause();
        }
        let tau = self.info.as_ref().and_then(|i| i.section_period).unwrap_or(0.5);
        if let Link::Live(h) = &self.link {
            h.step(tau);
        }
    }

    fn new_run(&mut self) {
        self.hist.clear();
        self.ghosts.clear();
        self.end = None;
        self.last_shown = None;
        self.poincare.reset();
        self.spectrum.reset();
        self.flash_at = None;
    }

    /// Restarts from τ = 0.
    pub fn reset(&mut self) {
        self.new_run();
        self.tau = 0.0;
        match &mut self.link {
            Link::Live(h) => {
                h.reset();
            }
            Link::Fixed { run, pending } => {
                *run = RunId(run.0 + 1);
                pending.clear();
            }
        }
    }

    /// Restarts from the state shown with Θ + ε.
    pub fn reset_perturbed(&mut self) {
        self.new_run();
        let eps = self.eps;
        if let Link::Live(h) = &mut self.link {
            h.reset_perturbed(eps);
        }
    }

    /// Makes `settings` (resolved to `config`) the scene and restarts with it.
    pub fn apply(&mut self, settings: Settings, config: Scenario) {
        self.settings = settings;
        self.config = config.clone();
        self.new_run();
        self.tau = 0.0;
        self.message = None;
        match &mut self.link {
            Link::Live(h) => {
                h.set_params(config);
            }
            Link::Fixed { run, pending } => {
                *run = RunId(run.0 + 1);
                pending.clear();
            }
        }
    }

    /// Sets one key (`section.key`) to `raw`; refuses invalid values with a message.
    pub fn set_key(&mut self, key: &str, raw: &str) -> bool {
        match self.settings.with(key, raw) {
            Ok((s, cfg)) => {
                self.apply(s, cfg);
                true
            }
            Err(e) => {
                self.message = Some(Message { text: e, error: true });
                false
            }
        }
    }

    /// Loads preset `name`.
    pub fn load_preset(&mut self, name: &str) {
        match Settings::preset(name).and_then(|s| s.resolve().map(|c| (s, c))) {
            Ok((s, c)) => {
                self.apply(s, c);
                self.message = Some(Message {
                    text: format!("preset {name}"),
                    error: false,
                });
            }
            Err(e) => {
                self.message = Some(Message { text: e, error: true });
            }
        }
    }

    fn send_speed(&self) {
        if let Link::Live(h) = &self.link {
            h.set_speed(if self.max_speed {
                Speed::Max
            } else {
                Speed::RealTime(self.speed)
            });
        }
    }

    fn send_ghosts(&self) {
        if let Link::Live(h) = &self.link {
            h.set_ghosts(self.ghost_count, self.ghost_eps);
        }
    }

    // ---- Updates ----

    fn ingest(&mut self, u: SimUpdate, now: f64) {
        match u {
            SimUpdate::Started { info, .. } => {
                self.tau = info.tau0;
                self.info = Some(*info);
            }
            SimUpdate::Paused { paused, tau, .. } => {
                self.paused = paused;
                self.tau = tau;
            }
            SimUpdate::Batch { batch, .. } => {
                for s in batch.samples {
                    self.hist.push_sample(s);
                }
                let mut impact = false;
                for e in batch.events {
                    impact |= e.kind == EventKind::Impact;
                    self.hist.push_event(e);
                }
                for p in batch.section {
                    self.hist.push_section(p);
                }
                self.hist.dropped_samples += batch.dropped_samples;
                if !batch.ghosts.is_empty() || self.ghost_count == 0 {
                    self.ghosts = batch.ghosts;
                }
                if batch.tau.is_finite() {
                    self.tau = batch.tau;
                }
                if impact {
                    self.flash_at = Some(now);
                }
            }
            SimUpdate::Finished { end, .. } => {
                if let RunEnd::Failed(msg) = &end {
                    self.message = Some(Message {
                        text: format!("run stopped: {msg}"),
                        error: true,
                    });
                }
                self.end = Some(end);
            }
        }
    }

    fn receive(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|i| i.time);
        let mut got = Vec::new();
        let more = match &mut self.link {
            Link::Live(h) => {
                h.drain(DRAIN_BUDGET, 4096, |u| got.push(u));
                // Whatever the budget left is picked up next frame.
                h.has_pending()
            }
            Link::Fixed { pending, run } => {
                let run = *run;
                got.extend(pending.drain(..).filter(|u| u.run() == run));
                false
            }
        };
        for u in got {
            self.ingest(u, now);
        }
        if more {
            ctx.request_repaint();
        }
    }

    // ---- Layout ----

    fn controls(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            ui.menu_button("File", |ui| self.file_menu(ui));
            ui.menu_button("Presets", |ui| {
                for (name, text) in crate::io::presets::PRESETS {
                    let title = text.lines().next().unwrap_or("").trim_start_matches('#').trim();
                    if ui.button(*name).on_hover_text(title).clicked() {
                        self.load_preset(name);
                        ui.close();
                    }
                }
            });
            ui.menu_button("View", |ui| {
                ui.checkbox(&mut self.show.params, "Parameters");
                ui.checkbox(&mut self.show.scene, "Block scene");
                ui.checkbox(&mut self.show.phase, "Phase portrait");
                ui.checkbox(&mut self.show.poincare, "Poincaré points");
                ui.checkbox(&mut self.show.history, "Time history");
                ui.checkbox(&mut self.show.spectrum, "Power spectrum");
                ui.checkbox(&mut self.show.bifurcation, "Bifurcation diagram");
                ui.checkbox(&mut self.show.lyapunov, "Lyapunov exponent");
                ui.separator();
                ui.checkbox(&mut self.forces, "Contact force and friction cone");
            });
            ui.separator();
            let label = if self.paused { "Play" } else { "Pause" };
            if ui.button(label).on_hover_text("Space").clicked() {
                self.toggle_pause();
            }
            if ui
                .button("Step")
                .on_hover_text("S: advance one forcing period 2π/Ω_h and pause")
                .clicked()
            {
                self.step();
            }
            if ui.button("Reset").on_hover_text("R: restart from τ = 0").clicked() {
                self.reset();
            }
            if ui
                .button("Reset perturbed")
                .on_hover_text("Restart from the state shown with Θ + ε")
                .clicked()
            {
                self.reset_perturbed();
            }
            let eps_label = ui.label("ε");
            ui.add(
                egui::DragValue::new(&mut self.eps)
                    .range(-0.5..=0.5)
                    .speed(1e-6)
                    .custom_formatter(|v, _| format!("{v:.1e}")),
            )
            .labelled_by(eps_label.id)
            .on_hover_text("Perturbation of Θ for Reset perturbed, units of ψ");
            ui.separator();
            let speed_label = ui.label("Speed");
            let r = ui
                .add_enabled(
                    !self.max_speed,
                    egui::Slider::new(&mut self.speed, Speed::MIN_MULTIPLE..=Speed::MAX_MULTIPLE)
                        .logarithmic(true)
                        .suffix("×")
                        .max_decimals(2),
                )
                .labelled_by(speed_label.id)
                .on_hover_text("Multiple of real time in the block's physical seconds (1 s = p τ)");
            if r.changed() {
                self.send_speed();
            }
            if ui.checkbox(&mut self.max_speed, "As fast as possible").changed() {
                self.send_speed();
            }
            ui.separator();
            let ghosts_label = ui.label("Ghosts");
            let r = ui
                .add(egui::DragValue::new(&mut self.ghost_count).range(0..=MAX_GHOSTS))
                .labelled_by(ghosts_label.id)
                .on_hover_text("Copies started from Θ perturbed by up to the ghost ε, drawn translucent");
            let eps_label = ui.label("ghost ε");
            let r2 = ui
                .add(
                    egui::DragValue::new(&mut self.ghost_eps)
                        .range(1e-12..=0.5)
                        .speed(1e-4)
                        .custom_formatter(|v, _| format!("{v:.1e}")),
                )
                .labelled_by(eps_label.id);
            if r.changed() || r2.changed() {
                self.send_ghosts();
            }
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        if ui.button("Open scene…").clicked() {
            ui.close();
            if let Some(path) = rfd::FileDialog::new()
                .add_filter("scene", &["toml", "json"])
                .pick_file()
            {
                match Settings::open(&path) {
                    Ok((s, c)) => self.apply(s, c),
                    Err(e) => self.message = Some(Message { text: e, error: true }),
                }
            }
        }
        if ui.button("Save scene…").clicked() {
            ui.close();
            if let Some(path) = rfd::FileDialog::new()
                .add_filter("scene", &["toml"])
                .set_file_name("scene.toml")
                .save_file()
            {
                self.message = Some(
                    match self
                        .settings
                        .to_toml()
                        .and_then(|t| export::write_atomic(&path, t.as_bytes()))
                    {
                        Ok(()) => Message {
                            text: format!("saved {}", path.display()),
                            error: false,
                        },
                        Err(e) => Message { text: e, error: true },
                    },
                );
            }
        }
        if ui.button("Export plots (PNG)…").clicked() {
            ui.close();
            if let Some(path) = rfd::FileDialog::new()
                .add_filter("PNG", &["png"])
                .set_file_name("plots.png")
                .save_file()
            {
                let r = export::plots_png(
                    &path,
                    &self.hist,
                    self.tau,
                    self.history_view.window,
                    self.phase.trail_tau,
                );
                self.message = Some(match r {
                    Ok(()) => Message {
                        text: format!("wrote {}", path.display()),
                        error: false,
                    },
                    Err(e) => Message { text: e, error: true },
                });
            }
        }
        if ui.button("Export data (CSV)…").clicked() {
            ui.close();
            if let Some(dir) = rfd::FileDialog::new().pick_folder() {
                self.message = Some(match export::data_csv(&dir, &self.hist) {
                    Ok(()) => Message {
                        text: format!("wrote history.csv, poincare.csv, events.csv in {}", dir.display()),
                        error: false,
                    },
                    Err(e) => Message { text: e, error: true },
                });
            }
        }
    }

    fn status(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            let p = self.info.as_ref().map_or(self.config.geometry().p, |i| i.geometry.p);
            ui.label(format!("τ = {:.2}", self.tau));
            ui.label(format!("t = {:.2} s", self.tau / p));
            let mode = self.hist.samples.last().map_or("–", |s| s.mode.name());
            ui.label(format!("mode: {mode}"));
            ui.label(format!("impacts: {}", self.hist.impacts));
            ui.label(format!(
                "Poincaré points: {}",
                self.hist.section.points().len() as u64 + self.hist.section.dropped
            ));
            let rate = if self.max_speed {
                "max".to_string()
            } else {
                format!("{:.2} τ/s", self.speed * p)
            };
            ui.label(format!("speed: {rate}"));
            if let Some(end) = &self.end {
                match end {
                    RunEnd::Terminal { mode, tau } => {
                        ui.colored_label(scene::mode_color(*mode), format!("{} at τ = {tau:.3}", mode.name()));
                    }
                    RunEnd::Failed(_) => {
                        ui.colored_label(egui::Color32::from_rgb(230, 80, 80), "failed");
                    }
                }
            }
            if self.paused {
                ui.label("paused");
            }
            // Wall-clock numbers only in the live app: a fixed stream must
            // draw the same pixels every time (snapshots).
            if matches!(self.link, Link::Live(_)) {
                ui.label(format!(
                    "app {:.1} ms/frame, {:.1} ms between frames",
                    self.frame_ms, self.frame_interval_ms
                ))
                .on_hover_text(
                    "CPU time of the app's own code per frame, and the interval between frames (rendering included)",
                );
            }
            if let Some(m) = &self.message {
                let color = if m.error {
                    egui::Color32::from_rgb(235, 90, 90)
                } else {
                    ui.visuals().weak_text_color()
                };
                ui.colored_label(color, &m.text);
            }
        });
    }

    fn params_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Parameters");
        ui.label(egui::RichText::new(&self.settings.origin).weak());
        egui::ScrollArea::vertical().show(ui, |ui| {
            let settings = &self.settings;
            let explicit = |k: &str| settings.explicit(k).is_some();
            let commit = params::show(ui, &self.config, &explicit, &mut self.edits);
            if let Some((key, raw)) = commit {
                self.set_key(key, &raw);
            }
            ui.add_space(8.0);
            ui.label(egui::RichText::new("Modes").strong());
            for (i, name) in Mode::NAMES.iter().enumerate() {
                ui.horizontal(|ui| {
                    let (r, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
                    ui.painter().rect_filled(r, 2.0, scene::MODE_COLORS[i]);
                    ui.label(*name);
                });
            }
        });
    }

    fn analyses_panel(&mut self, ui: &mut egui::Ui) {
        if self.show.bifurcation {
            ui.label("Bifurcation diagram (drag to zoom, double-click: full range)");
            let height = if self.show.lyapunov {
                ui.available_height() - 230.0
            } else {
                ui.available_height()
            };
            ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
                ui.vertical(|ui| self.bifurcation.show(ui, &self.settings, &self.config));
            });
        }
        if self.show.lyapunov {
            ui.separator();
            ui.label("Largest Lyapunov exponent (from the initial state)");
            self.lyapunov.show(ui, &self.config);
        }
    }

    fn scene_panel(&mut self, ui: &mut egui::Ui) {
        let rect = ui.available_rect_before_wrap();
        let (Some(info), Some(sample)) = (self.info.as_ref(), self.hist.samples.last()) else {
            ui.centered_and_justified(|ui| ui.label("waiting for the simulation…"));
            return;
        };
        self.last_shown = Some(*sample);
        let now = ui.input(|i| i.time);
        let flash = self
            .flash_at
            .map_or(0.0, |t0| (1.0 - (now - t0) / FLASH_S).clamp(0.0, 1.0)) as f32;
        if flash > 0.0 {
            ui.ctx().request_repaint_after(Duration::from_millis(16));
        }
        let input = SceneInput {
            geometry: info.geometry,
            sample,
            ghosts: &self.ghosts,
            mu_s: info.scenario.block.mu_s,
            terminal: match &self.end {
                Some(RunEnd::Terminal { mode, .. }) => Some(*mode),
                Some(RunEnd::Failed(_)) | None => None,
            },
            flash,
            forces: self.forces,
        };
        let (shapes, scale, y_mid) = scene::build(&input, rect, &mut self.camera);
        let view = scene::view(rect, scale, &self.camera, y_mid, ui.ctx().pixels_per_point());
        scene::paint(ui, rect, shapes, view, self.gpu);
        ui.allocate_rect(rect, egui::Sense::hover());
    }
}

impl eframe::App for RockingApp {
    fn logic(&mut self, ctx: &egui::Context, _frame: &mut eframe::Frame) {
        self.receive(ctx);
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let start = Instant::now();
        if !ui.ctx().egui_wants_keyboard_input() {
            let (space, r, s) = ui.input(|i| {
                (
                    i.key_pressed(egui::Key::Space),
                    i.key_pressed(egui::Key::R),
                    i.key_pressed(egui::Key::S),
                )
            });
            if space {
                self.toggle_pause();
            }
            if r {
                self.reset();
            }
            if s {
                self.step();
            }
        }
        egui::Panel::top("controls").show(ui, |ui| self.controls(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status(ui));
        if self.show.params {
            egui::Panel::left("params")
                .resizable(true)
                .default_size(300.0)
                .show(ui, |ui| self.params_panel(ui));
        }
        if self.show.history || self.show.spectrum {
            egui::Panel::bottom("history")
                .resizable(true)
                .default_size(190.0)
                .show(ui, |ui| {
                    let both = self.show.history && self.show.spectrum;
                    let width = ui.available_width();
                    let height = ui.available_height();
                    ui.horizontal(|ui| {
                        if self.show.history {
                            let w = if both { 0.64 * width } else { width };
                            ui.allocate_ui(egui::vec2(w, height), |ui| {
                                ui.vertical(|ui| {
                                    plots::history_plot(ui, &self.hist, &mut self.history_view, self.tau);
                                });
                            });
                        }
                        if self.show.spectrum {
                            let (dt, omega_h) = self.info.as_ref().map_or(
                                (crate::sim::runner::LIVE_SAMPLE_DT, self.config.excitation.omega_h),
                                |i| (i.sample_dt, i.scenario.excitation.omega_h),
                            );
                            ui.vertical(|ui| {
                                ui.label("Power spectrum of Θ (last 41 τ)");
                                plots::spectrum_plot(ui, &self.hist, &mut self.spectrum, dt, omega_h);
                            });
                        }
                    });
                });
        }
        if self.show.bifurcation || self.show.lyapunov {
            egui::Panel::right("analyses")
                .resizable(true)
                .default_size(420.0)
                .show(ui, |ui| self.analyses_panel(ui));
        }
        if !self.show.bifurcation {
            self.bifurcation.hide();
        }
        if !self.show.lyapunov {
            self.lyapunov.hide();
        }
        if self.show.phase || self.show.poincare {
            egui::Panel::right("plots")
                .resizable(true)
                .default_size(380.0)
                .show(ui, |ui| {
                    let both = self.show.phase && self.show.poincare;
                    let h = ui.available_height();
                    if self.show.phase {
                        ui.label("Phase portrait (click to start there)");
                        let height = if both { 0.5 * h - 24.0 } else { h - 20.0 };
                        ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
                            if let Some((theta, theta_dot)) =
                                plots::phase_plot(ui, &self.hist, &mut self.phase, self.tau)
                            {
                                self.start_at(theta, theta_dot);
                            }
                        });
                    }
                    if self.show.poincare {
                        ui.label("Poincaré points (double-click to fit)");
                        plots::poincare_plot(ui, &self.hist, &mut self.poincare);
                    }
                });
        }
        egui::CentralPanel::default().show(ui, |ui| {
            if self.show.scene {
                self.scene_panel(ui);
            } else {
                ui.centered_and_justified(|ui| ui.label("Block scene hidden (View menu)"));
            }
        });
        let ms = start.elapsed().as_secs_f32() * 1000.0;
        self.frame_ms = if self.frame_ms == 0.0 {
            ms
        } else {
            0.9 * self.frame_ms + 0.1 * ms
        };
        // The interval between frames, rendering included (while frames
        // come continuously; an idle app's long gaps are not frame times).
        let dt = ui.input(|i| i.unstable_dt) * 1000.0;
        if dt < 250.0 {
            self.frame_interval_ms = if self.frame_interval_ms == 0.0 {
                dt
            } else {
                0.9 * self.frame_interval_ms + 0.1 * dt
            };
        }
    }
}

impl RockingApp {
    /// Restarts from Θ = `theta`, Θ' = `theta_dot` (a click on the phase
    /// portrait), through the same validation as the panel.
    pub fn start_at(&mut self, theta: f64, theta_dot: f64) {
        let next = self
            .settings
            .with("initial.theta", &format!("{theta}"))
            .and_then(|(s, _)| s.with("initial.theta_dot", &format!("{theta_dot}")));
        match next {
            Ok((s, c)) => self.apply(s, c),
            Err(e) => self.message = Some(Message { text: e, error: true }),
        }
    }
}
