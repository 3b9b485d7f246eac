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

use super::eng_args::{
    BaseArgs, Owns, RecordUnitArgs, VerticalArg, flag_error, increasing, input, positive_list, read_record,
    search_ladder, show,
};
use super::error::BatchError;
use super::pulse_map::MAX_OMEGA_RATIO;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::engineering::overturn_scale::Failing as _;
use crate::analysis::engineering::rocking_spectrum::{
    OverturnOptions, SizeAxis, SizeRange, SizeRangeError, SpectrumPoint, SpectrumSpec, rocking_spectrum,
};
use crate::analysis::engineering::{Drive, EndState};
use crate::io::config::to_json;
use crate::io::csv::{self, Num};
use crate::io::engineering_files::{SpectrumRow, SpectrumWindowRow};
use crate::io::output;
use crate::model::excitation::pulse::MAX_TYPE_C_CYCLES;
use crate::plot::labels::{friction_text, num};
use crate::plot::rocking_spectrum::{OverturnScaleFigure, OverturnSeries, SpectrumFigure, SpectrumSeries};
use crate::sim::scenario::ShapeKind;

/// Pulse shapes on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PulseArg {
    /// Makris type A: a_p sin(ω_p t) over one period.
    OneSine,
    /// Makris type B: a_p cos(ω_p t) over one period.
    OneCosine,
    /// Makris type C_n (n = --cycles): zero final ground velocity and
    /// displacement.
    TypeC,
}

impl From<PulseArg> for ShapeKind {
    fn from(p: PulseArg) -> Self {
        match p {
            PulseArg::OneSine => ShapeKind::OneSine,
            PulseArg::OneCosine => ShapeKind::OneCosine,
            PulseArg::TypeC => ShapeKind::TypeC,
        }
    }
}

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
    /// The ground-acceleration record (PEER .AT2, two-column `time accel`
    /// text, or one-column text with --dt).
    #[arg(
        long,
        value_name = "FILE",
        conflicts_with = "pulse",
        required_unless_present = "pulse"
    )]
    pub record: Option<PathBuf>,
    /// Unit and time step of a text record.
    #[command(flatten)]
    pub reading: RecordUnitArgs,
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
    /// Main cycles n of a type-C pulse (default 1; only with --pulse
    /// type-c).
    #[arg(long, value_name = "N")]
    pub cycles: Option<u32>,
    /// Peak acceleration a_p of the pulse, g.
    #[arg(long, value_name = "G", requires = "pulse")]
    pub pulse_accel: Option<f64>,
    /// Period T_p = 2π/ω_p of the pulse, s.
    #[arg(long, value_name = "S", requires = "pulse")]
    pub pulse_period: Option<f64>,
    /// Factor on the motion (1 plays it as recorded).
    #[arg(long, value_name = "F", conflicts_with = "pga")]
    pub scale: Option<f64>,
    /// Scale the motion to this peak ground acceleration, g.
    #[arg(long, value_name = "G")]
    pub pga: Option<f64>,
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
    /// Slenderness ratios B/H, comma-separated or FROM:TO:N.
    #[arg(
        long = "b-over-h",
        value_name = "LIST",
        default_value = "0.25",
        allow_hyphen_values = true
    )]
    pub b_over_h: String,
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
    /// Worker threads (default: one per core; at most 4 per core). The
    /// output does not depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The motion as checked: what to run and what to write about it.
struct Motion {
    drive: Drive,
    /// Scale of the peak-rotation runs.
    scale: f64,
    /// PGA at scale 1, g.
    pga_g: f64,
    /// The vertical component's PGA at scale 1, g, when it is applied.
    pga_v_g: Option<f64>,
    /// Name for titles.
    name: String,
    /// Its description for spectrum.json.
    json: Json,
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
    let record = args.pulse.is_none();
    Owns {
        command: "spectrum",
        sizes: "--from/--to/--count, --size, --b-over-h",
        motion: if record {
            "--record, --unit, --dt, --scale/--pga"
        } else {
            "--pulse, --pulse-accel, --pulse-period, --cycles, --scale/--pga"
        },
        record,
        vertical: "--record-v",
    }
}

/// Refuses flags that the other flags make meaningless (each would be
/// ignored without a word).
fn refuse_ignored_flags(args: &SpectrumArgs) -> Result<(), BatchError> {
    let record_flags = [
        ("--unit", args.reading.unit.is_some()),
        ("--dt", args.reading.dt.is_some()),
    ];
    let pulse_flags = [
        ("--pulse-accel", args.pulse_accel.is_some()),
        ("--pulse-period", args.pulse_period.is_some()),
        ("--cycles", args.cycles.is_some()),
    ];
    if args.vertical == Some(VerticalArg::Record) && args.record_v.is_none() {
        return Err(input(anyhow!(
            "--vertical record: give the vertical component with --record-v FILE (or --vertical none)"
        )));
    }
    if args.record.is_some() {
        if let Some((flag, _)) = pulse_flags.iter().find(|(_, given)| *given) {
            return Err(input(anyhow!("{flag}: describes a --pulse, not a --record; remove it")));
        }
    } else if let Some((flag, _)) = record_flags.iter().find(|(_, given)| *given) {
        return Err(input(anyhow!("{flag}: reads a --record, not a --pulse; remove it")));
    }
    if let (Some(n), Some(shape)) = (args.cycles, args.pulse)
        && shape != PulseArg::TypeC
    {
        return Err(input(anyhow!(
            "--cycles {n}: only a type-c pulse has cycles (--pulse {}); remove it",
            ShapeKind::from(shape).name()
        )));
    }
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

fn motion(args: &SpectrumArgs) -> Result<Motion, BatchError> {
    let (drive, pga_g, json) = match (&args.record, args.pulse) {
        (Some(path), _) => {
            let spec = args.reading.spec()?;
            let record = read_record(path, &spec).map_err(|e| input(e.context("--record")))?;
            let peaks = record.series.peaks(1.0);
            let mut json = json!({
                "kind": "record",
                "file": path.display().to_string(),
                "unit": record.unit.name(),
                "samples": record.series.len(),
                "duration_s": record.series.duration_s(),
                "pga_g": peaks.pga_g,
                "pgv_m_s": peaks.pgv_m_s,
                "pgd_m": peaks.pgd_m,
                "vertical": Json::Null,
            });
            let use_vertical = args.vertical.unwrap_or(VerticalArg::Record) == VerticalArg::Record;
            let drive = match &args.record_v {
                Some(path_v) if use_vertical => {
                    let mut spec_v = spec;
                    if let Some(u) = &args.unit_v {
                        spec_v.unit = Some(
                            crate::model::units::AccelUnit::parse(u)
                                .ok_or_else(|| input(anyhow!("--unit-v {u}: unknown unit (known: g, m/s2, cm/s2)")))?,
                        );
                    }
                    let vertical = read_record(path_v, &spec_v).map_err(|e| input(e.context("--record-v")))?;
                    let pv = vertical.series.peaks(1.0);
                    json["vertical"] = json!({
                        "file": path_v.display().to_string(),
                        "unit": vertical.unit.name(),
                        "samples": vertical.series.len(),
                        "duration_s": vertical.series.duration_s(),
                        "pga_g": pv.pga_g,
                        "pgv_m_s": pv.pgv_m_s,
                        "pgd_m": pv.pgd_m,
                    });
                    Drive::Paired {
                        horizontal: record,
                        vertical,
                    }
                }
                _ => Drive::Record(record),
            };
            (drive, peaks.pga_g, json)
        }
        (None, Some(shape)) => {
            let positive = |flag: &str, v: Option<f64>| match v {
                Some(v) if v > 0.0 && v.is_finite() => Ok(v),
                Some(v) => Err(input(anyhow!("{flag} {}: must be a finite number > 0", show(v)))),
                None => Err(input(anyhow!("{flag}: required with --pulse"))),
            };
            let a_p_g = positive("--pulse-accel", args.pulse_accel)?;
            let period = positive("--pulse-period", args.pulse_period)?;
            let cycles = args.cycles.unwrap_or(1);
            if !(1..=MAX_TYPE_C_CYCLES).contains(&cycles) {
                return Err(input(anyhow!("--cycles {cycles}: must be in 1..={MAX_TYPE_C_CYCLES}")));
            }
            let drive = Drive::PhysicalPulse {
                shape: shape.into(),
                cycles,
                a_p_g,
                omega_p: std::f64::consts::TAU / period,
            };
            let json = json!({
                "kind": "pulse",
                "shape": ShapeKind::from(shape).name(),
                "cycles": cycles,
                "a_p_g": a_p_g,
                "period_s": period,
                "pga_g": a_p_g,
            });
            (drive, a_p_g, json)
        }
        (None, None) => return Err(input(anyhow!("--record FILE or --pulse SHAPE: one is required"))),
    };
    if pga_g <= 0.0 {
        return Err(input(anyhow!("--record: the record is all zeros (PGA 0 g)")));
    }
    let scale = match (args.scale, args.pga) {
        (Some(s), _) if !(s > 0.0 && s.is_finite()) => {
            return Err(input(anyhow!("--scale {}: must be > 0", show(s))));
        }
        (Some(s), _) => s,
        (None, Some(p)) if !(p > 0.0 && p.is_finite()) => {
            return Err(input(anyhow!("--pga {}: must be > 0 (g)", show(p))));
        }
        (None, Some(p)) => p / pga_g,
        (None, None) => 1.0,
    };
    let name = drive.name();
    let pga_v_g = match &drive {
        Drive::Paired { vertical, .. } => Some(vertical.series.peak_abs_g()),
        _ => None,
    };
    Ok(Motion {
        drive,
        scale,
        pga_g,
        pga_v_g,
        name,
        json,
    })
}

fn size_range(args: &SpectrumArgs) -> Result<SizeRange, BatchError> {
    let axis = match args.size {
        AxisArg::R => SizeAxis::HalfDiagonal,
        AxisArg::H => SizeAxis::Height,
    };
    if args.from == args.to && args.count > 1 {
        return Err(input(anyhow!(
            "--count {}: --from = --to = {} m gives {} identical blocks; give --count 1 or a --to above --from",
            args.count,
            show(args.from),
            args.count
        )));
    }
    let range = SizeRange::new(axis, args.from, args.to, args.count).map_err(|e| match e {
        SizeRangeError::From(v) => input(anyhow!("--from {}: must be a size > 0 (m)", show(v))),
        SizeRangeError::Reversed { from, to } => input(anyhow!(
            "--to {}: below --from {}; give from <= to",
            show(to),
            show(from)
        )),
        SizeRangeError::Count(n) => input(anyhow!(
            "--count {n}: must be >= 2 (or 1 when --from = --to) and at most 1000000"
        )),
    })?;
    // Sizes so close that they round to one value are the same block twice.
    if let Some(w) = range.values().windows(2).find(|w| w[1] <= w[0]) {
        return Err(input(anyhow!(
            "--count {}: --from {} to --to {} m are too close for {} distinct sizes ({} twice); give fewer",
            args.count,
            show(args.from),
            show(args.to),
            args.count,
            show(w[0])
        )));
    }
    Ok(range)
}

/// Runs `rocking spectrum`.
pub fn run(args: &SpectrumArgs) -> Result<(), BatchError> {
    refuse_ignored_flags(args)?;
    let base = args.base.load(&owns(args))?;
    let motion = motion(args)?;
    let sizes = size_range(args)?;
    let ratios = positive_list("--b-over-h", &args.b_over_h)?;
    increasing("--b-over-h", &ratios)?;
    if sizes.count * ratios.len() > crate::analysis::engineering::rocking_spectrum::MAX_BLOCKS {
        return Err(input(anyhow!("--count × --b-over-h: at most 1000000 blocks")));
    }
    let overturn = if args.overturn_scale {
        let (step, max) = (
            args.search_step.unwrap_or(SEARCH_STEP),
            args.search_max.unwrap_or(SEARCH_MAX),
        );
        let ladder = search_ladder("--search-step", step, "--search-max", max)?;
        let rel_tol = args.rel_tol.unwrap_or(REL_TOL);
        if !(rel_tol > 0.0 && rel_tol < 1.0) {
            return Err(input(anyhow!("--rel-tol {}: must be in (0, 1)", show(rel_tol))));
        }
        Some(OverturnOptions { ladder, rel_tol })
    } else {
        None
    };
    let spec = SpectrumSpec {
        base: &base,
        drive: &motion.drive,
        scale: motion.scale,
        sizes,
        b_over_h: ratios,
        overturn,
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
            show(args.pulse_period.unwrap_or(f64::NAN)),
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
    let pool = thread_pool(args.threads)?;
    output::check_writable(&args.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;

    let start = Instant::now();
    let bar = progress_bar(spec.sizes.count * spec.b_over_h.len(), "blocks", args.quiet);
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
    let summary = summary(&spec, &points);
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
            label: format!("B/H = {}", num(ratio)),
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
                label: format!("B/H = {}", num(ratio)),
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

    super::write::staged(&args.out, |staging| {
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
    if !args.quiet {
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
        crate::say!("wrote {}", args.out.display());
    }
    Ok(())
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
        t_overturn_s: (r.end == EndState::Overturned)
            .then_some(r.t_end_event_s)
            .flatten()
            .map(Num),
        t_flight_s: (r.end == EndState::Flight)
            .then_some(r.t_end_event_s)
            .flatten()
            .map(Num),
        overturn_scale: first.map(|(a, _)| Num(a)),
        overturn_pga_g: first.map(|(a, _)| Num(pga_of(a))),
        overturn_end: first.map(|(_, r)| r.end.name().to_string()),
        safe_windows: p.overturn.as_ref().map(|s| s.safe_windows.len() as u32),
    }
}

/// Per B/H: how many blocks overturned or flew, the largest that
/// overturned and the smallest that survived.
fn summary(spec: &SpectrumSpec<'_>, points: &[SpectrumPoint]) -> Json {
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
                "B/H = {}: {over} of {} overturned{}{}{}",
                num(ratio),
                of.len(),
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
