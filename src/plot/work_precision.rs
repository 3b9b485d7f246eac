//! The work–precision diagram: error against run time on log–log axes, one
//! line per method, one panel per scene (as in DifferentialEquations.jl's
//! benchmarks).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{FONT, Figure, PlotError, titled};
use crate::bench::Record;

/// The records to draw and the scenes in panel order.
#[derive(Clone, Debug)]
pub struct WorkPrecisionFigure<'a> {
    /// Every record.
    pub records: &'a [Record],
    /// Scene names, one panel each.
    pub scenes: Vec<String>,
}

const METHODS: [(&str, RGBColor); 4] = [
    ("dop853", RGBColor(31, 119, 180)),
    ("dopri5", RGBColor(44, 160, 44)),
    ("ralston", RGBColor(214, 39, 40)),
    ("taylor", RGBColor(148, 103, 189)),
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
            let recs: Vec<&Record> = self.records.iter().filter(|r| &r.scene == scene).collect();
            let (x0, x1) = log_range(recs.iter().map(|r| r.wall_s));
            let (y0, y1) = log_range(recs.iter().map(|r| r.error.max(1e-16)));
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("scene: {scene}"), (FONT, 20))
                .margin(12)
                .x_label_area_size(44)
                .y_label_area_size(70)
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(e)?;
            chart
                .configure_mesh()
                .x_desc("solver wall time (s)")
                .y_desc("max error of Θ, Θ', X' at τ_end")
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .label_style((FONT, 14))
                .axis_desc_style((FONT, 16))
                .light_line_style(RGBColor(238, 238, 238))
                .draw()
                .map_err(e)?;
            for (method, colour) in METHODS {
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
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                    .map_err(e)?;
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.9))
                .border_style(BLACK)
                .label_font((FONT, 15))
                .draw()
                .map_err(e)?;
        }
        Ok(())
    }
}
