//! The outcome-map view's widgets: the controls, the status line, the
//! legend and the map itself (one texture in a plot, with the scene's
//! crosshair; hover tells a cell's class and whether it was computed).

use crate::gui::panels::axes;
use egui::{Color32, TextureHandle};
use egui_plot::{HLine, Plot, PlotBounds, PlotImage, PlotPoint, VLine};

use super::slot::attractor_color;
use super::{AxisChoice, OutcomeMapView, RESOLUTIONS, Slot, current_value, default_range, keys};
use crate::analysis::map_refine::Source;
use crate::analysis::steady::Window;
use crate::gui::panels::bifurcation::{PAPER_WINDOW, SHORT_WINDOW};
use crate::plot::outcome_map::attractor_label;
use crate::sim::Scenario;

impl OutcomeMapView {
    fn axis_controls(ui: &mut egui::Ui, name: &str, axis: &mut AxisChoice, cfg: &Scenario) {
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(name);
            let mut chosen = None;
            egui::ComboBox::from_id_salt(("outcome map axis", name))
                .selected_text(&axis.key)
                .show_ui(ui, |ui| {
                    for k in keys(cfg) {
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
            ui.add(egui::DragValue::new(&mut axis.to).speed(0.01)).labelled_by(l.id);
        });
    }

    pub(super) fn controls(&mut self, ui: &mut egui::Ui, cfg: &Scenario) {
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
            // A stack starts at rest: it has no initial state to map.
            let basin = ui
                .add_enabled(cfg.stack.is_none(), egui::Button::new("Θ₀ × Θ'₀"))
                .on_hover_text("The basin of attraction: where each initial state ends up")
                .on_disabled_hover_text("A stack of blocks starts at rest on its base: it has no basin to map");
            if basin.clicked()
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
            if ui
                .button("Map")
                .on_hover_text("Compute the map over these axes")
                .clicked()
            {
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

    pub(super) fn status(&self, ui: &mut egui::Ui) {
        let red = Color32::from_rgb(235, 90, 90);
        if let Some(e) = &self.invalid {
            ui.colored_label(red, e);
            return;
        }
        let (computed, total) = self.computed();
        let (done, _) = self.progress();
        let share = if total > 0 {
            100.0 * computed as f64 / total as f64
        } else {
            0.0
        };
        let stopped = self.stopped_early();
        let line = if self.done {
            let took = self
                .took
                .map_or(String::new(), |t| format!(" in {:.1} s", t.as_secs_f64()));
            format!(
                "{n} × {n} cells{took}; {computed} computed ({share:.0} %, {stopped} stopped once their class was \
                 certain), the rest refined where classes meet",
                n = self.resolution
            )
        } else {
            let (stride, got, of) = self.level;
            format!("computing: {done} of {total} cells done; level {stride} cells per block, {got} / {of} computed")
        };
        ui.horizontal_wrapped(|ui| {
            ui.label(line).on_hover_text(
                "Computed coarse first, then refined where classes meet: a cell whose surroundings at the level above \
                 all have one class inherits it without being run (it counts as done). A cell's run stops as soon as \
                 its class is certain; chaotic and quasiperiodic cells run their whole window.",
            );
            if let Some((_, e)) = self.failed.first() {
                ui.colored_label(red, format!("{} failed, first: {e}", self.failed.len()));
            }
        });
    }

    /// The classes, and in a basin map its attractors instead of the
    /// periodic classes (their cells are coloured by attractor).
    pub(super) fn legend(&self, ui: &mut egui::Ui) {
        let swatch = |ui: &mut egui::Ui, color: Color32| {
            let (r, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
            ui.painter().rect_filled(r, 2.0, color);
        };
        ui.horizontal_wrapped(|ui| {
            for slot in Slot::ALL {
                let n = self.counts.iter().find(|(s, _)| *s == slot).map_or(0, |(_, n)| *n);
                if (slot == Slot::Failed && n == 0) || (self.basin && slot.is_periodic()) {
                    continue;
                }
                swatch(ui, slot.color());
                let text = egui::RichText::new(slot.name());
                ui.label(if n > 0 { text } else { text.weak() });
            }
        });
        // One attractor a line: its name is long, and wrapped it would
        // split from its swatch.
        for a in self.attractors().iter().filter(|_| self.basin) {
            let n = self
                .attractor_counts
                .iter()
                .find(|(id, _)| *id == a.id)
                .map_or(0, |(_, n)| *n);
            ui.horizontal(|ui| {
                swatch(ui, attractor_color(a.id));
                ui.label(attractor_label(a)).on_hover_text(format!(
                    "Periodic attractor {}: its cycle's section point with the largest Θ; {n} cells of the map reach it",
                    a.id
                ));
            });
        }
    }

    pub(super) fn plot(&mut self, ui: &mut egui::Ui, cfg: &Scenario) -> Option<[(String, f64); 2]> {
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
        let resp = axes::titled(
            axes::readable(Plot::new("outcome map")),
            ui,
            x.key.as_str(),
            y.key.as_str(),
        )
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
            // A dark line under the yellow one: the crosshair stays
            // visible over every class colour.
            for (color, width) in [(Color32::BLACK, 3.5), (mark, 1.5)] {
                if let Some(v) = current.0 {
                    plot_ui.vline(VLine::new("scene", v).color(color).width(width));
                }
                if let Some(v) = current.1 {
                    plot_ui.hline(HLine::new("scene", v).color(color).width(width));
                }
            }
            plot_ui.pointer_coordinate()
        });
        self.transform = Some(resp.transform);
        let hovered = resp.inner.and_then(index);
        let clicked = resp.response.clicked();
        if let Some((i, j)) = hovered {
            let attractor = self
                .label(i, j)
                .and_then(|l| l.attractor)
                .and_then(|id| self.attractors().iter().find(|a| a.id == id))
                .map_or(String::new(), |a| format!(", attractor {}", attractor_label(a)));
            let what = match self.cell(i, j) {
                Some((slot, source)) => match (source, self.response(i, j)) {
                    (Source::Computed, Some(Some(r))) => format!("{r}{attractor} (computed)"),
                    (Source::Computed, _) => format!("{}{attractor} (computed)", slot.name()),
                    (Source::Inherited | Source::Unknown, _) => {
                        format!("{}{attractor} (inherited: refined where classes meet)", slot.name())
                    }
                },
                None => match self.response(i, j) {
                    Some(Some(r)) => format!("{r} (computed)"),
                    Some(None) => "failed (computed)".to_string(),
                    None => "not yet computed".to_string(),
                },
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
