//! `sliding_spectrum`: the peak and residual sliding displacement against
//! the friction coefficient under one record (`rocking sliding-spectrum
//! --record`), over the library's
//! `analysis::engineering::sliding_spectrum`; sliding_spectrum.csv's
//! columns, the slide-only block's rows first.

use std::path::PathBuf;

use anyhow::anyhow;
use numpy::IntoPyArray as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::analysis::engineering::request::{self, Scaling};
use rocking::analysis::engineering::sliding_spectrum::{BlockKind, SlidingPoint, SlidingSpec, sliding_spectrum};
use rocking::analysis::engineering::{BlockSize, Drive, EndState};
use rocking::analysis::field::RequestField;
use rocking::analysis::silent;
use rocking::io::record::{RecordSpec, read_record_as};
use rocking::sim::scenario::Record;

use crate::errors::{Origin, config_error, record_error, run_error};
use crate::names::Keywords;
use crate::scene::Scene;
use crate::study::{Workers, checkpoint};

fn input(message: impl std::fmt::Display) -> PyErr {
    config_error(message.to_string(), Origin::default())
}

/// The sliding spectrum of the record at `record` (in `unit`, for text
/// files) scaled by `scale` or to `pga` (g), at the friction coefficients
/// `mu` (μ_s, increasing; μ_k = `kinetic_ratio`·μ_s), for the block that
/// cannot rock and for `block` = (width, height) m (default: the scene's).
/// Checked by the core's request and spec, whose messages name these
/// keywords; Ctrl-C is checked between chunks of coefficients.
#[pyfunction]
#[pyo3(signature = (scene, record, mu, *, unit=None, block=None, kinetic_ratio=1.0, scale=None, pga=None, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn _sliding_spectrum<'py>(
    py: Python<'py>,
    scene: &Scene,
    record: PathBuf,
    mu: Vec<f64>,
    unit: Option<&str>,
    block: Option<(f64, f64)>,
    kinetic_ratio: f64,
    scale: Option<f64>,
    pga: Option<f64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    sliding(
        py,
        scene,
        record,
        mu,
        unit,
        block,
        kinetic_ratio,
        scale,
        pga,
        threads,
        progress,
    )
}

#[allow(clippy::too_many_arguments)]
fn sliding<'py>(
    py: Python<'py>,
    scene: &Scene,
    record: PathBuf,
    mu: Vec<f64>,
    unit: Option<&str>,
    block: Option<(f64, f64)>,
    kinetic_ratio: f64,
    scale: Option<f64>,
    pga: Option<f64>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = scene.scenario();
    if base.excitation.record_v.is_some() {
        return Err(input(
            "base: excitation.file_v: sliding-spectrum runs horizontal motions only; use a scene without a vertical record",
        ));
    }
    let unit = unit
        .map(|text| request::unit(RequestField::Unit, text))
        .transpose()
        .map_err(|e| input(e.render(&Keywords)))?;
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
    let scale = Scaling { scale, pga_g: pga }
        .factor(pga_g)
        .map_err(|e| input(e.render(&Keywords)))?;
    let read = Record {
        path: record.clone(),
        series: loaded.series,
        unit: loaded.unit,
        dt: None,
        crc32: loaded.crc32,
        channel: None,
    };
    crate::simulate::warn_unit(py, "record", &read)?;
    let drive = Drive::Record(read);
    let size = match block {
        Some((w, h)) if w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite() => BlockSize {
            width_m: w,
            height_m: h,
        },
        Some((w, h)) => {
            return Err(input(format!(
                "block={w}x{h}: expected WIDTHxHEIGHT in metres, both > 0"
            )));
        }
        None => BlockSize {
            width_m: base.block.width,
            height_m: base.block.height,
        },
    };
    let spec = SlidingSpec {
        base,
        drive: &drive,
        scale,
        block: size,
        mu: mu.clone(),
        kinetic_ratio,
    };
    spec.check().map_err(|e| input(e.render(&Keywords)))?;
    let workers = Workers::new(threads)?;
    // Chunks of coefficients, each a spectrum of its own (both blocks per
    // μ), so the rows are those of one call; Ctrl-C between chunks.
    let chunk = (4 * workers.threads()).max(1);
    let points: Vec<SlidingPoint> = py.detach(|| -> PyResult<_> {
        let mut all = Vec::with_capacity(mu.len());
        for part in mu.chunks(chunk) {
            let one = SlidingSpec {
                mu: part.to_vec(),
                ..spec.clone()
            };
            let done = workers
                .run(|| sliding_spectrum(&one, &silent))
                .map_err(|e| run_error(&anyhow!(e)))?;
            all.extend(done);
            checkpoint(progress.as_ref(), all.len(), mu.len())?;
        }
        Ok(all)
    })?;
    let rows: Vec<(BlockKind, &SlidingPoint)> = BlockKind::ALL
        .iter()
        .flat_map(|&kind| points.iter().map(move |p| (kind, p)))
        .collect();
    let out = PyDict::new(py);
    let f = |g: &dyn Fn(BlockKind, &SlidingPoint) -> f64| {
        rows.iter()
            .map(|&(k, p)| g(k, p))
            .collect::<Vec<f64>>()
            .into_pyarray(py)
    };
    let given = |k: BlockKind, v: f64| if k == BlockKind::Given { v } else { f64::NAN };
    let event = |k: BlockKind, p: &SlidingPoint, e: EndState| {
        let r = p.of(k);
        if r.end == e {
            r.t_end_event_s.unwrap_or(f64::NAN)
        } else {
            f64::NAN
        }
    };
    out.set_item("block", rows.iter().map(|(k, _)| k.name()).collect::<Vec<_>>())?;
    out.set_item("width_m", f(&|k, _| given(k, size.width_m)))?;
    out.set_item("height_m", f(&|k, _| given(k, size.height_m)))?;
    out.set_item("mu", f(&|_, p| p.mu_s))?;
    out.set_item("mu_k", f(&|_, p| p.mu_k))?;
    out.set_item("end", rows.iter().map(|(k, p)| p.of(*k).end.name()).collect::<Vec<_>>())?;
    out.set_item("peak_sliding_m", f(&|k, p| p.of(k).peak_sliding_m))?;
    out.set_item(
        "residual_sliding_m",
        f(&|k, p| p.of(k).residual_sliding_m.unwrap_or(f64::NAN)),
    )?;
    out.set_item(
        "has_residual",
        rows.iter()
            .map(|(k, p)| p.of(*k).residual_sliding_m.is_some())
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    out.set_item("peak_theta_over_alpha", f(&|k, p| p.of(k).peak_theta_over_alpha))?;
    out.set_item("t_overturn_s", f(&|k, p| event(k, p, EndState::Overturned)))?;
    out.set_item("t_flight_s", f(&|k, p| event(k, p, EndState::Flight)))?;
    out.set_item("pga_g_record", pga_g)?;
    out.set_item("scale", scale)?;
    Ok(out)
}
