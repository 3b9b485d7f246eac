//! What a stack's run records at its events.

use super::StackMode;

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StackEventKind {
    /// A closed face opened on a corner.
    Uplift,
    /// An open interface closed on its other corner and rocks on it.
    Impact,
    /// An interface closed and stayed closed (its rate after the impact
    /// was in the wrong sense or below `run.zeno_eps`: an accumulation of
    /// impacts summed).
    Close,
    /// A block overturned.
    Overturn,
    /// A block lost contact.
    Flight,
    /// The base face started to slide (or reversed).
    Slip,
    /// The base face's slip stopped and it sticks.
    Stick,
}

impl StackEventKind {
    /// The word in `events.csv`.
    pub fn name(self) -> &'static str {
        match self {
            StackEventKind::Uplift => "uplift",
            StackEventKind::Impact => "impact",
            StackEventKind::Close => "close",
            StackEventKind::Overturn => "tumble",
            StackEventKind::Flight => "flight",
            StackEventKind::Slip => "slip",
            StackEventKind::Stick => "stick",
        }
    }
}

/// One event of a stack's run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackEvent {
    /// τ of the event.
    pub tau: f64,
    /// What happened.
    pub kind: StackEventKind,
    /// The interface (0 the base) or block it happened at.
    pub body: usize,
    /// Mode before.
    pub before: StackMode,
    /// Mode after.
    pub after: StackMode,
    /// The interface's q_i' before, rad per τ.
    pub q_dot_before: f64,
    /// And after.
    pub q_dot_after: f64,
}
