//! The ground motion of `spectrum` and `sliding-spectrum`: a record (with
//! `spectrum`'s optional vertical) or an analytic pulse, and its scale,
//! checked by the core's requests
//! ([`request`](crate::analysis::engineering::request)) and worded as
//! flags; what the output JSON says about it.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use serde_json::{Value as Json, json};

use super::eng_args::{RecordUnitArgs, input, read_record};
use super::error::BatchError;
use super::flags::Flags;
use crate::analysis::engineering::Drive;
use crate::analysis::engineering::request::{PulseRequest, RequestError, Scaling, unit};
use crate::analysis::field::RequestField;
use crate::io::record::RecordSpec;
use crate::sim::scenario::{Record, ShapeKind};

/// The record of `spectrum` and `sliding-spectrum` (or `--pulse`
/// instead) and how a text record is read.
#[derive(Debug, Clone, clap::Args)]
pub struct RecordArgs {
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
}

/// The flags of a pulse's numbers and of the motion's scale (after
/// `--pulse` in `spectrum` and `sliding-spectrum`).
#[derive(Debug, Clone, clap::Args)]
pub struct PulseScaleArgs {
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
}

/// The motion flags of a command, as given.
pub(crate) struct MotionArgs<'a> {
    /// `--record`.
    pub record: Option<&'a Path>,
    /// `--unit`, `--dt`, `--channel`.
    pub reading: &'a RecordUnitArgs,
    /// `--record-v` and `--unit-v`, when the vertical is applied.
    pub vertical: Option<(&'a PathBuf, Option<&'a str>)>,
    /// `--pulse`.
    pub pulse: Option<PulseArg>,
    /// `--cycles`, `--pulse-accel`, `--pulse-period`, `--scale`, `--pga`.
    pub numbers: &'a PulseScaleArgs,
}

/// The motion as checked: what to run and what to write about it.
pub(crate) struct Motion {
    /// What drives the runs.
    pub drive: Drive,
    /// Scale of the runs.
    pub scale: f64,
    /// PGA at scale 1, g.
    pub pga_g: f64,
    /// The vertical component's PGA at scale 1, g, when it is applied.
    pub pga_v_g: Option<f64>,
    /// Name for titles.
    pub name: String,
    /// Its description for the output JSON.
    pub json: Json,
}

/// A request error in the words of the flags.
pub(crate) fn flagged(e: RequestError) -> BatchError {
    input(anyhow!(e.render(&Flags)))
}

/// What the output JSON says about one record component.
fn component_json(path: &Path, record: &Record) -> Json {
    let series = &record.series;
    let peaks = series.peaks(1.0);
    json!({
        "file": path.display().to_string(),
        "unit": record.unit.name(),
        "samples": series.len(),
        "duration_s": series.duration_s(),
        "pga_g": peaks.pga_g,
        "pgv_m_s": peaks.pgv_m_s,
        "pgd_m": peaks.pgd_m,
    })
}

/// Warns on stderr when `record`'s PGA as read suggests a wrong unit:
/// the command runs, but a record in m/s² read as g would shake every
/// block ten times too hard without a word.
fn unit_warning(flag: &str, record: &Record) {
    if let Some(doubt) = record.unit_doubt() {
        eprintln!("warning: {flag} {}: {doubt}", record.path.display());
    }
}

/// Reads and checks the motion of `args`; `with_vertical_key` writes
/// `"vertical"` into a record's JSON (`spectrum`, which can apply one).
pub(crate) fn motion(args: &MotionArgs<'_>, with_vertical_key: bool) -> Result<Motion, BatchError> {
    let (drive, pga_g, json) = match (args.record, args.pulse) {
        (Some(path), _) => {
            let spec = args.reading.spec()?;
            let record = read_record(path, &spec).map_err(|e| input(e.context("--record")))?;
            let pga_g = record.series.peaks(1.0).pga_g;
            unit_warning("--record", &record);
            let mut json = component_json(path, &record);
            json["kind"] = json!("record");
            if with_vertical_key {
                json["vertical"] = Json::Null;
            }
            let drive = match args.vertical {
                Some((path_v, unit_v)) => {
                    let spec_v = RecordSpec {
                        unit: match unit_v {
                            Some(u) => Some(unit(RequestField::UnitV, u).map_err(flagged)?),
                            None => spec.unit,
                        },
                        ..spec
                    };
                    let vertical = read_record(path_v, &spec_v).map_err(|e| input(e.context("--record-v")))?;
                    unit_warning("--record-v", &vertical);
                    json["vertical"] = component_json(path_v, &vertical);
                    Drive::Paired {
                        horizontal: record,
                        vertical,
                    }
                }
                None => Drive::Record(record),
            };
            (drive, pga_g, json)
        }
        (None, Some(shape)) => {
            let pulse = PulseRequest {
                shape: shape.into(),
                cycles: args.numbers.cycles,
                accel_g: args.numbers.pulse_accel,
                period_s: args.numbers.pulse_period,
            }
            .checked()
            .map_err(flagged)?;
            let json = json!({
                "kind": "pulse",
                "shape": ShapeKind::from(shape).name(),
                "cycles": pulse.cycles,
                "a_p_g": pulse.a_p_g,
                "period_s": pulse.period_s,
                "pga_g": pulse.a_p_g,
            });
            (pulse.drive, pulse.a_p_g, json)
        }
        (None, None) => return Err(input(anyhow!("--record FILE or --pulse SHAPE: one is required"))),
    };
    let scale = Scaling {
        scale: args.numbers.scale,
        pga_g: args.numbers.pga,
    }
    .factor(pga_g)
    .map_err(flagged)?;
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

impl<'a> MotionArgs<'a> {
    /// The motion flags of a command's `--record` and its reading
    /// (`source`), `--pulse`, the pulse's numbers and the vertical
    /// component as applied.
    pub(crate) fn new(
        source: &'a RecordArgs,
        pulse: Option<PulseArg>,
        numbers: &'a PulseScaleArgs,
        vertical: Option<(&'a PathBuf, Option<&'a str>)>,
    ) -> Self {
        MotionArgs {
            record: source.record.as_deref(),
            reading: &source.reading,
            vertical,
            pulse,
            numbers,
        }
    }

    /// Refuses the flags of a record with a pulse and those of a pulse
    /// with a record (each would be ignored without a word), and cycles of
    /// a pulse that has none.
    pub(crate) fn refuse_mixed(&self) -> Result<(), BatchError> {
        refuse_mixed_motion(self.record.is_some(), self.pulse, self.reading, self.numbers)
    }
}

/// [`MotionArgs::refuse_mixed`] of the flags given apart.
fn refuse_mixed_motion(
    record: bool,
    pulse: Option<PulseArg>,
    reading: &RecordUnitArgs,
    numbers: &PulseScaleArgs,
) -> Result<(), BatchError> {
    let given = |v: bool, flag: &'static str| v.then_some(flag);
    if record {
        let pulse_flags = [
            given(numbers.pulse_accel.is_some(), "--pulse-accel"),
            given(numbers.pulse_period.is_some(), "--pulse-period"),
            given(numbers.cycles.is_some(), "--cycles"),
        ];
        if let Some(flag) = pulse_flags.into_iter().flatten().next() {
            return Err(input(anyhow!("{flag}: describes a --pulse, not a --record; remove it")));
        }
    } else {
        let record_flags = [
            given(reading.unit.is_some(), "--unit"),
            given(reading.dt.is_some(), "--dt"),
        ];
        if let Some(flag) = record_flags.into_iter().flatten().next() {
            return Err(input(anyhow!("{flag}: reads a --record, not a --pulse; remove it")));
        }
    }
    if let (Some(n), Some(shape)) = (numbers.cycles, pulse)
        && shape != PulseArg::TypeC
    {
        return Err(input(anyhow!(
            "--cycles {n}: only a type-c pulse has cycles (--pulse {}); remove it",
            ShapeKind::from(shape).name()
        )));
    }
    Ok(())
}

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
