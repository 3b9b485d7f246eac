//! The scene the tests of the equations and of their derived forms (the
//! tangent dynamics of `variational`, the Taylor series of `series`)
//! share, so each states only what it varies and a new field of
//! [`Model`] is filled in once.

use crate::model::Model;
use crate::model::excitation::{Excitation, Harmonic};
use crate::model::geometry::Geometry;
use crate::model::impact::ImpactLaw;
use crate::model::mode::{Mode, Sign};
use crate::model::params::FlightPolicy;

/// Harmonic forcing of `geo`'s block with `A_h = 2`, `Ω_h = 8`,
/// `Φ_h = 0.3` (strong enough to rock and slide a 1 × 4 block, fast
/// enough that a step of 0.3 spans a good part of a cycle) and the
/// vertical part `(A_v, Ω_v, Φ_v)`.
pub(crate) fn harmonic(geo: &Geometry, a_v: f64, omega_v: f64, phase_v: f64) -> Excitation {
    Excitation::Harmonic(Harmonic {
        a_h: 2.0,
        a_v,
        omega_h: 8.0,
        omega_v,
        phase_h: 0.3,
        phase_v,
        psi: geo.psi,
    })
}

/// The forcing of the default scene (`shared`: one sine for both
/// directions, `A_v = 2.5`) or with a vertical part of its own frequency
/// and phase (`A_v = 0.7`, `Ω_v = 5.5`, `Φ_v = −1.2`), which the fused
/// series keep apart.
pub(crate) fn two_sines(geo: &Geometry, shared: bool) -> Excitation {
    if shared {
        harmonic(geo, 2.5, 8.0, 0.3)
    } else {
        harmonic(geo, 0.7, 5.5, -1.2)
    }
}

/// A block of `geo` under `excitation`, with friction `μ_s = 0.4`,
/// `μ_k = 0.35` (it slides), restitution ratio 0.82, overturning at
/// `Θ = 1`, a run stopped at flight and a Zeno threshold of 10⁻⁵;
/// a test changes what it varies with `..model(geo, excitation)`.
pub(crate) fn model(geo: Geometry, excitation: Excitation) -> Model {
    Model {
        geo,
        mu_s: 0.4,
        mu_k: 0.35,
        law: ImpactLaw::Ratio { r: 0.82 },
        excitation,
        tumble_theta: 1.0,
        flight: FlightPolicy::Stop,
        zeno_eps: 1e-5,
        frame: None,
    }
}

/// Every moving mode, each pivot and slip sign: slide, rock and
/// slide-rock about each corner, in that order per corner.
pub(crate) fn moving_modes() -> Vec<Mode> {
    let mut modes = Vec::new();
    for s in [Sign::Pos, Sign::Neg] {
        modes.push(Mode::Slide { slip: s });
        modes.push(Mode::Rock { pivot: s });
        for slip in [Sign::Pos, Sign::Neg] {
            modes.push(Mode::SlideRock { pivot: s, slip });
        }
    }
    modes
}
