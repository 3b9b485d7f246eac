//! Labels with subscripts (`A_v`, `Ω_h`, `τ_end`, `ω_p/p`): the figures'
//! font has no subscript letters, so a subscript is drawn smaller and
//! lower, never as a raw underscore.
//!
//! A label marks a subscript as mathematics does in plain text: `_` after
//! a one-letter symbol (`A_v`, `τ_k`, `a_p`), the subscript being the
//! letters and digits that follow. An underscore inside a word is text:
//! config keys keep theirs (`run.zeno_eps`).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontTransform, IntoFont, TextStyle};

use super::{FONT, PlotError};

/// Size of a subscript relative to its text.
const SUB_SCALE: f64 = 0.72;

/// How far a subscript's top sits below its text's top, in units of the
/// text size: its baseline then falls about a fifth of the size below the
/// text's.
const SUB_DROP: f64 = 0.42;

/// The height `text` takes in `size`-pixel type, for layout.
pub fn height<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str, size: f64) -> Result<i32, PlotError> {
    let plain: String = runs(text).into_iter().map(|(t, _)| t).collect();
    let (_, h) = area
        .estimate_text_size(&plain, &TextStyle::from((FONT, size).into_font()))
        .map_err(PlotError::from_display)?;
    Ok(h as i32)
}

/// `text` split into runs of plain text (`false`) and subscripts (`true`).
pub fn runs(text: &str) -> Vec<(String, bool)> {
    let chars: Vec<char> = text.chars().collect();
    let mut out: Vec<(String, bool)> = Vec::new();
    let mut plain = String::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let symbol_before = i >= 1
            && chars[i - 1].is_alphabetic()
            && (i < 2 || !(chars[i - 2].is_alphanumeric() || chars[i - 2] == '_' || chars[i - 2] == '.'));
        let next_is_word = chars.get(i + 1).is_some_and(|n| n.is_ascii_alphanumeric());
        if c == '_' && symbol_before && next_is_word {
            let end = (i + 1..chars.len())
                .find(|&j| !chars[j].is_ascii_alphanumeric())
                .unwrap_or(chars.len());
            if !plain.is_empty() {
                out.push((std::mem::take(&mut plain), false));
            }
            out.push((chars[i + 1..end].iter().collect(), true));
            i = end;
        } else {
            plain.push(c);
            i += 1;
        }
    }
    if !plain.is_empty() {
        out.push((plain, false));
    }
    out
}

/// Whether `text` has a subscript to draw.
pub(crate) fn has_subscript(text: &str) -> bool {
    runs(text).iter().any(|(_, sub)| *sub)
}

/// Where a label is anchored along its line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// `at` is the middle of the label (axis titles, titles).
    Centre,
    /// `at` is where the label starts.
    Start,
}

/// Draws `text` on `area` in `size`-pixel type and `colour`, with its
/// subscripts, at pixel `at` (area coordinates): the top of the text, and
/// its middle or start as `anchor` says. `upright` turns it to read bottom
/// to top (a y-axis title): its top then faces left, at `at.0`.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    at: (i32, i32),
    size: f64,
    colour: &RGBColor,
    anchor: Anchor,
    upright: bool,
) -> Result<(), PlotError> {
    let e = PlotError::from_display;
    let pieces = runs(text);
    let style = |sub: bool| {
        let s = if sub { size * SUB_SCALE } else { size };
        let font = (FONT, s).into_font().color(colour);
        if upright {
            font.transform(FontTransform::Rotate270)
        } else {
            font
        }
        .pos(Pos::new(HPos::Left, VPos::Top))
    };
    let widths: Vec<i32> = pieces
        .iter()
        .map(|(t, sub)| {
            let s = if *sub { size * SUB_SCALE } else { size };
            area.estimate_text_size(t, &TextStyle::from((FONT, s).into_font()))
                .map(|(w, _)| w as i32)
                .map_err(e)
        })
        .collect::<Result<_, _>>()?;
    let total: i32 = widths.iter().sum();
    let start = match anchor {
        Anchor::Centre => -total / 2,
        Anchor::Start => 0,
    };
    let drop = (size * SUB_DROP).round() as i32;
    let mut offset = start;
    for ((t, sub), w) in pieces.iter().zip(widths) {
        let down = if *sub { drop } else { 0 };
        // Upright text advances up the page, and "down" is to its right.
        let pos = if upright {
            (at.0 + down, at.1 - offset)
        } else {
            (at.0 + offset, at.1 + down)
        };
        area.draw(&Text::new(t.clone(), pos, style(*sub))).map_err(e)?;
        offset += w;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shown(text: &str) -> Vec<(&'static str, bool)> {
        runs(text)
            .into_iter()
            .map(|(t, s)| (&*Box::leak(t.into_boxed_str()), s))
            .collect()
    }

    #[test]
    fn subscripts_follow_one_letter_symbols_and_keys_keep_their_underscores() {
        assert_eq!(shown("A_v = 3"), vec![("A", false), ("v", true), (" = 3", false)]);
        assert_eq!(
            shown("ω_p/p, pulse"),
            vec![("ω", false), ("p", true), ("/p, pulse", false)]
        );
        assert_eq!(
            shown("max error at τ_end"),
            vec![("max error at τ", false), ("end", true)]
        );
        assert_eq!(
            shown("Θ at τ_k = 2πk/Ω_h"),
            vec![("Θ at τ", false), ("k", true), (" = 2πk/Ω", false), ("h", true)]
        );
        assert_eq!(shown("run.zeno_eps"), vec![("run.zeno_eps", false)]);
        assert_eq!(shown("peak_theta_over_alpha"), vec![("peak_theta_over_alpha", false)]);
        assert_eq!(shown("x_"), vec![("x_", false)]);
        assert!(has_subscript("μ_s = 0.4") && !has_subscript("B/H = 0.2"));
    }
}
