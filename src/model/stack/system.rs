//! A stack as a [`HybridSystem`] (docs/model.md §18.6). Guard indices of a
//! running mode, K the number of blocks:
//!
//! | index | guard | positive while |
//! |---|---|---|
//! | i < K, interface i closed | min(right, left margin) | the resultant is inside the overlap |
//! | i < K, interface i open | s_i q_i | it rocks on corner s_i (0 is an impact) |
//! | i < K, interface i glued | 1 | always |
//! | K | the run's end: min of every open interface's normal force and overturning margin and every finite-friction interface's μ_s N − \|T\| | nothing ends the run |
//! | K + 1 + j (observer) | φ_j φ_j' | block j's \|φ_j\| grows |
//! | 2K + 1 + i (observer) | q_i q_i' | interface i's opening grows |

// Interfaces and blocks are numbered: indices name them.
#![allow(clippy::needless_range_loop)]

use std::cell::{Cell, RefCell};

use super::dynamics::{self, InterfaceLoad, StackAccel, is_open};
use super::pose::{Pose, V2};
use super::{Contact, MAX_BLOCKS, NS, StackGeometry, WORK_S};
use crate::integrate::hybrid::{DriverError, HybridSystem, Jump, MAX_GUARDS};
use crate::model::dynamics::Forcing;
use crate::model::excitation::Excitation;

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
    /// How the run ended, if it did.
    pub end: Option<StackEnd>,
}

impl StackMode {
    /// Every interface closed.
    pub const REST: StackMode = StackMode {
        contacts: [Contact::Closed; MAX_BLOCKS],
        end: None,
    };

    /// Whether every interface is closed (the stack moves with the base).
    pub fn at_rest(&self, k: usize) -> bool {
        self.end.is_none() && self.contacts[..k].iter().all(|&c| c == Contact::Closed)
    }

    /// The contacts as written in outputs: `closed/rock-right/…`, bottom
    /// first.
    pub fn name(&self, k: usize) -> String {
        match self.end {
            Some(StackEnd::Overturned(_)) => "tumbled".to_string(),
            Some(StackEnd::Flight(_)) => "flight".to_string(),
            None => self.contacts[..k]
                .iter()
                .map(|c| c.name())
                .collect::<Vec<_>>()
                .join("/"),
        }
    }
}

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
}

/// A slip the model does not follow: the run stops there, as bad input
/// (the interface's `static` is below what the motion needs).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StackError {
    /// The driver failed.
    #[error("{0}")]
    Driver(#[from] DriverError),
    /// Interface `iface` needs more friction than its `static`.
    #[error(
        "stack block {block}'s lower face would slip at t = {t_s:.4} s (τ = {tau:.4}): the friction it needs, |T|/N, reaches its static = {mu} there; sliding inside a stack is not simulated (docs/model.md §18.7): raise static or set it to inf"
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
        let still = contacts[..k].iter().all(|&c| c == Contact::Closed)
            && y[..k].iter().chain(&y[MAX_BLOCKS..MAX_BLOCKS + k]).all(|&x| x == 0.0);
        if still {
            &self.rest_pose
        } else {
            slot.fill(&self.geo, contacts, y);
            slot
        }
    }

    /// The pose, accelerations and gravity at `(t, y)` with `contacts`
    /// (the pose filled in `slot` unless it is the one at rest).
    #[inline]
    fn snapshot<'a>(
        &'a self,
        contacts: &[Contact; MAX_BLOCKS],
        t: f64,
        y: &[f64; NS],
        slot: &'a mut Pose,
    ) -> Snapshot<'a> {
        let pose = self.pose_in(contacts, y, slot);
        let g_e = self.gravity(t);
        let acc = dynamics::accelerations(&self.geo, contacts, pose, g_e);
        Snapshot { pose, acc, g_e }
    }

    /// The load on interface `i` in `s`.
    fn load(&self, s: &Snapshot, i: usize) -> InterfaceLoad {
        dynamics::interface_load(&self.geo, s.pose, &s.acc, s.g_e, self.g_unit, i)
    }

    /// The loads on every interface at `(t, y)` in `mode`.
    pub fn loads(&self, mode: &StackMode, t: f64, y: &[f64; NS]) -> [InterfaceLoad; MAX_BLOCKS] {
        let mut slot = self.rest_pose;
        let s = self.snapshot(&mode.contacts, t, y, &mut slot);
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

    /// The margins whose least ends the run: which interface, what, and
    /// the value.
    fn end_margin(&self, mode: &StackMode, s: &Snapshot) -> (usize, Ending, f64) {
        let mut least = (0, Ending::None, f64::INFINITY);
        for i in 0..self.geo.k {
            if self.geo.glued[i] {
                continue;
            }
            let finite_mu = self.geo.mu_s[i].is_finite();
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
    pub fn energy_unit(&self) -> f64 {
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

    fn note_extremes(&mut self, pose: &Pose, y: &[f64; NS]) {
        for j in 0..self.geo.k {
            self.tally.max_phi[j] = self.tally.max_phi[j].max(pose.phi[j].abs());
            self.tally.max_q[j] = self.tally.max_q[j].max(y[j].abs());
        }
    }

    /// Brings `contacts` at `(t, y)` to a consistent set: a closed face
    /// whose resultant has left its overlap opens on that corner; an
    /// interface at q = q' = 0 whose acceleration would close it closes.
    pub fn settle(&self, mut contacts: [Contact; MAX_BLOCKS], t: f64, y: &mut [f64; NS]) -> [Contact; MAX_BLOCKS] {
        let k = self.geo.k;
        let tol_m = 1e-12 * self.geo.r1;
        let tol_acc = 1e-12 * self.g_unit / self.geo.r1;
        for _ in 0..(2 * k + 2) {
            let mut slot = self.rest_pose;
            let s = self.snapshot(&contacts, t, y, &mut slot);
            let mut changed = false;
            for i in 0..k {
                if self.geo.glued[i] {
                    continue;
                }
                match contacts[i] {
                    Contact::Closed => {
                        let load = self.load(&s, i);
                        let (r, l) = (load.right_margin(), load.left_margin());
                        if r.min(l) < -tol_m {
                            contacts[i] = if r < l { Contact::Right } else { Contact::Left };
                            changed = true;
                        }
                    }
                    c => {
                        if y[i] == 0.0 && y[MAX_BLOCKS + i] == 0.0 && s.acc.q_ddot[i] * c.sign() < -tol_acc {
                            contacts[i] = Contact::Closed;
                            changed = true;
                        }
                    }
                }
                if changed {
                    break;
                }
            }
            if !changed {
                break;
            }
        }
        contacts
    }

    fn running(contacts: [Contact; MAX_BLOCKS]) -> StackMode {
        StackMode { contacts, end: None }
    }

    /// A face of interface `i` opened on the corner its resultant reached.
    fn uplift(&mut self, mode: StackMode, i: usize, t: f64, y: &[f64; NS]) -> Jump<StackMode, StackEvent, NS> {
        let mut slot = self.rest_pose;
        let s = self.snapshot(&mode.contacts, t, y, &mut slot);
        let load = self.load(&s, i);
        let mut contacts = mode.contacts;
        contacts[i] = if load.right_margin() <= load.left_margin() {
            Contact::Right
        } else {
            Contact::Left
        };
        let mut y = *y;
        let contacts = self.settle(contacts, t, &mut y);
        let after = Self::running(contacts);
        self.record_jump(mode, after, StackEventKind::Uplift, i, 0.0, 0.0, t, y)
    }

    /// Interface `i` closed while open: the impulse of the impact, with
    /// every interface then at q = 0 and closing (within round-off) taking
    /// part (docs/model.md §18.5).
    fn impact(&mut self, mode: StackMode, i: usize, t: f64, y: &[f64; NS]) -> Jump<StackMode, StackEvent, NS> {
        let k = self.geo.k;
        let before = Pose::new(&self.geo, &mode.contacts, y);
        let mut y = *y;
        let q_dot_before = y[MAX_BLOCKS + i];
        let mut contacts = mode.contacts;
        let mut impacting = [false; MAX_BLOCKS];
        for j in 0..k {
            let c = mode.contacts[j];
            let hits = j == i || (c != Contact::Closed && y[j].abs() <= 1e-14 && y[MAX_BLOCKS + j] * c.sign() < 0.0);
            if hits && !self.geo.glued[j] {
                impacting[j] = true;
                y[j] = 0.0;
                contacts[j] = if c == Contact::Right {
                    Contact::Left
                } else {
                    Contact::Right
                };
            }
        }
        let mut rates = [0.0; MAX_BLOCKS];
        for _ in 0..=k {
            let at = Pose::new(&self.geo, &contacts, &y);
            rates = dynamics::impact_rates(&self.geo, &contacts, &before, &at);
            // An impacting interface that would bounce back, or move on too
            // slowly to matter, stays closed.
            let mut closed_one = false;
            for j in 0..k {
                if impacting[j] && contacts[j] != Contact::Closed {
                    let slender = (self.geo.size[j][0] / self.geo.size[j][1]).atan();
                    if rates[j] * contacts[j].sign() <= self.zeno_eps * slender {
                        contacts[j] = Contact::Closed;
                        closed_one = true;
                    }
                }
            }
            if !closed_one {
                break;
            }
        }
        y[MAX_BLOCKS..MAX_BLOCKS + k].copy_from_slice(&rates[..k]);
        let after_pose = Pose::new(&self.geo, &contacts, &y);
        let loss = dynamics::kinetic(&self.geo, &before) - dynamics::kinetic(&self.geo, &after_pose);
        self.tally.impacts += 1;
        self.tally.impact_loss += loss / self.energy_unit();
        let contacts = self.settle(contacts, t, &mut y);
        let kind = if contacts[i] == Contact::Closed {
            StackEventKind::Close
        } else {
            StackEventKind::Impact
        };
        let after = Self::running(contacts);
        self.record_jump(mode, after, kind, i, q_dot_before, y[MAX_BLOCKS + i], t, y)
    }

    #[allow(clippy::too_many_arguments)]
    fn record_jump(
        &mut self,
        before: StackMode,
        after: StackMode,
        kind: StackEventKind,
        body: usize,
        q_dot_before: f64,
        q_dot_after: f64,
        t: f64,
        y: [f64; NS],
    ) -> Jump<StackMode, StackEvent, NS> {
        let pose = Pose::new(&self.geo, &after.contacts, &y);
        self.note_extremes(&pose, &y);
        Jump {
            mode: after,
            t,
            y,
            records: [
                Some(StackEvent {
                    tau: t,
                    kind,
                    body,
                    before,
                    after,
                    q_dot_before,
                    q_dot_after,
                }),
                None,
            ],
        }
    }
}

/// Which margin ends a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ending {
    None,
    Flight,
    Overturn,
    Slip,
}

impl HybridSystem<NS> for StackSystem {
    type Mode = StackMode;
    type Record = StackEvent;
    type Error = StackError;

    /// W.
    const QUADRATURES: usize = 1;

    fn rhs(&self, mode: StackMode, t: f64, y: &[f64; NS], dy: &mut [f64; NS]) {
        *dy = [0.0; NS];
        if mode.end.is_some() {
            return;
        }
        let mut slot = self.scratch.borrow_mut();
        // The rates alone: the blocks' accelerations are for the guards.
        let pose = self.pose_in(&mode.contacts, y, &mut slot);
        let q_ddot = dynamics::rotation_rates(&self.geo, &mode.contacts, pose, self.gravity(t));
        let k = self.geo.k;
        dy[..k].copy_from_slice(&y[MAX_BLOCKS..MAX_BLOCKS + k]);
        dy[MAX_BLOCKS..MAX_BLOCKS + k].copy_from_slice(&q_ddot[..k]);
        // The base's pseudo-forces (its acceleration, not gravity) on each
        // block's centre.
        let fo = self.forcing(t);
        let pseudo = [-fo.a * self.g_unit, -fo.av * self.g_unit];
        let mut power = 0.0;
        for j in 0..k {
            let v = pose.centre_vel[j];
            power += self.geo.mass[j] * (pseudo[0] * v[0] + pseudo[1] * v[1]);
        }
        dy[WORK_S] = power / self.energy_unit();
    }

    fn guards(&self, mode: StackMode, t: f64, y: &[f64; NS], g: &mut [f64; MAX_GUARDS]) -> usize {
        if mode.end.is_some() {
            return 0;
        }
        let k = self.geo.k;
        let mut slot = self.scratch.borrow_mut();
        let s = self.snapshot(&mode.contacts, t, y, &mut slot);
        for i in 0..k {
            g[i] = if self.geo.glued[i] {
                1.0
            } else {
                match mode.contacts[i] {
                    Contact::Closed => {
                        let load = self.load(&s, i);
                        load.right_margin().min(load.left_margin()) / self.geo.r1
                    }
                    c => c.sign() * y[i],
                }
            };
        }
        let (_, ending, margin) = self.end_margin(&mode, &s);
        g[k] = if ending == Ending::None { 1.0 } else { margin };
        for index in k + 1..3 * k + 1 {
            g[index] = self.observer_guard(&mode, index, y);
        }
        3 * k + 1
    }

    fn guard(&self, mode: StackMode, index: usize, t: f64, y: &[f64; NS]) -> f64 {
        let k = self.geo.k;
        if self.guard_is_cheap(mode, index) {
            if index < k {
                return if self.geo.glued[index] {
                    1.0
                } else {
                    mode.contacts[index].sign() * y[index]
                };
            }
            return self.observer_guard(&mode, index, y);
        }
        let mut g = [0.0; MAX_GUARDS];
        self.guards(mode, t, y, &mut g);
        g[index]
    }

    /// The impact guards and the observers read the state alone.
    fn guard_is_cheap(&self, mode: StackMode, index: usize) -> bool {
        let k = self.geo.k;
        if index < k {
            self.geo.glued[index] || mode.contacts[index] != Contact::Closed
        } else {
            index > k
        }
    }

    /// The leading components of `[q_1 … q_5, q_1' … q_5', W]` each
    /// guard reads: an open face's impact guard its own q_i, an
    /// observer the q and q' at and below its block or interface, the rest
    /// every block's q and q' (not the padding beyond block K): the dense
    /// output interpolates no more, one component instead of ten at each
    /// of an impact's root iterations.
    fn guard_reads(&self, mode: StackMode, index: usize) -> usize {
        let k = self.geo.k;
        if index < k && (self.geo.glued[index] || mode.contacts[index] != Contact::Closed) {
            index + 1
        } else if index > k && index <= 2 * k {
            MAX_BLOCKS + index - k
        } else if index > 2 * k {
            MAX_BLOCKS + index - 2 * k
        } else {
            MAX_BLOCKS + k
        }
    }

    fn is_observer(&self, _mode: StackMode, index: usize) -> bool {
        index > self.geo.k
    }

    fn observe(&mut self, mode: StackMode, _index: usize, _t: f64, y: &[f64; NS]) {
        let pose = Pose::new(&self.geo, &mode.contacts, y);
        self.note_extremes(&pose, y);
    }

    fn jump(
        &mut self,
        mode: StackMode,
        index: usize,
        t: f64,
        y: &[f64; NS],
    ) -> Result<Jump<StackMode, StackEvent, NS>, StackError> {
        let k = self.geo.k;
        if index < k {
            return Ok(if mode.contacts[index] == Contact::Closed {
                self.uplift(mode, index, t, y)
            } else {
                self.impact(mode, index, t, y)
            });
        }
        let mut slot = self.rest_pose;
        let s = self.snapshot(&mode.contacts, t, y, &mut slot);
        let (i, ending, _) = self.end_margin(&mode, &s);
        let (end, kind) = match ending {
            Ending::Slip => {
                let load = self.load(&s, i);
                // τ = p t with p² = g/G (G = g/p², the gravity unit).
                let p = (crate::model::geometry::G / self.g_unit).sqrt();
                return Err(StackError::Slip {
                    block: i + 1,
                    tau: t,
                    t_s: t / p,
                    demand: load.tangential.abs() / load.normal,
                    mu: self.geo.mu_s[i],
                });
            }
            Ending::Flight => (StackEnd::Flight(i), StackEventKind::Flight),
            Ending::Overturn | Ending::None => (StackEnd::Overturned(i), StackEventKind::Overturn),
        };
        let after = StackMode {
            contacts: mode.contacts,
            end: Some(end),
        };
        let q_dot = y[MAX_BLOCKS + i];
        Ok(self.record_jump(mode, after, kind, i, q_dot, q_dot, t, *y))
    }

    fn is_terminal(&self, mode: StackMode) -> bool {
        mode.end.is_some()
    }

    fn next_breakpoint(&self, t: f64) -> Option<f64> {
        self.excitation.next_breakpoint(t)
    }

    fn time_scale(&self) -> f64 {
        self.excitation.time_scale()
    }

    fn step_cap(&self, mode: StackMode) -> f64 {
        if mode.at_rest(self.geo.k) {
            self.excitation.time_scale()
        } else {
            f64::INFINITY
        }
    }
}
