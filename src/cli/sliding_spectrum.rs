//! `rocking sliding-spectrum`: the peak and residual sliding displacement
//! against the friction coefficient μ under one record or pulse, for a
//! block that cannot rock (rigid-plastic sliding) and for the given block.
//!
//! Writes into `--out`:
//! - `sliding_spectrum.csv`: one row per block and μ (the slide-only
//!   block's rows first), columns in docs/engineering.md;
//! - `sliding_spectrum.json`: the motion (file, unit, peaks), the block,
//!   the coefficients, how the slide-only block is realised, the base
//!   configuration, the crate version and a summary per block;
//! - `sliding_spectrum.png/svg`: peak and residual sliding against μ.
//!
//! Bad input exits 2 with a one-line error naming the flag or file before
//! anything runs; the folder appears whole or not at all. No `--shard`:
//! a spectrum is two runs per μ (0.09 s for twelve coefficients on El
//! Centro), far from needing a cluster.

use std::time::Instant;

use anyhow::{Context as _, anyhow};
use serde_json::{Value as Json, json};

use super::args::SceneArgs;
use super::eng_args::{BaseArgs, Owns, RunArgs, block, input, positive_list, show};
use super::eng_motion::PulseArg;
use super::eng_motion::{Motion, MotionArgs, PulseScaleArgs, RecordArgs};
use super::error::BatchError;
use super::flags::Flags;
use super::pulse_map::MAX_OMEGA_RATIO;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::engineering::response::end_time_as;
use crate::analysis::engineering::sliding_spectrum::{
    BlockKind, NO_SLIDING_M, SLIDE_ONLY_B_OVER_H, SlidingPoint, SlidingSpec, sliding_spectrum,
};
use crate::analysis::engineering::{BlockSize, Drive, EndState};
use crate::io::config::to_json;
use crate::io::csv::{self, Num};
use crate::io::output;
use crate::io::sliding_files::SlidingRow;
use crate::plot::labels::num;
use crate::plot::sliding_spectrum::{SlidingCurve, SlidingFigure};

/// Arguments of `rocking sliding-spectrum`.
#[derive(Debug, Clone, clap::Args)]
pub struct SlidingSpectrumArgs {
    /// The record and how it is read.
    #[command(flatten)]
    pub source: RecordArgs,
    /// An analytic pulse instead of a record; give --pulse-accel and
    /// --pulse-period.
    #[arg(long, value_enum, value_name = "SHAPE")]
    pub pulse: Option<PulseArg>,
    /// The pulse's numbers and the motion's scale.
    #[command(flatten)]
    pub motion: PulseScaleArgs,
    /// Friction coefficients μ (μ_s), each > 0, increasing:
    /// comma-separated, or FROM:TO:N for N evenly spaced values.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub mu: String,
    /// μ_k/μ_s of every run, in (0, 1] (1: one coefficient, μ_k = μ_s = μ,
    /// as sliding-block analyses assume).
    #[arg(long, value_name = "R", default_value_t = 1.0, allow_negative_numbers = true)]
    pub kinetic_ratio: f64,
    /// The block that may rock, WIDTHxHEIGHT in metres, e.g. 0.4x1.8
    /// (default: the block of --preset/--config, else 1x4).
    #[arg(long = "block", value_name = "BxH")]
    pub block: Option<String>,
    /// A preset or config for everything else (impact law, tolerances,
    /// overturning angle run.tumble_theta, record tail run.tail_s), and
    /// --set overrides. Its excitation and friction are replaced by the
    /// command's.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Threads, output folder, quiet.
    #[command(flatten)]
    pub run: RunArgs,
}

/// What the command sets itself, for refusing `--set` keys it would ignore.
fn owns(args: &SlidingSpectrumArgs) -> Owns {
    Owns::with_motion(
        "sliding-spectrum",
        "--block",
        args.pulse.is_none(),
        "nowhere: a sliding spectrum is of horizontal motion (use --batch with excitation.file_v for one run)",
    )
}

/// Refuses flags that the other flags make meaningless.
fn refuse_ignored_flags(args: &SlidingSpectrumArgs) -> Result<(), BatchError> {
    MotionArgs::new(&args.source, args.pulse, &args.motion, None).refuse_mixed()?;
    for set in &args.scene.sets {
        let key = set.split_once('=').map_or(set.as_str(), |(k, _)| k).trim();
        if key.split_once('.').is_some_and(|(section, _)| section == "friction") {
            return Err(input(anyhow!(
                "--set {key}: sliding-spectrum sets the friction itself (--mu, --kinetic-ratio); remove it"
            )));
        }
    }
    Ok(())
}

/// The motion of the flags, read and checked (horizontal only).
fn motion(args: &SlidingSpectrumArgs) -> Result<Motion, BatchError> {
    super::eng_motion::motion(&MotionArgs::new(&args.source, args.pulse, &args.motion, None), false)
}

/// Runs `rocking sliding-spectrum`.
pub fn run(args: &SlidingSpectrumArgs) -> Result<(), BatchError> {
    refuse_ignored_flags(args)?;
    let base = BaseArgs {
        friction: None,
        scene: args.scene.clone(),
    }
    .load(&owns(args))?;
    super::eng_args::refuse_stack(
        &base,
        "sliding-spectrum",
        "varies a single block's friction (--mu); a [[stack]] gives its base face's friction in its bottom table (docs/model.md §18.7): use a [block] scene",
    )?;
    let motion = motion(args)?;
    let mu = positive_list("--mu", &args.mu)?;
    let size = match &args.block {
        Some(text) => {
            let (w, h) = block("--block", text)?;
            BlockSize {
                width_m: w,
                height_m: h,
            }
        }
        None => BlockSize {
            width_m: base.block.width,
            height_m: base.block.height,
        },
    };
    let spec = SlidingSpec {
        base: &base,
        drive: &motion.drive,
        scale: motion.scale,
        block: size,
        mu,
        kinetic_ratio: args.kinetic_ratio,
    };
    spec.check().map_err(|e| input(anyhow!(e.render(&Flags))))?;
    // A pulse far shorter than the block's time scale is refused as in
    // `pulse-map` (see MAX_OMEGA_RATIO); both blocks share R, hence p.
    if let Drive::PhysicalPulse { omega_p, .. } = motion.drive
        && omega_p / size.p_per_s() > MAX_OMEGA_RATIO
    {
        return Err(input(anyhow!(
            "--pulse-period {}: ω_p/p = {} for the block R = {} m, above {} (see pulse-map --omega); give a longer period or a larger block",
            show(args.motion.pulse_period.unwrap_or(f64::NAN)),
            show(omega_p / size.p_per_s()),
            show(size.half_diagonal_m()),
            show(MAX_OMEGA_RATIO)
        )));
    }
    let pool = thread_pool(args.run.threads)?;
    output::check_writable(&args.run.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;

    let start = Instant::now();
    let bar = progress_bar(2 * spec.mu.len(), "runs", args.run.quiet);
    let points = pool
        .install(|| sliding_spectrum(&spec, &progress_fn(&bar)))
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();

    let pga = motion.scale * motion.pga_g;
    let block_text = format!("{} × {} m", num(size.width_m), num(size.height_m));
    let friction = if spec.kinetic_ratio == 1.0 {
        "μ_k = μ_s = μ".to_string()
    } else {
        format!("μ_k = {}·μ_s", num(spec.kinetic_ratio))
    };
    let rows: Vec<SlidingRow> = BlockKind::ALL
        .iter()
        .flat_map(|&kind| points.iter().map(move |p| row(kind, p, size)))
        .collect();
    let summary: Vec<Json> = BlockKind::ALL
        .iter()
        .map(|&kind| summary(kind, &points, &block_text))
        .collect();
    let meta = json!({
        "command": "rocking sliding-spectrum",
        "version": env!("CARGO_PKG_VERSION"),
        "motion": motion.json,
        "scale": motion.scale,
        "pga_g": pga,
        "block": { "width_m": size.width_m, "height_m": size.height_m, "r_m": size.half_diagonal_m(), "alpha_rad": size.alpha() },
        "slide_only": {
            "realisation": "the block model with the given block's R and B/H = 1000 (tan α = 1000): uplift needs |a_h| > g tan α and a sliding block tips only if μ_k > tan α, both refused, so only rest and slide remain, whose equations are the rigid-plastic block's exactly",
            "b_over_h": SLIDE_ONLY_B_OVER_H,
        },
        "mu": spec.mu,
        "kinetic_ratio": spec.kinetic_ratio,
        "record_tail_s": base.run.record_tail_s.unwrap_or(crate::sim::scenario::RECORD_TAIL_S),
        "pulse_tail_tau": crate::analysis::engineering::response::PULSE_TAIL_TAU,
        "summary": summary,
        "config": to_json(&base),
        "units": "displacements m (residual signed, +x to the right), times s, accelerations g; peak_theta_over_alpha = max|θ|/α",
    });
    let curve = |kind: BlockKind, label: String| SlidingCurve {
        label,
        points: points
            .iter()
            .map(|p| {
                let r = p.of(kind);
                (p.mu_s, r.peak_sliding_m, r.residual_sliding_m, r.end)
            })
            .collect(),
    };
    let fig = SlidingFigure {
        title: format!("Sliding spectrum under {}", motion.name),
        subtitle: format!(
            "PGA {pga:.3} g (scale {}); {friction}; block {block_text} (tan α = {:.3}), impact {}",
            num(motion.scale),
            size.width_m / size.height_m,
            base.impact.law.name()
        ),
        pga_g: Some(pga),
        tan_alpha: Some(size.width_m / size.height_m),
        curves: vec![
            curve(
                BlockKind::SlideOnly,
                "block that cannot rock (rigid-plastic sliding)".into(),
            ),
            curve(
                BlockKind::Given,
                format!("block {block_text} (may also rock and overturn)"),
            ),
        ],
    };

    super::write::staged(&args.run.out, |staging| {
        staging.text("sliding_spectrum.csv", &csv::to_string(rows))?;
        staging.text("sliding_spectrum.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
        super::write::figure(staging, "sliding_spectrum", &fig)?;
        Ok(())
    })?;
    if !args.run.quiet {
        crate::say!(
            "rocking sliding-spectrum under {} (PGA {pga:.3} g), {} coefficients, {friction}: {} runs in {wall:.2} s",
            motion.name,
            spec.mu.len(),
            2 * spec.mu.len()
        );
        for s in &summary {
            crate::say!("  {}", s["text"].as_str().unwrap_or_default());
        }
        crate::say!("wrote {}", args.run.out.display());
    }
    Ok(())
}

/// The CSV row of block `kind` at one μ.
fn row(kind: BlockKind, p: &SlidingPoint, size: BlockSize) -> SlidingRow {
    let r = p.of(kind);
    let given = kind == BlockKind::Given;
    SlidingRow {
        block: kind.name().to_string(),
        width_m: given.then_some(Num(size.width_m)),
        height_m: given.then_some(Num(size.height_m)),
        mu: Num(p.mu_s),
        mu_k: Num(p.mu_k),
        end: r.end.name().to_string(),
        peak_sliding_m: Num(r.peak_sliding_m),
        residual_sliding_m: r.residual_sliding_m.map(Num),
        peak_theta_over_alpha: Num(r.peak_theta_over_alpha),
        t_overturn_s: end_time_as(r.end, r.t_end_event_s, EndState::Overturned).map(Num),
        t_flight_s: end_time_as(r.end, r.t_end_event_s, EndState::Flight).map(Num),
    }
}

/// Per block: the largest peak and its μ, the smallest μ with no sliding,
/// and how many runs overturned or flew.
fn summary(kind: BlockKind, points: &[SlidingPoint], block_text: &str) -> Json {
    let of = |p: &SlidingPoint| *p.of(kind);
    let largest =
        points
            .iter()
            .map(|p| (p.mu_s, of(p).peak_sliding_m))
            .fold(None, |m: Option<(f64, f64)>, x| match m {
                Some(m) if m.1 >= x.1 => Some(m),
                _ => Some(x),
            });
    // The smallest μ from which no run slides (every larger μ too).
    let still = |p: &&SlidingPoint| of(p).peak_sliding_m <= NO_SLIDING_M && of(p).end.survived();
    let no_sliding_from = points.iter().rev().take_while(still).last().map(|p| p.mu_s);
    let count = |e: EndState| points.iter().filter(|p| of(p).end == e).count();
    let (over, flight) = (count(EndState::Overturned), count(EndState::Flight));
    let name = match kind {
        BlockKind::SlideOnly => "block that cannot rock".to_string(),
        BlockKind::Given => format!("block {block_text}"),
    };
    let text = format!(
        "{name}: largest peak sliding {}{}{}{}",
        largest.map_or("none".into(), |(mu, d)| format!("{d:.4} m at μ = {}", num(mu))),
        no_sliding_from.map_or(String::new(), |mu| format!("; no sliding from μ = {}", num(mu))),
        if over > 0 {
            format!("; overturned at {over} of {} μ", points.len())
        } else {
            String::new()
        },
        if flight > 0 {
            format!("; flight at {flight} of {} μ", points.len())
        } else {
            String::new()
        },
    );
    json!({
        "block": kind.name(),
        "largest_peak_sliding_m": largest.map(|l| l.1),
        "largest_peak_at_mu": largest.map(|l| l.0),
        "no_sliding_from_mu": no_sliding_from,
        "overturned": over,
        "flight": flight,
        "text": text,
    })
}
