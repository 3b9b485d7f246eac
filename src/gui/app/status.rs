//! The status bar: playhead, mode, counts, speed, how the run ended, frame
//! times (live app only), a GIF recording's progress and the last message;
//! and what the scene shows when there is no run to draw.

use super::{Link, RockingApp};
use crate::gui::panels::scene;
use crate::sim::protocol::RunEnd;

/// The colour of errors (and of the recording mark): a red that reads on
/// the dark and the light theme.
const ERROR_RED: egui::Color32 = egui::Color32::from_rgb(235, 90, 90);

/// How long a message stays in the status bar, s of wall-clock time: long
/// enough to read twice, short enough that a stale error does not sit
/// beside a run it no longer describes. Errors stay longer than notices.
const NOTICE_S: f64 = 8.0;
/// How long an error stays in the status bar, s (see [`NOTICE_S`]).
const ERROR_S: f64 = 20.0;

/// One item of the status bar: its text, colour and hover text.
struct Item {
    text: String,
    color: Option<egui::Color32>,
    hover: Option<String>,
}

impl Item {
    fn plain(text: String) -> Self {
        Self {
            text,
            color: None,
            hover: None,
        }
    }

    fn colored(text: String, color: egui::Color32) -> Self {
        Self {
            text,
            color: Some(color),
            hover: None,
        }
    }

    fn hover(mut self, text: impl Into<String>) -> Self {
        self.hover = Some(text.into());
        self
    }

    fn rich(&self) -> egui::RichText {
        let r = egui::RichText::new(&self.text);
        match self.color {
            Some(c) => r.color(c),
            None => r,
        }
    }

    /// Width of the item's text in points, as a label would draw it.
    fn width(&self, ui: &egui::Ui) -> f32 {
        let galley = egui::WidgetText::from(self.rich()).into_galley(
            ui,
            Some(egui::TextWrapMode::Extend),
            f32::INFINITY,
            egui::TextStyle::Body,
        );
        galley.size().x + ui.spacing().item_spacing.x
    }

    fn show(&self, ui: &mut egui::Ui, truncate: bool) {
        let mut label = egui::Label::new(self.rich());
        if truncate {
            label = label.truncate();
        }
        let r = ui.add(label);
        if let Some(h) = &self.hover {
            r.on_hover_text(h);
        }
    }
}

impl RockingApp {
    /// The status bar: one line at every width and presentation scale.
    /// Items come in order of importance (where the run is, its mode and
    /// counts, how it ended, the message); what does not fit is left out
    /// (the symbols' key, the frame times) or cut with "…" and shown whole
    /// on hover (a long message), instead of wrapping onto a second line
    /// that would push the plots up.
    pub(super) fn status(&mut self, ui: &mut egui::Ui) {
        // The bar is drawn every frame: the title and the pictures being
        // taken advance with it.
        self.share_tick(ui.ctx());
        let now = ui.input(|i| i.time);
        self.expire_message(now);
        let (essential, message, extra) = self.status_items(ui, now);
        let bar = ui.horizontal(|ui| {
            ui.set_min_width(ui.available_width());
            for item in &essential {
                if item.width(ui) <= ui.available_width() {
                    item.show(ui, false);
                } else if ui.available_width() > 60.0 {
                    // Cut with "…" (whole on hover) rather than dropped:
                    // how the run ended matters more than what follows.
                    item.show(ui, true);
                }
            }
            // The optional items go right of the message while they fit
            // beside it; the message then gets what is left, cut if long.
            let reserve = message
                .as_ref()
                .map_or(0.0, |m| m.width(ui).min(0.6 * ui.available_width()));
            let mut room = ui.available_width() - reserve;
            let mut right = Vec::new();
            for item in extra {
                let w = item.width(ui);
                if w <= room {
                    room -= w;
                    right.push(item);
                }
            }
            // Nothing to the right (and no room for a cut message): no
            // layout, which would take a few points past the window.
            if right.is_empty() && (message.is_none() || ui.available_width() < 30.0) {
                return;
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                for item in right.iter().rev() {
                    item.show(ui, false);
                }
                if let Some(m) = &message {
                    ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| m.show(ui, true));
                }
            });
        });
        self.status_rect = Some(bar.response.rect);
    }

    /// Forgets the status message once it has been shown long enough
    /// ([`NOTICE_S`], [`ERROR_S`]); a failed run keeps its reason on the
    /// "failed" mark's hover text.
    fn expire_message(&mut self, now: f64) {
        let Some(m) = &self.message else {
            self.message_since = None;
            return;
        };
        let since = match &self.message_since {
            Some((shown, t0)) if shown == m => *t0,
            _ => {
                self.message_since = Some((m.clone(), now));
                now
            }
        };
        let life = if m.error { ERROR_S } else { NOTICE_S };
        if now - since >= life {
            self.message = None;
            self.message_since = None;
        }
    }

    /// The status bar's items: the essential ones, the message, and the
    /// ones left out first when the bar is narrow.
    fn status_items(&self, ui: &egui::Ui, now: f64) -> (Vec<Item>, Option<Item>, Vec<Item>) {
        let p = self.info.as_ref().map_or(self.config.geometry().p, |i| i.geometry.p);
        let mut essential = vec![
            Item::plain(format!("τ = {:.2}", self.tau)),
            Item::plain(format!("t = {:.2} s", self.tau / p)),
        ];
        // A run that ended in a terminal mode is in it, whatever mode the
        // last sample before the event was drawn in.
        let mode = match &self.end {
            Some(RunEnd::Terminal { mode, .. }) => mode.name(),
            _ => self.hist.samples.last().map_or("–", |s| s.mode.name()),
        };
        essential.push(Item::plain(format!("mode: {mode}")));
        essential.push(Item::plain(format!("impacts: {}", self.hist.impacts)));
        essential.push(Item::plain(format!(
            "Poincaré points: {}",
            self.hist.section.points().len() as u64 + self.hist.section.dropped
        )));
        if let (Some(end), Some((_, name))) = (&self.end, self.stack_end()) {
            // A stack: the block that went over, in the batch run's words.
            let text = match end.end_state() {
                Some((crate::sim::EndState::Flight, tau)) => format!("{name} left the ground at t = {:.2} s", tau / p),
                Some((_, tau)) => format!("{name} overturned at t = {:.2} s", tau / p),
                None => format!("{name} stopped"),
            };
            essential.push(
                Item::colored(text, scene::mode_color(crate::model::Mode::Tumbled))
                    .hover("the blocks above its lower face carried their centre of mass over its pivot; the model stops there"),
            );
        } else if let Some(end) = &self.end {
            let tumble = self.info.as_ref().map(|i| i.scenario.run.tumble_theta);
            essential.push(end_item(end, tumble, p, self.record_label.is_some()));
        }
        if self.paused {
            essential.push(Item::plain("paused".into()));
        }
        if let Some(text) = self.recording_label(now) {
            essential.push(Item::colored(text, ERROR_RED));
        }
        let rate = if self.max_speed {
            "max".to_string()
        } else {
            format!("{:.2} τ/s", self.speed * p)
        };
        essential.push(Item::plain(format!("speed: {rate}")));
        let message = self.message.as_ref().map(|m| {
            let color = if m.error {
                ERROR_RED
            } else {
                ui.visuals().weak_text_color()
            };
            Item::colored(m.text.clone(), color).hover(m.text.clone())
        });
        // The symbols, explained on hover (Help ▸ Symbols lists them).
        let geo = self
            .info
            .as_ref()
            .map_or_else(|| self.config.geometry(), |i| i.geometry);
        let [theta, tau, psi, p_sym] = crate::gui::glossary::entries(&geo);
        let mut extra = vec![
            Item::plain("Θ = θ/ψ".into()).hover(theta.1),
            Item::plain("τ = p t".into()).hover(tau.1),
            Item::plain(format!("ψ = {:.2}°", geo.psi.to_degrees())).hover(psi.1),
            Item::plain(format!("p = {:.3}/s", geo.p)).hover(p_sym.1),
        ];
        // Wall-clock numbers only in the live app: a fixed stream must
        // draw the same pixels every time (snapshots).
        if matches!(self.link, Link::Live(_)) {
            extra.push(
                Item::plain(format!(
                    "app {:.1} ms/frame, {:.1} ms between frames",
                    self.frame_ms, self.frame_interval_ms
                ))
                .hover(
                    "CPU time of the app's own code per frame, and the interval between frames (rendering included)",
                ),
            );
        }
        (essential, message, extra)
    }

    /// What the scene shows while it has nothing to draw: why the run did
    /// not start, in red, if it failed to; else that it is coming.
    pub(super) fn no_run_label(&self, ui: &mut egui::Ui) {
        let failed = match &self.end {
            Some(RunEnd::Failed(msg)) => Some(msg),
            Some(RunEnd::Terminal { .. } | RunEnd::Rest { .. }) | None => None,
        };
        ui.centered_and_justified(|ui| match failed {
            Some(msg) => {
                ui.colored_label(ERROR_RED, format!("The run could not start: {msg}"));
            }
            None => {
                ui.label("waiting for the simulation…");
            }
        });
    }
}

/// How the run ended, short, with the why on hover.
fn end_item(end: &RunEnd, tumble_theta: Option<f64>, p: f64, record: bool) -> Item {
    use crate::model::Mode;
    match end {
        RunEnd::Terminal {
            mode: Mode::Tumbled,
            tau,
        } => {
            let limit = tumble_theta.unwrap_or(1.0);
            let text = format!(
                "tumbled at τ = {tau:.2} (t = {:.2} s); the fall is drawn, not simulated",
                tau / p
            );
            Item::colored(text.clone(), scene::mode_color(Mode::Tumbled)).hover(format!(
                "{text}: |Θ| reached {limit}, the centre of mass passed over the corner and the model stops there"
            ))
        }
        RunEnd::Terminal { mode, tau } => {
            Item::colored(format!("{} at τ = {tau:.2}", mode.name()), scene::mode_color(*mode))
        }
        RunEnd::Rest { tau, .. } => Item::colored(
            format!(
                "at rest{}, τ = {tau:.2} (t = {:.2} s)",
                if record {
                    " after the record"
                } else {
                    " for good (the base is still)"
                },
                tau / p
            ),
            scene::mode_color(Mode::Rest),
        ),
        RunEnd::Failed(msg) => Item::colored("failed".into(), ERROR_RED).hover(format!("the run stopped: {msg}")),
    }
}
