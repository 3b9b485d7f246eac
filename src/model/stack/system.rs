//! A stack as a [`HybridSystem`] (docs/model.md §18.6). Guard indices of a
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
use super::{Contact, FRICTION_S, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, Slip, StackGeometry, WORK_S};
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

    /// Brings `mode` at `(t, y)` to a consistent set of contacts: a closed
    /// face whose resultant has left its overlap opens on that corner; an
    /// interface at q = q' = 0 whose acceleration would close it closes; a
    /// stuck base face that needs more than its static friction slides.
    pub fn settle(&self, mut mode: StackMode, t: f64, y: &mut [f64; NS]) -> StackMode {
        let k = self.geo.k;
        let tol_m = 1e-12 * self.geo.r1;
        let tol_acc = 1e-12 * self.g_unit / self.geo.r1;
        for _ in 0..(2 * k + 3) {
            let mut slot = self.rest_pose;
            let s = self.snapshot(&mode, t, y, &mut slot);
            let mut changed = false;
            for i in 0..k {
                if self.geo.glued[i] {
                    continue;
                }
                match mode.contacts[i] {
                    Contact::Closed => {
                        let load = self.load(&s, i);
                        let (r, l) = (load.right_margin(), load.left_margin());
                        if r.min(l) < -tol_m {
                            mode.contacts[i] = if r < l { Contact::Right } else { Contact::Left };
                            changed = true;
                        }
                    }
                    c => {
                        if y[i] == 0.0 && y[MAX_BLOCKS + i] == 0.0 && s.acc.q_ddot[i] * c.sign() < -tol_acc {
                            mode.contacts[i] = Contact::Closed;
                            changed = true;
                        }
                    }
                }
                if changed {
                    break;
                }
            }
            if !changed && let Some(slip) = self.base_slips(&mode, &s, 1e-12) {
                mode.slip = slip;
                changed = true;
            }
            if !changed {
                break;
            }
        }
        mode
    }

    /// A face of interface `i` opened on the corner its resultant reached.
    fn uplift(&mut self, mode: StackMode, i: usize, t: f64, y: &[f64; NS]) -> Jump<StackMode, StackEvent, NS> {
        let mut slot = self.rest_pose;
        let s = self.snapshot(&mode, t, y, &mut slot);
        let load = self.load(&s, i);
        let mut after = mode;
        after.contacts[i] = if load.right_margin() <= load.left_margin() {
            Contact::Right
        } else {
            Contact::Left
        };
        let mut y = *y;
        let after = self.settle(after, t, &mut y);
        self.record_jump(mode, after, StackEventKind::Uplift, i, 0.0, 0.0, t, y)
    }

    /// Interface `i` closed while open: the impulse of the impact, with
    /// every interface then at q = 0 and closing (within round-off) taking
    /// part (docs/model.md §18.5), and the base face's friction through it
    /// (§18.7).
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
        // A slip goes on through an impact above the base; an impact at
        // the base stops it unless its new pivot cannot hold.
        let carried = if impacting[0] { Slip::Stuck } else { mode.slip };
        let (mut slip, mut rates, mut slide_rate);
        loop {
            (slip, rates, slide_rate) = self.impact_slip(&contacts, carried, &before, &y);
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
        y[SLIDE_RATE] = slide_rate;
        let after_pose = Pose::new(&self.geo, &contacts, &y);
        let loss = dynamics::kinetic(&self.geo, &before) - dynamics::kinetic(&self.geo, &after_pose);
        self.tally.impacts += 1;
        self.tally.impact_loss += loss / self.energy_unit();
        let after = self.settle(
            StackMode {
                contacts,
                slip,
                end: None,
            },
            t,
            &mut y,
        );
        let kind = if after.contacts[i] == Contact::Closed {
            StackEventKind::Close
        } else {
            StackEventKind::Impact
        };
        self.record_jump(mode, after, kind, i, q_dot_before, y[MAX_BLOCKS + i], t, y)
    }

    /// The base face's friction through an impact into `contacts`, from
    /// the pose `before` at the impact's positions `y`: the slip after it,
    /// the interface rates and the slip rate. The single block's rules,
    /// carried over (docs/model.md §7.3, §7.5, §18.7):
    /// - a slip `carried` through the impact goes on if its friction
    ///   impulse, −s μ_k times the normal one, leaves it moving the same way;
    /// - else the base sticks: a pivot (the base rocking) holds unless the
    ///   sticking impulse would pull it off the base, a closed face (a
    ///   landing flat on the base) holds while its impulse lies within
    ///   the static cone |P_T| ≤ μ_s P_N;
    /// - if it cannot hold, it slips against the impulse it would need,
    ///   in the first sense whose slip after is consistent.
    fn impact_slip(
        &self,
        contacts: &[Contact; MAX_BLOCKS],
        carried: Slip,
        before: &Pose,
        y: &[f64; NS],
    ) -> (Slip, [f64; MAX_BLOCKS], f64) {
        let at = Pose::new(&self.geo, contacts, y);
        let solve = |slip: Slip| {
            let friction = (slip != Slip::Stuck).then(|| slip.sign() * self.geo.mu_k[0]);
            dynamics::impact_rates(&self.geo, contacts, friction, before, &at)
        };
        if carried != Slip::Stuck {
            let (rates, u) = solve(carried);
            if u * carried.sign() > 0.0 {
                return (carried, rates, u);
            }
        }
        let (rates, _) = solve(Slip::Stuck);
        if !self.geo.base_slides() {
            return (Slip::Stuck, rates, 0.0);
        }
        // The base's impulse: the stack's change of momentum.
        let mut after = *y;
        after[MAX_BLOCKS..MAX_BLOCKS + self.geo.k].copy_from_slice(&rates[..self.geo.k]);
        after[SLIDE_RATE] = 0.0;
        let stuck = Pose::new(&self.geo, contacts, &after);
        let (mut pt, mut pn) = (0.0, 0.0);
        for j in 0..self.geo.k {
            let v = before.centre_vel[j];
            pt += self.geo.mass[j] * (stuck.centre_vel[j][0] - v[0]);
            pn += self.geo.mass[j] * (stuck.centre_vel[j][1] - v[1]);
        }
        // An impulse at round-off against the stack's momentum scale
        // M √(G R₁) (the end of an accumulation of impacts) holds: its sign
        // is noise.
        let tol = 1e-12 * self.geo.total_mass * (self.g_unit * self.geo.r1).sqrt();
        let holds = if contacts[0] == Contact::Closed {
            pt.abs() <= self.geo.mu_s[0] * pn + tol
        } else {
            pn >= -tol
        };
        if holds {
            return (Slip::Stuck, rates, 0.0);
        }
        let first = Slip::of_sign(-pt);
        let second = if first == Slip::Right { Slip::Left } else { Slip::Right };
        for slip in [first, second] {
            let (r, u) = solve(slip);
            if u * slip.sign() >= 0.0 {
                return if u == 0.0 { (Slip::Stuck, r, 0.0) } else { (slip, r, u) };
            }
        }
        (Slip::Stuck, rates, 0.0)
    }

    /// The base face's friction switches at `(t, y)`: at the `onset` of a
    /// slip (its stuck friction demand reached its static) it slides
    /// against the force it would need; when a slip stops (u' = 0) it
    /// sticks if its static friction can hold it, else it slides back.
    fn base_switch(
        &mut self,
        mode: StackMode,
        t: f64,
        y: &[f64; NS],
        onset: bool,
    ) -> Result<Jump<StackMode, StackEvent, NS>, StackError> {
        let mut y = *y;
        y[SLIDE_RATE] = 0.0;
        let stuck = StackMode {
            slip: Slip::Stuck,
            ..mode
        };
        let mut slot = self.rest_pose;
        let s = self.snapshot(&stuck, t, &y, &mut slot);
        let load = self.load(&s, 0);
        let mut after = stuck;
        let mut kind = StackEventKind::Stick;
        if onset || self.slip_margin(&load, 0) < 0.0 {
            after.slip = Slip::of_sign(-load.tangential);
            kind = StackEventKind::Slip;
            let mut slot = self.rest_pose;
            let d = self.snapshot(&after, t, &y, &mut slot).acc.painleve;
            if d <= 0.0 {
                return Err(self.painleve(t));
            }
        }
        let after = self.settle(after, t, &mut y);
        let q_dot = y[MAX_BLOCKS];
        Ok(self.record_jump(mode, after, kind, 0, q_dot, q_dot, t, y))
    }

    /// The Painlevé error at τ = `t`.
    fn painleve(&self, t: f64) -> StackError {
        StackError::Painleve {
            tau: t,
            t_s: t / self.p(),
            mu: self.geo.mu_k[0],
        }
    }

    /// p, 1/s: τ = p t with p² = g/G (G = g/p², the gravity unit).
    fn p(&self) -> f64 {
        (crate::model::geometry::G / self.g_unit).sqrt()
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
    Painleve,
}

impl HybridSystem<NS> for StackSystem {
    type Mode = StackMode;
    type Record = StackEvent;
    type Error = StackError;

    /// W and D.
    const QUADRATURES: usize = 2;

    fn rhs(&self, mode: StackMode, t: f64, y: &[f64; NS], dy: &mut [f64; NS]) {
        *dy = [0.0; NS];
        if mode.end.is_some() {
            return;
        }
        let mut slot = self.scratch.borrow_mut();
        // The rates alone: the blocks' accelerations are for the guards.
        let pose = self.pose_in(&mode.contacts, y, &mut slot);
        let friction = self.friction(&mode);
        let rates = dynamics::rotation_rates(&self.geo, &mode.contacts, friction, pose, self.gravity(t));
        let k = self.geo.k;
        dy[..k].copy_from_slice(&y[MAX_BLOCKS..MAX_BLOCKS + k]);
        dy[MAX_BLOCKS..MAX_BLOCKS + k].copy_from_slice(&rates.q_ddot[..k]);
        if friction.is_some() {
            dy[SLIDE] = y[SLIDE_RATE];
            dy[SLIDE_RATE] = rates.slide_acc;
            // Friction's power against the slip: μ_k N |u'|, written s μ_k N u'
            // with the mode's direction s: the same while the mode holds, and
            // smooth in the stages of a step that overshoots the slip's stop
            // (|u'| there put a kink in D's dense output before the stop was
            // located: 2·10⁻⁶ of the energy after 200 s of stick–slip).
            dy[FRICTION_S] = self.geo.mu_k[0] * rates.normal * mode.slip.sign() * y[SLIDE_RATE] / self.energy_unit();
        }
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

    /// At rest with the base: every face closed, the base face stuck and
    /// no rate left (each closed face's rate and the slip's are zero), so
    /// `rhs` writes zeros: the accelerations of a stack without a free
    /// coordinate, and no power, as nothing moves relative to the base.
    fn is_still(&self, mode: StackMode, y: &[f64; NS]) -> bool {
        let k = self.geo.k;
        mode.at_rest(k) && y[SLIDE_RATE] == 0.0 && y[MAX_BLOCKS..MAX_BLOCKS + k].iter().all(|&v| v == 0.0)
    }

    fn guards(&self, mode: StackMode, t: f64, y: &[f64; NS], g: &mut [f64; MAX_GUARDS]) -> usize {
        if mode.end.is_some() {
            return 0;
        }
        let k = self.geo.k;
        let mut slot = self.scratch.borrow_mut();
        let s = self.snapshot(&mode, t, y, &mut slot);
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
        g[3 * k + 1] = self.slide_guard(&mode, y);
        3 * k + 2
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
            if index == 3 * k + 1 {
                return self.slide_guard(&mode, y);
            }
            return self.observer_guard(&mode, index, y);
        }
        let mut g = [0.0; MAX_GUARDS];
        self.guards(mode, t, y, &mut g);
        g[index]
    }

    /// The impact guards, the observers and the slip's guard read the
    /// state alone.
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
        } else if index == 3 * k + 1 {
            SLIDE_RATE + 1
        } else if index > 2 * k {
            MAX_BLOCKS + index - 2 * k
        } else {
            MAX_BLOCKS + k
        }
    }

    fn is_observer(&self, _mode: StackMode, index: usize) -> bool {
        index > self.geo.k && index <= 3 * self.geo.k
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
        if index == 3 * k + 1 {
            return self.base_switch(mode, t, y, false);
        }
        let mut slot = self.rest_pose;
        let s = self.snapshot(&mode, t, y, &mut slot);
        let (i, ending, _) = self.end_margin(&mode, &s);
        let (end, kind) = match ending {
            Ending::Slip if i == 0 => return self.base_switch(mode, t, y, true),
            Ending::Slip => {
                let load = self.load(&s, i);
                return Err(StackError::Slip {
                    block: i + 1,
                    tau: t,
                    t_s: t / self.p(),
                    demand: load.tangential.abs() / load.normal,
                    mu: self.geo.mu_s[i],
                });
            }
            Ending::Painleve => return Err(self.painleve(t)),
            Ending::Flight => (StackEnd::Flight(i), StackEventKind::Flight),
            Ending::Overturn | Ending::None => (StackEnd::Overturned(i), StackEventKind::Overturn),
        };
        let after = StackMode { end: Some(end), ..mode };
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
