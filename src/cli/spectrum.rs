//! `rocking spectrum`: the rocking spectrum of one record or pulse over a
//! range of block sizes, and optionally each block's overturning scale.
//!
//! Writes into `--out`:
//! - `spectrum.csv`: one row per block (slenderness outer, size
//!   increasing), columns in docs/engineering.md;
//! - `safe_windows.csv` (with `--overturn-scale`): the safe windows above
//!   each block's first overturning scale;
//! - `spectrum.json`: the motion (file, unit, peaks), the sizes, the search,
//!   the base configuration, the crate version and a summary per B/H;
//! - `spectrum.png/svg` (peak θ/α against p) and, with
//!   `--overturn-scale`, `overturn_scale.png/svg`.
//!
//! Bad input exits 2 with a one-line error naming the flag or file before
//! anything runs; the folder appears whole or not at all.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, anyhow};
use serde_json::{Value as Json, json};

use super::eng_args::{BaseArgs, Owns, RunArgs, VerticalArg, flag_error, input, positive_list, show};
use super::eng_motion::{Motion, MotionArgs, PulseArg, PulseScaleArgs, RecordArgs, flagged};
use super::error::BatchError;
use super::pulse_map::MAX_OMEGA_RATIO;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::engineering::overturn_scale::Failing as _;
use crate::analysis::engineering::request::{self, OverturnRequest, SpectrumRequest};
use crate::analysis::engineering::response::end_time_as;
use crate::analysis::engineering::rocking_spectrum::{SizeAxis, SpectrumPoint, SpectrumSpec, rocking_spectrum};
use crate::analysis::engineering::{Drive, EndState};
use crate::io::config::to_json;
use crate::io::csv::{self, Num};
use crate::io::engineering_files::{SpectrumRow, SpectrumWindowRow};
use crate::io::output;
use crate::plot::labels::{friction_text, num};
use crate::plot::rocking_spectrum::{OverturnScaleFigure, OverturnSeries, SpectrumFigure, SpectrumSeries};
use crate::sim::Scenario;
use crate::sim::stack_answer::body_name;

/// The size axis on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum AxisArg {
    /// The half-diagonal R = ½√(B²+H²), m.
    R,
    /// The height H, m.
    H,
}

/// Arguments of `rocking spectrum`.
#[derive(Debug, Clone, clap::Args)]
pub struct SpectrumArgs {
    /// The record and how it is read.
    #[command(flatten)]
    pub source: RecordArgs,
    /// The vertical component of --record (positive upward), scaled by the
    /// same factor as the horizontal (a --pga sets the horizontal's PGA).
    #[arg(long = "record-v", value_name = "FILE", requires = "record")]
    pub record_v: Option<PathBuf>,
    /// Unit of a text --record-v (default: --unit).
    #[arg(long = "unit-v", value_name = "UNIT", requires = "record_v")]
    pub unit_v: Option<String>,
    /// Whether to apply the vertical component: `record` (the default when
    /// --record-v is given) or `none` (horizontal only, --record-v unread).
    #[arg(long, value_enum, value_name = "none|record")]
    pub vertical: Option<VerticalArg>,
    /// An analytic pulse instead of a record (its ω_p/p then differs from
    /// block to block); give --pulse-accel and --pulse-period.
    #[arg(long, value_enum, value_name = "SHAPE")]
    pub pulse: Option<PulseArg>,
    /// The pulse's numbers and the motion's scale.
    #[command(flatten)]
    pub motion: PulseScaleArgs,
    /// What the sizes step through: the half-diagonal R or the height H.
    #[arg(long, value_enum, default_value = "r")]
    pub size: AxisArg,
    /// Smallest size, m.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub from: f64,
    /// Largest size, m (>= --from).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub to: f64,
    /// Number of log-spaced sizes.
    #[arg(long, value_name = "N", default_value_t = 50)]
    pub count: usize,
    /// Slenderness ratios B/H, comma-separated or FROM:TO:N (default
    /// 0.25; a [[stack]] keeps its own: its bottom width over its height).
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub b_over_h: Option<String>,
    /// Also search each block's smallest overturning scale of the motion
    /// (step up by --search-step to --search-max, refine each change by
    /// bisection) and the safe windows above it.
    #[arg(long)]
    pub overturn_scale: bool,
    /// Step of the scale factors the search tries (default 0.1; only with
    /// --overturn-scale).
    #[arg(long, value_name = "F")]
    pub search_step: Option<f64>,
    /// Largest scale factor the search tries (default 5; only with
    /// --overturn-scale).
    #[arg(long, value_name = "F")]
    pub search_max: Option<f64>,
    /// Relative width to which each overturning boundary is refined
    /// (default 1e-3; only with --overturn-scale).
    #[arg(long, value_name = "R")]
    pub rel_tol: Option<f64>,
    /// Friction and the base scene.
    #[command(flatten)]
    pub base: BaseArgs,
    /// Threads, output folder, quiet.
    #[command(flatten)]
    pub run: RunArgs,
}

/// Default step of the overturning-scale search: a tenth of the motion as
/// read resolves the scales engineers quote to one decimal.
const SEARCH_STEP: f64 = 0.1;
/// Default largest scale searched: five times the motion as read.
const SEARCH_MAX: f64 = 5.0;
/// Default relative width of a refined boundary.
const REL_TOL: f64 = 1e-3;

/// The config keys a spectrum's run takes from its flags, for errors.
const FLAGS: &[(&str, &str)] = &[
    ("excitation.a_h", "--pulse-accel × --scale/--pga"),
    ("excitation.omega_h", "--pulse-period"),
    ("excitation.cycles", "--cycles"),
    ("excitation.scale_h", "--scale/--pga"),
    ("block.", "--from/--to/--count, --b-over-h"),
];

/// What `spectrum` sets itself, for refusing `--set` keys it would ignore.
fn owns(args: &SpectrumArgs) -> Owns {
    Owns::with_motion(
        "spectrum",
        "--from/--to/--count, --size, --b-over-h",
        args.pulse.is_none(),
        "--record-v",
    )
}

/// Refuses flags that the other flags make meaningless (each would be
/// ignored without a word).
fn refuse_ignored_flags(args: &SpectrumArgs) -> Result<(), BatchError> {
    if args.vertical == Some(VerticalArg::Record) && args.record_v.is_none() {
        return Err(input(anyhow!(
            "--vertical record: give the vertical component with --record-v FILE (or --vertical none)"
        )));
    }
    MotionArgs::new(&args.source, args.pulse, &args.motion, None).refuse_mixed()?;
    if !args.overturn_scale {
        for (flag, given) in [
            ("--search-step", args.search_step.is_some()),
            ("--search-max", args.search_max.is_some()),
            ("--rel-tol", args.rel_tol.is_some()),
        ] {
            if given {
                return Err(input(anyhow!(
                    "{flag}: only with --overturn-scale; add it or remove {flag}"
                )));
            }
        }
    }
    Ok(())
}

/// The motion of the flags, read and checked.
fn motion(args: &SpectrumArgs) -> Result<Motion, BatchError> {
    let use_vertical = args.vertical.unwrap_or(VerticalArg::Record) == VerticalArg::Record;
    let vertical = args
        .record_v
        .as_ref()
        .filter(|_| use_vertical)
        .map(|path| (path, args.unit_v.as_deref()));
    let flags = MotionArgs::new(&args.source, args.pulse, &args.motion, vertical);
    super::eng_motion::motion(&flags, true)
}

/// Runs `rocking spectrum`.
pub fn run(args: &SpectrumArgs) -> Result<(), BatchError> {
    refuse_ignored_flags(args)?;
    let base = args.base.load(&owns(args))?;
    let motion = motion(args)?;
    let mut request = SpectrumRequest {
        axis: match args.size {
            AxisArg::R => SizeAxis::HalfDiagonal,
            AxisArg::H => SizeAxis::Height,
        },
        from_m: args.from,
        to_m: args.to,
        count: args.count,
        b_over_h: Vec::new(),
        overturn: args.overturn_scale.then(|| OverturnRequest {
            search_step: args.search_step.unwrap_or(SEARCH_STEP),
            search_max: args.search_max.unwrap_or(SEARCH_MAX),
            rel_tol: args.rel_tol.unwrap_or(REL_TOL),
        }),
    };
    // The sizes before the ratios' list, as the flags are documented.
    request.size_range().map_err(flagged)?;
    let given = args
        .b_over_h
        .as_deref()
        .map(|text| positive_list("--b-over-h", text))
        .transpose()?;
    request.b_over_h = request::spectrum_ratios(&base, given).map_err(flagged)?;
    let blocks = request.checked().map_err(flagged)?;
    let spec = SpectrumSpec {
        base: &base,
        drive: &motion.drive,
        scale: motion.scale,
        sizes: blocks.sizes,
        b_over_h: blocks.b_over_h,
        overturn: blocks.overturn,
    };
    // A pulse far shorter than the block's time scale is refused as in
    // `pulse-map` (see MAX_OMEGA_RATIO).
    if let Drive::PhysicalPulse { omega_p, .. } = motion.drive
        && let Some((_, _, b)) = spec
            .blocks()
            .into_iter()
            .find(|(_, _, b)| omega_p / b.p_per_s() > MAX_OMEGA_RATIO)
    {
        return Err(input(anyhow!(
            "--pulse-period {}: ω_p/p = {} for the block R = {} m, above {} (see pulse-map --omega); give a longer period or larger blocks",
            show(args.motion.pulse_period.unwrap_or(f64::NAN)),
            show(omega_p / b.p_per_s()),
            show(b.half_diagonal_m()),
            show(MAX_OMEGA_RATIO)
        )));
    }
    // Every block's scenario is checked before anything runs.
    for (_, _, block) in spec.blocks() {
        crate::analysis::engineering::response::scenario_for(&base, block, &motion.drive, motion.scale).map_err(
            |e| {
                input(anyhow!(
                    "block {} × {} m: {}",
                    show(block.width_m),
                    show(block.height_m),
                    flag_error(&e, FLAGS)
                ))
            },
        )?;
    }
    let pool = thread_pool(args.run.threads)?;
    output::check_writable(&args.run.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;

    let start = Instant::now();
    let bar = progress_bar(spec.sizes.count * spec.b_over_h.len(), "blocks", args.run.quiet);
    let points = pool
        .install(|| rocking_spectrum(&spec, &progress_fn(&bar)))
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();

    let pga_of = |scale: f64| scale * motion.pga_g;
    let rows: Vec<SpectrumRow> = points.iter().map(|p| row(p, motion.scale, &pga_of)).collect();
    let windows: Vec<SpectrumWindowRow> = points
        .iter()
        .flat_map(|p| {
            p.overturn.iter().flat_map(move |s| {
                s.safe_windows.iter().map(move |w| SpectrumWindowRow {
                    b_over_h: Num(p.b_over_h),
                    r_m: Num(p.block.half_diagonal_m()),
                    from_scale: Num(w.from),
                    to_scale: w.to.map(Num),
                    from_pga_g: Num(pga_of(w.from)),
                    to_pga_g: w.to.map(|t| Num(pga_of(t))),
                })
            })
        })
        .collect();
    let summary = summary(&spec, &points, &base);
    let meta = json!({
        "command": "rocking spectrum",
        "version": env!("CARGO_PKG_VERSION"),
        "motion": motion.json,
        "scale": motion.scale,
        "pga_g": pga_of(motion.scale),
        "vertical": if motion.pga_v_g.is_some() { "record" } else { "none" },
        "pga_v_g": motion.pga_v_g.map(|v| v * motion.scale),
        "scaling": if motion.pga_v_g.is_some() {
            "the horizontal and vertical components are multiplied by the same scale; --pga sets the horizontal's PGA"
        } else {
            "the horizontal motion is multiplied by scale"
        },
        "sizes": spec.sizes,
        "b_over_h": spec.b_over_h,
        "record_tail_s": base.run.record_tail_s.unwrap_or(crate::sim::scenario::RECORD_TAIL_S),
        "pulse_tail_tau": crate::analysis::engineering::response::PULSE_TAIL_TAU,
        "overturn_scale": spec.overturn.as_ref().map(|o| json!({
            "step": args.search_step.unwrap_or(SEARCH_STEP),
            "max": o.ladder.last(),
            "rel_tol": o.rel_tol,
        })),
        "summary": summary,
        "config": to_json(&base),
        "units": "lengths m, times s, accelerations g, p 1/s; peak_theta_over_alpha = max|θ|/α; scale: factor on the motion as read",
    });
    let mut meta = meta;
    if let Some(blocks) = &base.stack {
        meta["stack"] = json!({
            "blocks": blocks.len(),
            "sizes": "each size is the stack's bounding block (its bottom block's width and its total height); every block's width, height and offset are scaled by one factor, so its shape stays the config's",
            "peak_theta_over_alpha": "of the block that turned most, over its own slenderness (summary.json's max_rotation_over_alpha)",
        });
    }
    let vertical_text = motion
        .pga_v_g
        .map_or_else(String::new, |v| format!(" + vertical PGA {:.3} g", v * motion.scale));
    let subtitle = format!(
        "{}, PGA {:.3} g{vertical_text} (scale {}); {}; overturning at θ/α = {}",
        motion.name,
        pga_of(motion.scale),
        num(motion.scale),
        friction_text(&base),
        num(base.run.tumble_theta)
    );
    let series: Vec<SpectrumSeries> = spec
        .b_over_h
        .iter()
        .map(|&ratio| SpectrumSeries {
            label: series_name(&base, ratio),
            points: points
                .iter()
                .filter(|p| p.b_over_h == ratio)
                .map(|p| (p.block.p_per_s(), p.response.peak_theta_over_alpha, p.response.end))
                .collect(),
        })
        .collect();
    let fig = SpectrumFigure {
        title: format!("Rocking spectrum: peak rotation under {}", motion.name),
        subtitle: subtitle.clone(),
        series,
    };
    let overturn_fig = spec.overturn.as_ref().map(|o| OverturnScaleFigure {
        title: format!("Smallest overturning PGA under {} (scaled)", motion.name),
        subtitle: format!(
            "{}; scales {} … {} step {}, boundaries to {} relative",
            friction_text(&base),
            num(args.search_step.unwrap_or(SEARCH_STEP)),
            num(o.ladder.last().copied().unwrap_or(0.0)),
            num(args.search_step.unwrap_or(SEARCH_STEP)),
            num(o.rel_tol)
        ),
        y_label: "smallest overturning PGA (g)".into(),
        y_max: pga_of(o.ladder.last().copied().unwrap_or(1.0)),
        series: spec
            .b_over_h
            .iter()
            .map(|&ratio| OverturnSeries {
                label: series_name(&base, ratio),
                points: points
                    .iter()
                    .filter(|p| p.b_over_h == ratio)
                    .map(|p| {
                        let s = p.overturn.as_ref();
                        (
                            p.block.p_per_s(),
                            s.and_then(|s| s.first_failure).map(|(a, _)| pga_of(a)),
                            s.map(|s| {
                                s.safe_windows
                                    .iter()
                                    .map(|w| (pga_of(w.from), w.to.map(pga_of)))
                                    .collect()
                            })
                            .unwrap_or_default(),
                        )
                    })
                    .collect(),
            })
            .collect(),
    });

    super::write::staged(&args.run.out, |staging| {
        staging.text("spectrum.csv", &csv::to_string(rows))?;
        if spec.overturn.is_some() {
            staging.text("safe_windows.csv", &csv::to_string(windows))?;
        }
        staging.text("spectrum.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
        super::write::figure(staging, "spectrum", &fig)?;
        if let Some(f) = &overturn_fig {
            super::write::figure(staging, "overturn_scale", f)?;
        }
        Ok(())
    })?;
    if !args.run.quiet {
        crate::say!(
            "rocking spectrum under {} (PGA {:.3} g{}): {} blocks in {wall:.2} s",
            motion.name,
            pga_of(motion.scale),
            motion.pga_v_g.map_or_else(String::new, |v| format!(
                ", vertical PGA {:.3} g, both scaled by {}",
                v * motion.scale,
                num(motion.scale)
            )),
            points.len()
        );
        if let Some(note) = super::eng_args::floor_note(&base) {
            crate::say!("  {note}");
        }
        for s in summary.as_array().into_iter().flatten() {
            crate::say!("  {}", s["text"].as_str().unwrap_or_default());
        }
        crate::say!("wrote {}", args.run.out.display());
    }
    Ok(())
}

/// A series' name in the figures and the summary: its B/H, or for a
/// stack its number of blocks too.
fn series_name(base: &Scenario, ratio: f64) -> String {
    match &base.stack {
        // Its B/H follows from its blocks (0.5555…): three digits read.
        Some(blocks) => format!("{}-block stack, B/H = {ratio:.3}", blocks.len()),
        None => format!("B/H = {}", num(ratio)),
    }
}

/// For a stack, which block went over how often (` (top block 12,
/// bottom block 3)`: the block whose lower face overturned, with all it
/// carries); empty for a block.
fn bodies_text(base: &Scenario, of: &[&SpectrumPoint]) -> String {
    let Some(blocks) = &base.stack else {
        return String::new();
    };
    let k = blocks.len();
    let counts: Vec<String> = (0..k)
        .rev()
        .filter_map(|j| {
            let n = of
                .iter()
                .filter(|p| p.response.end == EndState::Overturned && p.response.body == Some(j))
                .count();
            (n > 0).then(|| format!("{} {n}", body_name(j, k)))
        })
        .collect();
    if counts.is_empty() {
        String::new()
    } else {
        format!(" ({})", counts.join(", "))
    }
}

/// The CSV row of one block.
fn row(p: &SpectrumPoint, scale: f64, pga_of: &impl Fn(f64) -> f64) -> SpectrumRow {
    let r = &p.response;
    let first = p.overturn.as_ref().and_then(|s| s.first_failure);
    SpectrumRow {
        b_over_h: Num(p.b_over_h),
        alpha_rad: Num(p.block.alpha()),
        width_m: Num(p.block.width_m),
        height_m: Num(p.block.height_m),
        r_m: Num(p.block.half_diagonal_m()),
        p_per_s: Num(p.block.p_per_s()),
        scale: Num(scale),
        pga_g: Num(pga_of(scale)),
        end: r.end.name().to_string(),
        peak_theta_over_alpha: Num(r.peak_theta_over_alpha),
        t_overturn_s: end_time_as(r.end, r.t_end_event_s, EndState::Overturned).map(Num),
        t_flight_s: end_time_as(r.end, r.t_end_event_s, EndState::Flight).map(Num),
        overturn_scale: first.map(|(a, _)| Num(a)),
        overturn_pga_g: first.map(|(a, _)| Num(pga_of(a))),
        overturn_end: first.map(|(_, r)| r.end.name().to_string()),
        safe_windows: p.overturn.as_ref().map(|s| s.safe_windows.len() as u32),
    }
}

/// Per B/H: how many blocks overturned or flew, the largest that
/// overturned and the smallest that survived.
fn summary(spec: &SpectrumSpec<'_>, points: &[SpectrumPoint], base: &Scenario) -> Json {
    let per: Vec<Json> = spec
        .b_over_h
        .iter()
        .map(|&ratio| {
            let of: Vec<&SpectrumPoint> = points.iter().filter(|p| p.b_over_h == ratio).collect();
            let count = |e: EndState| of.iter().filter(|p| p.response.end == e).count();
            let largest_overturned = of
                .iter()
                .filter(|p| p.response.fails())
                .map(|p| p.block.half_diagonal_m())
                .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
            let smallest_survivor = of
                .iter()
                .filter(|p| p.response.end.survived())
                .map(|p| p.block.half_diagonal_m())
                .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.min(r))));
            let (over, flight) = (count(EndState::Overturned), count(EndState::Flight));
            let peak_survivor = of
                .iter()
                .filter(|p| p.response.end.survived())
                .map(|p| p.response.peak_theta_over_alpha)
                .fold(0.0, f64::max);
            let text = format!(
                "{}: {over} of {} overturned{}{}{}{}",
                series_name(base, ratio),
                of.len(),
                bodies_text(base, &of),
                if flight > 0 {
                    format!(", {flight} in flight")
                } else {
                    String::new()
                },
                largest_overturned.map_or(String::new(), |r| format!("; largest overturned R = {r:.3} m")),
                smallest_survivor.map_or(String::new(), |r| format!(
                    "; smallest survivor R = {r:.3} m; survivors' largest peak θ/α = {peak_survivor:.3}"
                )),
            );
            json!({
                "b_over_h": ratio,
                "blocks": of.len(),
                "overturned": over,
                "flight": flight,
                "largest_overturned_r_m": largest_overturned,
                "smallest_survivor_r_m": smallest_survivor,
                "text": text,
            })
        })
        .collect();
    Json::Array(per)
}
