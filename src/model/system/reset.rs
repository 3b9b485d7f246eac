//! The reset maps of the block: what a guard's event does to the mode and
//! the state (impact, accumulation, the simple switches), and the settling
//! of a freshly entered mode into a consistent one.

use super::{BlockSystem, EventKind, EventRecord, ModelJump, jump_to};
use crate::integrate::hybrid::Jump;
use crate::model::dynamics::{self, Tilt};
use crate::model::energy;
use crate::model::impact::{self, ImpactLaw, PreImpact};
use crate::model::mode::{Mode, Sign};
use crate::model::state::{N, THETA, THETA_DOT, X, X_DOT};

impl BlockSystem {
    /// Brings a freshly entered mode to a consistent one at the same
    /// instant: a rock mode whose friction demand exceeds the cone slips, a
    /// rest whose base lifts it rocks, a flat slide with μ_k > tan ψ tips,
    /// and so on (MODEL-DECISIONS "Modes and switches").
    pub fn settle(&mut self, mut mode: Mode, t: f64, y: &mut [f64; N]) -> Mode {
        let fo = self.model.excitation.forcing(t);
        let geo = self.model.geo;
        let (mu_s, mu_k) = (self.model.mu_s, self.model.mu_k);
        // Each pass moves to a mode the previous one ruled out; six passes
        // cover the longest chain (rest → rock → slide-rock → reversed slip).
        for _ in 0..6 {
            let next = match mode {
                Mode::Tumbled | Mode::Flight => None,
                Mode::Rest => {
                    let b = fo.b();
                    let lift = [Sign::Pos, Sign::Neg]
                        .into_iter()
                        .find(|&s| dynamics::restoring(&geo, s, fo) < 0.0);
                    let slide = mu_s.is_finite() && fo.a.abs() > mu_s * b;
                    if b <= 0.0 && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else {
                        match (lift, slide) {
                            (Some(s), true) if geo.tan_psi <= mu_s => Some(rock_from_flat(s, y)),
                            (Some(s), false) => Some(rock_from_flat(s, y)),
                            (_, true) => {
                                y[X_DOT] = 0.0;
                                Some(Mode::Slide { slip: Sign::of(-fo.a) })
                            }
                            (None, false) => None,
                        }
                    }
                }
                Mode::Slide { slip } => {
                    if fo.b() <= 0.0 && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else if mu_k > geo.tan_psi {
                        // Tips about the leading corner (docs/model.md §5).
                        y[THETA] = 0.0;
                        y[THETA_DOT] = 0.0;
                        Some(Mode::SlideRock { pivot: slip, slip })
                    } else {
                        None
                    }
                }
                Mode::Rock { pivot } => {
                    let acc = self.accel_with(mode, fo, y);
                    if acc.normal <= 0.0 && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else if y[THETA] == 0.0 && y[THETA_DOT] == 0.0 && pivot.value() * acc.theta_ddot < 0.0 {
                        Some(Mode::Rest)
                    } else if mu_s.is_finite()
                        && acc.friction.abs() > mu_s * acc.normal
                        && dynamics::slide_rock_denominator(&geo, pivot, Sign::of(-acc.friction), mu_k, y[THETA]) > 0.0
                    {
                        // (With D <= 0 slip has no unique motion, the
                        // Painlevé case: the corner stays stuck.)
                        let tilt = Tilt::new(&geo, pivot, y[THETA]);
                        y[X_DOT] = tilt.c * geo.psi * y[THETA_DOT];
                        Some(Mode::SlideRock {
                            pivot,
                            slip: Sign::of(-acc.friction),
                        })
                    } else {
                        None
                    }
                }
                Mode::SlideRock { pivot, slip } => {
                    let acc = self.accel_with(mode, fo, y);
                    if acc.normal <= 0.0 && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else if y[THETA] == 0.0 && y[THETA_DOT] == 0.0 && pivot.value() * acc.theta_ddot < 0.0 {
                        Some(Mode::Slide { slip })
                    } else {
                        let vp = dynamics::pivot_slip_velocity(&geo, pivot, y[THETA], y[THETA_DOT], y[X_DOT]);
                        if vp != 0.0 {
                            None
                        } else {
                            // Entered at zero slip: the slip must grow in
                            // direction σ, or reverse, or the corner sticks.
                            let grows = |sl: Sign| {
                                let m = Mode::SlideRock { pivot, slip: sl };
                                let a = self.accel_with(m, fo, y);
                                sl.value() * dynamics::pivot_slip_accel(&geo, pivot, y[THETA], y[THETA_DOT], &a) > 0.0
                            };
                            if grows(slip) {
                                None
                            } else if grows(slip.flip()) {
                                Some(Mode::SlideRock {
                                    pivot,
                                    slip: slip.flip(),
                                })
                            } else {
                                None
                            }
                        }
                    }
                }
            };
            match next {
                Some(m) => mode = m,
                None => return mode,
            }
        }
        mode
    }

    /// The impact reset map (docs/model.md §7) with MODEL-DECISIONS'
    /// accumulation rule.
    pub(super) fn impact(&mut self, before: Mode, pivot: Sign, t: f64, y: &[f64; N]) -> ModelJump {
        let geo = self.model.geo;
        let striking = pivot.flip();
        let w = geo.psi * y[THETA_DOT];
        let pre = PreImpact {
            striking,
            w,
            x_dot: y[X_DOT],
            y_dot: pivot.value() * geo.sin_psi * w,
        };
        let mut post = impact::apply_law(&geo, &self.model.law, &pre);
        if post.impulse.1 < 0.0 && post.slip.is_none() {
            // With infinite friction at impact, stopping a large pre-impact
            // slip can need a pulling normal impulse, which a contact cannot
            // give: the corner slips, with the block's own friction
            // (docs/model.md §7.3). Pre-impact slip needs finite friction,
            // so these coefficients are finite here.
            let e = match self.model.law {
                ImpactLaw::Impulse { e, .. } => e,
                ImpactLaw::Housner | ImpactLaw::CornerMomentum | ImpactLaw::Ratio { .. } => 0.0,
            };
            post = impact::impulse_law(&geo, &pre, e, self.model.mu_s, self.model.mu_k);
        }
        if impact::reverses(&pre, &post) {
            let (mu_s, mu_k) = match self.model.law {
                ImpactLaw::Impulse { mu_s, mu_k, .. } => (mu_s, mu_k),
                ImpactLaw::Housner | ImpactLaw::CornerMomentum | ImpactLaw::Ratio { .. } => {
                    (self.model.mu_s, self.model.mu_k)
                }
            };
            post = impact::flat_landing(&pre, mu_s, mu_k);
        }
        self.tally.impacts += 1;
        let e_before = energy::kinetic(&geo, pre.x_dot, pre.y_dot, y[THETA_DOT]);

        let mut yn = *y;
        yn[THETA] = 0.0;
        yn[THETA_DOT] = post.w / geo.psi;
        let mut mode = match post.slip {
            _ if post.flat => {
                yn[X_DOT] = post.x_dot;
                match post.slip {
                    Some(slip) if self.friction_finite() => Mode::Slide { slip },
                    _ => {
                        yn[X_DOT] = 0.0;
                        Mode::Rest
                    }
                }
            }
            Some(slip) if self.friction_finite() => {
                yn[X_DOT] = post.x_dot;
                Mode::SlideRock { pivot: striking, slip }
            }
            Some(_) | None => {
                yn[X_DOT] = geo.cos_psi * post.w;
                Mode::Rock { pivot: striking }
            }
        };
        if post.lifts_off {
            if self.stops_at_flight() {
                mode = Mode::Flight;
            } else {
                self.tally.flight_violations += 1;
            }
        }
        let mut record = EventRecord {
            tau: t,
            kind: EventKind::Impact,
            before,
            after: mode,
            theta: 0.0,
            theta_dot_before: y[THETA_DOT],
            theta_dot_after: yn[THETA_DOT],
            x_dot: yn[X_DOT],
            x: yn[X],
        };
        if mode == Mode::Flight {
            // Kinetic energy after, with the lifted-off vertical velocity,
            // which the state vector does not hold: keep it for the audit.
            yn[X_DOT] = post.x_dot;
            record.x_dot = post.x_dot;
            self.tally.lift_off_y_dot = Some(post.y_dot);
            let e_after = energy::kinetic(&geo, post.x_dot, post.y_dot, yn[THETA_DOT]);
            self.tally.impact_loss += e_before - e_after;
            return jump_to(mode, t, yn, Some(record));
        }

        if !post.flat && yn[THETA_DOT].abs() < self.model.zeno_eps {
            return self.accumulate(record, e_before, t, &pre, &post, yn);
        }
        if post.flat && yn[X_DOT].abs() < self.model.zeno_eps * geo.psi {
            // A flat landing that leaves almost no motion ends a different
            // accumulation (landing, tipping, sticking, landing …, each
            // cycle smaller): the block is put to rest, with the same
            // threshold as for rocking (|X'| ≈ ψ|Θ'| cos ψ).
            self.tally.impact_loss += e_before;
            yn[X_DOT] = 0.0;
            let mode = self.settle(Mode::Rest, t, &mut yn);
            record.kind = EventKind::Rest;
            record.after = mode;
            record.x_dot = yn[X_DOT];
            return jump_to(mode, t, yn, Some(record));
        }
        let (_, y_dot_after) = energy::height(&geo, mode, 0.0, yn[THETA_DOT]);
        let e_after = energy::kinetic(&geo, yn[X_DOT], y_dot_after, yn[THETA_DOT]);
        self.tally.impact_loss += e_before - e_after;
        let mode = self.settle(mode, t, &mut yn);
        record.after = mode;
        record.x_dot = yn[X_DOT];
        jump_to(mode, t, yn, Some(record))
    }

    /// Impact accumulation (MODEL-DECISIONS): the remaining impacts are
    /// summed in closed form (docs/model.md §10) and the block put flat.
    fn accumulate(
        &mut self,
        record: EventRecord,
        e_before: f64,
        t: f64,
        pre: &PreImpact,
        post: &impact::PostImpact,
        mut yn: [f64; N],
    ) -> ModelJump {
        let geo = self.model.geo;
        let fo = self.model.excitation.forcing(t);
        let striking = pre.striking;
        let k_next = dynamics::restoring(&geo, striking, fo);
        let k_after = dynamics::restoring(&geo, striking.flip(), fo);
        // All kinetic energy left is lost in the accumulation (the slip of
        // the corner, if any, continues as flat sliding).
        // A slip slower than the accumulation threshold (|X'| < ψ zeno_eps,
        // the rocking threshold's horizontal counterpart) is summed away
        // too: otherwise a block with μ_k > tan ψ would slide, tip and
        // accumulate again in an endless cascade of ever smaller cycles.
        let slip_velocity = match (post.slip, self.friction_finite()) {
            (Some(_), true) => post.x_dot - geo.cos_psi * post.w,
            _ => 0.0,
        };
        let slip_velocity = if slip_velocity.abs() < self.model.zeno_eps * geo.psi {
            0.0
        } else {
            slip_velocity
        };
        self.tally.impact_loss += e_before - energy::kinetic(&geo, slip_velocity, 0.0, 0.0);
        yn[THETA] = 0.0;
        yn[THETA_DOT] = 0.0;
        yn[X_DOT] = slip_velocity;
        let flat = if slip_velocity != 0.0 {
            Mode::Slide {
                slip: Sign::of(slip_velocity),
            }
        } else {
            Mode::Rest
        };
        // Without a restoring push on both sides the base lifts the block at
        // once: rocking restarts from Θ = Θ' = 0 on the side the base drives
        // it to.
        let t_acc = (k_next > 0.0 && k_after > 0.0).then(|| {
            let r = if pre.w != 0.0 { (post.w / pre.w).abs() } else { 0.0 };
            impact::accumulation_end(t, post.w.abs(), r, k_next, k_after)
        });
        let mode = self.settle(flat, t_acc.unwrap_or(t), &mut yn);
        accumulated(record, striking, t_acc, mode, yn)
    }
}

/// A one-body model (the block, the frame) that brings a freshly entered
/// mode to a consistent one; its switches other than impacts are then
/// alike.
pub(crate) trait Settles {
    /// The consistent mode `mode` leads to at `t`, `y` adjusted to it.
    fn settled(&mut self, mode: Mode, t: f64, y: &mut [f64; N]) -> Mode;

    /// A switch other than an impact: `target` (with state `yn`) settled
    /// at `t`, and its event record, `kind` corrected for what settling
    /// made of it.
    fn simple(
        &mut self,
        kind: EventKind,
        before: Mode,
        target: Mode,
        t: f64,
        y: &[f64; N],
        mut yn: [f64; N],
    ) -> ModelJump {
        let mode = self.settled(target, t, &mut yn);
        // A stick that cannot hold is a slip reversal; a slide that stops
        // is a stick even if the base then lifts the block.
        let kind = match (kind, mode) {
            (EventKind::Stick, Mode::SlideRock { .. } | Mode::Slide { .. }) => EventKind::Slip,
            (k, _) => k,
        };
        jump_to(mode, t, yn, Some(EventRecord::switch(kind, t, before, mode, y, &yn)))
    }
}

impl Settles for BlockSystem {
    fn settled(&mut self, mode: Mode, t: f64, y: &mut [f64; N]) -> Mode {
        self.settle(mode, t, y)
    }
}

/// The end of an impact accumulation begun by `impact` on corner
/// `striking`, the body put flat in `mode` with state `yn`. One summed to
/// `t_acc` records the impact and the rest there; one that ends at once
/// (the base lifts the body at the impact) records the impact as the rest.
/// The block's and the frame's.
pub(crate) fn accumulated(
    mut impact: EventRecord,
    striking: Sign,
    t_acc: Option<f64>,
    mode: Mode,
    yn: [f64; N],
) -> ModelJump {
    let Some(t_acc) = t_acc else {
        impact.kind = EventKind::Rest;
        impact.after = mode;
        impact.theta_dot_after = 0.0;
        impact.x_dot = yn[X_DOT];
        return jump_to(mode, impact.tau, yn, Some(impact));
    };
    impact.after = Mode::Rock { pivot: striking };
    let rest = EventRecord {
        tau: t_acc,
        kind: EventKind::Rest,
        before: Mode::Rock { pivot: striking },
        after: mode,
        theta: 0.0,
        theta_dot_before: impact.theta_dot_after,
        theta_dot_after: 0.0,
        x_dot: yn[X_DOT],
        x: yn[X],
    };
    Jump {
        mode,
        t: t_acc,
        y: yn,
        records: [Some(impact), Some(rest)],
    }
}

/// A flat body lifting off on the corner that uplift guard `index` names
/// (1: the right, 2: the left), from rest.
pub(crate) fn uplift(index: usize, y: &mut [f64; N]) -> Mode {
    rock_from_flat(if index == 1 { Sign::Pos } else { Sign::Neg }, y)
}

/// A flat block starting to rock about `pivot` from rest.
pub(crate) fn rock_from_flat(pivot: Sign, y: &mut [f64; N]) -> Mode {
    y[THETA] = 0.0;
    y[THETA_DOT] = 0.0;
    y[X_DOT] = 0.0;
    Mode::Rock { pivot }
}
