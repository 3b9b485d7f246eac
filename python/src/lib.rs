//! `rocking._rocking`: the Python binding of the rocking simulator.
//!
//! A thin layer over the core's public API: scenes are built by the config
//! layer (the CLI's keys, units and messages), runs and analyses are the
//! library's, and results leave as numpy arrays. Nothing here computes
//! physics. Long calls release the GIL, use all cores (rayon) and check
//! for Ctrl-C between chunks. The Python package `rocking` wraps these
//! functions in typed result classes.

use pyo3::prelude::*;

mod convert;
mod errors;
mod fragility;
mod interrupt;
mod keys;
mod map;
mod memory;
mod names;
mod scene;
mod simulate;
mod sliding;
mod spectrum;
mod stack;
mod study;

#[pymodule]
fn _rocking(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    // numpy's C API now, not on the first array a call returns: loaded
    // lazily, a Ctrl-C pending at that moment made its import fail inside
    // a call, which surfaced as a PanicException.
    let _ = numpy::PyArray1::<f64>::zeros(py, [0], false);
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ConfigError", py.get_type::<errors::ConfigError>())?;
    m.add("RecordError", py.get_type::<errors::RecordError>())?;
    m.add("RunError", py.get_type::<errors::RunError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(scene::_scene_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(scene::presets, m)?)?;
    m.add_function(wrap_pyfunction!(scene::_keys_help, m)?)?;
    m.add_function(wrap_pyfunction!(scene::_undocumented_keys, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::_lyapunov, m)?)?;
    m.add_function(wrap_pyfunction!(study::_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(map::_outcome_map, m)?)?;
    m.add_function(wrap_pyfunction!(map::_outcome_cells, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::_fragility_blocks, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::_fragility_runs, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::_fragility_fits, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum::_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(sliding::_sliding_spectrum, m)?)?;
    Ok(())
}
