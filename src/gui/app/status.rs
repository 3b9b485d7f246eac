//! The status bar: playhead, mode, counts, speed, how the run ended, frame
//! times (live app only), a GIF recording's progress and the last message;
//! and what the scene shows when there is no run to draw.

use super::{Link, RockingApp};
use crate::gui::panels::scene;
use crate::sim::protocol::RunEnd;

/// The colour of errors (and of the recording mark): a red that reads on
/// the dark and the light theme.
const ERROR_RED: egui::Color32 = egui::Color32::from_rgb(235, 90, 90);

impl RockingApp {
    pub(super) fn status(&mut self, ui: &mut egui::Ui) {
        // The bar is drawn every frame: the title and the pictures being
        // taken advance with it.
        self.share_tick(ui.ctx());
        ui.horizontal_wrapped(|ui| {
            let p = self.info.as_ref().map_or(self.config.geometry().p, |i| i.geometry.p);
            ui.label(format!("τ = {:.2}", self.tau));
            ui.label(format!("t = {:.2} s", self.tau / p));
            // The symbols, explained on hover (Help ▸ Symbols lists them).
            let geo = self.info.as_ref().map_or_else(|| self.config.geometry(), |i| i.geometry);
            let [theta, tau, psi, p_sym] = crate::gui::glossary::entries(&geo);
            ui.label("Θ = θ/ψ").on_hover_text(theta.1);
            ui.label("τ = p t").on_hover_text(tau.1);
            ui.label(format!("ψ = {:.2}°", geo.psi.to_degrees())).on_hover_text(psi.1);
            ui.label(format!("p = {:.3}/s", geo.p)).on_hover_text(p_sym.1);
            ui.separator();
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
                    RunEnd::Terminal {
                        mode: crate::model::Mode::Tumbled,
                        tau,
                    } => {
                        // When and why, and that the fall shown is drawn.
                        let limit = self.info.as_ref().map_or(1.0, |i| i.scenario.run.tumble_theta);
                        ui.colored_label(
                            scene::mode_color(crate::model::Mode::Tumbled),
                            format!(
                                "tumbled at τ = {tau:.2} (t = {:.2} s): |Θ| reached {limit}, the centre of mass over the corner; the fall after it is drawn, not simulated",
                                tau / p
                            ),
                        );
                    }
                    RunEnd::Terminal { mode, tau } => {
                        ui.colored_label(scene::mode_color(*mode), format!("{} at τ = {tau:.3}", mode.name()));
                    }
                    RunEnd::Rest { tau, .. } => {
                        ui.colored_label(
                            scene::mode_color(crate::model::Mode::Rest),
                            format!("at rest after the record, τ = {tau:.3}"),
                        );
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
            if let Some(text) = self.recording_label(ui.input(|i| i.time)) {
                ui.colored_label(ERROR_RED, text);
            }
            if let Some(m) = &self.message {
                let color = if m.error {
                    ERROR_RED
                } else {
                    ui.visuals().weak_text_color()
                };
                ui.colored_label(color, &m.text);
            }
        });
    }

    /// What the scene shows while it has nothing to draw: why the run did
    /// not start, in red, if it failed to; else that it is coming.
    pub(super) fn no_run_label(&self, ui: &mut egui::Ui) {
        let failed = match &self.end {
            Some(RunEnd::Failed(msg)) => Some(msg),
            Some(RunEnd::Terminal { .. } | RunEnd::Rest { .. }) | None => None,
        };
        ui.centered_and_justified(|ui| match failed {
            Some(msg) => {
                ui.colored_label(ERROR_RED, format!("The run could not start: {msg}"));
            }
            None => {
                ui.label("waiting for the simulation…");
            }
        });
    }
}
