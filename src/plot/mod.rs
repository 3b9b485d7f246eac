//! Figures of the analyses, drawn with plotters as PNG and SVG: the
//! bifurcation diagram, the outcome map, the time history Θ(τ), the power
//! spectrum and the Poincaré map.
//!
//! Contract:
//! - Each figure is a plain data struct implementing [`Figure`]; drawing is
//!   generic over the plotters backend, so the PNG and the SVG are the same
//!   drawing. Nothing here computes physics or reads files.
//! - Text uses the Ubuntu Light font shipped with egui
//!   (`epaint_default_fonts`), registered with plotters' `ab_glyph` once per
//!   process, so no system font library is needed (ECOSYSTEM.md).
//! - Output is deterministic: the same data gives the same bytes.
//! - Non-finite data points are skipped, never drawn.

pub mod bifurcation;
pub mod fragility;
mod hues;
pub mod incremental;
pub mod labels;
pub mod marks;
pub mod outcome_map;
pub mod poincare;
pub mod pulse_map;
pub mod rich;
pub mod rocking_spectrum;
pub mod sliding_spectrum;
pub mod spectrum;
pub mod style;
#[cfg(test)]
pub(crate) mod svg_text;
pub mod ticks;
pub mod time_history;
pub mod work_precision;

use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// The font family name the figures use.
pub(crate) const FONT: &str = "sans-serif";

/// A drawing or font error, as one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("plot: {0}")]
pub struct PlotError(pub String);

impl PlotError {
    /// Wraps any backend error.
    pub(crate) fn from_display<E: std::fmt::Display>(e: E) -> Self {
        Self(e.to_string())
    }
}

/// Registers the figure font with plotters (once per process).
pub(crate) fn ensure_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT)
                .map_err(|_| "the Ubuntu Light font could not be loaded".to_string())
        })
        .clone()
        .map_err(PlotError)
}

/// A figure that can be drawn on any plotters backend.
pub trait Figure {
    /// Size in pixels (PNG) or SVG units. Default 1200 × 800: readable on
    /// a screen and in a report at half width.
    fn size(&self) -> (u32, u32) {
        (1200, 800)
    }

    /// Draws the figure on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>;

    /// Writes the figure as a PNG file at `path`.
    fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        ensure_font()?;
        let root = BitMapBackend::new(path, self.size()).into_drawing_area();
        self.draw(&root)?;
        root.present().map_err(PlotError::from_display)
    }

    /// The figure as an SVG document.
    fn to_svg(&self) -> Result<String, PlotError> {
        ensure_font()?;
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, self.size()).into_drawing_area();
            self.draw(&root)?;
            root.present().map_err(PlotError::from_display)?;
        }
        Ok(svg)
    }
}

/// Fills the background white and writes a title (and an optional second
/// line) at the top, with subscripts ([`rich`]); returns the area below.
pub fn titled<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: &str,
) -> Result<DrawingArea<DB, Shift>, PlotError> {
    root.fill(&WHITE).map_err(PlotError::from_display)?;
    let area = title_line(root, title, 26.0, &BLACK)?;
    if subtitle.is_empty() {
        Ok(area)
    } else {
        title_line(&area, subtitle, 18.0, &RGBColor(70, 70, 70))
    }
}

/// One centred line of text at the top of `area` (spaced as plotters'
/// `titled`, and a little more when a subscript hangs below it); returns
/// the area below.
fn title_line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    colour: &RGBColor,
) -> Result<DrawingArea<DB, Shift>, PlotError> {
    let mut h = rich::height(area, text, size)?;
    if rich::has_subscript(text) {
        h += (0.2 * size).round() as i32;
    }
    let pad = (h / 2).min(5);
    let (w, _) = area.dim_in_pixel();
    rich::draw(
        area,
        text,
        (w as i32 / 2, pad),
        size,
        colour,
        rich::Anchor::Centre,
        false,
    )?;
    Ok(area.margin(pad * 2 + h, 0, 0, 0))
}

/// Writes the titles of a chart's axes, with subscripts ([`rich`]): `x`
/// centred at the bottom of the `x_area`-pixel label area under the
/// plotting area `plot` (its pixel ranges, as
/// `chart.plotting_area().get_pixel_range()` gives them), `y` upright at
/// the left of the `y_area`-pixel label area beside it. Drawn on `root`, the
/// figure's whole area.
pub(crate) fn axis_titles<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plot: (Range<i32>, Range<i32>),
    (x, y): (&str, &str),
    size: f64,
    (x_area, y_area): (i32, i32),
) -> Result<(), PlotError> {
    let (base_x, base_y) = root.get_base_pixel();
    let (xs, ys) = plot;
    let colour = RGBColor(0, 0, 0);
    let h = rich::height(root, x, size)? + if rich::has_subscript(x) { (0.2 * size) as i32 } else { 0 };
    rich::draw(
        root,
        x,
        ((xs.start + xs.end) / 2 - base_x, ys.end + x_area - h - 2 - base_y),
        size,
        &colour,
        rich::Anchor::Centre,
        false,
    )?;
    rich::draw(
        root,
        y,
        (xs.start - y_area + 2 - base_x, (ys.start + ys.end) / 2 - base_y),
        size,
        &colour,
        rich::Anchor::Centre,
        true,
    )
}

/// A range `[lo, hi]` padded by `pad` of its width, widened to at least
/// `min_width` around its centre, from finite values (`default` if none).
pub(crate) fn padded_range(
    values: impl Iterator<Item = f64>,
    pad: f64,
    min_width: f64,
    default: (f64, f64),
) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return default;
    }
    let width = (hi - lo).max(min_width);
    let mid = 0.5 * (lo + hi);
    let half = 0.5 * width * (1.0 + 2.0 * pad);
    (mid - half, mid + half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn padded_range_pads_and_widens() {
        let (lo, hi) = padded_range([0.0, 1.0].into_iter(), 0.1, 0.0, (0.0, 1.0));
        assert!((lo + 0.1).abs() < 1e-15 && (hi - 1.1).abs() < 1e-15, "{lo} {hi}");
        assert_eq!(padded_range([2.0].into_iter(), 0.0, 1.0, (0.0, 1.0)), (1.5, 2.5));
        assert_eq!(padded_range([f64::NAN].into_iter(), 0.0, 1.0, (-1.0, 1.0)), (-1.0, 1.0));
    }

    #[test]
    fn font_registers() {
        ensure_font().unwrap();
        ensure_font().unwrap();
    }
}
