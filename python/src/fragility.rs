//! `fragility`: the runs of `rocking fragility` (blocks × intensity levels ×
//! records, each record scaled to the level) and the lognormal fits of
//! each block, over the library's `analysis::engineering::fragility`.
//!
//! The runs are indexed as the CLI indexes them (block outer, level,
//! record inner), so any subset (a Dask chunk, a CLI shard) computes the
//! same rows; the fits are computed from all rows at the end.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::analysis::engineering::fragility::{
    FragilityCheckError, FragilitySpec, Intensity, SuiteRecord, fit_block, run_fragility, summarise,
};
use rocking::analysis::engineering::lognormal::{FitError, LognormalFit};
use rocking::analysis::engineering::request::{self, RequestError};
use rocking::analysis::engineering::{BlockSize, Drive, EndState};
use rocking::analysis::field::RequestField;
use rocking::analysis::silent;
use rocking::io::record::{RecordSpec, read_record_as};
use rocking::sim::scenario::Record;
use serde_json::json;

use crate::convert::json_to_py;
use crate::errors::{Origin, config_error, record_error, run_error};
use crate::names::Keywords;
use crate::scene::Scene;
use crate::study::{Workers, checkpoint};

/// Bad input without a key.
fn input(message: impl std::fmt::Display) -> PyErr {
    config_error(message.to_string(), Origin::default())
}

/// A request the core refuses, in the words of the keywords.
fn refused(e: RequestError) -> PyErr {
    input(e.render(&Keywords))
}

/// The intensity measure named `im`.
fn intensity(im: &str) -> PyResult<Intensity> {
    match im {
        "pga" => Ok(Intensity::Pga),
        "pgv" => Ok(Intensity::Pgv),
        "pga-tan-alpha" => Ok(Intensity::PgaTanAlpha),
        "pgv-p-tan-alpha" => Ok(Intensity::PgvPTanAlpha),
        "sa" => Ok(Intensity::Sa),
        other => Err(input(format!(
            "im={other}: expected pga, pgv, pga-tan-alpha, pgv-p-tan-alpha or sa"
        ))),
    }
}

/// A record as Python gives it: (path, unit, vertical path, vertical
/// unit), the optional parts `None`.
pub type RecordArg = (PathBuf, Option<String>, Option<PathBuf>, Option<String>);

/// Reads one component in its unit (text files need one; an AT2 header
/// states its own).
fn component(path: &Path, unit: Option<&str>) -> PyResult<Record> {
    let unit = unit
        .map(|text| request::unit(RequestField::Unit, text))
        .transpose()
        .map_err(refused)?;
    let spec = RecordSpec {
        unit,
        dt: None,
        channel: None,
    };
    let loaded = read_record_as(path, &spec).map_err(|e| record_error(path, &e))?;
    Ok(Record {
        path: path.to_path_buf(),
        series: loaded.series,
        unit: loaded.unit,
        dt: None,
        crc32: loaded.crc32,
        channel: None,
    })
}

/// Whether the study applies the verticals: `vertical` as given ("none",
/// "record"), else when every record names one; a suite naming verticals
/// for some records only must say which study it means (as the CLI).
fn vertical_choice(vertical: Option<&str>, records: &[RecordArg]) -> PyResult<bool> {
    let lacking = records.iter().position(|r| r.2.is_none());
    let named = records.iter().position(|r| r.2.is_some());
    match (vertical, lacking, named) {
        (Some("none"), _, _) => Ok(false),
        (Some("record"), Some(i), _) => Err(input(format!(
            "vertical=\"record\": records[{i}] names no vertical component (give (path, unit, vertical_path, vertical_unit))"
        ))),
        (Some("record"), None, _) | (None, None, _) => Ok(true),
        (None, Some(_), None) => Ok(false),
        (None, Some(i), Some(j)) => Err(input(format!(
            "records[{j}] names a vertical component but records[{i}] does not; complete the suite, or give vertical=\"none\" to run horizontals only"
        ))),
        (Some(other), _, _) => Err(input(format!("vertical={other:?}: expected \"none\" or \"record\""))),
    }
}

/// Reads the suite: each record in its unit, with its vertical when
/// `with_vertical`, and the value its intensity measure is built on at
/// scale 1.
fn suite(
    records: Vec<RecordArg>,
    im: Intensity,
    sa_period: Option<f64>,
    with_vertical: bool,
) -> PyResult<Vec<SuiteRecord>> {
    let mut out = Vec::with_capacity(records.len());
    for (path, unit, path_v, unit_v) in records {
        let record = component(&path, unit.as_deref())?;
        let value = request::record_intensity(&path, &record.series, im, sa_period).map_err(refused)?;
        let drive = match path_v {
            Some(pv) if with_vertical => Drive::Paired {
                horizontal: record,
                vertical: component(&pv, unit_v.as_deref())?,
            },
            _ => Drive::Record(record),
        };
        out.push(SuiteRecord {
            drive,
            intensity: value,
        });
    }
    if out.is_empty() {
        return Err(input("records: no records given"));
    }
    Ok(out)
}

/// The blocks of a fragility study of `scene` under `im`: those given
/// (width, height in m), or, with none (`None`), a stack scene's own
/// bounding block; refused as the CLI refuses them.
#[pyfunction]
#[pyo3(signature = (scene, blocks, im="pga"))]
pub fn _fragility_blocks(scene: &Scene, blocks: Option<Vec<(f64, f64)>>, im: &str) -> PyResult<Vec<(f64, f64)>> {
    let given = blocks
        .unwrap_or_default()
        .into_iter()
        .map(|(width_m, height_m)| BlockSize { width_m, height_m })
        .collect();
    let blocks = request::fragility_blocks(scene.scenario(), given, intensity(im)?).map_err(refused)?;
    Ok(blocks.iter().map(|b| (b.width_m, b.height_m)).collect())
}

/// The runs `indices` (default all) of a fragility study of `blocks`
/// (width, height in m) under `records` ((path, unit or None)) scaled to
/// `levels` of `im` ("pga" in g, "pgv" in m/s), on the scene's friction,
/// impact law and tolerances: runs.csv's columns.
#[pyfunction]
#[pyo3(signature = (scene, records, levels, blocks, *, im="pga", sa_period=None, vertical=None, threads=None, indices=None, check_only=false, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn _fragility_runs<'py>(
    py: Python<'py>,
    scene: &Scene,
    records: Vec<RecordArg>,
    levels: Vec<f64>,
    blocks: Vec<(f64, f64)>,
    im: &str,
    sa_period: Option<f64>,
    vertical: Option<&str>,
    threads: Option<usize>,
    indices: Option<Vec<usize>>,
    check_only: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    fragility_runs(
        py, scene, records, levels, blocks, im, sa_period, vertical, threads, indices, check_only, progress,
    )
}

#[allow(clippy::too_many_arguments)]
fn fragility_runs<'py>(
    py: Python<'py>,
    scene: &Scene,
    records: Vec<RecordArg>,
    levels: Vec<f64>,
    blocks: Vec<(f64, f64)>,
    im: &str,
    sa_period: Option<f64>,
    vertical: Option<&str>,
    threads: Option<usize>,
    indices: Option<Vec<usize>>,
    check_only: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = scene.scenario();
    let im = intensity(im)?;
    request::levels_and_blocks(&levels, blocks.len()).map_err(refused)?;
    // A stack refuses the rocking measures (it has no one α).
    let given = blocks
        .iter()
        .map(|&(width_m, height_m)| BlockSize { width_m, height_m })
        .collect();
    request::fragility_blocks(base, given, im).map_err(refused)?;
    // As the CLI: a value given twice would count its runs twice and
    // narrow the fits' bands without a word.
    for (j, v) in levels.iter().enumerate() {
        if let Some(i) = levels[..j].iter().position(|u| u == v) {
            return Err(input(format!(
                "levels[{i}] and levels[{j}] are both {v}; give each level once"
            )));
        }
    }
    for (j, b) in blocks.iter().enumerate() {
        if let Some(i) = blocks[..j].iter().position(|c| c == b) {
            return Err(input(format!(
                "blocks[{i}] and blocks[{j}] are both {} x {} m; give each block once",
                b.0, b.1
            )));
        }
    }
    let canonical: Vec<PathBuf> = records
        .iter()
        .map(|(p, _, _, _)| p.canonicalize().unwrap_or_else(|_| p.clone()))
        .collect();
    for (j, p) in canonical.iter().enumerate() {
        if let Some(i) = canonical[..j].iter().position(|q| q == p) {
            return Err(input(format!(
                "records[{i}] and records[{j}]: the record {} is listed twice; list each record once",
                p.display()
            )));
        }
    }
    let blocks: Vec<BlockSize> = blocks
        .into_iter()
        .map(|(width_m, height_m)| BlockSize { width_m, height_m })
        .collect();
    let with_vertical = vertical_choice(vertical, &records)?;
    let sa_period = request::sa_period(im, sa_period).map_err(refused)?;
    let records = suite(records, im, sa_period, with_vertical)?;
    let spec = FragilitySpec {
        base,
        records: &records,
        levels: &levels,
        blocks: &blocks,
        im,
    };
    spec.check().map_err(|e| match e {
        FragilityCheckError::Scenario { block: b, error } => {
            input(format!("blocks={}x{}: {error}", b.width_m, b.height_m))
        }
        too_many @ FragilityCheckError::TooManyRuns(_) => input(too_many),
    })?;
    let indices = indices.unwrap_or_else(|| (0..spec.run_count()).collect());
    if let Some(i) = indices.iter().find(|&&i| i >= spec.run_count()) {
        return Err(input(format!("run {i}: there are {} runs", spec.run_count())));
    }
    let workers = Workers::new(threads)?;
    let runs = if check_only {
        Vec::new()
    } else {
        let chunk = 4 * workers.threads().max(2);
        py.detach(|| -> PyResult<_> {
            let mut runs = Vec::with_capacity(indices.len());
            for part in indices.chunks(chunk) {
                let done = workers
                    .run(|| run_fragility(&spec, part, &silent))
                    .map_err(|e| run_error(&anyhow!(e)))?;
                runs.extend(done);
                checkpoint(progress.as_ref(), runs.len(), indices.len())?;
            }
            Ok(runs)
        })?
    };
    let out = PyDict::new(py);
    out.set_item("count", spec.run_count())?;
    out.set_item("im", im.column())?;
    out.set_item("records", records.iter().map(|r| r.drive.name()).collect::<Vec<_>>())?;
    out.set_item(
        "run",
        indices[..runs.len()]
            .iter()
            .map(|&i| i as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "block",
        runs.iter()
            .map(|r| r.at.block as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    let col = |f: &dyn Fn(&rocking::analysis::engineering::fragility::FragilityRun) -> f64| {
        runs.iter().map(f).collect::<Vec<f64>>()
    };
    out.set_item("width_m", col(&|r| blocks[r.at.block].width_m).into_pyarray(py))?;
    out.set_item("height_m", col(&|r| blocks[r.at.block].height_m).into_pyarray(py))?;
    out.set_item(
        "record",
        runs.iter()
            .map(|r| records[r.at.record].drive.name())
            .collect::<Vec<_>>(),
    )?;
    out.set_item("level", col(&|r| levels[r.at.level]).into_pyarray(py))?;
    out.set_item("scale", col(&|r| r.scale).into_pyarray(py))?;
    out.set_item("end", runs.iter().map(|r| r.response.end.name()).collect::<Vec<_>>())?;
    out.set_item(
        "peak_theta_over_alpha",
        col(&|r| r.response.peak_theta_over_alpha).into_pyarray(py),
    )?;
    out.set_item(
        "t_end_s",
        col(&|r| r.response.t_end_event_s.unwrap_or(f64::NAN)).into_pyarray(py),
    )?;
    out.set_item(
        "has_t_end",
        runs.iter()
            .map(|r| r.response.t_end_event_s.is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    Ok(out)
}

/// A fit as fragility.json writes it, or `{"error": …}`.
fn fit_json(fit: &Result<LognormalFit, FitError>) -> serde_json::Value {
    match fit {
        Ok(f) => serde_json::to_value(f).unwrap_or(serde_json::Value::Null),
        Err(e) => json!({ "error": e.to_string() }),
    }
}

/// Counts and both lognormal fits per block, from the runs (run index,
/// end state name, peak θ/α) of a study with `blocks` blocks, `levels` and
/// `records` records; `threshold` is the θ/α whose exceedance is counted.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn _fragility_fits<'py>(
    py: Python<'py>,
    blocks: usize,
    levels: Vec<f64>,
    records: usize,
    threshold: f64,
    run: Vec<usize>,
    end: Vec<String>,
    peak: Vec<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    request::threshold(threshold).map_err(refused)?;
    let (nl, nr) = (levels.len(), records.max(1));
    let mut rows = Vec::with_capacity(run.len());
    for ((&i, e), &p) in run.iter().zip(&end).zip(&peak) {
        let state = EndState::from_name(e).ok_or_else(|| input(format!("end state {e:?}: unknown")))?;
        rows.push((i / (nl * nr), (i / nr) % nl, state, p));
    }
    let counts = summarise(blocks, nl, threshold, rows);
    let out: Vec<serde_json::Value> = counts
        .iter()
        .enumerate()
        .map(|(b, c)| {
            let fits = fit_block(&levels, c);
            let per_level: Vec<serde_json::Value> = levels
                .iter()
                .zip(c)
                .map(|(&level, s)| {
                    json!({
                        "level": level, "runs": s.runs, "overturned": s.overturned, "flight": s.flight,
                        "exceeded": s.exceeded, "fraction_overturned": s.fraction_overturned(),
                        "fraction_exceeded": s.fraction_exceeded(),
                        "fit_overturned": fits.overturn.as_ref().ok().map(|f| f.at(level)),
                        "fit_exceeded": fits.exceed.as_ref().ok().map(|f| f.at(level)),
                    })
                })
                .collect();
            json!({
                "block": b,
                "overturning": fit_json(&fits.overturn),
                "exceedance": fit_json(&fits.exceed),
                "levels": per_level,
            })
        })
        .collect();
    json_to_py(py, &serde_json::Value::Array(out))
}
