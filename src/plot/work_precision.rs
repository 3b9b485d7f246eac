//! The work–precision diagram: error against run time on log–log axes, one
//! line per method, one panel per scene (as in DifferentialEquations.jl's
//! benchmarks).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::hues;
use super::marks::{Marker, shape};
use super::style::Frame;
use super::style::Legend;
use super::ticks::{log_axis, tick_label};
use super::{Figure, PlotError, titled};

/// Each scene's panel: smaller than [`Frame::panel`] (12 px margin, 14 px
/// numbers, 16 px titles), as four or more panels share the figure.
const FRAME: Frame = Frame {
    margin: 12,
    label_areas: (44, 70),
    tick_size: 14,
    title_size: 16.0,
};

/// One point of a work–precision curve, as the figure draws it: the
/// benchmark (`bench`) measures it, the figure needs no more of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkPoint<'a> {
    /// Scene name: the panel it is drawn in.
    pub scene: &'a str,
    /// Method name (`dop853`, `dopri5`, `ralston`, `taylor`): its line.
    pub method: &'a str,
    /// Median wall time of the repeats, s (x axis).
    pub wall_s: f64,
    /// Max-norm error of (Θ, Θ', X') at τ_end against the reference (y
    /// axis).
    pub error: f64,
}

/// The points to draw and the scenes in panel order.
#[derive(Clone, Debug)]
pub(crate) struct WorkPrecisionFigure<'a> {
    /// Every point.
    pub points: &'a [WorkPoint<'a>],
    /// Scene names, one panel each.
    pub scenes: Vec<String>,
}

const METHODS: [(&str, RGBColor); 4] = [
    ("dop853", hues::BLUE),
    ("dopri5", hues::GREEN),
    ("ralston", hues::RED),
    ("taylor", hues::PURPLE),
];

fn log_range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.filter(|x| x.is_finite() && *x > 0.0) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if lo > hi { (1e-6, 1.0) } else { (lo / 2.0, hi * 2.0) }
}

impl Figure for WorkPrecisionFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1400, 1000)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(
            root,
            "Work–precision: error at τ_end vs solver wall time",
            "median of repeats; DOP853, DOPRI5, Taylor at rtol 1e-2 … 1e-13, Ralston (the paper's) at steps 0.004 … 0.00025",
        )?;
        let cols = 2;
        let rows = self.scenes.len().div_ceil(cols).max(1);
        let panels = area.split_evenly((rows, cols));
        for (scene, panel) in self.scenes.iter().zip(panels.iter()) {
            let recs: Vec<&WorkPoint> = self.points.iter().filter(|r| r.scene == scene.as_str()).collect();
            let (x0, x1) = log_range(recs.iter().map(|r| r.wall_s));
            let (y0, y1) = log_range(recs.iter().map(|r| r.error.max(1e-16)));
            let mut chart = FRAME.chart(
                panel,
                Some(&format!("scene: {scene}")),
                log_axis(x0..x1),
                log_axis(y0..y1),
            )?;
            FRAME
                .grid(&mut chart)
                .x_label_formatter(&|v| tick_label(*v))
                .y_label_formatter(&|v| tick_label(*v))
                .draw()
                .map_err(e)?;
            FRAME.titles(
                root,
                &chart,
                ("solver wall time (s)", "max error of Θ, Θ', X' at τ_end"),
            )?;
            for (k, (method, colour)) in METHODS.into_iter().enumerate() {
                let mut pts: Vec<(f64, f64)> = recs
                    .iter()
                    .filter(|r| r.method == method && r.wall_s > 0.0)
                    .map(|r| (r.wall_s, r.error.max(1e-16)))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                chart
                    .draw_series(LineSeries::new(pts.iter().copied(), colour.stroke_width(2)))
                    .map_err(e)?
                    .label(method)
                    .legend(move |(x, y)| Marker {
                        at: (x + 10, y),
                        shape: shape(k),
                        colour,
                        r: 4,
                        line: true,
                    });
                chart
                    .draw_series(pts.iter().map(|&at| Marker {
                        at,
                        shape: shape(k),
                        colour,
                        r: 4,
                        line: false,
                    }))
                    .map_err(e)?;
            }
            Legend {
                frame: BLACK,
                // Middle right: where this figure's legend has always sat (plotters' default).
                ..Legend::at(SeriesLabelPosition::MiddleRight, 15)
            }
            .draw(&mut chart)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn narrow_log_axes_are_numbered_methods_have_their_own_markers_and_no_underscore_shows() {
        // Wall times within a factor of 3 and errors within a decade: no
        // power of ten inside either padded axis.
        let record = |method: &'static str, wall_s: f64, error: f64| WorkPoint {
            scene: "rack",
            method,
            wall_s,
            error,
        };
        let records = [
            record("dop853", 0.0021, 2.1e-7),
            record("dop853", 0.0035, 3.5e-7),
            record("dopri5", 0.0025, 2.5e-7),
            record("dopri5", 0.0031, 4.1e-7),
        ];
        let fig = WorkPrecisionFigure {
            points: &records,
            scenes: vec!["rack".into()],
        };
        let svg = fig.to_svg().unwrap();
        crate::plot::svg_text::assert_numbered(&svg, "work-precision");
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        // dopri5 (the second method) is drawn with squares.
        assert!(
            svg.lines().any(|l| l.starts_with("<rect") && l.contains("#2CA02C")),
            "dopri5 has no square marker"
        );
    }
}
