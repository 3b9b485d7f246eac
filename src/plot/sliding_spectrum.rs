//! The sliding spectrum: two panels against the friction coefficient μ,
//! the peak sliding displacement and the residual (final, signed) one, one
//! line and marker shape per block (the slide-only block, the given
//! block). A run that overturned is marked by a cross of its series'
//! colour at its peak before overturning (it has no residual), flight by a
//! black triangle; a grey vertical line marks μ = PGA/g, above which the
//! slide-only block never slips, and one in the given block's colour
//! μ = tan α, above which that block cannot slide flat (it rocks first).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::marks::{MARK, colour, flight_legend, legend_entry, marker, overturned_legend};
use super::style::{Frame, Legend};
use super::{Figure, PlotError, padded_range, titled};
use crate::analysis::engineering::EndState;

/// Each panel's frame: 50 px below and 84 px left of its plotting area
/// for numbers and titles (millimetre numbers such as 0.0125 need the
/// width).
const FRAME: Frame = Frame::panel((50, 84));

/// One block's curve.
#[derive(Clone, Debug)]
pub(crate) struct SlidingCurve {
    /// Legend text.
    pub label: String,
    /// (μ, peak sliding m, residual sliding m if it exists, end), μ
    /// increasing.
    pub points: Vec<(f64, f64, Option<f64>, EndState)>,
}

/// The figure.
#[derive(Clone, Debug)]
pub(crate) struct SlidingFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// PGA of the motion as run, g (the vertical line μ = PGA/g), if known.
    pub pga_g: Option<f64>,
    /// tan α of the given block (the vertical line μ = tan α in its
    /// colour, above which it cannot slide flat: it rocks first).
    pub tan_alpha: Option<f64>,
    /// The curves (slide-only first).
    pub curves: Vec<SlidingCurve>,
}

impl Figure for SlidingFigure {
    fn size(&self) -> (u32, u32) {
        (1600, 800)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let all = || self.curves.iter().flat_map(|c| c.points.iter());
        let (mut x0, mut x1) = padded_range(all().map(|p| p.0), 0.04, 0.01, (0.0, 1.0));
        x0 = x0.max(0.0);
        if let Some(pga) = self.pga_g.filter(|v| v.is_finite() && *v > x0) {
            // Show the line only where it falls inside the μ range tried
            // (or just beyond it).
            if pga < x1 * 1.25 {
                x1 = x1.max(pga * 1.04);
            }
        }
        let peak_top = all()
            .map(|p| p.1)
            .filter(|v| v.is_finite())
            .fold(0.0_f64, f64::max)
            .max(1e-3)
            * 1.08;
        let (r0, r1) = padded_range(
            all().filter_map(|p| p.2).chain(std::iter::once(0.0)),
            0.06,
            2e-3,
            (-1e-3, 1e-3),
        );
        let cells = area.split_evenly((1, 2));
        let panels: [(&str, &str, (f64, f64), bool); 2] = [
            ("peak", "peak sliding displacement (m)", (0.0, peak_top), false),
            ("residual", "residual sliding displacement (m), +x", (r0, r1), true),
        ];
        for ((caption, y_title, (y0, y1), residual), cell) in panels.into_iter().zip(cells.iter()) {
            let mut chart = FRAME.chart(cell, Some(caption), x0..x1, y0..y1)?;
            FRAME.grid(&mut chart).draw().map_err(e)?;
            FRAME.titles(root, &chart, ("friction coefficient μ", y_title))?;
            if residual {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(x0, 0.0), (x1, 0.0)],
                        MARK.mix(0.5).stroke_width(1),
                    )))
                    .map_err(e)?;
            }
            if let Some(pga) = self.pga_g.filter(|v| v.is_finite() && *v > x0 && *v < x1) {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(pga, y0), (pga, y1)],
                        MARK.mix(0.6).stroke_width(2),
                    )))
                    .map_err(e)?
                    .label(format!("μ = PGA/g = {pga:.3}: the slide-only block never slips above"))
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], MARK.stroke_width(2)));
            }
            if let Some(t) = self.tan_alpha.filter(|v| v.is_finite() && *v > x0 && *v < x1) {
                let c = colour(1);
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(t, y0), (t, y1)],
                        c.mix(0.45).stroke_width(2),
                    )))
                    .map_err(e)?
                    .label(format!(
                        "μ = tan α = {t:.3}: the block rocks rather than slides flat above"
                    ))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.mix(0.45).stroke_width(2)));
            }
            let mut any_overturned = false;
            let mut any_flight = false;
            for (i, curve) in self.curves.iter().enumerate() {
                let c = colour(i);
                let value = |p: &(f64, f64, Option<f64>, EndState)| if residual { p.2 } else { Some(p.1) };
                let shown: Vec<(f64, f64, EndState)> = curve
                    .points
                    .iter()
                    .filter_map(|p| value(p).map(|v| (p.0, v, p.3)))
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .collect();
                any_overturned |= shown.iter().any(|p| p.2 == EndState::Overturned);
                any_flight |= shown.iter().any(|p| p.2 == EndState::Flight);
                // Earlier series' markers larger: where both blocks slide
                // alike, the first still shows around the second.
                let r = 4 + 2 * (self.curves.len() - 1 - i).min(3) as i32;
                chart
                    .draw_series(LineSeries::new(
                        shown.iter().map(|p| (p.0, p.1.clamp(y0, y1))),
                        c.stroke_width(2),
                    ))
                    .map_err(e)?
                    .label(curve.label.as_str())
                    .legend(move |at| legend_entry(i, at, true));
                chart
                    .draw_series(
                        shown
                            .iter()
                            .filter(|p| p.2.survived())
                            .map(|p| marker(i, (p.0, p.1), r)),
                    )
                    .map_err(e)?;
                chart
                    .draw_series(
                        shown
                            .iter()
                            .filter(|p| p.2 == EndState::Overturned)
                            .map(|p| Cross::new((p.0, p.1.clamp(y0, y1)), r + 2, c.stroke_width(3))),
                    )
                    .map_err(e)?;
                chart
                    .draw_series(
                        shown
                            .iter()
                            .filter(|p| p.2 == EndState::Flight)
                            .map(|p| TriangleMarker::new((p.0, p.1.clamp(y0, y1)), 6, BLACK.filled())),
                    )
                    .map_err(e)?;
            }
            if any_overturned {
                overturned_legend(&mut chart, "overturned (× at its peak before, no residual)")?;
            }
            if any_flight {
                flight_legend(&mut chart)?;
            }
            // Sliding falls with μ: the upper right is usually empty.
            Legend::at(SeriesLabelPosition::UpperRight, 14).draw(&mut chart)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_both_panels_with_each_blocks_marker_and_numbered_axes() {
        let fig = SlidingFigure {
            title: "Sliding spectrum".into(),
            subtitle: "μ_k = μ_s".into(),
            pga_g: Some(0.35),
            tan_alpha: Some(0.222),
            curves: vec![
                SlidingCurve {
                    label: "slide-only".into(),
                    points: vec![
                        (0.1, 0.2, Some(-0.1), EndState::Rest),
                        (0.3, 0.01, Some(0.005), EndState::Rest),
                    ],
                },
                SlidingCurve {
                    label: "0.4 × 1.8 m".into(),
                    points: vec![
                        (0.1, 0.15, None, EndState::Overturned),
                        (0.3, 0.0, Some(0.0), EndState::Rest),
                    ],
                },
            ],
        };
        let svg = fig.to_svg().unwrap();
        for text in [
            "slide-only",
            "0.4 × 1.8 m",
            "peak",
            "residual",
            "overturned",
            "PGA/g = 0.350",
        ] {
            assert!(svg.contains(text), "{text}");
        }
        // The second block's markers are orange squares (the first's blue
        // discs).
        assert!(
            svg.lines().any(|l| l.starts_with("<rect") && l.contains("#FF7F0E")),
            "block 1 has no square marker"
        );
        assert_eq!(crate::plot::svg_text::underscores(&svg), Vec::<String>::new());
        crate::plot::svg_text::assert_numbered(&svg, "sliding spectrum");
    }
}
