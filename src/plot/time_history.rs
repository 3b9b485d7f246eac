//! The time history Θ(τ), with the tumble angle marked.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::hues;
use super::style::Frame;
use super::{FONT, Figure, PlotError, padded_range, titled};

/// The data of a time-history figure.
#[derive(Clone, Debug)]
pub struct TimeHistoryFigure<'a> {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// τ of each sample, increasing.
    pub tau: &'a [f64],
    /// Θ of each sample.
    pub theta: &'a [f64],
    /// |Θ| at which the block tumbles, drawn as dashed lines if it lies
    /// within twice the range of the data (`None`: not drawn).
    pub tumble_theta: Option<f64>,
}

impl Figure for TimeHistoryFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = PlotError::from_display;
        let area = titled(root, &self.title, &self.subtitle)?;
        let (t0, t1) = padded_range(self.tau.iter().copied(), 0.0, 1e-9, (0.0, 1.0));
        let (mut y0, mut y1) = padded_range(self.theta.iter().copied(), 0.08, 0.02, (-1.0, 1.0));
        let tumble = self
            .tumble_theta
            .filter(|t| t.is_finite() && *t > 0.0 && *t <= 2.0 * y1.abs().max(y0.abs()));
        if let Some(t) = tumble {
            y0 = y0.min(-1.05 * t);
            y1 = y1.max(1.05 * t);
        }
        let frame = Frame::whole((52, 80));
        let mut chart = frame.chart(&area, None, t0..t1, y0..y1)?;
        // Titles without subscripts: plotters' own axis descriptions.
        frame
            .grid(&mut chart)
            .x_desc("τ = p t")
            .y_desc("Θ = θ/ψ")
            .axis_desc_style((FONT, 19))
            .draw()
            .map_err(e)?;
        if let Some(t) = tumble {
            for level in [t, -t] {
                let dash = RGBColor(200, 60, 60);
                let n = 120;
                chart
                    .draw_series((0..n).step_by(2).map(|i| {
                        let a = t0 + (t1 - t0) * f64::from(i) / f64::from(n);
                        let b = t0 + (t1 - t0) * f64::from(i + 1) / f64::from(n);
                        PathElement::new([(a, level), (b, level)], dash.stroke_width(1))
                    }))
                    .map_err(e)?;
            }
            chart
                .draw_series(std::iter::once(Text::new(
                    "tumble angle",
                    (t0 + 0.01 * (t1 - t0), t),
                    (FONT, 15).into_font().color(&RGBColor(200, 60, 60)),
                )))
                .map_err(e)?;
        }
        let line = envelope(self.tau, self.theta, t0, t1, 2 * self.size().0 as usize);
        chart
            .draw_series(LineSeries::new(line, hues::BLUE.stroke_width(1)))
            .map_err(e)?;
        Ok(())
    }
}

/// The finite samples reduced to at most four per bucket (first, minimum,
/// maximum, last, in time order) over `buckets` equal τ intervals of
/// `[t0, t1]`: the drawn line is the same to the pixel, and a long history
/// does not make a huge SVG.
fn envelope(tau: &[f64], theta: &[f64], t0: f64, t1: f64, buckets: usize) -> Vec<(f64, f64)> {
    let width = (t1 - t0) / buckets.max(1) as f64;
    let mut out = Vec::new();
    let mut bucket: Vec<(f64, f64)> = Vec::new();
    let mut current = None;
    let flush = |bucket: &mut Vec<(f64, f64)>, out: &mut Vec<(f64, f64)>| {
        if bucket.len() <= 4 {
            out.append(bucket);
            return;
        }
        let by = |a: &&(f64, f64), b: &&(f64, f64)| a.1.total_cmp(&b.1);
        let (Some(&first), Some(&last)) = (bucket.first(), bucket.last()) else {
            return;
        };
        let lo = bucket.iter().min_by(by).copied().unwrap_or(first);
        let hi = bucket.iter().max_by(by).copied().unwrap_or(first);
        let mut keep = [first, lo, hi, last];
        keep.sort_by(|a, b| a.0.total_cmp(&b.0));
        out.extend(keep);
        bucket.clear();
    };
    for (&t, &y) in tau.iter().zip(theta).filter(|(t, y)| t.is_finite() && y.is_finite()) {
        let b = if width > 0.0 {
            ((t - t0) / width).floor() as i64
        } else {
            0
        };
        if current != Some(b) {
            flush(&mut bucket, &mut out);
            current = Some(b);
        }
        bucket.push((t, y));
    }
    flush(&mut bucket, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn envelope_keeps_extremes_in_time_order() {
        let tau: Vec<f64> = (0..1000).map(f64::from).collect();
        let theta: Vec<f64> = tau.iter().map(|t| (t * 0.37).sin()).collect();
        let env = envelope(&tau, &theta, 0.0, 999.0, 10);
        assert!(env.len() <= 44);
        assert!(env.windows(2).all(|w| w[0].0 <= w[1].0));
        let max = env.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        let true_max = theta.iter().copied().fold(f64::MIN, f64::max);
        assert_eq!(max, true_max);
        assert_eq!(envelope(&tau[..3], &theta[..3], 0.0, 2.0, 10).len(), 3);
    }
}
