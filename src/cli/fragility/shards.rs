//! `rocking merge` of fragility shards: each shard's rows and layout read
//! back, checked to belong together, and written as one run writes them.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow, bail};
use serde_json::Value as Json;

use super::Layout;
use super::write::write_whole;
use crate::analysis::engineering::fragility::Intensity;
use crate::analysis::engineering::{BlockSize, EndState};
use crate::analysis::orbit_diagram::Shard;
use crate::cli::eng_args::input;
use crate::cli::error::BatchError;
use crate::cli::merge::MergeArgs;
use crate::io::csv;
use crate::io::engineering_files::FragilityRunRow;
use crate::io::output;

/// Whether `dirs` are fragility shards (the first holds a
/// `fragility.json`): `rocking merge` then joins them with [`merge`].
pub(crate) fn are_fragility_shards(dirs: &[PathBuf]) -> bool {
    dirs.first().is_some_and(|d| d.join("fragility.json").is_file())
}

/// One shard read back.
struct ShardDir {
    dir: PathBuf,
    shard: Shard,
    /// `fragility.json` without its `shard` (left null) and `files`.
    common: Json,
    rows: Vec<(u64, FragilityRunRow)>,
    /// `fragility.json`'s `files`: the rows and CRC-32 of `runs.csv`.
    files: Json,
}

fn read_shard(dir: &Path) -> anyhow::Result<ShardDir> {
    let (path, mut common, shard) =
        crate::cli::merge::shard_json(dir, "fragility.json", "rocking fragility", "it is a whole study")?;
    if shard.count == 0 || shard.index >= shard.count {
        bail!(
            "{}: shard {}/{} is out of range",
            path.display(),
            shard.index,
            shard.count
        );
    }
    // Shards of versions before these checks have none: their runs cannot
    // be told from edited ones, so they are not merged.
    let files = common.as_object_mut().and_then(|o| o.remove("files")).ok_or_else(|| {
        anyhow!(
            "{}: no \"files\" entry (rows and CRC-32 of runs.csv), so an edited runs.csv cannot be noticed; recompute the shard with this version",
            path.display()
        )
    })?;
    Ok(ShardDir {
        dir: dir.to_path_buf(),
        shard,
        common,
        rows: csv::read(&dir.join("runs.csv"))?,
        files,
    })
}

/// The layout recorded in a shard's `fragility.json`.
fn layout_of(common: &Json, path: &Path) -> anyhow::Result<Layout> {
    let field = |k: &str| {
        common
            .get(k)
            .ok_or_else(|| anyhow!("{}: missing \"{k}\"", path.display()))
    };
    let im: Intensity =
        serde_json::from_value(field("im")?.clone()).with_context(|| format!("{}: im", path.display()))?;
    let levels: Vec<f64> =
        serde_json::from_value(field("levels")?.clone()).with_context(|| format!("{}: levels", path.display()))?;
    let blocks: Vec<BlockSize> = field("blocks")?
        .as_array()
        .ok_or_else(|| anyhow!("{}: blocks is not a list", path.display()))?
        .iter()
        .map(|b| {
            Some(BlockSize {
                width_m: b.get("width_m")?.as_f64()?,
                height_m: b.get("height_m")?.as_f64()?,
            })
        })
        .collect::<Option<_>>()
        .ok_or_else(|| anyhow!("{}: bad blocks", path.display()))?;
    let records = field("records")?
        .as_array()
        .ok_or_else(|| anyhow!("{}: records is not a list", path.display()))?
        .len();
    let threshold = field("threshold_theta_over_alpha")?
        .as_f64()
        .ok_or_else(|| anyhow!("{}: bad threshold_theta_over_alpha", path.display()))?;
    let friction = field("friction")?.as_str().unwrap_or_default().to_string();
    let overturn_at = field("config")?
        .pointer("/run/tumble_theta")
        .and_then(Json::as_f64)
        .ok_or_else(|| anyhow!("{}: config has no run.tumble_theta", path.display()))?;
    let sa_period = common.get("sa_period_s").and_then(Json::as_f64);
    let vertical = common.get("vertical").and_then(Json::as_str) == Some("record");
    let stack = field("config")?.get("stack").and_then(Json::as_array).map(Vec::len);
    let layout = Layout {
        im,
        levels,
        blocks,
        records,
        threshold,
        friction,
        overturn_at,
        sa_period,
        vertical,
        stack,
    };
    if field("runs")?.as_u64() != Some(layout.runs() as u64) {
        bail!("{}: runs disagrees with blocks × levels × records", path.display());
    }
    Ok(layout)
}

/// `rocking merge` of fragility shards: checks that they are the shards
/// 0 … N−1 of one study, each once, with exactly their runs, and writes
/// the files one run writes.
pub fn merge(args: &MergeArgs) -> Result<(), BatchError> {
    let shards = crate::cli::merge::read_shards(args, read_shard)?;
    let by_index = crate::cli::merge::in_index_order(
        &shards,
        |s| (&s.dir, s.shard, &s.common),
        |s, first| {
            format!(
                "{}: not the same study as {} (fragility.json differs)",
                s.dir.display(),
                first.dir.display()
            )
        },
    )?;
    let (first, n) = (&shards[0], shards[0].shard.count);
    let layout = layout_of(&first.common, &first.dir.join("fragility.json")).map_err(input)?;
    let total = layout.runs();
    let mut rows: Vec<FragilityRunRow> = Vec::with_capacity(total);
    let mut pos = vec![0usize; n];
    for i in 0..total {
        let k = i % n;
        let Some(s) = by_index[k] else {
            return Err(input(anyhow!("shard {k}/{n} is missing")));
        };
        let path = s.dir.join("runs.csv");
        let Some((line, row)) = s.rows.get(pos[k]) else {
            return Err(input(anyhow!("{}: ends before run {i}", path.display())));
        };
        if row.run != i as u64 {
            return Err(input(anyhow!(
                "{}:{line}: run {} where the shard has run {i}",
                path.display(),
                row.run
            )));
        }
        if EndState::from_name(&row.end).is_none() {
            return Err(input(anyhow!("{}:{line}: unknown end {:?}", path.display(), row.end)));
        }
        pos[k] += 1;
        rows.push(row.clone());
    }
    for s in &shards {
        if let Some((line, _)) = s.rows.get(pos[s.shard.index]) {
            return Err(input(anyhow!(
                "{}:{line}: a row beyond the shard's runs",
                s.dir.join("runs.csv").display()
            )));
        }
    }
    // After the rows (a wrong row is named by its line): the count and
    // checksum, which catch a well-formed row edited by hand.
    for s in &shards {
        crate::cli::merge::check_file(&s.dir, "runs.csv", &s.files, &s.dir.join("fragility.json")).map_err(input)?;
    }
    output::check_writable(&args.out)
        .context("--out: cannot write the output directory")
        .map_err(input)?;
    let mut common = first.common.clone();
    common["shard"] = Json::Null;
    let lines = write_whole(&args.out, common, &layout, rows)?;
    if !args.quiet {
        crate::say!("merged {n} fragility shards: {total} runs");
        for l in lines {
            crate::say!("  {l}");
        }
        crate::say!("wrote {}", args.out.display());
    }
    Ok(())
}
