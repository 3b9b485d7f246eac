//! What the engineering commands (`spectrum`, `pulse-map`, `fragility`)
//! share on the command line: the base scene with its friction, reading a
//! record with its unit, and number lists. Every error names the flag (or
//! the file and line) and is bad input (exit 2).

use std::path::{Path, PathBuf};

use anyhow::anyhow;

use super::args::SceneArgs;
use super::error::BatchError;
use super::flags::Flags;
use crate::analysis::engineering::request::unit;
use crate::analysis::field::RequestField;
pub use crate::analysis::field::show;
use crate::io::config;
use crate::io::record::{RecordError, RecordSpec, read_record_as};
use crate::sim::scenario::Record;
use crate::sim::{Scenario, ScenarioError};

/// Most values of one list flag.
pub(crate) const MAX_LIST: usize = 100_000;

/// The block's contact and the solver: a scene, and the friction flag.
#[derive(Debug, Clone, clap::Args)]
pub struct BaseArgs {
    /// Friction of the block, μ_s = μ_k (`none`: no sliding, pure rocking,
    /// the default unless --preset/--config set one). For distinct
    /// coefficients use --set friction.static=… --set friction.kinetic=….
    #[arg(long, value_name = "MU|none")]
    pub friction: Option<String>,
    /// A preset or config for everything else (impact law, tolerances,
    /// overturning angle run.tumble_theta, record tail run.tail_s), and
    /// --set overrides. Without --preset/--config the base is the paper's
    /// defaults: Housner impact, no sliding, rtol 1e-10. Its block and
    /// excitation are replaced by the command's.
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// How an engineering command runs and where it writes.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
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

/// What an engineering command sets itself on every run, so that a
/// `--set` of a key it would replace or ignore is refused naming the flags
/// that set it instead.
#[derive(Clone, Copy, Debug)]
pub struct Owns {
    /// The command, as typed (`spectrum`).
    pub command: &'static str,
    /// The flags that set the blocks' sizes.
    pub sizes: &'static str,
    /// The flags that set the motion.
    pub motion: &'static str,
    /// Whether the motion is a record (a run lasts the record and
    /// `run.tail_s`); otherwise a pulse (the pulse and 50 τ).
    pub record: bool,
    /// Where the vertical motion comes from (for messages).
    pub vertical: &'static str,
}

/// Whether an engineering command applies the vertical components its
/// records name (`--vertical`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum VerticalArg {
    /// Horizontal motion only: the vertical components named are not read.
    None,
    /// Each record's vertical component, scaled with its horizontal.
    Record,
}

impl VerticalArg {
    /// Flag value, as typed.
    pub fn name(self) -> &'static str {
        match self {
            VerticalArg::None => "none",
            VerticalArg::Record => "record",
        }
    }
}

/// Whether `name` (of `[excitation]`) is a vertical-motion key: the
/// command takes the vertical from its own flags (a suite line's
/// `+ VPATH`, `--record-v`), scaled with the horizontal. The catalogue
/// names every vertical key with the suffix `_v`.
fn is_vertical_key(name: &str) -> bool {
    name.ends_with("_v") && crate::sim::catalogue::spec(&format!("excitation.{name}")).is_some()
}

/// The flags that set the motion of a record (`record`) or else a pulse,
/// for refusing a `--set` of a motion key ([`Owns::motion`]).
fn motion_flags(record: bool) -> &'static str {
    if record {
        "--record, --unit, --dt, --scale/--pga"
    } else {
        "--pulse, --pulse-accel, --pulse-period, --cycles, --scale/--pga"
    }
}

impl Owns {
    /// What `command` sets itself when its motion is a record (`record`)
    /// or else a pulse: the blocks' sizes by the flags `sizes`, the motion
    /// by that kind's flags, the vertical motion from `vertical`.
    pub(crate) fn with_motion(
        command: &'static str,
        sizes: &'static str,
        record: bool,
        vertical: &'static str,
    ) -> Owns {
        Owns {
            command,
            sizes,
            motion: motion_flags(record),
            record,
            vertical,
        }
    }

    /// Why `--set key` is refused, if it is: the engineering runs replace
    /// the block, the motion, the initial state, the run's end, its output
    /// and analyses (see `response::scenario_for`); a vertical motion
    /// set by key would be applied unscaled and unnamed, so it comes from
    /// the command's own flags instead.
    pub fn refusal(&self, key: &str) -> Option<String> {
        let (section, name) = key.split_once('.')?;
        let cmd = self.command;
        let why = match (section, name) {
            ("block", _) => format!("{cmd} sets every block's size itself ({}); remove it", self.sizes),
            ("excitation", n) if is_vertical_key(n) => format!(
                "{cmd} takes the vertical motion from {} and scales it with the horizontal; remove it",
                self.vertical
            ),
            ("excitation", _) => format!("{cmd} sets the motion itself ({}); remove it", self.motion),
            ("initial", _) => format!("{cmd} starts every run at rest; remove it"),
            ("run", "tau_end" | "t_end") if self.record => format!(
                "{cmd} runs each record to its end and run.tail_s after it (default 30 s); remove it (or set run.tail_s)"
            ),
            ("run", "tau_end" | "t_end" | "tail_s") if !self.record => {
                format!("{cmd} runs each pulse and 50 τ after it; remove it")
            }
            ("run", "output_dt") => format!("{cmd} keeps no time history; remove it"),
            ("analysis", _) => format!("{cmd} computes no Lyapunov exponent or spectrum of a history; remove it"),
            _ => return None,
        };
        Some(format!("--set {key}: {why}"))
    }
}

impl BaseArgs {
    /// The base scenario for the command described by `owns`, validated;
    /// a `--set` of a key the command sets itself, `--friction` with
    /// `--set friction.*`, and a vertical record from any source are
    /// refused.
    pub fn load(&self, owns: &Owns) -> Result<Scenario, BatchError> {
        for set in &self.scene.sets {
            let key = set.split_once('=').map_or(set.as_str(), |(k, _)| k).trim();
            if let Some(why) = owns.refusal(key) {
                return Err(input(anyhow!(why)));
            }
            if let (Some(f), Some(("friction", _))) = (&self.friction, key.split_once('.')) {
                return Err(input(anyhow!(
                    "--friction {f} and --set {key}: both set the friction; give one"
                )));
            }
        }
        let mut base = if self.scene.preset.is_none() && self.scene.config.is_none() {
            let (table, source) = config::base_table(&self.scene.sets).map_err(input)?;
            config::from_table(&table, &source).map_err(input)?
        } else {
            self.scene.load().map_err(input)?
        };
        if base.excitation.record_v.is_some() {
            let from = match (&self.scene.preset, &self.scene.config) {
                (Some(p), _) => format!("--preset {p}"),
                (_, Some(c)) => format!("--config {}", c.display()),
                _ => "the base scene".into(),
            };
            return Err(input(anyhow!(
                "{from}: excitation.file_v: {} takes the vertical motion from {} and scales it with the horizontal; use a config without a vertical record",
                owns.command,
                owns.vertical
            )));
        }
        if let Some(text) = &self.friction {
            let mu = match text.trim() {
                "none" | "inf" => f64::INFINITY,
                t => match t.parse::<f64>() {
                    Ok(mu) if mu >= 0.0 && mu.is_finite() => mu,
                    _ => {
                        return Err(input(anyhow!("--friction {text}: expected a coefficient >= 0 or none")));
                    }
                },
            };
            base.block.mu_s = mu;
            base.block.mu_k = None;
            base.validate().map_err(|e| input(anyhow!("--friction {text}: {e}")))?;
        }
        Ok(base)
    }
}

/// Refuses a `[[stack]]` base scene for `command`, which runs single
/// blocks only, with `why` and what to use instead.
pub(crate) fn refuse_stack(base: &Scenario, command: &str, why: &str) -> Result<(), BatchError> {
    match base.stack {
        Some(_) => Err(input(anyhow!("stack: {command} {why}"))),
        None => Ok(()),
    }
}

/// How text records are read: their unit and, for one-column files, the
/// time step.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct RecordUnitArgs {
    /// Unit of the accelerations of text records: g, m/s2 or cm/s2
    /// (required for text files; an AT2 file states its own, which must
    /// agree if both are given).
    #[arg(long, value_name = "UNIT")]
    pub unit: Option<String>,
    /// Time step of one-column text records, s (sample k at k·dt).
    #[arg(long, value_name = "S")]
    pub dt: Option<f64>,
    /// The channel to read, from 1, of COSMOS files that hold several (a
    /// station's components one after the other); such a file is refused
    /// without it.
    #[arg(long, value_name = "N")]
    pub channel: Option<usize>,
}

impl RecordUnitArgs {
    /// The reading spec, or an error naming --unit.
    pub fn spec(&self) -> Result<RecordSpec, BatchError> {
        let unit = match &self.unit {
            None => None,
            Some(text) => Some(unit(RequestField::Unit, text).map_err(|e| input(anyhow!(e.render(&Flags))))?),
        };
        if self.channel == Some(0) {
            return Err(input(anyhow!("--channel 0: channels are counted from 1")));
        }
        Ok(RecordSpec {
            unit,
            dt: self.dt,
            channel: self.channel,
        })
    }
}

/// Reads the record at `path` with `spec`; a missing unit names --unit, a
/// missing step --dt, anything else the file and line.
pub(crate) fn read_record(path: &Path, spec: &RecordSpec) -> anyhow::Result<Record> {
    let loaded = read_record_as(path, spec).map_err(|e| match e {
        RecordError::NoUnit { .. } | RecordError::HeaderNoUnit { .. } | RecordError::NoHeaderUnit { .. } => {
            anyhow!("{e} (give the unit with --unit g|m/s2|cm/s2)")
        }
        RecordError::NoStep { .. } | RecordError::StatedStep { .. } => anyhow!("{e} (--dt)"),
        RecordError::Channels { .. } | RecordError::NoSuchChannel { .. } => anyhow!("{e} (--channel N)"),
        other => anyhow!(other),
    })?;
    Ok(Record {
        path: path.to_path_buf(),
        series: loaded.series,
        unit: loaded.unit,
        dt: spec.dt,
        crc32: loaded.crc32,
        channel: spec.channel,
    })
}

/// A list flag's values: `a,b,c` or `FROM:TO:N` (N evenly spaced values,
/// both ends included), each finite and > 0, no value twice (a repeated
/// level or ratio would count its runs twice or draw one block twice).
pub(crate) fn positive_list(flag: &str, text: &str) -> Result<Vec<f64>, BatchError> {
    let bad = |what: String| input(anyhow!("{flag} {text}: {what}"));
    let range = if let [from, to, n] = text.split(':').collect::<Vec<_>>()[..] {
        let (Ok(from), Ok(to), Ok(n)) = (
            from.trim().parse::<f64>(),
            to.trim().parse::<f64>(),
            n.trim().parse::<usize>(),
        ) else {
            return Err(bad(
                "expected FROM:TO:N (numbers, N an integer >= 1) or a comma list".into()
            ));
        };
        if to < from {
            return Err(bad(format!("TO = {} is below FROM = {}", show(to), show(from))));
        }
        if from == to && n > 1 {
            return Err(bad(format!(
                "FROM = TO = {} gives the same value {n} times; give N = 1 or a TO above FROM",
                show(from)
            )));
        }
        if n == 0 || n > MAX_LIST || (n == 1 && from != to) {
            return Err(bad(format!(
                "N = {n}: must be >= 2 (1 when FROM = TO) and at most {MAX_LIST}"
            )));
        }
        Some(
            (0..n)
                .map(|i| {
                    if i + 1 == n {
                        to
                    } else {
                        from + (to - from) * i as f64 / (n - 1).max(1) as f64
                    }
                })
                .collect::<Vec<f64>>(),
        )
    } else {
        None
    };
    let from_range = range.is_some();
    let values: Vec<f64> = match range {
        Some(values) => values,
        None => text
            .split(',')
            .map(|t| {
                t.trim()
                    .parse::<f64>()
                    .map_err(|_| bad(format!("{t:?} is not a number")))
            })
            .collect::<Result<_, _>>()?,
    };
    if values.is_empty() || values.len() > MAX_LIST {
        return Err(bad(format!("needs 1 to {MAX_LIST} values")));
    }
    if let Some(v) = values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(bad(format!(
            "{} is not > 0 (every value must be a finite number > 0)",
            show(*v)
        )));
    }
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    if let Some(w) = order.windows(2).find(|w| values[w[0]] == values[w[1]]) {
        let (i, j) = (w[0].min(w[1]), w[0].max(w[1]));
        return Err(bad(if from_range {
            format!(
                "values {} and {} are both {} (the step is below the numbers' resolution); give a smaller N",
                i + 1,
                j + 1,
                show(values[i])
            )
        } else {
            format!(
                "{} is given twice (values {} and {}); give each once",
                show(values[i]),
                i + 1,
                j + 1
            )
        }));
    }
    Ok(values)
}

/// Checks that `values` increase strictly (for grids), naming `flag`.
pub fn increasing(flag: &str, values: &[f64]) -> Result<(), BatchError> {
    match values.windows(2).find(|w| w[1] <= w[0]) {
        Some(w) => Err(input(anyhow!(
            "{flag}: values must increase ({} then {})",
            show(w[0]),
            show(w[1])
        ))),
        None => Ok(()),
    }
}

/// A block `BxH` in metres (`0.6x2.0`), both > 0.
pub fn block(flag: &str, text: &str) -> Result<(f64, f64), BatchError> {
    let parsed = text
        .split_once(['x', 'X', '×'])
        .and_then(|(b, h)| Some((b.trim().parse::<f64>().ok()?, h.trim().parse::<f64>().ok()?)));
    match parsed {
        Some((b, h)) if b > 0.0 && h > 0.0 && b.is_finite() && h.is_finite() => Ok((b, h)),
        _ => Err(input(anyhow!(
            "{flag} {text}: expected WIDTHxHEIGHT in metres, both > 0, e.g. 0.6x2.0"
        ))),
    }
}

/// `e` with its config key replaced by the flag the user typed, from
/// `flags` (`(key, flag)` pairs), the key kept in brackets:
/// `--pulse-period (excitation.omega_h): …`. A key with no flag is kept.
pub(crate) fn flag_error(e: &ScenarioError, flags: &[(&str, &str)]) -> String {
    match flags.iter().find(|(key, _)| e.key.starts_with(key)) {
        Some((_, flag)) => format!("{flag} ({}): {}", e.key, e.message),
        None => e.to_string(),
    }
}

/// One line saying the block stands on a floor, for the engineering
/// commands' printed answers, when the base scene has `[floor]`: the
/// levels and scales are the ground motion's, and the block feels it
/// filtered through the building.
pub(crate) fn floor_note(base: &Scenario) -> Option<String> {
    let floor = base.floor.as_ref()?;
    let modes: Vec<String> = floor
        .modes
        .iter()
        .map(|m| {
            format!(
                "T = {} s, ζ = {} %, Γφ = {}",
                show(m.period_s),
                show(100.0 * m.damping),
                show(m.participation)
            )
        })
        .collect();
    Some(format!(
        "on a floor ([floor]: {}): the levels and scales are the ground motion's, filtered through the building to the block",
        modes.join("; ")
    ))
}

/// Bad input.
pub fn input(e: impl Into<anyhow::Error>) -> BatchError {
    BatchError::Input(e.into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_ranges_and_blocks_parse_and_are_checked() {
        assert_eq!(positive_list("--levels", "0.1,0.2, 0.3").unwrap(), vec![0.1, 0.2, 0.3]);
        assert_eq!(positive_list("--levels", "0.5:1.5:3").unwrap(), vec![0.5, 1.0, 1.5]);
        for bad in [
            "0,0.1",
            "-0.1",
            "0.1,x",
            "1:0.5:3",
            "0.1:1:0",
            "",
            "0.1,0.2,0.1",
            "0.1:0.1:3",
        ] {
            let e = match positive_list("--levels", bad) {
                Err(BatchError::Input(e)) => e.to_string(),
                other => panic!("{bad}: {other:?}"),
            };
            assert!(e.starts_with("--levels"), "{e}");
        }
        assert_eq!(block("--block", "0.6x2.0").unwrap(), (0.6, 2.0));
        assert!(block("--block", "0.6").is_err());
        assert!(block("--block", "0x2").is_err());
        assert!(increasing("--b-over-h", &[0.1, 0.1]).is_err());
    }
}
