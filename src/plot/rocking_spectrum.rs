//! The rocking spectrum: peak θ/α against the frequency parameter p (log
//! axis), one line per slenderness, overturned blocks marked by crosses
//! on the line θ/α = 1 and flight by triangles; and the overturning-scale
//! spectrum: the smallest overturning PGA against p, with the safe windows
//! above it as light bars of the series colour. Also the palette the engineering figures share.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{FONT, Figure, PlotError, titled};
use crate::analysis::engineering::EndState;

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

/// Red of overturning marks.
const OVERTURN: RGBColor = RGBColor(214, 39, 40);

/// `[lo, hi]` of the finite positive values, widened by a factor on each
/// side for a log axis (`default` if none).
pub fn log_range(values: impl Iterator<Item = f64>, default: (f64, f64)) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi { default } else { (lo / 1.15, hi * 1.15) }
}

/// One slenderness of a spectrum.
#[derive(Clone, Debug)]
pub struct SpectrumSeries {
    /// Legend text, e.g. `B/H = 0.2`.
    pub label: String,
    /// (p in 1/s, peak θ/α, end), p decreasing or increasing.
    pub points: Vec<(f64, f64, EndState)>,
}

/// The peak-rotation spectrum.
#[derive(Clone, Debug)]
pub struct SpectrumFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// The series.
    pub series: Vec<SpectrumSeries>,
}

impl Figure for SpectrumFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let (x0, x1) = log_range(all().map(|p| p.0), (0.1, 10.0));
        let y1 = all()
            .map(|p| p.1)
            .filter(|v| v.is_finite())
            .fold(1.0_f64, f64::max)
            .min(2.0)
            * 1.08;
        let mut chart = ChartBuilder::on(&area)
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(80)
            .build_cartesian_2d((x0..x1).log_scale(), 0.0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("p = √(3g/4R), frequency parameter (1/s)")
            .y_desc("peak rotation θ/α")
            .label_style((FONT, 16))
            .axis_desc_style((FONT, 19))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x0, 1.0), (x1, 1.0)],
                OVERTURN.mix(0.5).stroke_width(1),
            )))
            .map_err(e)?;
        for (i, s) in self.series.iter().enumerate() {
            let c = colour(i);
            let mut pts: Vec<(f64, f64, EndState)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|p| (p.0, p.1.min(y1))),
                    c.stroke_width(2),
                ))
                .map_err(e)?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.2.survived())
                        .map(|p| Circle::new((p.0, p.1), 3, c.filled())),
                )
                .map_err(e)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.2 == EndState::Overturned)
                        .map(|p| Cross::new((p.0, p.1.min(y1)), 5, OVERTURN.stroke_width(2))),
                )
                .map_err(e)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.2 == EndState::Flight)
                        .map(|p| TriangleMarker::new((p.0, p.1.min(y1)), 6, BLACK.filled())),
                )
                .map_err(e)?;
        }
        chart
            .draw_series(std::iter::empty::<Cross<(f64, f64), i32>>())
            .map_err(e)?
            .label("overturned (× on θ/α = 1)")
            .legend(|(x, y)| Cross::new((x + 10, y), 5, OVERTURN.stroke_width(2)));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(150, 150, 150))
            .label_font((FONT, 16))
            .draw()
            .map_err(e)?;
        Ok(())
    }
}

/// One block of an overturning-scale figure: (x, the smallest failing
/// amplitude or `None`, the safe windows above it as (from, to), `to`
/// `None` when open).
pub type ScalePoint = (f64, Option<f64>, Vec<(f64, Option<f64>)>);

/// One slenderness of an overturning-scale spectrum.
#[derive(Clone, Debug)]
pub struct OverturnSeries {
    /// Legend text.
    pub label: String,
    /// (p in 1/s, smallest overturning PGA in g, safe windows in g).
    pub points: Vec<ScalePoint>,
}

/// The overturning-scale spectrum.
#[derive(Clone, Debug)]
pub struct OverturnScaleFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Largest amplitude tried (top of the axis; open windows reach it).
    pub y_max: f64,
    /// The series.
    pub series: Vec<OverturnSeries>,
}

/// Grey of the safe windows' legend entry (each window is drawn in its
/// series' colour, lightened).
const SAFE: RGBColor = RGBColor(160, 160, 160);

impl Figure for OverturnScaleFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let (x0, x1) = log_range(
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
            (0.1, 10.0),
        );
        let y1 = if self.y_max.is_finite() && self.y_max > 0.0 {
            self.y_max * 1.05
        } else {
            1.0
        };
        let mut chart = ChartBuilder::on(&area)
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(80)
            .build_cartesian_2d((x0..x1).log_scale(), 0.0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("p = √(3g/4R), frequency parameter (1/s)")
            .y_desc(self.y_label.as_str())
            .label_style((FONT, 16))
            .axis_desc_style((FONT, 19))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(e)?;
        let mut any_window = false;
        for (i, s) in self.series.iter().enumerate() {
            let c = colour(i);
            let mut pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|p| p.1.map(|y| (p.0, y)))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (p, _, windows) in &s.points {
                for &(from, to) in windows {
                    any_window = true;
                    let top = to.unwrap_or(self.y_max).min(y1);
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(*p, from), (*p, top)],
                            c.mix(0.35).stroke_width(4),
                        )))
                        .map_err(e)?;
                }
            }
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))
                .map_err(e)?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(e)?;
        }
        if any_window {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(e)?
                .label("light bars: safe windows above it")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], SAFE.stroke_width(3)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(150, 150, 150))
            .label_font((FONT, 16))
            .draw()
            .map_err(e)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_figures_draw_as_svg() {
        let fig = SpectrumFigure {
            title: "t".into(),
            subtitle: "s".into(),
            series: vec![SpectrumSeries {
                label: "B/H = 0.2".into(),
                points: vec![(1.0, 0.3, EndState::Rest), (3.0, 1.0, EndState::Overturned)],
            }],
        };
        let svg = fig.to_svg().unwrap();
        assert!(svg.contains("B/H = 0.2") && svg.contains("overturned"));
        let over = OverturnScaleFigure {
            title: "t".into(),
            subtitle: "s".into(),
            y_label: "PGA (g)".into(),
            y_max: 2.0,
            series: vec![OverturnSeries {
                label: "B/H = 0.2".into(),
                points: vec![(1.0, Some(0.5), vec![(0.7, Some(0.9))]), (3.0, None, vec![])],
            }],
        };
        assert!(over.to_svg().unwrap().contains("safe windows above it"));
        assert_eq!(log_range([f64::NAN, -1.0].into_iter(), (0.1, 10.0)), (0.1, 10.0));
    }
}
