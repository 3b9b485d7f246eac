//! Largest Lyapunov exponents along a bifurcation diagram: one exponent per
//! aperiodic value (chaotic or quasiperiodic), so that an exponent the paper
//! quotes without its A_v (Fig. 10's 0.51) can be set against the range of
//! ours.

use rayon::prelude::*;

use super::ReproduceError;
use super::diagrams::{Diagram, PARAM};
use crate::analysis::classify::Response;
use crate::analysis::lyapunov::{Lyapunov, LyapunovOptions, Method, lyapunov};
use crate::io::presets;

/// The exponent of one value of a diagram.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanPoint {
    /// A_v.
    pub a_v: f64,
    /// The class of the value in the diagram.
    pub response: Response,
    /// Largest exponent per τ and its standard error, or why there is none.
    pub exponent: Result<(f64, f64), String>,
}

/// Exponents over one diagram.
#[derive(Clone, Debug, PartialEq)]
pub struct Scan {
    /// The paper's figure number.
    pub figure: u32,
    /// Discarded start and end of each Lyapunov run, τ.
    pub window: (f64, f64),
    /// Forcing period 2π/Ω_h, τ (to convert to per cycle).
    pub period: f64,
    /// One point per aperiodic value, increasing A_v.
    pub points: Vec<ScanPoint>,
}

impl Scan {
    /// The finite exponents per τ.
    pub fn exponents(&self) -> Vec<f64> {
        self.points
            .iter()
            .filter_map(|p| p.exponent.as_ref().ok().map(|e| e.0))
            .collect()
    }
}

/// Computes the largest exponent (tangent dynamics) of every chaotic or
/// quasiperiodic value of `diagram`, over τ `window.0`–`window.1`, in
/// parallel (collected by index, so deterministic).
pub(crate) fn lyapunov_scan(diagram: &Diagram, window: (f64, f64), batches: usize) -> Result<Scan, ReproduceError> {
    let fail = |e: String| ReproduceError::Figure {
        figure: diagram.figure,
        what: "Lyapunov scan".to_string(),
        error: e,
    };
    let preset = format!("fig{}", diagram.figure);
    if presets::get(&preset).is_none() {
        return Err(fail(format!("no preset {preset}")));
    }
    let base = crate::io::config::load(Some(&preset), None, &diagram.sets).map_err(|e| fail(e.to_string()))?;
    let period = std::f64::consts::TAU / diagram.config.excitation.omega_h;
    let opts = LyapunovOptions {
        method: Method::Tangent,
        transient_tau: window.0,
        total_tau: window.1,
        batches,
        ..LyapunovOptions::default()
    };
    let targets: Vec<(f64, Response)> = diagram
        .values
        .iter()
        .filter(|v| matches!(v.response, Response::Chaotic | Response::Quasiperiodic))
        .map(|v| (v.value, v.response))
        .collect();
    let points = targets
        .par_iter()
        .map(|&(a_v, response)| {
            let cfg = crate::sim::Param::apply(&base, &[(PARAM, a_v)]).map_err(|e| fail(e.to_string()))?;
            let model = cfg.model().map_err(|e| fail(e.to_string()))?;
            let exponent = match lyapunov(&model, &cfg.initial, &opts) {
                Ok(Lyapunov::Exponents(r)) => Ok((r.largest_per_tau, r.stderr)),
                Ok(Lyapunov::None { no_exponent, tau, .. }) => {
                    Err(format!("no exponent: {} at τ = {tau:.1}", no_exponent.name()))
                }
                Err(e) => Err(e.to_string()),
            };
            Ok(ScanPoint {
                a_v,
                response,
                exponent,
            })
        })
        .collect::<Result<Vec<_>, ReproduceError>>()?;
    Ok(Scan {
        figure: diagram.figure,
        window,
        period,
        points,
    })
}
