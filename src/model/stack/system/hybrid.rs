//! The stack's [`HybridSystem`]: its vector field, its guards (indexed as the module doc's table) and its jumps.

use super::{Ending, StackEnd, StackError, StackEvent, StackEventKind, StackMode, StackSystem};
use crate::integrate::hybrid::{HybridSystem, Jump, MAX_GUARDS};
use crate::model::stack::dynamics;
use crate::model::stack::pose::Pose;
use crate::model::stack::{Contact, FRICTION_S, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, WORK_S};

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
