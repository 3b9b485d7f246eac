//! Recorded ground motion: sampling acceleration records.
//!
//! Contract:
//! - Units: a [`Series`] holds times in seconds (s) and accelerations as
//!   fractions of g (a/g, g = 9.81 m/s²). [`RecordExcitation`] works in the
//!   model's normalised time τ = p·t, where p = sqrt(3 g / (4 R)) [1/s] is the
//!   block's frequency parameter, and returns accelerations in g.
//! - Source: the samples come from [`Series::new`], or from a file through
//!   [`read_record`](crate::io::record::read_record) (PEER NGA `.AT2` or
//!   two-column text): the model never reads files.
//! - Interpolation: linear between samples, exact at sample times. The input
//!   is therefore piecewise linear with a kink at every sample;
//!   [`Series::next_sample_after`] and [`RecordExcitation::next_breakpoint`]
//!   tell the integrator where those kinks are so that it can stop on them.
//! - Outside the record: the ground is at rest, so the acceleration is 0
//!   before the first sample time and after the last one (a jump there if the
//!   record does not start or end at 0 g).
//! - Errors: samples that break a [`Series`] invariant are rejected with a
//!   [`SeriesError`], never repaired.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Largest |acceleration| accepted from a record, in g.
///
/// The largest peak ground acceleration ever recorded is about 4 g, so a value
/// above 100 g is a units mix-up (cm/s² or m/s² read as g) or a corrupt file,
/// not ground motion; it is rejected rather than simulated.
pub(crate) const MAX_ABS_ACCEL_G: f64 = 100.0;

/// Shortest time step between record samples accepted from a file, s.
///
/// Accelerographs sample at 50–1000 Hz and resampled records rarely go
/// beyond 10 kHz; a step below 1e-5 s (100 kHz) is a unit mix-up (µs or ms
/// read as s) or a corrupt header, and with steps near the smallest double
/// the record's own integrals (PGV, PGD) underflow to nonsense.
pub(crate) const MIN_STEP_S: f64 = 1e-5;

/// Longest time step between record samples accepted from a file, s: 10 s
/// between samples (0.1 Hz) cannot describe ground shaking, whose energy
/// lies between about 0.1 and 30 Hz; such a step is a unit mix-up (ms read
/// as s) or a gap in the file.
pub(crate) const MAX_STEP_S: f64 = 10.0;

/// Whether `step_s` lies in [[`MIN_STEP_S`], [`MAX_STEP_S`]], up to a
/// relative 1e-9 so that the differences of times written at exactly 1e-5
/// s (or 10 s) apart pass.
pub(crate) fn step_in_range(step_s: f64) -> bool {
    let slack = 1.0 + 1e-9;
    step_s * slack >= MIN_STEP_S && step_s <= MAX_STEP_S * slack
}

/// Samples of ground acceleration: accelerations in g at strictly increasing
/// times in seconds, the first at or after t = 0.
///
/// Always holds at least 2 samples, all finite, with |a| <= [`MAX_ABS_ACCEL_G`].
/// Built by [`Series::new`] or [`read_record`](crate::io::record::read_record),
/// which enforce these invariants.
///
/// The samples are shared, never copied, between clones: a scenario, the
/// model built from it for each run, and every parallel sweep point hold
/// the one copy read from the file (tens of thousands of samples, read
/// once per scene), and a clone costs two reference counts.
#[derive(Debug)]
pub struct Series {
    /// Sample times, s; strictly increasing, first >= 0.
    times_s: Arc<[f64]>,
    /// Accelerations at those times, in g.
    accel_g: Arc<[f64]>,
    /// Where the last lookup landed ([`Series::count_at_or_before`]): an
    /// integrator asks for times in order, mostly inside one interval or
    /// the next, and a binary search over thousands of samples for each of
    /// them was about half a record run's forcing cost. Only a hint: every
    /// use checks it, so any value gives the same answers. Atomic so that a
    /// series shared between threads stays `Sync`; each clone (each
    /// thread's runs) has its own hint over the shared samples.
    hint: AtomicUsize,
}

impl Clone for Series {
    fn clone(&self) -> Self {
        Self {
            times_s: Arc::clone(&self.times_s),
            accel_g: Arc::clone(&self.accel_g),
            hint: AtomicUsize::new(self.hint.load(Ordering::Relaxed)),
        }
    }
}

/// The same samples; the search hint is no part of the value.
impl PartialEq for Series {
    fn eq(&self, other: &Self) -> bool {
        self.times_s == other.times_s && self.accel_g == other.accel_g
    }
}

/// Why [`Series::new`] rejected its samples. Indices are 0-based.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// The two vectors have different lengths.
    #[error("{times} times but {values} acceleration values")]
    LengthMismatch {
        /// Number of times given.
        times: usize,
        /// Number of acceleration values given.
        values: usize,
    },
    /// Fewer than 2 samples: no interval to interpolate over.
    #[error("need at least 2 samples, found {found}")]
    TooFewSamples {
        /// Number of samples given.
        found: usize,
    },
    /// A time or an acceleration is NaN or infinite.
    #[error("sample {index}: non-finite time or acceleration")]
    NonFinite {
        /// Index of the offending sample.
        index: usize,
    },
    /// The first time is negative.
    #[error("first time {time} s is negative")]
    NegativeStart {
        /// The first sample time, s.
        time: f64,
    },
    /// A time does not exceed the one before it.
    #[error("sample {index}: time {time} does not increase (previous {previous})")]
    NotIncreasing {
        /// Index of the offending sample.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The previous sample's time, s.
        previous: f64,
    },
    /// |acceleration| exceeds [`MAX_ABS_ACCEL_G`].
    #[error("sample {index}: |acceleration| of {value} g exceeds the {max} g sanity limit", max = MAX_ABS_ACCEL_G)]
    TooLarge {
        /// Index of the offending sample.
        index: usize,
        /// The acceleration, g.
        value: f64,
    },
}

impl Series {
    /// Builds a series from sample times (s) and accelerations (g).
    ///
    /// # Errors
    /// [`SeriesError`] unless the lengths match, there are at least 2
    /// samples, every value is finite, the first time is >= 0, times strictly
    /// increase and every |acceleration| <= [`MAX_ABS_ACCEL_G`].
    pub fn new(times_s: Vec<f64>, accel_g: Vec<f64>) -> Result<Self, SeriesError> {
        if times_s.len() != accel_g.len() {
            return Err(SeriesError::LengthMismatch {
                times: times_s.len(),
                values: accel_g.len(),
            });
        }
        if times_s.len() < 2 {
            return Err(SeriesError::TooFewSamples { found: times_s.len() });
        }
        let mut previous: Option<f64> = None;
        for (index, (&time, &value)) in times_s.iter().zip(&accel_g).enumerate() {
            if !time.is_finite() || !value.is_finite() {
                return Err(SeriesError::NonFinite { index });
            }
            match previous {
                None if time < 0.0 => return Err(SeriesError::NegativeStart { time }),
                Some(previous) if time <= previous => {
                    return Err(SeriesError::NotIncreasing { index, time, previous });
                }
                _ => {}
            }
            if value.abs() > MAX_ABS_ACCEL_G {
                return Err(SeriesError::TooLarge { index, value });
            }
            previous = Some(time);
        }
        Ok(Self {
            times_s: times_s.into(),
            accel_g: accel_g.into(),
            hint: AtomicUsize::new(0),
        })
    }

    /// Builds a series from samples the caller has already checked against
    /// every invariant of [`Series::new`], without checking them again.
    ///
    /// For the record reader, which checks each sample as it parses it so
    /// that its errors can name the file's line; a second pass would only
    /// repeat that work. Debug builds re-check, to catch a reader bug.
    pub(crate) fn from_checked(times_s: Vec<f64>, accel_g: Vec<f64>) -> Self {
        debug_assert!(
            Self::new(times_s.clone(), accel_g.clone()).is_ok(),
            "record samples break a Series invariant"
        );
        Self {
            times_s: times_s.into(),
            accel_g: accel_g.into(),
            hint: AtomicUsize::new(0),
        }
    }

    /// Sample times, s (strictly increasing, first >= 0).
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }

    /// Sample accelerations, g, one per entry of [`Series::times_s`].
    pub fn accel_g(&self) -> &[f64] {
        &self.accel_g
    }

    /// Number of samples (always >= 2).
    pub fn len(&self) -> usize {
        self.times_s.len()
    }

    /// Always `false`: a series holds at least 2 samples. Provided because
    /// [`Series::len`] is public.
    pub fn is_empty(&self) -> bool {
        self.times_s.is_empty()
    }

    /// Time of the first sample, s. Before it the ground is at rest.
    pub fn start_s(&self) -> f64 {
        self.times_s.first().copied().unwrap_or(0.0)
    }

    /// Duration of the record in s, measured from t = 0 (not from the first
    /// sample): the time of the last sample, after which the ground is at
    /// rest. Measured from 0 because the record sits on the simulation's
    /// absolute time axis, which starts at 0.
    pub fn duration_s(&self) -> f64 {
        self.times_s.last().copied().unwrap_or(0.0)
    }

    /// Largest |acceleration| over the samples, g (the record's PGA). Since the
    /// interpolation is linear it is also the peak of [`Series::accel_at`].
    pub fn peak_abs_g(&self) -> f64 {
        self.accel_g.iter().fold(0.0, |peak, a| peak.max(a.abs()))
    }

    /// Acceleration at time `t_s` (s), in g, by linear interpolation between
    /// the neighbouring samples; exactly the sample value at a sample time.
    ///
    /// Returns 0 for `t_s` before the first sample time or after the last one
    /// (ground at rest), and NaN for a NaN `t_s` so that a bad time is caught
    /// by the integrator's non-finite check rather than hidden. O(log n):
    /// binary search.
    pub fn accel_at(&self, t_s: f64) -> f64 {
        if t_s.is_nan() {
            return f64::NAN;
        }
        // Number of samples at or before t_s.
        let i = self.count_at_or_before(t_s);
        let Some(before) = i.checked_sub(1) else {
            return 0.0; // before the first sample
        };
        let (Some(&t0), Some(&a0)) = (self.times_s.get(before), self.accel_g.get(before)) else {
            return 0.0;
        };
        if t0 == t_s {
            return a0;
        }
        match (self.times_s.get(i), self.accel_g.get(i)) {
            (Some(&t1), Some(&a1)) => a0 + (a1 - a0) * ((t_s - t0) / (t1 - t0)),
            _ => 0.0, // after the last sample
        }
    }

    /// The first sample time strictly greater than `t_s`, in s, or `None`
    /// past the last sample (or for a NaN `t_s`). These are the kinks of the
    /// piecewise-linear input, where the integrator should stop. O(log n).
    pub fn next_sample_after(&self, t_s: f64) -> Option<f64> {
        if t_s.is_nan() {
            return None;
        }
        let i = self.count_at_or_before(t_s);
        self.times_s.get(i).copied()
    }

    /// The number of samples at or before `t_s` (`partition_point(t_i <=
    /// t_s)`), trying the last answer and the one after it before a binary
    /// search. `t_s` is not NaN.
    #[inline]
    fn count_at_or_before(&self, t_s: f64) -> usize {
        let n = self.times_s.len();
        let fits = |c: usize| {
            (c == 0 || self.times_s.get(c - 1).is_some_and(|&t| t <= t_s))
                && (c == n || self.times_s.get(c).is_some_and(|&t| t > t_s))
        };
        let h = self.hint.load(Ordering::Relaxed);
        let c = if fits(h) {
            h
        } else if h < n && fits(h + 1) {
            h + 1
        } else {
            self.times_s.partition_point(|&t| t <= t_s)
        };
        self.hint.store(c, Ordering::Relaxed);
        c
    }
}

/// Peak values of the ground motion a series describes, after a scale
/// factor: what an engineer quotes for a record.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct GroundPeaks {
    /// Peak ground acceleration, g.
    pub pga_g: f64,
    /// Peak ground velocity, m/s.
    pub pgv_m_s: f64,
    /// Peak ground displacement, m.
    pub pgd_m: f64,
}

impl Series {
    /// The peaks of `scale` times this record, with velocity and
    /// displacement integrated exactly from the piecewise-linear
    /// acceleration the model sees, the ground at rest at t = 0 (before the
    /// first sample it does not move).
    ///
    /// No baseline correction is applied: these are the peaks of the base
    /// motion as simulated. Taken up to the last sample; an uncorrected
    /// record that ends with a residual velocity drifts on after it, which
    /// the block (whose frame is the base's) never feels.
    pub fn peaks(&self, scale: f64) -> GroundPeaks {
        let g = crate::model::geometry::G;
        let (mut v, mut d) = (0.0_f64, 0.0_f64);
        let (mut pgv, mut pgd) = (0.0_f64, 0.0_f64);
        for (t, a) in self.times_s.windows(2).zip(self.accel_g.windows(2)) {
            let h = t[1] - t[0];
            // Over one interval a is linear, v quadratic and d cubic; the
            // peak of |v| inside an interval is at a zero of a, checked too.
            let (a0, a1) = (scale * g * a[0], scale * g * a[1]);
            if a0 * a1 < 0.0 {
                let s = a0 / (a0 - a1) * h;
                let v_mid = v + a0 * s + 0.5 * (a1 - a0) / h * s * s;
                pgv = pgv.max(v_mid.abs());
            }
            // |d| peaks inside the interval where v = v + a0 s + k s²/2
            // crosses zero.
            let k = (a1 - a0) / h;
            for s in velocity_zeros(v, a0, k, h) {
                pgd = pgd.max((d + v * s + 0.5 * a0 * s * s + k * s * s * s / 6.0).abs());
            }
            let v_next = v + 0.5 * (a0 + a1) * h;
            d += v * h + (2.0 * a0 + a1) * h * h / 6.0;
            v = v_next;
            pgv = pgv.max(v.abs());
            pgd = pgd.max(d.abs());
        }
        GroundPeaks {
            pga_g: scale.abs() * self.peak_abs_g(),
            pgv_m_s: pgv,
            pgd_m: pgd,
        }
    }

    /// This series with every acceleration multiplied by `factor` (a unit
    /// conversion), or the error naming the first sample that then breaks
    /// the |a| limit.
    pub fn scaled(&self, factor: f64) -> Result<Series, SeriesError> {
        Series::new(self.times_s.to_vec(), self.accel_g.iter().map(|a| a * factor).collect())
    }
}

/// The times s in (0, h) at which v + a0·s + k·s²/2 = 0.
fn velocity_zeros(v: f64, a0: f64, k: f64, h: f64) -> impl Iterator<Item = f64> {
    let roots: [Option<f64>; 2] = if k == 0.0 {
        [(a0 != 0.0).then(|| -v / a0), None]
    } else {
        let disc = a0 * a0 - 2.0 * k * v;
        if disc < 0.0 {
            [None, None]
        } else {
            let r = disc.sqrt();
            [Some((-a0 + r) / k), Some((-a0 - r) / k)]
        }
    };
    roots.into_iter().flatten().filter(move |s| *s > 0.0 && *s < h)
}

/// A recorded base excitation in the model's normalised time.
///
/// Conversion: the model's time is τ = p·t with p in 1/s and t in s, so the
/// record is sampled at t = τ / p, and a sample at time t_k (s) lies at
/// τ_k = p·t_k. Each component is multiplied by its scale factor (for
/// amplitude scaling studies); results are in g, the vertical one positive
/// upward.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordExcitation {
    /// Horizontal component.
    horizontal: Series,
    /// Vertical component (positive upward), if any.
    vertical: Option<Series>,
    /// Frequency parameter p, 1/s.
    p: f64,
    /// Scale factor on the horizontal component (dimensionless).
    scale_h: f64,
    /// Scale factor on the vertical component (dimensionless).
    scale_v: f64,
}

impl RecordExcitation {
    /// Combines a horizontal record with an optional vertical one (positive
    /// upward), for a block of frequency parameter `p_per_s` (1/s), scaling
    /// the components by `scale_h` and `scale_v` (dimensionless; 1 replays the
    /// record as recorded).
    ///
    /// `p_per_s` must be finite and > 0; it comes from the block geometry,
    /// which the model validates. Any other value gives meaningless (but not
    /// panicking) results.
    pub fn new(horizontal: Series, vertical: Option<Series>, p_per_s: f64, scale_h: f64, scale_v: f64) -> Self {
        Self {
            horizontal,
            vertical,
            p: p_per_s,
            scale_h,
            scale_v,
        }
    }

    /// The horizontal component.
    pub fn horizontal(&self) -> &Series {
        &self.horizontal
    }

    /// The vertical component (positive upward), if any.
    pub fn vertical(&self) -> Option<&Series> {
        self.vertical.as_ref()
    }

    /// Frequency parameter p, 1/s.
    pub fn p_per_s(&self) -> f64 {
        self.p
    }

    /// Scale factor on the horizontal component.
    pub fn scale_h(&self) -> f64 {
        self.scale_h
    }

    /// Scale factor on the vertical component.
    pub fn scale_v(&self) -> f64 {
        self.scale_v
    }

    /// Ground acceleration `(a_h, a_v)` at normalised time `tau`, in g:
    /// `(scale_h · a_h(τ/p), scale_v · a_v(τ/p))`, with `a_v` positive upward
    /// and 0 when there is no vertical record. Each component is 0 outside
    /// its record (see [`Series::accel_at`]).
    pub fn accel(&self, tau: f64) -> (f64, f64) {
        let t_s = tau / self.p;
        let a_h = self.scale_h * self.horizontal.accel_at(t_s);
        let a_v = match &self.vertical {
            Some(vertical) => self.scale_v * vertical.accel_at(t_s),
            None => 0.0,
        };
        (a_h, a_v)
    }

    /// The smallest τ' > `tau` at which either component has a sample (a
    /// kink of the input), with sample times converted as τ' = p·t_k; `None`
    /// past the last sample of both.
    ///
    /// The comparison is made on p·t_k itself, so the result is strictly
    /// greater than `tau` even when `tau` is a previous breakpoint and `tau/p`
    /// rounds below its sample time.
    pub fn next_breakpoint(&self, tau: f64) -> Option<f64> {
        let h = next_tau(&self.horizontal, tau, self.p);
        let v = self
            .vertical
            .as_ref()
            .and_then(|vertical| next_tau(vertical, tau, self.p));
        match (h, v) {
            (Some(h), Some(v)) => Some(h.min(v)),
            (h, v) => h.or(v),
        }
    }

    /// End of the excitation in τ: p times the larger of the two components'
    /// [`Series::duration_s`]. After it the ground is at rest.
    pub fn end_tau(&self) -> f64 {
        let end_s = match &self.vertical {
            Some(vertical) => self.horizontal.duration_s().max(vertical.duration_s()),
            None => self.horizontal.duration_s(),
        };
        end_s * self.p
    }
}

/// First p·t_k strictly greater than `tau`, searched on p·t_k directly (which
/// is non-decreasing in t_k for p > 0, so the binary search is valid).
fn next_tau(series: &Series, tau: f64, p: f64) -> Option<f64> {
    if tau.is_nan() {
        return None;
    }
    let i = series.times_s.partition_point(|&t| t * p <= tau);
    series.times_s.get(i).map(|&t| t * p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(times: &[f64], accel: &[f64]) -> Series {
        Series::new(times.to_vec(), accel.to_vec()).unwrap()
    }

    // ---- Series ----

    #[test]
    fn interpolates_linearly_and_exactly_at_samples() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.accel_at(0.5), 0.2);
        assert_eq!(s.accel_at(1.0), -0.4);
        assert_eq!(s.accel_at(2.0), 0.6);
        assert!((s.accel_at(0.75) - (-0.1)).abs() < 1e-15);
        assert!((s.accel_at(1.5) - 0.1).abs() < 1e-15);
        assert!((s.accel_at(1.25) - (-0.15)).abs() < 1e-15);
    }

    #[test]
    fn zero_outside_the_record_nan_for_nan() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.accel_at(0.0), 0.0);
        assert_eq!(s.accel_at(0.499_999), 0.0);
        assert_eq!(s.accel_at(-3.0), 0.0);
        assert_eq!(s.accel_at(2.000_001), 0.0);
        assert_eq!(s.accel_at(f64::INFINITY), 0.0);
        assert_eq!(s.accel_at(f64::NEG_INFINITY), 0.0);
        assert!(s.accel_at(f64::NAN).is_nan());
    }

    #[test]
    fn series_accessors() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.len(), 3);
        assert!(!s.is_empty());
        assert_eq!(s.start_s(), 0.5);
        assert_eq!(s.duration_s(), 2.0);
        assert_eq!(s.peak_abs_g(), 0.6);
        assert_eq!(s.times_s(), &[0.5, 1.0, 2.0]);
        assert_eq!(s.accel_g(), &[0.2, -0.4, 0.6]);
    }

    #[test]
    fn next_sample_after_is_strict() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.next_sample_after(-1.0), Some(0.5));
        assert_eq!(s.next_sample_after(0.5), Some(1.0));
        assert_eq!(s.next_sample_after(0.7), Some(1.0));
        assert_eq!(s.next_sample_after(1.0), Some(2.0));
        assert_eq!(s.next_sample_after(2.0), None);
        assert_eq!(s.next_sample_after(5.0), None);
        assert_eq!(s.next_sample_after(f64::NAN), None);
    }

    #[test]
    fn series_new_validates() {
        use SeriesError as E;
        let new = |t: &[f64], a: &[f64]| Series::new(t.to_vec(), a.to_vec()).unwrap_err();
        assert_eq!(new(&[0.0, 1.0], &[0.0]), E::LengthMismatch { times: 2, values: 1 });
        assert_eq!(new(&[0.0], &[0.0]), E::TooFewSamples { found: 1 });
        assert_eq!(new(&[], &[]), E::TooFewSamples { found: 0 });
        assert_eq!(new(&[0.0, f64::NAN], &[0.0, 0.0]), E::NonFinite { index: 1 });
        assert_eq!(new(&[0.0, 1.0], &[0.0, f64::INFINITY]), E::NonFinite { index: 1 });
        assert_eq!(new(&[-0.1, 1.0], &[0.0, 0.0]), E::NegativeStart { time: -0.1 });
        assert_eq!(
            new(&[0.0, 1.0, 1.0], &[0.0, 0.0, 0.0]),
            E::NotIncreasing {
                index: 2,
                time: 1.0,
                previous: 1.0
            }
        );
        assert_eq!(
            new(&[0.0, 1.0], &[0.0, -100.5]),
            E::TooLarge {
                index: 1,
                value: -100.5
            }
        );
        assert!(Series::new(vec![0.0, 1.0], vec![100.0, -100.0]).is_ok());
    }

    // ---- RecordExcitation ----

    #[test]
    fn excitation_converts_time_and_scales() {
        let h = series(&[0.0, 1.0, 2.0], &[0.0, 0.4, 0.0]);
        let v = series(&[0.0, 0.5, 1.5], &[0.1, 0.3, -0.1]);
        let p = 4.0;
        let ex = RecordExcitation::new(h.clone(), Some(v.clone()), p, 2.0, -0.5);
        for &tau in &[-1.0, 0.0, 0.3, 1.0, 2.0, 3.7, 4.0, 6.0, 7.9, 8.0, 9.0] {
            let (a_h, a_v) = ex.accel(tau);
            assert_eq!(a_h, 2.0 * h.accel_at(tau / p));
            assert_eq!(a_v, -0.5 * v.accel_at(tau / p));
        }
        assert!((ex.accel(2.0).0 - 0.4).abs() < 1e-15); // t = 0.5 s, a_h = 0.2 g
        assert_eq!(ex.end_tau(), 8.0);
        let h_only = RecordExcitation::new(h, None, p, 1.0, 3.0);
        assert_eq!(h_only.accel(2.0).1, 0.0);
        assert_eq!(h_only.end_tau(), 8.0);
        assert!(h_only.vertical().is_none());
        assert_eq!(h_only.p_per_s(), 4.0);
        assert_eq!((h_only.scale_h(), h_only.scale_v()), (1.0, 3.0));
    }

    #[test]
    fn end_tau_takes_the_longer_component() {
        let h = series(&[0.0, 1.0], &[0.0, 0.1]);
        let v = series(&[0.0, 3.0], &[0.0, 0.1]);
        let ex = RecordExcitation::new(h, Some(v), 2.0, 1.0, 1.0);
        assert_eq!(ex.end_tau(), 6.0);
    }

    #[test]
    fn next_breakpoint_merges_both_components() {
        let h = series(&[0.0, 1.0, 2.0], &[0.0, 0.4, 0.0]);
        let v = series(&[0.25, 0.5, 1.5, 3.0], &[0.1, 0.3, -0.1, 0.0]);
        let ex = RecordExcitation::new(h, Some(v), 2.0, 1.0, 1.0);
        let mut tau = -1.0;
        let mut seen = Vec::new();
        while let Some(next) = ex.next_breakpoint(tau) {
            assert!(next > tau);
            seen.push(next);
            tau = next;
        }
        assert_eq!(seen, vec![0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 6.0]);
        assert_eq!(ex.next_breakpoint(f64::NAN), None);
    }

    #[test]
    fn a_clone_and_the_excitation_built_from_it_share_the_samples() {
        let times: Vec<f64> = (0..1000).map(|k| k as f64 * 0.01).collect();
        let accel: Vec<f64> = times.iter().map(|t| (3.0 * t).sin()).collect();
        let h = Series::new(times.clone(), accel.clone()).unwrap();
        let copy = h.clone();
        // The same memory, not equal copies of it.
        assert!(std::ptr::eq(h.times_s().as_ptr(), copy.times_s().as_ptr()));
        assert!(std::ptr::eq(h.accel_g().as_ptr(), copy.accel_g().as_ptr()));
        let ex = RecordExcitation::new(copy, None, 2.0, 1.0, 1.0);
        assert!(std::ptr::eq(h.accel_g().as_ptr(), ex.horizontal().accel_g().as_ptr()));
        assert_eq!((h.times_s(), h.accel_g()), (&times[..], &accel[..]));
    }

    #[test]
    fn next_breakpoint_strict_despite_rounding() {
        // p and times chosen so that (t·p)/p often differs from t.
        let times: Vec<f64> = (0..2000).map(|k| k as f64 * 0.01).collect();
        let accel = vec![0.0; times.len()];
        let h = Series::new(times.clone(), accel).unwrap();
        let p = 3.0_f64.sqrt() * 1.234_567;
        let ex = RecordExcitation::new(h, None, p, 1.0, 1.0);
        let mut tau = 0.0;
        let mut count = 1;
        while let Some(next) = ex.next_breakpoint(tau) {
            assert!(next > tau);
            tau = next;
            count += 1;
        }
        assert_eq!(count, times.len());
        assert_eq!(tau, ex.end_tau());
    }

    #[test]
    fn peaks_of_a_constant_and_of_a_reversing_acceleration_are_the_closed_forms() {
        let g = crate::model::geometry::G;
        // 1 g for 1 s: v = g t, d = g t²/2.
        let step = Series::new(vec![0.0, 1.0], vec![1.0, 1.0]).unwrap();
        let p = step.peaks(1.0);
        assert_eq!(p.pga_g, 1.0);
        assert!((p.pgv_m_s - g).abs() < 1e-12 && (p.pgd_m - 0.5 * g).abs() < 1e-12);
        assert_eq!(step.peaks(-2.0).pga_g, 2.0);
        // a = g(1 − t) on [0, 3]: v = g(t − t²/2) peaks at t = 1 (g/2) inside
        // the interval and ends at −1.5 g; d = g(t²/2 − t³/6) peaks at t = 2
        // (2g/3) where v = 0, and is 0 again at t = 3.
        let ramp = Series::new(vec![0.0, 3.0], vec![1.0, -2.0]).unwrap();
        let p = ramp.peaks(1.0);
        assert!((p.pgv_m_s - 1.5 * g).abs() < 1e-12, "{p:?}");
        assert!((p.pgd_m - 2.0 * g / 3.0).abs() < 1e-12, "{p:?}");
        let half = Series::new(vec![0.0, 1.5], vec![1.0, -0.5]).unwrap();
        assert!((half.peaks(1.0).pgv_m_s - 0.5 * g).abs() < 1e-12);
    }
}
