//! A stack of rectangular blocks standing on each other on the moving
//! base: a tombstone of stacked stones, a statue on its pedestal, a
//! cabinet on a plinth. EQUATIONS ONLY, derived in `docs/model.md` §18.
//!
//! Every interface (the base under the bottom block, and each block's
//! lower face on the block below) is closed, rocks about either end of the
//! faces' overlap, or is glued (never opens). The generalised coordinates
//! are the relative rotations q_i of the open interfaces, so a closed or
//! glued interface costs nothing; the equations of motion are Lagrange's
//! for those coordinates, with each interface's pivot stuck.
//!
//! Units: lengths in metres, time in τ = p t with the bottom block's p
//! (so a stack's τ and its normalised amplitudes are its bottom block's),
//! angles in radians, clockwise positive as the single block's θ (q_i > 0
//! rocks interface i on its right corner). Masses are per unit depth and
//! density (a block's mass is its area), so forces are per ρ.
//!
//! The base face slides on the base with Coulomb friction (the bottom
//! table's `static` and `kinetic`), flat or while any interface rocks, as
//! the single block's slide and slide-rock (§18.7): the slip u of the
//! whole stack along the base is then a coordinate too.
//!
//! What the model does not follow, each stopping the run with its reason
//! rather than going on wrongly: flight of any block (as the single
//! block's flight), and slip at an upper interface whose friction demand
//! reaches its static coefficient (a finite upper `static` is checked, not
//! followed).

mod dynamics;
mod geometry;
mod outline;
mod pose;
mod system;
#[cfg(test)]
mod tests;

pub use dynamics::{InterfaceLoad, StackAccel};
pub use geometry::{StackGeometry, StackShapeError};
pub use outline::{corners, outlines, rest_corners};
pub use pose::Pose;
pub use system::{StackEnd, StackError, StackEvent, StackEventKind, StackMode, StackSystem, StackTally};

/// Most blocks in a stack: the driver's guard budget (one guard per
/// interface, one per block's rotation extremum and one per interface's
/// opening extremum, one for the run's end and one for the base's slip:
/// 3·5 + 2 = 17).
pub const MAX_BLOCKS: usize = 5;

/// Length of a stack's state: `[q_1 … q_K, q_1' … q_K', u, u', W, D]`
/// with the rotations padded to [`MAX_BLOCKS`] (the unused components
/// stay 0).
pub const NS: usize = 2 * MAX_BLOCKS + 4;

/// Index of the base face's slip u in the state: the stack's horizontal
/// displacement along the base caused by sliding, m.
pub const SLIDE: usize = 2 * MAX_BLOCKS;

/// Index of the slip rate u', m per τ.
pub const SLIDE_RATE: usize = 2 * MAX_BLOCKS + 1;

/// Index of the base's work W in the state, per M G R₁ (M the stack's
/// mass, G = g/p², R₁ the bottom block's half-diagonal). W and D come
/// last: the driver takes the trailing components as quadratures.
pub const WORK_S: usize = 2 * MAX_BLOCKS + 2;

/// Index of the energy D dissipated by the base face's sliding friction,
/// per M G R₁.
pub const FRICTION_S: usize = 2 * MAX_BLOCKS + 3;

/// One block of a stack (config `[[stack]]`, bottom to top).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackBlock {
    /// Width, m.
    pub width: f64,
    /// Height, m.
    pub height: f64,
    /// Its centre's horizontal offset from the centre of the block below
    /// at rest, m (0 for the bottom block, whose centre is the origin).
    pub offset: f64,
    /// Static friction coefficient at its lower face (`inf`: no slip).
    /// The bottom block's face slides on the base when the demand reaches
    /// it; an upper face's is checked, not followed: a demand reaching it
    /// stops the run with its time and value.
    pub mu_s: f64,
    /// Kinetic friction coefficient at its lower face, as given (`None`:
    /// the static one). Acts while the base face slides; an upper face
    /// never slips, so its value is only echoed.
    pub mu_k: Option<f64>,
    /// Whether its lower face is glued (never opens: an anchored object).
    pub glued: bool,
}

impl StackBlock {
    /// A block of `width` × `height` m whose centre is `offset` m from the
    /// centre of the block below, with the config's defaults: no slip
    /// (`static = inf`) and not glued.
    pub fn new(width: f64, height: f64, offset: f64) -> Self {
        StackBlock {
            width,
            height,
            offset,
            mu_s: f64::INFINITY,
            mu_k: None,
            glued: false,
        }
    }
}

/// Whether the base face slips on the base, and which way.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Slip {
    /// The face (or its pivot) sticks to the base.
    Stuck,
    /// Sliding to the right (u' > 0).
    Right,
    /// Sliding to the left (u' < 0).
    Left,
}

impl Slip {
    /// +1 sliding right, −1 left, 0 stuck.
    pub fn sign(self) -> f64 {
        match self {
            Slip::Stuck => 0.0,
            Slip::Right => 1.0,
            Slip::Left => -1.0,
        }
    }

    /// Sliding towards the sign of `v`.
    pub fn of_sign(v: f64) -> Slip {
        if v > 0.0 { Slip::Right } else { Slip::Left }
    }
}

/// Where a contact is: which corner of an interface's overlap carries it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Contact {
    /// The whole face is down.
    Closed,
    /// Rocking on the left corner (q < 0).
    Left,
    /// Rocking on the right corner (q > 0).
    Right,
}

impl Contact {
    /// The word used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Contact::Closed => "closed",
            Contact::Left => "rock-left",
            Contact::Right => "rock-right",
        }
    }

    /// The contact rocking towards the sign of `q`.
    pub fn of_sign(q: f64) -> Contact {
        if q > 0.0 { Contact::Right } else { Contact::Left }
    }

    /// +1 for right, −1 for left, 0 closed.
    pub fn sign(self) -> f64 {
        match self {
            Contact::Closed => 0.0,
            Contact::Left => -1.0,
            Contact::Right => 1.0,
        }
    }
}
