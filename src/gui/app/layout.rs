//! The window's layout: which panel goes where, the panels' own contents
//! (parameters, analyses, block scene) and the frame timing.

use std::time::{Duration, Instant};

use super::RockingApp;
use super::lecture::{self, SideTab};
use crate::gui::panels::banner::{self, Verdict};
use crate::gui::panels::ground;
use crate::gui::panels::params;
use crate::gui::panels::plots;
use crate::gui::panels::scene::{self, SceneInput};
use crate::model::Mode;
use crate::sim::protocol::RunEnd;

/// How long an impact flash lasts, s of wall-clock time.
const FLASH_S: f64 = 0.18;

impl RockingApp {
    fn params_panel(&mut self, ui: &mut egui::Ui) {
        // Fill the width the layout gave the panel (a panel otherwise
        // shrinks to its widest row and clips the unit column).
        ui.set_min_width(ui.available_width());
        ui.heading("Parameters");
        ui.label(egui::RichText::new(&self.settings.origin).weak());
        egui::ScrollArea::both().show(ui, |ui| {
            let settings = &self.settings;
            let explicit = |k: &str| settings.explicit(k);
            let commit = params::show(ui, &self.config, &explicit, &mut self.edits);
            if let Some(c) = commit {
                self.commit(c);
            }
        });
    }

    /// The tabs the side panel has: the plots and each analysis the View
    /// menu opened.
    pub(super) fn side_tabs(&self) -> Vec<SideTab> {
        let mut tabs = Vec::new();
        if self.show.phase || (self.show.poincare && self.has_section()) {
            tabs.push(SideTab::Plots);
        }
        if self.show.bifurcation {
            tabs.push(SideTab::Bifurcation);
        }
        if self.show.lyapunov {
            tabs.push(SideTab::Lyapunov);
        }
        if self.show.map {
            tabs.push(SideTab::Map);
        }
        tabs
    }

    /// A side panel showing one of `tabs`, with a tab bar when there are
    /// several.
    fn side_panel(&mut self, ui: &mut egui::Ui, tabs: &[SideTab]) {
        let Some(&first) = tabs.first() else {
            return;
        };
        // A tab that just appeared (an analysis opened from the View menu
        // or by a test) comes to the front; a closed one gives way.
        if let Some(&new) = tabs.iter().rev().find(|t| !self.lecture.tabs_seen.contains(t)) {
            self.lecture.tab = new;
        }
        self.lecture.tabs_seen = tabs.to_vec();
        if !tabs.contains(&self.lecture.tab) {
            self.lecture.tab = first;
        }
        if tabs.len() > 1 {
            ui.horizontal_wrapped(|ui| {
                for &tab in tabs {
                    ui.selectable_value(&mut self.lecture.tab, tab, tab.name());
                }
            });
            ui.separator();
        }
        match self.lecture.tab {
            SideTab::Plots => self.plots_panel(ui),
            SideTab::Bifurcation => {
                ui.label("Bifurcation diagram (drag to zoom, double-click: full range)");
                self.bifurcation.show(ui, &self.settings, &self.config);
            }
            SideTab::Lyapunov => {
                ui.label("Largest Lyapunov exponent (from the initial state)");
                self.lyapunov.show(ui, &self.config);
            }
            SideTab::Map => self.outcome_map_panel(ui),
        }
    }

    fn scene_panel(&mut self, ui: &mut egui::Ui) {
        let mut full = ui.available_rect_before_wrap();
        // What to look at, then the mode legend, each as tall as its text
        // needs at this width, above the block.
        if self.note().is_some() {
            let used = ui
                .scope_builder(egui::UiBuilder::new().max_rect(full), |ui| self.note_strip(ui))
                .response
                .rect;
            full.min.y = used.max.y + 4.0;
        }
        let used = ui
            .scope_builder(egui::UiBuilder::new().max_rect(full), lecture::legend)
            .response
            .rect;
        full.min.y = used.max.y + 2.0;
        let (Some(info), Some(sample)) = (self.info.as_ref(), self.hist.samples.last()) else {
            self.no_run_label(ui);
            return;
        };
        let verdict = self.end.as_ref().and_then(|e| Verdict::of(e, info.geometry));
        // A record scene: the banner in its own strip above the block.
        let rect = match &self.record_label {
            Some(label) => {
                let strip = egui::Rect::from_min_size(full.min, egui::vec2(full.width(), banner::STRIP_HEIGHT));
                let lines = match &verdict {
                    Some(v) => banner::Lines::verdict(v, Some(label.title())),
                    None => banner::Lines::playing(sample, info.geometry, Some(label.title())),
                };
                banner::show(ui, strip.shrink2(egui::vec2(10.0, 4.0)), &lines);
                egui::Rect::from_min_max(egui::pos2(full.min.x, strip.max.y), full.max)
            }
            None => full,
        };
        let now = ui.input(|i| i.time);
        // After a tumble: the fall onto the side, drawn (not simulated).
        let tumbled = matches!(
            self.end,
            Some(RunEnd::Terminal {
                mode: Mode::Tumbled,
                ..
            })
        );
        let mut falling = None;
        if tumbled {
            let t0 = *self.lecture.fall_t0.get_or_insert(now);
            let (shown, done) = lecture::fallen(&info.geometry, sample, now - t0);
            if !done {
                ui.ctx().request_repaint();
            }
            falling = Some(shown);
        }
        let sample = falling.as_ref().unwrap_or(sample);
        self.last_shown = Some(*sample);
        self.lecture.scene_rect = Some(full);
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
                Some(RunEnd::Rest { .. } | RunEnd::Failed(_)) | None => None,
            },
            flash,
            forces: self.forces,
        };
        let (shapes, scale, y_mid) = scene::build(&input, rect, &mut self.camera);
        let view = scene::view(rect, scale, &self.camera, y_mid, ui.ctx().pixels_per_point());
        scene::paint(ui, rect, shapes, view, self.gpu);
        scene::ghost_caption(ui, rect, &input);
        if falling.is_some() {
            let text = "after the tumble: drawn, not simulated (the model stops when the centre of mass passes over the corner)";
            // Wrapped to the scene's width: one line is wider than a narrow
            // scene and was cut at both ends.
            let mut job = egui::text::LayoutJob::simple(
                text.to_owned(),
                egui::FontId::proportional(14.0),
                egui::Color32::from_rgb(255, 170, 150),
                rect.width() - 16.0,
            );
            job.halign = egui::Align::Center;
            let galley = ui.painter().layout_job(job);
            let top = rect.max.y - 8.0 - galley.size().y;
            ui.painter()
                .galley(egui::pos2(rect.center().x, top), galley, egui::Color32::WHITE);
        }
        if self.record_label.is_none()
            && let Some(v) = &verdict
        {
            // Any other scene that tumbles: the verdict over the block.
            let lines = banner::Lines::verdict(v, None);
            let below = usize::from(lines.detail.is_some());
            let plate = egui::Rect::from_min_size(
                rect.min + egui::vec2(10.0, 10.0),
                egui::vec2(rect.width() - 20.0, banner::plate_height(below)),
            );
            banner::show(ui, plate, &lines);
        }
        ui.allocate_rect(full, egui::Sense::hover());
    }

    /// Whether the run takes stroboscopic section points (harmonic
    /// excitation): without them the Poincaré plot has nothing to show.
    fn has_section(&self) -> bool {
        self.info.as_ref().map_or_else(
            || self.config.excitation.forcing_period().is_some(),
            |i| i.section_period.is_some(),
        )
    }

    /// The bottom panel: the time history, and beside it the ground
    /// acceleration of a record scene (always) or the power spectrum.
    fn history_panel(&mut self, ui: &mut egui::Ui) {
        let scales = self.scales();
        let ground = self.record_label.clone();
        let spectrum = self.show.spectrum && ground.is_none();
        let both = self.show.history && (spectrum || ground.is_some());
        let width = ui.available_width();
        let height = ui.available_height();
        ui.horizontal(|ui| {
            if self.show.history {
                let w = if both { 0.6 * width } else { width };
                ui.allocate_ui(egui::vec2(w, height), |ui| {
                    ui.vertical(|ui| {
                        plots::history_plot(ui, &self.hist, &mut self.history_view, self.tau, &scales);
                    });
                });
            }
            if let Some(label) = &ground {
                ui.vertical(|ui| {
                    ground::ground_plot(ui, &self.hist, &mut self.ground, label, self.tau, &scales);
                });
            } else if spectrum {
                let (dt, omega_h) = self.info.as_ref().map_or(
                    (crate::sim::runner::LIVE_SAMPLE_DT, self.config.excitation.omega_h),
                    |i| (i.sample_dt, i.scenario.excitation.omega_h),
                );
                ui.vertical(|ui| {
                    // One line, cut with "…" in a narrow column (egui shows it whole on
                    // hover), so the plot keeps its height at a large presentation scale.
                    ui.add(egui::Label::new("Power spectrum of Θ (last 41 τ)").truncate());
                    plots::spectrum_plot(ui, &self.hist, &mut self.spectrum, dt, omega_h, &scales);
                });
            }
        });
    }

    fn plots_panel(&mut self, ui: &mut egui::Ui) {
        let scales = self.scales();
        let poincare = self.show.poincare && self.has_section();
        let both = self.show.phase && poincare;
        let h = ui.available_height();
        if self.show.phase {
            ui.label("Phase portrait (click to start there)");
            // The Poincaré plot below has its section controls to fit too.
            let height = if both { 0.44 * h - 20.0 } else { h - 20.0 };
            ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
                if let Some((theta, theta_dot)) = plots::phase_plot(ui, &self.hist, &mut self.phase, self.tau, &scales)
                {
                    self.start_at(theta, theta_dot);
                }
            });
        }
        if poincare {
            ui.label("Poincaré points (double-click to fit)");
            if let Some(phase) = plots::poincare_plot(ui, &self.hist, &mut self.poincare, &scales) {
                self.set_section_phase(phase);
            }
        }
    }

    /// Updates the frame times the status bar shows: app CPU time per
    /// frame and the interval between frames, both smoothed over about ten
    /// frames.
    fn time_frame(&mut self, ui: &egui::Ui, start: Instant) {
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

impl eframe::App for RockingApp {
    fn logic(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        self.receive(ctx);
        self.share_logic(ctx, frame);
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let start = Instant::now();
        self.keys(ui);
        self.follow_scale(ui.ctx());
        // Panel sizes are fractions of the window (in points, so of what
        // the presentation scale leaves): the block scene keeps at least
        // a third of the width with every panel open, at 1280 × 800 and
        // on a 1920 × 1080 projector alike.
        // Before the window reports its size (eframe's first pass runs on
        // egui's 10,000-pixel placeholder), lay nothing out: panel sizes
        // are remembered, and defaults taken from a placeholder would stick
        // (a side panel half off screen at a presentation scale).
        let screen = ui.ctx().content_rect();
        let zoom = ui.ctx().zoom_factor();
        if screen.width() * zoom >= 9_999.0 && screen.height() * zoom >= 9_999.0 {
            ui.ctx().request_repaint();
            return;
        }
        let (w, h) = (screen.width(), screen.height());
        // Panels remember the size the user gave them, per presentation
        // scale: a new scale starts from its own proportional defaults
        // instead of keeping sizes in points meant for another.
        let at = (self.lecture.scale * 100.0).round() as i32;
        egui::Panel::top("controls").show(ui, |ui| self.controls(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status(ui));
        if self.show.params {
            egui::Panel::left(("params", at))
                .resizable(true)
                .default_size((0.23 * w).clamp(180.0, 340.0))
                .size_range(150.0..=(0.3 * w).max(160.0))
                .show(ui, |ui| self.params_panel(ui));
        }
        if self.show.history || self.show.spectrum || self.record_label.is_some() {
            // A record scene's bottom panel carries the ground trace, the
            // earthquake itself: taller, with its own id so that each kind
            // keeps the height the user gave it.
            let (id, height) = if self.record_label.is_some() {
                ("history with ground", 0.31 * h)
            } else {
                ("history", 0.24 * h)
            };
            egui::Panel::bottom((id, at))
                .resizable(true)
                .default_size(height.clamp(140.0, 330.0))
                .size_range(90.0..=(0.42 * h).max(100.0))
                .show(ui, |ui| self.history_panel(ui));
        }
        if !self.show.bifurcation {
            self.bifurcation.hide();
        }
        if !self.show.lyapunov {
            self.lyapunov.hide();
        }
        if !self.show.map {
            self.outcome_map.hide();
        }
        let tabs = self.side_tabs();
        // A wide window (a 1920-pixel projector at scale 1) has room for
        // the plots beside an analysis; a narrower one tabs them.
        let wide = w >= 1500.0;
        if wide && tabs.len() > 1 && tabs[0] == SideTab::Plots {
            egui::Panel::right(("analyses", at))
                .resizable(true)
                .default_size(0.22 * w)
                .size_range(200.0..=0.27 * w)
                .show(ui, |ui| self.side_panel(ui, &tabs[1..]));
            self.lecture.tabs_seen.push(SideTab::Plots);
            egui::Panel::right(("plots", at))
                .resizable(true)
                .default_size(0.2 * w)
                .size_range(200.0..=0.25 * w)
                .show(ui, |ui| self.plots_panel(ui));
        } else if !tabs.is_empty() {
            egui::Panel::right(("side", at))
                .resizable(true)
                .default_size((0.3 * w).clamp(220.0, 560.0))
                .size_range(180.0..=(0.35 * w).max(190.0))
                .show(ui, |ui| self.side_panel(ui, &tabs));
        }
        egui::CentralPanel::default().show(ui, |ui| {
            if self.show.scene {
                self.scene_panel(ui);
            } else {
                ui.centered_and_justified(|ui| ui.label("Block scene hidden (View menu)"));
            }
        });
        self.record_window(ui.ctx());
        self.time_frame(ui, start);
    }
}
