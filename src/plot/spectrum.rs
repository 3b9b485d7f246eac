//! The power spectrum: PSD on a logarithmic axis against ω/Ω_h, with the
//! dominant peaks marked by their harmonic number.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::hues;
use super::style::Frame;
use super::{FONT, Figure, PlotError, titled};
use crate::analysis::spectrum::Peak;

/// Dynamic range shown below the highest bin (twelve decades: beyond that
/// lies rounding noise of a double-precision signal).
const DECADES: f64 = 12.0;

/// The data of a spectrum figure.
#[derive(Clone, Debug)]
pub struct SpectrumFigure<'a> {
    /// First title line.
    pub title: String,
    /// Second title line (window, taper).
    pub subtitle: String,
    /// ω/Ω_h of each bin.
    pub harmonic: &'a [f64],
    /// PSD of each bin, Θ² per (cycle per unit τ).
    pub psd: &'a [f64],
    /// Peaks to mark.
    pub peaks: &'a [Peak],
    /// Right end of the axis in ω/Ω_h (e.g. 4: the first four harmonics).
    pub max_harmonic: f64,
}

impl Figure for SpectrumFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 700)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let x1 = if self.max_harmonic.is_finite() && self.max_harmonic > 0.0 {
            self.max_harmonic
        } else {
            self.harmonic
                .iter()
                .copied()
                .filter(|h| h.is_finite())
                .fold(1.0, f64::max)
        };
        let shown = || {
            self.harmonic
                .iter()
                .zip(self.psd)
                .filter(move |(h, p)| h.is_finite() && p.is_finite() && **h <= x1)
        };
        let top = shown().fold(0.0_f64, |a, (_, p)| a.max(*p));
        let top = if top > 0.0 { top } else { 1.0 };
        let floor = top * 10f64.powf(-DECADES);
        let (y0, y1) = (floor, top * 10.0);
        let frame = Frame::whole((52, 90));
        let mut chart = frame.chart(&area, None, 0.0..x1, (y0..y1).log_scale())?;
        frame
            .grid(&mut chart)
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(e)?;
        frame.titles(
            root,
            &chart,
            (
                "ω/Ω_h (ω = 2πf in units of p; 1 = the forcing frequency)",
                "PSD of Θ (per cycle per unit τ)",
            ),
        )?;
        chart
            .draw_series(LineSeries::new(
                shown().map(|(h, p)| (*h, p.max(floor))),
                hues::BLUE.stroke_width(1),
            ))
            .map_err(e)?;
        let red = RGBColor(200, 40, 40);
        for p in self.peaks.iter().filter(|p| p.harmonic <= x1 && p.psd > floor) {
            chart
                .draw_series(std::iter::once(Circle::new((p.harmonic, p.psd), 4, red.filled())))
                .map_err(e)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{:.3}", p.harmonic),
                    (p.harmonic, p.psd * 2.5),
                    (FONT, 15).into_font().color(&red),
                )))
                .map_err(e)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frequency_axis_shows_its_subscript_not_an_underscore() {
        let harmonic: Vec<f64> = (0..50).map(|k| f64::from(k) * 0.1).collect();
        let psd: Vec<f64> = harmonic
            .iter()
            .map(|h| 1e-3 / (1.0 + (h - 1.0).powi(2) * 100.0))
            .collect();
        let fig = SpectrumFigure {
            title: "t".into(),
            subtitle: "Ω_h = Ω_v = 8".into(),
            harmonic: &harmonic,
            psd: &psd,
            peaks: &[],
            max_harmonic: 4.0,
        };
        let svg = fig.to_svg().unwrap();
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "power spectrum");
    }
}
