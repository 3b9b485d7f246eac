//! The Taylor coefficients generated from the vector field of `dynamics`
//! (the one written over a generic scalar) evaluated over jets: the
//! general recurrences of `model::ad`, with the forcing's series (from
//! [`ForcingSeries`], not differentiated) as a known input.

use super::{ForcingSeries, INV, MAX_ORDER};
use crate::model::ad::Tape;
use crate::model::dynamics::{self, Forcing};
use crate::model::mode::Mode;
use crate::model::params::Model;
use crate::model::state::N;

/// What [`super::taylor`] computes, generated: the coefficients of the
/// block in `mode` through `(t, y)` in `c[0..=order]`; `false` if the
/// excitation has no series or the order is above [`MAX_ORDER`].
pub fn taylor(model: &Model, mode: Mode, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
    if order >= MAX_ORDER || c.len() < order + 1 {
        return false;
    }
    let mut f = ForcingSeries::none();
    if !f.fill(&model.excitation, t, order) {
        return false;
    }
    let c = &mut c[..=order];
    c[0] = *y;
    let tape = Tape::<{ MAX_ORDER + 1 }>::new();
    for k in 0..order {
        if !tape.begin(k) {
            return false;
        }
        let state = c[k].map(|v| tape.variable(v));
        let fo = Forcing {
            a: tape.known(&f.a),
            av: tape.known(&f.av),
        };
        let dy = dynamics::field(&model.geo, model.mu_k, mode, fo, &state);
        // y' = g gives y_{k+1} = g_k/(k+1).
        let inv = INV[k + 1];
        c[k + 1] = dy.map(|g| g.coeff(k) * inv);
    }
    true
}

#[cfg(test)]
mod tests;
