//! How the series of a figure are told apart: each has a colour and a
//! marker shape of its own, so that two series stay distinct in grey print
//! and for readers who do not tell the hues apart.

use plotters::chart::ChartContext;
use plotters::element::{Drawable, IntoDynElement, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};

use super::PlotError;
use super::hues;

/// Grey of the marks no series owns (an overturning line, the legend's
/// generic overturned cross): dark enough to read, not black like the
/// axes.
pub(crate) const MARK: RGBColor = RGBColor(90, 90, 90);

/// Colours of successive series (blocks, slendernesses, pulses): the
/// matplotlib "tab10" hues, distinct in print and on screen.
pub const PALETTE: [RGBColor; 8] = [
    hues::BLUE,
    hues::ORANGE,
    hues::GREEN,
    hues::PURPLE,
    hues::BROWN,
    hues::PINK,
    hues::GREY,
    hues::CYAN,
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

/// Adds a legend entry `label` drawn by `entry`, with nothing drawn on the
/// chart: for a kind of mark that several series share (crosses where a
/// block overturned), named once.
pub(crate) fn legend_only<'a, DB, X, Y, E, F>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    label: &str,
    entry: F,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
    E: IntoDynElement<'a, DB, BackendCoord>,
    F: Fn(BackendCoord) -> E + 'a,
{
    chart
        .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
        .map_err(PlotError::from_display)?
        .label(label)
        .legend(entry);
    Ok(())
}

/// The legend entry of the overturned crosses (drawn in each series'
/// colour; the entry in [`MARK`] grey stands for all), with `label`
/// saying where they sit.
pub(crate) fn overturned_legend<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    label: &str,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    legend_only(chart, label, |(x, y)| Cross::new((x + 10, y), 5, MARK.stroke_width(2)))
}

/// The legend entry of the black flight triangles.
pub(crate) fn flight_legend<'a, DB, X, Y>(chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    legend_only(chart, "flight (the block left the ground)", |(x, y)| {
        TriangleMarker::new((x + 10, y), 6, BLACK.filled())
    })
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
