//! The legend box the figures share, so each figure names only where its
//! legend goes and how large its text is.

use plotters::chart::{ChartContext, SeriesLabelPosition};
use plotters::coord::CoordTranslate;
use plotters::prelude::*;

use super::{FONT, PlotError};

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
