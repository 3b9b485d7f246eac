//! The pulse overturning map: the smallest overturning amplitude
//! a_p/(g tan α) against ω_p/p, one line and marker per pulse and
//! slenderness, the
//! safe windows above it as light bars (the regions that Makris & Roussos
//! 2000 show between the two overturning modes).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::marks::{colour, legend_entry, marker};
use super::rocking_spectrum::ScalePoint;
use super::style::Legend;
use super::{FONT, Figure, PlotError, axis_titles, padded_range, titled};

/// Pixels below and left of the plotting area for numbers and titles.
const LABEL_AREAS: (i32, i32) = (56, 80);

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

/// Grey of the safe windows' legend entry (each window is drawn in its
/// series' colour, lightened).
const SAFE: RGBColor = RGBColor(160, 160, 160);

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
        let mut chart = ChartBuilder::on(&area)
            .margin(16)
            .x_label_area_size(LABEL_AREAS.0)
            .y_label_area_size(LABEL_AREAS.1)
            .build_cartesian_2d(x0.max(0.0)..x1, 0.0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .label_style((FONT, 16))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(e)?;
        axis_titles(
            root,
            chart.plotting_area().get_pixel_range(),
            (
                "ω_p/p, pulse frequency over the frequency parameter",
                "a_p/(g tan α), smallest overturning amplitude",
            ),
            19.0,
            LABEL_AREAS,
        )?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x0.max(0.0), 1.0), (x1, 1.0)],
                RGBColor(150, 150, 150),
            )))
            .map_err(e)?;
        let mut any_window = false;
        for (i, s) in self.series.iter().enumerate() {
            let c = colour(i);
            for (x, _, windows) in &s.points {
                for &(from, to) in windows {
                    any_window = true;
                    let top = to.unwrap_or(self.y_max).min(y1);
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(*x, from), (*x, top)],
                            c.mix(0.35).stroke_width(4),
                        )))
                        .map_err(e)?;
                }
            }
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|p| p.1.map(|y| (p.0, y)))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))
                .map_err(e)?
                .label(s.label.as_str())
                .legend(move |at| legend_entry(i, at, true));
            chart.draw_series(pts.iter().map(|&p| marker(i, p, 4))).map_err(e)?;
        }
        if any_window {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(e)?
                .label("light bars: safe windows above it")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], SAFE.stroke_width(3)));
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
