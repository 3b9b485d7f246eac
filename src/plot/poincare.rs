//! The Poincaré map: the stroboscopic points (Θ, Θ') as small dots.

use std::collections::BTreeSet;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::style::Frame;
use super::{FONT, Figure, PlotError, padded_range, titled};

/// The data of a Poincaré-map figure.
#[derive(Clone, Debug)]
pub struct PoincareFigure<'a> {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// The points (Θ, Θ') at τ_k = 2πk/Ω_h.
    pub points: &'a [(f64, f64)],
}

impl Figure for PoincareFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 900)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let (x0, x1) = padded_range(self.points.iter().map(|p| p.0), 0.08, 0.02, (-1.0, 1.0));
        let (y0, y1) = padded_range(self.points.iter().map(|p| p.1), 0.08, 0.02, (-1.0, 1.0));
        let frame = Frame::whole((52, 80));
        let mut chart = frame.chart(&area, None, x0..x1, y0..y1)?;
        // Titles without subscripts: plotters' own axis descriptions.
        frame
            .grid(&mut chart)
            .x_desc("Θ = θ/ψ")
            .y_desc("Θ' = dΘ/dτ")
            .axis_desc_style((FONT, 19))
            .draw()
            .map_err(e)?;
        // Points closer than a small fraction of a pixel are drawn once (a
        // periodic response repeats its k points hundreds of times), and a
        // handful of distinct points (a periodic response) is drawn larger so
        // that it shows.
        let (cx, cy) = ((x1 - x0) / 10_000.0, (y1 - y0) / 10_000.0);
        let mut keys: BTreeSet<(i64, i64)> = BTreeSet::new();
        let mut dots: Vec<(f64, f64)> = Vec::new();
        for &(x, y) in self.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
            let key = (((x - x0) / cx).round() as i64, ((y - y0) / cy).round() as i64);
            if keys.insert(key) {
                dots.push((x, y));
            }
        }
        let radius = if dots.len() <= 64 { 5 } else { 2 };
        chart
            .draw_series(
                dots.iter()
                    .map(|&p| Circle::new(p, radius, RGBColor(20, 20, 20).filled())),
            )
            .map_err(e)?;
        Ok(())
    }
}
