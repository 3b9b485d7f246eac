//! Incremental curves of a fragility study (incremental dynamic analysis):
//! one panel per block, one curve per record, the peak rotation θ/α on the
//! x-axis against the intensity level on the y-axis, as the IDA literature
//! draws them (Vamvatsikos & Cornell 2002). A run that overturned is drawn
//! at the overturning angle with a cross, a flight there with a triangle.
//! The curve goes on above an overturning level: a rocking block that
//! overturns at one level may survive a stronger one (the safe windows of
//! `spectrum --overturn-scale`), and the figure must show it.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::marks::{colour, marker};
use super::style::{Frame, Legend};
use super::{Figure, PlotError, titled};
use crate::analysis::engineering::EndState;

/// Each panel's frame: 50 px below and 64 px left of its plotting area
/// for numbers and titles.
const FRAME: Frame = Frame::panel((50, 64));

/// Most records named in the legend (of the first panel): beyond it the
/// legend would cover the curves, and incremental.csv names each.
const MAX_LEGEND: usize = 12;

/// Most panels in one row; more blocks wrap onto further rows.
const PANELS_PER_ROW: usize = 3;

/// One record's curve in one panel: (level, peak θ/α, end) in increasing
/// level.
#[derive(Clone, Debug)]
pub(crate) struct IncrementalCurve {
    /// The record's name.
    pub label: String,
    /// Its runs.
    pub points: Vec<(f64, f64, EndState)>,
}

/// One block's panel.
#[derive(Clone, Debug)]
pub(crate) struct IncrementalPanel {
    /// Caption (the block).
    pub caption: String,
    /// One curve per record.
    pub curves: Vec<IncrementalCurve>,
}

/// The figure.
#[derive(Clone, Debug)]
pub(crate) struct IncrementalFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Largest level (the axis ends a little beyond).
    pub y_max: f64,
    /// The overturning angle θ/α (`run.tumble_theta`), where overturned
    /// runs are drawn.
    pub overturn_at: f64,
    /// One panel per block.
    pub panels: Vec<IncrementalPanel>,
}

impl Figure for IncrementalFigure {
    fn size(&self) -> (u32, u32) {
        let rows = self.panels.len().div_ceil(PANELS_PER_ROW).max(1) as u32;
        let cols = self.panels.len().clamp(1, PANELS_PER_ROW) as u32;
        (560 * cols + 80, 120 + 560 * rows)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let y1 = if self.y_max.is_finite() && self.y_max > 0.0 {
            self.y_max * 1.05
        } else {
            1.0
        };
        let x1 = if self.overturn_at.is_finite() && self.overturn_at > 0.0 {
            self.overturn_at * 1.1
        } else {
            1.1
        };
        let rows = self.panels.len().div_ceil(PANELS_PER_ROW).max(1);
        let cols = self.panels.len().clamp(1, PANELS_PER_ROW);
        let cells = area.split_evenly((rows, cols));
        for (k, (panel, cell)) in self.panels.iter().zip(cells.iter()).enumerate() {
            let first = k == 0;
            let mut chart = FRAME.chart(cell, Some(panel.caption.as_str()), 0.0..x1, 0.0..y1)?;
            FRAME.grid(&mut chart).draw().map_err(e)?;
            FRAME.titles(root, &chart, ("peak rotation θ/α", self.y_label.as_str()))?;
            // The overturning angle, where the curves end.
            chart
                .draw_series(LineSeries::new(
                    [(self.overturn_at, 0.0), (self.overturn_at, y1)],
                    RGBColor(180, 0, 0).stroke_width(1),
                ))
                .map_err(e)?;
            for (i, curve) in panel.curves.iter().enumerate() {
                let c = colour(i);
                let at = |&(level, peak, end): &(f64, f64, EndState)| {
                    let x = if end.survived() {
                        peak.min(self.overturn_at)
                    } else {
                        self.overturn_at
                    };
                    (x, level)
                };
                let points: Vec<((f64, f64), EndState)> = curve
                    .points
                    .iter()
                    .map(|p| (at(p), p.2))
                    .filter(|((x, y), _)| x.is_finite() && y.is_finite())
                    .collect();
                let line = chart
                    .draw_series(LineSeries::new(points.iter().map(|p| p.0), c.stroke_width(2)))
                    .map_err(e)?;
                if first && panel.curves.len() <= MAX_LEGEND {
                    line.label(curve.label.as_str())
                        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], c.stroke_width(2)));
                }
                chart
                    .draw_series(points.iter().filter(|p| p.1.survived()).map(|p| marker(i, p.0, 3)))
                    .map_err(e)?;
                chart
                    .draw_series(
                        points
                            .iter()
                            .filter(|p| p.1 == EndState::Overturned)
                            .map(|p| Cross::new(p.0, 7, c.stroke_width(3))),
                    )
                    .map_err(e)?;
                chart
                    .draw_series(
                        points
                            .iter()
                            .filter(|p| p.1 == EndState::Flight)
                            .map(|p| TriangleMarker::new(p.0, 7, c.filled())),
                    )
                    .map_err(e)?;
            }
            if first && panel.curves.len() <= MAX_LEGEND {
                Legend::at(SeriesLabelPosition::LowerRight, 13).draw(&mut chart)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overturned_runs_are_crossed_at_the_overturning_angle_and_the_curve_goes_on_above() {
        let fig = IncrementalFigure {
            title: "Incremental curves".into(),
            subtitle: "s".into(),
            y_label: "PGA (g)".into(),
            y_max: 0.6,
            overturn_at: 1.0,
            panels: vec![IncrementalPanel {
                caption: "0.6 × 2 m".into(),
                curves: vec![IncrementalCurve {
                    label: "elcentro".into(),
                    points: vec![
                        (0.2, 0.0, EndState::Rest),
                        (0.4, 0.35, EndState::Rest),
                        (0.5, 1.0, EndState::Overturned),
                        (0.6, 0.2, EndState::Rest),
                    ],
                }],
            }],
        };
        let svg = fig.to_svg().unwrap();
        assert!(svg.contains("peak rotation θ/α"));
        crate::plot::svg_text::assert_numbered(&svg, "incremental");
        // One polyline through all four runs, the survival at 0.6 g above
        // the overturning at 0.5 g included.
        let blue = svg
            .lines()
            .filter(|l| l.starts_with("<polyline") && l.contains("#1F77B4"))
            .map(|l| l.matches(',').count())
            .max()
            .unwrap_or(0);
        assert_eq!(blue, 4, "{svg}");
    }
}
