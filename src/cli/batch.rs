//! `rocking --batch`: one headless run.

use anyhow::Context as _;

use super::Cli;
use super::error::BatchError;
use super::exponents::{lyapunov_summary, say_lyapunov};
use crate::io::csv::{self, Num, Row};
use crate::io::output::{self, RunFiles};
use crate::io::staging::Staging;
use crate::sim::scenario::SpectrumRange;
use crate::sim::{self, Scenario};

/// Bytes of one `history.csv` row, for the estimate printed before a large
/// run: 153–160 measured over 5·10⁶ and 5·10⁷ rows of the fig4 scene.
const HISTORY_BYTES_PER_ROW: f64 = 160.0;

/// Steps per second of `ralston`, for the estimate printed before a long
/// run: 1.2·10⁷ measured (fig4, τ 4·10⁴, release build), rounded down.
const RALSTON_STEPS_PER_S: f64 = 1e7;

/// Runs `--batch` as described by `cli`. Nothing is written unless the run
/// succeeds.
pub fn run(cli: &Cli) -> Result<(), BatchError> {
    let cfg: Scenario = cli.scene.load().map_err(|e| BatchError::Input(e.into()))?;
    if cfg.stack.is_some() {
        return super::stack_batch::run(cli, &cfg);
    }
    let model = cfg.model().map_err(|e| BatchError::Input(e.into()))?;
    for warning in cfg.warnings() {
        eprintln!("{warning}");
    }
    output::check_writable(&cli.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(BatchError::Input)?;
    // A fixed-step run's length is known before it starts: one clearly
    // longer than a minute is said (runs beyond run.max_steps are refused
    // by the scenario's checks).
    if cfg.run.method() == sim::Method::Ralston {
        let steps = cfg.tau_end() / cfg.run.step;
        let seconds = steps / RALSTON_STEPS_PER_S;
        if seconds > 60.0 {
            eprintln!(
                "note: run.method = \"ralston\" takes {steps:.2e} steps of {:?} over τ = {:?}: about {:.0} minutes at 10^7 steps per second",
                cfg.run.step,
                cfg.tau_end(),
                seconds / 60.0
            );
        }
    }
    // A history of more than a gigabyte is said before it is written (the
    // 5e7-row limit of run.output_dt caps it near 8 GB).
    if cfg.run.output_dt > 0.0 {
        let rows = (cfg.tau_end() / cfg.run.output_dt).floor() + 1.0;
        let bytes = rows * HISTORY_BYTES_PER_ROW;
        if bytes > 1e9 {
            eprintln!(
                "note: history.csv will hold about {rows:.2e} rows, about {:.1} GB (run.output_dt = {:?} over τ = {:?})",
                bytes / 1e9,
                cfg.run.output_dt,
                cfg.tau_end()
            );
        }
    }
    // The CSV files are written as the run produces them, into a staging
    // folder that becomes --out only when everything is written: memory
    // does not grow with the run, and a failed run leaves nothing.
    let geo = cfg.geometry();
    let mut staging = Staging::new(&cli.out)
        .context("--out")
        .map_err(super::write::output_error)?;
    let mut files = RunFiles::create(&mut staging, geo, cfg.frame, cfg.analyses.spectrum)
        .context("--out")
        .map_err(super::write::output_error)?;
    let res = sim::simulate_into(model, &cfg.initial, &cfg.run_options(), &mut files)
        .context("simulation failed")
        .map_err(BatchError::Run)?;
    let history = files
        .finish()
        .with_context(|| format!("writing {}", cli.out.display()))
        .map_err(super::write::output_error)?;
    let mut summary = output::summary_json(&cfg, &res);
    let exponents = if cfg.analyses.lyapunov {
        Some(lyapunov_summary(&cfg)?)
    } else {
        None
    };
    if let (Some(l), Some(obj)) = (&exponents, summary.as_object_mut()) {
        obj.insert("lyapunov".to_string(), l.summary());
    }
    let spectrum = if cfg.analyses.spectrum {
        Some(spectrum_of(&cfg, &history)?)
    } else {
        None
    };
    if let (Some((_, peaks)), Some(obj)) = (&spectrum, summary.as_object_mut()) {
        obj.insert("spectrum".to_string(), peaks.clone());
    }
    let summary_text = serde_json::to_string_pretty(&summary)
        .context("serialising summary.json")
        .map_err(BatchError::Run)?;
    let write = |staging: &mut Staging| -> anyhow::Result<()> {
        staging.text("summary.json", &(summary_text + "\n"))?;
        if let Some((csv, _)) = spectrum {
            staging.text("spectrum.csv", &csv)?;
        }
        Ok(())
    };
    write(&mut staging)
        .and_then(|()| Ok(staging.commit()?))
        .with_context(|| format!("writing {}", cli.out.display()))
        .map_err(super::write::output_error)?;
    if !cli.quiet {
        crate::say!("{}", sim::Physical::of(&cfg, &res).line());
        let outcome = serde_json::to_value(res.outcome).unwrap_or_default();
        crate::say!(
            "outcome {} at tau {:.6} | impacts {} | max |theta| {:.6} | energy residual {:.2e} (relative {:.1e}) | {} steps, {} rhs evals, solver {:.3} s",
            outcome.as_str().unwrap_or("?"),
            res.tau_end,
            res.tally.impacts,
            res.max_abs_theta,
            res.energy.residual,
            res.energy.relative_residual,
            res.stats.accepted,
            res.stats.rhs_evals,
            res.wall_s,
        );
        crate::say!(
            "wrote {}/{{summary.json, events.csv ({} events), poincare.csv ({} points), history.csv ({} rows)}}",
            cli.out.display(),
            res.tallies.events,
            res.tallies.section,
            res.tallies.history
        );
        say_lyapunov(exponents.as_ref());
    }
    Ok(())
}

/// The power spectrum of Θ(τ) from the run's history (`analysis.spectrum`):
/// `spectrum.csv` (`freq,omega,omega_over_omega_h,psd`; f in cycles per
/// unit τ, ω = 2πf in units of p, ω/Ω_h with `excitation.omega_h`) and the
/// ten dominant peaks for `summary.json`.
fn spectrum_of(cfg: &Scenario, history: &[sim::HistoryRow]) -> Result<(String, serde_json::Value), BatchError> {
    use crate::analysis::spectrum::{SpectrumOptions, SpectrumWindow, theta_spectrum};
    let window = match cfg.analyses.spectrum_window {
        SpectrumRange::Paper => SpectrumWindow::Paper,
        SpectrumRange::All => SpectrumWindow::All,
    };
    let sp = theta_spectrum(history, window, &SpectrumOptions::default())
        .context("analysis.spectrum")
        .map_err(BatchError::Run)?;
    /// A row of `spectrum.csv`.
    #[derive(serde::Serialize)]
    struct SpectrumRow {
        freq: Num,
        omega: Num,
        omega_over_omega_h: Num,
        psd: Num,
    }
    impl Row for SpectrumRow {
        const HEADER: &'static [&'static str] = &["freq", "omega", "omega_over_omega_h", "psd"];
    }
    let csv = csv::to_string(sp.freq.iter().zip(&sp.psd).map(|(&f, &p)| {
        let omega = std::f64::consts::TAU * f;
        SpectrumRow {
            freq: Num(f),
            omega: Num(omega),
            omega_over_omega_h: Num(omega / cfg.excitation.omega_h),
            psd: Num(p),
        }
    }));
    let peaks = sp.peaks(10, 1e-6, cfg.excitation.omega_h);
    let summary = serde_json::json!({
        "window": cfg.analyses.spectrum_window.name(),
        "samples": sp.n,
        "dt": sp.dt,
        "taper": "hann",
        "peaks": peaks,
    });
    Ok((csv, summary))
}
