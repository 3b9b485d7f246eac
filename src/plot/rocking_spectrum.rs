//! The rocking spectrum: peak θ/α against the frequency parameter p (log
//! axis, numbered however narrow its range), one line and marker shape per
//! slenderness, overturned blocks marked by crosses of their series' colour
//! on the line θ/α = 1 and flight by black triangles; and the
//! overturning-scale spectrum: the smallest overturning PGA against p, with
//! the safe windows above it as light bars of the series colour.

use plotters::chart::ChartContext;
use plotters::coord::Shift;
use plotters::coord::combinators::{LogCoord, WithKeyPoints};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::marks::{MARK, flight_legend, legend_entry, legend_only, marker, overturned_legend};
use super::style::{Frame, Legend};
use super::ticks::{log_axis, tick_label};
use super::{Figure, PlotError, titled};
use crate::analysis::engineering::EndState;

pub use super::marks::{PALETTE, colour};

/// Title of the p axis, shared by both figures.
const P_AXIS: &str = "p = √(3g/4R), frequency parameter (1/s)";

/// Both figures' frame: 56 px below and 80 px left of the plotting area
/// for numbers and titles.
const FRAME: Frame = Frame::whole((56, 80));

/// `[lo, hi]` of the finite positive values, widened by a factor on each
/// side for a log axis (`default` if none).
pub(crate) fn log_range(values: impl Iterator<Item = f64>, default: (f64, f64)) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi { default } else { (lo / 1.15, hi * 1.15) }
}

/// The chart of both figures on `area`: p over `x` on a log axis numbered
/// however narrow its range, `y_title` from 0 to `y1`, with its frame and
/// titles drawn (on `root`, the figure's whole area).
#[allow(clippy::type_complexity)]
fn p_chart<'a, DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    area: &'a DrawingArea<DB, Shift>,
    x: std::ops::Range<f64>,
    y1: f64,
    y_title: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<WithKeyPoints<LogCoord<f64>>, RangedCoordf64>>, PlotError> {
    let mut chart = FRAME.chart(area, None, log_axis(x), 0.0..y1)?;
    FRAME
        .grid(&mut chart)
        .x_label_formatter(&|v| tick_label(*v))
        .draw()
        .map_err(PlotError::from_display)?;
    FRAME.titles(root, &chart, (P_AXIS, y_title))?;
    Ok(chart)
}

/// One slenderness of a spectrum.
#[derive(Clone, Debug)]
pub struct SpectrumSeries {
    /// Legend text, e.g. `B/H = 0.2`.
    pub label: String,
    /// (p in 1/s, peak θ/α, end), p decreasing or increasing.
    pub points: Vec<(f64, f64, EndState)>,
}

/// The peak-rotation spectrum.
#[derive(Clone, Debug)]
pub struct SpectrumFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// The series.
    pub series: Vec<SpectrumSeries>,
}

impl Figure for SpectrumFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let (x0, x1) = log_range(all().map(|p| p.0), (0.1, 10.0));
        let y1 = all()
            .map(|p| p.1)
            .filter(|v| v.is_finite())
            .fold(1.0_f64, f64::max)
            .min(2.0)
            * 1.08;
        let mut chart = p_chart(root, &area, x0..x1, y1, "peak rotation θ/α")?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x0, 1.0), (x1, 1.0)],
                MARK.mix(0.5).stroke_width(1),
            )))
            .map_err(e)?;
        let mut any_flight = false;
        let mut any_overturned = false;
        for (i, s) in self.series.iter().enumerate() {
            let c = colour(i);
            let mut pts: Vec<(f64, f64, EndState)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            // Smaller marks on a dense series (a spectrum of 200 sizes),
            // whose markers would otherwise merge into a band.
            let r = if pts.len() > 60 { 3 } else { 4 };
            any_flight |= pts.iter().any(|p| p.2 == EndState::Flight);
            any_overturned |= pts.iter().any(|p| p.2 == EndState::Overturned);
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|p| (p.0, p.1.min(y1))),
                    c.stroke_width(2),
                ))
                .map_err(e)?
                .label(s.label.as_str())
                .legend(move |at| legend_entry(i, at, true));
            chart
                .draw_series(pts.iter().filter(|p| p.2.survived()).map(|p| marker(i, (p.0, p.1), r)))
                .map_err(e)?;
            // In the series' own colour, earlier series larger: where blocks
            // of several B/H overturn at the same p (the same R), each cross
            // still shows around the later ones drawn over it.
            let arm = r + 1 + 2 * (self.series.len() - 1 - i).min(4) as i32;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.2 == EndState::Overturned)
                        .map(|p| Cross::new((p.0, p.1.min(y1)), arm, c.stroke_width(3))),
                )
                .map_err(e)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| p.2 == EndState::Flight)
                        .map(|p| TriangleMarker::new((p.0, p.1.min(y1)), 6, BLACK.filled())),
                )
                .map_err(e)?;
        }
        if any_overturned {
            overturned_legend(&mut chart, "overturned (× on θ/α = 1, in its series' colour)")?;
        }
        if any_flight {
            flight_legend(&mut chart)?;
        }
        // Where a spectrum is usually empty: small blocks (high p) overturn
        // at the top, large ones (low p) rock little at the bottom left.
        Legend::at(SeriesLabelPosition::LowerRight, 16).draw(&mut chart)?;
        Ok(())
    }
}

/// One block of an overturning-scale figure: (x, the smallest failing
/// amplitude or `None`, the safe windows above it as (from, to), `to`
/// `None` when open).
pub(crate) type ScalePoint = (f64, Option<f64>, Vec<(f64, Option<f64>)>);

/// One slenderness of an overturning-scale spectrum.
#[derive(Clone, Debug)]
pub(crate) struct OverturnSeries {
    /// Legend text.
    pub label: String,
    /// (p in 1/s, smallest overturning PGA in g, safe windows in g).
    pub points: Vec<ScalePoint>,
}

/// The overturning-scale spectrum.
#[derive(Clone, Debug)]
pub(crate) struct OverturnScaleFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Largest amplitude tried (top of the axis; open windows reach it).
    pub y_max: f64,
    /// The series.
    pub series: Vec<OverturnSeries>,
}

/// Grey of the safe windows' legend entry (each window is drawn in its
/// series' colour, lightened).
const SAFE: RGBColor = RGBColor(160, 160, 160);

impl Figure for OverturnScaleFigure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let area = titled(root, &self.title, &self.subtitle)?;
        let (x0, x1) = log_range(
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
            (0.1, 10.0),
        );
        let y1 = if self.y_max.is_finite() && self.y_max > 0.0 {
            self.y_max * 1.05
        } else {
            1.0
        };
        let mut chart = p_chart(root, &area, x0..x1, y1, &self.y_label)?;
        let mut any_window = false;
        for (i, s) in self.series.iter().enumerate() {
            any_window |= scale_series(&mut chart, i, &s.label, &s.points, (self.y_max, y1), true)?;
        }
        if any_window {
            safe_windows_legend(&mut chart)?;
        }
        Legend::at(SeriesLabelPosition::UpperRight, 16).draw(&mut chart)?;
        Ok(())
    }
}

/// Draws series `i` of an overturning-scale figure (this spectrum, the
/// pulse map) on `chart`: its safe windows as light bars of its colour
/// (an open window reaches `y_max`; all are cut at the axis top `y_top`),
/// then its smallest overturning amplitudes as a line with markers, in
/// increasing x if `sort`. Returns whether it had a window.
pub(crate) fn scale_series<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    i: usize,
    label: &str,
    points: &[ScalePoint],
    (y_max, y_top): (f64, f64),
    sort: bool,
) -> Result<bool, PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let e = PlotError::from_display;
    let c = colour(i);
    let mut any_window = false;
    for (x, _, windows) in points {
        for &(from, to) in windows {
            any_window = true;
            let top = to.unwrap_or(y_max).min(y_top);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(*x, from), (*x, top)],
                    c.mix(0.35).stroke_width(4),
                )))
                .map_err(e)?;
        }
    }
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| p.1.map(|y| (p.0, y)))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if sort {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    chart
        .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))
        .map_err(e)?
        .label(label)
        .legend(move |at| legend_entry(i, at, true));
    chart.draw_series(pts.iter().map(|&p| marker(i, p, 4))).map_err(e)?;
    Ok(any_window)
}

/// The legend entry of the safe windows' light bars.
pub(crate) fn safe_windows_legend<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    legend_only(chart, "light bars: safe windows above it", |(x, y)| {
        PathElement::new(vec![(x, y), (x + 20, y)], SAFE.stroke_width(3))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_figures_draw_as_svg() {
        let fig = SpectrumFigure {
            title: "t".into(),
            subtitle: "s".into(),
            series: vec![SpectrumSeries {
                label: "B/H = 0.2".into(),
                points: vec![(1.0, 0.3, EndState::Rest), (3.0, 1.0, EndState::Overturned)],
            }],
        };
        let svg = fig.to_svg().unwrap();
        assert!(svg.contains("B/H = 0.2") && svg.contains("overturned"));
        let over = OverturnScaleFigure {
            title: "t".into(),
            subtitle: "s".into(),
            y_label: "PGA (g)".into(),
            y_max: 2.0,
            series: vec![OverturnSeries {
                label: "B/H = 0.2".into(),
                points: vec![(1.0, Some(0.5), vec![(0.7, Some(0.9))]), (3.0, None, vec![])],
            }],
        };
        assert!(over.to_svg().unwrap().contains("safe windows above it"));
        assert_eq!(log_range([f64::NAN, -1.0].into_iter(), (0.1, 10.0)), (0.1, 10.0));
    }

    fn two_series(overturned: bool) -> SpectrumFigure {
        let end = if overturned {
            EndState::Overturned
        } else {
            EndState::Rest
        };
        SpectrumFigure {
            title: "t".into(),
            subtitle: "μ_s = 0.4, μ_k = 0.35".into(),
            series: vec![
                SpectrumSeries {
                    label: "B/H = 0.2".into(),
                    points: vec![(2.0, 0.3, EndState::Rest), (2.5, 1.0, EndState::Overturned)],
                },
                SpectrumSeries {
                    label: "B/H = 0.3".into(),
                    points: vec![(2.2, 0.2, EndState::Rest), (3.0, 1.0, end)],
                },
            ],
        }
    }

    #[test]
    fn both_figures_number_their_p_axis_when_p_spans_less_than_a_decade() {
        // p of blocks 2 to 3 1/s: no power of ten on the axis.
        let svg = two_series(true).to_svg().unwrap();
        crate::plot::svg_text::assert_numbered(&svg, "spectrum");
        let over = OverturnScaleFigure {
            title: "t".into(),
            subtitle: "s".into(),
            y_label: "smallest overturning PGA (g)".into(),
            y_max: 2.0,
            series: vec![OverturnSeries {
                label: "B/H = 0.2".into(),
                points: vec![(2.0, Some(0.5), vec![]), (3.0, Some(0.9), vec![])],
            }],
        };
        crate::plot::svg_text::assert_numbered(&over.to_svg().unwrap(), "overturn scale");
        // A single block: p is one value.
        let one = OverturnScaleFigure {
            series: vec![OverturnSeries {
                label: "B/H = 0.2".into(),
                points: vec![(2.6, Some(0.5), vec![])],
            }],
            ..over
        };
        crate::plot::svg_text::assert_numbered(&one.to_svg().unwrap(), "one block");
    }

    #[test]
    fn overturned_crosses_take_their_series_colour_and_labels_show_no_underscore() {
        // Series 1's colour appears more often when its block overturns:
        // its cross is drawn in it, not in a red shared by every series.
        let orange = "#FF7F0E";
        let with = two_series(true).to_svg().unwrap();
        let without = two_series(false).to_svg().unwrap();
        assert!(
            with.matches(orange).count() > without.matches(orange).count(),
            "series 1's overturning cross is not in its colour"
        );
        assert!(!with.contains("#D62728"), "a shared red cross is drawn");
        for label in ["B/H = 0.2", "B/H = 0.3", "overturned"] {
            assert!(with.contains(label), "no legend entry {label}");
        }
        assert_eq!(crate::plot::svg_text::underscores(&with), Vec::<String>::new());
    }
}
