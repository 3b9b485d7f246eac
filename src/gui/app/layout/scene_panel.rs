//! The central panel: the animated scene, its legend and its banner.

use std::time::Duration;

use super::super::RockingApp;
use super::super::frame_layout::BannerRects;
use super::super::lecture;
use crate::gui::panels::banner::{self, Verdict};
use crate::gui::panels::scene::{self, SceneInput};
use crate::gui::panels::stack_scene::{self, StackSceneInput};
use crate::model::kinematics;
use crate::sim::EndState;
use crate::sim::protocol::RunEnd;
use crate::sim::stack_answer::body_name;

/// How long an impact flash lasts, s of wall-clock time.
const FLASH_S: f64 = 0.18;

/// The remark under the verdict after a tumble, on the banner's plate
/// (over the ground or the fallen block it hid them; the status bar says
/// why the model stops there).
const FALL_NOTE: &str = "the fall after the tumble is drawn (not simulated)";

impl RockingApp {
    /// The central panel: what to look at, the mode legend and the
    /// animated block (or stack, or frame) with its banner.
    pub(super) fn scene_panel(&mut self, ui: &mut egui::Ui) {
        let mut full = ui.available_rect_before_wrap();
        // What to look at, then the mode legend, each as tall as its text
        // needs at this width, above the block.
        if self.note().is_some() {
            // At most 40 % of the scene's height (scrolled beyond): a long
            // note in a short scene (a large presentation scale) left the
            // block a sliver.
            let row = ui.text_style_height(&egui::TextStyle::Body);
            let most = (0.4 * full.height() - row).max(2.0 * row);
            let used = ui
                .scope_builder(egui::UiBuilder::new().max_rect(full), |ui| {
                    egui::ScrollArea::vertical()
                        .id_salt("note")
                        .max_height(most)
                        .auto_shrink([false, true])
                        .show(ui, |ui| self.note_strip(ui));
                })
                .response
                .rect;
            full.min.y = used.max.y + 4.0;
        }
        if std::env::var_os("LAYOUT_DEBUG").is_some() {
            eprintln!(
                "central start {:?} max {:?} full {:?}",
                ui.min_rect(),
                ui.max_rect(),
                full
            );
        }
        let used = ui
            .scope_builder(egui::UiBuilder::new().max_rect(full), lecture::legend)
            .response
            .rect;
        if std::env::var_os("LAYOUT_DEBUG").is_some() {
            eprintln!(
                "after legend {:?} max {:?} used {:?}",
                ui.min_rect(),
                ui.max_rect(),
                used
            );
        }
        full.min.y = used.max.y + 2.0;
        let (Some(info), Some(sample)) = (self.info.as_ref(), self.hist.samples.last()) else {
            self.no_run_label(ui);
            return;
        };
        let stack = info.stack.zip(sample.stack);
        let verdict = self.end.as_ref().and_then(|e| Verdict::of(e, info.geometry)).map(|v| {
            // A stack's verdict names the block that overturned or flew,
            // in the words of the batch run's answer.
            match self.stack_end() {
                Some((_, name)) => v.about(name),
                None => v,
            }
        });
        // After a tumble: the fall onto the side, drawn (not simulated;
        // a block's only).
        let tumbled = verdict.is_some_and(|v| v.end == EndState::Overturned) && stack.is_none();
        // A record scene: the banner in its own strip above the block.
        let rect = match &self.record_label {
            Some(label) => {
                let mut lines = match (&verdict, stack) {
                    (Some(v), _) => banner::Lines::verdict(v, Some(label.title())),
                    (None, Some((g, _))) => {
                        let name = body_name(self.chosen_body().unwrap_or(g.k - 1), g.k);
                        banner::Lines::playing_body(sample, info.geometry, name, Some(label.title()))
                    }
                    (None, None) => banner::Lines::playing(sample, info.geometry, Some(label.title())),
                };
                if tumbled {
                    lines.note = Some(FALL_NOTE.to_owned());
                }
                let fitted = banner::fit(ui, full.width() - 20.0, &lines);
                let strip = egui::Rect::from_min_size(
                    full.min,
                    egui::vec2(full.width(), banner::STRIP_HEIGHT.max(fitted.height + 8.0)),
                );
                let plate = strip.shrink2(egui::vec2(10.0, 4.0));
                let (text, last) = banner::show(ui, plate, &fitted);
                self.frame_layout.banner = Some(BannerRects { plate, text });
                if tumbled {
                    self.frame_layout.caption = Some(last);
                }
                egui::Rect::from_min_max(egui::pos2(full.min.x, strip.max.y), full.max)
            }
            None => full,
        };
        let now = ui.input(|i| i.time);
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
        let stack_input = stack.as_ref().map(|(geo, frame)| StackSceneInput {
            geo,
            frame,
            base_x: sample.base_x * info.geometry.r,
            flash,
            flash_face: self.flash_face,
            ended: self.stack_end().map(|(e, _)| e),
        });
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
            frame: info.scenario.frame,
        };
        let (shapes, scale, y_mid, top) = match &stack_input {
            Some(si) => {
                let (shapes, scale, y_mid, drawn) = stack_scene::build(si, rect, &mut self.camera);
                let top = drawn.iter().flat_map(|b| b.corners()).map(|c| c[1]).fold(0.0, f64::max);
                self.stack_drawn = Some((*si.frame, drawn.iter().map(|b| b.corners()).collect()));
                (shapes, scale, y_mid, top)
            }
            None => {
                let (shapes, scale, y_mid) = scene::build(&input, rect, &mut self.camera);
                let p = crate::sim::protocol::pose(&info.geometry, sample.theta, sample.x, sample.mode, sample.base_x);
                let reach = kinematics::half_height_turned_m(&info.geometry, p.angle);
                (shapes, scale, y_mid, p.y + reach)
            }
        };
        // Where the block's top and the table's top are drawn (points), for
        // the layout tests: world height y is drawn at centre − (y − y_mid)·scale.
        let to_screen = |y: f64| rect.center().y - ((y - y_mid) * scale) as f32;
        self.frame_layout.block_top = Some(to_screen(top));
        self.frame_layout.table_top = Some(to_screen(0.0));
        let view = scene::view(rect, scale, &self.camera, y_mid, ui.ctx().pixels_per_point());
        scene::paint(ui, rect, shapes, view, self.gpu);
        scene::ghost_caption(ui, rect, &input);
        // Any scene but a record's (whose banner has its strip above):
        // the verdict on a plate over the top of the scene, where the sky
        // is once the block has fallen.
        // Survival there would cover the block it is about (a free-rocking
        // block at rest): only a record scene, whose banner has its own
        // strip, says SURVIVED; the status bar says how any run ended.
        if self.record_label.is_none()
            && let Some(v) = verdict.as_ref().filter(|v| !v.end.survived())
        {
            let mut lines = banner::Lines::verdict(v, None);
            if tumbled {
                lines.note = Some(FALL_NOTE.to_owned());
            }
            let fitted = banner::fit(ui, rect.width() - 20.0, &lines);
            let plate = egui::Rect::from_min_size(
                rect.min + egui::vec2(10.0, 10.0),
                egui::vec2(rect.width() - 20.0, fitted.height),
            );
            let (text, last) = banner::show(ui, plate, &fitted);
            self.frame_layout.banner = Some(BannerRects { plate, text });
            if tumbled {
                self.frame_layout.caption = Some(last);
            }
        }
        ui.allocate_rect(full, egui::Sense::hover());
        if std::env::var_os("LAYOUT_DEBUG").is_some() {
            eprintln!("central end {:?} max {:?}", ui.min_rect(), ui.max_rect());
        }
    }
}
