//! The response examples of the paper (Figs. 7, 8, 11–13, 16–19): for one
//! configuration, its time history, power spectra, Poincaré map, largest
//! Lyapunov exponent (two methods) and maximum amplitude.
//!
//! Three runs from the preset's initial state (rest), all deterministic:
//! 1. **the paper's run**, τ 0–`history_end` (800) sampled every 0.004
//!    (the paper's step): the time history and both spectra come from it;
//! 2. **a long run**, τ 0–`long_end`, section only: its Poincaré points
//!    after the transient show the attractor with many more points than
//!    the paper's 255, and they are what the response is classified from;
//! 3. **the Lyapunov run**, tangent dynamics and two trajectories on one
//!    fiducial trajectory ([`Method::Both`]).
//!
//! A run that tumbles is reported as such (with its τ), never as NaN.

use super::ReproduceError;
use super::paper::PaperFigure;
use crate::analysis::classify::{ClassifyOptions, Response, classify_points};
use crate::analysis::lyapunov::{Lyapunov, LyapunovOptions, Method, lyapunov};
use crate::analysis::section::{after_transient, block_coordinates};
use crate::analysis::spectrum::{
    PAPER_DT, Peak, SpectrumOptions, SpectrumWindow, theta_spectrum,
};
use crate::analysis::steady::ParamBase;
use crate::io::config::Config;
use crate::sim::{Outcome, simulate};

/// Sampling step of the paper's run, τ (the paper's integration step).
pub const HISTORY_DT: f64 = PAPER_DT;
/// Sampling step of the long run's history used for the long spectrum, τ:
/// 25 cycles per unit τ at Nyquist, i.e. 19 harmonics of Ω_h = 8.
pub const LONG_DT: f64 = 0.02;

/// Run lengths of a response example.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ResponseSettings {
    /// End of the paper's run, τ. Default 800 (200,000 steps of 0.004).
    pub history_end: f64,
    /// Start of the time-history view and of the steady part, τ.
    /// Default 600 (the paper's transient).
    pub transient: f64,
    /// End of the long run, τ. Default 4000: ~4300 Poincaré points at
    /// Ω_h = 8, enough to draw the attractor.
    pub long_end: f64,
    /// Discarded start of the Lyapunov run, τ.
    pub lyapunov_transient: f64,
    /// End of the Lyapunov run, τ.
    pub lyapunov_end: f64,
    /// Batches for the Lyapunov error bars.
    pub lyapunov_batches: usize,
}

impl ResponseSettings {
    /// The full settings: paper's run to 800, long run to 4000, Lyapunov
    /// exponents over τ 600–2600 (2000 τ, ~2500 periods at Ω_h = 8, the
    /// default of [`LyapunovOptions`]).
    pub fn full() -> Self {
        Self {
            history_end: 800.0,
            transient: 600.0,
            long_end: 4000.0,
            lyapunov_transient: 600.0,
            lyapunov_end: 2600.0,
            lyapunov_batches: 16,
        }
    }

    /// CI-sized settings: the same paper's run, a long run to 1200 and
    /// Lyapunov exponents over τ 200–600 (a rough estimate).
    pub fn quick() -> Self {
        Self {
            history_end: 800.0,
            transient: 600.0,
            long_end: 1200.0,
            lyapunov_transient: 200.0,
            lyapunov_end: 600.0,
            lyapunov_batches: 8,
        }
    }
}

/// A power spectrum of Θ ready to plot and report.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumData {
    /// First τ of the window.
    pub tau_from: f64,
    /// Last τ of the window.
    pub tau_to: f64,
    /// Number of samples.
    pub samples: usize,
    /// Sample spacing, τ.
    pub dt: f64,
    /// ω/Ω_h of each bin.
    pub harmonic: Vec<f64>,
    /// PSD of each bin.
    pub psd: Vec<f64>,
    /// The strongest peaks, strongest first.
    pub peaks: Vec<Peak>,
    /// Total power Σ S Δf (Hann-weighted mean square of Θ).
    pub total_power: f64,
}

/// Everything computed for one response example.
#[derive(Clone, Debug)]
pub struct ResponseExample {
    /// The paper's figure number.
    pub figure: u32,
    /// The configuration (the preset; `run.tau_end` that of the paper's run).
    pub config: Config,
    /// The run lengths.
    pub settings: ResponseSettings,
    /// How the paper's run ended.
    pub outcome: Outcome,
    /// τ at which it tumbled, if it did.
    pub tumble_tau: Option<f64>,
    /// Largest |Θ| over the paper's run, τ 0–800 (transient included).
    pub max_abs_theta: f64,
    /// Largest |Θ| of the samples at τ ≥ transient (None if the run
    /// ended before).
    pub max_abs_theta_steady: Option<f64>,
    /// Times the normal force vanished (counted, `flight = "ignore"`).
    pub flight_violations: u64,
    /// Impacts per forcing cycle over the paper's run.
    pub impacts_per_cycle: f64,
    /// (τ, Θ) of the paper's run from the transient on (or from 0 if it
    /// tumbled before).
    pub history: Vec<(f64, f64)>,
    /// The spectrum of the paper's window (τ 12–28.4), if the run lasted.
    pub spectrum_paper: Result<SpectrumData, String>,
    /// The spectrum of the long run from the transient on.
    pub spectrum_long: Result<SpectrumData, String>,
    /// How the long run ended, its end τ and its tumble τ.
    pub long_outcome: Outcome,
    /// τ at which the long run ended.
    pub long_tau_end: f64,
    /// Largest |Θ| over the long run.
    pub long_max_abs_theta: f64,
    /// (Θ, Θ') of the long run's section points after the transient.
    pub poincare: Vec<(f64, f64)>,
    /// Mean Θ and mean Θ' of those points (the attractor's asymmetry).
    pub poincare_mean: Option<(f64, f64)>,
    /// The long run's class, decided by the Lyapunov exponent when there
    /// is one.
    pub response: Response,
    /// The Lyapunov result, or why it failed.
    pub lyapunov: Result<Lyapunov, String>,
    /// Wall time, s.
    pub wall_s: f64,
}

/// Computes the response example of `figure`.
pub fn run_response(
    figure: &PaperFigure,
    settings: &ResponseSettings,
    classify: &ClassifyOptions,
) -> Result<ResponseExample, ReproduceError> {
    let start = std::time::Instant::now();
    let fail = |what: &str, e: String| ReproduceError::Figure {
        figure: figure.number,
        what: what.to_string(),
        error: e,
    };
    let base = ParamBase::load(Some(figure.preset), None, &[]).map_err(|e| fail("configuration", e.to_string()))?;
    let mut config = base.resolve(&[]).map_err(|e| fail("configuration", e.to_string()))?;
    config.tau_end = settings.history_end;
    let model = config.model().map_err(|e| fail("configuration", e.to_string()))?;
    let Some(period) = model.excitation.forcing_period() else {
        return Err(fail("configuration", "the excitation is not harmonic".to_string()));
    };
    let init = config.initial();

    // 1. The paper's run.
    let mut opts = config.run_options();
    opts.output_dt = Some(HISTORY_DT);
    opts.section = true;
    let paper = simulate(model.clone(), &init, &opts).map_err(|e| fail("the paper's run", e.to_string()))?;
    let view_from = if paper.tau_end > settings.transient {
        settings.transient
    } else {
        0.0
    };
    let history: Vec<(f64, f64)> = paper
        .history
        .iter()
        .filter(|r| r.tau >= view_from)
        .map(|r| (r.tau, r.theta))
        .collect();
    let max_abs_theta_steady = paper
        .history
        .iter()
        .filter(|r| r.tau >= settings.transient)
        .map(|r| r.theta.abs())
        .reduce(f64::max);
    let spec_opts = SpectrumOptions::default();
    let omega_h = config.omega_h;
    let spectrum_paper = spectrum(&paper.history, SpectrumWindow::Paper, &spec_opts, omega_h);

    // 2. The long run.
    let mut long_opts = opts;
    long_opts.tau_end = settings.long_end;
    long_opts.output_dt = Some(LONG_DT);
    let long = simulate(model.clone(), &init, &long_opts).map_err(|e| fail("the long run", e.to_string()))?;
    let first = (settings.transient / LONG_DT).ceil() as usize;
    let last = (long.tau_end / LONG_DT).floor() as usize;
    let spectrum_long = if last > first + 64 {
        spectrum(
            &long.history,
            SpectrumWindow::Samples {
                first,
                count: last - first,
                dt: LONG_DT,
            },
            &spec_opts,
            omega_h,
        )
    } else {
        Err(format!(
            "the run ended at τ = {:.1}, before a window after τ = {} could be taken",
            long.tau_end, settings.transient
        ))
    };
    let steady = after_transient(&long.section, settings.transient);
    let poincare: Vec<(f64, f64)> = if long.outcome == Outcome::Tumbled || long.outcome == Outcome::Flight {
        Vec::new()
    } else {
        steady.iter().map(|r| (r.theta, r.theta_dot)).collect()
    };
    let poincare_mean = (!poincare.is_empty()).then(|| {
        let n = poincare.len() as f64;
        (
            poincare.iter().map(|p| p.0).sum::<f64>() / n,
            poincare.iter().map(|p| p.1).sum::<f64>() / n,
        )
    });

    // 3. Lyapunov exponents.
    let lyap_opts = LyapunovOptions {
        method: Method::Both,
        transient_tau: settings.lyapunov_transient,
        total_tau: settings.lyapunov_end,
        batches: settings.lyapunov_batches,
        ..LyapunovOptions::default()
    };
    let lyapunov = lyapunov(&model, &init, &lyap_opts).map_err(|e| e.to_string());

    let response = match long.outcome {
        Outcome::Tumbled => Response::Tumbled,
        Outcome::Flight => Response::Flight,
        Outcome::Rest | Outcome::Running => {
            let lambda = lyapunov.as_ref().ok().and_then(Lyapunov::largest_per_tau);
            classify_points(&block_coordinates(steady), lambda, classify)
                .map_err(|e| fail("classification", e.to_string()))?
        }
    };
    let cycles = (paper.tau_end / period).max(1.0);
    Ok(ResponseExample {
        figure: figure.number,
        config,
        settings: *settings,
        outcome: paper.outcome,
        tumble_tau: paper.tumble_tau,
        max_abs_theta: paper.max_abs_theta,
        max_abs_theta_steady,
        flight_violations: paper.tally.flight_violations,
        impacts_per_cycle: paper.tally.impacts as f64 / cycles,
        history,
        spectrum_paper,
        spectrum_long,
        long_outcome: long.outcome,
        long_tau_end: long.tau_end,
        long_max_abs_theta: long.max_abs_theta,
        poincare,
        poincare_mean,
        response,
        lyapunov,
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// The spectrum of Θ over `window` of `history`, with its peaks (the six
/// strongest above 10⁻⁶ of the highest).
fn spectrum(
    history: &[crate::sim::HistoryRow],
    window: SpectrumWindow,
    opts: &SpectrumOptions,
    omega_h: f64,
) -> Result<SpectrumData, String> {
    let s = theta_spectrum(history, window, opts).map_err(|e| e.to_string())?;
    let (tau_from, count, dt) = match window {
        SpectrumWindow::Paper => (
            crate::analysis::spectrum::PAPER_FIRST as f64 * PAPER_DT,
            crate::analysis::spectrum::PAPER_COUNT,
            PAPER_DT,
        ),
        SpectrumWindow::Samples { first, count, dt } => (first as f64 * dt, count, dt),
        SpectrumWindow::All => (history.first().map_or(0.0, |r| r.tau), history.len(), s.dt),
    };
    let harmonic: Vec<f64> = s.omega().iter().map(|w| w / omega_h).collect();
    Ok(SpectrumData {
        tau_from,
        tau_to: tau_from + (count.saturating_sub(1)) as f64 * dt,
        samples: s.n,
        dt: s.dt,
        peaks: s.peaks(6, 1e-6, omega_h),
        total_power: s.total_power(),
        harmonic,
        psd: s.psd,
    })
}
