//! Fragility curves: two panels, P(overturning) and P(θ/α ≥ threshold)
//! against the intensity measure; per block (a colour and a marker shape
//! each) the observed fractions as markers, the fitted lognormal curve as a
//! line and its pointwise 95 % band shaded.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::marks::{colour, legend_entry, marker};
use super::style::{Frame, Legend};
use super::{Figure, PlotError, titled};

/// Each panel's frame: 50 px below and 64 px left of its plotting area
/// for numbers and titles.
const FRAME: Frame = Frame::panel((50, 64));
use crate::analysis::engineering::lognormal::BandPoint;

/// One block in one panel.
#[derive(Clone, Debug)]
pub(crate) struct FragilityCurve {
    /// Legend text (the block and its fit).
    pub label: String,
    /// Observed (level, fraction).
    pub observed: Vec<(f64, f64)>,
    /// The fitted curve with its band, increasing level; empty without a fit.
    pub fitted: Vec<BandPoint>,
}

/// One panel.
#[derive(Clone, Debug)]
pub(crate) struct FragilityPanel {
    /// Panel caption.
    pub caption: String,
    /// Its curves, one per block.
    pub curves: Vec<FragilityCurve>,
}

/// The figure.
#[derive(Clone, Debug)]
pub(crate) struct FragilityFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// Largest level (the axis ends a little beyond).
    pub x_max: f64,
    /// The panels.
    pub panels: Vec<FragilityPanel>,
}

impl Figure for FragilityFigure {
    fn size(&self) -> (u32, u32) {
        (1600, 800)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let x1 = if self.x_max.is_finite() && self.x_max > 0.0 {
            self.x_max * 1.05
        } else {
            1.0
        };
        let cells = area.split_evenly((1, self.panels.len().max(1)));
        for (panel, cell) in self.panels.iter().zip(cells.iter()) {
            let mut chart = FRAME.chart(cell, Some(panel.caption.as_str()), 0.0..x1, 0.0..1.02)?;
            FRAME.grid(&mut chart).draw().map_err(e)?;
            FRAME.titles(root, &chart, (self.x_label.as_str(), "probability"))?;
            for (i, curve) in panel.curves.iter().enumerate() {
                let c = colour(i);
                // Earlier blocks' markers larger: fractions of 0 and 1 are
                // shared by many blocks, and each must show around the
                // later ones drawn over it.
                let r = 4 + 2 * (panel.curves.len() - 1 - i).min(3) as i32;
                let fitted: Vec<&BandPoint> = curve
                    .fitted
                    .iter()
                    .filter(|b| [b.level, b.p, b.lo, b.hi].iter().all(|v| v.is_finite()))
                    .collect();
                let has_fit = fitted.len() >= 2;
                if has_fit {
                    let band: Vec<(f64, f64)> = fitted
                        .iter()
                        .map(|b| (b.level, b.hi))
                        .chain(fitted.iter().rev().map(|b| (b.level, b.lo)))
                        .collect();
                    chart
                        .draw_series(std::iter::once(Polygon::new(band, c.mix(0.15).filled())))
                        .map_err(e)?;
                    chart
                        .draw_series(LineSeries::new(
                            fitted.iter().map(|b| (b.level, b.p)),
                            c.stroke_width(2),
                        ))
                        .map_err(e)?;
                }
                chart
                    .draw_series(
                        curve
                            .observed
                            .iter()
                            .filter(|p| p.0.is_finite() && p.1.is_finite())
                            .map(|&p| marker(i, p, r)),
                    )
                    .map_err(e)?
                    .label(curve.label.as_str())
                    .legend(move |at| legend_entry(i, at, has_fit));
            }
            Legend::at(SeriesLabelPosition::LowerRight, 14).draw(&mut chart)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_as_svg() {
        let band = |level: f64, p: f64| BandPoint {
            level,
            p,
            lo: p * 0.8,
            hi: (p * 1.2).min(1.0),
        };
        let fig = FragilityFigure {
            title: "t".into(),
            subtitle: "s".into(),
            x_label: "PGA (g)".into(),
            x_max: 1.0,
            panels: vec![FragilityPanel {
                caption: "overturning".into(),
                curves: vec![FragilityCurve {
                    label: "0.6 × 2.0 m".into(),
                    observed: vec![(0.5, 0.2), (1.0, 0.9)],
                    fitted: vec![band(0.5, 0.25), band(1.0, 0.85)],
                }],
            }],
        };
        assert!(fig.to_svg().unwrap().contains("0.6 × 2.0 m"));
    }

    #[test]
    fn each_block_has_its_own_marker_shape_and_the_subtitle_its_subscripts() {
        let curve = |label: &str| FragilityCurve {
            label: label.into(),
            observed: vec![(0.2, 0.0), (0.6, 1.0)],
            fitted: vec![],
        };
        let fig = FragilityFigure {
            title: "t".into(),
            subtitle: "μ_s = 0.5, μ_k = 0.5; markers: fraction of records".into(),
            x_label: "PGA (g)".into(),
            x_max: 0.6,
            panels: vec![FragilityPanel {
                caption: "overturning".into(),
                curves: vec![curve("0.6 × 2 m"), curve("0.3 × 1.2 m")],
            }],
        };
        let svg = fig.to_svg().unwrap();
        // Block 1's markers are orange squares (block 0's blue discs).
        assert!(
            svg.lines().any(|l| l.starts_with("<rect") && l.contains("#FF7F0E")),
            "block 1 has no square marker"
        );
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "fragility");
    }
}
