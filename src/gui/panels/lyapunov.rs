//! The largest Lyapunov exponent of the scene, estimated in the background
//! over ever longer windows and shown with its running (convergence) curve.
//!
//! Contract:
//! - The view does no analysis: a thread named `lyapunov` calls
//!   [`crate::analysis::lyapunov::of_scenario`] on the scene's
//!   configuration, from its initial state, by the method the body has
//!   ([`method_for`]: tangent dynamics with saltation matrices for the
//!   block and the frame, two trajectories for a stack), for windows ending
//!   at each of [`STAGES`] in turn, and sends each answer as it is done. Each stage is a fresh run from τ = 0, so every
//!   number shown is a complete, reproducible estimate; the latest one is
//!   the longest window.
//! - The stages stop at the first answer without a finite exponent
//!   (tumbling, rest, flat phases) or error: a longer window would say the
//!   same.
//! - The computation is a [`Job`] whose channel holds every stage, so it
//!   never waits on the view.
//! - A new scene cancels the old computation (checked between stages; the
//!   stage running finishes in the background and is discarded) and starts
//!   over. Hidden, the view does no work: the computation is cancelled and
//!   starts over when shown again.

use crate::gui::panels::axes;
use egui::Color32;
use egui_plot::{HLine, Line, Plot, PlotPoints};

use crate::analysis::lyapunov::{Lyapunov, LyapunovOptions, Method, method_for, of_scenario};
use crate::sim::Scenario;
use crate::sim::job::{Job, Link, Waker};

/// Discarded start of every window, τ. 200 τ (a third of the paper's 600)
/// keeps the first number quick; the longer stages dilute what remains of
/// a chaotic transient.
pub const TRANSIENT_TAU: f64 = 200.0;

/// Ends of the successive windows, τ: each doubles the accumulation, so the
/// batch-means error roughly shrinks by √2 per stage, and the whole
/// sequence costs about twice its last stage.
pub(crate) const STAGES: [f64; 5] = [500.0, 1000.0, 2000.0, 4000.0, 8000.0];

/// Most points of the convergence curve drawn.
const CURVE_POINTS: usize = 2000;

/// One finished stage.
#[derive(Clone, Debug, PartialEq)]
pub struct Stage {
    /// End of its window, τ.
    pub total_tau: f64,
    /// The exponents, or why there are none, or the error (one line).
    pub answer: Result<Lyapunov, String>,
}

/// The background estimate of one scene.
type Worker = Job<Stage>;

/// Starts the stages of `cfg` on a thread named `lyapunov`.
fn start(cfg: Scenario, waker: Waker) -> Result<Worker, String> {
    Job::spawn("lyapunov", STAGES.len(), waker, move |link| stages(&cfg, &link))
        .map_err(|e| format!("cannot start the lyapunov thread: {e}"))
}

/// Sends each stage of `cfg` as it is done, until one has no finite
/// exponent or the job is cancelled.
fn stages(cfg: &Scenario, link: &Link<Stage>) {
    for total_tau in STAGES {
        if link.cancelled() {
            return;
        }
        let opts = LyapunovOptions {
            method: method_for(cfg),
            transient_tau: TRANSIENT_TAU,
            total_tau,
            ..LyapunovOptions::default()
        };
        let answer = of_scenario(cfg, &opts).map_err(|e| e.to_string());
        let last = !matches!(answer, Ok(Lyapunov::Exponents(_)));
        if link.cancelled() || link.send(Stage { total_tau, answer }).is_err() || last {
            return;
        }
    }
}

/// What the hover over an estimate says of its method.
fn method_note(method: Method) -> &'static str {
    match method {
        Method::Benettin => {
            "Two trajectories renormalised once per forcing period (this body's tangent equations are not written, so the largest exponent only); ± is the standard error of batch means"
        }
        Method::Tangent | Method::Both => {
            "Tangent dynamics with saltation matrices; ± is the standard error of batch means"
        }
    }
}

/// The Lyapunov view's state.
#[derive(Default)]
pub struct LyapunovView {
    key: Option<Scenario>,
    worker: Option<Worker>,
    retired: Vec<Worker>,
    latest: Option<Stage>,
    error: Option<String>,
    /// Computations started over the view's life (work counter).
    pub runs: u64,
    /// Stages received over the view's life (work counter).
    pub stages: u64,
}

impl LyapunovView {
    /// The longest finished stage of the current scene.
    pub fn latest(&self) -> Option<&Stage> {
        self.latest.as_ref()
    }

    /// The latest estimate of the largest exponent per τ, if finite.
    pub fn value(&self) -> Option<f64> {
        self.latest.as_ref()?.answer.as_ref().ok()?.largest_per_tau()
    }

    /// Lyapunov threads still running, cancelled ones included.
    pub fn threads(&self) -> usize {
        self.retired
            .iter()
            .chain(self.worker.iter())
            .filter(|w| !w.finished())
            .count()
    }

    /// Stops work while hidden; starts over when shown.
    pub fn hide(&mut self) {
        self.retired.retain(|w| !w.finished());
        if let Some(w) = self.worker.take() {
            if !w.finished() {
                self.key = None;
            }
            w.cancel();
            self.retired.push(w);
        }
    }

    fn restart(&mut self, cfg: &Scenario, ctx: &egui::Context) {
        if let Some(w) = self.worker.take() {
            w.cancel();
            self.retired.push(w);
        }
        self.key = Some(cfg.clone());
        self.latest = None;
        self.error = None;
        let ctx = ctx.clone();
        match start(cfg.clone(), Box::new(move || ctx.request_repaint())) {
            Ok(w) => {
                self.worker = Some(w);
                self.runs += 1;
            }
            Err(e) => self.error = Some(e),
        }
    }

    /// Draws the view for the scene `cfg`, (re)starting the estimate when
    /// the scene changed.
    pub fn show(&mut self, ui: &mut egui::Ui, cfg: &Scenario) {
        self.retired.retain(|w| !w.finished());
        if self.key.as_ref() != Some(cfg) {
            self.restart(cfg, ui.ctx());
        }
        if let Some(w) = &self.worker {
            for s in w.drain() {
                self.stages += 1;
                self.latest = Some(s);
            }
        }
        let running = self.worker.as_ref().is_some_and(|w| !w.finished());
        let red = Color32::from_rgb(235, 90, 90);
        if let Some(e) = &self.error {
            ui.colored_label(red, e);
            return;
        }
        let window = |total: f64| format!("τ {TRANSIENT_TAU}–{total}");
        match &self.latest {
            None => {
                ui.label(format!("λ₁: computing ({})…", window(STAGES[0])));
            }
            Some(Stage { answer: Err(e), .. }) => {
                ui.colored_label(red, e);
            }
            Some(Stage {
                total_tau,
                answer: Ok(Lyapunov::None { no_exponent, tau, .. }),
            }) => {
                ui.label(format!(
                    "λ₁: no finite exponent ({} at τ = {tau:.1}, window {})",
                    no_exponent.name(),
                    window(*total_tau)
                ));
            }
            Some(Stage {
                total_tau,
                answer: Ok(Lyapunov::Exponents(r)),
            }) => {
                let more = if running { ", refining…" } else { "" };
                ui.label(format!(
                    "λ₁ = {:.4} ± {:.4} per τ ({:.4} per cycle), window {}{more}",
                    r.largest_per_tau,
                    r.stderr,
                    r.per_cycle,
                    window(*total_tau)
                ))
                .on_hover_text(method_note(r.method));
                let stride = r.convergence.len().div_ceil(CURVE_POINTS).max(1);
                let pts: Vec<[f64; 2]> = r.convergence.iter().step_by(stride).map(|&(t, l)| [t, l]).collect();
                axes::titled(axes::readable(Plot::new("lyapunov")), ui, "τ", "λ₁ running, per τ")
                    .allow_double_click_reset(true)
                    .show(ui, |plot_ui| {
                        plot_ui.line(
                            Line::new("running estimate", PlotPoints::new(pts))
                                .color(Color32::from_rgb(255, 170, 80))
                                .allow_hover(false),
                        );
                        plot_ui.hline(HLine::new("0", 0.0).color(Color32::from_gray(120)));
                    });
            }
        }
    }
}

impl Drop for LyapunovView {
    fn drop(&mut self) {
        // Cancel all first so they stop together; each Worker joins on drop.
        for w in self.retired.iter().chain(self.worker.iter()) {
            w.cancel();
        }
    }
}
