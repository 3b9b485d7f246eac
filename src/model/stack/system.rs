//! A stack as a [`HybridSystem`](crate::integrate::hybrid::HybridSystem) (docs/model.md §18.6). Guard indices of a
//! running mode, K the number of blocks:
//!
//! | index | guard | positive while |
//! |---|---|---|
//! | i < K, interface i closed | min(right, left margin) | the resultant is inside the overlap |
//! | i < K, interface i open | s_i q_i | it rocks on corner s_i (0 is an impact) |
//! | i < K, interface i glued | 1 | always |
//! | K | the run's end: min of every open interface's normal force and overturning margin, every finite-friction interface's μ_s N − \|T\| (the base's only while it sticks: there it starts a slip) and, while the base slides, the Painlevé ratio D | nothing ends the run |
//! | K + 1 + j (observer) | φ_j φ_j' | block j's \|φ_j\| grows |
//! | 2K + 1 + i (observer) | q_i q_i' | interface i's opening grows |
//! | 3K + 1 | s u' while the base slides with sense s, else 1 | it slides on |

// Interfaces and blocks are numbered: indices name them.
#![allow(clippy::needless_range_loop)]

use std::cell::{Cell, RefCell};

use super::dynamics::{self, InterfaceLoad, StackAccel, is_open};
use super::pose::{Pose, V2};
use super::{Contact, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, Slip, StackGeometry};
use crate::model::dynamics::Forcing;
use crate::model::excitation::Excitation;

mod error;
mod event;
mod hybrid;
mod jumps;

pub use error::StackError;
pub use event::{StackEvent, StackEventKind};

/// How a stack's run ended early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StackEnd {
    /// Everything above interface `i` passed over its pivot: block `i`
    /// (and what it carries) overturned.
    Overturned(usize),
    /// Block `i` lost contact with what is below it.
    Flight(usize),
}

impl StackEnd {
    /// The block whose lower face it happened at (0 = bottom).
    pub fn body(self) -> usize {
        match self {
            StackEnd::Overturned(i) | StackEnd::Flight(i) => i,
        }
    }
}

/// A stack's discrete state: each interface's contact, or how it ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackMode {
    /// Each interface's contact (unused entries closed).
    pub contacts: [Contact; MAX_BLOCKS],
    /// Whether the base face slides on the base.
    pub slip: Slip,
    /// How the run ended, if it did.
    pub end: Option<StackEnd>,
}

impl StackMode {
    /// Every interface closed.
    pub const REST: StackMode = StackMode {
        contacts: [Contact::Closed; MAX_BLOCKS],
        slip: Slip::Stuck,
        end: None,
    };

    /// A running mode with `contacts`, the base stuck.
    pub fn stuck(contacts: [Contact; MAX_BLOCKS]) -> StackMode {
        StackMode {
            contacts,
            slip: Slip::Stuck,
            end: None,
        }
    }

    /// Whether every interface is closed and the base face sticks (the
    /// stack moves with the base).
    pub fn at_rest(&self, k: usize) -> bool {
        self.end.is_none() && self.slip == Slip::Stuck && self.contacts[..k].iter().all(|&c| c == Contact::Closed)
    }

    /// Whether the base face slides.
    pub fn sliding(&self) -> bool {
        self.slip != Slip::Stuck
    }

    /// The contacts as written in outputs: `closed/rock-right/…`, bottom
    /// first; a sliding base face reads `slide` (closed) or
    /// `slide-rock-left`/`slide-rock-right`, as the single block's modes.
    pub fn name(&self, k: usize) -> String {
        match self.end {
            Some(StackEnd::Overturned(_)) => "tumbled".to_string(),
            Some(StackEnd::Flight(_)) => "flight".to_string(),
            None => self.contacts[..k]
                .iter()
                .enumerate()
                .map(|(i, c)| match (i, self.slip, c) {
                    (0, Slip::Stuck, c) | (1.., _, c) => c.name(),
                    (0, _, Contact::Closed) => "slide",
                    (0, _, Contact::Left) => "slide-rock-left",
                    (0, _, Contact::Right) => "slide-rock-right",
                })
                .collect::<Vec<_>>()
                .join("/"),
        }
    }
}

/// What a stack's run tallied.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StackTally {
    /// Impacts (at any interface).
    pub impacts: u64,
    /// Kinetic energy lost at impacts, per M G R₁.
    pub impact_loss: f64,
    /// Each block's largest |φ_j|, rad.
    pub max_phi: [f64; MAX_BLOCKS],
    /// Each interface's largest |q_i|, rad.
    pub max_q: [f64; MAX_BLOCKS],
    /// The largest |u|, the base face's slip, m.
    pub max_slide: f64,
}

/// A stack of blocks on the moving base.
#[derive(Clone, Debug)]
pub struct StackSystem {
    /// Its shape.
    pub geo: StackGeometry,
    /// The base motion, in the bottom block's τ.
    pub excitation: Excitation,
    /// Post-impact |q'| below which an interface closes, per the block's
    /// slenderness (as the single block's `run.zeno_eps` on Θ').
    pub zeno_eps: f64,
    /// Tallies.
    pub tally: StackTally,
    /// g/p², m per τ² (= 4R₁/3).
    g_unit: f64,
    /// The forcing at the last evaluation.
    last_forcing: Cell<(f64, Forcing)>,
    /// The pose at rest (every q and q' zero; the pivots do not matter).
    rest_pose: Pose,
    /// The vector field's and the guards' pose, refilled in place at each
    /// evaluation (neither calls the other while it holds it).
    scratch: RefCell<Pose>,
}

/// Everything the guards of one state read.
struct Snapshot<'a> {
    pose: &'a Pose,
    acc: StackAccel,
    g_e: V2,
}

impl StackSystem {
    /// A stack of shape `geo` under `excitation`.
    pub fn new(geo: StackGeometry, excitation: Excitation, zeno_eps: f64) -> Self {
        StackSystem {
            rest_pose: Pose::new(&geo, &[Contact::Closed; MAX_BLOCKS], &[0.0; NS]),
            scratch: RefCell::new(Pose::new(&geo, &[Contact::Closed; MAX_BLOCKS], &[0.0; NS])),
            g_unit: 4.0 * geo.r1 / 3.0,
            geo,
            excitation,
            zeno_eps,
            tally: StackTally::default(),
            last_forcing: Cell::new((f64::NAN, Forcing { a: 0.0, av: 0.0 })),
        }
    }

    /// g/p², m per τ²: gravity in the stack's units.
    pub fn g_unit(&self) -> f64 {
        self.g_unit
    }

    fn forcing(&self, t: f64) -> Forcing {
        let (tl, fl) = self.last_forcing.get();
        if tl.to_bits() == t.to_bits() {
            return fl;
        }
        let fo = self.excitation.forcing(t);
        self.last_forcing.set((t, fo));
        fo
    }

    /// The effective gravity in the base frame at τ = `t`, m per τ².
    pub fn gravity(&self, t: f64) -> V2 {
        let fo = self.forcing(t);
        [-fo.a * self.g_unit, -(1.0 + fo.av) * self.g_unit]
    }

    /// The pose of `y` with `contacts`: the one kept at rest, or `slot`
    /// refilled (a pose of this stack). Borrowed, not returned: a pose is
    /// 600 bytes, and building and copying one at every evaluation cost a
    /// tenth of a stack's run.
    #[inline]
    fn pose_in<'a>(&'a self, contacts: &[Contact; MAX_BLOCKS], y: &[f64; NS], slot: &'a mut Pose) -> &'a Pose {
        // At rest (most of a record) the pose is the one at rest. Not for
        // an open face at q = 0: its pivot decides its partial velocities.
        let k = self.geo.k;
        // The slip u only translates the stack, which moves nothing the
        // callers read (they take differences of positions).
        let still = contacts[..k].iter().all(|&c| c == Contact::Closed)
            && y[SLIDE_RATE] == 0.0
            && y[..k].iter().chain(&y[MAX_BLOCKS..MAX_BLOCKS + k]).all(|&x| x == 0.0);
        if still {
            &self.rest_pose
        } else {
            slot.fill(&self.geo, contacts, y);
            slot
        }
    }

    /// s μ_k while `mode`'s base face slides.
    #[inline]
    fn friction(&self, mode: &StackMode) -> Option<f64> {
        mode.sliding().then(|| mode.slip.sign() * self.geo.mu_k[0])
    }

    /// The pose, accelerations and gravity at `(t, y)` in `mode` (the pose
    /// filled in `slot` unless it is the one at rest).
    #[inline]
    fn snapshot<'a>(&'a self, mode: &StackMode, t: f64, y: &[f64; NS], slot: &'a mut Pose) -> Snapshot<'a> {
        let pose = self.pose_in(&mode.contacts, y, slot);
        let g_e = self.gravity(t);
        let acc = dynamics::accelerations(&self.geo, &mode.contacts, self.friction(mode), pose, g_e);
        Snapshot { pose, acc, g_e }
    }

    /// The load on interface `i` in `s`.
    fn load(&self, s: &Snapshot, i: usize) -> InterfaceLoad {
        dynamics::interface_load(&self.geo, s.pose, &s.acc, s.g_e, self.g_unit, i)
    }

    /// The loads on every interface at `(t, y)` in `mode`.
    pub fn loads(&self, mode: &StackMode, t: f64, y: &[f64; NS]) -> [InterfaceLoad; MAX_BLOCKS] {
        let mut slot = self.rest_pose;
        let s = self.snapshot(mode, t, y, &mut slot);
        let mut out = [InterfaceLoad {
            normal: 0.0,
            tangential: 0.0,
            about_left: 0.0,
            about_right: 0.0,
        }; MAX_BLOCKS];
        for (i, o) in out.iter_mut().enumerate().take(self.geo.k) {
            *o = self.load(&s, i);
        }
        out
    }

    /// How far interface `i`'s carried blocks are from passing over its
    /// pivot (m, horizontal in the base frame; ≤ 0: overturned).
    fn overturn_margin(&self, pose: &Pose, contact: Contact, i: usize) -> f64 {
        let mut moment = 0.0;
        for j in i..self.geo.k {
            moment += self.geo.mass[j] * (pose.centre[j][0] - pose.pivot[i][0]);
        }
        -contact.sign() * moment / self.geo.mass_above(i)
    }

    /// Interface `i`'s slip margin μ_s N − |T| (per weight), +∞ when it
    /// cannot slip.
    fn slip_margin(&self, load: &InterfaceLoad, i: usize) -> f64 {
        let mu = self.geo.mu_s[i];
        if self.geo.glued[i] || mu.is_infinite() {
            f64::INFINITY
        } else {
            mu * load.normal - load.tangential.abs()
        }
    }

    /// The margins whose least ends the run (or starts the base's slip):
    /// which interface, what, and the value.
    fn end_margin(&self, mode: &StackMode, s: &Snapshot) -> (usize, Ending, f64) {
        let mut least = (0, Ending::None, f64::INFINITY);
        if mode.sliding() {
            least = (0, Ending::Painleve, s.acc.painleve);
        }
        for i in 0..self.geo.k {
            if self.geo.glued[i] {
                continue;
            }
            // A sliding base face has no static margin: its slip stops on
            // its own guard.
            let finite_mu = self.geo.mu_s[i].is_finite() && !(i == 0 && mode.sliding());
            let open = is_open(&self.geo, &mode.contacts, i);
            if !open && !finite_mu {
                continue;
            }
            let load = self.load(s, i);
            let mut consider = |what: Ending, v: f64| {
                if v < least.2 {
                    least = (i, what, v);
                }
            };
            if open {
                consider(Ending::Flight, load.normal);
                consider(
                    Ending::Overturn,
                    self.overturn_margin(s.pose, mode.contacts[i], i) / self.geo.r1,
                );
            }
            if finite_mu {
                consider(Ending::Slip, self.slip_margin(&load, i));
            }
        }
        least
    }

    /// Kinetic plus potential energy of `(mode, y)`, per M G R₁.
    pub fn energy(&self, mode: &StackMode, y: &[f64; NS]) -> f64 {
        let pose = Pose::new(&self.geo, &mode.contacts, y);
        (dynamics::kinetic(&self.geo, &pose) + dynamics::potential(&self.geo, &pose, self.g_unit)) / self.energy_unit()
    }

    /// M G R₁, the energy unit.
    pub(crate) fn energy_unit(&self) -> f64 {
        self.geo.total_mass * self.g_unit * self.geo.r1
    }

    /// The pose of `(mode, y)`.
    pub fn pose(&self, mode: &StackMode, y: &[f64; NS]) -> Pose {
        Pose::new(&self.geo, &mode.contacts, y)
    }

    /// Observer `index` (> K): φ_j φ_j' for block j, q_i q_i' for
    /// interface i; 1 where the block or interface cannot turn in `mode`
    /// (every interface at or below it shut), so a stack at rest has no
    /// guard sitting at 0 for the driver to sample.
    fn observer_guard(&self, mode: &StackMode, index: usize, y: &[f64; NS]) -> f64 {
        let k = self.geo.k;
        let open = |i: usize| is_open(&self.geo, &mode.contacts, i);
        if index <= 2 * k {
            let j = index - k - 1;
            if !(0..=j).any(open) {
                return 1.0;
            }
            let (phi, omega) = (0..=j).fold((0.0, 0.0), |(p, w), i| (p + y[i], w + y[MAX_BLOCKS + i]));
            phi * omega
        } else {
            let i = index - 2 * k - 1;
            if !open(i) {
                return 1.0;
            }
            y[i] * y[MAX_BLOCKS + i]
        }
    }

    /// The slip's guard: s u' while the base face slides with sense s
    /// (0: the slip stops), 1 while it sticks.
    fn slide_guard(&self, mode: &StackMode, y: &[f64; NS]) -> f64 {
        if mode.sliding() {
            mode.slip.sign() * y[SLIDE_RATE]
        } else {
            1.0
        }
    }

    fn note_extremes(&mut self, pose: &Pose, y: &[f64; NS]) {
        for j in 0..self.geo.k {
            self.tally.max_phi[j] = self.tally.max_phi[j].max(pose.phi[j].abs());
            self.tally.max_q[j] = self.tally.max_q[j].max(y[j].abs());
        }
        self.tally.max_slide = self.tally.max_slide.max(y[SLIDE].abs());
    }

    /// Whether the base face, stuck in `mode` at `s`, needs more friction
    /// than its `static` (beyond `tol`, per weight); if so, the sense it
    /// slides in: against the tangential force it would need.
    fn base_slips(&self, mode: &StackMode, s: &Snapshot, tol: f64) -> Option<Slip> {
        if mode.sliding() || !self.geo.base_slides() {
            return None;
        }
        let load = self.load(s, 0);
        (self.slip_margin(&load, 0) < -tol).then(|| Slip::of_sign(-load.tangential))
    }
}

/// Which margin ends a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ending {
    None,
    Flight,
    Overturn,
    Slip,
    Painleve,
}
