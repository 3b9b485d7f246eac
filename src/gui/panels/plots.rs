//! The plots: phase portrait Θ–Θ' with a fading trail, the accumulating
//! Poincaré points, and the time history in a moving window.
//!
//! Each plot draws from the app's [`RunHistory`] decimated to screen
//! resolution (see [`crate::gui::history`]); a hidden plot is not called and
//! does no work.

use egui::Color32;
use egui_plot::{Line, Plot, PlotBounds, PlotImage, PlotPoint, PlotPoints, Points};

use crate::gui::history::{DensityGrid, RunHistory, decimate_min_max};

/// Phase portrait settings.
#[derive(Clone, Debug)]
pub struct PhaseView {
    /// Length of the trail, τ.
    pub trail_tau: f64,
    /// Points built for the trail over the app's life (work counter).
    pub work: u64,
}

impl Default for PhaseView {
    fn default() -> Self {
        // 20 τ: about 25 forcing cycles at Ω = 8, enough to see an attractor
        // take shape without hiding the current motion.
        Self {
            trail_tau: 20.0,
            work: 0,
        }
    }
}

/// Trail segments of decreasing age, drawn with increasing opacity.
const TRAIL_SEGMENTS: usize = 10;

/// Most trail points drawn: the trail is thinned to this.
const TRAIL_POINTS: usize = 2400;

/// Draws the phase portrait. Returns the (Θ, Θ') the user clicked, if any.
pub fn phase_plot(ui: &mut egui::Ui, hist: &RunHistory, view: &mut PhaseView, now: f64) -> Option<(f64, f64)> {
    let t0 = now - view.trail_tau;
    let start = hist.samples.len() - hist.samples.iter().rev().take_while(|s| s.tau >= t0).count();
    let recent: Vec<[f64; 2]> = {
        let n = hist.samples.len() - start;
        let stride = n.div_ceil(TRAIL_POINTS).max(1);
        let mut v: Vec<[f64; 2]> = hist
            .samples
            .iter()
            .skip(start)
            .step_by(stride)
            .map(|s| [s.theta, s.theta_dot])
            .collect();
        if let Some(last) = hist.samples.last()
            && stride > 1
        {
            v.push([last.theta, last.theta_dot]);
        }
        v
    };
    view.work += recent.len() as u64;
    let resp = Plot::new("phase")
        .x_axis_label("Θ")
        .y_axis_label("Θ'")
        .include_x(-1.0)
        .include_x(1.0)
        .include_y(0.0)
        .allow_double_click_reset(true)
        .show(ui, |plot_ui| {
            let n = recent.len();
            if n >= 2 {
                let per = n.div_ceil(TRAIL_SEGMENTS);
                for (i, chunk_start) in (0..n).step_by(per).enumerate() {
                    let end = (chunk_start + per + 1).min(n);
                    let alpha = 0.12 + 0.88 * (i as f32 + 1.0) / TRAIL_SEGMENTS as f32;
                    plot_ui.line(
                        Line::new("", PlotPoints::new(recent[chunk_start..end].to_vec()))
                            .color(Color32::from_rgb(110, 170, 255).gamma_multiply(alpha))
                            .width(1.5)
                            .allow_hover(false),
                    );
                }
            }
            if let Some(last) = recent.last() {
                plot_ui.points(
                    Points::new("now", vec![*last])
                        .radius(4.0)
                        .color(Color32::from_rgb(255, 230, 60)),
                );
            }
            plot_ui.pointer_coordinate()
        });
    if resp.response.clicked() {
        resp.inner.map(|p| (p.x, p.y))
    } else {
        None
    }
}

/// Poincaré plot state: the density grid, its texture, and whether the view
/// follows the data.
pub struct PoincareView {
    /// Density grid (work counter inside).
    pub grid: DensityGrid,
    texture: Option<egui::TextureHandle>,
    /// Fit the view to the points each frame until the user pans or zooms.
    pub auto_fit: bool,
}

impl Default for PoincareView {
    fn default() -> Self {
        Self {
            grid: DensityGrid::default(),
            texture: None,
            auto_fit: true,
        }
    }
}

impl PoincareView {
    /// Forget the view (new run).
    pub fn reset(&mut self) {
        self.auto_fit = true;
    }
}

/// Draws the Poincaré points as a per-pixel density image.
pub fn poincare_plot(ui: &mut egui::Ui, hist: &RunHistory, view: &mut PoincareView) {
    let bbox = hist.section.bbox();
    let ppp = ui.ctx().pixels_per_point();
    let auto_fit = view.auto_fit;
    let PoincareView { grid, texture, .. } = view;
    let resp = Plot::new("poincare")
        .x_axis_label("Θ(τ_k)")
        .y_axis_label("Θ'(τ_k)")
        .auto_bounds(false)
        .allow_double_click_reset(false)
        .show(ui, |plot_ui| {
            if auto_fit && let Some(b) = bbox {
                let (dx, dy) = ((b[1] - b[0]).max(1e-3), (b[3] - b[2]).max(1e-3));
                plot_ui.set_plot_bounds(PlotBounds::from_min_max(
                    [b[0] - 0.06 * dx, b[2] - 0.06 * dy],
                    [b[1] + 0.06 * dx, b[3] + 0.06 * dy],
                ));
            }
            let bounds = plot_ui.plot_bounds();
            let frame = *plot_ui.transform().frame();
            // One cell per 2×2 physical pixels: a lone point stays visible.
            let size = [
                (frame.width() * ppp * 0.5).round().max(1.0) as usize,
                (frame.height() * ppp * 0.5).round().max(1.0) as usize,
            ];
            let v = [bounds.min()[0], bounds.max()[0], bounds.min()[1], bounds.max()[1]];
            let changed = grid.update(&hist.section, v, size);
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
                        PlotPoint::new(0.5 * (v[0] + v[1]), 0.5 * (v[2] + v[3])),
                        egui::vec2((v[1] - v[0]) as f32, (v[3] - v[2]) as f32),
                    )
                    .allow_hover(false),
                );
            }
        });
    let r = &resp.response;
    if r.dragged() || (r.hovered() && ui.input(|i| i.smooth_scroll_delta != egui::Vec2::ZERO || i.zoom_delta() != 1.0))
    {
        view.auto_fit = false;
    }
    if r.double_clicked() {
        view.auto_fit = true;
    }
}

/// Time-history settings.
#[derive(Clone, Debug)]
pub struct HistoryView {
    /// Window length, τ.
    pub window: f64,
    /// Also draw X.
    pub show_x: bool,
    /// Also draw a_h/g.
    pub show_a_h: bool,
    /// Also draw a_v/g.
    pub show_a_v: bool,
    scratch: Vec<PlotPoint>,
    /// Points passed to the plot over the app's life (work counter).
    pub work: u64,
}

impl Default for HistoryView {
    fn default() -> Self {
        // 40 τ: about 50 forcing cycles at Ω = 8, as the paper's time
        // histories show.
        Self {
            window: 40.0,
            show_x: false,
            show_a_h: false,
            show_a_v: false,
            scratch: Vec::new(),
            work: 0,
        }
    }
}

/// One curve of the time history: name, shown, colour, and its value.
type Series = (&'static str, bool, Color32, fn(&crate::sim::protocol::Sample) -> f64);

/// Draws the time history in the window ending at `now`.
pub fn history_plot(ui: &mut egui::Ui, hist: &RunHistory, view: &mut HistoryView, now: f64) {
    ui.horizontal(|ui| {
        ui.label("window");
        ui.add(
            egui::DragValue::new(&mut view.window)
                .range(1.0..=500.0)
                .suffix(" τ")
                .speed(0.5),
        )
        .on_hover_text("Length of the moving window, τ");
        ui.checkbox(&mut view.show_x, "X");
        ui.checkbox(&mut view.show_a_h, "a_h/g");
        ui.checkbox(&mut view.show_a_v, "a_v/g");
    });
    let (t0, t1) = (now - view.window, now.max(now - view.window + 1e-9));
    let columns = (ui.available_width() * ui.ctx().pixels_per_point()).max(16.0) as usize;
    let series: [Series; 4] = [
        ("Θ", true, Color32::from_rgb(110, 170, 255), |s| s.theta),
        ("X", view.show_x, Color32::from_rgb(90, 200, 120), |s| s.x),
        ("a_h/g", view.show_a_h, Color32::from_rgb(240, 150, 50), |s| s.a_h),
        ("a_v/g", view.show_a_v, Color32::from_rgb(200, 100, 220), |s| s.a_v),
    ];
    let mut lines = Vec::new();
    for (name, on, color, f) in series {
        if !on {
            continue;
        }
        decimate_min_max(
            hist.samples.iter().map(|s| (s.tau, f(s))),
            t0,
            t1,
            columns,
            &mut view.scratch,
        );
        view.work += view.scratch.len() as u64;
        lines.push((name, color, view.scratch.clone()));
    }
    Plot::new("history")
        .x_axis_label("τ")
        .legend(egui_plot::Legend::default())
        .auto_bounds([false, true])
        .include_y(-1.0)
        .include_y(1.0)
        .allow_drag([false, true])
        .allow_zoom([false, true])
        .allow_scroll([false, true])
        .show(ui, |plot_ui| {
            plot_ui.set_plot_bounds_x(t0..=t1);
            for (name, color, pts) in lines {
                plot_ui.line(Line::new(name, PlotPoints::Owned(pts)).color(color).width(1.2));
            }
        });
}

/// Samples of the last stretch of Θ the spectrum is taken from: 2¹³ at the
/// live spacing of 0.005 τ is 41 τ, about 52 forcing periods at Ω = 8, a
/// resolution Δω = 2π/41 ≈ 0.15 p.
pub const SPECTRUM_SAMPLES: usize = 1 << 13;

/// Power-spectrum plot state: the last spectrum, recomputed at most every
/// [`SpectrumView::EVERY_TAU`] of playback.
#[derive(Clone, Debug, Default)]
pub struct SpectrumView {
    /// (ω in units of p, log₁₀ PSD) of the last spectrum.
    points: Vec<[f64; 2]>,
    /// τ of the last sample it was computed at.
    at: f64,
    /// Why there is none, if there is none.
    note: Option<String>,
    /// Spectra computed over the app's life (work counter).
    pub work: u64,
}

impl SpectrumView {
    /// Playback τ between recomputations: a spectrum of 41 τ changes little
    /// in 1 τ, and this keeps the FFT off most frames.
    pub const EVERY_TAU: f64 = 1.0;

    /// Forget (new run).
    pub fn reset(&mut self) {
        *self = Self {
            work: self.work,
            ..Self::default()
        };
    }
}

/// Draws the power spectrum of Θ over the last [`SPECTRUM_SAMPLES`]
/// samples, computed by [`crate::analysis::spectrum::power_spectrum`], with
/// the forcing frequency Ω_h marked.
pub fn spectrum_plot(ui: &mut egui::Ui, hist: &RunHistory, view: &mut SpectrumView, sample_dt: f64, omega_h: f64) {
    let last = hist.samples.last().map_or(0.0, |s| s.tau);
    if view.points.is_empty() || (last - view.at).abs() >= SpectrumView::EVERY_TAU {
        // Only a gap-free stretch on the sample grid is a valid FFT input.
        let n = hist.samples.len();
        let take = n.min(SPECTRUM_SAMPLES);
        let tail: Vec<(f64, f64)> = hist.samples.iter().skip(n - take).map(|s| (s.tau, s.theta)).collect();
        let start = tail
            .windows(2)
            .rposition(|w| ((w[1].0 - w[0].0) / sample_dt - 1.0).abs() > 1e-6)
            .map_or(0, |i| i + 1);
        let values: Vec<f64> = tail[start..].iter().map(|p| p.1).collect();
        view.at = last;
        match crate::analysis::spectrum::power_spectrum(&values, sample_dt, &Default::default()) {
            Ok(sp) => {
                let top = sp.psd.iter().copied().fold(0.0_f64, f64::max).max(f64::MIN_POSITIVE);
                view.points = sp
                    .omega()
                    .into_iter()
                    .zip(&sp.psd)
                    .skip(1)
                    .filter(|(w, _)| *w <= 4.0 * omega_h.max(1.0))
                    .map(|(w, s)| [w, (s / top).max(1e-16).log10()])
                    .collect();
                view.note = None;
                view.work += 1;
            }
            Err(e) => {
                view.points.clear();
                view.note = Some(e.to_string());
            }
        }
    }
    if let Some(note) = &view.note {
        ui.label(egui::RichText::new(note).weak());
    }
    let pts = view.points.clone();
    Plot::new("spectrum")
        .x_axis_label("ω / p")
        .y_axis_label("log10 S/S_max")
        .include_y(0.0)
        .include_y(-8.0)
        .show(ui, |plot_ui| {
            plot_ui.line(
                Line::new("S(ω)", PlotPoints::new(pts))
                    .color(Color32::from_rgb(110, 170, 255))
                    .width(1.2),
            );
            plot_ui.vline(
                egui_plot::VLine::new("Ω_h", omega_h)
                    .color(Color32::from_rgb(240, 150, 50).gamma_multiply(0.7))
                    .width(1.0),
            );
        });
}
