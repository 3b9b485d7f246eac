//! Why a stack's run stops short: a slip the model does not follow, or the driver's failure.

use crate::integrate::hybrid::DriverError;

/// A slip the model does not follow: the run stops there, as bad input
/// (the interface's `static` is below what the motion needs).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StackError {
    /// The driver failed.
    #[error("{0}")]
    Driver(#[from] DriverError),
    /// Interface `iface` needs more friction than its `static`.
    #[error(
        "stack block {block}'s lower face would slip at t = {t_s:.4} s (τ = {tau:.4}): the friction it needs, |T|/N, reaches its static = {mu} there; sliding between blocks is not simulated, only on the base (docs/model.md §18.8): raise stack[{index}].static or set it to inf", index = block - 1
    )]
    Slip {
        /// 1-based index of the block above the interface.
        block: usize,
        /// τ of the slip.
        tau: f64,
        /// Its time, s.
        t_s: f64,
        /// |T|/N there.
        demand: f64,
        /// The interface's static coefficient.
        mu: f64,
    },
    /// The sliding base face has no unique motion (the Painlevé paradox).
    #[error(
        "the stack's base face would slide with no unique motion at t = {t_s:.4} s (τ = {tau:.4}): its kinetic friction {mu} is too high for this stack's shape (the Painlevé paradox, docs/model.md §18.7): lower stack[0].kinetic"
    )]
    Painleve {
        /// τ.
        tau: f64,
        /// t, s.
        t_s: f64,
        /// The base face's kinetic coefficient.
        mu: f64,
    },
}

impl StackError {
    /// Whether the input (a friction coefficient) is to blame, not the
    /// solver.
    pub fn is_input(&self) -> bool {
        !matches!(self, StackError::Driver(_))
    }

    /// The config key to change, for an input error.
    pub fn key(&self) -> Option<String> {
        match self {
            StackError::Driver(_) => None,
            StackError::Slip { block, .. } => Some(format!("stack[{}].static", block.saturating_sub(1))),
            StackError::Painleve { .. } => Some("stack[0].kinetic".to_string()),
        }
    }
}
