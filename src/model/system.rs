//! The block as a hybrid system: vector field per mode, guards, reset maps.
//!
//! State `y = [Θ, Θ', X, X', W, D]`: the normalised angle and angular
//! velocity, the horizontal position and velocity of the centre of mass
//! (relative to the base, per R), and two quadratures for the energy audit:
//! `W`, the work done by the base's pseudo-forces, and `D`, the energy
//! dissipated by sliding friction (both per m g R).
//!
//! Guard indices per mode (each guard is positive inside the mode):
//!
//! | mode | 0 | 1 | 2 | 3 | 4 | 5 |
//! |---|---|---|---|---|---|---|
//! | rest | flight b | uplift right κ₊ | uplift left κ₋ | slide +x μ_s b + a | slide −x μ_s b − a | |
//! | slide σ | stick σX' | flight b | | | | |
//! | rock s | impact sΘ | tumble Θ_t − sΘ | flight n | extremum sΘ' (observer) | slip μ_s n − sf | slip μ_s n + sf |
//! | slide-rock s,σ | impact sΘ | tumble Θ_t − sΘ | flight n | extremum sΘ' (observer) | stick σX_p' | |
//!
//! Slide guards exist only with finite friction. With `flight = ignore` the
//! flight guard only counts violations.

use std::cell::Cell;

use super::dynamics::{self, Accel, Forcing, Tilt};
use super::energy;
use super::excitation::Excitation;
use super::geometry::Geometry;
use super::impact::{self, ImpactLaw, PreImpact};
use super::mode::{Mode, Sign};
use crate::integrate::hybrid::{DriverError, HybridSystem, Jump, MAX_GUARDS};

/// Length of the state vector.
pub const N: usize = 6;
/// Index of Θ in the state.
pub const THETA: usize = 0;
/// Index of Θ'.
pub const THETA_DOT: usize = 1;
/// Index of X.
pub const X: usize = 2;
/// Index of X'.
pub const X_DOT: usize = 3;
/// Index of the base work W.
pub const WORK: usize = 4;
/// Index of the friction dissipation D.
pub const FRICTION_LOSS: usize = 5;

/// What happens when the normal force vanishes (MODEL-DECISIONS "Flight").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlightPolicy {
    /// Stop the run and report flight (default).
    Stop,
    /// Keep integrating the grounded equations, as the paper did, and count
    /// the violations.
    Ignore,
}

/// Kind of event, as written in `events.csv`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// A corner leaves the base (rest/slide → rock/slide-rock).
    Uplift,
    /// Contact starts to slip (or reverses its slip).
    Slip,
    /// Slipping contact sticks.
    Stick,
    /// The lifted corner strikes the base at Θ = 0.
    Impact,
    /// The block comes to rest after an accumulation of impacts.
    Rest,
    /// |Θ| reached the tumble angle.
    Tumble,
    /// The normal force vanished.
    Flight,
}

impl EventKind {
    /// Name used in `events.csv`.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Uplift => "uplift",
            EventKind::Slip => "slip",
            EventKind::Stick => "stick",
            EventKind::Impact => "impact",
            EventKind::Rest => "rest",
            EventKind::Tumble => "tumble",
            EventKind::Flight => "flight",
        }
    }
}

/// One event, as reported to observers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventRecord {
    /// Time of the event (for `Rest` after accumulation, the accumulation
    /// time).
    pub tau: f64,
    /// What happened.
    pub kind: EventKind,
    /// Mode before.
    pub before: Mode,
    /// Mode after (after any immediate follow-up switch at the same instant).
    pub after: Mode,
    /// Θ at the event.
    pub theta: f64,
    /// Θ' just before.
    pub theta_dot_before: f64,
    /// Θ' just after.
    pub theta_dot_after: f64,
    /// X' just after.
    pub x_dot: f64,
}

/// Physical parameters of a run, normalised (MODEL-DECISIONS).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Block geometry.
    pub geo: Geometry,
    /// Static friction coefficient μ_s (`inf`: no sliding).
    pub mu_s: f64,
    /// Kinetic friction coefficient μ_k (<= μ_s).
    pub mu_k: f64,
    /// Impact law.
    pub law: ImpactLaw,
    /// Base motion.
    pub excitation: Excitation,
    /// |Θ| at which the block counts as tumbled (default 1; capped at the
    /// side-landing angle π/(2ψ)).
    pub tumble_theta: f64,
    /// What to do at flight.
    pub flight: FlightPolicy,
    /// Post-impact |Θ'| below which an impact accumulation is summed in
    /// closed form and the block put to rest (default 1e-5).
    pub zeno_eps: f64,
}

/// Things the system tallies as it runs, beyond the state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Energy lost at impacts (and in summed accumulations), per m g R.
    pub impact_loss: f64,
    /// Times the normal force vanished while `flight = ignore`.
    pub flight_violations: u64,
    /// Largest |Θ| at an extremum.
    pub max_abs_theta: f64,
    /// Impacts.
    pub impacts: u64,
    /// Y' with which an impact threw the block off the base (flight by
    /// vertical restitution), kept for the final energy.
    pub lift_off_y_dot: Option<f64>,
}

/// The block as a [`HybridSystem`].
#[derive(Clone, Debug)]
pub struct BlockSystem {
    /// Parameters.
    pub model: Model,
    /// Tallies.
    pub tally: Tally,
    /// The forcing at the time of the last evaluation: the guards at a
    /// step's end are evaluated at the time of its last (FSAL) right-hand
    /// side and reuse its sine. Same bits either way.
    last_forcing: Cell<(f64, Forcing)>,
}

/// Errors from the model side of a run.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// The driver failed.
    #[error(transparent)]
    Driver(#[from] DriverError),
}

impl BlockSystem {
    /// A system for `model` with zeroed tallies.
    pub fn new(model: Model) -> Self {
        Self {
            model,
            tally: Tally::default(),
            last_forcing: Cell::new((f64::NAN, Forcing { a: 0.0, av: 0.0 })),
        }
    }

    /// The forcing at `t`, remembered for the next call at the same `t`.
    #[inline]
    fn forcing(&self, t: f64) -> Forcing {
        let (tl, fl) = self.last_forcing.get();
        if tl.to_bits() == t.to_bits() {
            return fl;
        }
        let fo = self.model.excitation.forcing(t);
        self.last_forcing.set((t, fo));
        fo
    }

    /// The effective tumble angle: `tumble_theta` capped at the side landing.
    pub fn tumble_angle(&self) -> f64 {
        self.model.tumble_theta.min(self.model.geo.side_theta())
    }

    fn friction_finite(&self) -> bool {
        self.model.mu_s.is_finite()
    }

    fn stops_at_flight(&self) -> bool {
        self.model.flight == FlightPolicy::Stop
    }

    /// Accelerations and contact forces of `mode` at `(t, y)`.
    pub fn accel(&self, mode: Mode, t: f64, y: &[f64; N]) -> Accel {
        let fo = self.model.excitation.forcing(t);
        self.accel_with(mode, fo, y)
    }

    fn accel_with(&self, mode: Mode, fo: Forcing, y: &[f64; N]) -> Accel {
        let geo = &self.model.geo;
        match mode {
            Mode::Rest | Mode::Tumbled | Mode::Flight => dynamics::rest(fo),
            Mode::Slide { slip } => dynamics::slide(slip, self.model.mu_k, fo),
            Mode::Rock { pivot } => dynamics::rock(geo, pivot, y[THETA], y[THETA_DOT], fo),
            Mode::SlideRock { pivot, slip } => {
                dynamics::slide_rock(geo, pivot, slip, self.model.mu_k, y[THETA], y[THETA_DOT], fo)
            }
        }
    }

    /// Mechanical energy / (m g R) of `y` in `mode`.
    pub fn energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        energy::total(&self.model.geo, mode, y[THETA], y[THETA_DOT], y[X_DOT])
    }

    /// Mechanical energy at the end of a run: as [`energy`](Self::energy),
    /// except that a block thrown off the base by an impact keeps the
    /// vertical velocity it left with.
    pub fn final_energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        match (mode, self.tally.lift_off_y_dot) {
            (Mode::Flight, Some(y_dot)) => {
                let geo = &self.model.geo;
                energy::kinetic(geo, y[X_DOT], y_dot, y[THETA_DOT]) + geo.cos_psi
            }
            _ => self.energy(mode, y),
        }
    }

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
    fn impact(&mut self, before: Mode, pivot: Sign, t: f64, y: &[f64; N]) -> Jump<Mode, EventRecord, N> {
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
                ImpactLaw::Housner | ImpactLaw::Ratio { .. } => 0.0,
            };
            post = impact::impulse_law(&geo, &pre, e, self.model.mu_s, self.model.mu_k);
        }
        if impact::reverses(&pre, &post) {
            let (mu_s, mu_k) = match self.model.law {
                ImpactLaw::Impulse { mu_s, mu_k, .. } => (mu_s, mu_k),
                ImpactLaw::Housner | ImpactLaw::Ratio { .. } => (self.model.mu_s, self.model.mu_k),
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
        };
        if mode == Mode::Flight {
            // Kinetic energy after, with the lifted-off vertical velocity,
            // which the state vector does not hold: keep it for the audit.
            yn[X_DOT] = post.x_dot;
            record.x_dot = post.x_dot;
            self.tally.lift_off_y_dot = Some(post.y_dot);
            let e_after = energy::kinetic(&geo, post.x_dot, post.y_dot, yn[THETA_DOT]);
            self.tally.impact_loss += e_before - e_after;
            return Jump {
                mode,
                t,
                y: yn,
                records: [Some(record), None],
            };
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
            return Jump {
                mode,
                t,
                y: yn,
                records: [Some(record), None],
            };
        }
        let (_, y_dot_after) = energy::height(&geo, mode, 0.0, yn[THETA_DOT]);
        let e_after = energy::kinetic(&geo, yn[X_DOT], y_dot_after, yn[THETA_DOT]);
        self.tally.impact_loss += e_before - e_after;
        let mode = self.settle(mode, t, &mut yn);
        record.after = mode;
        record.x_dot = yn[X_DOT];
        Jump {
            mode,
            t,
            y: yn,
            records: [Some(record), None],
        }
    }

    /// Impact accumulation (MODEL-DECISIONS): the remaining impacts are
    /// summed in closed form (docs/model.md §10) and the block put flat.
    fn accumulate(
        &mut self,
        mut record: EventRecord,
        e_before: f64,
        t: f64,
        pre: &PreImpact,
        post: &impact::PostImpact,
        mut yn: [f64; N],
    ) -> Jump<Mode, EventRecord, N> {
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
        if k_next > 0.0 && k_after > 0.0 {
            let v = post.w.abs();
            let r = if pre.w != 0.0 { (post.w / pre.w).abs() } else { 0.0 };
            let dt = if r < 1.0 {
                2.0 * v * (1.0 / k_next + r / k_after) / (1.0 - r * r)
            } else {
                2.0 * v / k_next
            };
            let mut t_acc = t + dt;
            if t_acc <= t {
                t_acc = t.next_up();
            }
            let mode = self.settle(flat, t_acc, &mut yn);
            record.after = Mode::Rock { pivot: striking };
            let rest = EventRecord {
                tau: t_acc,
                kind: EventKind::Rest,
                before: Mode::Rock { pivot: striking },
                after: mode,
                theta: 0.0,
                theta_dot_before: record.theta_dot_after,
                theta_dot_after: 0.0,
                x_dot: yn[X_DOT],
            };
            Jump {
                mode,
                t: t_acc,
                y: yn,
                records: [Some(record), Some(rest)],
            }
        } else {
            // The base lifts the block at once: rocking restarts from
            // Θ = Θ' = 0 on the side the base drives it to.
            let mode = self.settle(flat, t, &mut yn);
            record.kind = EventKind::Rest;
            record.after = mode;
            record.theta_dot_after = 0.0;
            record.x_dot = yn[X_DOT];
            Jump {
                mode,
                t,
                y: yn,
                records: [Some(record), None],
            }
        }
    }

    fn simple(
        &mut self,
        kind: EventKind,
        before: Mode,
        target: Mode,
        t: f64,
        y: &[f64; N],
        mut yn: [f64; N],
    ) -> Jump<Mode, EventRecord, N> {
        let mode = self.settle(target, t, &mut yn);
        // A stick that cannot hold is a slip reversal; a slide that stops
        // is a stick even if the base then lifts the block.
        let kind = match (kind, mode) {
            (EventKind::Stick, Mode::SlideRock { .. } | Mode::Slide { .. }) => EventKind::Slip,
            (k, _) => k,
        };
        Jump {
            mode,
            t,
            y: yn,
            records: [
                Some(EventRecord {
                    tau: t,
                    kind,
                    before,
                    after: mode,
                    theta: y[THETA],
                    theta_dot_before: y[THETA_DOT],
                    theta_dot_after: yn[THETA_DOT],
                    x_dot: yn[X_DOT],
                }),
                None,
            ],
        }
    }
}

/// A flat block starting to rock about `pivot` from rest.
fn rock_from_flat(pivot: Sign, y: &mut [f64; N]) -> Mode {
    y[THETA] = 0.0;
    y[THETA_DOT] = 0.0;
    y[X_DOT] = 0.0;
    Mode::Rock { pivot }
}

impl HybridSystem<N> for BlockSystem {
    type Mode = Mode;
    type Record = EventRecord;
    type Error = ModelError;

    /// W and D: the vector field reads Θ, Θ' and X' only.
    const QUADRATURES: usize = 2;

    #[inline]
    fn rhs(&self, mode: Mode, t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        let fo = self.forcing(t);
        let geo = &self.model.geo;
        match mode {
            Mode::Rest | Mode::Tumbled | Mode::Flight => *dy = [0.0; N],
            Mode::Slide { slip } => {
                let acc = dynamics::slide(slip, self.model.mu_k, fo);
                *dy = [
                    0.0,
                    0.0,
                    y[X_DOT],
                    acc.x_ddot,
                    -fo.a * y[X_DOT],
                    -acc.friction * y[X_DOT],
                ];
            }
            Mode::Rock { pivot } => {
                let tilt = Tilt::new(geo, pivot, y[THETA]);
                let acc = dynamics::rock_at(geo, pivot, tilt, y[THETA_DOT], fo);
                let w = geo.psi * y[THETA_DOT];
                let y_dot = pivot.value() * tilt.sn * w;
                *dy = [
                    y[THETA_DOT],
                    acc.theta_ddot,
                    y[X_DOT],
                    acc.x_ddot,
                    -fo.a * y[X_DOT] - fo.av * y_dot,
                    0.0,
                ];
            }
            Mode::SlideRock { pivot, slip } => {
                let tilt = Tilt::new(geo, pivot, y[THETA]);
                let acc = dynamics::slide_rock_at(geo, pivot, slip, self.model.mu_k, tilt, y[THETA_DOT], fo);
                let w = geo.psi * y[THETA_DOT];
                let y_dot = pivot.value() * tilt.sn * w;
                let vp = y[X_DOT] - tilt.c * w;
                *dy = [
                    y[THETA_DOT],
                    acc.theta_ddot,
                    y[X_DOT],
                    acc.x_ddot,
                    -fo.a * y[X_DOT] - fo.av * y_dot,
                    -acc.friction * vp,
                ];
            }
        }
    }

    #[inline]
    fn taylor(&self, mode: Mode, t: f64, y: &[f64; N], order: usize, c: &mut [[f64; N]]) -> bool {
        super::series::taylor(&self.model, mode, t, y, order, c)
    }

    fn guards(&self, mode: Mode, t: f64, y: &[f64; N], g: &mut [f64; MAX_GUARDS]) -> usize {
        let fo = self.forcing(t);
        let geo = &self.model.geo;
        let mu_s = self.model.mu_s;
        match mode {
            Mode::Tumbled | Mode::Flight => 0,
            Mode::Rest => {
                let b = fo.b();
                // Flight first: when b reaches 0 the uplift guards κ = b sin ψ
                // ± a cos ψ may reach 0 at the same instant, and ties go to
                // the lowest index.
                g[0] = b;
                g[1] = dynamics::restoring(geo, Sign::Pos, fo);
                g[2] = dynamics::restoring(geo, Sign::Neg, fo);
                if self.friction_finite() {
                    g[3] = mu_s * b + fo.a;
                    g[4] = mu_s * b - fo.a;
                    5
                } else {
                    3
                }
            }
            Mode::Slide { slip } => {
                g[0] = slip.value() * y[X_DOT];
                g[1] = fo.b();
                2
            }
            Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => {
                let s = pivot.value();
                let acc = self.accel_with(mode, fo, y);
                g[0] = s * y[THETA];
                g[1] = self.tumble_angle() - s * y[THETA];
                g[2] = acc.normal;
                g[3] = s * y[THETA_DOT];
                match mode {
                    Mode::SlideRock { slip, .. } => {
                        let vp = dynamics::pivot_slip_velocity(geo, pivot, y[THETA], y[THETA_DOT], y[X_DOT]);
                        g[4] = slip.value() * vp;
                        5
                    }
                    _ if self.friction_finite() => {
                        let f_side = s * acc.friction;
                        g[4] = mu_s * acc.normal - f_side;
                        g[5] = mu_s * acc.normal + f_side;
                        6
                    }
                    _ => 4,
                }
            }
        }
    }

    #[inline]
    fn guard(&self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> f64 {
        // The geometric guards of the rocking modes need neither the
        // forcing nor the contact forces; the same expressions as `guards`.
        match (mode, index) {
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 0) => pivot.value() * y[THETA],
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 1) => self.tumble_angle() - pivot.value() * y[THETA],
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 3) => pivot.value() * y[THETA_DOT],
            (Mode::SlideRock { pivot, slip }, 4) => {
                let vp = dynamics::pivot_slip_velocity(&self.model.geo, pivot, y[THETA], y[THETA_DOT], y[X_DOT]);
                slip.value() * vp
            }
            (Mode::Slide { slip }, 0) => slip.value() * y[X_DOT],
            _ => {
                let mut g = [0.0; MAX_GUARDS];
                self.guards(mode, t, y, &mut g);
                g[index]
            }
        }
    }

    /// The flight guard of rocking, n > 0, from a bound over the step: with
    /// |ψΘ''| ≤ b_max + a_max at every state and time, |Θ'| along the step
    /// is at most (|Θ'₀| + |Θ'₁| + h M)/2 (it can grow at rate M from either
    /// end), |Θ| at most (|Θ₀| + |Θ₁| + h V)/2 likewise, and
    /// [`dynamics::rock_normal_lower_bound`] bounds n over those states and
    /// every forcing the excitation can give. On the paper's scenes the
    /// bound is about 0.6 against n ≈ 0.9: long steps at loose tolerances
    /// then sample only the geometric guards, which need no forcing.
    fn guard_stays_positive(&self, mode: Mode, index: usize, h: f64, y0: &[f64; N], y1: &[f64; N]) -> bool {
        if !matches!(mode, Mode::Rock { .. }) || index != 2 {
            return false;
        }
        let Some((a_max, av_max)) = self.model.excitation.peak_accel() else {
            return false;
        };
        let geo = &self.model.geo;
        let m = (1.0 + av_max + a_max) * geo.inv_psi;
        let v = 0.5 * (y0[THETA_DOT].abs() + y1[THETA_DOT].abs() + h * m);
        let th = 0.5 * (y0[THETA].abs() + y1[THETA].abs() + h * v);
        // Far above round-off and the interpolant's error, far below the
        // bound's own slack.
        const MARGIN: f64 = 1e-3;
        dynamics::rock_normal_lower_bound(geo, th, v, a_max, 1.0 - av_max) > MARGIN
    }

    /// Θ for the impact and tumble guards, Θ and Θ' for the extremum and
    /// for every guard of rocking about a stuck corner (its forces, hence
    /// the flight and slip-onset guards, depend on the tilt and its rate
    /// alone: `dynamics::rock_at`); the rest read Θ, Θ', X and X' (through
    /// the forces, or the pivot's slip).
    fn guard_reads(&self, mode: Mode, index: usize) -> usize {
        match (mode, index) {
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 0 | 1) => THETA + 1,
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 3) => THETA_DOT + 1,
            (Mode::Rock { .. }, _) => THETA_DOT + 1,
            _ => N - Self::QUADRATURES,
        }
    }

    /// The guards `guard` evaluates without the forcing and the contact
    /// forces (its special cases).
    fn guard_is_cheap(&self, mode: Mode, index: usize) -> bool {
        matches!(
            (mode, index),
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 0 | 1 | 3)
                | (Mode::SlideRock { .. }, 4)
                | (Mode::Slide { .. }, 0)
        )
    }

    fn is_observer(&self, mode: Mode, index: usize) -> bool {
        match mode {
            Mode::Rock { .. } | Mode::SlideRock { .. } => index == 3 || (index == 2 && !self.stops_at_flight()),
            Mode::Rest => index == 0 && !self.stops_at_flight(),
            Mode::Slide { .. } => index == 1 && !self.stops_at_flight(),
            Mode::Tumbled | Mode::Flight => false,
        }
    }

    /// The extremum observer of rocking records the largest |Θ|: its root
    /// in `[ta, tb]`, where Θ' = 0, is within `M (tb − ta)²/2` of Θ at
    /// either end (Taylor's theorem with |Θ''| ≤ M = (b_max + a_max)/ψ, the
    /// bound of `guard_stays_positive`), so when that stays at or below the
    /// largest |Θ| so far the root cannot raise it and is not located (most
    /// extrema of a run that has settled into its range). Slide-rock, whose
    /// Θ'' has no such simple bound, and the flight observer always record.
    fn observer_may_record(&self, mode: Mode, index: usize, ta: f64, ya: &[f64; N], tb: f64, yb: &[f64; N]) -> bool {
        if !matches!(mode, Mode::Rock { .. }) || index != 3 {
            return true;
        }
        let Some((a_max, av_max)) = self.model.excitation.peak_accel() else {
            return true;
        };
        let m = (1.0 + av_max + a_max) * self.model.geo.inv_psi;
        let dt = tb - ta;
        // The samples are the dense output, within the tolerance of the
        // solution: a margin far above that.
        const MARGIN: f64 = 1e-6;
        let peak = ya[THETA].abs().max(yb[THETA].abs()) + 0.5 * m * dt * dt + MARGIN;
        !(peak.is_finite() && peak <= self.tally.max_abs_theta)
    }

    fn observe(&mut self, mode: Mode, index: usize, _t: f64, y: &[f64; N]) {
        match (mode, index) {
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 3) => {
                self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs());
            }
            _ => self.tally.flight_violations += 1,
        }
    }

    fn jump(
        &mut self,
        mode: Mode,
        index: usize,
        t: f64,
        y: &[f64; N],
    ) -> Result<Jump<Mode, EventRecord, N>, ModelError> {
        let mut yn = *y;
        let jump = match (mode, index) {
            (Mode::Rest, 1 | 2) => {
                let pivot = if index == 1 { Sign::Pos } else { Sign::Neg };
                let target = rock_from_flat(pivot, &mut yn);
                self.simple(EventKind::Uplift, mode, target, t, y, yn)
            }
            (Mode::Rest, 0) | (Mode::Slide { .. }, 1) | (Mode::Rock { .. } | Mode::SlideRock { .. }, 2) => {
                self.simple(EventKind::Flight, mode, Mode::Flight, t, y, yn)
            }
            (Mode::Rest, _) => {
                let slip = if index == 3 { Sign::Pos } else { Sign::Neg };
                yn[X_DOT] = 0.0;
                self.simple(EventKind::Slip, mode, Mode::Slide { slip }, t, y, yn)
            }
            (Mode::Slide { .. }, _) => {
                yn[X_DOT] = 0.0;
                self.simple(EventKind::Stick, mode, Mode::Rest, t, y, yn)
            }
            (Mode::Rock { pivot } | Mode::SlideRock { pivot, .. }, 0) => self.impact(mode, pivot, t, y),
            (Mode::Rock { .. } | Mode::SlideRock { .. }, 1) => {
                self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs());
                self.simple(EventKind::Tumble, mode, Mode::Tumbled, t, y, yn)
            }
            (Mode::Rock { pivot }, _) => {
                // Guard 4: s f reached μ_s n, friction pushes towards s, the
                // corner slips towards −s; guard 5 the other way.
                let slip = if index == 4 { pivot.flip() } else { pivot };
                self.simple(EventKind::Slip, mode, Mode::SlideRock { pivot, slip }, t, y, yn)
            }
            (Mode::SlideRock { pivot, .. }, _) => {
                let tilt = Tilt::new(&self.model.geo, pivot, y[THETA]);
                yn[X_DOT] = tilt.c * self.model.geo.psi * y[THETA_DOT];
                self.simple(EventKind::Stick, mode, Mode::Rock { pivot }, t, y, yn)
            }
            (Mode::Tumbled | Mode::Flight, _) => Jump {
                mode,
                t,
                y: yn,
                records: [None, None],
            },
        };
        Ok(jump)
    }

    fn is_terminal(&self, mode: Mode) -> bool {
        mode.is_terminal()
    }

    fn next_breakpoint(&self, t: f64) -> Option<f64> {
        self.model.excitation.next_breakpoint(t)
    }

    fn time_scale(&self) -> f64 {
        self.model.excitation.time_scale()
    }

    fn step_cap(&self, mode: Mode) -> f64 {
        // At rest the state does not move and every guard is a function of
        // the forcing alone; in the other modes the forcing drives the
        // state, whose error control resolves it.
        match mode {
            Mode::Rest => self.model.excitation.time_scale(),
            _ => f64::INFINITY,
        }
    }
}
