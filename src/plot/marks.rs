//! How the series of a figure are told apart: each has a colour and a
//! marker shape of its own, so that two series stay distinct in grey print
//! and for readers who do not tell the hues apart.

use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};

/// Colours of successive series (blocks, slendernesses, pulses): the
/// matplotlib "tab10" hues, distinct in print and on screen.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(23, 190, 207),
];

/// Colour of series `i`.
pub fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Marker shapes of successive series. Five shapes against eight colours:
/// the pair (colour, shape) repeats only after 40 series. The triangle
/// pointing up and the cross are kept for flight and overturning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// A filled disc.
    Disc,
    /// A filled square.
    Square,
    /// A filled diamond.
    Diamond,
    /// A filled triangle pointing down.
    TriangleDown,
    /// An open ring.
    Ring,
}

/// Shapes in the order series take them.
pub(crate) const SHAPES: [Shape; 5] = [
    Shape::Disc,
    Shape::Square,
    Shape::Diamond,
    Shape::TriangleDown,
    Shape::Ring,
];

/// Marker shape of series `i`.
pub fn shape(i: usize) -> Shape {
    SHAPES[i % SHAPES.len()]
}

/// A marker: a shape of a colour and radius (pixels) at a point, with a
/// short line through it in a legend. One element type for every shape,
/// so a series' markers are one plotters series.
#[derive(Clone, Debug, PartialEq)]
pub struct Marker<C> {
    /// Where, in the chart's coordinates (pixels in a legend).
    pub at: C,
    /// Its shape.
    pub shape: Shape,
    /// Its colour.
    pub colour: RGBColor,
    /// Its radius, pixels.
    pub r: i32,
    /// Whether a 20-pixel line in the colour runs through it (a legend
    /// entry of a series drawn as a line with markers).
    pub line: bool,
}

/// Series `i`'s marker of radius `r` pixels at `at` (chart coordinates).
pub fn marker<C>(i: usize, at: C, r: i32) -> Marker<C> {
    Marker {
        at,
        shape: shape(i),
        colour: colour(i),
        r,
        line: false,
    }
}

/// Series `i`'s legend entry at legend position `at`: its marker, on a
/// short line in its colour when `line` (a series drawn as a line).
pub(crate) fn legend_entry(i: usize, (x, y): (i32, i32), line: bool) -> Marker<(i32, i32)> {
    Marker {
        line,
        ..marker(i, (x + 10, y), 4)
    }
}

impl<'a, C> PointCollection<'a, C> for &'a Marker<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;

    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for Marker<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut points: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = points.next() else {
            return Ok(());
        };
        let (c, r) = (self.colour, self.r);
        if self.line {
            backend.draw_path([(x - 10, y), (x + 10, y)], &c.stroke_width(2))?;
        }
        let d = r + 1;
        match self.shape {
            Shape::Disc => backend.draw_circle((x, y), r.max(0) as u32, &c, true),
            Shape::Square => backend.draw_rect((x - r, y - r), (x + r, y + r), &c, true),
            Shape::Diamond => backend.fill_polygon([(x, y - d), (x + d, y), (x, y + d), (x - d, y)], &c),
            Shape::TriangleDown => backend.fill_polygon([(x - d, y - d + 1), (x + d, y - d + 1), (x, y + d)], &c),
            Shape::Ring => {
                // A white disc under the ring, so it reads as open over a line.
                backend.draw_circle((x, y), r.max(0) as u32, &WHITE, true)?;
                backend.draw_circle((x, y), r.max(0) as u32, &c.stroke_width(2), false)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forty_series_have_forty_distinct_looks() {
        let looks: std::collections::HashSet<((u8, u8, u8), Shape)> = (0..40)
            .map(|i| {
                let c = colour(i);
                ((c.0, c.1, c.2), shape(i))
            })
            .collect();
        assert_eq!(looks.len(), 40);
    }
}
