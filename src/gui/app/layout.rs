//! The window's layout: which panel goes where, the panels' own contents
//! (parameters, analyses, block scene) and the frame timing.

use std::time::{Duration, Instant};

use super::RockingApp;
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
        ui.heading("Parameters");
        ui.label(egui::RichText::new(&self.settings.origin).weak());
        egui::ScrollArea::vertical().show(ui, |ui| {
            let settings = &self.settings;
            let explicit = |k: &str| settings.explicit(k);
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
        let full = ui.available_rect_before_wrap();
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
                Some(RunEnd::Rest { .. } | RunEnd::Failed(_)) | None => None,
            },
            flash,
            forces: self.forces,
        };
        let (shapes, scale, y_mid) = scene::build(&input, rect, &mut self.camera);
        let view = scene::view(rect, scale, &self.camera, y_mid, ui.ctx().pixels_per_point());
        scene::paint(ui, rect, shapes, view, self.gpu);
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
                    ui.label("Power spectrum of Θ (last 41 τ)");
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
            let height = if both { 0.5 * h - 24.0 } else { h - 20.0 };
            ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
                if let Some((theta, theta_dot)) = plots::phase_plot(ui, &self.hist, &mut self.phase, self.tau, &scales)
                {
                    self.start_at(theta, theta_dot);
                }
            });
        }
        if poincare {
            ui.label("Poincaré points (double-click to fit)");
            plots::poincare_plot(ui, &self.hist, &mut self.poincare, &scales);
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
    fn logic(&mut self, ctx: &egui::Context, _frame: &mut eframe::Frame) {
        self.receive(ctx);
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let start = Instant::now();
        self.keys(ui);
        egui::Panel::top("controls").show(ui, |ui| self.controls(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status(ui));
        if self.show.params {
            egui::Panel::left("params")
                .resizable(true)
                .default_size(300.0)
                .show(ui, |ui| self.params_panel(ui));
        }
        if self.show.history || self.show.spectrum || self.record_label.is_some() {
            // A record scene's bottom panel carries the ground trace, the
            // earthquake itself: taller, with its own id so that each kind
            // keeps the height the user gave it.
            let (id, height) = if self.record_label.is_some() {
                ("history with ground", 250.0)
            } else {
                ("history", 190.0)
            };
            egui::Panel::bottom(id)
                .resizable(true)
                .default_size(height)
                .show(ui, |ui| self.history_panel(ui));
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
        if self.show.phase || (self.show.poincare && self.has_section()) {
            egui::Panel::right("plots")
                .resizable(true)
                .default_size(380.0)
                .show(ui, |ui| self.plots_panel(ui));
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
