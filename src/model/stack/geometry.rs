//! A stack's shape at rest: each block's mass, inertia and centre, and
//! each interface's overlap (docs/model.md §18.1).

use super::{MAX_BLOCKS, StackBlock};

/// Why blocks cannot stand as a stack.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StackShapeError {
    /// Fewer than 2 or more than [`MAX_BLOCKS`] blocks.
    #[error("a stack has 2 to {MAX_BLOCKS} blocks (one block is a [block]); got {0}")]
    Count(usize),
    /// A block's face does not overlap the one below.
    #[error(
        "block {index} (from the bottom, 1-based) does not rest on the block below: its offset puts its face beside the lower block's top"
    )]
    NoOverlap {
        /// 1-based index of the block.
        index: usize,
    },
}

/// The rest shape of a stack, in the base frame (x to the right, y up,
/// origin under the bottom block's centre), lengths in m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackGeometry {
    /// Number of blocks K.
    pub k: usize,
    /// Each block's mass per unit depth and density: its area, m².
    pub mass: [f64; MAX_BLOCKS],
    /// Each block's moment of inertia about its centre, m⁴ (m (w² + h²)/12).
    pub inertia: [f64; MAX_BLOCKS],
    /// Each block's centre at rest.
    pub centre: [[f64; 2]; MAX_BLOCKS],
    /// Each interface's left and right corner at rest: the ends of the
    /// overlap of the block's lower face with what is below it.
    pub corners: [[[f64; 2]; 2]; MAX_BLOCKS],
    /// Each block's width and height, m.
    pub size: [[f64; 2]; MAX_BLOCKS],
    /// Each interface's static friction coefficient.
    pub mu_s: [f64; MAX_BLOCKS],
    /// Each interface's kinetic friction coefficient (the static one when
    /// none is given): the base face's acts while it slides.
    pub mu_k: [f64; MAX_BLOCKS],
    /// Whether each interface is glued.
    pub glued: [bool; MAX_BLOCKS],
    /// The stack's mass.
    pub total_mass: f64,
    /// The bottom block's half-diagonal R₁, m: the length unit of energies.
    pub r1: f64,
}

impl StackGeometry {
    /// The shape of `blocks`, bottom to top.
    pub fn new(blocks: &[StackBlock]) -> Result<Self, StackShapeError> {
        let k = blocks.len();
        if !(2..=MAX_BLOCKS).contains(&k) {
            return Err(StackShapeError::Count(k));
        }
        let mut geo = StackGeometry {
            k,
            mass: [0.0; MAX_BLOCKS],
            inertia: [0.0; MAX_BLOCKS],
            centre: [[0.0; 2]; MAX_BLOCKS],
            corners: [[[0.0; 2]; 2]; MAX_BLOCKS],
            size: [[0.0; 2]; MAX_BLOCKS],
            mu_s: [f64::INFINITY; MAX_BLOCKS],
            mu_k: [f64::INFINITY; MAX_BLOCKS],
            glued: [false; MAX_BLOCKS],
            total_mass: 0.0,
            r1: 0.5 * blocks[0].width.hypot(blocks[0].height),
        };
        let mut top = 0.0;
        for (j, b) in blocks.iter().enumerate() {
            let (w, h) = (b.width, b.height);
            let x = if j == 0 { 0.0 } else { geo.centre[j - 1][0] + b.offset };
            let (left, right) = if j == 0 {
                (x - 0.5 * w, x + 0.5 * w)
            } else {
                let below = geo.centre[j - 1][0];
                let half = 0.5 * geo.size[j - 1][0];
                ((x - 0.5 * w).max(below - half), (x + 0.5 * w).min(below + half))
            };
            if right <= left {
                return Err(StackShapeError::NoOverlap { index: j + 1 });
            }
            geo.mass[j] = w * h;
            geo.inertia[j] = w * h * (w * w + h * h) / 12.0;
            geo.centre[j] = [x, top + 0.5 * h];
            geo.corners[j] = [[left, top], [right, top]];
            geo.size[j] = [w, h];
            geo.mu_s[j] = b.mu_s;
            geo.mu_k[j] = b.mu_k.unwrap_or(b.mu_s);
            geo.glued[j] = b.glued;
            geo.total_mass += geo.mass[j];
            top += h;
        }
        Ok(geo)
    }

    /// K, as a bound the compiler can see (K ≤ [`MAX_BLOCKS`] by
    /// construction): loops to it index the per-block arrays without
    /// bounds checks, which the vector field runs at every evaluation.
    #[inline(always)]
    pub(crate) fn blocks(&self) -> usize {
        self.k.min(MAX_BLOCKS)
    }

    /// The mass of blocks `i..K` (what interface `i` carries).
    pub(crate) fn mass_above(&self, i: usize) -> f64 {
        self.mass[i..self.k].iter().sum()
    }

    /// Whether the base face can slide (finite friction, not glued).
    pub(crate) fn base_slides(&self) -> bool {
        self.mu_s[0].is_finite() && !self.glued[0]
    }

    /// The length of interface `i`'s overlap, m.
    pub fn span(&self, i: usize) -> f64 {
        self.corners[i][1][0] - self.corners[i][0][0]
    }
}
