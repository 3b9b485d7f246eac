//! `rocking merge`: joins the shards of a sweep (`rocking sweep --shard K/N`)
//! into exactly the files a single run writes: the same `classes.csv`,
//! `points.csv` and `sweep.json` byte for byte (rows are copied verbatim in
//! value order), and the figures drawn from the same numbers.
//!
//! The shards must belong to one sweep: their `sweep.json` files must agree
//! in everything but the shard (configuration, parameter, grid, window,
//! classifier, version), and every shard 0 … N−1 must be given exactly once.
//! Each shard's files must be whole and unchanged: every row well formed
//! and finite (a broken one is named by its line), the shard's own values
//! in order, and the row count and CRC-32 its `sweep.json` recorded
//! (`files`). Any disagreement is bad input (exit 2) and nothing is written.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow, bail};
use serde_json::Value as Json;

use super::error::BatchError;
use super::sweep::SweepMeta;
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::orbit_diagram::{Continuation, Grid, Shard};
use crate::analysis::steady::Window;
use crate::io::config;
use crate::io::csv;
use crate::io::output;
use crate::io::sweep_files::{ClassRow, PointRow};

/// Arguments of `rocking merge`.
#[derive(Debug, Clone, clap::Args)]
pub struct MergeArgs {
    /// Output directory for the merged sweep.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The shard directories (any order).
    #[arg(value_name = "SHARD_DIR", required = true)]
    pub shards: Vec<PathBuf>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// One shard read from disk.
struct ShardDir {
    dir: PathBuf,
    shard: Shard,
    /// `sweep.json` with its `shard` entry set to null.
    common: Json,
    /// classes.csv rows with their lines.
    classes: Vec<(u64, ClassRow)>,
    /// points.csv rows with their lines, in file order.
    points: Vec<(u64, PointRow)>,
    /// `sweep.json`'s `files`: each file's rows and CRC-32.
    files: Json,
}

fn read_text(path: &Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| path.display().to_string())
}

/// A shard's JSON `file` in `dir`, written by `command` (`rocking
/// sweep`): the JSON with its `shard` entry taken out in place (left as
/// null, so that the rest is exactly the JSON of the whole study, key order
/// included) and that entry; `whole` says what a JSON without one is.
pub(super) fn shard_json(dir: &Path, file: &str, command: &str, whole: &str) -> anyhow::Result<(PathBuf, Json, Shard)> {
    let json_path = dir.join(file);
    let text = read_text(&json_path)?;
    let mut common: Json =
        serde_json::from_str(&text).with_context(|| format!("{}: not valid JSON", json_path.display()))?;
    if common.get("command").and_then(Json::as_str) != Some(command) {
        bail!("{}: not written by `{command}`", json_path.display());
    }
    let shard_value = common.get_mut("shard").map(Json::take).unwrap_or(Json::Null);
    if shard_value.is_null() {
        bail!("{}: not a shard ({file} has no shard; {whole})", dir.display());
    }
    let shard: Shard =
        serde_json::from_value(shard_value).with_context(|| format!("{}: bad \"shard\" entry", json_path.display()))?;
    Ok((json_path, common, shard))
}

fn read_shard(dir: &Path) -> anyhow::Result<ShardDir> {
    let (json_path, mut common, shard) = shard_json(dir, "sweep.json", "rocking sweep", "it is already a whole sweep")?;
    // The files' rows and checksums, written by the shard's run: removed
    // from the common part (a whole sweep has none) and checked here.
    let files = common.as_object_mut().and_then(|o| o.remove("files")).ok_or_else(|| {
        anyhow!(
            "{}: no \"files\" entry (rows and CRC-32 of the shard's files)",
            json_path.display()
        )
    })?;

    if shard.count == 0 || shard.index >= shard.count {
        bail!(
            "{}: shard {}/{} is out of range",
            json_path.display(),
            shard.index,
            shard.count
        );
    }
    Ok(ShardDir {
        dir: dir.to_path_buf(),
        shard,
        common,
        classes: csv::read(&dir.join("classes.csv"))?,
        points: csv::read(&dir.join("points.csv"))?,
        files,
    })
}

/// Checks shard file `name` in `dir` against its entry in `files` (from
/// `sweep.json`): the same number of data rows and the same CRC-32.
pub(super) fn check_file(dir: &Path, name: &str, files: &Json, json_path: &Path) -> anyhow::Result<()> {
    let path = dir.join(name);
    let bytes = std::fs::read(&path).with_context(|| path.display().to_string())?;
    let entry = files.get(name);
    let rows = entry.and_then(|e| e.get("rows")).and_then(Json::as_u64);
    let crc = entry.and_then(|e| e.get("crc32")).and_then(Json::as_str);
    let (Some(rows), Some(crc)) = (rows, crc) else {
        bail!("{}: files.{name} lacks its rows or crc32", json_path.display());
    };
    let found_rows = String::from_utf8_lossy(&bytes).lines().count().saturating_sub(1) as u64;
    if found_rows != rows {
        bail!(
            "{}: {found_rows} rows, but the shard wrote {rows} (the file was cut or changed)",
            path.display()
        );
    }
    let found = format!("{:08x}", crc32fast::hash(&bytes));
    if found != crc {
        bail!(
            "{}: CRC-32 {found}, but the shard wrote {crc} (the file changed since)",
            path.display()
        );
    }
    Ok(())
}

/// The first top-level key whose value differs between two JSON objects.
fn first_difference(a: &Json, b: &Json) -> String {
    let (Some(a), Some(b)) = (a.as_object(), b.as_object()) else {
        return "(whole file)".into();
    };
    a.keys()
        .chain(b.keys())
        .find(|k| a.get(*k) != b.get(*k))
        .cloned()
        .unwrap_or_default()
}

/// Reads the sweep settings back from the common part of `sweep.json`.
fn meta_of(common: &Json, json_path: &Path) -> anyhow::Result<SweepMeta> {
    let field = |k: &str| {
        common
            .get(k)
            .cloned()
            .ok_or_else(|| anyhow!("{}: missing \"{k}\"", json_path.display()))
    };
    let key: String = serde_json::from_value(field("param")?)?;
    let param = config::param(&key).map_err(|e| anyhow!("{}: param {e}", json_path.display()))?;
    let g = field("grid")?;
    let num = |v: &Json, k: &str| {
        v.get(k)
            .and_then(Json::as_f64)
            .ok_or_else(|| anyhow!("{}: missing grid.{k}", json_path.display()))
    };
    let grid = Grid::new(num(&g, "from")?, num(&g, "to")?, num(&g, "step")?)
        .map_err(|e| anyhow!("{}: {}", json_path.display(), e.render(&super::flags::Flags)))?;
    if g.get("count").and_then(Json::as_u64) != Some(grid.count as u64) {
        bail!("{}: grid.count disagrees with from/to/step", json_path.display());
    }
    let continuation = match field("continuation")?.as_str() {
        Some("none") => Continuation::None,
        other => bail!(
            "{}: continuation {other:?}: only sweeps without continuation can be sharded",
            json_path.display()
        ),
    };
    let w = field("window")?;
    let window = Window {
        transient: num(&w, "transient")?,
        tau_end: num(&w, "tau_end")?,
    };
    let c = field("classify")?;
    let classify = ClassifyOptions {
        k_max: c.get("k_max").and_then(Json::as_u64).unwrap_or(0) as u32,
        rel_tol: num(&c, "rel_tol")?,
        abs_tol: num(&c, "abs_tol")?,
        min_rotation_fraction: num(&c, "min_rotation_fraction")?,
        max_tour_ratio: num(&c, "max_tour_ratio")?,
        lyapunov_threshold: num(&c, "lyapunov_threshold")?,
    };
    let (table, source) = config::read_file(json_path)?;
    let config = config::from_table(&table, &source)?;
    Ok(SweepMeta {
        param,
        grid,
        continuation,
        window,
        classify,
        config,
    })
}

/// `path` made absolute with its symbolic links resolved, as far as it
/// exists (a folder not yet made keeps its remaining components).
fn resolved(path: &Path) -> PathBuf {
    let mut existing = path.to_path_buf();
    let mut rest = Vec::new();
    while !existing.as_os_str().is_empty() && std::fs::canonicalize(&existing).is_err() {
        if let Some(name) = existing.file_name() {
            rest.push(name.to_os_string());
        }
        existing = existing.parent().map(Path::to_path_buf).unwrap_or_default();
    }
    let base = if existing.as_os_str().is_empty() {
        std::env::current_dir().unwrap_or_default()
    } else {
        std::fs::canonicalize(&existing).unwrap_or(existing)
    };
    rest.into_iter().rev().fold(base, |p, c| p.join(c))
}

/// Whether folder `out` is `shard` or contains it (writing `out` would
/// replace the shard being read).
pub(super) fn contains(out: &Path, shard: &Path) -> bool {
    resolved(shard).starts_with(resolved(out))
}

/// The shards `args` names, each read by `read`, once an `--out` among
/// them is refused.
pub(super) fn read_shards<T>(
    args: &MergeArgs,
    read: impl Fn(&Path) -> anyhow::Result<T>,
) -> Result<Vec<T>, BatchError> {
    refuse_out_in_shards(args)?;
    args.shards
        .iter()
        .map(|d| read(d))
        .collect::<anyhow::Result<_>>()
        .map_err(BatchError::Input)
}

/// Refuses an `--out` that is or contains a shard being merged (writing it
/// would replace what is read).
fn refuse_out_in_shards(args: &MergeArgs) -> Result<(), BatchError> {
    match args.shards.iter().find(|s| contains(&args.out, s)) {
        Some(shard) => Err(BatchError::Input(anyhow!(
            "--out {}: is or contains the shard {} being merged; write the merge elsewhere",
            args.out.display(),
            shard.display()
        ))),
        None => Ok(()),
    }
}

/// The shards `0/N … N−1/N` of one study, each given once, by index
/// (every entry `Some`); `place` gives a shard's folder, `K/N` and its
/// JSON without the shard (the same for every shard of one study), and
/// `differs(s, first)` words why shard `s` is of another study than the
/// first. At least one shard is given.
pub(super) fn in_index_order<T>(
    shards: &[T],
    place: impl Fn(&T) -> (&PathBuf, Shard, &Json),
    differs: impl Fn(&T, &T) -> String,
) -> Result<Vec<Option<&T>>, BatchError> {
    let input = BatchError::Input;
    let Some(first) = shards.first() else {
        return Err(input(anyhow!("no shard directories given")));
    };
    let (first_dir, first_shard, first_common) = place(first);
    let n = first_shard.count;
    for s in &shards[1..] {
        let (dir, shard, common) = place(s);
        if common != first_common {
            return Err(input(anyhow!(differs(s, first))));
        }
        if shard.count != n {
            return Err(input(anyhow!(
                "{}: shard {}/{} but {} is one of {n} shards",
                dir.display(),
                shard.index,
                shard.count,
                first_dir.display()
            )));
        }
    }
    let mut by_index: Vec<Option<&T>> = vec![None; n];
    for s in shards {
        let (dir, shard, _) = place(s);
        if let Some(other) = by_index[shard.index] {
            return Err(input(anyhow!(
                "{}: shard {}/{n} is given twice (also {})",
                dir.display(),
                shard.index,
                place(other).0.display()
            )));
        }
        by_index[shard.index] = Some(s);
    }
    if let Some(missing) = by_index.iter().position(Option::is_none) {
        return Err(input(anyhow!("shard {missing}/{n} is missing")));
    }
    Ok(by_index)
}

/// Runs `rocking merge`.
pub fn run(args: &MergeArgs) -> Result<(), BatchError> {
    let input = BatchError::Input;
    let shards = read_shards(args, read_shard)?;
    let by_index = in_index_order(
        &shards,
        |s| (&s.dir, s.shard, &s.common),
        |s, first| {
            format!(
                "{}: not the same sweep as {} (sweep.json differs in \"{}\")",
                s.dir.display(),
                first.dir.display(),
                first_difference(&s.common, &first.common)
            )
        },
    )?;
    let (first, n) = (&shards[0], shards[0].shard.count);
    let meta = meta_of(&first.common, &first.dir.join("sweep.json")).map_err(input)?;
    let grid = meta.grid;

    // Each shard's classes rows must be exactly its values, in order; its
    // points rows must come in blocks of those values, in the same order.
    let mut class_rows: Vec<&ClassRow> = Vec::with_capacity(grid.count);
    let mut point_rows: Vec<&PointRow> = Vec::new();
    let mut class_pos = vec![0usize; n];
    let mut point_pos = vec![0usize; n];
    let mut values: Vec<(f64, Response)> = Vec::with_capacity(grid.count);
    let mut points: Vec<(f64, f64)> = Vec::new();
    for i in 0..grid.count {
        let k = i % n;
        let Some(s) = by_index[k] else {
            return Err(input(anyhow!("shard {k}/{n} is missing")));
        };
        let expected = grid.value(i);
        let classes_path = s.dir.join("classes.csv");
        let Some((line, row)) = s.classes.get(class_pos[k]) else {
            return Err(input(anyhow!(
                "{}: ends before value {expected:?}",
                classes_path.display()
            )));
        };
        if row.value.0.to_bits() != expected.to_bits() {
            return Err(input(anyhow!(
                "{}:{line}: value {:?} where the sweep has {expected:?}",
                classes_path.display(),
                row.value.0
            )));
        }
        let response = Response::from_name(&row.outcome, row.period)
            .ok_or_else(|| {
                anyhow!(
                    "{}:{line}: unknown outcome {:?} (period {:?})",
                    classes_path.display(),
                    row.outcome,
                    row.period
                )
            })
            .map_err(input)?;
        class_pos[k] += 1;
        class_rows.push(row);
        values.push((expected, response));
        while let Some((_, p)) = s
            .points
            .get(point_pos[k])
            .filter(|(_, p)| p.value.0.to_bits() == expected.to_bits())
        {
            points.push((expected, p.theta.0));
            point_rows.push(p);
            point_pos[k] += 1;
        }
    }
    for s in &shards {
        let k = s.shard.index;
        if let Some((line, _)) = s.classes.get(class_pos[k]) {
            return Err(input(anyhow!(
                "{}:{line}: a row beyond the shard's values",
                s.dir.join("classes.csv").display()
            )));
        }
        if let Some((line, _)) = s.points.get(point_pos[k]) {
            return Err(input(anyhow!(
                "{}:{line}: a point whose value is not the shard's, or out of order",
                s.dir.join("points.csv").display()
            )));
        }
    }
    // After the rows (a wrong row is named by its line): the counts and
    // checksums, which catch a file cut at a row boundary or changed.
    for s in &shards {
        for name in ["classes.csv", "points.csv"] {
            check_file(&s.dir, name, &s.files, &s.dir.join("sweep.json")).map_err(input)?;
        }
    }
    let classes_out = csv::to_string(class_rows.into_iter().cloned());
    let points_out = csv::to_string(point_rows.into_iter().cloned());

    output::check_writable(&args.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(input)?;
    super::write::staged(&args.out, |staging| {
        staging.text("classes.csv", &classes_out)?;
        staging.text("points.csv", &points_out)?;
        staging.text("sweep.json", &(serde_json::to_string_pretty(&first.common)? + "\n"))?;
        let fig = meta.figure(&values, &points);
        super::write::figure(staging, "bifurcation", &fig)?;
        Ok(())
    })?;
    if !args.quiet {
        crate::say!(
            "merged {n} shards: {} values, {} points; wrote {}",
            values.len(),
            points.len(),
            args.out.display()
        );
    }
    Ok(())
}
