//! The time history in a moving window: Θ (and X, a_h, a_v when asked)
//! against τ, coloured by mode.

use egui::Color32;
use egui_plot::{Line, Plot, PlotPoint, PlotPoints};

use crate::gui::history::{RunHistory, decimate_min_max};
use crate::gui::panels::axes;
use crate::gui::units::Scales;

/// Time-history settings.
#[derive(Clone, Debug)]
pub(crate) struct HistoryView {
    /// Window length, τ.
    pub window: f64,
    /// Also draw X.
    pub show_x: bool,
    /// Also draw a_h/g.
    pub show_a_h: bool,
    /// Also draw a_v/g.
    pub show_a_v: bool,
    /// Whether the user set the window (then a new scene keeps it).
    pub user_window: bool,
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
            user_window: false,
            scratch: Vec::new(),
            work: 0,
        }
    }
}

impl HistoryView {
    /// The window for a new run, unless the user chose one: the whole
    /// record (`record_tau`, τ, and 2 % more) so the response lines up with
    /// the ground trace beside it, else the default.
    pub(crate) fn fit_run(&mut self, record_tau: Option<f64>) {
        if self.user_window {
            return;
        }
        self.window = match record_tau {
            Some(tau) => (1.02 * tau).clamp(1.0, 500.0),
            None => Self::default().window,
        };
    }
}

/// One curve of the time history: legend name, shown, colour, and its
/// value in the units of the scales.
type Series = (
    &'static str,
    bool,
    Color32,
    fn(&Scales, &crate::sim::protocol::Sample) -> f64,
);

/// Draws the time history in the window ending at `now` (τ), in the units
/// of `scales`: the time axis in s or τ, θ in degrees or Θ, the sliding
/// displacement in cm or X per R; accelerations are per unit g in both.
/// Dashed lines mark ±α, the overturning angle of a block at rest.
pub(crate) fn history_plot(ui: &mut egui::Ui, hist: &RunHistory, view: &mut HistoryView, now: f64, scales: &Scales) {
    // Wrapped: one row would be wider than a narrow column and push the
    // plot beside it off its room.
    ui.horizontal_wrapped(|ui| {
        // The axes' units in words too: the plot's own titles are painted
        // small, and this line is also what a screen reader (and a test) reads.
        ui.label(egui::RichText::new(format!("{} against {}", scales.theta_label(), scales.time_label())).strong());
        ui.separator();
        ui.label("window");
        let mut shown = scales.time(view.window);
        let r = ui
            .add(
                egui::DragValue::new(&mut shown)
                    .range(scales.time(1.0)..=scales.time(500.0))
                    .suffix(scales.time_suffix())
                    .speed(scales.time(0.5))
                    .max_decimals(1),
            )
            .on_hover_text("Length of the moving window");
        if r.changed() {
            view.window = scales.tau_of(shown).clamp(1.0, 500.0);
            view.user_window = true;
        }
        ui.checkbox(&mut view.show_x, scales.horizontal_label());
        ui.checkbox(&mut view.show_a_h, "a_h [g]");
        ui.checkbox(&mut view.show_a_v, "a_v [g]");
    });
    // The window starts at τ = 0 until the run is longer than it, so a
    // young run fills it from the left instead of hiding behind empty time.
    let t0 = (now - view.window).max(0.0);
    let t1 = t0 + view.window;
    let columns = (ui.available_width() * ui.ctx().pixels_per_point()).max(16.0) as usize;
    let series: [Series; 4] = [
        (scales.theta_label(), true, Color32::from_rgb(110, 170, 255), |c, s| {
            c.theta(s.theta)
        }),
        (
            scales.horizontal_label(),
            view.show_x,
            Color32::from_rgb(90, 200, 120),
            |c, s| c.horizontal(s.theta, s.x),
        ),
        ("a_h [g]", view.show_a_h, Color32::from_rgb(240, 150, 50), |_, s| s.a_h),
        ("a_v [g]", view.show_a_v, Color32::from_rgb(200, 100, 220), |_, s| s.a_v),
    ];
    let mut lines = Vec::new();
    for (name, on, color, f) in series {
        if !on {
            continue;
        }
        decimate_min_max(
            hist.samples.iter().map(|s| (scales.time(s.tau), f(scales, s))),
            scales.time(t0),
            scales.time(t1),
            columns,
            &mut view.scratch,
        );
        view.work += view.scratch.len() as u64;
        lines.push((name, color, view.scratch.clone()));
    }
    let tip = scales.tip_angle();
    let resp = axes::titled(
        axes::readable(Plot::new("history")),
        ui,
        scales.time_label(),
        scales.theta_label(),
    )
    .legend(egui_plot::Legend::default())
    .auto_bounds([false, true])
    .include_y(-tip)
    .include_y(tip)
    .allow_drag([false, true])
    .allow_zoom([false, true])
    .allow_scroll([false, true])
    .show(ui, |plot_ui| {
        plot_ui.set_plot_bounds_x(scales.time(t0)..=scales.time(t1));
        for y in [-tip, tip] {
            plot_ui.hline(
                egui_plot::HLine::new("±α", y)
                    .color(Color32::from_rgb(230, 80, 80).gamma_multiply(0.6))
                    .style(egui_plot::LineStyle::dashed_loose())
                    .allow_hover(false),
            );
        }
        for (name, color, pts) in lines {
            plot_ui.line(Line::new(name, PlotPoints::Owned(pts)).color(color).width(1.2));
        }
    });
    axes::record(ui, "history", &resp.transform);
}
