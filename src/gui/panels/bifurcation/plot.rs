//! The bifurcation diagram drawn: points by class, legend, current-value marker.

use egui::Color32;
use egui_plot::{Legend, Plot, PlotBounds, PlotPoint, PlotPoints, Points, Polygon, Text, VLine};

use super::{BifurcationView, current_value, short_name};
use crate::analysis::classify::Response;
use crate::gui::panels::axes;
use crate::sim::Scenario;

/// The marker's value: four significant digits, as the sliders apply them.
fn marker_text(v: f64) -> String {
    crate::gui::panels::slider::slider_text(v)
}

/// Where the marker's label sits against its line: to the right of it in
/// the left half of the range, to the left in the right half, so it stays
/// inside the plot.
fn marker_anchor(v: f64, from: f64, to: f64) -> egui::Align2 {
    if v <= 0.5 * (from + to) {
        egui::Align2::LEFT_BOTTOM
    } else {
        egui::Align2::RIGHT_BOTTOM
    }
}

/// Colour of a response class in the diagram.
fn class_color(r: Response) -> Color32 {
    match r {
        Response::Periodic { .. } => Color32::from_rgb(110, 170, 255),
        Response::Quasiperiodic => Color32::from_rgb(120, 220, 140),
        Response::Chaotic => Color32::from_rgb(255, 170, 80),
        Response::Rest | Response::Tumbled | Response::Flight => Color32::from_gray(170),
    }
}

/// Legend names, in drawing order.
const CLASSES: [&str; 4] = ["periodic", "quasiperiodic", "chaotic", "rest"];

fn class_slot(r: Response) -> usize {
    match r {
        Response::Periodic { .. } => 0,
        Response::Quasiperiodic => 1,
        Response::Chaotic => 2,
        Response::Rest | Response::Tumbled | Response::Flight => 3,
    }
}

impl BifurcationView {
    /// The diagram: each value's section points coloured by class, the
    /// legend, and the scene's current value marked.
    pub(super) fn plot(&mut self, ui: &mut egui::Ui, cfg: &Scenario) {
        let current = current_value(cfg, &self.param);
        let param = self.param.as_str();
        let (from, to) = (self.from, self.to);
        let y_zoom = self.y_zoom;
        let columns = &self.columns;
        let drag_from = self.drag_from;
        let (lo, hi) = columns
            .iter()
            .flat_map(|c| c.thetas.iter())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            });
        let resp = axes::titled(
            axes::readable(Plot::new("bifurcation")),
            ui,
            self.param.as_str(),
            "Θ(τ_k)",
        )
        .legend(Legend::default())
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .allow_double_click_reset(false)
        .show(ui, |plot_ui| {
            let pad = 0.02 * (to - from);
            let [y0, y1] = y_zoom.unwrap_or(if lo <= hi {
                let d = (hi - lo).max(1e-3);
                [lo - 0.05 * d, hi + 0.05 * d]
            } else {
                [-1.0, 1.0]
            });
            plot_ui.set_plot_bounds(PlotBounds::from_min_max([from - pad, y0], [to + pad, y1]));
            let t = *plot_ui.transform();
            let rows = (t.frame().height() * plot_ui.ctx().pixels_per_point()).max(1.0) as f64;
            let mut by_class: [Vec<[f64; 2]>; 4] = Default::default();
            let mut pixels: Vec<i64> = Vec::new();
            for c in columns {
                pixels.clear();
                pixels.extend(
                    c.thetas
                        .iter()
                        .filter(|&&t| t >= y0 && t <= y1)
                        .map(|&t| ((t - y0) / (y1 - y0) * rows) as i64),
                );
                pixels.sort_unstable();
                pixels.dedup();
                let slot = &mut by_class[class_slot(c.response)];
                slot.extend(
                    pixels
                        .iter()
                        .map(|&p| [c.value, y0 + (p as f64 + 0.5) / rows * (y1 - y0)]),
                );
            }
            let mut drawn = 0;
            for (i, pts) in by_class.into_iter().enumerate() {
                if pts.is_empty() {
                    continue;
                }
                drawn += pts.len();
                let color = class_color(match i {
                    0 => Response::Periodic { period: 1 },
                    1 => Response::Quasiperiodic,
                    2 => Response::Chaotic,
                    _ => Response::Rest,
                });
                plot_ui.points(
                    Points::new(CLASSES[i], PlotPoints::new(pts))
                        .radius(1.0)
                        .color(color)
                        .allow_hover(false),
                );
            }
            if let Some(v) = current {
                let marker = Color32::from_rgb(255, 230, 60);
                plot_ui.vline(VLine::new("current run", v).color(marker).width(1.5));
                // Labelled at the foot of the line, inside the plot (the
                // legend holds the top corner); unnamed, so that the
                // legend lists the line once.
                plot_ui.text(
                    Text::new(
                        "",
                        PlotPoint::new(v, y0 + 0.02 * (y1 - y0)),
                        egui::RichText::new(format!(" current run: {} = {} ", short_name(param), marker_text(v)))
                            .size(14.0)
                            .color(marker)
                            .background_color(Color32::from_black_alpha(180)),
                    )
                    .anchor(marker_anchor(v, from, to))
                    .allow_hover(false),
                );
            }
            let pointer = plot_ui.pointer_coordinate();
            if let (Some(a), Some(b)) = (drag_from, pointer) {
                let rect = vec![[a.x, a.y], [b.x, a.y], [b.x, b.y], [a.x, b.y]];
                plot_ui.polygon(
                    Polygon::new("zoom", PlotPoints::new(rect))
                        .fill_color(Color32::from_rgba_unmultiplied(255, 255, 255, 24))
                        .stroke(egui::Stroke::new(1.0, Color32::WHITE))
                        .allow_hover(false),
                );
            }
            (drawn, pointer)
        });
        let (drawn, pointer) = resp.inner;
        self.drawn = drawn;
        let r = &resp.response;
        if r.drag_started() {
            self.drag_from = pointer;
        }
        if r.drag_stopped() {
            if let (Some(a), Some(b)) = (self.drag_from.take(), pointer) {
                self.zoom(a, b);
            }
        } else if self.drag_from.is_some() && !r.dragged() {
            self.drag_from = None;
        }
        if r.double_clicked() {
            self.full_range(cfg);
        }
    }
}
