//! The rocking frame as a [`HybridSystem`]: rest, rocking on stuck
//! corners, and the terminal modes. Guard indices (each positive inside
//! its mode):
//!
//! | mode | 0 | 1 | 2 | 3 | 4 |
//! |---|---|---|---|---|---|
//! | rest | flight b | uplift right κ₊ | uplift left κ₋ | | |
//! | rock s | impact sΘ | tumble Θ_t − sΘ | flight: base normal | extremum sΘ' (observer) | flight: beam normal |
//!
//! The indices of rest and of rock's first four guards are the block's, so
//! events read alike in both models.

use super::{Frame, FrameAccel, rock};
use crate::integrate::hybrid::{HybridSystem, MAX_GUARDS};
use crate::model::ad::Scalar;
use crate::model::dynamics::{self, Forcing, Tilt};
use crate::model::energy;
use crate::model::geometry::GAMMA;
use crate::model::impact::{self, ImpactLaw};
use crate::model::mode::{Mode, Sign};
use crate::model::params::{FlightPolicy, Model};
use crate::model::state::{N, THETA, THETA_DOT, X_DOT};
use crate::model::system::{
    EventKind, EventRecord, LastForcing, ModelError, ModelJump, Settles, Tally, accumulated, jump_to, one_body_system,
    rock_from_flat, uplift,
};

/// The rocking frame as a hybrid system.
#[derive(Clone, Debug)]
pub struct FrameSystem {
    /// Parameters: the column's geometry and the frame's.
    pub model: Model,
    /// Tallies.
    pub tally: Tally,
    /// The frame (a massless beam if the model has none: lone columns).
    frame: Frame,
    /// [`Frame::kappa`], computed once.
    kappa: f64,
    /// The forcing at the last evaluation, as the block keeps it.
    last_forcing: LastForcing,
}

impl FrameSystem {
    /// A system for `model` with zeroed tallies.
    pub fn new(model: Model) -> Self {
        let frame = model.frame.unwrap_or(Frame {
            columns: 2,
            beam_mass_ratio: 0.0,
        });
        Self {
            kappa: frame.kappa(),
            frame,
            model,
            tally: Tally::default(),
            last_forcing: LastForcing::new(),
        }
    }

    fn stops_at_flight(&self) -> bool {
        self.model.flight == FlightPolicy::Stop
    }

    pub(crate) fn tumble_angle(&self) -> f64 {
        self.model.tumble_theta.min(self.model.geo.side_theta())
    }

    /// Accelerations and forces of rocking about `pivot` at `y`.
    #[inline]
    fn rocking(&self, pivot: Sign, fo: Forcing, y: &[f64; N]) -> FrameAccel {
        self.rocking_at(pivot, fo, y[THETA], y[THETA_DOT])
    }

    /// [`rocking`](Self::rocking) of a generic Θ and Θ'.
    #[inline(always)]
    fn rocking_at<S: Scalar>(&self, pivot: Sign, fo: Forcing<S>, theta: S, theta_dot: S) -> FrameAccel<S> {
        let geo = &self.model.geo;
        let tilt = Tilt::of(geo, pivot, theta);
        rock(&self.frame, self.kappa, pivot, tilt, theta_dot * geo.psi, fo)
    }

    /// The vector field of `mode` at forcing `fo` and state `y`, written
    /// once over a generic [`Scalar`]: the run's right-hand side over
    /// `f64`, its Jacobian over dual numbers (`tangent.rs`).
    #[inline(always)]
    pub(super) fn field<S: Scalar>(&self, mode: Mode, fo: Forcing<S>, y: &[S; N]) -> [S; N] {
        let zero = y[THETA].constant(0.0);
        match mode {
            Mode::Rock { pivot } => {
                let geo = &self.model.geo;
                let acc = self.rocking_at(pivot, fo, y[THETA], y[THETA_DOT]);
                let tilt = Tilt::of(geo, pivot, y[THETA]);
                let y_dot = tilt.sn * pivot.value() * geo.psi * y[THETA_DOT];
                [
                    y[THETA_DOT],
                    acc.wdd * geo.inv_psi,
                    y[X_DOT],
                    acc.x_ddot,
                    // The base's pseudo-forces on the columns and the beam,
                    // whose support moves twice as far (docs/model.md §16.2).
                    (fo.a * y[X_DOT] + fo.av * y_dot) * -self.frame.lever(),
                    zero,
                ]
            }
            Mode::Rest | Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => [zero; N],
        }
    }

    /// The guards of `mode` (the table in the module docs) at forcing `fo`
    /// and state `y` into `g`, and how many there are; generic as
    /// [`field`](Self::field), for the guards' gradients.
    #[inline(always)]
    pub(super) fn guard_values<S: Scalar>(
        &self,
        mode: Mode,
        fo: Forcing<S>,
        y: &[S; N],
        g: &mut [S; MAX_GUARDS],
    ) -> usize {
        let geo = &self.model.geo;
        match mode {
            Mode::Rest => {
                g[0] = fo.b();
                g[1] = dynamics::restoring(geo, Sign::Pos, fo);
                g[2] = dynamics::restoring(geo, Sign::Neg, fo);
                3
            }
            Mode::Rock { pivot } => {
                let s = pivot.value();
                let acc = self.rocking_at(pivot, fo, y[THETA], y[THETA_DOT]);
                g[0] = y[THETA] * s;
                g[1] = -(y[THETA] * s) + self.tumble_angle();
                g[2] = acc.base_normal;
                g[3] = y[THETA_DOT] * s;
                g[4] = acc.beam_normal;
                5
            }
            Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => 0,
        }
    }

    /// The impact ratio of the frame's law: the `ratio` law's r, or the
    /// frame's own momentum balance ([`Frame::restitution`]).
    pub(super) fn impact_ratio(&self) -> f64 {
        match self.model.law {
            ImpactLaw::Ratio { r } => r,
            // The frame's own momentum balance; `impulse` is refused for a
            // frame when the scenario is checked.
            ImpactLaw::Housner | ImpactLaw::CornerMomentum | ImpactLaw::Impulse { .. } => {
                self.frame.restitution(&self.model.geo)
            }
        }
    }

    /// The base's reactions on one column with its share of the beam, per
    /// column weight: the columns' and the beam's inertia, the beam's
    /// support accelerating twice as fast as a column's centre.
    pub(crate) fn base_forces(&self, mode: Mode, t: f64, y: &[f64; N]) -> (f64, f64) {
        let fo = self.model.excitation.forcing(t);
        match mode {
            Mode::Rock { pivot } => {
                let acc = self.rocking(pivot, fo, y);
                let g = self.frame.beam_mass_ratio;
                let column = fo.a + GAMMA * acc.x_ddot;
                let beam = fo.a + 2.0 * GAMMA * acc.x_ddot;
                (acc.base_normal, column + g * beam)
            }
            _ => {
                let g = self.frame.beam_mass_ratio;
                (fo.b() * (1.0 + g), fo.a * (1.0 + g))
            }
        }
    }

    /// Mechanical energy per m_c g R: ½(1 + 3γ_b)w² + (1 + 2γ_b)Y, with Y
    /// the height of a column's centre (docs/model.md §16.2).
    pub fn energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        let geo = &self.model.geo;
        let (height, _) = energy::height(geo, mode, y[THETA], y[THETA_DOT]);
        self.frame.kinetic(geo.psi * y[THETA_DOT]) + self.frame.lever() * height
    }

    /// Mechanical energy at a run's end: a frame keeps no velocity outside
    /// its state (no impact throws it off the base).
    pub fn final_energy(&self, mode: Mode, y: &[f64; N]) -> f64 {
        self.energy(mode, y)
    }

    /// Brings a freshly entered mode to a consistent one at `t`: a rest
    /// the base lifts rocks, a rocking frame whose base or beam loses
    /// contact flies, a frame flat and still whose base drives it back
    /// rests.
    pub fn settle(&mut self, mut mode: Mode, t: f64, y: &mut [f64; N]) -> Mode {
        let fo = self.model.excitation.forcing(t);
        let geo = self.model.geo;
        // Rest → rock → flight or rest is the longest chain.
        for _ in 0..4 {
            let next = match mode {
                Mode::Rest => {
                    if fo.b() <= 0.0 && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else {
                        [Sign::Pos, Sign::Neg]
                            .into_iter()
                            .find(|&s| dynamics::restoring(&geo, s, fo) < 0.0)
                            .map(|s| rock_from_flat(s, y))
                    }
                }
                Mode::Rock { pivot } => {
                    let acc = self.rocking(pivot, fo, y);
                    if (acc.base_normal <= 0.0 || acc.beam_normal <= 0.0) && self.stops_at_flight() {
                        Some(Mode::Flight)
                    } else if y[THETA] == 0.0 && y[THETA_DOT] == 0.0 && pivot.value() * acc.wdd < 0.0 {
                        Some(Mode::Rest)
                    } else {
                        None
                    }
                }
                // A frame never slides; the terminal modes stay.
                Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => None,
            };
            match next {
                Some(m) => mode = m,
                None => return mode,
            }
        }
        mode
    }

    /// The impact at Θ = 0 (docs/model.md §16.3): every column's other
    /// corner and the beam's other supports strike and stick; the
    /// angular velocity is multiplied by the frame's coefficient (or the
    /// `ratio` law's r). An accumulation is summed in closed form as the
    /// block's (docs/model.md §10, with the frame's κ).
    fn impact(&mut self, before: Mode, pivot: Sign, t: f64, y: &[f64; N]) -> ModelJump {
        let geo = self.model.geo;
        let striking = pivot.flip();
        let r = self.impact_ratio();
        self.tally.impacts += 1;
        let w_before = geo.psi * y[THETA_DOT];
        let e_before = self.frame.kinetic(w_before);
        // r ≤ 0: the momentum balance cannot be met rotating about the new
        // corners (it would drive the old ones into the base), so the frame
        // lands flat and loses all its kinetic energy.
        let w_after = r.max(0.0) * w_before;
        let mut yn = *y;
        yn[THETA] = 0.0;
        yn[THETA_DOT] = w_after / geo.psi;
        yn[X_DOT] = geo.cos_psi * w_after;
        let mut impact = EventRecord::switch(EventKind::Impact, t, before, Mode::Rock { pivot: striking }, y, &yn);
        impact.theta = 0.0;
        if yn[THETA_DOT].abs() < self.model.zeno_eps {
            return self.accumulate(impact, e_before, t, striking, r.max(0.0), w_after, yn);
        }
        self.tally.impact_loss += e_before - self.frame.kinetic(w_after);
        let mode = self.settle(Mode::Rock { pivot: striking }, t, &mut yn);
        impact.after = mode;
        jump_to(mode, t, yn, Some(impact))
    }

    /// The rest of an impact accumulation summed in closed form: the frame
    /// put flat `dt` later, dt = 2v(1/k₊ + r/k₋)/(1 − r²) with k the
    /// deceleration κ·(b sin ψ ± a cos ψ) on each side (docs/model.md §10).
    #[allow(clippy::too_many_arguments)]
    fn accumulate(
        &mut self,
        impact: EventRecord,
        e_before: f64,
        t: f64,
        striking: Sign,
        r: f64,
        w_after: f64,
        mut yn: [f64; N],
    ) -> ModelJump {
        let geo = self.model.geo;
        let fo = self.model.excitation.forcing(t);
        let k_next = self.kappa * dynamics::restoring(&geo, striking, fo);
        let k_after = self.kappa * dynamics::restoring(&geo, striking.flip(), fo);
        self.tally.impact_loss += e_before;
        yn[THETA] = 0.0;
        yn[THETA_DOT] = 0.0;
        yn[X_DOT] = 0.0;
        // Without a restoring push on both sides the base lifts the frame at
        // once: it restarts from flat.
        let t_acc =
            (k_next > 0.0 && k_after > 0.0).then(|| impact::accumulation_end(t, w_after.abs(), r, k_next, k_after));
        let mode = self.settle(Mode::Rest, t_acc.unwrap_or(t), &mut yn);
        accumulated(impact, striking, t_acc, mode, yn)
    }
}

/// The frame never slides, so no switch of its settles into a slip.
impl Settles for FrameSystem {
    fn settled(&mut self, mode: Mode, t: f64, y: &mut [f64; N]) -> Mode {
        self.settle(mode, t, y)
    }
}

impl HybridSystem<N> for FrameSystem {
    one_body_system!();

    /// W and D.
    const QUADRATURES: usize = 2;

    #[inline]
    fn rhs(&self, mode: Mode, t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        *dy = match mode {
            Mode::Rock { .. } => self.field(mode, self.last_forcing.at(&self.model.excitation, t), y),
            Mode::Rest | Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => [0.0; N],
        };
    }

    fn guards(&self, mode: Mode, t: f64, y: &[f64; N], g: &mut [f64; MAX_GUARDS]) -> usize {
        let fo = self.last_forcing.at(&self.model.excitation, t);
        self.guard_values(mode, fo, y, g)
    }

    #[inline]
    fn guard(&self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> f64 {
        match (mode, index) {
            (Mode::Rock { pivot }, 0) => pivot.value() * y[THETA],
            (Mode::Rock { pivot }, 1) => self.tumble_angle() - pivot.value() * y[THETA],
            (Mode::Rock { pivot }, 3) => pivot.value() * y[THETA_DOT],
            _ => {
                let mut g = [0.0; MAX_GUARDS];
                self.guards(mode, t, y, &mut g);
                g[index]
            }
        }
    }

    fn guard_is_cheap(&self, mode: Mode, index: usize) -> bool {
        matches!((mode, index), (Mode::Rock { .. }, 0 | 1 | 3))
    }

    /// Θ for impact and tumble; Θ and Θ' for the rest of rocking (its
    /// forces depend on the tilt and its rate alone).
    fn guard_reads(&self, mode: Mode, index: usize) -> usize {
        match (mode, index) {
            (Mode::Rock { .. }, 0 | 1) => THETA + 1,
            (Mode::Rock { .. }, _) => THETA_DOT + 1,
            _ => N - Self::QUADRATURES,
        }
    }

    fn is_observer(&self, mode: Mode, index: usize) -> bool {
        match mode {
            Mode::Rock { .. } => index == 3 || (matches!(index, 2 | 4) && !self.stops_at_flight()),
            Mode::Rest => index == 0 && !self.stops_at_flight(),
            Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight => false,
        }
    }

    fn observe(&mut self, mode: Mode, index: usize, _t: f64, y: &[f64; N]) {
        match (mode, index) {
            (Mode::Rock { .. }, 3) => self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs()),
            _ => self.tally.flight_violations += 1,
        }
    }

    fn jump(&mut self, mode: Mode, index: usize, t: f64, y: &[f64; N]) -> Result<ModelJump, ModelError> {
        let mut yn = *y;
        let jump = match (mode, index) {
            (Mode::Rest, 1 | 2) => self.simple(EventKind::Uplift, mode, uplift(index, &mut yn), t, y, yn),
            (Mode::Rest, _) | (Mode::Rock { .. }, 2 | 4) => {
                self.simple(EventKind::Flight, mode, Mode::Flight, t, y, yn)
            }
            (Mode::Rock { pivot }, 0) => self.impact(mode, pivot, t, y),
            (Mode::Rock { .. }, _) => {
                self.tally.max_abs_theta = self.tally.max_abs_theta.max(y[THETA].abs());
                self.simple(EventKind::Tumble, mode, Mode::Tumbled, t, y, yn)
            }
            (Mode::Slide { .. } | Mode::SlideRock { .. } | Mode::Tumbled | Mode::Flight, _) => {
                jump_to(mode, t, yn, None)
            }
        };
        Ok(jump)
    }
}
