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
//!    fiducial trajectory ([`Method::Both`]); if it tumbles, a second one
//!    over the rocking before the tumble gives the finite-time exponent of
//!    that chaotic transient, labelled as such;
//! 4. **neighbouring runs** at A_v·(1 + k·10⁻⁹), classified over the
//!    paper's window: how typical the preset's own run is.
//!
//! A run that tumbles is reported as such (with its τ), never as NaN; its
//! Poincaré map and long spectrum then show the rocking before the tumble.

use super::ReproduceError;
use super::paper::PaperFigure;
use super::variant::Variant;
use crate::analysis::classify::{ClassifyOptions, Response, classify_points};
use crate::analysis::lyapunov::{Lyapunov, LyapunovOptions, Method, NoExponent, lyapunov};
use crate::analysis::section::{after_transient, block_coordinates};
use crate::analysis::spectrum::{PAPER_DT, Peak, SpectrumOptions, SpectrumWindow, theta_spectrum};
use crate::analysis::steady::{Window, steady_response};
use crate::io::config::load;
use crate::model::Model;
use crate::sim::{Outcome, Param, Scenario, SectionRow, simulate};

/// Sampling step of the paper's run, τ (the paper's integration step).
pub(crate) const HISTORY_DT: f64 = PAPER_DT;
/// Sampling step of the long run's history used for the long spectrum, τ:
/// 25 cycles per unit τ at Nyquist, i.e. 19 harmonics of Ω_h = 8.
pub(crate) const LONG_DT: f64 = 0.02;

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
    /// The response is classified from the long run's last `end_window`
    /// τ: what it settles to, after any chaotic transient. Default 800
    /// (~1000 points at Ω_h = 8).
    pub end_window: f64,
    /// Discarded start of the Lyapunov run, τ.
    pub lyapunov_transient: f64,
    /// End of the Lyapunov run, τ.
    pub lyapunov_end: f64,
    /// Batches for the Lyapunov error bars.
    pub lyapunov_batches: usize,
    /// Neighbouring runs: A_v·(1 + k·10⁻⁹) for k = 1 … this, each over the
    /// paper's window (τ 600–800) and classified, to show how typical the
    /// preset's own run is of the response at this A_v (a chaotic response
    /// makes every neighbour follow a different trajectory).
    pub neighbours: usize,
}

/// Relative step of the neighbouring runs' A_v: far below any precision
/// the paper could have meant, far above rounding.
pub(crate) const NEIGHBOUR_STEP: f64 = 1e-9;

impl ResponseSettings {
    /// The full settings: paper's run to 800, long run to 4000, Lyapunov
    /// exponents over τ 600–2600 (2000 τ, ~2500 periods at Ω_h = 8, the
    /// default of [`LyapunovOptions`]).
    pub fn full() -> Self {
        Self {
            history_end: 800.0,
            transient: 600.0,
            long_end: 4000.0,
            end_window: 800.0,
            lyapunov_transient: 600.0,
            lyapunov_end: 2600.0,
            lyapunov_batches: 16,
            neighbours: 24,
        }
    }

    /// CI-sized settings: the same paper's run, a long run to 1200,
    /// Lyapunov exponents over τ 600–1000 (a rough estimate of the steady
    /// response) and 4 neighbours.
    pub fn quick() -> Self {
        Self {
            history_end: 800.0,
            transient: 600.0,
            long_end: 1200.0,
            end_window: 400.0,
            lyapunov_transient: 600.0,
            lyapunov_end: 1000.0,
            lyapunov_batches: 8,
            neighbours: 4,
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
    pub config: Scenario,
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
    /// First τ of the Poincaré points and of the long spectrum: the
    /// transient, or a quarter of the run's length when it tumbled before
    /// the transient was over (the points then show the chaotic transient).
    pub steady_from: f64,
    /// (Θ, Θ') of the long run's section points from `steady_from` on.
    pub poincare: Vec<(f64, f64)>,
    /// Mean Θ and mean Θ' of those points (the attractor's asymmetry).
    pub poincare_mean: Option<(f64, f64)>,
    /// First τ of the points the response is classified from (the last
    /// `end_window` of the long run).
    pub end_from: f64,
    /// The class of the end of the long run; between chaotic and
    /// quasiperiodic, the Lyapunov exponent decides when there is one.
    pub response: Response,
    /// The Lyapunov result, or why it failed.
    pub lyapunov: Result<Lyapunov, String>,
    /// When the Lyapunov run tumbled: the exponent of the chaotic transient
    /// before it, over `(from, to)` τ, with the tumble τ — a finite-time
    /// exponent, labelled as such.
    pub transient_lyapunov: Option<TransientExponent>,
    /// The responses of the neighbouring runs (see
    /// [`ResponseSettings::neighbours`]), in k order.
    pub neighbours: Vec<Response>,
    /// Wall time, s.
    pub wall_s: f64,
}

/// Computes the response example of `figure`.
pub(crate) fn run_response(
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
    let base = load(Some(figure.preset), None, &[]).map_err(|e| fail("configuration", e.to_string()))?;
    let (config, model, period) = paper_setup(&base, settings, &fail)?;
    let init = config.initial;

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
    let omega_h = config.excitation.omega_h;
    let spectrum_paper = spectrum(&paper.history, SpectrumWindow::Paper, &spec_opts, omega_h);

    // 2. The long run.
    let mut long_opts = opts;
    long_opts.tau_end = settings.long_end;
    long_opts.output_dt = Some(LONG_DT);
    let long = simulate(model.clone(), &init, &long_opts).map_err(|e| fail("the long run", e.to_string()))?;
    let terminal = matches!(long.outcome, Outcome::Tumbled | Outcome::Flight);
    let steady_from = if terminal && long.tau_end < settings.transient + 50.0 {
        0.25 * long.tau_end
    } else {
        settings.transient
    };
    let first = (steady_from / LONG_DT).ceil() as usize;
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
            "the run ended at τ = {:.1}, before a window after τ = {steady_from} could be taken",
            long.tau_end
        ))
    };
    let steady = after_transient(&long.section, steady_from);
    let end_from = (long.tau_end - settings.end_window).max(steady_from);
    let poincare: Vec<(f64, f64)> = steady.iter().map(|r| (r.theta, r.theta_dot)).collect();
    let poincare_mean = (!poincare.is_empty()).then(|| {
        let n = poincare.len() as f64;
        (
            poincare.iter().map(|p| p.0).sum::<f64>() / n,
            poincare.iter().map(|p| p.1).sum::<f64>() / n,
        )
    });

    // 3. Lyapunov exponents.
    let (lyap, transient_lyapunov) = exponents(&model, &init, settings, Method::Both, period);

    // 4. The neighbours.
    let neighbours = (1..=settings.neighbours)
        .map(|k| {
            let a_v = config.excitation.a_v * (1.0 + k as f64 * NEIGHBOUR_STEP);
            let cfg = Param::apply(&base, &[(Param::Av, a_v)]).map_err(|e| fail("neighbouring runs", e.to_string()))?;
            let w = Window {
                transient: settings.transient,
                tau_end: settings.history_end,
            };
            steady_response(&cfg, &w, classify, None)
                .map(|s| s.response)
                .map_err(|e| fail("neighbouring runs", e.to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;

    let response = end_response(long.outcome, after_transient(steady, end_from), &lyap, classify, &fail)?;
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
        steady_from,
        end_from,
        poincare,
        poincare_mean,
        response,
        lyapunov: lyap,
        transient_lyapunov,
        neighbours,
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// The configuration of the paper's run from `base` (its end at the
/// settings' `history_end`), its model and its forcing period; `fail`
/// words an error.
fn paper_setup(
    base: &Scenario,
    settings: &ResponseSettings,
    fail: &impl Fn(&str, String) -> ReproduceError,
) -> Result<(Scenario, Model, f64), ReproduceError> {
    let mut config = base.clone();
    config.run.tau_end = settings.history_end;
    let model = config.model().map_err(|e| fail("configuration", e.to_string()))?;
    let Some(period) = model.excitation.forcing_period() else {
        return Err(fail("configuration", "the excitation is not harmonic".to_string()));
    };
    Ok((config, model, period))
}

/// The class of the end of a long run that ended by `outcome`: tumbled
/// or flight as it ended, else the class of its section points `rows`
/// (between chaotic and quasiperiodic, the largest exponent of `lyap`
/// decides when there is one).
fn end_response(
    outcome: Outcome,
    rows: &[SectionRow],
    lyap: &Result<Lyapunov, String>,
    classify: &ClassifyOptions,
    fail: &impl Fn(&str, String) -> ReproduceError,
) -> Result<Response, ReproduceError> {
    Ok(match outcome {
        Outcome::Tumbled => Response::Tumbled,
        Outcome::Flight => Response::Flight,
        Outcome::Rest | Outcome::Running => {
            let lambda = lyap.as_ref().ok().and_then(Lyapunov::largest_per_tau);
            classify_points(&block_coordinates(rows), lambda, classify)
                .map_err(|e| fail("classification", e.to_string()))?
        }
    })
}

/// The Lyapunov exponents of `model` from `init` over the settings'
/// window by `method`; if that run tumbles, also those of the rocking
/// before the tumble (from a quarter of its length, or the usual
/// transient if earlier, to five periods before it, if that leaves at
/// least 20 periods), with that window `(from, to, tumble τ)`.
pub fn exponents(
    model: &Model,
    init: &crate::sim::InitialState,
    settings: &ResponseSettings,
    method: Method,
    period: f64,
) -> TransientExponents {
    let opts = LyapunovOptions {
        method,
        transient_tau: settings.lyapunov_transient,
        total_tau: settings.lyapunov_end,
        batches: settings.lyapunov_batches,
        ..LyapunovOptions::default()
    };
    let main = lyapunov(model, init, &opts).map_err(|e| e.to_string());
    let transient = match &main {
        Ok(Lyapunov::None {
            no_exponent: NoExponent::Tumbled,
            tau,
            ..
        }) => {
            let from = settings.lyapunov_transient.min(0.25 * tau);
            let to = tau - 5.0 * period;
            (to - from >= 20.0 * period).then(|| {
                let opts = LyapunovOptions {
                    transient_tau: from,
                    total_tau: to,
                    ..opts
                };
                TransientExponent {
                    window: TransientWindow {
                        from,
                        to,
                        tumble_tau: *tau,
                    },
                    lyapunov: lyapunov(model, init, &opts).map_err(|e| e.to_string()),
                }
            })
        }
        Ok(_) | Err(_) => None,
    };
    (main, transient)
}

/// The result of [`exponents`]: the exponents over the settings' window,
/// and those of the transient before a tumble.
pub(crate) type TransientExponents = (Result<Lyapunov, String>, Option<TransientExponent>);

/// The window of a chaotic transient's exponent, τ.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TransientWindow {
    /// Start of the accumulation.
    pub from: f64,
    /// End of the accumulation (five periods before the tumble).
    pub to: f64,
    /// When that run tumbled.
    pub tumble_tau: f64,
}

/// The Lyapunov exponents of the rocking before a tumble: a finite-time
/// exponent of a chaotic transient, labelled as such wherever it is shown.
#[derive(Clone, Debug, PartialEq)]
pub struct TransientExponent {
    /// Its window.
    pub window: TransientWindow,
    /// The exponents, or why there are none.
    pub lyapunov: Result<Lyapunov, String>,
}

/// A response example recomputed with an impact-law variant (fewer
/// outputs: no history, spectra or neighbours).
#[derive(Clone, Debug)]
pub struct ResponseVariant {
    /// The paper's figure number.
    pub figure: u32,
    /// The variant.
    pub variant: Variant,
    /// Its `--set` assignments.
    pub sets: Vec<String>,
    /// Largest |Θ| over the paper's run, τ 0–800.
    pub max_abs_theta: f64,
    /// τ at which the long run tumbled, if it did.
    pub tumble_tau: Option<f64>,
    /// First τ of the points the response is classified from.
    pub end_from: f64,
    /// τ at which the long run ended.
    pub long_tau_end: f64,
    /// The class of the end of the long run.
    pub response: Response,
    /// Largest exponent by tangent dynamics over the settings' window.
    pub lyapunov: Result<Lyapunov, String>,
    /// The exponent of the transient before a tumble.
    pub transient_lyapunov: Option<TransientExponent>,
    /// Wall time, s.
    pub wall_s: f64,
}

/// The impact-law variants run for a response example: Housner's law and
/// the printed eq. 20 (r = 0.830) for every figure, and the paper's
/// impact law with friction (eqs. 17–27) where the block can slide
/// (without sliding it is Housner's law).
pub(crate) fn response_variants(cfg: &Scenario) -> Vec<Variant> {
    if cfg.block.mu_s.is_finite() {
        vec![Variant::Housner, Variant::ImpulseLaw, Variant::PrintedEq20]
    } else {
        vec![Variant::Housner, Variant::PrintedEq20]
    }
}

/// Computes the response example of `figure` with `variant`.
pub(crate) fn run_response_variant(
    figure: &PaperFigure,
    variant: Variant,
    settings: &ResponseSettings,
    classify: &ClassifyOptions,
) -> Result<ResponseVariant, ReproduceError> {
    let start = std::time::Instant::now();
    let fail = |what: &str, e: String| ReproduceError::Figure {
        figure: figure.number,
        what: format!("{what} ({})", variant.slug()),
        error: e,
    };
    let plain = load(Some(figure.preset), None, &[]).map_err(|e| fail("configuration", e.to_string()))?;
    let geo = plain.geometry();
    let sets = variant.sets(&geo);
    let base = load(Some(figure.preset), None, &sets).map_err(|e| fail("configuration", e.to_string()))?;
    let (config, model, period) = paper_setup(&base, settings, &fail)?;
    let init = config.initial;
    let mut opts = config.run_options();
    opts.output_dt = None;
    opts.section = true;
    let paper = simulate(model.clone(), &init, &opts).map_err(|e| fail("the paper's run", e.to_string()))?;
    let mut long_opts = opts;
    long_opts.tau_end = settings.long_end;
    let long = simulate(model.clone(), &init, &long_opts).map_err(|e| fail("the long run", e.to_string()))?;
    let (lyap, transient_lyapunov) = exponents(&model, &init, settings, Method::Tangent, period);
    let end_from = (long.tau_end - settings.end_window).max(settings.transient);
    let response = end_response(
        long.outcome,
        after_transient(&long.section, end_from),
        &lyap,
        classify,
        &fail,
    )?;
    Ok(ResponseVariant {
        figure: figure.number,
        variant,
        sets,
        max_abs_theta: paper.max_abs_theta,
        tumble_tau: long.tumble_tau,
        end_from,
        long_tau_end: long.tau_end,
        response,
        lyapunov: lyap,
        transient_lyapunov,
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
