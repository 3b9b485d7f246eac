//! The plots: phase portrait Θ–Θ' with a fading trail (and a trail per
//! ghost copy, in the ghost's scene colour), the accumulating Poincaré
//! points, and the time history in a moving window.
//!
//! Each plot draws from the app's [`RunHistory`] decimated to screen
//! resolution (see [`crate::gui::history`]); a hidden plot is not called and
//! does no work. Values are shown in the units of a [`Scales`]
//! (normalised or physical), whose axis titles name them.

use crate::gui::panels::axes;
use egui::Color32;
use egui_plot::{Line, Plot, PlotBounds, PlotImage, PlotPoint, PlotPoints, Points};

use crate::gui::history::{DensityGrid, RunHistory, decimate_min_max};
use crate::gui::panels::scene;
use crate::gui::units::Scales;
use crate::model::Mode;

/// Phase portrait settings.
#[derive(Clone, Debug)]
pub struct PhaseView {
    /// Length of the trail, τ.
    pub trail_tau: f64,
    /// Points built for the trail over the app's life (work counter).
    pub work: u64,
    /// The block's trail drawn last frame, (Θ, Θ') in the units shown.
    pub drawn: Vec<[f64; 2]>,
    /// Colour and number of points of each ghost's trail drawn last
    /// frame, by ghost index.
    pub ghosts_drawn: Vec<(Color32, usize)>,
    /// Once the run has ended: the τ the trail ends at from then on (see
    /// [`PhaseView::hold`]).
    pub held: Option<f64>,
}

impl Default for PhaseView {
    fn default() -> Self {
        // 20 τ: about 25 forcing cycles at Ω = 8, enough to see an attractor
        // take shape without hiding the current motion.
        Self {
            trail_tau: 20.0,
            work: 0,
            drawn: Vec::new(),
            ghosts_drawn: Vec::new(),
            held: None,
        }
    }
}

impl PhaseView {
    /// The trail for a new run: a record's whole length (`record_tau`, τ),
    /// so the portrait of an earthquake shows all of it, else the default.
    pub(crate) fn fit_run(&mut self, record_tau: Option<f64>) {
        self.trail_tau = record_tau.map_or(Self::default().trail_tau, |tau| tau.max(1.0));
        self.held = None;
    }

    /// The run has ended (rest, tumble or failure): from now on the trail
    /// ends where the block last moved and no longer fades. A run at rest
    /// keeps going at the origin until it ends, which would push the
    /// motion that led there (free rocking's spiral) out of the trail.
    pub fn hold(&mut self, hist: &RunHistory) {
        let moving = hist.samples.iter().rev().find(|s| s.mode != Mode::Rest);
        self.held = moving.or(hist.samples.last()).map(|s| s.tau);
    }
}

/// Length of each ghost's trail, τ: a short tail (a little over one
/// forcing period at Ω_h = 8) behind each ghost's dot. Twenty full-length
/// trails retrace the same attractor as the block's and merge into one
/// blur; short tails show the ghosts as a cloud spreading over it.
pub(crate) const GHOST_TAIL_TAU: f64 = 1.0;

/// Largest τ between two points of a ghost's tail that are joined. One
/// point arrives per frame: 0.03 τ apart at 1× on the default block, 0.16
/// at 5×; a line over a longer gap would cut across the attractor where
/// the ghost never went, so faster playback draws shorter tails, down to
/// the dot alone.
const GHOST_TAIL_GAP: f64 = 0.25;

/// Trail segments of decreasing age, drawn with increasing opacity.
const TRAIL_SEGMENTS: usize = 10;

/// How far back an ended run's trail reaches at least, τ: the whole of
/// free rocking's release-to-rest (21 τ) and the last few dozen forcing
/// periods before a tumble.
const HELD_TRAIL_TAU: f64 = 60.0;

/// Most trail points drawn: the trail is thinned to this.
const TRAIL_POINTS: usize = 2400;

/// Draws the phase portrait in the units of `scales`. Returns the (Θ, Θ')
/// the user clicked (in the model's units), if any.
pub(crate) fn phase_plot(
    ui: &mut egui::Ui,
    hist: &RunHistory,
    view: &mut PhaseView,
    now: f64,
    scales: &Scales,
) -> Option<(f64, f64)> {
    let now = view.held.map_or(now, |held| held.min(now));
    // An ended run's trail no longer fades, and reaches back at least
    // HELD_TRAIL_TAU: free rocking's whole spiral, from the release to rest.
    let t0 = match view.held {
        Some(_) => now - view.trail_tau.max(HELD_TRAIL_TAU),
        None => now - view.trail_tau,
    };
    let end = hist.samples.len() - hist.samples.iter().rev().take_while(|s| s.tau > now).count();
    let start = end - hist.samples.iter().take(end).rev().take_while(|s| s.tau >= t0).count();
    let recent: Vec<[f64; 2]> = {
        let n = end - start;
        let stride = n.div_ceil(TRAIL_POINTS).max(1);
        let mut v: Vec<[f64; 2]> = hist
            .samples
            .iter()
            .skip(start)
            .take(end - start)
            .step_by(stride)
            .map(|s| [scales.theta(s.theta), scales.theta_dot(s.theta_dot)])
            .collect();
        if let Some(last) = end.checked_sub(1).and_then(|i| hist.samples.iter().nth(i))
            && stride > 1
        {
            v.push([scales.theta(last.theta), scales.theta_dot(last.theta_dot)]);
        }
        v
    };
    view.work += recent.len() as u64;
    view.drawn.clone_from(&recent);
    let ghosts = ghost_trails(hist, now, scales);
    view.ghosts_drawn = ghosts.iter().map(|(c, pts)| (*c, pts.len())).collect();
    let tip = scales.tip_angle();
    let resp = axes::titled(
        axes::readable(Plot::new("phase")),
        ui,
        scales.theta_label(),
        scales.theta_dot_label(),
    )
    .include_x(-tip)
    .include_x(tip)
    .include_y(0.0)
    .allow_double_click_reset(true)
    .show(ui, |plot_ui| {
        let n = recent.len();
        if n >= 2 {
            let per = n.div_ceil(TRAIL_SEGMENTS);
            for (i, chunk_start) in (0..n).step_by(per).enumerate() {
                let end = (chunk_start + per + 1).min(n);
                let alpha = if view.held.is_some() {
                    0.9
                } else {
                    0.12 + 0.88 * (i as f32 + 1.0) / TRAIL_SEGMENTS as f32
                };
                plot_ui.line(
                    Line::new("", PlotPoints::new(recent[chunk_start..end].to_vec()))
                        .color(Color32::from_rgb(110, 170, 255).gamma_multiply(alpha))
                        .width(1.5)
                        .allow_hover(false),
                );
            }
        }
        // The ghosts over the block's trail, as in the scene: while they
        // follow the block they draw over its trail, and as they separate
        // each tail moves on its own over the attractor.
        for (colour, points) in ghosts {
            let Some(last) = points.last().copied() else {
                continue;
            };
            plot_ui.line(
                Line::new("", PlotPoints::new(points))
                    .color(colour.gamma_multiply(0.85))
                    .width(1.5)
                    .allow_hover(false),
            );
            plot_ui.points(Points::new("", vec![last]).radius(3.5).color(colour));
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
    axes::record(ui, "phase", &resp.transform);
    if resp.response.clicked() {
        resp.inner.map(|p| scales.state_of(p.x, p.y))
    } else {
        None
    }
}

/// Each ghost's tail up to `now`: its last [`GHOST_TAIL_TAU`], back to the
/// first gap over [`GHOST_TAIL_GAP`], in the units of `scales`, with its
/// colour in the scene.
fn ghost_trails(hist: &RunHistory, now: f64, scales: &Scales) -> Vec<(Color32, Vec<[f64; 2]>)> {
    let trails = &hist.ghost_trails;
    let n = trails.len();
    (0..n)
        .map(|k| {
            let mut newer = f64::INFINITY;
            let mut points: Vec<[f64; 2]> = trails
                .trail(k)
                .rev()
                .skip_while(|p| p.tau > now)
                .take_while(|p| {
                    // The newest point always (the ghost's dot).
                    let keep =
                        newer == f64::INFINITY || (newer - p.tau <= GHOST_TAIL_GAP && p.tau >= now - GHOST_TAIL_TAU);
                    newer = p.tau;
                    keep
                })
                .map(|p| [scales.theta(p.theta), scales.theta_dot(p.theta_dot)])
                .collect();
            points.reverse();
            (scene::ghost_color(k, n), points)
        })
        .collect()
}

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

/// Samples of the last stretch of Θ the spectrum is taken from: 2¹³ at the
/// live spacing of 0.005 τ is 41 τ, about 52 forcing periods at Ω = 8, a
/// resolution Δω = 2π/41 ≈ 0.15 p.
pub(crate) const SPECTRUM_SAMPLES: usize = 1 << 13;

/// Power-spectrum plot state: the last spectrum, recomputed at most every
/// [`SpectrumView::EVERY_TAU`] of playback.
#[derive(Clone, Debug, Default)]
pub(crate) struct SpectrumView {
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
    pub(crate) const EVERY_TAU: f64 = 1.0;

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
/// the forcing frequency Ω_h marked; frequencies in the units of `scales`
/// (Hz or ω/p).
pub(crate) fn spectrum_plot(
    ui: &mut egui::Ui,
    hist: &RunHistory,
    view: &mut SpectrumView,
    sample_dt: f64,
    omega_h: f64,
    scales: &Scales,
) {
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
    let pts: Vec<[f64; 2]> = view.points.iter().map(|p| [scales.frequency(p[0]), p[1]]).collect();
    let resp = axes::titled(
        axes::readable(Plot::new("spectrum")),
        ui,
        scales.frequency_label(),
        "log10 S/S_max",
    )
    .include_y(0.0)
    .include_y(-8.0)
    .show(ui, |plot_ui| {
        plot_ui.line(
            Line::new("S(ω)", PlotPoints::new(pts))
                .color(Color32::from_rgb(110, 170, 255))
                .width(1.2),
        );
        plot_ui.vline(
            egui_plot::VLine::new("Ω_h", scales.frequency(omega_h))
                .color(Color32::from_rgb(240, 150, 50).gamma_multiply(0.7))
                .width(1.0),
        );
    });
    axes::record(ui, "spectrum", &resp.transform);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Sign;
    use crate::sim::protocol::Sample;

    fn history(modes: &[(f64, Mode)]) -> RunHistory {
        let mut hist = RunHistory::default();
        for &(tau, mode) in modes {
            hist.push_sample(Sample::flat(tau, mode, 0.0));
        }
        hist
    }

    #[test]
    fn an_ended_run_holds_its_trail_where_the_block_last_moved() {
        let rock = Mode::Rock { pivot: Sign::Pos };
        let mut view = PhaseView::default();
        // Rest: held at the last motion, not at the run's end.
        view.hold(&history(&[
            (0.0, rock),
            (21.0, rock),
            (22.0, Mode::Rest),
            (60.0, Mode::Rest),
        ]));
        assert_eq!(view.held, Some(21.0));
        // Tumble or failure: held at the last sample.
        view.hold(&history(&[(0.0, rock), (5.0, Mode::Tumbled)]));
        assert_eq!(view.held, Some(5.0));
        view.hold(&history(&[(0.0, rock), (3.0, rock)]));
        assert_eq!(view.held, Some(3.0));
        // A block that never moved: its only state.
        view.hold(&history(&[(0.0, Mode::Rest), (1.0, Mode::Rest)]));
        assert_eq!(view.held, Some(1.0));
        // A new run lets the trail move again.
        view.fit_run(None);
        assert_eq!(view.held, None);
    }
}
