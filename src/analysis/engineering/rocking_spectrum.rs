//! The rocking spectrum: one ground motion, a range of block sizes (and
//! slendernesses); per block the peak rotation θ/α, whether it overturned
//! and when, and optionally the smallest scale of the motion that
//! overturns it ([`overturn_scale`](super::overturn_scale)).
//!
//! Sizes are log-spaced in the half-diagonal R or in the height H at a
//! fixed B/H, as rocking spectra are drawn against the frequency parameter
//! p = √(3g/(4R)) (Makris & Konstantinidis 2003), which falls as the block
//! grows. Blocks run in parallel and are collected by index.

use rayon::prelude::*;

use super::overturn_scale::{ScaleSearch, search};
use super::response::{BlockResponse, BlockSize, Drive, ResponseError, respond};
use crate::analysis::{Progress, ProgressFn};
use crate::sim::Scenario;

/// Most blocks (sizes × slendernesses) of one spectrum.
pub const MAX_BLOCKS: usize = 1_000_000;

/// What the size range steps through.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeAxis {
    /// The half-diagonal R, m.
    HalfDiagonal,
    /// The height H, m.
    Height,
}

impl SizeAxis {
    /// Output name.
    pub fn name(self) -> &'static str {
        match self {
            SizeAxis::HalfDiagonal => "half_diagonal",
            SizeAxis::Height => "height",
        }
    }
}

/// `count` log-spaced sizes from `from_m` to `to_m` (both included), m.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SizeRange {
    /// What is stepped.
    pub axis: SizeAxis,
    /// Smallest size, m, > 0.
    pub from_m: f64,
    /// Largest size, m, ≥ `from_m`.
    pub to_m: f64,
    /// Number of sizes, ≥ 1 (1 only when from = to).
    pub count: usize,
}

/// A size range that cannot be stepped through.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SizeRangeError {
    /// The smallest size is not a positive finite number.
    #[error("from = {0} m: must be a finite size > 0")]
    From(f64),
    /// The largest size is below the smallest.
    #[error("to = {to} m is below from = {from} m")]
    Reversed {
        /// From, m.
        from: f64,
        /// To, m.
        to: f64,
    },
    /// The count is 0, too large, or 1 for a range of two sizes.
    #[error("count = {0}: must be >= 2 (or 1 when from = to) and at most 1000000")]
    Count(usize),
}

impl SizeRange {
    /// A checked range.
    pub fn new(axis: SizeAxis, from_m: f64, to_m: f64, count: usize) -> Result<Self, SizeRangeError> {
        if !(from_m > 0.0 && from_m.is_finite()) {
            return Err(SizeRangeError::From(from_m));
        }
        if !(to_m >= from_m && to_m.is_finite()) {
            return Err(SizeRangeError::Reversed { from: from_m, to: to_m });
        }
        if count == 0 || count > MAX_BLOCKS || (count == 1 && to_m != from_m) {
            return Err(SizeRangeError::Count(count));
        }
        Ok(Self {
            axis,
            from_m,
            to_m,
            count,
        })
    }

    /// The sizes, m, increasing: from·(to/from)^(i/(count−1)).
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.from_m];
        }
        let ratio = self.to_m / self.from_m;
        let last = (self.count - 1) as f64;
        (0..self.count)
            .map(|i| match i {
                0 => self.from_m,
                i if i + 1 == self.count => self.to_m,
                i => self.from_m * ratio.powf(i as f64 / last),
            })
            .collect()
    }

    /// The block of size `value` and slenderness ratio `b_over_h`.
    pub fn block(&self, value: f64, b_over_h: f64) -> BlockSize {
        match self.axis {
            SizeAxis::HalfDiagonal => BlockSize::from_half_diagonal(value, b_over_h),
            SizeAxis::Height => BlockSize::from_height(value, b_over_h),
        }
    }
}

/// The overturning-scale search of each block: the scales tried and the
/// bisection tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct OverturnOptions {
    /// Scale factors stepped through, increasing, > 0.
    pub ladder: Vec<f64>,
    /// Relative width to which each boundary is refined, > 0.
    pub rel_tol: f64,
}

/// What to compute.
#[derive(Clone, Debug)]
pub struct SpectrumSpec<'a> {
    /// Friction, impact law, tolerances, overturning angle.
    pub base: &'a Scenario,
    /// The ground motion.
    pub drive: &'a Drive,
    /// Its scale factor for the peak-rotation runs (1 plays it as given).
    pub scale: f64,
    /// The sizes.
    pub sizes: SizeRange,
    /// Slenderness ratios B/H, each > 0.
    pub b_over_h: Vec<f64>,
    /// The overturning-scale search, if wanted.
    pub overturn: Option<OverturnOptions>,
}

/// One block of the spectrum.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumPoint {
    /// B/H of the block.
    pub b_over_h: f64,
    /// Its size value on the range's axis, m.
    pub size_m: f64,
    /// The block.
    pub block: BlockSize,
    /// Its response at the spectrum's scale.
    pub response: BlockResponse,
    /// The overturning-scale search, when asked for.
    pub overturn: Option<ScaleSearch<BlockResponse>>,
}

/// A run of the spectrum that failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("block B = {width_m} m, H = {height_m} m: {error}", width_m = block.width_m, height_m = block.height_m)]
pub struct SpectrumError {
    /// The block.
    pub block: BlockSize,
    /// What failed.
    pub error: ResponseError,
}

impl SpectrumSpec<'_> {
    /// The blocks in output order: slenderness outer, size inner
    /// (increasing).
    pub fn blocks(&self) -> Vec<(f64, f64, BlockSize)> {
        let values = self.sizes.values();
        self.b_over_h
            .iter()
            .flat_map(|&ratio| values.iter().map(move |&v| (ratio, v, self.sizes.block(v, ratio))))
            .collect()
    }
}

/// Runs the spectrum; progress counts blocks.
pub fn rocking_spectrum(
    spec: &SpectrumSpec<'_>,
    progress: &ProgressFn<'_>,
) -> Result<Vec<SpectrumPoint>, SpectrumError> {
    let blocks = spec.blocks();
    progress(Progress::Total(blocks.len() as u64));
    blocks
        .par_iter()
        .map(|&(b_over_h, size_m, block)| {
            let fail = |error| SpectrumError { block, error };
            let response = respond(spec.base, block, spec.drive, spec.scale).map_err(fail)?;
            let overturn = match &spec.overturn {
                Some(o) => Some(
                    search(&o.ladder, o.rel_tol, &|scale| {
                        respond(spec.base, block, spec.drive, scale)
                    })
                    .map_err(fail)?,
                ),
                None => None,
            };
            progress(Progress::Done);
            Ok(SpectrumPoint {
                b_over_h,
                size_m,
                block,
                response,
                overturn,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::engineering::EndState;
    use crate::analysis::engineering::overturn_scale::ladder;

    #[test]
    fn sizes_are_log_spaced_and_checked() {
        let r = SizeRange::new(SizeAxis::HalfDiagonal, 0.1, 10.0, 3).unwrap();
        let v = r.values();
        assert_eq!(v[0], 0.1);
        assert!((v[1] - 1.0).abs() < 1e-15);
        assert_eq!(v[2], 10.0);
        assert_eq!(
            SizeRange::new(SizeAxis::Height, 2.0, 2.0, 1).unwrap().values(),
            vec![2.0]
        );
        assert!(matches!(
            SizeRange::new(SizeAxis::Height, 2.0, 1.0, 5),
            Err(SizeRangeError::Reversed { .. })
        ));
        assert!(SizeRange::new(SizeAxis::Height, 0.0, 1.0, 5).is_err());
        assert!(SizeRange::new(SizeAxis::Height, 1.0, 2.0, 1).is_err());
        assert!(SizeRange::new(SizeAxis::Height, 1.0, 2.0, 0).is_err());
    }

    /// A one-sine acceleration record of amplitude `a_g` and period
    /// `period_s`, sampled every 5 ms, then 0.
    fn sine_record(a_g: f64, period_s: f64) -> Drive {
        let n = (period_s / 0.005).round() as usize;
        let t: Vec<f64> = (0..=n + 1).map(|i| i as f64 * 0.005).collect();
        let a: Vec<f64> = t
            .iter()
            .map(|&t| {
                if t <= period_s {
                    a_g * (std::f64::consts::TAU * t / period_s).sin()
                } else {
                    0.0
                }
            })
            .collect();
        super::super::test_record("sine.txt", t, a)
    }

    #[test]
    fn a_tiny_spectrum_small_blocks_overturn_large_ones_survive() {
        // A 0.5 g, 1 s one-sine pulse on blocks of B/H = 0.2 (uplift at
        // 0.2 g): the small blocks overturn (Housner's size effect), the
        // largest barely rock.
        let base = Scenario::default();
        let drive = sine_record(0.5, 1.0);
        let spec = SpectrumSpec {
            base: &base,
            drive: &drive,
            scale: 1.0,
            sizes: SizeRange::new(SizeAxis::HalfDiagonal, 0.1, 20.0, 4).unwrap(),
            b_over_h: vec![0.2],
            overturn: Some(OverturnOptions {
                ladder: ladder(0.5, 3.0).unwrap(),
                rel_tol: 1e-3,
            }),
        };
        let points = rocking_spectrum(&spec, &crate::analysis::silent).unwrap();
        assert_eq!(points.len(), 4);
        assert_eq!(points[0].response.end, EndState::Overturned);
        let last = points.last().unwrap();
        assert!(last.response.end.survived(), "{last:?}");
        assert!(last.response.peak_theta_over_alpha < 1.0);
        // Peak rotation falls with size among the survivors, and every
        // block rocks (0.5 g > g tan α).
        for p in &points {
            assert!(p.response.peak_theta_over_alpha > 0.0, "{p:?}");
        }
        // The smallest scale that overturns the small block is at most 1
        // and above the uplift scale 0.2/0.5; the largest needs more than 1.
        let first = points[0].overturn.as_ref().unwrap().first_failure.unwrap().0;
        assert!(first <= 1.0 && first > 0.4, "{first}");
        if let Some((s, _)) = last.overturn.as_ref().unwrap().first_failure {
            assert!(s > 1.0, "{s}");
        }
        // p and R of the blocks follow the range.
        assert!((points[0].block.half_diagonal_m() - 0.1).abs() < 1e-12);
    }
}
