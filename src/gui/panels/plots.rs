//! The plots: phase portrait Θ–Θ' with a fading trail (and a trail per
//! ghost copy, in the ghost's scene colour), the accumulating Poincaré
//! points, and the time history in a moving window.
//!
//! Each plot draws from the app's [`RunHistory`] decimated to screen
//! resolution (see [`crate::gui::history`]); a hidden plot is not called and
//! does no work. Values are shown in the units of a [`Scales`]
//! (normalised or physical), whose axis titles name them.
//!
//! The phase portrait is drawn here; the Poincaré points in `poincare.rs`,
//! the time history in `history.rs` and the power spectrum in
//! `spectrum.rs`.

mod history;
mod poincare;
mod spectrum;

pub(crate) use history::{HistoryView, history_plot};
pub(crate) use poincare::poincare_plot;
pub use poincare::{PoincareView, SectionKind};
pub(crate) use spectrum::{SpectrumView, spectrum_plot};

use crate::gui::panels::axes;
use egui::Color32;
use egui_plot::{Line, Plot, PlotPoints, Points};

use crate::gui::history::RunHistory;
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
