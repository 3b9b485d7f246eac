//! The Poincaré plot: the section points accumulated as a density, the
//! latest ones marked, and the choice of section.

use egui::Color32;
use egui_plot::{Plot, PlotBounds, PlotImage, PlotPoint, Points};

use crate::gui::history::{DensityGrid, RunHistory};
use crate::gui::panels::axes;
use crate::gui::units::Scales;

/// Which Poincaré section the plot shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SectionKind {
    /// Stroboscopic: (Θ, Θ') once a forcing period, at forcing phase φ,
    /// τ_k = (2πk + φ)/Ω_h (the simulation thread takes these points).
    #[default]
    Stroboscopic,
    /// At impacts: (forcing phase at the impact, Θ' just before it), from
    /// the events the app keeps (Θ is 0 at every impact).
    Impact,
}

/// Poincaré plot state: which section, the density grid, its texture, and
/// whether the view follows the data.
pub struct PoincareView {
    /// Density grid of the section shown (work counter inside).
    pub grid: DensityGrid,
    texture: Option<egui::TextureHandle>,
    /// Fit the view to the points each frame until the user pans or zooms.
    pub auto_fit: bool,
    /// The section shown.
    pub section: SectionKind,
    /// The stroboscopic section's forcing phase φ, rad, as the user set it.
    pub phase: f64,
    /// The section the grid was binned for (a switch rebins).
    binned_for: SectionKind,
}

impl Default for PoincareView {
    fn default() -> Self {
        Self {
            grid: DensityGrid::default(),
            texture: None,
            auto_fit: true,
            section: SectionKind::default(),
            // τ_k = 2πk/Ω_h: the paper's section.
            phase: 0.0,
            binned_for: SectionKind::default(),
        }
    }
}

impl PoincareView {
    /// Forget the view (new run).
    pub fn reset(&mut self) {
        self.auto_fit = true;
    }

    /// How many points the grid has binned from the section shown (all of
    /// them once it is up to date, in view or not).
    pub fn plotted(&self) -> usize {
        self.grid.binned()
    }

    /// Shows `section` from now on: refits the view and rebins from the
    /// points kept (the grid keeps its work counter).
    pub fn switch(&mut self, section: SectionKind) {
        self.section = section;
        if self.binned_for != section {
            self.binned_for = section;
            self.grid.forget();
            self.auto_fit = true;
        }
    }
}

/// The section selector above the plot: stroboscopic (with its phase) or
/// at impacts. Returns a new phase if the user changed it.
fn section_selector(ui: &mut egui::Ui, view: &mut PoincareView) -> Option<f64> {
    let mut chosen = view.section;
    let mut new_phase = None;
    ui.horizontal_wrapped(|ui| {
        // "Section" before the two choices where all three fit on a row; a
        // narrow column keeps the row for the plot (the hovers say what
        // each choice is).
        let word = |ui: &egui::Ui, t: &str| {
            egui::WidgetText::from(t)
                .into_galley(ui, Some(egui::TextWrapMode::Extend), f32::INFINITY, egui::TextStyle::Body)
                .size()
                .x
        };
        let pad = 2.0 * ui.spacing().button_padding.x + ui.spacing().item_spacing.x;
        let row = word(ui, "Section") + word(ui, "stroboscopic") + word(ui, "at impacts") + 3.0 * pad;
        if ui.available_width() >= row {
            ui.label("Section");
        }
        ui.selectable_value(&mut chosen, SectionKind::Stroboscopic, "stroboscopic")
            .on_hover_text("(Θ, Θ') once a forcing period, at τ_k = (2πk + φ)/Ω_h");
        ui.selectable_value(&mut chosen, SectionKind::Impact, "at impacts")
            .on_hover_text("Θ' just before each impact against the forcing phase Ω_h τ mod 2π at that impact (Θ is 0 at every impact)");
        if chosen == SectionKind::Stroboscopic {
            ui.spacing_mut().slider_width = 90.0;
            // The slider and its number are one widget laid out in a row of
            // its own, which cannot wrap: start a new row unless φ, the
            // slider and "6.28 rad" all fit (else the row grows past the
            // panel, which then grows past the window).
            let number = 5.0 * egui::TextStyle::Body.resolve(ui.style()).size;
            if ui.available_size_before_wrap().x < ui.spacing().slider_width + number + 24.0 {
                ui.end_row();
            }
            let pl = ui.label("φ");
            let mut phase = view.phase;
            let r = ui
                .add(
                    egui::Slider::new(&mut phase, 0.0..=std::f64::consts::TAU)
                        .suffix(" rad")
                        .max_decimals(2),
                )
                .labelled_by(pl.id)
                .on_hover_text("Forcing phase of the section, τ_k = (2πk + φ)/Ω_h: changing it keeps the motion going and starts the section's points over");
            if r.changed() && phase != view.phase {
                view.phase = phase;
                new_phase = Some(phase);
            }
        }
    });
    view.switch(chosen);
    // What the points are, in words: the plot's axis titles are painted
    // small, and this line is what a screen reader (and a test) reads.
    let caption = match view.section {
        SectionKind::Stroboscopic => format!(
            "(Θ, Θ') once a forcing period, at Ω_h τ = 2πk + {:.2}; the latest {LATEST_SECTION_POINTS} enlarged",
            view.phase
        ),
        SectionKind::Impact => format!(
            "Θ' just before each impact, against the forcing phase at that impact; the latest {LATEST_SECTION_POINTS} enlarged"
        ),
    };
    // One line, cut with "…" when narrow (the hover has it whole), so the
    // plot below keeps its height at a large presentation scale.
    ui.add(egui::Label::new(egui::RichText::new(&caption).weak()).truncate())
        .on_hover_text(caption);
    new_phase
}

/// How many of the latest section points are drawn enlarged: 16 shows
/// every dot of a period-8 orbit (the end of the paper's Fig. 4 cascade)
/// twice over.
pub(crate) const LATEST_SECTION_POINTS: usize = 16;

/// Draws the section selector and the Poincaré points of the section
/// chosen as a per-pixel density image, in the units of `scales` (both are
/// linear in Θ and Θ', so the points are binned in the model's units over
/// the view converted back; the impact section's phase is in rad in both).
/// Returns the stroboscopic phase the user asked for, if they changed it:
/// the caller sends it to the simulation thread.
pub(crate) fn poincare_plot(
    ui: &mut egui::Ui,
    hist: &RunHistory,
    view: &mut PoincareView,
    scales: &Scales,
) -> Option<f64> {
    let new_phase = section_selector(ui, view);
    let impact = view.section == SectionKind::Impact;
    let store = if impact { &hist.impact_section } else { &hist.section };
    // Converts a point of the section, in the model's units, to the units shown.
    let to_shown = |x: f64, y: f64| -> (f64, f64) {
        if impact {
            (x, scales.theta_dot(y))
        } else {
            (scales.theta(x), scales.theta_dot(y))
        }
    };
    let to_model = |x: f64, y: f64| -> (f64, f64) {
        let (theta, theta_dot) = scales.state_of(x, y);
        if impact { (x, theta_dot) } else { (theta, theta_dot) }
    };
    let bbox = store.bbox().map(|b| {
        let (x0, y0) = to_shown(b[0], b[2]);
        let (x1, y1) = to_shown(b[1], b[3]);
        [x0.min(x1), x0.max(x1), y0.min(y1), y0.max(y1)]
    });
    let (x_label, y_label) = if impact {
        (
            "Ω_h τ mod 2π at impact [rad]".to_string(),
            format!("{} before impact", scales.theta_dot_label()),
        )
    } else {
        let at = if view.phase == 0.0 {
            "at τ_k = 2πk/Ω_h".to_string()
        } else {
            format!("at τ_k = (2πk + {:.2})/Ω_h", view.phase)
        };
        (
            format!("{} {at}", scales.theta_label()),
            format!("{} {at}", scales.theta_dot_label()),
        )
    };
    let ppp = ui.ctx().pixels_per_point();
    let auto_fit = view.auto_fit;
    let PoincareView { grid, texture, .. } = view;
    let resp = axes::titled(axes::readable(Plot::new("poincare")), ui, &x_label, &y_label)
        .auto_bounds(false)
        .allow_double_click_reset(false)
        .show(ui, |plot_ui| {
            if auto_fit && let Some(b) = bbox {
                // Widened to whole numbered steps, so even a period-one
                // orbit's near-coincident points on a short axis get two
                // numbers on each axis.
                let size = plot_ui.transform().frame().size();
                let (min_gap, floor) = axes::gaps(&plot_ui.ctx().global_style());
                let (x0, x1) = axes::nice_bounds(b[0], b[1], f64::from(size.x), min_gap[0], floor[0], 0.04);
                let (y0, y1) = axes::nice_bounds(b[2], b[3], f64::from(size.y), min_gap[1], floor[1], 0.04);
                plot_ui.set_plot_bounds(PlotBounds::from_min_max([x0, y0], [x1, y1]));
            }
            let bounds = plot_ui.plot_bounds();
            let frame = *plot_ui.transform().frame();
            // One cell per 2×2 physical pixels: a lone point stays visible.
            // Never more than the GPU's largest texture (a tall panel at a
            // large presentation scale would ask for more, and egui panics).
            let max_side = plot_ui.ctx().input(|i| i.max_texture_side).max(1) as f32;
            let size = [
                (frame.width() * ppp * 0.5).round().clamp(1.0, max_side) as usize,
                (frame.height() * ppp * 0.5).round().clamp(1.0, max_side) as usize,
            ];
            let shown = [bounds.min()[0], bounds.max()[0], bounds.min()[1], bounds.max()[1]];
            let (lo, hi) = (to_model(shown[0], shown[2]), to_model(shown[1], shown[3]));
            let v = [lo.0, hi.0, lo.1, hi.1];
            let changed = grid.update(store, v, size);
            if changed || texture.is_none() {
                let image = grid.to_image(Color32::from_rgb(120, 175, 255), Color32::from_rgb(255, 235, 120));
                match texture {
                    Some(t) => t.set(image, egui::TextureOptions::NEAREST),
                    None => {
                        *texture = Some(plot_ui.ctx().load_texture(
                            "poincare density",
                            image,
                            egui::TextureOptions::NEAREST,
                        ))
                    }
                }
            }
            if let Some(t) = texture.as_ref()
                && grid.view == v
            {
                plot_ui.add(
                    PlotImage::new(
                        "section",
                        t.id(),
                        PlotPoint::new(0.5 * (shown[0] + shown[1]), 0.5 * (shown[2] + shown[3])),
                        egui::vec2((shown[1] - shown[0]) as f32, (shown[3] - shown[2]) as f32),
                    )
                    .allow_hover(false),
                );
            }
            // Where the motion is now: the latest points enlarged, so a
            // period-k orbit shows k large dots that a lecture hall can
            // see (the density image's cells are two pixels) and a
            // dragged parameter's new orbit stands out from its transient.
            let latest: Vec<[f64; 2]> = store
                .points()
                .iter()
                .rev()
                .take(LATEST_SECTION_POINTS)
                .map(|p| {
                    let (x, y) = to_shown(p[0], p[1]);
                    [x, y]
                })
                .collect();
            if !latest.is_empty() {
                plot_ui.points(
                    Points::new("latest", latest)
                        .radius(3.5)
                        .color(Color32::from_rgb(255, 150, 60))
                        .allow_hover(false),
                );
            }
        });
    axes::record(ui, "poincare", &resp.transform);
    let r = &resp.response;
    if r.dragged() || (r.hovered() && ui.input(|i| i.smooth_scroll_delta != egui::Vec2::ZERO || i.zoom_delta() != 1.0))
    {
        view.auto_fit = false;
    }
    if r.double_clicked() {
        view.auto_fit = true;
    }
    new_phase
}
