//! A stack's jumps: settling the contacts, an uplift, an impact with the base face's friction through it, and the base face's slip and stick.

use super::{StackError, StackEvent, StackEventKind, StackMode, StackSystem};
use crate::integrate::hybrid::Jump;
use crate::model::stack::dynamics;
use crate::model::stack::pose::Pose;
use crate::model::stack::{Contact, MAX_BLOCKS, NS, SLIDE_RATE, Slip};

impl StackSystem {
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
    pub(super) fn uplift(
        &mut self,
        mode: StackMode,
        i: usize,
        t: f64,
        y: &[f64; NS],
    ) -> Jump<StackMode, StackEvent, NS> {
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
    pub(super) fn impact(
        &mut self,
        mode: StackMode,
        i: usize,
        t: f64,
        y: &[f64; NS],
    ) -> Jump<StackMode, StackEvent, NS> {
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
    pub(super) fn base_switch(
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
    pub(super) fn painleve(&self, t: f64) -> StackError {
        StackError::Painleve {
            tau: t,
            t_s: t / self.p(),
            mu: self.geo.mu_k[0],
        }
    }

    /// p, 1/s: τ = p t with p² = g/G (G = g/p², the gravity unit).
    pub(super) fn p(&self) -> f64 {
        (crate::model::geometry::G / self.g_unit).sqrt()
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn record_jump(
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
