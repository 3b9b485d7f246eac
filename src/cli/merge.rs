//! `rocking merge`: joins the shards of a sweep (`rocking sweep --shard K/N`)
//! into exactly the files a single run writes: the same `classes.csv`,
//! `points.csv` and `sweep.json` byte for byte (rows are copied verbatim in
//! value order), and the figures drawn from the same numbers.
//!
//! The shards must belong to one sweep: their `sweep.json` files must agree
//! in everything but the shard (configuration, parameter, grid, window,
//! classifier, version), and every shard 0 … N−1 must be given exactly once.
//! Any disagreement is bad input (exit 2) and nothing is written.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow, bail};
use serde_json::Value as Json;

use super::batch::BatchError;
use super::sweep::{CLASSES_HEADER, POINTS_HEADER, SweepMeta};
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::orbit_diagram::{Continuation, Grid, Shard};
use crate::analysis::steady::Window;
use crate::io::config;
use crate::io::output;
use crate::io::staging::Staging;
use crate::plot::Figure as _;

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
    /// classes.csv rows (no header, no newline).
    classes: Vec<String>,
    /// points.csv rows (no header, no newline), in file order.
    points: Vec<String>,
}

fn read_text(path: &Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| path.display().to_string())
}

/// The rows of a CSV after checking its header.
fn rows(path: &Path, header: &str) -> anyhow::Result<Vec<String>> {
    let text = read_text(path)?;
    let mut lines = text.lines();
    match lines.next() {
        Some(h) if h == header => {}
        _ => bail!("{}:1: expected the header `{header}`", path.display()),
    }
    Ok(lines.map(str::to_string).collect())
}

fn read_shard(dir: &Path) -> anyhow::Result<ShardDir> {
    let json_path = dir.join("sweep.json");
    let text = read_text(&json_path)?;
    let mut common: Json =
        serde_json::from_str(&text).with_context(|| format!("{}: not valid JSON", json_path.display()))?;
    if common.get("command").and_then(Json::as_str) != Some("rocking sweep") {
        bail!("{}: not written by `rocking sweep`", json_path.display());
    }
    // Taken out in place (left as null), so that the common part is exactly
    // the `sweep.json` of the whole sweep, key order included.
    let shard_value = common.get_mut("shard").map(Json::take).unwrap_or(Json::Null);
    if shard_value.is_null() {
        bail!(
            "{}: not a shard (sweep.json has no shard; it is already a whole sweep)",
            dir.display()
        );
    }
    let shard: Shard =
        serde_json::from_value(shard_value).with_context(|| format!("{}: bad \"shard\" entry", json_path.display()))?;
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
        classes: rows(&dir.join("classes.csv"), CLASSES_HEADER)?,
        points: rows(&dir.join("points.csv"), POINTS_HEADER)?,
    })
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
        .map_err(|e| anyhow!("{}: {e}", json_path.display()))?;
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

/// The value cell (first field) of a CSV row.
fn value_cell(row: &str) -> &str {
    row.split(',').next().unwrap_or("")
}

/// Runs `rocking merge`.
pub fn run(args: &MergeArgs) -> Result<(), BatchError> {
    let input = BatchError::Input;
    let shards: Vec<ShardDir> = args
        .shards
        .iter()
        .map(|d| read_shard(d))
        .collect::<anyhow::Result<_>>()
        .map_err(input)?;
    let Some(first) = shards.first() else {
        return Err(input(anyhow!("no shard directories given")));
    };
    let n = first.shard.count;
    for s in &shards[1..] {
        if s.common != first.common {
            return Err(input(anyhow!(
                "{}: not the same sweep as {} (sweep.json differs in \"{}\")",
                s.dir.display(),
                first.dir.display(),
                first_difference(&s.common, &first.common)
            )));
        }
        if s.shard.count != n {
            return Err(input(anyhow!(
                "{}: shard {}/{} but {} is one of {n} shards",
                s.dir.display(),
                s.shard.index,
                s.shard.count,
                first.dir.display()
            )));
        }
    }
    let mut by_index: Vec<Option<&ShardDir>> = vec![None; n];
    for s in &shards {
        if let Some(other) = by_index[s.shard.index] {
            return Err(input(anyhow!(
                "{}: shard {}/{n} is given twice (also {})",
                s.dir.display(),
                s.shard.index,
                other.dir.display()
            )));
        }
        by_index[s.shard.index] = Some(s);
    }
    if let Some(missing) = by_index.iter().position(Option::is_none) {
        return Err(input(anyhow!("shard {missing}/{n} is missing")));
    }
    let meta = meta_of(&first.common, &first.dir.join("sweep.json")).map_err(input)?;
    let grid = meta.grid;

    // Each shard's classes rows must be exactly its values, in order; its
    // points rows must come in blocks of those values, in the same order.
    let mut classes_out = format!("{CLASSES_HEADER}\n");
    let mut points_out = format!("{POINTS_HEADER}\n");
    let mut class_pos = vec![0usize; n];
    let mut point_pos = vec![0usize; n];
    let mut values: Vec<(f64, Response)> = Vec::with_capacity(grid.count);
    let mut points: Vec<(f64, f64)> = Vec::new();
    for i in 0..grid.count {
        let k = i % n;
        let Some(s) = by_index[k] else {
            return Err(input(anyhow!("shard {k}/{n} is missing")));
        };
        let expected = format!("{:?}", grid.value(i));
        let classes_path = s.dir.join("classes.csv");
        let Some(row) = s.classes.get(class_pos[k]) else {
            return Err(input(anyhow!(
                "{}: ends before value {expected} (row {})",
                classes_path.display(),
                class_pos[k] + 2
            )));
        };
        if value_cell(row) != expected {
            return Err(input(anyhow!(
                "{}:{}: value {} where the sweep has {expected}",
                classes_path.display(),
                class_pos[k] + 2,
                value_cell(row)
            )));
        }
        let fields: Vec<&str> = row.split(',').collect();
        let response = match fields.as_slice() {
            [_, outcome, period, _, _] => {
                let period = if period.is_empty() { None } else { period.parse().ok() };
                Response::from_name(outcome, period)
            }
            _ => None,
        }
        .ok_or_else(|| {
            anyhow!(
                "{}:{}: expected `{CLASSES_HEADER}`",
                classes_path.display(),
                class_pos[k] + 2
            )
        })
        .map_err(input)?;
        class_pos[k] += 1;
        classes_out.push_str(row);
        classes_out.push('\n');
        values.push((grid.value(i), response));
        while let Some(p) = s.points.get(point_pos[k]).filter(|p| value_cell(p) == expected) {
            let theta = p
                .split(',')
                .nth(3)
                .and_then(|t| t.parse::<f64>().ok())
                .ok_or_else(|| {
                    anyhow!(
                        "{}:{}: expected `{POINTS_HEADER}`",
                        s.dir.join("points.csv").display(),
                        point_pos[k] + 2
                    )
                })
                .map_err(input)?;
            points.push((grid.value(i), theta));
            points_out.push_str(p);
            points_out.push('\n');
            point_pos[k] += 1;
        }
    }
    for s in &shards {
        let k = s.shard.index;
        if class_pos[k] != s.classes.len() {
            return Err(input(anyhow!(
                "{}:{}: a row beyond the shard's values",
                s.dir.join("classes.csv").display(),
                class_pos[k] + 2
            )));
        }
        if point_pos[k] != s.points.len() {
            return Err(input(anyhow!(
                "{}:{}: a point whose value is not the shard's, or out of order",
                s.dir.join("points.csv").display(),
                point_pos[k] + 2
            )));
        }
    }

    output::check_writable(&args.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(input)?;
    let mut staging = Staging::new(&args.out).context("--out").map_err(BatchError::Run)?;
    let write = |staging: &mut Staging| -> anyhow::Result<()> {
        staging.text("classes.csv", &classes_out)?;
        staging.text("points.csv", &points_out)?;
        staging.text("sweep.json", &(serde_json::to_string_pretty(&first.common)? + "\n"))?;
        let fig = meta.figure(&values, &points);
        fig.write_png(&staging.path("bifurcation.png"))?;
        staging.text("bifurcation.svg", &fig.to_svg()?)?;
        Ok(())
    };
    write(&mut staging)
        .and_then(|()| Ok(staging.commit()?))
        .with_context(|| format!("writing {}", args.out.display()))
        .map_err(BatchError::Run)?;
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
