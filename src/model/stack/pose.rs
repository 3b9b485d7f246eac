//! Where a stack's blocks are and how fast they move, from the relative
//! rotations of its interfaces (docs/model.md §18.2).
//!
//! Block j is carried by every interface at or below it: its placement is
//! `x ↦ Rot(φ_j) x + o_j` (x its point at rest), with φ_j = q_1 + … + q_j
//! and the pivot of each open interface held where the block below puts
//! it. A point x of block j moves at Σ_{i ≤ j} q_i' J(x − P_i), J the
//! clockwise quarter turn (x, y) ↦ (y, −x): each open interface turns
//! everything above it about its pivot. The base face's slip u carries
//! everything along the base: it adds (u, 0) to every position and
//! (u', 0) to every velocity.

use super::{Contact, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, StackGeometry};

/// A vector in the base frame, m (or m per τ).
pub(crate) type V2 = [f64; 2];

/// The clockwise quarter turn J: d/dφ Rot(φ) = J Rot(φ).
#[inline]
pub fn quarter(v: V2) -> V2 {
    [v[1], -v[0]]
}

#[inline]
pub(crate) fn sub(a: V2, b: V2) -> V2 {
    [a[0] - b[0], a[1] - b[1]]
}

#[inline]
pub(crate) fn dot(a: V2, b: V2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The positions and velocities of a stack's blocks and pivots.
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    /// Blocks.
    pub k: usize,
    /// Each block's rotation φ_j, rad (clockwise).
    pub phi: [f64; MAX_BLOCKS],
    /// Each block's angular velocity φ_j', rad per τ.
    pub omega: [f64; MAX_BLOCKS],
    /// cos φ_j and sin φ_j.
    cs: [[f64; 2]; MAX_BLOCKS],
    /// o_j of each block's placement.
    origin: [V2; MAX_BLOCKS],
    /// Each interface's pivot (its left corner when closed), m.
    pub pivot: [V2; MAX_BLOCKS],
    /// Each block's centre, m.
    pub centre: [V2; MAX_BLOCKS],
    /// Each block's centre's velocity, m per τ.
    pub centre_vel: [V2; MAX_BLOCKS],
    /// Each pivot's velocity (a point of the block below), m per τ.
    pub pivot_vel: [V2; MAX_BLOCKS],
    /// The interfaces' rates q_i', rad per τ.
    pub q_dot: [f64; MAX_BLOCKS],
    /// The base face's slip u, m.
    pub slide: f64,
    /// Its rate u', m per τ.
    pub slide_vel: f64,
}

impl Pose {
    /// The pose of state `y` with contacts `contacts`.
    pub fn new(geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS], y: &[f64; NS]) -> Pose {
        let mut pose = Pose {
            k: geo.k,
            phi: [0.0; MAX_BLOCKS],
            omega: [0.0; MAX_BLOCKS],
            cs: [[1.0, 0.0]; MAX_BLOCKS],
            origin: [[0.0; 2]; MAX_BLOCKS],
            pivot: [[0.0; 2]; MAX_BLOCKS],
            centre: [[0.0; 2]; MAX_BLOCKS],
            centre_vel: [[0.0; 2]; MAX_BLOCKS],
            pivot_vel: [[0.0; 2]; MAX_BLOCKS],
            q_dot: [0.0; MAX_BLOCKS],
            slide: 0.0,
            slide_vel: 0.0,
        };
        pose.fill(geo, contacts, y);
        pose
    }

    /// Makes this the pose of state `y` with contacts `contacts`, in place:
    /// the first K entries of each array are written, the rest left as
    /// they are (a pose of the same stack keeps them 0). The vector field
    /// refills one pose rather than building and copying a new one.
    pub(crate) fn fill(&mut self, geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS], y: &[f64; NS]) {
        let k = geo.blocks();
        self.k = k;
        self.slide = y[SLIDE];
        self.slide_vel = y[SLIDE_RATE];
        let (mut phi, mut omega) = (0.0, 0.0);
        for j in 0..k {
            phi += y[j];
            omega += y[MAX_BLOCKS + j];
            self.phi[j] = phi;
            self.omega[j] = omega;
            self.q_dot[j] = y[MAX_BLOCKS + j];
            // A closed face (q_j = 0) turns block j with the one below:
            // the same angle, so the same cosine and sine, bit for bit.
            self.cs[j] = if y[j] == 0.0 {
                if j == 0 { [1.0, 0.0] } else { self.cs[j - 1] }
            } else {
                [phi.cos(), phi.sin()]
            };
            let corner = geo.corners[j][usize::from(contacts[j] == Contact::Right)];
            // The pivot is a point of the block below (the base for j = 0).
            let p = if j == 0 {
                [corner[0] + self.slide, corner[1]]
            } else {
                self.place(j - 1, corner)
            };
            self.pivot[j] = p;
            let turned = self.turn(j, corner);
            self.origin[j] = sub(p, turned);
            self.centre[j] = self.place(j, geo.centre[j]);
        }
        for j in 0..k {
            self.pivot_vel[j] = if j == 0 {
                [self.slide_vel, 0.0]
            } else {
                self.velocity(j - 1, self.pivot[j])
            };
            self.centre_vel[j] = self.velocity(j, self.centre[j]);
        }
    }

    /// Rot(φ_j) x.
    #[inline]
    fn turn(&self, j: usize, x: V2) -> V2 {
        let [c, s] = self.cs[j];
        [x[0] * c + x[1] * s, -x[0] * s + x[1] * c]
    }

    /// Where block j's point `rest` (its position at rest) is now.
    #[inline]
    pub fn place(&self, j: usize, rest: V2) -> V2 {
        let t = self.turn(j, rest);
        [t[0] + self.origin[j][0], t[1] + self.origin[j][1]]
    }

    /// A direction of block j (a vector at rest) now.
    #[inline]
    pub fn direction(&self, j: usize, rest: V2) -> V2 {
        self.turn(j, rest)
    }

    /// The velocity of block j's point now at `x`.
    #[inline]
    pub fn velocity(&self, j: usize, x: V2) -> V2 {
        let mut v = [self.slide_vel, 0.0];
        for i in 0..=j {
            let qd = self.q_dot[i];
            if qd != 0.0 {
                let u = quarter(sub(x, self.pivot[i]));
                v[0] += qd * u[0];
                v[1] += qd * u[1];
            }
        }
        v
    }
}
