//! Where a live run starts: the scenario's initial state, or a state restarted with Θ perturbed.

use super::driver::LiveSystem;
use crate::model::Mode;
use crate::model::system::{N, THETA, THETA_DOT, X, X_DOT};
use crate::sim::{InitialState, initial_mode};

/// Where a run starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Start {
    /// τ = 0 and the scenario's initial state.
    Initial,
    /// From the state `y` in `mode` at `tau`, with Θ increased by `eps`.
    Perturbed {
        /// τ to start at.
        tau: f64,
        /// State to start from.
        y: [f64; N],
        /// Its mode.
        mode: Mode,
        /// Added to Θ.
        eps: f64,
    },
}

/// The mode and state of a block restarted from `(mode, y)` with Θ + `eps`.
///
/// X' is kept where the contact slips, and recomputed as the no-slip value
/// where the pivot sticks (a perturbed Θ changes it), so the perturbed state
/// is admissible for the same contact.
pub(super) fn perturbed_state(
    system: &mut dyn LiveSystem,
    tau: f64,
    mode: Mode,
    y: &[f64; N],
    eps: f64,
) -> Result<(Mode, [f64; N]), String> {
    let theta = y[THETA] + eps;
    let tumble = system.overturn_angle();
    if !theta.is_finite() || theta.abs() >= tumble {
        return Err(format!(
            "perturbed Θ = {theta} is not inside the tumble angle ±{tumble}"
        ));
    }
    let keeps_slip = match mode {
        Mode::Slide { .. } | Mode::SlideRock { .. } => true,
        Mode::Rest | Mode::Rock { .. } | Mode::Tumbled | Mode::Flight => false,
    };
    let init = InitialState {
        theta,
        theta_dot: y[THETA_DOT],
        x_dot: keeps_slip.then_some(y[X_DOT]),
    };
    let (m, mut y0) = initial_mode(system.params(), &init).map_err(|e| e.to_string())?;
    y0[X] = y[X];
    let m = system.settle_mode(m, tau, &mut y0);
    Ok((m, y0))
}
