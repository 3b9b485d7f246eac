//! The tangent dynamics generated from the equations of `dynamics` and the
//! guards of `system` by forward-mode automatic differentiation: the
//! field over dual numbers seeded in `z = (Θ, Θ', X')`, the guards over
//! dual numbers seeded in `(Θ, Θ', X', τ)` with the forcing's rate of
//! change as its τ-partial.

use super::{COORDS, DIM, GuardGradient};
use crate::integrate::hybrid::MAX_GUARDS;
use crate::model::ad::Dual;
use crate::model::dynamics::{self, Forcing};
use crate::model::mode::Mode;
use crate::model::params::Model;
use crate::model::state::N;
use crate::model::system::{guard_values, tumble_angle};

/// `∂(Θ', Θ'', X'')/∂(Θ, Θ', X')` of `mode`'s vector field
/// (`dynamics::field`) at forcing `fo` and state `y`.
#[inline]
pub fn field_jacobian(model: &Model, mode: Mode, fo: Forcing, y: &[f64; N]) -> [[f64; DIM]; DIM] {
    let fo = Forcing {
        a: Dual::<DIM>::constant(fo.a),
        av: Dual::constant(fo.av),
    };
    let dy = dynamics::field(&model.geo, model.mu_k, mode, fo, &Dual::seeded(y, &COORDS));
    COORDS.map(|i| dy[i].d)
}

/// Gradient of guard `index` of `mode` (`system::guard_values`) at forcing
/// `fo`, forcing rate `rate` and state `y`; `None` for an index the mode
/// does not have.
pub fn guard_gradient(
    model: &Model,
    mode: Mode,
    index: usize,
    fo: Forcing,
    rate: Forcing,
    y: &[f64; N],
) -> Option<GuardGradient> {
    // Directions: Θ, Θ', X' (COORDS), then τ.
    const T: usize = DIM;
    let fo = fo.timed::<{ DIM + 1 }>(rate);
    let mut g = [Dual::constant(0.0); MAX_GUARDS];
    let n = guard_values(model, tumble_angle(model), mode, fo, &Dual::seeded(y, &COORDS), &mut g);
    let d = g.get(index).filter(|_| index < n)?.d;
    Some(GuardGradient {
        state: [d[0], d[1], d[2]],
        time: d[T],
    })
}

#[cfg(test)]
mod tests;
