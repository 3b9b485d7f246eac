//! The pulse overturning map: the smallest overturning amplitude
//! a_p/(g tan α) against ω_p/p, one line and marker per pulse and
//! slenderness, the
//! safe windows above it as light bars (the regions that Makris & Roussos
//! 2000 show between the two overturning modes).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::rocking_spectrum::{ScalePoint, safe_windows_legend, scale_series};
use super::style::{Frame, Legend};
use super::{Figure, PlotError, padded_range, titled};

/// One pulse at one slenderness.
#[derive(Clone, Debug)]
pub(crate) struct PulseMapSeries {
    /// Legend text.
    pub label: String,
    /// (ω_p/p, smallest overturning a_p/(g tan α), safe windows).
    pub points: Vec<ScalePoint>,
}

/// The map.
#[derive(Clone, Debug)]
pub(crate) struct PulseMapFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// Largest amplitude tried.
    pub y_max: f64,
    /// The series.
    pub series: Vec<PulseMapSeries>,
}

impl Figure for PulseMapFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let (x0, x1) = padded_range(
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
            0.03,
            0.5,
            (0.0, 10.0),
        );
        let y1 = if self.y_max.is_finite() && self.y_max > 0.0 {
            self.y_max * 1.05
        } else {
            10.0
        };
        let frame = Frame::whole((56, 80));
        let mut chart = frame.chart(&area, None, x0.max(0.0)..x1, 0.0..y1)?;
        frame.grid(&mut chart).draw().map_err(e)?;
        frame.titles(
            root,
            &chart,
            (
                "ω_p/p, pulse frequency over the frequency parameter",
                "a_p/(g tan α), smallest overturning amplitude",
            ),
        )?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x0.max(0.0), 1.0), (x1, 1.0)],
                RGBColor(150, 150, 150),
            )))
            .map_err(e)?;
        let mut any_window = false;
        for (i, s) in self.series.iter().enumerate() {
            // In the order the study gave: pulses are tabulated by ω_p/p.
            any_window |= scale_series(&mut chart, i, &s.label, &s.points, (self.y_max, y1), false)?;
        }
        if any_window {
            safe_windows_legend(&mut chart)?;
        }
        Legend::at(SeriesLabelPosition::UpperLeft, 16).draw(&mut chart)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_as_svg() {
        let fig = PulseMapFigure {
            title: "t".into(),
            subtitle: "s".into(),
            y_max: 10.0,
            series: vec![PulseMapSeries {
                label: "one-sine, B/H = 0.2".into(),
                points: vec![
                    (1.0, Some(1.2), vec![]),
                    (4.0, Some(3.0), vec![(4.0, None)]),
                    (8.0, None, vec![]),
                ],
            }],
        };
        let svg = fig.to_svg().unwrap();
        assert!(svg.contains("one-sine") && svg.contains("safe windows above it"));
    }

    #[test]
    fn subscripts_are_drawn_not_written_as_underscores_and_axes_are_numbered() {
        let fig = PulseMapFigure {
            title: "t".into(),
            subtitle: "μ_s = 0.5, μ_k = 0.5; a_p/(g tan α) = 0.1 … 6".into(),
            y_max: 6.0,
            series: vec![
                PulseMapSeries {
                    label: "one-sine, B/H = 0.2".into(),
                    points: vec![(2.0, Some(1.2), vec![]), (3.0, Some(1.4), vec![])],
                },
                PulseMapSeries {
                    label: "one-cosine, B/H = 0.2".into(),
                    points: vec![(2.0, Some(1.3), vec![]), (3.0, Some(1.8), vec![])],
                },
            ],
        };
        let svg = fig.to_svg().unwrap();
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "pulse map");
        // The second series' markers are squares, not discs like the first's.
        assert!(svg.contains("<rect") && svg.contains("#FF7F0E"), "no square marker");
    }
}
