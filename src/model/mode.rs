//! Contact modes and signs.

use serde::Serialize;

/// A sign: the pivot side (`Pos` = right corner, θ > 0) or a slip direction
/// (`Pos` = +x).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Sign {
    /// −1: left corner, or slipping towards −x.
    Neg,
    /// +1: right corner, or slipping towards +x.
    Pos,
}

impl Sign {
    /// −1.0 or +1.0.
    #[inline]
    pub fn value(self) -> f64 {
        match self {
            Sign::Neg => -1.0,
            Sign::Pos => 1.0,
        }
    }

    /// The other sign.
    #[inline]
    pub fn flip(self) -> Self {
        match self {
            Sign::Neg => Sign::Pos,
            Sign::Pos => Sign::Neg,
        }
    }

    /// The sign of `x`; `Pos` for `+0.0`, `Neg` for `-0.0` and negatives.
    #[inline]
    pub fn of(x: f64) -> Self {
        if x.is_sign_negative() { Sign::Neg } else { Sign::Pos }
    }
}

/// Contact mode of the block (MODEL-DECISIONS "Modes and switches").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Mode {
    /// Flat and stuck to the base.
    Rest,
    /// Flat, sliding in direction `slip`.
    Slide {
        /// Direction of the sliding velocity.
        slip: Sign,
    },
    /// Rotating about the corner `pivot`, which sticks.
    Rock {
        /// The corner in contact (`Pos` = right, θ > 0).
        pivot: Sign,
    },
    /// Rotating about the corner `pivot`, which slips in direction `slip`
    /// against kinetic friction.
    SlideRock {
        /// The corner in contact.
        pivot: Sign,
        /// Direction of the corner's slip velocity.
        slip: Sign,
    },
    /// Terminal: `|Θ|` reached the tumble angle.
    Tumbled,
    /// Terminal: the normal force vanished (or an impact with vertical
    /// restitution threw the block off the base).
    Flight,
}

impl Mode {
    /// Name used in every output file: `rest`, `slide`, `rock`,
    /// `slide-rock`, `tumbled`, `flight`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Rest => "rest",
            Mode::Slide { .. } => "slide",
            Mode::Rock { .. } => "rock",
            Mode::SlideRock { .. } => "slide-rock",
            Mode::Tumbled => "tumbled",
            Mode::Flight => "flight",
        }
    }

    /// Whether the mode ends a run.
    pub fn is_terminal(self) -> bool {
        match self {
            Mode::Tumbled | Mode::Flight => true,
            Mode::Rest | Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. } => false,
        }
    }

    /// Index into per-mode tables (`rest, slide, rock, slide-rock, tumbled, flight`).
    pub fn index(self) -> usize {
        match self {
            Mode::Rest => 0,
            Mode::Slide { .. } => 1,
            Mode::Rock { .. } => 2,
            Mode::SlideRock { .. } => 3,
            Mode::Tumbled => 4,
            Mode::Flight => 5,
        }
    }

    /// The mode names in [`index`](Mode::index) order.
    pub(crate) const NAMES: [&'static str; 6] = ["rest", "slide", "rock", "slide-rock", "tumbled", "flight"];
}
