//! Accumulation of log growth factors with a batch-means error estimate.
//!
//! The accumulation window (after the transient) is split into `batches`
//! consecutive batches of renormalisation intervals of (nearly) equal
//! length. Each batch gives its own exponent estimate; the standard error
//! of the overall estimate is the standard deviation of the batch means
//! over √batches (the batch-means method for correlated time series, e.g.
//! Flyvbjerg & Petersen 1989). Batches long compared with the decorrelation
//! time make the batch means nearly independent.

use serde::Serialize;

/// Exponent estimates with error bars.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Estimate<const D: usize> {
    /// Exponents per unit time (natural log), in renormalisation order
    /// (the first is the largest).
    #[serde(with = "serde_arrays")]
    pub exponents: [f64; D],
    /// Standard errors of the exponents (batch means), per unit time.
    #[serde(with = "serde_arrays")]
    pub stderr: [f64; D],
    /// `(t, running estimate of the first exponent)` at up to
    /// [`CONVERGENCE_POINTS`] renormalisation times.
    pub convergence: Vec<(f64, f64)>,
    /// Renormalisations that contributed.
    pub renormalisations: u64,
    /// Start and end of the accumulation window.
    pub t_start: f64,
    /// End of the accumulation window.
    pub t_end: f64,
    /// Number of batches used for the error estimate.
    pub batches: usize,
    /// The batch means of the first exponent, in time order (for paired
    /// comparisons of two estimates from one trajectory).
    pub batch_means: Vec<f64>,
    /// Total time over which growth was measured (0: nothing was).
    pub span: f64,
}

/// Most points kept in [`Estimate::convergence`]: enough to plot the
/// running estimate, few enough for a summary file.
pub const CONVERGENCE_POINTS: usize = 200;

/// Serialises fixed-size arrays as sequences (serde does so only up to 32
/// and not for const-generic lengths).
mod serde_arrays {
    use serde::Serializer;
    use serde::ser::SerializeSeq as _;

    pub(crate) fn serialize<S: Serializer, const D: usize>(a: &[f64; D], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(D))?;
        for x in a {
            seq.serialize_element(x)?;
        }
        seq.end()
    }
}

/// Standard error of the mean of `xs` (0 for fewer than two values).
pub fn standard_error(xs: &[f64]) -> f64 {
    let n = xs.len();
    if n < 2 {
        return 0.0;
    }
    let m = xs.iter().sum::<f64>() / n as f64;
    let var = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n as f64 - 1.0);
    (var / n as f64).sqrt()
}

/// Running sums of `ln R_ii` over a fixed number of intervals.
#[derive(Clone, Debug)]
pub struct Accumulator<const D: usize> {
    intervals: u64,
    batches: usize,
    done: u64,
    sum: [f64; D],
    batch_sum: Vec<[f64; D]>,
    batch_len: Vec<f64>,
    convergence: Vec<(f64, f64)>,
    stride: u64,
    t_start: f64,
    t_last: f64,
    elapsed: f64,
}

impl<const D: usize> Accumulator<D> {
    /// An accumulator for `intervals` renormalisations (>= 1) split into
    /// `batches` batches (clamped to `1..=intervals`), starting at
    /// `t_start`. Allocates here, never in [`push`](Self::push).
    pub fn new(intervals: u64, batches: usize, t_start: f64) -> Self {
        let intervals = intervals.max(1);
        let batches = batches.clamp(1, usize::try_from(intervals).unwrap_or(usize::MAX));
        let stride = (intervals / CONVERGENCE_POINTS as u64).max(1);
        Self {
            intervals,
            batches,
            done: 0,
            sum: [0.0; D],
            batch_sum: vec![[0.0; D]; batches],
            batch_len: vec![0.0; batches],
            convergence: Vec::with_capacity(CONVERGENCE_POINTS + 2),
            stride,
            t_start,
            t_last: t_start,
            elapsed: 0.0,
        }
    }

    /// Whether every interval has been pushed.
    pub(crate) fn is_full(&self) -> bool {
        self.done >= self.intervals
    }

    /// Adds the log growth factors of the interval that ends at `t` and
    /// measured growth over time `dt` (0 for an interval that measured
    /// nothing, e.g. a two-trajectory step without renormalisation; its
    /// growth then comes with a later interval's longer `dt`).
    pub fn push(&mut self, t: f64, dt: f64, logs: &[f64; D]) {
        if self.is_full() {
            return;
        }
        let b = ((self.done as u128 * self.batches as u128) / self.intervals as u128) as usize;
        let b = b.min(self.batches - 1);
        for ((sum, batch), log) in self.sum.iter_mut().zip(self.batch_sum[b].iter_mut()).zip(logs) {
            *sum += log;
            *batch += log;
        }
        self.batch_len[b] += dt;
        self.elapsed += dt;
        self.done += 1;
        self.t_last = t;
        if (self.done.is_multiple_of(self.stride) || self.done == self.intervals) && self.elapsed > 0.0 {
            self.convergence
                .push((t, self.sum.first().copied().unwrap_or(0.0) / self.elapsed));
        }
    }

    /// The estimates so far (zeros and zero errors before any push).
    pub fn estimate(&self) -> Estimate<D> {
        let mut exponents = [0.0; D];
        let mut stderr = [0.0; D];
        if self.elapsed > 0.0 {
            for (e, sum) in exponents.iter_mut().zip(&self.sum) {
                *e = sum / self.elapsed;
            }
        }
        let used: Vec<usize> = (0..self.batches).filter(|&b| self.batch_len[b] > 0.0).collect();
        let nb = used.len();
        let batch_means = used
            .iter()
            .map(|&b| self.batch_sum[b].first().copied().unwrap_or(0.0) / self.batch_len[b])
            .collect();
        for (i, se) in stderr.iter_mut().enumerate() {
            let means: Vec<f64> = used.iter().map(|&b| self.batch_sum[b][i] / self.batch_len[b]).collect();
            *se = standard_error(&means);
        }
        Estimate {
            exponents,
            stderr,
            convergence: self.convergence.clone(),
            renormalisations: self.done,
            t_start: self.t_start,
            t_end: self.t_last,
            batches: nb,
            batch_means,
            span: self.elapsed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_growth_gives_exact_rate_and_zero_error() {
        let mut acc = Accumulator::<2>::new(100, 10, 5.0);
        for k in 1..=100 {
            acc.push(5.0 + 0.5 * k as f64, 0.5, &[0.5 * 0.3, -0.5 * 1.2]);
        }
        let e = acc.estimate();
        assert!((e.exponents[0] - 0.3).abs() < 1e-14);
        assert!((e.exponents[1] + 1.2).abs() < 1e-14);
        assert!(e.stderr[0] < 1e-14 && e.stderr[1] < 1e-14);
        assert_eq!(e.batches, 10);
        assert_eq!(e.renormalisations, 100);
        assert!(e.convergence.len() <= CONVERGENCE_POINTS + 1);
        assert_eq!(e.convergence.last().map(|p| p.0), Some(55.0));
    }

    #[test]
    fn batch_means_error_of_alternating_batches() {
        // Batches alternate between rates 1 and 3: mean 2, sd of batch means
        // sqrt(4·1/3)... computed directly.
        let mut acc = Accumulator::<1>::new(40, 4, 0.0);
        for k in 0..40 {
            let rate = if (k / 10) % 2 == 0 { 1.0 } else { 3.0 };
            acc.push((k + 1) as f64, 1.0, &[rate]);
        }
        let e = acc.estimate();
        assert!((e.exponents[0] - 2.0).abs() < 1e-14);
        // Batch means 1, 3, 1, 3: sample variance 4/3, stderr sqrt(4/3/4).
        assert!((e.stderr[0] - (1.0f64 / 3.0).sqrt()).abs() < 1e-14);
    }
}
