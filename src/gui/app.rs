//! The app: its state, how it is made, what it answers and the actions it
//! takes. The rest, by job: `receive` (the message loop with the
//! simulation thread), `controls` (top bar, menus, keyboard), `layout`
//! (where the panels go, and the frame), `status` (the status bar),
//! `record_open` (opening a record, and asking what its file leaves out),
//! `share` (the window title, and the window as a GIF or PNG),
//! `file_dialog` (asking for a path, with or without the desktop's dialog).
//!
//! Contract: the app does no mechanics. Everything it shows comes from the
//! simulation thread's updates ([`crate::sim::protocol`]), filtered by run
//! id; it only stores (bounded), decimates and draws them. Updates are
//! drained in [`eframe::App::logic`] under a time budget. The app repaints
//! when the thread wakes it or while an impact flash fades, so a paused app
//! with no input does no work at all.

use std::collections::VecDeque;

use crate::gui::block_view;
use crate::gui::history::RunHistory;
use crate::gui::panels::bifurcation::BifurcationView;
use crate::gui::panels::ground::{GroundView, RecordLabel};
use crate::gui::panels::lyapunov::LyapunovView;
use crate::gui::panels::outcome_map::OutcomeMapView;
use crate::gui::panels::params::{Commit, Edits};
use crate::gui::panels::plots::{HistoryView, PhaseView, PoincareView, SpectrumView};
use crate::gui::panels::scene::Camera;
use crate::gui::settings::Settings;
use crate::gui::units::Units;
use crate::sim::Scenario;
use crate::sim::protocol::{GhostState, RunEnd, RunId, RunInfo, SimUpdate, Speed, StartFrom};
use crate::sim::runner::SimHandle;

mod controls;
mod file_dialog;
pub mod frame_layout;
mod layout;
pub mod lecture;
mod map_panel;
mod offscreen;
mod queries;
mod receive;
mod record_open;
mod share;
mod status;
mod style;

pub use file_dialog::{FileAsk, NO_DIALOG, NativeDialog, PathKind};
pub use record_open::RecordQuestion;
pub use share::window_title;

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
    /// The outcome map over two keys. Off at start: it keeps every core
    /// busy for minutes.
    pub map: bool,
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
            map: false,
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

/// The status-bar line after writing a file: `done()` if it was written,
/// else why not.
fn written(r: Result<(), String>, done: impl FnOnce() -> String) -> Message {
    match r {
        Ok(()) => Message {
            text: done(),
            error: false,
        },
        Err(e) => Message { text: e, error: true },
    }
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
    outcome_map: OutcomeMapView,
    camera: Camera,
    flash_at: Option<f64>,
    /// The stack's face (interface) the latest impact was at.
    flash_face: Option<usize>,
    /// The stack's block the plots show (0 the bottom); `None`: the top.
    /// Kept across runs, as the user chose it.
    body: Option<usize>,
    /// The stack's blocks as drawn last frame: each one's four corners,
    /// m, in the base's rest frame (lower left, lower right, upper right,
    /// upper left), and the state they were drawn from.
    stack_drawn: Option<(crate::sim::protocol::StackFrame, Vec<[[f64; 2]; 4]>)>,
    message: Option<Message>,
    /// The message the status bar shows and when it first showed it
    /// (egui's clock, s), for its expiry.
    message_since: Option<(Message, f64)>,
    /// Where the status bar was drawn last (points).
    status_rect: Option<egui::Rect>,
    gpu: bool,
    frame_ms: f32,
    frame_interval_ms: f32,
    last_shown: Option<crate::sim::protocol::Sample>,
    /// The units the user chose with the switch; `None` until they do,
    /// then kept for the rest of the session whatever scene is loaded.
    units_choice: Option<Units>,
    /// The current run's record (name, PGA), read when it started.
    record_label: Option<RecordLabel>,
    ground: GroundView,
    record_question: Option<RecordQuestion>,
    /// The note, the side panel's tab, the presentation scale, the fall.
    lecture: lecture::Lecture,
    /// The window title, GIF recording and PNG export ([`share`]).
    share: share::Share,
    /// How File menu items ask for a path ([`file_dialog`]).
    files: file_dialog::FileDialogs,
    /// Where the last frame put its panels ([`frame_layout`]).
    frame_layout: frame_layout::FrameLayout,
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
        let mut end = None;
        let link = match SimHandle::spawn(config.clone(), speed, paused, waker) {
            Ok(h) => Link::Live(h),
            Err(e) => {
                message = Some(Message {
                    text: e.to_string(),
                    error: true,
                });
                // Shown in the scene's place too (there will be no run).
                end = Some(RunEnd::Failed(e.to_string()));
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
        let preset = app.settings.origin.strip_prefix("preset ").map(str::to_owned);
        if let Some(name) = preset {
            app.show_note_of_preset(&name);
        }
        app.end = end;
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
        style::apply(&cc.egui_ctx, style::TextSizes::NORMAL);
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
            outcome_map: OutcomeMapView::default(),
            camera: Camera::default(),
            flash_at: None,
            flash_face: None,
            body: None,
            stack_drawn: None,
            message: None,
            message_since: None,
            status_rect: None,
            gpu,
            frame_ms: 0.0,
            frame_interval_ms: 0.0,
            last_shown: None,
            units_choice: None,
            record_label: None,
            ground: GroundView::default(),
            record_question: None,
            lecture: lecture::Lecture::default(),
            share: share::Share::default(),
            files: file_dialog::FileDialogs::default(),
            frame_layout: frame_layout::FrameLayout::default(),
        }
    }

    // ---- Actions ----

    /// Shows numbers in `units` from now on (this session), whatever scene
    /// is loaded next.
    pub(crate) fn set_units(&mut self, units: Units) {
        self.units_choice = Some(units);
    }

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
        self.record_label = None;
        self.poincare.reset();
        self.spectrum.reset();
        self.flash_at = None;
        self.flash_face = None;
        self.stack_drawn = None;
        self.lecture.fall_t0 = None;
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

    /// For a stack, says in the status bar that `what` is a block's only
    /// and returns true (the caller then does nothing): a stack starts
    /// from rest, as its batch run does, and has one trajectory.
    fn stack_refuses(&mut self, what: &str) -> bool {
        if self.config.stack.is_none() {
            return false;
        }
        self.message = Some(Message {
            text: format!("{what} is for one block: a stack starts from rest, as its batch run does"),
            error: false,
        });
        true
    }

    /// Restarts from the state shown with Θ + ε.
    pub fn reset_perturbed(&mut self) {
        if self.stack_refuses("a perturbed restart") {
            return;
        }
        self.new_run();
        let eps = self.eps;
        if let Link::Live(h) = &mut self.link {
            h.reset_perturbed(eps);
        }
    }

    /// Makes `settings` (resolved to `config`) the scene and restarts with
    /// it from τ = 0.
    pub fn apply(&mut self, settings: Settings, config: Scenario) {
        self.apply_from(settings, config, StartFrom::Initial);
    }

    /// Makes `settings` (resolved to `config`) the scene and restarts with
    /// it from `from`. The old run's plots are cleared either way, so the
    /// new parameters' attractor is drawn alone.
    pub(crate) fn apply_from(&mut self, settings: Settings, config: Scenario, from: StartFrom) {
        if settings.origin != self.settings.origin {
            // Another scene: its note, if any, comes with it (load_preset).
            self.lecture.note = None;
        }
        self.settings = settings;
        self.config = config.clone();
        self.new_run();
        if from == StartFrom::Initial {
            self.tau = 0.0;
        }
        self.message = None;
        match &mut self.link {
            Link::Live(h) => {
                h.set_params_from(config, from);
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

    /// Sets one key to `raw` as a slider drag does: to the scene
    /// [`RockingApp::set_key`] would give, refused with the same message,
    /// but as a typed edit of the scene shown that reads no record file
    /// ([`Settings::dragged`]), since it comes every frame of a drag;
    /// restarting from where the panel's toggle says
    /// ([`RockingApp::drag_from`]; an initial-state key always restarts
    /// from the initial state it sets).
    pub(crate) fn drag_key(&mut self, key: &str, raw: &str) -> bool {
        let from = if key.starts_with("initial.") {
            StartFrom::Initial
        } else {
            self.edits.drag_from
        };
        match self.settings.dragged(key, raw, &self.config) {
            Ok((s, cfg)) => {
                self.apply_from(s, cfg, from);
                true
            }
            Err(e) => {
                self.message = Some(Message { text: e, error: true });
                false
            }
        }
    }

    /// Applies a value from the parameter panel: a drag as
    /// [`RockingApp::drag_key`], a typed or chosen value as
    /// [`RockingApp::set_key`].
    pub fn commit(&mut self, c: Commit) -> bool {
        if c.dragged {
            self.drag_key(c.key, &c.raw)
        } else {
            self.set_key(c.key, &c.raw)
        }
    }

    /// Takes the stroboscopic section at forcing phase `phase` (rad) from
    /// now on: the run goes on from the state shown, so the time history
    /// and phase portrait are kept and only the section points start over.
    pub fn set_section_phase(&mut self, phase: f64) {
        if self.stack_refuses("a section at another phase") {
            return;
        }
        self.poincare.phase = phase;
        if self.end.is_some() {
            // An ended run cannot go on: the thread starts the scene over.
            self.new_run();
        } else {
            self.hist.clear_section();
            self.poincare.reset();
        }
        match &mut self.link {
            Link::Live(h) => {
                h.set_section_phase(phase);
            }
            Link::Fixed { run, pending } => {
                *run = RunId(run.0 + 1);
                pending.clear();
            }
        }
    }

    /// Loads preset `name`.
    pub fn load_preset(&mut self, name: &str) {
        match Settings::preset(name).and_then(|s| s.resolve().map(|c| (s, c))) {
            Ok((s, c)) => {
                self.apply(s, c);
                self.show_note_of_preset(name);
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

    fn send_ghosts(&mut self) {
        // The new ghosts start from the block's state: their old trails
        // would end in a jump to it.
        self.hist.ghost_trails.clear();
        if self.ghost_count > 0 && self.stack_refuses("ghost copies") {
            return;
        }
        if let Link::Live(h) = &self.link {
            h.set_ghosts(self.ghost_count, self.ghost_eps);
        }
    }

    /// Restarts from Θ = `theta`, Θ' = `theta_dot` (a click on the phase
    /// portrait), through the same validation as the panel.
    pub(crate) fn start_at(&mut self, theta: f64, theta_dot: f64) {
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
