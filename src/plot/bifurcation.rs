//! The bifurcation diagram: Poincaré points of Θ against the swept
//! parameter, small dots coloured by response class; tumbled (and flight)
//! values are left blank, as in the paper, and marked by a shaded band.

use std::collections::BTreeSet;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::labels::{legend_entries, response_colour, response_label};
use super::style::{Frame, Legend};
use super::{Figure, PlotError, padded_range, titled};
use crate::analysis::classify::Response;

/// The data of a bifurcation diagram.
#[derive(Clone, Debug)]
pub struct BifurcationFigure<'a> {
    /// First title line (what is swept and the fixed parameters).
    pub title: String,
    /// Second title line (what the points are: section, window).
    pub subtitle: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label: what Θ is ([`section_theta`](super::labels::section_theta)).
    pub y_label: &'static str,
    /// Every swept value with its response, increasing.
    pub values: &'a [(f64, Response)],
    /// The points: (value, Θ) for every kept section point.
    pub points: &'a [(f64, f64)],
    /// The sweep step (width of a tumbled value's band).
    pub step: f64,
}

/// Light red of a tumbled value's band.
const TUMBLED_BAND: RGBColor = RGBColor(250, 205, 205);
/// Light pink of a flight value's band.
const FLIGHT_BAND: RGBColor = RGBColor(240, 215, 240);

impl BifurcationFigure<'_> {
    /// The points to draw: non-finite ones dropped, and duplicates within a
    /// fraction of a pixel at one value dropped (a period-k response repeats
    /// its k points hundreds of times; drawing them once keeps the SVG
    /// small and changes no pixel).
    fn drawn_points(&self, y_range: (f64, f64)) -> Vec<(f64, f64, Response)> {
        let cell = (y_range.1 - y_range.0) / 20_000.0;
        let mut out: Vec<(f64, f64, Response)> = Vec::new();
        let mut vi = 0;
        let mut seen: BTreeSet<i64> = BTreeSet::new();
        let mut current = f64::NAN;
        for &(value, theta) in self.points.iter().filter(|(v, t)| v.is_finite() && t.is_finite()) {
            if value != current {
                current = value;
                seen.clear();
            }
            let key = ((theta - y_range.0) / cell).round() as i64;
            if !seen.insert(key) {
                continue;
            }
            while vi + 1 < self.values.len() && self.values[vi].0 < value {
                vi += 1;
            }
            let response = match self.values.get(vi) {
                Some(&(v, r)) if v == value => r,
                _ => Response::Chaotic,
            };
            out.push((value, theta, response));
        }
        out
    }
}

impl Figure for BifurcationFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let area = titled(root, &self.title, &self.subtitle)?;
        let e = PlotError::from_display;
        let half = 0.5 * self.step.max(0.0);
        let (x0, x1) = match (self.values.first(), self.values.last()) {
            (Some(a), Some(b)) => (a.0 - half.max(1e-9), b.0 + half.max(1e-9)),
            _ => (0.0, 1.0),
        };
        let (y0, y1) = padded_range(self.points.iter().map(|p| p.1), 0.05, 0.02, (-1.0, 1.0));
        let frame = Frame::whole((56, 80));
        let mut chart = frame.chart(&area, None, x0..x1, y0..y1)?;
        frame.grid(&mut chart).draw().map_err(e)?;
        frame.titles(root, &chart, (self.x_label.as_str(), self.y_label))?;

        for (band, colour, label) in [
            (Response::Tumbled, TUMBLED_BAND, "tumbled (blank)"),
            (Response::Flight, FLIGHT_BAND, "flight (blank)"),
        ] {
            let xs: Vec<f64> = self
                .values
                .iter()
                .filter(|(_, r)| *r == band)
                .map(|(v, _)| *v)
                .collect();
            if xs.is_empty() {
                continue;
            }
            chart
                .draw_series(
                    xs.iter()
                        .map(|&v| Rectangle::new([(v - half, y0), (v + half, y1)], colour.filled())),
                )
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 16, y + 6)], colour.filled()));
        }
        let y_zero = [(x0, 0.0), (x1, 0.0)];
        chart
            .draw_series(std::iter::once(PathElement::new(y_zero, RGBColor(160, 160, 160))))
            .map_err(e)?;

        let pts = self.drawn_points((y0, y1));
        // Small dots, as in the paper; larger when there are few of them
        // (a diagram of mostly periodic values), so that the branches show.
        let radius = if pts.len() <= 20_000 { 2 } else { 1 };
        for key in legend_entries(self.values.iter().map(|v| v.1).filter(|r| !r.is_terminal())) {
            let colour = response_colour(key);
            let group: Vec<(f64, f64)> = pts
                .iter()
                .filter(|p| super::labels::legend_key(p.2) == key)
                .map(|p| (p.0, p.1))
                .collect();
            chart
                .draw_series(group.iter().map(|&p| Circle::new(p, radius, colour.filled())))
                .map_err(e)?
                .label(response_label(key))
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
        }
        Legend {
            fill: 0.85,
            ..Legend::at(SeriesLabelPosition::UpperLeft, 16)
        }
        .draw(&mut chart)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parameter_and_section_labels_show_subscripts_not_underscores() {
        let values = [
            (0.0, Response::Periodic { period: 1 }),
            (1.0, Response::Periodic { period: 2 }),
        ];
        let points = [(0.0, 0.01), (1.0, 0.02), (1.0, -0.02)];
        let fig = BifurcationFigure {
            title: "Bifurcation diagram over A_v".into(),
            subtitle: "Ω_h = Ω_v = 8".into(),
            x_label: crate::plot::labels::param_label(crate::sim::Param::Av),
            y_label: crate::plot::labels::section_theta(&crate::sim::Scenario::default()),
            values: &values,
            points: &points,
            step: 1.0,
        };
        let svg = fig.to_svg().unwrap();
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "bifurcation");
    }
}
