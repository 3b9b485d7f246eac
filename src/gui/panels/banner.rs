//! The verdict over the block scene, large enough to read on a projector:
//! `OVERTURNED at t = 4.78 s` when the block tumbles, `SURVIVED` with the
//! peak rotation and sliding when a record run comes to rest after the
//! record. A record scene has the banner from the start, in a strip of its
//! own above the block (so the block never hides behind it, and the scene
//! does not jump when the verdict comes): the clock and the block's
//! rotation and sliding while the record plays, and the record's name and
//! PGA under them.
//!
//! It only words what the simulation thread sent (how the run ended,
//! [`RunEnd`], read as the core's [`EndState`], and the latest sample), in seconds, degrees and centimetres
//! whatever units the plots show: the verdict is an engineer's answer.

use egui::{Color32, RichText};

use crate::gui::units::{Scales, Units};
use crate::model::geometry::Geometry;
use crate::sim::EndState;
use crate::sim::protocol::{RunEnd, Sample};

/// A run's end as the banner says it: the core's [`EndState`] with the
/// numbers the banner shows, in seconds, degrees and centimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Verdict {
    /// How the run ended.
    pub end: EndState,
    /// When, s.
    pub t_s: f64,
    /// For a block at rest after the record: its peaks.
    pub peaks: Option<Peaks>,
    /// The body it is about, for a stack (`top block`): the headline is
    /// then the batch run's answer, `top block overturned at t = 5.30 s`.
    pub subject: Option<&'static str>,
}

/// The peaks of a block that survived.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peaks {
    /// Largest |θ|, degrees.
    pub peak_deg: f64,
    /// Largest |θ| per α (1 tips a block at rest over).
    pub over_alpha: f64,
    /// Largest |sliding displacement|, cm.
    pub sliding_cm: f64,
}

impl Verdict {
    /// The verdict on `end` for a block of geometry `geo`; `None` for a run
    /// that failed (the status bar says why) or a terminal mode that is
    /// neither.
    pub fn of(end: &RunEnd, geo: Geometry) -> Option<Self> {
        let si = Scales::new(Units::Physical, geo);
        let (state, tau) = end.end_state()?;
        let peaks = match *end {
            RunEnd::Rest {
                max_abs_theta,
                max_abs_sliding,
                ..
            } => Some(Peaks {
                peak_deg: si.theta(max_abs_theta),
                over_alpha: max_abs_theta,
                sliding_cm: si.sliding_cm(max_abs_sliding),
            }),
            RunEnd::Terminal { .. } | RunEnd::Failed(_) => None,
        };
        Some(Verdict {
            end: state,
            t_s: si.seconds(tau),
            peaks,
            subject: None,
        })
    }

    /// This verdict about `subject` (a stack's block that overturned or
    /// flew); a survival is the whole stack's, and keeps its words.
    pub fn about(self, subject: &'static str) -> Self {
        Self {
            subject: Some(subject),
            ..self
        }
    }

    /// The large line: `OVERTURNED at t = 4.78 s`, `SURVIVED`, …
    pub fn headline(&self) -> String {
        let t_s = self.t_s;
        match (self.end, self.subject) {
            // The words of `summary.json`'s answer (`Physical::line`).
            (EndState::Overturned, Some(s)) => return format!("{s} overturned at t = {t_s:.2} s"),
            (EndState::Flight, Some(s)) => return format!("{s} left the ground (flight) at t = {t_s:.2} s"),
            _ => {}
        }
        match self.end {
            EndState::Overturned => format!("OVERTURNED at t = {t_s:.2} s"),
            EndState::Flight => format!("LEFT THE GROUND at t = {t_s:.2} s"),
            EndState::Rest | EndState::Moving => "SURVIVED".to_string(),
        }
    }

    /// The line under it, if any: the peaks of a block that survived.
    pub(crate) fn detail(&self) -> Option<String> {
        self.peaks.map(
            |Peaks {
                 peak_deg,
                 over_alpha,
                 sliding_cm,
             }| format!("peak rotation {peak_deg:.1}° ({over_alpha:.2} α) · sliding {sliding_cm:.1} cm"),
        )
    }

    /// The headline's colour: red for a block lost, green for one that stood.
    pub fn color(&self) -> Color32 {
        if self.end.survived() {
            Color32::from_rgb(110, 225, 120)
        } else {
            Color32::from_rgb(255, 95, 85)
        }
    }
}

/// Size of the headline, points: about 5 % of a 1280 × 800 window's
/// height, readable from the back of a lecture room.
const HEADLINE_PT: f32 = 40.0;

/// Size of the lines under it, points.
const DETAIL_PT: f32 = 22.0;

/// Size of the remark at the bottom, points.
const NOTE_PT: f32 = 16.0;

/// Colour of the remark: a pale red, like the tumbled block.
const NOTE_COLOR: Color32 = Color32::from_rgb(255, 170, 150);

/// The lines of a banner.
#[derive(Clone, Debug, PartialEq)]
pub struct Lines {
    /// The large line.
    pub headline: String,
    /// Its colour.
    pub color: Color32,
    /// The line under it.
    pub detail: Option<String>,
    /// The last line (the record's name and PGA).
    pub subtitle: Option<String>,
    /// A remark under them, smaller (after a tumble: the fall shown is
    /// drawn, not simulated).
    pub note: Option<String>,
}

impl Lines {
    /// The verdict's lines, with `subtitle` under them.
    pub fn verdict(v: &Verdict, subtitle: Option<String>) -> Self {
        Self {
            headline: v.headline(),
            color: v.color(),
            detail: v.detail(),
            subtitle,
            note: None,
        }
    }

    /// While a record plays: the clock, and the block's rotation and
    /// sliding at the latest sample (block geometry `geo`).
    pub fn playing(sample: &Sample, geo: Geometry, subtitle: Option<String>) -> Self {
        let si = Scales::new(Units::Physical, geo);
        Self {
            headline: format!("t = {:.2} s", si.seconds(sample.tau)),
            color: Color32::WHITE,
            detail: Some(format!(
                "θ = {}° · sliding {} cm",
                one_decimal(si.theta(sample.theta)),
                one_decimal(si.horizontal(sample.theta, sample.x))
            )),
            subtitle,
            note: None,
        }
    }
}

impl Lines {
    /// While a record plays under a stack: the clock, and block `name`'s
    /// rotation (the sample's Θ is that block's φ over the bottom block's
    /// ψ, `geo` the bottom block's).
    pub(crate) fn playing_body(sample: &Sample, geo: Geometry, name: &str, subtitle: Option<String>) -> Self {
        let si = Scales::new(Units::Physical, geo);
        Self {
            headline: format!("t = {:.2} s", si.seconds(sample.tau)),
            color: Color32::WHITE,
            detail: Some(format!("{name}: φ = {}°", one_decimal(si.theta(sample.theta)))),
            subtitle,
            note: None,
        }
    }
}

/// `x` with one decimal, without the `-0.0` a tiny negative value prints as.
fn one_decimal(x: f64) -> String {
    let s = format!("{x:.1}");
    if s == "-0.0" { "0.0".to_string() } else { s }
}

/// Space above and below the lines on the plate, points.
const PAD: f32 = 8.0;

/// Space left and right of the lines on the plate, points.
const SIDE: f32 = 12.0;

/// Gap between lines, points.
const LINE_GAP: f32 = 2.0;

/// Smallest size a line is shrunk to, points: below it, it wraps instead
/// (in a plate grown to hold it).
const MIN_PT: f32 = 14.0;

/// Height of the strip a record scene's banner takes above the block,
/// points: always room for the headline and two lines at full size, so the
/// scene keeps its size when the verdict replaces the clock.
pub(crate) const STRIP_HEIGHT: f32 = 1.3 * HEADLINE_PT + 2.0 * 1.35 * DETAIL_PT + 2.0 * PAD;

/// A banner fitted to a width: each line's size, and the plate's height.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// Each line's text, size (points) and colour.
    lines: Vec<(String, f32, Color32)>,
    /// The plate's height, points.
    pub height: f32,
}

/// Fits `lines` to a plate `width` points wide: each line at its nominal
/// size where it fits on one row, else shrunk until it does (a long time
/// such as `OVERTURNED at t = 157.53 s` on a narrow scene), and wrapped
/// only below [`MIN_PT`]; the plate is as tall as the lines then are.
pub fn fit(ui: &egui::Ui, width: f32, lines: &Lines) -> Fitted {
    let inner = (width - 2.0 * SIDE).max(1.0);
    let mut all = vec![(lines.headline.clone(), HEADLINE_PT, lines.color)];
    if let Some(d) = &lines.detail {
        all.push((d.clone(), DETAIL_PT, Color32::WHITE));
    }
    if let Some(s) = &lines.subtitle {
        all.push((s.clone(), DETAIL_PT, Color32::from_gray(215)));
    }
    if let Some(n) = &lines.note {
        all.push((n.clone(), NOTE_PT, NOTE_COLOR));
    }
    let painter = ui.painter();
    let mut height = 2.0 * PAD - LINE_GAP;
    for (text, size, color) in &mut all {
        let one = painter.layout_no_wrap(text.clone(), egui::FontId::proportional(*size), *color);
        if one.size().x > inner {
            // Text width grows in proportion to the size; a hair of slack
            // for rounding.
            *size = (*size * 0.98 * inner / one.size().x).max(MIN_PT);
        }
        let laid = painter.layout(text.clone(), egui::FontId::proportional(*size), *color, inner);
        height += laid.size().y + LINE_GAP;
    }
    Fitted { lines: all, height }
}

/// Draws `fitted` centred on a dark plate filling `rect` (as wide as it
/// was fitted to; a record's strip may be taller than it needs). Returns
/// where the text went, and where its last line went.
pub fn show(ui: &mut egui::Ui, rect: egui::Rect, fitted: &Fitted) -> (egui::Rect, egui::Rect) {
    ui.painter().rect_filled(rect, 8.0, Color32::from_black_alpha(170));
    let builder = egui::UiBuilder::new()
        .max_rect(rect.shrink2(egui::vec2(SIDE, PAD)))
        .layout(egui::Layout::top_down(egui::Align::Center));
    let text = ui.scope_builder(builder, |ui| {
        ui.spacing_mut().item_spacing.y = LINE_GAP;
        let mut last = egui::Rect::NOTHING;
        for (line, size, color) in &fitted.lines {
            last = ui
                .add(egui::Label::new(RichText::new(line).size(*size).color(*color)).wrap())
                .rect;
        }
        last
    });
    (text.response.rect, text.inner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mode;

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
    fn a_playing_record_shows_no_negative_zero() {
        let geo = Geometry::new(0.6, 2.0);
        let mut y = [0.0; crate::model::system::N];
        y[crate::model::system::X] = -1e-9;
        let state = crate::sim::HistoryRow::of_state(geo.p, Mode::Rest, &y);
        let sample = Sample::still(state, 1.0);
        let lines = Lines::playing(&sample, geo, None);
        assert_eq!(lines.headline, "t = 1.00 s");
        assert_eq!(lines.detail.as_deref(), Some("θ = 0.0° · sliding 0.0 cm"));
    }

    #[test]
    fn a_failed_run_has_no_verdict() {
        let geo = Geometry::new(1.0, 4.0);
        assert_eq!(Verdict::of(&RunEnd::Failed("x".into()), geo), None);
    }
}
