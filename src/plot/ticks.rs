//! Where the numbers of an axis go, and how they are written, so that
//! every axis of every figure carries at least two numbers whatever its
//! range.
//!
//! plotters numbers a logarithmic axis only at powers of ten (and, when
//! the range spans several, at their multiples): an axis spanning less than
//! a decade, such as the frequency parameter p of one block or of the
//! blocks of one building (p from 2 to 3 1/s), shows no number at all.
//! [`log_axis`] gives such an axis its own ticks.

use std::ops::Range;

use plotters::coord::combinators::{BindKeyPoints, IntoLogRange, LogCoord, WithKeyPoints};

/// Fewest numbers an axis shows.
pub const MIN_TICKS: usize = 2;

/// Most numbers an axis shows before a sparser set is taken: more crowd
/// 16-pixel labels on a 1000-pixel axis.
const MAX_TICKS: usize = 12;

/// Ticks of a logarithmic axis over `[lo, hi]` (0 < lo < hi): the sparsest
/// of the sets {1}, {1, 2, 5}, {1, 2, 3, 5}, {1, …, 9} × 10^k with at least
/// three values in range (and at most [`MAX_TICKS`]); when even the densest
/// has fewer than three (the range spans less than a factor of about 1.5),
/// evenly spaced round values as on a linear axis. Always at least
/// [`MIN_TICKS`] values for a non-empty range; none for an invalid one.
pub(crate) fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo) {
        return Vec::new();
    }
    let mantissas: [&[f64]; 4] = [
        &[1.0],
        &[1.0, 2.0, 5.0],
        &[1.0, 2.0, 3.0, 5.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ];
    for set in mantissas {
        let ticks = decade_multiples(lo, hi, set);
        if (3..=MAX_TICKS).contains(&ticks.len()) {
            return ticks;
        }
        if ticks.len() > MAX_TICKS {
            // Sparser sets had fewer than three; this one has too many:
            // the range spans many decades, so the decades alone will do.
            return decade_multiples(lo, hi, &[1.0]);
        }
    }
    linear_ticks(lo, hi)
}

/// The values m·10^k (m in `mantissas`) in `[lo, hi]`, increasing.
fn decade_multiples(lo: f64, hi: f64, mantissas: &[f64]) -> Vec<f64> {
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut out = Vec::new();
    for k in k0..=k1 {
        for m in mantissas {
            // Written out and parsed back so that 3e-1 is the double
            // nearest 0.3, not 3 · 0.1's rounding.
            let v: f64 = format!("{m}e{k}").parse().unwrap_or(f64::NAN);
            if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                out.push(v);
            }
        }
    }
    out
}

/// Evenly spaced round values in `[lo, hi]`: the finest step of 1, 2 or
/// 5 × 10^k that cuts the range into at most six parts (three to seven
/// values).
pub(crate) fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    let raw = (hi - lo) / 4.0;
    let decade = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|s| (hi - lo) / s <= 6.0)
        .unwrap_or(10.0 * decade);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|i| round_to_step(i as f64 * step, step)).collect()
}

/// `v` rounded to the decimals of `step` (0.30000000000000004 → 0.3).
fn round_to_step(v: f64, step: f64) -> f64 {
    let decimals = (-step.log10().floor()).max(0.0) as usize + 1;
    format!("{v:.decimals$}").parse().unwrap_or(v)
}

/// A logarithmic axis over `range` numbered at [`log_ticks`], with light
/// grid lines at every 1…9 × 10^k inside it.
pub(crate) fn log_axis(range: Range<f64>) -> WithKeyPoints<LogCoord<f64>> {
    let (lo, hi) = (range.start, range.end);
    let light = decade_multiples(lo, hi, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    range
        .log_scale()
        .with_key_points(log_ticks(lo, hi))
        .with_light_points(light)
}

/// A tick's number as short as it reads (`2`, `0.5`, `2.5`, `1e-5`): six
/// significant digits at most, trailing zeros dropped.
pub(crate) fn tick_label(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { "0".into() } else { format!("{v}") };
    }
    let magnitude = v.abs().log10().floor();
    if !(-4.0..6.0).contains(&magnitude) {
        let text = format!("{v:.5e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let decimals = (5.0 - magnitude).max(0.0) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_axis_within_one_decade_still_has_numbers() {
        // p of the blocks of one building: no power of ten inside.
        let t = log_ticks(2.0 / 1.15, 3.0 * 1.15);
        assert!(t.len() >= 3, "{t:?}");
        assert!(t.iter().all(|v| (2.0 / 1.15..=3.45).contains(v)), "{t:?}");
        // A single block: a range of a factor 1.3.
        let t = log_ticks(2.5 / 1.15, 2.5 * 1.15);
        assert!(t.len() >= MIN_TICKS, "{t:?}");
        // Many decades: powers of ten only.
        assert_eq!(
            log_ticks(1e-3, 1e6),
            vec![1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6]
        );
        assert_eq!(log_ticks(0.15, 12.0), vec![0.2, 0.5, 1.0, 2.0, 5.0, 10.0]);
        assert!(log_ticks(1.0, 1.0).is_empty() && log_ticks(-1.0, 1.0).is_empty());
    }

    #[test]
    fn linear_ticks_are_round() {
        assert_eq!(linear_ticks(2.17, 2.88), vec![2.2, 2.4, 2.6, 2.8]);
        assert_eq!(linear_ticks(0.0, 1.0), vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        // p of blocks 0.3 to 0.6 m (3.5 to 4.95 1/s), padded.
        assert_eq!(log_ticks(3.045, 5.69), vec![3.5, 4.0, 4.5, 5.0, 5.5]);
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(2.0), "2");
        assert_eq!(tick_label(0.30000000000000004), "0.3");
        assert_eq!(tick_label(2.5), "2.5");
        assert_eq!(tick_label(20.0), "20");
        assert_eq!(tick_label(1e-5), "1e-5");
        assert_eq!(tick_label(1e6), "1e6");
        assert_eq!(tick_label(0.0), "0");
    }
}
