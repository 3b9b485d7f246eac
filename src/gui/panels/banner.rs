//! The verdict over the block scene, large enough to read on a projector:
//! `OVERTURNED at t = 4.78 s` when the block tumbles, `SURVIVED` with the
//! peak rotation and sliding when a record run comes to rest after the
//! record.
//!
//! It only words how the simulation thread said the run ended
//! ([`RunEnd`]), in seconds, degrees and centimetres whatever units the
//! plots show: the verdict is an engineer's answer.

use egui::{Color32, RichText};

use crate::gui::units::{Scales, Units};
use crate::model::Mode;
use crate::model::geometry::Geometry;
use crate::sim::protocol::RunEnd;

/// How a run ended, as the banner says it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Tumbled at `t_s` seconds.
    Overturned {
        /// When, s.
        t_s: f64,
    },
    /// Left the ground (the normal force vanished) at `t_s`: the model
    /// stops there.
    Flight {
        /// When, s.
        t_s: f64,
    },
    /// At rest after the record.
    Survived {
        /// Largest |θ|, degrees.
        peak_deg: f64,
        /// Largest |θ| per α (1 tips a block at rest over).
        over_alpha: f64,
        /// Largest |sliding displacement|, cm.
        sliding_cm: f64,
    },
}

impl Verdict {
    /// The verdict on `end` for a block of geometry `geo`; `None` for a run
    /// that failed (the status bar says why) or a terminal mode that is
    /// neither.
    pub fn of(end: &RunEnd, geo: Geometry) -> Option<Self> {
        let si = Scales::new(Units::Physical, geo);
        match *end {
            RunEnd::Terminal { mode, tau } => match mode {
                Mode::Tumbled => Some(Verdict::Overturned { t_s: si.seconds(tau) }),
                Mode::Flight => Some(Verdict::Flight { t_s: si.seconds(tau) }),
                Mode::Rest | Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. } => None,
            },
            RunEnd::Rest {
                max_abs_theta,
                max_abs_sliding,
                ..
            } => Some(Verdict::Survived {
                peak_deg: si.theta(max_abs_theta),
                over_alpha: max_abs_theta,
                sliding_cm: si.sliding_cm(max_abs_sliding),
            }),
            RunEnd::Failed(_) => None,
        }
    }

    /// The large line: `OVERTURNED at t = 4.78 s`, `SURVIVED`, …
    pub fn headline(&self) -> String {
        match self {
            Verdict::Overturned { t_s } => format!("OVERTURNED at t = {t_s:.2} s"),
            Verdict::Flight { t_s } => format!("LEFT THE GROUND at t = {t_s:.2} s"),
            Verdict::Survived { .. } => "SURVIVED".to_string(),
        }
    }

    /// The line under it, if any: the peaks of a block that survived.
    pub fn detail(&self) -> Option<String> {
        match self {
            Verdict::Overturned { .. } | Verdict::Flight { .. } => None,
            Verdict::Survived {
                peak_deg,
                over_alpha,
                sliding_cm,
            } => Some(format!(
                "peak rotation {peak_deg:.1}° ({over_alpha:.2} α) · sliding {sliding_cm:.1} cm"
            )),
        }
    }

    fn color(&self) -> Color32 {
        match self {
            Verdict::Overturned { .. } | Verdict::Flight { .. } => Color32::from_rgb(255, 95, 85),
            Verdict::Survived { .. } => Color32::from_rgb(110, 225, 120),
        }
    }
}

/// Size of the headline, points: about 5 % of a 1280 × 800 window's
/// height, readable from the back of a lecture room.
const HEADLINE_PT: f32 = 40.0;

/// Size of the lines under it, points.
const DETAIL_PT: f32 = 22.0;

/// Draws the banner at the top of `rect` (over the scene): the verdict if
/// the run has one, and `subtitle` (the record's name and PGA) under it.
pub fn show(ui: &mut egui::Ui, rect: egui::Rect, verdict: Option<&Verdict>, subtitle: Option<&str>) {
    if verdict.is_none() && subtitle.is_none() {
        return;
    }
    let builder = egui::UiBuilder::new()
        .max_rect(rect.shrink(10.0))
        .layout(egui::Layout::top_down(egui::Align::Center));
    ui.scope_builder(builder, |ui| {
        egui::Frame::new()
            .fill(Color32::from_black_alpha(170))
            .corner_radius(8.0)
            .inner_margin(egui::Margin::symmetric(18, 8))
            .show(ui, |ui| {
                ui.vertical_centered(|ui| {
                    if let Some(v) = verdict {
                        ui.label(RichText::new(v.headline()).size(HEADLINE_PT).strong().color(v.color()));
                        if let Some(d) = v.detail() {
                            ui.label(RichText::new(d).size(DETAIL_PT).color(Color32::WHITE));
                        }
                    }
                    if let Some(s) = subtitle {
                        let size = if verdict.is_some() { DETAIL_PT } else { 0.8 * DETAIL_PT };
                        ui.label(RichText::new(s).size(size).color(Color32::from_gray(220)));
                    }
                });
            });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tumble_is_worded_in_seconds() {
        let geo = Geometry::new(0.6, 2.0);
        let end = RunEnd::Terminal {
            mode: Mode::Tumbled,
            tau: 2.0 * geo.p,
        };
        let v = Verdict::of(&end, geo).expect("a verdict");
        assert_eq!(v.headline(), "OVERTURNED at t = 2.00 s");
        assert_eq!(v.detail(), None);
    }

    #[test]
    fn a_survivor_gets_its_peaks_in_degrees_and_centimetres() {
        let geo = Geometry::new(0.6, 2.0);
        let end = RunEnd::Rest {
            tau: 100.0,
            max_abs_theta: 0.5,
            max_abs_sliding: 0.01,
        };
        let v = Verdict::of(&end, geo).expect("a verdict");
        assert_eq!(v.headline(), "SURVIVED");
        let want = format!(
            "peak rotation {:.1}° (0.50 α) · sliding {:.1} cm",
            0.5 * geo.psi.to_degrees(),
            geo.r
        );
        assert_eq!(v.detail().as_deref(), Some(want.as_str()));
    }

    #[test]
    fn a_failed_run_has_no_verdict() {
        let geo = Geometry::new(1.0, 4.0);
        assert_eq!(Verdict::of(&RunEnd::Failed("x".into()), geo), None);
    }
}
