//! `rocking fragility`: fragility curves of blocks under a suite of
//! records scaled to intensity levels, and the merge of its shards.
//!
//! Writes into `--out`:
//! - `runs.csv`: one row per run (block outer, level, record inner);
//! - `fractions.csv`: per block and level the counts, the fractions
//!   overturned and reaching the θ/α threshold, and the fitted curves with
//!   their 95 % bands at that level;
//! - `fragility.json`: the suite (files, units, peaks), levels, blocks,
//!   threshold, base configuration and version, and per block both
//!   lognormal fits (median, β, their 95 % intervals, the band on a fine
//!   grid) or why there is none;
//! - `fragility.png/svg`.
//!
//! A shard (`--shard K/N`) computes the runs i with i mod N = K and writes
//! only `runs.csv` and `fragility.json`; `rocking merge` joins the shards
//! and writes exactly the files one run writes (the fits are computed from
//! the joined rows, whose numbers round-trip bit for bit).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, anyhow};
use serde_json::{Value as Json, json};

mod shards;
mod write;

pub(crate) use shards::{are_fragility_shards, merge};
use write::write_whole;

use super::eng_args::{
    BaseArgs, Owns, RecordUnitArgs, RunArgs, VerticalArg, block, flag_error, input, positive_list, read_record, show,
};
use super::eng_motion::flagged;
use super::error::BatchError;
use super::flags::Flags;
use super::suite::{SuiteEntry, suite};
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::engineering::fragility::{
    FragilityCheckError, FragilitySpec, Intensity, SuiteRecord, run_fragility,
};
use crate::analysis::engineering::request;
use crate::analysis::engineering::{BlockSize, Drive, EndState};
use crate::analysis::orbit_diagram::Shard;
use crate::io::config::to_json;
use crate::io::csv::{self, Num};
use crate::io::engineering_files::FragilityRunRow;
use crate::io::output;
use crate::plot::labels::{friction_text, num};
use crate::sim::scenario::{IMPLAUSIBLE_PGA_G, IMPLAUSIBLY_SMALL_PGA_G, Record, readable_g};

/// The intensity measure on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ImArg {
    /// Peak ground acceleration, g.
    Pga,
    /// Peak ground velocity, m/s (integrated from the record as the model
    /// sees it, no baseline correction).
    Pgv,
    /// PGA/(g tan α), dimensionless (1 = the block's static uplift
    /// acceleration; Dimitrakopoulos & Paraskeva 2015).
    PgaTanAlpha,
    /// PGV·p/(g tan α), dimensionless (Dimitrakopoulos & Paraskeva 2015).
    PgvPTanAlpha,
    /// Sa(T, 5 %), g: the record's pseudo-spectral acceleration at the
    /// period --sa-period, exact for the piecewise-linear record.
    Sa,
}

/// Arguments of `rocking fragility`.
#[derive(Debug, Clone, clap::Args)]
pub struct FragilityArgs {
    /// A record file, or a folder whose files are all records (taken in
    /// name order); repeatable.
    #[arg(long = "records", value_name = "FILE|DIR")]
    pub records: Vec<PathBuf>,
    /// A list of records, one per line: `PATH [UNIT] [channel=N]`, or a
    /// horizontal and its vertical `PATH [UNIT] + VPATH [UNIT]` (PATH
    /// relative to the list's folder, UNIT g|m/s2|cm/s2 for text files,
    /// channel=N of a COSMOS file of several; `#` comments).
    #[arg(long, value_name = "LIST")]
    pub suite: Option<PathBuf>,
    /// Whether to apply the vertical components the suite names, scaled by
    /// the same factor as their horizontals: `record` (the default when
    /// every line names one) or `none` (horizontal only).
    #[arg(long, value_enum, value_name = "none|record")]
    pub vertical: Option<VerticalArg>,
    /// Unit (and time step) of text records without their own.
    #[command(flatten)]
    pub reading: RecordUnitArgs,
    /// The intensity measure the records are scaled to.
    #[arg(long, value_enum, default_value = "pga")]
    pub im: ImArg,
    /// The period T of `--im sa`, s (Sa at 5 % damping).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub sa_period: Option<f64>,
    /// Intensity levels (g for PGA, m/s for PGV, dimensionless for the
    /// rocking measures), each > 0: comma-separated, or FROM:TO:N for N
    /// evenly spaced levels.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub levels: String,
    /// A block WIDTHxHEIGHT in metres, e.g. 0.6x2.0; repeatable. With a
    /// [[stack]] scene, the stack's bounding block (bottom width x total
    /// height, of the stack's own B/H), the whole stack scaled to it; the
    /// stack as given when left out.
    #[arg(long = "block", value_name = "BxH")]
    pub blocks: Vec<String>,
    /// Peak rotation θ/α whose exceedance is counted and fitted too.
    #[arg(
        long,
        value_name = "THETA/ALPHA",
        default_value_t = 0.5,
        allow_negative_numbers = true
    )]
    pub threshold: f64,
    /// Compute only runs i with i mod N = K (K from 0), for cluster array
    /// jobs; join the shards with `rocking merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Friction and the base scene.
    #[command(flatten)]
    pub base: BaseArgs,
    /// Threads, output folder, quiet.
    #[command(flatten)]
    pub run: RunArgs,
}

/// What the files are computed from besides the runs: read back from
/// `fragility.json` by the merge.
struct Layout {
    im: Intensity,
    levels: Vec<f64>,
    blocks: Vec<BlockSize>,
    records: usize,
    threshold: f64,
    friction: String,
    /// The overturning angle θ/α (`run.tumble_theta`).
    overturn_at: f64,
    /// The period of `--im sa`, s.
    sa_period: Option<f64>,
    /// Whether the records' vertical components ran.
    vertical: bool,
    /// A stack's number of blocks (its sizes are its bounding block's);
    /// `None` for a block.
    stack: Option<usize>,
}

impl Layout {
    /// The motion and contact for a figure's subtitle: the friction, and
    /// whether the verticals ran.
    fn conditions(&self) -> String {
        if self.vertical {
            format!("{}, with each record's vertical", self.friction)
        } else {
            self.friction.clone()
        }
    }
}

impl Layout {
    /// What block `block` is called in the answer and the figure:
    /// `0.6 × 2 m`, or `3-block stack 0.75 × 1.35 m`.
    fn block_name(&self, block: &BlockSize) -> String {
        let size = format!("{} × {} m", num(block.width_m), num(block.height_m));
        match self.stack {
            Some(k) => format!("{k}-block stack {size}"),
            None => size,
        }
    }

    fn runs(&self) -> usize {
        self.blocks.len() * self.levels.len() * self.records
    }
}

/// What `fragility` sets itself, for refusing `--set` keys it would
/// ignore.
const OWNS: Owns = Owns {
    command: "fragility",
    sizes: "--block",
    motion: "--records/--suite, --unit, --dt, --im, --levels",
    record: true,
    vertical: "the suite's `+ VPATH` lines (--vertical record)",
};

/// Scale factor above which a record's scaling is worth a warning: beyond
/// about 10 a scaled record's duration and frequency content no longer
/// match the intensity it is scaled to (a weak, short record stands in for
/// a strong, long one), and the fit leans on motion no site produces.
pub(crate) const LARGE_SCALE: f64 = 10.0;

/// The warnings about one record of the suite, one line each: its PGA as
/// read (in its unit) beyond what ground motion does, which suggests a wrong
/// unit (above [`IMPLAUSIBLE_PGA_G`], below [`IMPLAUSIBLY_SMALL_PGA_G`]), and
/// a scale factor above [`LARGE_SCALE`] to reach the highest level.
fn record_warnings(
    name: &str,
    record: &Record,
    im: Intensity,
    intensity: f64,
    levels: &[f64],
    blocks: &[BlockSize],
) -> Vec<String> {
    let mut out = Vec::new();
    let pga = record.series.peaks(1.0).pga_g;
    let doubt = if pga > IMPLAUSIBLE_PGA_G {
        Some(format!("implausible for ground motion (above {IMPLAUSIBLE_PGA_G} g)"))
    } else if pga < IMPLAUSIBLY_SMALL_PGA_G {
        Some(format!(
            "implausibly small for ground motion (below {IMPLAUSIBLY_SMALL_PGA_G} g)"
        ))
    } else {
        None
    };
    if let Some(doubt) = doubt {
        out.push(format!(
            "warning: record {name} ({}): PGA {} g as read in {} is {doubt}; check its unit",
            record.path.display(),
            readable_g(pga),
            record.unit
        ));
    }
    let top = levels.iter().copied().fold(0.0, f64::max);
    let scale = blocks
        .iter()
        .map(|&b| top / (intensity * im.block_factor(b)))
        .fold(0.0, f64::max);
    if scale > LARGE_SCALE {
        let unit = im.unit();
        let level = if unit.is_empty() {
            format!("{} {}", im.label(), num(top))
        } else {
            format!("{} {unit}", num(top))
        };
        out.push(format!(
            "warning: record {name} ({}): scaled by up to {scale:.1} to reach level {level} (above {LARGE_SCALE}: a weak record stands in for a much stronger one)",
            record.path.display(),
        ));
    }
    out
}

/// Runs `rocking fragility`.
pub fn run(args: &FragilityArgs) -> Result<(), BatchError> {
    let base = args.base.load(&OWNS)?;
    let im = match args.im {
        ImArg::Pga => Intensity::Pga,
        ImArg::Pgv => Intensity::Pgv,
        ImArg::PgaTanAlpha => Intensity::PgaTanAlpha,
        ImArg::PgvPTanAlpha => Intensity::PgvPTanAlpha,
        ImArg::Sa => Intensity::Sa,
    };
    let sa_period = request::sa_period(im, args.sa_period).map_err(flagged)?;
    let levels = positive_list("--levels", &args.levels)?;
    let blocks: Vec<BlockSize> = args
        .blocks
        .iter()
        .map(|b| {
            block("--block", b).map(|(w, h)| BlockSize {
                width_m: w,
                height_m: h,
            })
        })
        .collect::<Result<_, _>>()?;
    let blocks = request::fragility_blocks(&base, blocks, im).map_err(flagged)?;
    // The same block twice would count its runs twice in every fraction.
    for (j, b) in blocks.iter().enumerate() {
        if let Some(i) = blocks[..j].iter().position(|a| a == b) {
            return Err(input(anyhow!(
                "--block {} and --block {}: the same {} x {} m block twice; give each block once",
                args.blocks[i],
                args.blocks[j],
                show(b.width_m),
                show(b.height_m)
            )));
        }
    }
    request::threshold(args.threshold).map_err(flagged)?;
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()
        .map_err(super::sweep::plan_input)?;
    let spec_read = args.reading.spec()?;
    let entries = suite(&args.records, args.suite.as_deref(), spec_read)?;
    let vertical = vertical_choice(args.vertical, &entries)?;
    let mut records = Vec::with_capacity(entries.len());
    let mut record_json = Vec::with_capacity(entries.len());
    for SuiteEntry {
        path,
        spec,
        vertical: named_vertical,
        origin,
    } in &entries
    {
        let named = |e: anyhow::Error| match origin {
            Some(o) => input(e.context(o.clone())),
            None => input(e.context("--records")),
        };
        let record = read_record(path, spec).map_err(named)?;
        let peaks = record.series.peaks(1.0);
        let intensity = request::record_intensity(path, &record.series, im, sa_period)
            .map_err(|e| named(anyhow!(e.render(&Flags))))?;
        for warning in record_warnings(
            &Drive::Record(record.clone()).name(),
            &record,
            im,
            intensity,
            &levels,
            &blocks,
        ) {
            eprintln!("{warning}");
        }
        let vertical_record = match named_vertical {
            Some((path_v, spec_v)) if vertical == VerticalArg::Record => {
                Some(read_record(path_v, spec_v).map_err(named)?)
            }
            _ => None,
        };
        record_json.push(json!({
            "file": path.display().to_string(),
            "name": Drive::Record(record.clone()).name(),
            "unit": record.unit.name(),
            "pga_g": peaks.pga_g,
            "pgv_m_s": peaks.pgv_m_s,
            "pgd_m": peaks.pgd_m,
            "sa_g": sa_period.map(|_| intensity),
            "duration_s": record.series.duration_s(),
            "vertical": vertical_record.as_ref().map(|v| {
                let pv = v.series.peaks(1.0);
                json!({
                    "file": v.path.display().to_string(),
                    "unit": v.unit.name(),
                    "pga_g": pv.pga_g,
                    "pgv_m_s": pv.pgv_m_s,
                    "pgd_m": pv.pgd_m,
                    "duration_s": v.series.duration_s(),
                })
            }),
        }));
        let drive = match vertical_record {
            Some(v) => Drive::Paired {
                horizontal: record,
                vertical: v,
            },
            None => Drive::Record(record),
        };
        records.push(SuiteRecord { drive, intensity });
    }
    let spec = FragilitySpec {
        base: &base,
        records: &records,
        levels: &levels,
        blocks: &blocks,
        im,
    };
    spec.check().map_err(|e| match e {
        FragilityCheckError::Scenario { block: b, error } => input(anyhow!(
            "--block {}x{}: {}",
            show(b.width_m),
            show(b.height_m),
            flag_error(&error, &[("excitation.scale_h", "--levels")])
        )),
        too_many @ FragilityCheckError::TooManyRuns(_) => input(anyhow!(too_many)),
    })?;
    let pool = thread_pool(args.run.threads)?;
    output::check_writable(&args.run.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;
    let indices: Vec<usize> = match shard {
        None => (0..spec.run_count()).collect(),
        Some(s) => (s.index..spec.run_count()).step_by(s.count).collect(),
    };

    let start = Instant::now();
    let bar = progress_bar(indices.len(), "runs", args.run.quiet);
    let runs = pool
        .install(|| run_fragility(&spec, &indices, &progress_fn(&bar)))
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();

    // Each record's peak accelerations at scale 1, g.
    let pga_h: Vec<f64> = records
        .iter()
        .map(|r| match &r.drive {
            Drive::Record(h) | Drive::Paired { horizontal: h, .. } => h.series.peak_abs_g(),
            Drive::PhysicalPulse { .. } | Drive::NormalisedPulse { .. } => 0.0,
        })
        .collect();
    let pga_v: Vec<Option<f64>> = records
        .iter()
        .map(|r| match &r.drive {
            Drive::Paired { vertical, .. } => Some(vertical.series.peak_abs_g()),
            _ => None,
        })
        .collect();
    let rows: Vec<FragilityRunRow> = runs
        .iter()
        .zip(&indices)
        .map(|(r, &i)| {
            let b = blocks[r.at.block];
            let resp = &r.response;
            FragilityRunRow {
                run: i as u64,
                block: r.at.block as u64,
                width_m: Num(b.width_m),
                height_m: Num(b.height_m),
                record: records[r.at.record].drive.name(),
                im: im.column().to_string(),
                level: Num(levels[r.at.level]),
                scale: Num(r.scale),
                end: resp.end.name().to_string(),
                peak_theta_over_alpha: Num(resp.peak_theta_over_alpha),
                t_overturn_s: (resp.end == EndState::Overturned)
                    .then_some(resp.t_end_event_s)
                    .flatten()
                    .map(Num),
                t_flight_s: (resp.end == EndState::Flight)
                    .then_some(resp.t_end_event_s)
                    .flatten()
                    .map(Num),
                pga_h_g: Num(r.scale * pga_h[r.at.record]),
                pga_v_g: pga_v[r.at.record].map(|v| Num(r.scale * v)),
            }
        })
        .collect();
    let layout = Layout {
        im,
        levels: levels.clone(),
        blocks: blocks.clone(),
        records: records.len(),
        threshold: args.threshold,
        friction: friction_text(&base),
        stack: base.stack.as_ref().map(Vec::len),
        overturn_at: base.run.tumble_theta,
        sa_period,
        vertical: vertical == VerticalArg::Record,
    };
    let common = json!({
        "command": "rocking fragility",
        "version": env!("CARGO_PKG_VERSION"),
        "im": im,
        "sa_period_s": sa_period,
        "sa_damping": sa_period.map(|_| crate::analysis::engineering::fragility::SA_DAMPING),
        "levels": levels,
        "blocks": blocks,
        "records": record_json,
        "threshold_theta_over_alpha": args.threshold,
        "vertical": vertical,
        "scaling": match vertical {
            VerticalArg::Record => "each record's horizontal and vertical components are multiplied by one factor: the level over the horizontal's intensity measure",
            VerticalArg::None => "each record's horizontal component is multiplied by the level over its intensity measure; no vertical motion",
        },
        "record_tail_s": base.run.record_tail_s.unwrap_or(crate::sim::scenario::RECORD_TAIL_S),
        "runs": spec.run_count(),
        "shard": Json::Null,
        "friction": layout.friction,
        "config": to_json(&base),
        "units": "levels in the unit of `im` (pga: g, pgv: m/s); lengths m, times s; peak_theta_over_alpha = max|θ|/α; fits: P = Φ(ln(level/median)/beta), 95 % intervals from the Fisher information (delta method)",
    });
    let lines = match shard {
        Some(s) => {
            let mut meta = common;
            meta["shard"] = json!(s);
            let runs_csv = csv::to_string(rows);
            // What makes a shard checkable by `merge`, as a sweep shard: the
            // file's rows and CRC-32, so a cut or edited file is noticed.
            meta["files"] = json!({ "runs.csv": super::sweep::file_check(&runs_csv) });
            super::write::staged(&args.run.out, |staging| {
                staging.text("runs.csv", &runs_csv)?;
                staging.text("fragility.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
                Ok(())
            })?;
            vec![format!(
                "shard {}/{}: {} of {} runs",
                s.index,
                s.count,
                indices.len(),
                spec.run_count()
            )]
        }
        None => write_whole(&args.run.out, common, &layout, rows)?,
    };
    if !args.run.quiet {
        crate::say!(
            "fragility: {} blocks × {} levels × {} records = {} runs in {wall:.2} s",
            blocks.len(),
            levels.len(),
            records.len(),
            indices.len()
        );
        match vertical {
            VerticalArg::Record => crate::say!(
                "  with the vertical components, each scaled by the same factor as its horizontal (level / the horizontal's intensity)"
            ),
            VerticalArg::None if entries.iter().any(|e| e.vertical.is_some()) => {
                crate::say!(
                    "  horizontal motion only: the vertical components the suite names are not read (--vertical none)"
                )
            }
            VerticalArg::None => {}
        }
        if let Some(note) = super::eng_args::floor_note(&base) {
            crate::say!("  {note}");
        }
        for l in lines {
            crate::say!("  {l}");
        }
        crate::say!("wrote {}", args.run.out.display());
    }
    Ok(())
}

/// Whether the study applies vertical components: `--vertical` as given,
/// else `record` when every record names one and `none` when none does.
/// A suite that names a vertical for some records only must say which it
/// means: running some records with their verticals and others without
/// would mix two studies in one curve.
fn vertical_choice(flag: Option<VerticalArg>, entries: &[SuiteEntry]) -> Result<VerticalArg, BatchError> {
    let lacking = entries.iter().find(|e| e.vertical.is_none());
    let named = entries.iter().find(|e| e.vertical.is_some());
    let at = |e: &SuiteEntry| {
        e.origin
            .clone()
            .unwrap_or_else(|| format!("--records {}", e.path.display()))
    };
    match (flag, lacking, named) {
        (Some(VerticalArg::None), _, _) => Ok(VerticalArg::None),
        (Some(VerticalArg::Record), Some(e), _) => Err(input(anyhow!(
            "--vertical record: {} names no vertical component (write `PATH [UNIT] + VPATH [UNIT]` in a --suite list)",
            at(e)
        ))),
        (Some(VerticalArg::Record), None, _) | (None, None, _) => Ok(VerticalArg::Record),
        (None, Some(_), None) => Ok(VerticalArg::None),
        (None, Some(e), Some(v)) => Err(input(anyhow!(
            "{} names a vertical component but {} does not; complete the suite, or give --vertical none to run horizontals only",
            at(v),
            at(e)
        ))),
    }
}
