//! The chart frame and the legend box the figures share, so each figure
//! names only its ranges, its axis titles and where its legend goes.

use plotters::chart::{ChartContext, MeshStyle, SeriesLabelPosition};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

use super::{FONT, PlotError, axis_titles};

/// Grey of the light grid lines: a guide for the eye that stays behind
/// the data.
const GRID: RGBColor = RGBColor(238, 238, 238);

/// Text size of a panel's caption, px.
const CAPTION: u32 = 20;

/// How one chart is framed: the blank margin and the label areas around
/// its plotting area, and the sizes of its tick labels and axis titles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    /// Blank pixels around the chart.
    pub margin: u32,
    /// Pixels under the plotting area (numbers and the x title) and left
    /// of it (numbers and the y title).
    pub label_areas: (i32, i32),
    /// Tick-label text size, px.
    pub tick_size: u32,
    /// Axis-title text size, px.
    pub title_size: f64,
}

impl Frame {
    /// A chart that fills the figure: 16 px margin, 16 px numbers and 19 px
    /// titles, readable at half width in a report.
    pub const fn whole(label_areas: (i32, i32)) -> Self {
        Self {
            margin: 16,
            label_areas,
            tick_size: 16,
            title_size: 19.0,
        }
    }

    /// One of several panels side by side: 14 px margin, 15 px numbers and
    /// 17 px titles, so that two or three panels fit across the figure.
    pub const fn panel(label_areas: (i32, i32)) -> Self {
        Self {
            margin: 14,
            label_areas,
            tick_size: 15,
            title_size: 17.0,
        }
    }

    /// A chart on `area` over `x` × `y`, with `caption` above it (20 px) if
    /// given.
    #[allow(clippy::type_complexity)]
    pub fn chart<'a, DB: DrawingBackend, X: AsRangedCoord, Y: AsRangedCoord>(
        &self,
        area: &'a DrawingArea<DB, Shift>,
        caption: Option<&str>,
        x: X,
        y: Y,
    ) -> Result<ChartContext<'a, DB, Cartesian2d<X::CoordDescType, Y::CoordDescType>>, PlotError> {
        let mut builder = ChartBuilder::on(area);
        if let Some(caption) = caption {
            builder.caption(caption, (FONT, CAPTION));
        }
        builder
            .margin(self.margin)
            .x_label_area_size(self.label_areas.0)
            .y_label_area_size(self.label_areas.1)
            .build_cartesian_2d(x, y)
            .map_err(PlotError::from_display)
    }

    /// The mesh of `chart` with the frame's numbers and a light grid; the
    /// caller adds what its axes need (number formats) and draws it.
    pub fn grid<'a, 'b, DB, X, Y, XT, YT>(
        &self,
        chart: &'b mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    ) -> MeshStyle<'a, 'b, X, Y, DB>
    where
        DB: DrawingBackend,
        X: Ranged<ValueType = XT> + ValueFormatter<XT>,
        Y: Ranged<ValueType = YT> + ValueFormatter<YT>,
    {
        let mut mesh = chart.configure_mesh();
        mesh.label_style((FONT, self.tick_size)).light_line_style(GRID);
        mesh
    }

    /// Writes the axis titles `(x, y)` of `chart` in its label areas, with
    /// subscripts ([`axis_titles`]), on `root`, the figure's whole area.
    pub fn titles<DB: DrawingBackend, X: Ranged, Y: Ranged>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
        titles: (&str, &str),
    ) -> Result<(), PlotError> {
        axis_titles(
            root,
            chart.plotting_area().get_pixel_range(),
            titles,
            self.title_size,
            self.label_areas,
        )
    }
}

/// Grey of the legend frame: visible on white without competing with the
/// black axes.
const FRAME: RGBColor = RGBColor(150, 150, 150);

/// How one figure's legend box looks.
pub(crate) struct Legend {
    /// Corner (or edge) of the plotting area the box sits in.
    pub position: SeriesLabelPosition,
    /// Label text size in pixels.
    pub font_size: u32,
    /// Opacity of the white fill (0–1): below 1 so data under the box still
    /// shows faintly instead of vanishing.
    pub fill: f64,
    /// Colour of the box's frame.
    pub frame: RGBColor,
}

impl Legend {
    /// The usual box: 90 % white fill and a grey frame.
    pub const fn at(position: SeriesLabelPosition, font_size: u32) -> Self {
        Self {
            position,
            font_size,
            fill: 0.9,
            frame: FRAME,
        }
    }

    /// Draws the labels of the series drawn so far on `chart`.
    pub fn draw<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
        self,
        chart: &mut ChartContext<'a, DB, CT>,
    ) -> Result<(), PlotError> {
        chart
            .configure_series_labels()
            .position(self.position)
            .background_style(WHITE.mix(self.fill))
            .border_style(self.frame)
            .label_font((FONT, self.font_size))
            .draw()
            .map_err(PlotError::from_display)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How the test legend is drawn.
    enum Way {
        /// The plotters chain the figures used to spell out.
        ByHand,
        /// Through [`Legend`], with this fill.
        Shared(f64),
    }

    /// Draws one labelled series on a 300×200 SVG, then its legend `way`.
    fn svg_with(way: Way) -> String {
        super::super::ensure_font().unwrap();
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (300, 200)).into_drawing_area();
            let mut chart = ChartBuilder::on(&root).build_cartesian_2d(0.0..1.0, 0.0..1.0).unwrap();
            chart
                .draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], &BLACK))
                .unwrap()
                .label("a line")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
            match way {
                Way::ByHand => chart
                    .configure_series_labels()
                    .position(SeriesLabelPosition::LowerRight)
                    .background_style(WHITE.mix(0.9))
                    .border_style(RGBColor(150, 150, 150))
                    .label_font((FONT, 14))
                    .draw()
                    .unwrap(),
                Way::Shared(fill) => Legend {
                    fill,
                    ..Legend::at(SeriesLabelPosition::LowerRight, 14)
                }
                .draw(&mut chart)
                .unwrap(),
            }
            root.present().unwrap();
        }
        svg
    }

    #[test]
    fn the_shared_legend_box_is_the_one_the_figures_wrote_out_by_hand() {
        // Same bytes: fill, frame, corner and text size all as written by hand.
        let by_hand = svg_with(Way::ByHand);
        assert!(by_hand.contains("a line"));
        assert_eq!(svg_with(Way::Shared(0.9)), by_hand);
        // A different fill must show, so the comparison above is not blind.
        assert_ne!(svg_with(Way::Shared(0.5)), by_hand);
    }
}
