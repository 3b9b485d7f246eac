//! `spectrum`: the rocking spectrum of one record over a range of block
//! sizes (`rocking spectrum --record`), over the library's
//! `analysis::engineering::rocking_spectrum`, optionally with each block's
//! overturning scale; spectrum.csv's columns.

use std::path::PathBuf;

use anyhow::anyhow;
use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::analysis::engineering::request::{self, OverturnRequest, RequestError, Scaling, SpectrumRequest};
use rocking::analysis::engineering::response::scenario_for;
use rocking::analysis::engineering::rocking_spectrum::{SizeAxis, SpectrumPoint, SpectrumSpec, rocking_spectrum};
use rocking::analysis::engineering::{Drive, EndState};
use rocking::analysis::field::RequestField;
use rocking::analysis::silent;
use rocking::io::record::{RecordSpec, read_record_as};
use rocking::sim::scenario::Record;

use crate::errors::{Origin, config_error, record_error, run_error};
use crate::names::Keywords;
use crate::scene::Scene;
use crate::study::{Workers, checkpoint};

/// A request the core refuses, in the words of the keywords.
fn input(e: RequestError) -> PyErr {
    config_error(e.render(&Keywords), Origin::default())
}

/// The rocking spectrum of the record at `record` (in `unit`, for text
/// files) scaled by `scale` or to `pga` (g), over `count` log-spaced sizes
/// `from_m … to_m` of the half-diagonal R (`size="r"`) or the height H
/// (`"h"`), for each B/H in `b_over_h` (default 0.25; a stack scene's
/// own, its whole stack scaled to each size); with `overturn_scale`, each
/// block's smallest overturning scale, searched on the ladder
/// `search_step … search_max` and refined to `rel_tol`. Checked with the
/// core's request ([`SpectrumRequest`]), whose messages name these
/// keywords; Ctrl-C is checked between B/H ratios.
#[pyfunction]
#[pyo3(signature = (scene, record, sizes, *, unit=None, record_v=None, unit_v=None, size="r", b_over_h=None, scale=None, pga=None, overturn_scale=false, search_step=0.1, search_max=5.0, rel_tol=1e-3, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn _spectrum<'py>(
    py: Python<'py>,
    scene: &Scene,
    record: PathBuf,
    sizes: (f64, f64, usize),
    unit: Option<&str>,
    record_v: Option<PathBuf>,
    unit_v: Option<&str>,
    size: &str,
    b_over_h: Option<Vec<f64>>,
    scale: Option<f64>,
    pga: Option<f64>,
    overturn_scale: bool,
    search_step: f64,
    search_max: f64,
    rel_tol: f64,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    spectrum(
        py,
        scene,
        record,
        sizes,
        unit,
        record_v,
        unit_v,
        size,
        b_over_h,
        scale,
        pga,
        overturn_scale,
        search_step,
        search_max,
        rel_tol,
        threads,
        progress,
    )
}

#[allow(clippy::too_many_arguments)]
fn spectrum<'py>(
    py: Python<'py>,
    scene: &Scene,
    record: PathBuf,
    sizes: (f64, f64, usize),
    unit: Option<&str>,
    record_v: Option<PathBuf>,
    unit_v: Option<&str>,
    size: &str,
    b_over_h: Option<Vec<f64>>,
    scale: Option<f64>,
    pga: Option<f64>,
    overturn_scale: bool,
    search_step: f64,
    search_max: f64,
    rel_tol: f64,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = scene.scenario();
    let unit = unit
        .map(|text| request::unit(RequestField::Unit, text))
        .transpose()
        .map_err(input)?;
    let loaded = read_record_as(
        &record,
        &RecordSpec {
            unit,
            dt: None,
            channel: None,
        },
    )
    .map_err(|e| record_error(&record, &e))?;
    let pga_g = loaded.series.peaks(1.0).pga_g;
    let horizontal = Record {
        path: record.clone(),
        series: loaded.series,
        unit: loaded.unit,
        dt: None,
        crc32: loaded.crc32,
        channel: None,
    };
    crate::simulate::warn_unit(py, "record", &horizontal)?;
    // The vertical (positive upward), scaled by the same factor as the
    // horizontal, as `rocking spectrum --record-v`.
    let drive = match record_v {
        None => Drive::Record(horizontal),
        Some(path_v) => {
            let unit_v = match unit_v {
                None => unit,
                Some(text) => Some(request::unit(RequestField::UnitV, text).map_err(input)?),
            };
            let spec = RecordSpec {
                unit: unit_v,
                dt: None,
                channel: None,
            };
            let v = read_record_as(&path_v, &spec).map_err(|e| record_error(&path_v, &e))?;
            let vertical = Record {
                path: path_v,
                series: v.series,
                unit: v.unit,
                dt: None,
                crc32: v.crc32,
                channel: None,
            };
            crate::simulate::warn_unit(py, "record_v", &vertical)?;
            Drive::Paired { horizontal, vertical }
        }
    };
    let scale = Scaling { scale, pga_g: pga }.factor(pga_g).map_err(input)?;
    let axis = match size {
        "r" => SizeAxis::HalfDiagonal,
        "h" => SizeAxis::Height,
        other => {
            return Err(config_error(
                format!("size={other}: expected r or h"),
                Origin::default(),
            ));
        }
    };
    let (from_m, to_m, count) = sizes;
    let blocks = SpectrumRequest {
        axis,
        from_m,
        to_m,
        count,
        b_over_h: request::spectrum_ratios(base, b_over_h).map_err(input)?,
        overturn: overturn_scale.then_some(OverturnRequest {
            search_step,
            search_max,
            rel_tol,
        }),
    }
    .checked()
    .map_err(input)?;
    let total = blocks.sizes.count * blocks.b_over_h.len();
    let spec = SpectrumSpec {
        base,
        drive: &drive,
        scale,
        sizes: blocks.sizes,
        b_over_h: blocks.b_over_h,
        overturn: blocks.overturn,
    };
    for (_, _, block) in spec.blocks() {
        scenario_for(base, block, &drive, scale).map_err(|e| {
            config_error(
                format!("block {} × {} m: {e}", block.width_m, block.height_m),
                Origin::default(),
            )
        })?;
    }
    let workers = Workers::new(threads)?;
    // One B/H at a time: the blocks of a ratio are a spectrum of their own
    // (ratio outer, size inner), so the rows are the same.
    let points: Vec<SpectrumPoint> = py.detach(|| -> PyResult<_> {
        let mut all = Vec::new();
        for &ratio in &spec.b_over_h {
            let one = SpectrumSpec {
                b_over_h: vec![ratio],
                ..spec.clone()
            };
            let done = workers
                .run(|| rocking_spectrum(&one, &silent))
                .map_err(|e| run_error(&anyhow!(e)))?;
            all.extend(done);
            checkpoint(progress.as_ref(), all.len(), total)?;
        }
        Ok(all)
    })?;
    let out = PyDict::new(py);
    let f = |g: &dyn Fn(&SpectrumPoint) -> f64| points.iter().map(g).collect::<Vec<f64>>().into_pyarray(py);
    let first = |p: &SpectrumPoint| {
        p.overturn
            .as_ref()
            .and_then(|s| s.first_failure.as_ref().map(|(a, r)| (*a, r.end)))
    };
    out.set_item("b_over_h", f(&|p| p.b_over_h))?;
    out.set_item("alpha_rad", f(&|p| p.block.alpha()))?;
    out.set_item("width_m", f(&|p| p.block.width_m))?;
    out.set_item("height_m", f(&|p| p.block.height_m))?;
    out.set_item("r_m", f(&|p| p.block.half_diagonal_m()))?;
    out.set_item("p_per_s", f(&|p| p.block.p_per_s()))?;
    out.set_item("scale", f(&|_| scale))?;
    out.set_item("pga_g", f(&|_| scale * pga_g))?;
    out.set_item("end", points.iter().map(|p| p.response.end.name()).collect::<Vec<_>>())?;
    out.set_item("peak_theta_over_alpha", f(&|p| p.response.peak_theta_over_alpha))?;
    out.set_item("t_end_s", f(&|p| p.response.t_end_event_s.unwrap_or(f64::NAN)))?;
    out.set_item(
        "has_t_end",
        points
            .iter()
            .map(|p| p.response.t_end_event_s.is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item("overturn_scale", f(&|p| first(p).map_or(f64::NAN, |(a, _)| a)))?;
    out.set_item("overturn_pga_g", f(&|p| first(p).map_or(f64::NAN, |(a, _)| a * pga_g)))?;
    out.set_item(
        "overturn_end",
        points
            .iter()
            .map(|p| first(p).map_or("", |(_, e): (f64, EndState)| e.name()))
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "has_overturn_scale",
        points
            .iter()
            .map(|p| first(p).is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "safe_windows",
        points
            .iter()
            .map(|p| p.overturn.as_ref().map_or(0, |s| s.safe_windows.len() as u32))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item("pga_g_record", pga_g)?;
    Ok(out)
}
