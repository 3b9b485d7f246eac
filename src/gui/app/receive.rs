//! The message loop: updates from the simulation thread (or the fixed
//! stream) drained under a time budget and stored, filtered by run id.

use std::time::Duration;

use super::{Link, Message, RockingApp};
use crate::gui::history::section_row;
use crate::gui::panels::ground::RecordLabel;
use crate::model::EventKind;
use crate::model::stack::StackEventKind;
use crate::sim::protocol::{RunEnd, SimUpdate};

/// Time per frame the app spends receiving updates: leaves most of a 60 Hz
/// frame to layout and drawing (rerun's `receive_messages` budget).
const DRAIN_BUDGET: Duration = Duration::from_millis(8);

impl RockingApp {
    fn ingest(&mut self, u: SimUpdate, now: f64) {
        match u {
            SimUpdate::Started { info, .. } => {
                if self.hist.samples.last().is_some_and(|s| s.tau > info.tau0) {
                    // Kept across a section-phase change, but the thread
                    // could not go on and started over: time went back.
                    self.hist.clear();
                }
                self.tau = info.tau0;
                self.hist.forcing_period = info.section_period;
                self.record_label = RecordLabel::of(&info.scenario);
                self.history_view.fit_run(info.scenario.record_end_tau());
                self.phase.fit_run(info.scenario.record_end_tau());
                self.info = Some(*info);
                // A body chosen beyond a shorter stack's top: the top.
                if let (Some(j), Some(k)) = (self.body, self.stack().map(|g| g.k)) {
                    self.body = Some(j.min(k - 1));
                }
            }
            SimUpdate::Paused { paused, tau, .. } => {
                self.paused = paused;
                self.tau = tau;
            }
            SimUpdate::Batch { batch, .. } => {
                // A stack's samples carry its whole state: the plots show
                // the chosen block's.
                let body = self.chosen_body().zip(self.info.as_ref().map(|i| i.geometry));
                for mut s in batch.samples {
                    if let (Some(f), Some((j, geo))) = (s.stack, body) {
                        s.state = f.body_row(j, &geo);
                    }
                    self.hist.push_sample(s);
                }
                for e in batch.stack_events {
                    if matches!(e.kind, StackEventKind::Impact | StackEventKind::Close) {
                        self.flash_at = Some(now);
                        self.flash_face = Some(e.body);
                    }
                    self.hist.push_stack_event(e);
                }
                let mut section = batch.section.into_iter();
                if let Some((j, geo)) = body {
                    for f in batch.stack_section {
                        if let Some(p) = section.next() {
                            self.hist.push_stack_section(section_row(p.k, &f, j, &geo), f);
                        }
                    }
                }
                let mut impact = false;
                for e in batch.events {
                    impact |= e.kind == EventKind::Impact;
                    self.hist.push_event(e);
                }
                for p in section {
                    self.hist.push_section(p);
                }
                self.hist.dropped_samples += batch.dropped_samples;
                if !batch.ghosts.is_empty() || self.ghost_count == 0 {
                    self.hist.ghost_trails.push(batch.tau, &batch.ghosts);
                    self.ghosts = batch.ghosts;
                }
                if batch.tau.is_finite() {
                    self.tau = batch.tau;
                }
                if impact {
                    self.flash_at = Some(now);
                }
            }
            SimUpdate::Finished { end, .. } => {
                if let RunEnd::Failed(msg) = &end {
                    // A run with no sample did not start (e.g. its record
                    // file is gone): say so, not that it stopped.
                    let what = if self.hist.samples.is_empty() {
                        "the run could not start"
                    } else {
                        "run stopped"
                    };
                    self.message = Some(Message {
                        text: format!("{what}: {msg}"),
                        error: true,
                    });
                }
                self.phase.hold(&self.hist);
                self.end = Some(end);
            }
        }
    }

    pub(super) fn receive(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|i| i.time);
        let mut got = Vec::new();
        let more = match &mut self.link {
            Link::Live(h) => {
                h.drain(DRAIN_BUDGET, 4096, |u| got.push(u));
                // Whatever the budget left is picked up next frame.
                h.has_pending()
            }
            Link::Fixed { pending, run } => {
                let run = *run;
                got.extend(pending.drain(..).filter(|u| u.run() == run));
                false
            }
        };
        for u in got {
            self.ingest(u, now);
        }
        if more {
            ctx.request_repaint();
        }
    }
}
