//! `rocking pulse-map`: the Makris-style overturning map of analytic
//! pulses: for each pulse shape, slenderness and ω_p/p, the smallest
//! amplitude a_p/(g tan α) that overturns the block, and the safe windows
//! above it.
//!
//! Writes into `--out`: `pulse_map.csv`, `safe_windows.csv`,
//! `pulse_map.json` (the settings, the base configuration and the crate
//! version) and `pulse_map.png/svg`. Bad input exits 2 naming the flag;
//! nothing is written on error.

use std::time::Instant;

use anyhow::{Context as _, anyhow};
use serde_json::json;

use super::eng_args::{BaseArgs, Owns, RunArgs, flag_error, increasing, input, positive_list, show};
use super::eng_motion::flagged;
use super::error::BatchError;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::engineering::BlockSize;
use crate::analysis::engineering::Drive;
use crate::analysis::engineering::pulse_map::{MAP_BLOCK_R_M, PulseKind, PulseMapSpec, pulse_map};
use crate::analysis::engineering::request::search_ladder;
use crate::analysis::engineering::response::scenario_for;
use crate::analysis::field::RequestField;
use crate::io::config::to_json;
use crate::io::csv::{self, Num};
use crate::io::engineering_files::{PulseMapRow, PulseWindowRow};
use crate::io::output;
use crate::model::excitation::pulse::MAX_TYPE_C_CYCLES;
use crate::plot::labels::{friction_text, num};
use crate::plot::pulse_map::{PulseMapFigure, PulseMapSeries};
use crate::sim::scenario::ShapeKind;

/// Arguments of `rocking pulse-map`.
#[derive(Debug, Clone, clap::Args)]
pub struct PulseMapArgs {
    /// Pulse shapes, comma-separated: one-sine (Makris type A), one-cosine
    /// (type B), type-c (type C_n, n = --cycles).
    #[arg(long, value_name = "LIST", default_value = "one-sine,one-cosine,type-c")]
    pub pulse: String,
    /// Main cycles n of the type-C pulse (default 1; only with type-c in
    /// --pulse).
    #[arg(long, value_name = "N")]
    pub cycles: Option<u32>,
    /// Slenderness ratios B/H, comma-separated or FROM:TO:N.
    #[arg(long, value_name = "LIST", default_value = "0.2", allow_hyphen_values = true)]
    pub b_over_h: String,
    /// Pulse frequencies ω_p/p, comma-separated or FROM:TO:N (increasing).
    #[arg(long, value_name = "LIST", default_value = "1:10:19", allow_hyphen_values = true)]
    pub omega: String,
    /// Step of the amplitudes a_p/(g tan α) tried (the search's
    /// resolution: windows narrower than a step can be missed).
    #[arg(long, value_name = "A", default_value_t = 0.1)]
    pub amp_step: f64,
    /// Largest amplitude a_p/(g tan α) tried.
    #[arg(long, value_name = "A", default_value_t = 20.0)]
    pub amp_max: f64,
    /// Relative width to which each boundary is refined.
    #[arg(long, value_name = "R", default_value_t = 1e-3)]
    pub rel_tol: f64,
    /// Friction and the base scene.
    #[command(flatten)]
    pub base: BaseArgs,
    /// Threads, output folder, quiet.
    #[command(flatten)]
    pub run: RunArgs,
}

/// Largest pulse frequency ω_p/p a map (or a pulse spectrum) runs. Ground
/// pulses have periods of about 0.2–10 s (ω_p up to about 31 rad/s) and
/// blocks of R = 0.05–20 m have p = 0.6–12 1/s, so real cases stay below
/// ω_p/p ≈ 60; 1000 leaves a factor of 15 for asymptotic studies. Beyond
/// it the answer is known (the overturning amplitude grows as (ω_p/p)²:
/// 15.5 at 10 for B/H = 0.2, so about 1.5e5 at 1000, far above any
/// --amp-max) and a point costs time in proportion to ω_p/p (about 70 min
/// at 1e6).
pub(crate) const MAX_OMEGA_RATIO: f64 = 1000.0;

/// What `pulse-map` sets itself, for refusing `--set` keys it would
/// ignore.
const OWNS: Owns = Owns {
    command: "pulse-map",
    sizes: "--b-over-h; the map depends on the block only through B/H",
    motion: "--pulse, --omega, --cycles, --amp-step/--amp-max",
    record: false,
    vertical: "nowhere (a pulse map is of horizontal pulses)",
};

/// The config keys a map's run takes from its flags, for errors.
const FLAGS: &[(&str, &str)] = &[
    ("excitation.a_h", "--amp-max"),
    ("excitation.omega_h", "--omega"),
    ("excitation.cycles", "--cycles"),
    ("block.", "--b-over-h"),
];

fn pulses(args: &PulseMapArgs) -> Result<Vec<PulseKind>, BatchError> {
    let n_cycles = args.cycles.unwrap_or(1);
    if !(1..=MAX_TYPE_C_CYCLES).contains(&n_cycles) {
        return Err(input(anyhow!(
            "--cycles {n_cycles}: must be in 1..={MAX_TYPE_C_CYCLES}"
        )));
    }
    let mut out: Vec<PulseKind> = Vec::new();
    for name in args.pulse.split(',').map(str::trim) {
        let shape = match name {
            "one-sine" => ShapeKind::OneSine,
            "one-cosine" => ShapeKind::OneCosine,
            "type-c" => ShapeKind::TypeC,
            other => {
                return Err(input(anyhow!(
                    "--pulse {other}: unknown pulse (known: one-sine, one-cosine, type-c)"
                )));
            }
        };
        let cycles = if shape == ShapeKind::TypeC { n_cycles } else { 1 };
        let kind = PulseKind { shape, cycles };
        if out.contains(&kind) {
            return Err(input(anyhow!("--pulse {}: {name} is listed twice", args.pulse)));
        }
        out.push(kind);
    }
    if let Some(n) = args.cycles
        && !out.iter().any(|k| k.shape == ShapeKind::TypeC)
    {
        return Err(input(anyhow!(
            "--cycles {n}: only a type-c pulse has cycles, and --pulse {} has none; remove it",
            args.pulse
        )));
    }
    Ok(out)
}

/// Runs `rocking pulse-map`.
pub fn run(args: &PulseMapArgs) -> Result<(), BatchError> {
    let base = args.base.load(&OWNS)?;
    super::eng_args::refuse_stack(
        &base,
        "pulse-map",
        "maps blocks of each --b-over-h at R = 1 m, and a [[stack]] keeps its own shape: use `rocking spectrum --pulse SHAPE` on it",
    )?;
    let pulses = pulses(args)?;
    let ratios = positive_list("--b-over-h", &args.b_over_h)?;
    increasing("--b-over-h", &ratios)?;
    let omegas = positive_list("--omega", &args.omega)?;
    increasing("--omega", &omegas)?;
    if let Some(&w) = omegas.iter().find(|&&w| w > MAX_OMEGA_RATIO) {
        return Err(input(anyhow!(
            "--omega {}: ω_p/p = {} is above {}: ground pulses on real blocks stay below 60, and such a point runs for minutes to hours",
            args.omega,
            show(w),
            show(MAX_OMEGA_RATIO)
        )));
    }
    let ladder =
        search_ladder(RequestField::AmpStep, args.amp_step, RequestField::AmpMax, args.amp_max).map_err(flagged)?;
    if !(args.rel_tol > 0.0 && args.rel_tol < 1.0) {
        return Err(input(anyhow!("--rel-tol {}: must be in (0, 1)", show(args.rel_tol))));
    }
    for &pulse in &pulses {
        for &ratio in &ratios {
            for &omega_ratio in &omegas {
                let drive = Drive::NormalisedPulse {
                    shape: pulse.shape,
                    cycles: pulse.cycles,
                    omega_ratio,
                };
                let block = BlockSize::from_half_diagonal(MAP_BLOCK_R_M, ratio);
                scenario_for(&base, block, &drive, args.amp_max).map_err(|e| {
                    input(anyhow!(
                        "--omega {}, --b-over-h {}: {}",
                        show(omega_ratio),
                        show(ratio),
                        flag_error(&e, FLAGS)
                    ))
                })?;
            }
        }
    }
    let spec = PulseMapSpec {
        base: &base,
        pulses,
        b_over_h: ratios,
        omega_ratios: omegas,
        ladder,
        rel_tol: args.rel_tol,
    };
    let pool = thread_pool(args.run.threads)?;
    output::check_writable(&args.run.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;
    let start = Instant::now();
    let cells = spec.pulses.len() * spec.b_over_h.len() * spec.omega_ratios.len();
    let bar = progress_bar(cells, "points", args.run.quiet);
    let points = pool
        .install(|| pulse_map(&spec, &progress_fn(&bar)))
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();

    let rows: Vec<PulseMapRow> = points
        .iter()
        .map(|p| {
            let first = p.search.first_failure;
            PulseMapRow {
                pulse: p.pulse.name(),
                b_over_h: Num(p.b_over_h),
                alpha_rad: Num(p.b_over_h.atan()),
                omega_ratio: Num(p.omega_ratio),
                min_overturn_amplitude: first.map(|(a, _)| Num(a)),
                // a_p/g = (a_p/(g tan α))·tan α, tan α = B/H.
                min_overturn_ap_g: first.map(|(a, _)| Num(a * p.b_over_h)),
                overturn_end: first.map(|(_, r)| r.end.name().to_string()),
                safe_windows: p.search.safe_windows.len() as u32,
            }
        })
        .collect();
    let windows: Vec<PulseWindowRow> = points
        .iter()
        .flat_map(|p| {
            p.search.safe_windows.iter().map(move |w| PulseWindowRow {
                pulse: p.pulse.name(),
                b_over_h: Num(p.b_over_h),
                omega_ratio: Num(p.omega_ratio),
                from_amplitude: Num(w.from),
                to_amplitude: w.to.map(Num),
            })
        })
        .collect();
    let meta = json!({
        "command": "rocking pulse-map",
        "version": env!("CARGO_PKG_VERSION"),
        "pulses": spec.pulses.iter().map(|p| p.name()).collect::<Vec<_>>(),
        "b_over_h": spec.b_over_h,
        "omega_ratio": spec.omega_ratios,
        "amplitude": {"step": args.amp_step, "max": spec.ladder.last(), "rel_tol": spec.rel_tol},
        "block_r_m": MAP_BLOCK_R_M,
        "pulse_tail_tau": crate::analysis::engineering::response::PULSE_TAIL_TAU,
        "config": to_json(&base),
        "units": "amplitude a_p/(g tan α); omega_ratio ω_p/p; the response depends on the block only through α (block_r_m is arbitrary)",
    });
    let mut series = Vec::new();
    for &pulse in &spec.pulses {
        for &ratio in &spec.b_over_h {
            series.push(PulseMapSeries {
                label: format!("{}, B/H = {}", pulse.name(), num(ratio)),
                points: points
                    .iter()
                    .filter(|p| p.pulse == pulse && p.b_over_h == ratio)
                    .map(|p| {
                        (
                            p.omega_ratio,
                            p.search.first_failure.map(|(a, _)| a),
                            p.search.safe_windows.iter().map(|w| (w.from, w.to)).collect(),
                        )
                    })
                    .collect(),
            });
        }
    }
    let fig = PulseMapFigure {
        title: "Pulse overturning map: smallest overturning amplitude".into(),
        subtitle: format!(
            "{}; a_p/(g tan α) = {} … {} step {}, boundaries to {} relative",
            friction_text(&base),
            num(args.amp_step),
            num(spec.ladder.last().copied().unwrap_or(0.0)),
            num(args.amp_step),
            num(spec.rel_tol)
        ),
        y_max: spec.ladder.last().copied().unwrap_or(1.0),
        series,
    };
    super::write::staged(&args.run.out, |staging| {
        staging.text("pulse_map.csv", &csv::to_string(rows))?;
        staging.text("safe_windows.csv", &csv::to_string(windows))?;
        staging.text("pulse_map.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
        super::write::figure(staging, "pulse_map", &fig)?;
        Ok(())
    })?;
    if !args.run.quiet {
        crate::say!("pulse overturning map: {} points in {wall:.2} s", points.len());
        for p in &points {
            let windows = &p.search.safe_windows;
            crate::say!(
                "  {:<10} B/H = {:<5} ω_p/p = {:<6} min a_p/(g tan α) = {}{}",
                p.pulse.name(),
                num(p.b_over_h),
                num(p.omega_ratio),
                p.search
                    .first_failure
                    .map_or(format!("none up to {}", num(args.amp_max)), |(a, _)| format!("{a:.4}")),
                if windows.is_empty() {
                    String::new()
                } else {
                    format!(" ({} safe window(s) above)", windows.len())
                }
            );
        }
        crate::say!("wrote {}", args.run.out.display());
    }
    Ok(())
}
