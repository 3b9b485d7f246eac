//! The window's layout: which panel goes where, the panels' own contents
//! (parameters, analyses, block scene) and the frame timing.

use std::time::Instant;

use super::RockingApp;
use super::lecture::{BottomTab, PlotTab, SideTab};
use crate::analysis::lyapunov;
use crate::gui::panels::ground;
use crate::gui::panels::params;
use crate::gui::panels::plots;
use crate::gui::panels::stack_params;
use crate::sim::stack_answer::body_name;

mod scene_panel;

impl RockingApp {
    fn params_panel(&mut self, ui: &mut egui::Ui) {
        // Fill the width the layout gave the panel (a panel otherwise
        // shrinks to its widest row and clips the unit column).
        ui.set_min_width(ui.available_width());
        ui.heading("Parameters");
        ui.label(egui::RichText::new(&self.settings.origin).weak());
        self.body_selector(ui);
        let panel_w = ui.available_width();
        let out = egui::ScrollArea::both().show(ui, |ui| {
            // A stack's blocks first: what the scene is made of.
            let stack = stack_params::show(ui, &self.config, &mut self.edits);
            let settings = &self.settings;
            let explicit = |k: &str| settings.explicit(k);
            params::show(ui, &self.config, &explicit, &mut self.edits).or(stack)
        });
        // The width the rows need (names, sliders, values and units side by
        // side): the next frame sizes the panel to hold it.
        let frame = egui::Frame::side_top_panel(ui.style()).total_margin().sum().x;
        self.frame_layout.params_need = out.content_size.x + (panel_w - out.inner_rect.width()) + frame + 1.0;
        if let Some(c) = out.inner {
            self.commit(c);
        }
    }

    /// For a stack: which block the phase portrait, the time history and
    /// the Poincaré points show (the top one unless chosen).
    fn body_selector(&mut self, ui: &mut egui::Ui) {
        let (Some(k), Some(current)) = (self.stack().map(|g| g.k), self.chosen_body()) else {
            return;
        };
        let mut chosen = current;
        ui.horizontal(|ui| {
            let label = ui.label("Plots show");
            egui::ComboBox::from_id_salt("stack body")
                .selected_text(body_name(current, k))
                .show_ui(ui, |ui| {
                    for j in (0..k).rev() {
                        ui.selectable_value(&mut chosen, j, body_name(j, k));
                    }
                })
                .response
                .labelled_by(label.id)
                .on_hover_text("The block whose absolute rotation φ the phase portrait, the time history and the Poincaré points show");
        });
        if chosen != current {
            self.choose_body(chosen);
        }
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
        // Fill the width the layout gave the panel: egui remembers a
        // panel's size as what its contents took, so contents narrower
        // than the panel would shrink it frame after frame.
        ui.set_min_width(ui.available_width());
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
                ui.label(match lyapunov::method_for(&self.config) {
                    lyapunov::Method::Benettin => {
                        "Largest Lyapunov exponent (from the initial state, by two trajectories)"
                    }
                    lyapunov::Method::Tangent | lyapunov::Method::Both => {
                        "Largest Lyapunov exponent (from the initial state)"
                    }
                });
                self.lyapunov.show(ui, &self.config);
            }
            SideTab::Map => self.outcome_map_panel(ui),
        }
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
    /// acceleration of a record scene (always) or the power spectrum; as
    /// tabs where the panel is too narrow for both side by side.
    fn history_panel(&mut self, ui: &mut egui::Ui) {
        let scales = self.scales();
        let ground = self.record_label.clone();
        let spectrum = self.show.spectrum && ground.is_none();
        let both = self.show.history && (spectrum || ground.is_some());
        let width = ui.available_width();
        let tabbed = both && 0.4 * width < min_plot(ui).x;
        let (mut show_history, mut show_other) = (self.show.history, spectrum || ground.is_some());
        if tabbed {
            let other = if ground.is_some() {
                "Ground acceleration"
            } else {
                "Power spectrum"
            };
            ui.horizontal_wrapped(|ui| {
                ui.selectable_value(&mut self.lecture.bottom_tab, BottomTab::History, "Time history");
                ui.selectable_value(&mut self.lecture.bottom_tab, BottomTab::Other, other);
            });
            show_history = self.lecture.bottom_tab == BottomTab::History;
            show_other = !show_history;
        }
        let height = ui.available_height();
        ui.horizontal(|ui| {
            if show_history {
                let w = if show_other { 0.6 * width } else { width };
                ui.allocate_ui(egui::vec2(w, height), |ui| {
                    ui.vertical(|ui| {
                        plots::history_plot(ui, &self.hist, &mut self.history_view, self.tau, &scales);
                    });
                });
            }
            if !show_other {
                return;
            }
            // The rest of the width and the whole height (a row's height is
            // otherwise that of what it holds so far).
            let size = egui::vec2(ui.available_width(), height);
            if let Some(label) = &ground {
                ui.allocate_ui(size, |ui| {
                    ui.vertical(|ui| {
                        ground::ground_plot(ui, &self.hist, &mut self.ground, label, self.tau, &scales);
                    });
                });
            } else if spectrum {
                let (dt, omega_h) = self.info.as_ref().map_or(
                    (crate::sim::runner::LIVE_SAMPLE_DT, self.config.excitation.omega_h),
                    |i| (i.sample_dt, i.scenario.excitation.omega_h),
                );
                ui.allocate_ui(size, |ui| {
                    ui.vertical(|ui| {
                        // One line, cut with "…" in a narrow column (egui shows it whole on
                        // hover), so the plot keeps its height at a large presentation scale.
                        ui.add(egui::Label::new("Power spectrum of Θ (last 41 τ)").truncate());
                        plots::spectrum_plot(ui, &self.hist, &mut self.spectrum, dt, omega_h, &scales);
                    });
                });
            }
        });
    }

    /// The phase portrait above the Poincaré points; as tabs where the
    /// column is too short for both (a large scale) or in the lecture
    /// presentation, so the plot shown keeps a size a hall can read.
    fn plots_panel(&mut self, ui: &mut egui::Ui) {
        // Fill the panel's width (see side_panel).
        ui.set_min_width(ui.available_width());
        let scales = self.scales();
        let poincare = self.show.poincare && self.has_section();
        let both = self.show.phase && poincare;
        // Both stacked need two plots and four rows of text (two titles,
        // the section's controls and its caption).
        let row = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
        let tabbed = both && (self.lecture.presentation || ui.available_height() < 2.0 * min_plot(ui).y + 5.0 * row);
        let (mut phase, mut section) = (self.show.phase, poincare);
        if tabbed {
            // Wrapped: a row that cannot wrap widens a narrow column past
            // the window (a stack's wide parameter panel at 150 %).
            ui.horizontal_wrapped(|ui| {
                ui.selectable_value(&mut self.lecture.plot_tab, PlotTab::Phase, "Phase portrait");
                ui.selectable_value(&mut self.lecture.plot_tab, PlotTab::Poincare, "Poincaré points")
                    .on_hover_text("Double-click the plot to fit it to its points");
            });
            phase = self.lecture.plot_tab == PlotTab::Phase;
            section = !phase;
        }
        let h = ui.available_height();
        if phase {
            // One line, cut with "…" in a narrow column (whole on hover):
            // the plot's height below counts one row for it.
            ui.add(egui::Label::new("Phase portrait (click to start there)").truncate());
            // The Poincaré plot below has its section controls to fit too.
            let height = if section { 0.44 * h - row } else { h - row };
            ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
                if let Some((theta, theta_dot)) = plots::phase_plot(ui, &self.hist, &mut self.phase, self.tau, &scales)
                {
                    self.start_at(theta, theta_dot);
                }
            });
        }
        if section {
            // Under its own tab the title would repeat the tab's name: the
            // hint goes on the tab's hover instead, and the plot keeps the row.
            if !tabbed {
                ui.add(egui::Label::new("Poincaré points (double-click to fit)").truncate());
            }
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
        // (And per presentation: the lecture's larger text has its own.)
        let at = (
            (self.presentation_scale() * 100.0).round() as i32,
            self.lecture.presentation,
        );
        let mut panels = Vec::new();
        let r = egui::Panel::top("controls").show(ui, |ui| self.controls(ui));
        panels.push(("controls", r.response.rect));
        let r = egui::Panel::bottom("status").show(ui, |ui| self.status(ui));
        panels.push(("status", r.response.rect));
        if self.show.params {
            // As wide as its rows need (measured last frame; a narrower
            // panel scrolls them sideways and cuts the units off), within
            // 40 % of the window.
            let need = self.frame_layout.params_need;
            let most = (0.4 * w).max(160.0);
            let r = egui::Panel::left(("params", at))
                .resizable(true)
                .default_size((0.23 * w).clamp(180.0, 340.0).max(need).min(most))
                .size_range(need.clamp(150.0, most)..=(0.3 * w).max(need).clamp(160.0, most))
                .show(ui, |ui| self.params_panel(ui));
            panels.push(("params", r.response.rect));
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
            // Tall enough for a readable plot under its row of controls and
            // a row of tabs, within 42 % of the window.
            let row = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
            let need = min_plot(ui).y + 2.0 * row + 16.0;
            let most = (0.42 * h).max(100.0);
            let r = egui::Panel::bottom((id, at))
                .resizable(true)
                .default_size(height.clamp(140.0, 330.0).max(need).min(most))
                .size_range(need.clamp(90.0, most)..=most)
                .show(ui, |ui| self.history_panel(ui));
            panels.push(("history", r.response.rect));
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
        // What the right-hand panels may take: the block scene keeps 30 %
        // of the width whatever the parameter panel took, inside the
        // central panel's margins.
        let left = panels.iter().find(|p| p.0 == "params").map_or(0.0, |p| p.1.width());
        let margins = egui::Frame::central_panel(ui.style()).total_margin().sum().x;
        let mut budget = 0.7 * w - left - margins - 2.0;
        if wide && tabs.len() > 1 && tabs[0] == SideTab::Plots {
            let (lo, hi) = range_within(200.0, 0.27 * w, budget - 200.0);
            let r = egui::Panel::right(("analyses", at))
                .resizable(true)
                .default_size((0.22 * w).clamp(lo, hi))
                .size_range(lo..=hi)
                .show(ui, |ui| self.side_panel(ui, &tabs[1..]));
            panels.push(("analyses", r.response.rect));
            budget -= r.response.rect.width();
            self.lecture.tabs_seen.push(SideTab::Plots);
            let (lo, hi) = range_within(200.0, 0.25 * w, budget);
            let r = egui::Panel::right(("plots", at))
                .resizable(true)
                .default_size((0.2 * w).clamp(lo, hi))
                .size_range(lo..=hi)
                .show(ui, |ui| self.plots_panel(ui));
            panels.push(("plots", r.response.rect));
        } else if !tabs.is_empty() {
            // The lecture presentation's larger numbers take more of the
            // plots' width: the column is wider to keep them large.
            let share = if self.lecture.presentation { 0.35 } else { 0.3 };
            let (lo, hi) = range_within(180.0, (0.35 * w).max(190.0), budget);
            let r = egui::Panel::right(("side", at))
                .resizable(true)
                .default_size((share * w).clamp(220.0, 560.0).clamp(lo, hi))
                .size_range(lo..=hi)
                .show(ui, |ui| self.side_panel(ui, &tabs));
            panels.push(("side", r.response.rect));
        }
        self.frame_layout.banner = None;
        self.frame_layout.caption = None;
        self.frame_layout.block_top = None;
        self.frame_layout.table_top = None;
        let r = egui::CentralPanel::default().show(ui, |ui| {
            if self.show.scene {
                self.scene_panel(ui);
            } else {
                ui.centered_and_justified(|ui| ui.label("Block scene hidden (View menu)"));
            }
        });
        panels.push(("central", r.response.rect));
        self.frame_layout.screen = screen;
        self.frame_layout.panels = panels;
        self.record_window(ui.ctx());
        self.time_frame(ui, start);
    }
}

/// A panel's size range, points: from `min` to `max`, but never more than
/// `room` (then the range is `room` alone, however small).
fn range_within(min: f32, max: f32, room: f32) -> (f32, f32) {
    let hi = max.min(room).max(1.0);
    (min.min(hi), hi)
}

/// The smallest plot, axes included, that still reads, points: room for
/// two numbered ticks a readable gap apart on each axis and the numbers
/// and title beside them, in the style's plot-number font.
fn min_plot(ui: &egui::Ui) -> egui::Vec2 {
    let f = crate::gui::panels::axes::number_font(ui.style()).size;
    egui::vec2(16.0 * f, 8.0 * f)
}
