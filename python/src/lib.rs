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
mod scene;
mod simulate;
mod spectrum;
mod study;

#[pymodule]
fn _rocking(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ConfigError", py.get_type::<errors::ConfigError>())?;
    m.add("RecordError", py.get_type::<errors::RecordError>())?;
    m.add("RunError", py.get_type::<errors::RunError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(scene::_scene_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(scene::presets, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::_lyapunov, m)?)?;
    m.add_function(wrap_pyfunction!(study::_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(study::_outcome_map, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::_fragility_runs, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::_fragility_fits, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum::_spectrum, m)?)?;
    Ok(())
}
