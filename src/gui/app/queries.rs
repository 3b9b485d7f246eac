//! What the app shows and holds, read by its panels, its status bar and
//! the tests.

use super::{Link, Message, RockingApp};
use crate::gui::history::RunHistory;
use crate::gui::panels::bifurcation::BifurcationView;
use crate::gui::panels::ground::RecordLabel;
use crate::gui::panels::lyapunov::LyapunovView;
use crate::gui::panels::plots::{PhaseView, PoincareView};
use crate::gui::units::{Scales, Units};
use crate::sim::Scenario;
use crate::sim::protocol::{RunEnd, RunId, RunInfo, StartFrom};

impl RockingApp {
    /// Whether the scene is drawn by the wgpu pipeline.
    pub fn gpu(&self) -> bool {
        self.gpu
    }
    /// Whether the contact force and friction cone are drawn.
    pub fn forces_shown(&self) -> bool {
        self.forces
    }
    /// The playhead, τ.
    pub fn tau(&self) -> f64 {
        self.tau
    }
    /// Whether paused.
    pub fn paused(&self) -> bool {
        self.paused
    }
    /// The configuration of the scene (what the panel shows).
    pub fn config(&self) -> &Scenario {
        &self.config
    }
    /// What the current run is running, once it has started.
    pub fn run_info(&self) -> Option<&RunInfo> {
        self.info.as_ref()
    }
    /// The current run.
    pub fn run_id(&self) -> RunId {
        match &self.link {
            Link::Live(h) => h.current_run(),
            Link::Fixed { run, .. } => *run,
        }
    }
    /// What the app keeps of the run.
    pub fn history(&self) -> &RunHistory {
        &self.hist
    }
    /// How the run ended, if it has.
    pub fn end(&self) -> Option<&RunEnd> {
        self.end.as_ref()
    }
    /// Where the status bar was drawn last (points), once drawn.
    pub fn status_rect(&self) -> Option<egui::Rect> {
        self.status_rect
    }
    /// The status-bar message.
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }
    /// Work done by each plot so far: (phase trail points, Poincaré points
    /// binned, time-history points, spectra computed). A hidden plot's
    /// count stays put.
    pub fn plot_work(&self) -> (u64, u64, u64, u64) {
        (
            self.phase.work,
            self.poincare.grid.work,
            self.history_view.work,
            self.spectrum.work,
        )
    }
    /// The bifurcation view (its sweep settings are public fields).
    pub fn bifurcation(&self) -> &BifurcationView {
        &self.bifurcation
    }
    /// The bifurcation view, to change its sweep.
    pub fn bifurcation_mut(&mut self) -> &mut BifurcationView {
        &mut self.bifurcation
    }
    /// The Poincaré view: which section it shows and what it binned.
    pub fn poincare(&self) -> &PoincareView {
        &self.poincare
    }
    /// The phase portrait's view: what its trails drew last frame.
    pub fn phase_view(&self) -> &PhaseView {
        &self.phase
    }
    /// Where a slider drag restarts the run from (the panel's toggle).
    pub fn drag_from(&self) -> StartFrom {
        self.edits.drag_from
    }
    /// The Lyapunov view.
    pub fn lyapunov(&self) -> &LyapunovView {
        &self.lyapunov
    }
    /// The units numbers are shown in: the user's choice, or the scene's
    /// default ([`Units::default_for`]: physical for a record).
    pub fn units(&self) -> Units {
        self.units_choice
            .unwrap_or_else(|| Units::default_for(self.config.excitation.kind))
    }
    /// Conversions to the units shown, for the block being run (the
    /// panel's block before the run has started).
    pub fn scales(&self) -> Scales {
        let geo = self
            .info
            .as_ref()
            .map_or_else(|| self.config.geometry(), |i| i.geometry);
        let scales = Scales::new(self.units(), geo);
        match (self.chosen_body(), self.stack()) {
            (Some(j), Some(g)) => scales.with_body(
                crate::sim::stack_answer::body_name(j, g.k),
                (g.size[j][0] / g.size[j][1]).atan(),
            ),
            _ => scales,
        }
    }
    /// The current run's record (name and PGA after scale), for a record run.
    pub fn record_label(&self) -> Option<&RecordLabel> {
        self.record_label.as_ref()
    }
    /// CPU time of the last frame's app code (layout and data), ms.
    pub fn frame_ms(&self) -> f32 {
        self.frame_ms
    }

    /// A stack's shape, while a stack runs.
    pub fn stack(&self) -> Option<&crate::model::stack::StackGeometry> {
        self.info.as_ref().and_then(|i| i.stack.as_ref())
    }

    /// The stack's block the plots show (0 the bottom), while a stack
    /// runs: the one chosen, or the top.
    pub fn chosen_body(&self) -> Option<usize> {
        let k = self.stack()?.k;
        Some(self.body.unwrap_or(k - 1).min(k - 1))
    }

    /// Shows block `j` of the stack (0 the bottom) in the phase portrait,
    /// the time history and the Poincaré points, from the states already
    /// kept: the run goes on.
    pub fn choose_body(&mut self, j: usize) {
        self.body = Some(j);
        let Some((k, geo)) = self.info.as_ref().and_then(|i| i.stack.map(|g| (g.k, i.geometry))) else {
            return;
        };
        self.hist.show_body(j.min(k - 1), &geo);
        self.poincare.reset();
        self.spectrum.reset();
    }

    /// How a stack's run ended, if it did by overturning or flight: that
    /// end, with the block it happened at (from the run's last event).
    pub(crate) fn stack_end(&self) -> Option<(crate::model::stack::StackEnd, &'static str)> {
        use crate::model::stack::{StackEnd, StackEventKind};
        let k = self.stack()?.k;
        let e = self.hist.stack_events.last()?;
        let end = match e.kind {
            StackEventKind::Overturn => StackEnd::Overturned(e.body),
            StackEventKind::Flight => StackEnd::Flight(e.body),
            StackEventKind::Uplift
            | StackEventKind::Impact
            | StackEventKind::Close
            | StackEventKind::Slip
            | StackEventKind::Stick => return None,
        };
        self.end.as_ref()?;
        Some((end, crate::sim::stack_answer::body_name(e.body, k)))
    }

    /// The stack as drawn last frame: the state, and each block's corners
    /// (m, bottom to top; lower left, lower right, upper right, upper left).
    pub fn stack_drawn(&self) -> Option<&(crate::sim::protocol::StackFrame, Vec<[[f64; 2]; 4]>)> {
        self.stack_drawn.as_ref()
    }

    /// Adds section points directly (measurements of the plot with many
    /// points in a fixed stream).
    pub fn push_section_points(&mut self, points: impl IntoIterator<Item = crate::sim::SectionRow>) {
        for p in points {
            self.hist.push_section(p);
        }
    }
}
