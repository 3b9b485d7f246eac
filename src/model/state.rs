//! The state vector shared by every mode, and the indices into it.
//!
//! `y = [Θ, Θ', X, X', W, D]`: the normalised angle and angular velocity,
//! the horizontal position and velocity of the centre of mass (relative to
//! the base, per R), and two quadratures for the energy audit: `W`, the work
//! done by the base's pseudo-forces, and `D`, the energy dissipated by
//! sliding friction (both per m g R). The quadratures come last because the
//! driver takes the trailing components as quadratures
//! (`HybridSystem::QUADRATURES`): read by neither the vector field nor the
//! guards, so left out of the guards' interpolants.

/// Length of the state vector.
pub const N: usize = 6;
/// Index of Θ in the state.
pub const THETA: usize = 0;
/// Index of Θ'.
pub const THETA_DOT: usize = 1;
/// Index of X.
pub const X: usize = 2;
/// Index of X'.
pub const X_DOT: usize = 3;
/// Index of the base work W.
pub const WORK: usize = 4;
/// Index of the friction dissipation D.
pub const FRICTION_LOSS: usize = 5;
