//! A stack's answer in physical units (`summary.json`'s `physical`): the
//! single block's fields for the stack as a whole, and each block's own
//! in `bodies`, bottom to top.

use super::answer::{Body, ModeSeconds, Physical, RecordPeaks, floor_peaks};
use super::end_state::EndState;
use super::scenario::Scenario;
use super::stack_run::StackRun;
use crate::model::stack::StackEnd;

/// What the outputs call block `j` of a stack of `k`: `bottom block`,
/// `middle block` (of three), `block 2` …, `top block`.
pub(crate) fn body_name(j: usize, k: usize) -> &'static str {
    const MIDDLE: [&str; 3] = ["block 2", "block 3", "block 4"];
    match (j, k) {
        (0, _) => "bottom block",
        (j, k) if j + 1 == k => "top block",
        (1, 3) => "middle block",
        (j, _) => MIDDLE[(j - 1).min(2)],
    }
}

impl Physical {
    /// The answer of a stack's run `run` of scenario `s`.
    pub fn of_stack(s: &Scenario, run: &StackRun) -> Self {
        let geo = s.geometry();
        let sec = |tau: f64| tau / geo.p;
        let k = run.geo.k;
        let end_state = EndState::of(run.outcome);
        let over = match run.end {
            Some((StackEnd::Overturned(i), tau)) => Some((i, tau)),
            _ => None,
        };
        let bodies: Vec<Body> = (0..k)
            .map(|j| Body {
                name: body_name(j, k).to_string(),
                max_rotation_deg: run.tally.max_phi[j].to_degrees(),
                // Everything above an interface that overturns goes over.
                overturned: over.is_some_and(|(i, _)| j >= i),
                // Only the base face slides (docs/model.md §18.7), and it
                // carries every block: each one's displacement along the
                // base caused by sliding is the base face's slip.
                max_sliding_m: run.tally.max_slide,
                // The lifted corner of its lower face rises span·sin q.
                max_uplift_m: run.geo.span(j) * run.tally.max_q[j].min(std::f64::consts::FRAC_PI_2).sin(),
            })
            .collect();
        let (_, phi, phi_over_alpha) = run.most_turned();
        let base_mu = run.geo.mu_s[0];
        Physical {
            overturned: end_state == EndState::Overturned,
            t_overturn_s: over.map(|(_, tau)| sec(tau)),
            max_rotation_rad: phi,
            max_rotation_deg: phi.to_degrees(),
            max_rotation_over_alpha: phi_over_alpha,
            max_sliding_m: run.tally.max_slide,
            residual_sliding_m: run.last.y[crate::model::stack::SLIDE],
            max_uplift_m: bodies.iter().map(|b| b.max_uplift_m).fold(0.0, f64::max),
            impacts: run.tally.impacts,
            mode_time_s: ModeSeconds {
                rest: sec(run.mode_tau[0]),
                slide: sec(run.mode_tau[1]),
                rock: sec(run.mode_tau[2]),
                slide_rock: sec(run.mode_tau[3]),
            },
            t_end_s: sec(run.tau_end),
            t_rest_s: run.tau_rest.map(sec),
            end_state,
            record_complete: s.record_complete(),
            record_h: RecordPeaks::of(s, &s.excitation.record_h, s.excitation.scale_h),
            record_v: RecordPeaks::of(s, &s.excitation.record_v, s.excitation.scale_v),
            floor: floor_peaks(s),
            impact_law: "stack",
            impact_r: None,
            friction_static: base_mu.is_finite().then_some(base_mu),
            friction_kinetic: base_mu.is_finite().then_some(run.geo.mu_k[0]),
            bodies: Some(bodies),
            subject: Some(match run.end {
                Some((StackEnd::Overturned(i) | StackEnd::Flight(i), _)) => body_name(i, k),
                None => "stack",
            }),
        }
    }
}
