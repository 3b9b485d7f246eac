//! Text sizes readable from the back of a lecture hall.
//!
//! egui's defaults (body 12.5 pt, small 9 pt) are for a desktop at arm's
//! length: projected from a 1280-pixel image onto a 4 m screen, text under
//! about 14 px cannot be read from 15 m. So every text style is at least
//! 14 points (14 px at presentation scale 1), and the lecture presentation
//! ([`TextSizes::LECTURE`]) enlarges them again, plot numbers to 20.

use crate::gui::panels::axes;

/// The size of each text style, points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TextSizes {
    /// Small text (egui's 9 pt default is unreadable projected).
    pub small: f32,
    /// Labels, values, notes, axis titles.
    pub body: f32,
    /// Button captions.
    pub button: f32,
    /// Fixed-width text.
    pub monospace: f32,
    /// Panel headings.
    pub heading: f32,
    /// Plot tick numbers ([`axes::PLOT_NUMBERS`]).
    pub plot_numbers: f32,
}

impl TextSizes {
    /// The default: nothing below 14 px at scale 1, body text a little
    /// larger so parameter names and values read at a glance.
    pub(crate) const NORMAL: Self = Self {
        small: 14.0,
        body: 15.0,
        button: 15.0,
        monospace: 14.0,
        heading: 20.0,
        plot_numbers: 15.0,
    };

    /// The lecture presentation: plot numbers at 20 px and the rest
    /// enlarged less, so the plots keep most of their room.
    pub(crate) const LECTURE: Self = Self {
        small: 17.0,
        body: 18.0,
        button: 18.0,
        monospace: 17.0,
        heading: 24.0,
        plot_numbers: 20.0,
    };

    /// The sizes for the lecture presentation or not.
    pub fn of(lecture: bool) -> Self {
        if lecture { Self::LECTURE } else { Self::NORMAL }
    }
}

/// Sets `ctx`'s text styles to `sizes` (in every theme).
pub fn apply(ctx: &egui::Context, sizes: TextSizes) {
    use egui::{FontFamily, FontId, TextStyle};
    ctx.all_styles_mut(|style| {
        let styles = &mut style.text_styles;
        styles.insert(TextStyle::Small, FontId::new(sizes.small, FontFamily::Proportional));
        styles.insert(TextStyle::Body, FontId::new(sizes.body, FontFamily::Proportional));
        styles.insert(TextStyle::Button, FontId::new(sizes.button, FontFamily::Proportional));
        styles.insert(
            TextStyle::Monospace,
            FontId::new(sizes.monospace, FontFamily::Monospace),
        );
        styles.insert(TextStyle::Heading, FontId::new(sizes.heading, FontFamily::Proportional));
        styles.insert(
            TextStyle::Name(axes::PLOT_NUMBERS.into()),
            FontId::new(sizes.plot_numbers, FontFamily::Proportional),
        );
    });
}
