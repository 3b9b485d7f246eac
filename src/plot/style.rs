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
pub struct Legend {
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
