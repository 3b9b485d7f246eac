//! The outcome map: one coloured cell per (x, y) pair, by response class
//! (with a legend) or by largest Lyapunov exponent (with a colour bar).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::hues;
use super::labels::{legend_entries, legend_key, response_colour, response_label};
use super::style::Frame;
use super::{FONT, Figure, PlotError, titled};
use crate::analysis::attractor::Attractor;
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
    /// A basin map's attractors: each cell's attractor number (row order)
    /// and the attractors; periodic cells are then coloured by attractor,
    /// the legend naming each by its period and representative point.
    pub basins: Option<Basins<'a>>,
}

/// The attractors of a basin map, for its colours and legend.
#[derive(Clone, Copy, Debug)]
pub struct Basins<'a> {
    /// Each cell's attractor number (from 1), row order.
    pub ids: &'a [Option<u32>],
    /// The attractors, numbered 1, 2, ….
    pub attractors: &'a [Attractor],
}

/// Colours of attractors 1, 2, … (cycled beyond ten): a qualitative set
/// that avoids the grey of rest, the near-black of tumbling and the red
/// of chaos.
const ATTRACTOR_COLOURS: [RGBColor; 10] = [
    hues::BLUE,
    hues::GREEN,
    hues::ORANGE,
    hues::PURPLE,
    hues::CYAN,
    hues::BROWN,
    hues::OLIVE,
    hues::PINK,
    hues::LIGHT_BLUE,
    hues::LIGHT_GREEN,
];

/// The colour of attractor `id` (from 1): the figure's, and the app's
/// map panel's, so that the two agree.
pub(crate) fn attractor_colour(id: u32) -> RGBColor {
    ATTRACTOR_COLOURS[(id.max(1) as usize - 1) % ATTRACTOR_COLOURS.len()]
}

/// The legend text of an attractor: `A2: period 2, Θ = 0.3125, Θ' = -0.0513`.
pub fn attractor_label(a: &Attractor) -> String {
    format!(
        "A{}: period {}, Θ = {:.4}, Θ' = {:.4}",
        a.id, a.period, a.point[0], a.point[1]
    )
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

    fn colour(&self, c: usize, scale: f64) -> RGBColor {
        let cell = &self.cells[c];
        match (self.colouring, cell.1) {
            (MapColouring::Lyapunov, Some(l)) if l.is_finite() => diverging(l, scale),
            _ => match self.basins.and_then(|b| b.ids.get(c).copied().flatten()) {
                Some(id) => attractor_colour(id),
                None => response_colour(cell.0),
            },
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
        let frame = Frame::whole((56, 80));
        let mut chart = frame.chart(&plot_area, None, x0..x1, y0..y1)?;
        // No grid: the cells fill the plotting area.
        frame.grid(&mut chart).disable_mesh().draw().map_err(e)?;
        frame.titles(root, &chart, (self.x_label.as_str(), self.y_label.as_str()))?;
        let scale = self.lyapunov_scale();
        let nx = self.x.len();
        // One rectangle per run of equal colour along a row: a 1000 × 1000
        // map is a few thousand shapes, not a million, in the SVG.
        let mut runs = Vec::new();
        for j in 0..self.y.len() {
            let mut start = 0;
            while start < nx {
                let colour = self.colour(j * nx + start, scale);
                let mut end = start + 1;
                while end < nx && self.colour(j * nx + end, scale) == colour {
                    end += 1;
                }
                runs.push(Rectangle::new(
                    [(xe[start], ye[j]), (xe[end], ye[j + 1])],
                    colour.filled(),
                ));
                start = end;
            }
        }
        chart.draw_series(runs).map_err(e)?;

        // Legend: the classes present, then (for λ colouring) a colour bar.
        let text = (FONT, 17).into_font().color(&BLACK);
        let mut row = 30;
        let in_basin = |c: usize| self.basins.is_some_and(|b| b.ids.get(c).copied().flatten().is_some());
        let classes = legend_entries(
            self.cells
                .iter()
                .enumerate()
                .filter(|&(c, _)| !in_basin(c))
                .map(|(_, cell)| cell.0),
        );
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
        if let (Some(b), MapColouring::Outcome) = (self.basins, self.colouring) {
            let small = (FONT, 14).into_font().color(&BLACK);
            for a in b.attractors {
                legend_area
                    .draw(&Rectangle::new(
                        [(10, row), (34, row + 20)],
                        attractor_colour(a.id).filled(),
                    ))
                    .map_err(e)?;
                legend_area
                    .draw(&Rectangle::new([(10, row), (34, row + 20)], BLACK.stroke_width(1)))
                    .map_err(e)?;
                legend_area
                    .draw(&Text::new(attractor_label(a), (42, row + 3), small.clone()))
                    .map_err(e)?;
                row += 30;
            }
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
            basins: None,
        };
        let svg = fig.to_svg().unwrap();
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "outcome map");
    }
}
