//! Helpers of the record tests on real files (`real_files`) and on files
//! the tests write (`written_files`), in one place both import from: the
//! written-file tests check their writer against the real-file tests'
//! independent parser ([`raw_channel`]).

use super::{RecordSpec, Series};

/// A spec stating only the channel, 1-based.
pub(super) fn channel(k: usize) -> RecordSpec {
    RecordSpec {
        channel: Some(k),
        ..RecordSpec::default()
    }
}

/// The largest |a| of a series as read, and its time.
pub(super) fn peak_and_time(series: &Series) -> (f64, f64) {
    let (k, a) = series
        .accel_g()
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap();
    (*a, series.times_s()[k])
}

/// The test's own reading of a COSMOS channel, by the header layout the
/// format fixes and by whitespace: the data line's count, the real
/// header's sampling interval (value 62, ms), peak (64) and its time (65),
/// and the values.
pub(super) struct Raw {
    pub count: usize,
    pub step_ms: f64,
    pub peak: f64,
    pub peak_time_s: f64,
    pub values: Vec<f64>,
}

pub(super) fn raw_channel(text: &str, k: usize) -> Raw {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.contains("(Format v"))
        .nth(k - 1)
        .unwrap()
        .0;
    let real_at = start + lines[start..].iter().position(|l| l.contains("Real-header")).unwrap();
    let real_lines: usize = lines[real_at].split_whitespace().nth(5).unwrap().parse().unwrap();
    let reals: Vec<f64> = lines[real_at + 1..=real_at + real_lines]
        .iter()
        .flat_map(|l| l.split_whitespace().map(|v| v.parse::<f64>().unwrap()))
        .collect();
    let data_at = start
        + lines[start..]
            .iter()
            .position(|l| l.contains("acceleration pts"))
            .unwrap();
    let count: usize = lines[data_at].split_whitespace().next().unwrap().parse().unwrap();
    let values: Vec<f64> = lines[data_at + 1..]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .take(count)
        // NaN for glued values, which whitespace cannot part: NaN equals
        // nothing, so a comparison with them fails.
        .map(|v| v.parse().unwrap_or(f64::NAN))
        .collect();
    Raw {
        count,
        step_ms: reals[61],
        peak: reals[63],
        peak_time_s: reals[64],
        values,
    }
}
