//! What the engineering commands (`spectrum`, `pulse-map`, `fragility`)
//! share on the command line: the base scene with its friction, reading a
//! record with its unit, and number lists. Every error names the flag (or
//! the file and line) and is bad input (exit 2).

use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow};

use super::args::SceneArgs;
use super::batch::BatchError;
use crate::io::config;
use crate::io::record::{RecordError, RecordSpec, read_record_as};
use crate::model::units::AccelUnit;
use crate::sim::Scenario;
use crate::sim::scenario::Record;

/// Most values of one list flag.
pub const MAX_LIST: usize = 100_000;

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

impl BaseArgs {
    /// The base scenario, validated.
    pub fn load(&self) -> Result<Scenario, BatchError> {
        let mut base = if self.scene.preset.is_none() && self.scene.config.is_none() {
            let (table, source) = config::base_table(&self.scene.sets).map_err(input)?;
            config::from_table(&table, &source).map_err(input)?
        } else {
            self.scene.load().map_err(input)?
        };
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
}

impl RecordUnitArgs {
    /// The reading spec, or an error naming --unit.
    pub fn spec(&self) -> Result<RecordSpec, BatchError> {
        let unit = match &self.unit {
            None => None,
            Some(text) => Some(
                AccelUnit::parse(text)
                    .ok_or_else(|| input(anyhow!("--unit {text}: unknown unit (known: g, m/s2, cm/s2)")))?,
            ),
        };
        Ok(RecordSpec { unit, dt: self.dt })
    }
}

/// Reads the record at `path` with `spec`; a missing unit names --unit, a
/// missing step --dt, anything else the file and line.
pub fn read_record(path: &Path, spec: &RecordSpec) -> anyhow::Result<Record> {
    let loaded = read_record_as(path, spec).map_err(|e| match e {
        RecordError::NoUnit { .. } | RecordError::HeaderNoUnit { .. } => {
            anyhow!("{e} (give the unit with --unit g|m/s2|cm/s2)")
        }
        RecordError::NoStep { .. } | RecordError::StatedStep { .. } => anyhow!("{e} (--dt)"),
        other => anyhow!(other),
    })?;
    Ok(Record {
        path: path.to_path_buf(),
        series: loaded.series,
        unit: loaded.unit,
        dt: spec.dt,
        crc32: loaded.crc32,
    })
}

/// A list flag's values: `a,b,c` or `FROM:TO:N` (N evenly spaced values,
/// both ends included), each finite and > 0.
pub fn positive_list(flag: &str, text: &str) -> Result<Vec<f64>, BatchError> {
    let bad = |what: String| input(anyhow!("{flag} {text}: {what}"));
    let values: Vec<f64> = if let [from, to, n] = text.split(':').collect::<Vec<_>>()[..] {
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
            return Err(bad(format!("TO = {to} is below FROM = {from}")));
        }
        if n == 0 || n > MAX_LIST || (n == 1 && from != to) {
            return Err(bad(format!(
                "N = {n}: must be >= 2 (1 when FROM = TO) and at most {MAX_LIST}"
            )));
        }
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    to
                } else {
                    from + (to - from) * i as f64 / (n - 1).max(1) as f64
                }
            })
            .collect()
    } else {
        text.split(',')
            .map(|t| {
                t.trim()
                    .parse::<f64>()
                    .map_err(|_| bad(format!("{t:?} is not a number")))
            })
            .collect::<Result<_, _>>()?
    };
    if values.is_empty() || values.len() > MAX_LIST {
        return Err(bad(format!("needs 1 to {MAX_LIST} values")));
    }
    if let Some(v) = values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(bad(format!("{v} is not > 0 (every value must be a finite number > 0)")));
    }
    Ok(values)
}

/// Checks that `values` increase strictly (for grids), naming `flag`.
pub fn increasing(flag: &str, values: &[f64]) -> Result<(), BatchError> {
    match values.windows(2).find(|w| w[1] <= w[0]) {
        Some(w) => Err(input(anyhow!("{flag}: values must increase ({} then {})", w[0], w[1]))),
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

/// One record of a suite: its file, how to read it, and where it was
/// named (`LIST:LINE` for a suite list, else `None`).
pub type SuiteEntry = (PathBuf, RecordSpec, Option<String>);

/// The record files named by `files` (each a file, or a folder whose
/// regular files are taken in name order) and by the suite list `suite`
/// (one record per line, `PATH [UNIT]`, `#` comments, paths relative to
/// the list's folder), each with its reading spec; errors name the flag or
/// the list's file and line.
pub fn suite(files: &[PathBuf], suite: Option<&Path>, spec: RecordSpec) -> Result<Vec<SuiteEntry>, BatchError> {
    let mut out = Vec::new();
    for f in files {
        if f.is_dir() {
            let mut entries: Vec<PathBuf> = std::fs::read_dir(f)
                .with_context(|| format!("--records {}", f.display()))
                .map_err(input)?
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.is_file() && !p.file_name().is_some_and(|n| n.to_string_lossy().starts_with('.')))
                .collect();
            entries.sort();
            if entries.is_empty() {
                return Err(input(anyhow!("--records {}: the folder holds no files", f.display())));
            }
            out.extend(entries.into_iter().map(|p| (p, spec, None)));
        } else {
            out.push((f.clone(), spec, None));
        }
    }
    if let Some(list) = suite {
        let text = std::fs::read_to_string(list)
            .with_context(|| format!("--suite {}", list.display()))
            .map_err(input)?;
        let dir = list.parent().unwrap_or(Path::new("."));
        for (i, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let mut fields = line.split_whitespace();
            let (Some(path), unit, None) = (fields.next(), fields.next(), fields.next()) else {
                return Err(input(anyhow!(
                    "{}:{}: expected `PATH [UNIT]`, found {line:?}",
                    list.display(),
                    i + 1
                )));
            };
            let mut s = spec;
            if let Some(u) = unit {
                s.unit = Some(AccelUnit::parse(u).ok_or_else(|| {
                    input(anyhow!(
                        "{}:{}: unknown unit {u:?} (known: g, m/s2, cm/s2)",
                        list.display(),
                        i + 1
                    ))
                })?);
            }
            let p = PathBuf::from(path);
            out.push((
                if p.is_absolute() { p } else { dir.join(p) },
                s,
                Some(format!("{}:{}", list.display(), i + 1)),
            ));
        }
    }
    if out.is_empty() {
        return Err(input(anyhow!(
            "--records: give the records with --records FILE|DIR (repeatable) or --suite LIST"
        )));
    }
    Ok(out)
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
        for bad in ["0,0.1", "-0.1", "0.1,x", "1:0.5:3", "0.1:1:0", ""] {
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
