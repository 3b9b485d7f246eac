//! Power spectrum of a uniformly sampled signal, Θ(τ) in particular.
//!
//! Definitions (samples x_n, n = 0 … N−1, spacing Δτ, taper w_n):
//! - X_k = Σ_n w_n x_n e^{−2πikn/N} (realfft, k = 0 … ⌊N/2⌋);
//! - the one-sided power spectral density
//!   S_k = c_k Δτ |X_k|² / Σ_n w_n², with c_k = 2 except c_0 = 1 and, for
//!   even N, c_{N/2} = 1; in units of x² per (cycle per unit τ);
//! - so that Σ_k S_k Δf = Σ_n (w_n x_n)² / Σ_n w_n² (Parseval), Δf = 1/(NΔτ):
//!   the mean square of the signal without a taper, its taper-weighted mean
//!   square with one. A sine of amplitude A puts A²/2 under its peak.
//!
//! Frequency axes: f_k = k/(NΔτ) in cycles per unit τ; ω = 2πf in units of
//! p (τ = p t, so ω is the angular frequency over p, the unit of Ω_h); and
//! ω/Ω_h, the harmonic number of the excitation (1 = the forcing frequency,
//! 1/2 = a period-2 subharmonic).
//!
//! The paper's window: its spectra use "a time history of from 3,000 to
//! 7,096", i.e. 4096 samples. We read these as sample indices at its
//! integration step Δτ = 0.004: samples n = 3000 … 7095, τ = 12 to 28.38
//! (28.384 exclusive) — early in the run, inside the transient.
//! [`SpectrumWindow::Paper`] reproduces that; with a history on the same
//! grid (`run.output_dt = 0.004`) no interpolation is needed.
//!
//! Contract: non-finite samples, a non-positive spacing or a window outside
//! the history are errors; outputs are finite.

use std::f64::consts::TAU;

use realfft::RealFftPlanner;

use crate::sim::HistoryRow;

/// The paper's integration step, the spacing of its spectrum's samples.
pub(crate) const PAPER_DT: f64 = 0.004;
/// Index of the paper's first spectrum sample.
pub(crate) const PAPER_FIRST: usize = 3000;
/// The paper's number of spectrum samples (7,096 − 3,000).
pub(crate) const PAPER_COUNT: usize = 4096;

/// Fewest samples a spectrum is computed from.
pub(crate) const MIN_SAMPLES: usize = crate::sim::scenario::MIN_SPECTRUM_SAMPLES;

/// Taper applied before the transform.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Taper {
    /// Hann window w_n = sin²(πn/N) (periodic form). Default: its sidelobes
    /// fall off fast, so the weak subharmonics of a periodic rocking
    /// response are not buried under the forcing line's leakage.
    #[default]
    Hann,
    /// No taper (rectangular window).
    None,
}

/// Options of [`power_spectrum`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SpectrumOptions {
    /// Taper. Default Hann.
    pub taper: Taper,
    /// Subtract the mean before tapering. Default true: the mean carries no
    /// dynamics, and with a taper it leaks into the lowest bins.
    pub remove_mean: bool,
}

impl Default for SpectrumOptions {
    fn default() -> Self {
        Self {
            taper: Taper::Hann,
            remove_mean: true,
        }
    }
}

/// Which samples of a time history a spectrum is taken from.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum SpectrumWindow {
    /// The whole history, at its own spacing.
    All,
    /// The paper's: samples 3000 … 7095 at Δτ = 0.004 (τ 12 to 28.384).
    Paper,
    /// Samples at τ_n = n·`dt` for n = `first` … `first + count − 1`.
    Samples {
        /// First sample index.
        first: usize,
        /// Number of samples.
        count: usize,
        /// Spacing in τ.
        dt: f64,
    },
}

/// A one-sided power spectrum.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// Sample spacing Δτ.
    pub dt: f64,
    /// Number of samples N.
    pub n: usize,
    /// Frequencies f_k = k/(NΔτ), cycles per unit τ.
    pub freq: Vec<f64>,
    /// One-sided PSD S_k, signal² per (cycle per unit τ).
    pub psd: Vec<f64>,
}

/// A spectral peak.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Peak {
    /// Bin of the local maximum.
    pub bin: usize,
    /// Frequency, cycles per unit τ, refined between bins by a parabola
    /// through the logarithms of the three highest bins (exact for a
    /// Gaussian peak, within a few hundredths of a bin for a Hann-windowed
    /// sine).
    pub freq: f64,
    /// ω = 2πf, in units of p.
    pub omega: f64,
    /// ω/Ω_h.
    pub harmonic: f64,
    /// PSD at the bin.
    pub psd: f64,
    /// Power under the peak: Σ S_k Δf from the minimum on its left to the
    /// one on its right (A²/2 for a sine of amplitude A).
    pub power: f64,
}

/// Errors of the spectrum functions.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    /// Fewer than [`MIN_SAMPLES`] samples.
    #[error("{0} samples; a spectrum needs at least {MIN_SAMPLES}")]
    TooFewSamples(usize),
    /// The spacing is not finite and positive.
    #[error("sample spacing {0} must be finite and > 0")]
    BadSpacing(f64),
    /// A sample is NaN or infinite.
    #[error("sample {0} is not finite")]
    NonFinite(usize),
    /// The requested window is not inside the history.
    #[error("spectrum window τ {from}..{to} is outside the history τ {have_from}..{have_to}")]
    Outside {
        /// First τ needed.
        from: f64,
        /// Last τ needed.
        to: f64,
        /// First τ of the history.
        have_from: f64,
        /// Last τ of the history.
        have_to: f64,
    },
    /// The history is not sampled uniformly (needed for `All`).
    #[error("the history is not uniformly sampled at row {0}")]
    NotUniform(usize),
    /// Nodes, values and slopes of different lengths.
    #[error("resample: times, values and slopes differ in length")]
    LengthMismatch,
    /// The FFT failed.
    #[error("FFT: {0}")]
    Fft(String),
}

/// The one-sided PSD of `samples` spaced `dt` apart (module docs).
pub(crate) fn power_spectrum(samples: &[f64], dt: f64, opts: &SpectrumOptions) -> Result<Spectrum, SpectrumError> {
    let n = samples.len();
    if n < MIN_SAMPLES {
        return Err(SpectrumError::TooFewSamples(n));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(SpectrumError::BadSpacing(dt));
    }
    if let Some(i) = samples.iter().position(|x| !x.is_finite()) {
        return Err(SpectrumError::NonFinite(i));
    }
    let mean = if opts.remove_mean {
        samples.iter().sum::<f64>() / n as f64
    } else {
        0.0
    };
    let weight = |i: usize| match opts.taper {
        Taper::Hann => (std::f64::consts::PI * i as f64 / n as f64).sin().powi(2),
        Taper::None => 1.0,
    };
    let mut input: Vec<f64> = samples
        .iter()
        .enumerate()
        .map(|(i, x)| (x - mean) * weight(i))
        .collect();
    let w2: f64 = (0..n).map(|i| weight(i).powi(2)).sum();
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(n);
    let mut output = fft.make_output_vec();
    fft.process(&mut input, &mut output)
        .map_err(|e| SpectrumError::Fft(e.to_string()))?;
    let df = 1.0 / (n as f64 * dt);
    let last = n / 2;
    let psd = output
        .iter()
        .enumerate()
        .map(|(k, x)| {
            let single = k == 0 || (n.is_multiple_of(2) && k == last);
            let c = if single { 1.0 } else { 2.0 };
            c * dt * x.norm_sqr() / w2
        })
        .collect();
    let freq = (0..output.len()).map(|k| k as f64 * df).collect();
    Ok(Spectrum { dt, n, freq, psd })
}

impl Spectrum {
    /// Bin width Δf = 1/(NΔτ), cycles per unit τ.
    pub(crate) fn df(&self) -> f64 {
        1.0 / (self.n as f64 * self.dt)
    }

    /// Σ S_k Δf: the (taper-weighted) mean square of the signal.
    pub(crate) fn total_power(&self) -> f64 {
        self.psd.iter().sum::<f64>() * self.df()
    }

    /// ω_k = 2πf_k of every bin, in units of p.
    pub fn omega(&self) -> Vec<f64> {
        self.freq.iter().map(|f| TAU * f).collect()
    }

    /// The `count` strongest local maxima (S_{k−1} < S_k ≥ S_{k+1}, k ≥ 1),
    /// strongest first, ignoring those below `min_relative` of the highest
    /// (e.g. 1e-8: rounding noise is not a frequency). `omega_h` gives the
    /// harmonic numbers.
    pub fn peaks(&self, count: usize, min_relative: f64, omega_h: f64) -> Vec<Peak> {
        let s = &self.psd;
        let top = s.iter().skip(1).fold(0.0_f64, |a, &b| a.max(b));
        let df = self.df();
        let mut peaks: Vec<Peak> = (1..s.len())
            .filter(|&k| s[k] > s[k - 1] && s.get(k + 1).is_none_or(|&r| s[k] >= r) && s[k] > min_relative * top)
            .map(|k| {
                let delta = match (s.get(k - 1), s.get(k + 1)) {
                    (Some(&a), Some(&c)) if a > 0.0 && c > 0.0 => {
                        let (la, lb, lc) = (a.ln(), s[k].ln(), c.ln());
                        let denom = la - 2.0 * lb + lc;
                        if denom < 0.0 {
                            (0.5 * (la - lc) / denom).clamp(-0.5, 0.5)
                        } else {
                            0.0
                        }
                    }
                    _ => 0.0,
                };
                let mut lo = k;
                while lo > 1 && s[lo - 1] < s[lo] {
                    lo -= 1;
                }
                let mut hi = k;
                while hi + 1 < s.len() && s[hi + 1] < s[hi] {
                    hi += 1;
                }
                let freq = (k as f64 + delta) * df;
                Peak {
                    bin: k,
                    freq,
                    omega: TAU * freq,
                    harmonic: TAU * freq / omega_h,
                    psd: s[k],
                    power: s[lo..=hi].iter().sum::<f64>() * df,
                }
            })
            .collect();
        peaks.sort_by(|a, b| b.psd.total_cmp(&a.psd).then(a.bin.cmp(&b.bin)));
        peaks.truncate(count);
        peaks
    }
}

/// Values of a sampled function at `times`, from nodes `tau` (increasing)
/// with `value`s and, if given, `slope`s: cubic Hermite interpolation with
/// the slopes, linear without. A time equal to a node takes its value
/// exactly. Inside an interval containing an impact (where the slope jumps)
/// the Hermite cubic is only as good as linear interpolation; with a
/// history on the requested grid no interpolation happens at all.
pub fn resample(tau: &[f64], value: &[f64], slope: Option<&[f64]>, times: &[f64]) -> Result<Vec<f64>, SpectrumError> {
    if value.len() != tau.len() || slope.is_some_and(|d| d.len() != tau.len()) {
        return Err(SpectrumError::LengthMismatch);
    }
    let (Some(&first), Some(&last)) = (tau.first(), tau.last()) else {
        return Err(SpectrumError::TooFewSamples(0));
    };
    let (Some(&t_lo), Some(&t_hi)) = (times.first(), times.last()) else {
        return Ok(Vec::new());
    };
    if t_lo < first || t_hi > last {
        return Err(SpectrumError::Outside {
            from: t_lo,
            to: t_hi,
            have_from: first,
            have_to: last,
        });
    }
    let mut out = Vec::with_capacity(times.len());
    for &t in times {
        let i = tau.partition_point(|&x| x < t);
        let v = match tau.get(i) {
            Some(&ti) if ti == t => value[i],
            _ if i == 0 || i >= tau.len() => {
                return Err(SpectrumError::Outside {
                    from: t_lo,
                    to: t_hi,
                    have_from: first,
                    have_to: last,
                });
            }
            _ => {
                let (t0, t1) = (tau[i - 1], tau[i]);
                let h = t1 - t0;
                let u = (t - t0) / h;
                match slope {
                    Some(d) => {
                        let (h00, h10) = ((1.0 + 2.0 * u) * (1.0 - u).powi(2), u * (1.0 - u).powi(2));
                        let (h01, h11) = (u * u * (3.0 - 2.0 * u), u * u * (u - 1.0));
                        h00 * value[i - 1] + h10 * h * d[i - 1] + h01 * value[i] + h11 * h * d[i]
                    }
                    None => value[i - 1] + u * (value[i] - value[i - 1]),
                }
            }
        };
        out.push(v);
    }
    Ok(out)
}

/// The Θ samples of a time history for `window`, with their spacing.
pub(crate) fn theta_samples(history: &[HistoryRow], window: SpectrumWindow) -> Result<(Vec<f64>, f64), SpectrumError> {
    let (first, count, dt) = match window {
        SpectrumWindow::All => {
            let n = history.len();
            if n < MIN_SAMPLES {
                return Err(SpectrumError::TooFewSamples(n));
            }
            let dt = (history[n - 1].tau - history[0].tau) / (n - 1) as f64;
            if !(dt.is_finite() && dt > 0.0) {
                return Err(SpectrumError::BadSpacing(dt));
            }
            if let Some(i) = history
                .windows(2)
                .position(|w| ((w[1].tau - w[0].tau) - dt).abs() > 1e-6 * dt)
            {
                return Err(SpectrumError::NotUniform(i + 1));
            }
            return Ok((history.iter().map(|r| r.theta).collect(), dt));
        }
        SpectrumWindow::Paper => (PAPER_FIRST, PAPER_COUNT, PAPER_DT),
        SpectrumWindow::Samples { first, count, dt } => (first, count, dt),
    };
    if !(dt.is_finite() && dt > 0.0) {
        return Err(SpectrumError::BadSpacing(dt));
    }
    let times: Vec<f64> = (first..first + count).map(|i| i as f64 * dt).collect();
    let tau: Vec<f64> = history.iter().map(|r| r.tau).collect();
    let theta: Vec<f64> = history.iter().map(|r| r.theta).collect();
    let theta_dot: Vec<f64> = history.iter().map(|r| r.theta_dot).collect();
    Ok((resample(&tau, &theta, Some(&theta_dot), &times)?, dt))
}

/// The spectrum of Θ over `window` of a time history.
pub fn theta_spectrum(
    history: &[HistoryRow],
    window: SpectrumWindow,
    opts: &SpectrumOptions,
) -> Result<Spectrum, SpectrumError> {
    let (samples, dt) = theta_samples(history, window)?;
    power_spectrum(&samples, dt, opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Mode, Sign};

    fn sines(n: usize, dt: f64, parts: &[(f64, f64)]) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                parts.iter().map(|(a, f)| a * (TAU * f * t).sin()).sum()
            })
            .collect()
    }

    #[test]
    fn parseval_holds_without_and_with_a_taper() {
        let x: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919) % 101) as f64 / 50.0 - 1.0 + 0.3)
            .collect();
        let no_taper = SpectrumOptions {
            taper: Taper::None,
            remove_mean: false,
        };
        let s = power_spectrum(&x, 0.01, &no_taper).unwrap();
        let mean_square = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
        assert!((s.total_power() - mean_square).abs() < 1e-12 * mean_square);
        // Odd length: no Nyquist bin.
        let s = power_spectrum(&x[..999], 0.01, &no_taper).unwrap();
        let ms = x[..999].iter().map(|v| v * v).sum::<f64>() / 999.0;
        assert!((s.total_power() - ms).abs() < 1e-12 * ms);
        let hann = SpectrumOptions {
            taper: Taper::Hann,
            remove_mean: false,
        };
        let s = power_spectrum(&x, 0.01, &hann).unwrap();
        let w = |i: usize| (std::f64::consts::PI * i as f64 / 1000.0).sin().powi(2);
        let weighted: f64 = x.iter().enumerate().map(|(i, v)| (w(i) * v).powi(2)).sum::<f64>()
            / (0..1000).map(|i| w(i).powi(2)).sum::<f64>();
        assert!((s.total_power() - weighted).abs() < 1e-12 * weighted);
    }

    #[test]
    fn sum_of_sines_gives_their_frequencies_and_powers() {
        // Bin-centred sines: N = 4096, dt = 0.004, df = 1/16.384.
        let (n, dt) = (4096, 0.004);
        let df = 1.0 / (n as f64 * dt);
        let (f1, f2) = (40.0 * df, 100.0 * df);
        let x = sines(n, dt, &[(1.0, f1), (0.25, f2)]);
        let s = power_spectrum(&x, dt, &SpectrumOptions::default()).unwrap();
        let p = s.peaks(5, 1e-10, 8.0);
        assert_eq!(p.len(), 2, "{p:?}");
        assert_eq!(p[0].bin, 40);
        assert!((p[0].freq - f1).abs() < 1e-9);
        assert!((p[0].power - 0.5).abs() < 1e-9, "{}", p[0].power);
        assert_eq!(p[1].bin, 100);
        assert!((p[1].power - 0.25 * 0.25 / 2.0).abs() < 1e-9);
        assert!((p[0].omega - TAU * f1).abs() < 1e-9);
        assert!((p[0].harmonic - TAU * f1 / 8.0).abs() < 1e-9);
        // Off-bin: the forcing frequency of the paper (Ω = 8) and its
        // half, which fall between bins.
        let (g1, g2) = (8.0 / TAU, 4.0 / TAU);
        let x = sines(n, dt, &[(0.8, g1), (0.3, g2)]);
        let s = power_spectrum(&x, dt, &SpectrumOptions::default()).unwrap();
        let p = s.peaks(2, 1e-6, 8.0);
        assert!((p[0].freq - g1).abs() < 0.05 * df, "{} vs {g1}", p[0].freq);
        assert!((p[0].harmonic - 1.0).abs() < 0.01);
        assert!((p[1].freq - g2).abs() < 0.05 * df);
        assert!((p[1].harmonic - 0.5).abs() < 0.01);
        assert!((p[0].power / (0.8 * 0.8 / 2.0) - 1.0).abs() < 0.02, "{}", p[0].power);
        assert!((p[1].power / (0.3 * 0.3 / 2.0) - 1.0).abs() < 0.02, "{}", p[1].power);
    }

    #[test]
    fn bad_input_is_an_error() {
        let o = SpectrumOptions::default();
        assert_eq!(power_spectrum(&[1.0; 4], 0.1, &o), Err(SpectrumError::TooFewSamples(4)));
        assert_eq!(power_spectrum(&[1.0; 16], 0.0, &o), Err(SpectrumError::BadSpacing(0.0)));
        let mut x = vec![1.0; 16];
        x[3] = f64::NAN;
        assert_eq!(power_spectrum(&x, 0.1, &o), Err(SpectrumError::NonFinite(3)));
    }

    #[test]
    fn resample_is_exact_on_nodes_and_for_cubics() {
        let tau: Vec<f64> = (0..11).map(|i| f64::from(i) * 0.1).collect();
        let f = |t: f64| 2.0 * t * t * t - t + 0.5;
        let df = |t: f64| 6.0 * t * t - 1.0;
        let v: Vec<f64> = tau.iter().map(|&t| f(t)).collect();
        let d: Vec<f64> = tau.iter().map(|&t| df(t)).collect();
        let times = [0.0, 0.15, 0.33, 0.5, 0.999, 1.0];
        let r = resample(&tau, &v, Some(&d), &times).unwrap();
        for (t, x) in times.iter().zip(r) {
            assert!((x - f(*t)).abs() < 1e-12, "{t}");
        }
        assert_eq!(resample(&tau, &v, None, &[tau[3]]).unwrap()[0], v[3]);
        assert!(matches!(
            resample(&tau, &v, None, &[0.5, 1.2]),
            Err(SpectrumError::Outside { .. })
        ));
        assert_eq!(
            resample(&tau, &v[1..], None, &[0.5]),
            Err(SpectrumError::LengthMismatch)
        );
    }

    #[test]
    fn paper_window_takes_samples_3000_to_7095_of_a_history_on_its_grid() {
        let rows: Vec<HistoryRow> = (0..8000)
            .map(|i| {
                let tau = f64::from(i) * PAPER_DT;
                HistoryRow {
                    tau,
                    theta: (3.0 * tau).sin(),
                    theta_dot: 3.0 * (3.0 * tau).cos(),
                    x: 0.0,
                    x_dot: 0.0,
                    mode: Mode::Rock { pivot: Sign::Pos },
                }
            })
            .collect();
        let (x, dt) = theta_samples(&rows, SpectrumWindow::Paper).unwrap();
        assert_eq!((x.len(), dt), (4096, 0.004));
        assert_eq!(x[0], rows[3000].theta);
        assert_eq!(x[4095], rows[7095].theta);
        let (all, dt_all) = theta_samples(&rows, SpectrumWindow::All).unwrap();
        assert_eq!(all.len(), 8000);
        assert!((dt_all - 0.004).abs() < 1e-15);
        assert!(theta_samples(&rows[..5000], SpectrumWindow::Paper).is_err());
    }
}
