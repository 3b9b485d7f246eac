//! The outcome map: one coloured cell per (x, y) pair, by response class
//! (with a legend) or by largest Lyapunov exponent (with a colour bar).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::labels::{legend_entries, legend_key, response_colour, response_label};
use super::{FONT, Figure, PlotError, axis_titles, titled};
use crate::analysis::classify::Response;

/// What the cells are coloured by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapColouring {
    /// The response class.
    Outcome,
    /// The largest Lyapunov exponent (blue < 0 < red); cells without one
    /// (tumbled, flight, rest) keep their class colour.
    Lyapunov,
}

/// The data of an outcome map.
#[derive(Clone, Debug)]
pub struct OutcomeMapFigure<'a> {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// x values, increasing.
    pub x: &'a [f64],
    /// y values, increasing.
    pub y: &'a [f64],
    /// Cells in row order (y outer, x inner): response and exponent.
    pub cells: &'a [(Response, Option<f64>)],
    /// Colouring.
    pub colouring: MapColouring,
}

/// Cell edges: halfway between neighbouring values (a single value v gets
/// the cell v ± 10 %, or ±0.5 for v = 0).
fn edges(v: &[f64]) -> Vec<f64> {
    match v {
        [] => Vec::new(),
        [only] => {
            let h = if *only == 0.0 { 0.5 } else { 0.1 * only.abs() };
            vec![only - h, only + h]
        }
        _ => {
            let n = v.len();
            let mut e = Vec::with_capacity(n + 1);
            e.push(v[0] - 0.5 * (v[1] - v[0]));
            for w in v.windows(2) {
                e.push(0.5 * (w[0] + w[1]));
            }
            e.push(v[n - 1] + 0.5 * (v[n - 1] - v[n - 2]));
            e
        }
    }
}

/// Blue–white–red for λ in [−scale, scale].
fn diverging(lambda: f64, scale: f64) -> RGBColor {
    let t = (lambda / scale).clamp(-1.0, 1.0);
    let mix = |a: f64, b: f64, s: f64| (a + (b - a) * s).round() as u8;
    if t < 0.0 {
        let s = -t;
        RGBColor(mix(255.0, 33.0, s), mix(255.0, 102.0, s), mix(255.0, 172.0, s))
    } else {
        RGBColor(mix(255.0, 178.0, t), mix(255.0, 24.0, t), mix(255.0, 43.0, t))
    }
}

impl OutcomeMapFigure<'_> {
    fn lyapunov_scale(&self) -> f64 {
        let m = self
            .cells
            .iter()
            .filter_map(|c| c.1)
            .filter(|l| l.is_finite())
            .fold(0.0_f64, |a, l| a.max(l.abs()));
        if m > 0.0 { m } else { 1.0 }
    }

    fn colour(&self, cell: &(Response, Option<f64>), scale: f64) -> RGBColor {
        match (self.colouring, cell.1) {
            (MapColouring::Lyapunov, Some(l)) if l.is_finite() => diverging(l, scale),
            _ => response_colour(cell.0),
        }
    }
}

impl Figure for OutcomeMapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 900)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let (w, _) = area.dim_in_pixel();
        let (plot_area, legend_area) = area.split_horizontally(w.saturating_sub(260));
        let (xe, ye) = (edges(self.x), edges(self.y));
        let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) = (xe.first(), xe.last(), ye.first(), ye.last()) else {
            return Err(PlotError("an outcome map needs at least one x and one y value".into()));
        };
        if self.cells.len() != self.x.len() * self.y.len() {
            return Err(PlotError(format!(
                "{} cells for {} × {} values",
                self.cells.len(),
                self.x.len(),
                self.y.len()
            )));
        }
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .label_style((FONT, 16))
            .draw()
            .map_err(e)?;
        axis_titles(
            root,
            chart.plotting_area().get_pixel_range(),
            (self.x_label.as_str(), self.y_label.as_str()),
            19.0,
            (56, 80),
        )?;
        let scale = self.lyapunov_scale();
        let nx = self.x.len();
        chart
            .draw_series(self.cells.iter().enumerate().map(|(c, cell)| {
                let (i, j) = (c % nx, c / nx);
                Rectangle::new(
                    [(xe[i], ye[j]), (xe[i + 1], ye[j + 1])],
                    self.colour(cell, scale).filled(),
                )
            }))
            .map_err(e)?;

        // Legend: the classes present, then (for λ colouring) a colour bar.
        let text = (FONT, 17).into_font().color(&BLACK);
        let mut row = 30;
        let classes = legend_entries(self.cells.iter().map(|c| c.0));
        let shown: Vec<Response> = match self.colouring {
            MapColouring::Outcome => classes,
            MapColouring::Lyapunov => classes
                .into_iter()
                .filter(|r| {
                    self.cells
                        .iter()
                        .any(|c| legend_key(c.0) == *r && !c.1.is_some_and(f64::is_finite))
                })
                .collect(),
        };
        legend_area
            .draw(&Text::new(
                match self.colouring {
                    MapColouring::Outcome => "response",
                    MapColouring::Lyapunov => "largest Lyapunov exponent",
                },
                (10, row - 22),
                (FONT, 18).into_font().color(&BLACK),
            ))
            .map_err(e)?;
        for r in shown {
            legend_area
                .draw(&Rectangle::new(
                    [(10, row), (34, row + 20)],
                    response_colour(r).filled(),
                ))
                .map_err(e)?;
            legend_area
                .draw(&Rectangle::new([(10, row), (34, row + 20)], BLACK.stroke_width(1)))
                .map_err(e)?;
            legend_area
                .draw(&Text::new(response_label(r), (42, row + 2), text.clone()))
                .map_err(e)?;
            row += 30;
        }
        if self.colouring == MapColouring::Lyapunov {
            row += 10;
            let steps = 40;
            for s in 0..steps {
                let l = scale * (1.0 - 2.0 * f64::from(s) / f64::from(steps));
                let top = row + s * 6;
                legend_area
                    .draw(&Rectangle::new(
                        [(10, top), (34, top + 6)],
                        diverging(l, scale).filled(),
                    ))
                    .map_err(e)?;
            }
            for (frac, value) in [(0.0, scale), (0.5, 0.0), (1.0, -scale)] {
                let y = row + (frac * f64::from(steps) * 6.0) as i32;
                legend_area
                    .draw(&Text::new(format!("{value:+.3} per τ"), (42, y - 8), text.clone()))
                    .map_err(e)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_edges_are_midpoints() {
        assert_eq!(edges(&[0.0, 1.0, 3.0]), vec![-0.5, 0.5, 2.0, 4.0]);
        assert_eq!(edges(&[2.0]), vec![1.8, 2.2]);
        assert_eq!(edges(&[0.0]), vec![-0.5, 0.5]);
        assert!(edges(&[]).is_empty());
    }

    #[test]
    fn diverging_scale_ends() {
        assert_eq!(diverging(0.0, 1.0), RGBColor(255, 255, 255));
        assert_eq!(diverging(-2.0, 1.0), RGBColor(33, 102, 172));
        assert_eq!(diverging(1.0, 1.0), RGBColor(178, 24, 43));
    }

    #[test]
    fn axis_labels_show_subscripts_not_underscores() {
        let cells = [(Response::Periodic { period: 1 }, None); 4];
        let fig = OutcomeMapFigure {
            title: "Outcome map over A_v × Ω_h".into(),
            subtitle: "s".into(),
            x_label: crate::plot::labels::param_label(crate::sim::Param::Av),
            y_label: crate::plot::labels::param_label(crate::sim::Param::OmegaH),
            x: &[0.0, 1.0],
            y: &[4.0, 8.0],
            cells: &cells,
            colouring: MapColouring::Outcome,
        };
        let svg = fig.to_svg().unwrap();
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "outcome map");
    }
}
