//! One run of a stack of blocks (config `[[stack]]`) from rest to
//! `tau_end`, a terminal event, or rest after a record's end.
//!
//! The single block's run (`sim::run`) is generic over models with the
//! block's state; a stack's state holds one angle per interface, so it has
//! this run of its own, with the same options, the same rest rule after a
//! record and the same energy audit.

use std::time::Instant;

use super::run::{EnergyAudit, Outcome, RunOptions};
use crate::integrate::hybrid::{Advance, Driver, Observer, Outputs};
use crate::integrate::{Dop853, Dopri5, StepStats, Stepper};
use crate::model::excitation::Excitation;
use crate::model::stack::{
    FRICTION_S, NS, StackEnd, StackEvent, StackGeometry, StackMode, StackSystem, StackTally, WORK_S,
};

pub use crate::model::stack::StackError;

/// A state kept for the outputs.
#[derive(Clone, Copy, Debug)]
pub struct StackSample {
    /// τ.
    pub tau: f64,
    /// The mode.
    pub mode: StackMode,
    /// The state.
    pub y: [f64; NS],
}

/// A state at a section time τ_k = 2πk/Ω_h (harmonic forcing only).
#[derive(Clone, Copy, Debug)]
pub struct StackSection {
    /// k.
    pub k: u64,
    /// The state at τ_k.
    pub at: StackSample,
}

/// Everything a stack's run produces.
#[derive(Clone, Debug)]
pub struct StackRun {
    /// Its shape.
    pub geo: StackGeometry,
    /// How it ended.
    pub outcome: Outcome,
    /// The terminal event (which block overturned or flew) and its τ.
    pub end: Option<(StackEnd, f64)>,
    /// τ at which it ended.
    pub tau_end: f64,
    /// τ at which it last came to rest (every interface closed), if it
    /// ended at rest; 0 if it never moved.
    pub tau_rest: Option<f64>,
    /// τ spent with every interface closed and the base stuck.
    pub rest_tau: f64,
    /// τ spent in each of the single block's mode kinds: rest, slide
    /// (every interface closed, the base face sliding), rock (any
    /// interface open, the base stuck) and slide-rock (both).
    pub mode_tau: [f64; 4],
    /// Events in time order.
    pub events: Vec<StackEvent>,
    /// The regular history (every `output_dt`).
    pub history: Vec<StackSample>,
    /// The stroboscopic section at τ_k = 2πk/Ω_h, when `run.section` was
    /// asked for and the forcing is harmonic (a sweep's or a map's points).
    pub section: Vec<StackSection>,
    /// The final state.
    pub last: StackSample,
    /// Impacts and extremes.
    pub tally: StackTally,
    /// The energy audit, per M G R₁.
    pub energy: EnergyAudit,
    /// Stepper counters.
    pub stats: StepStats,
    /// Solver wall time, s.
    pub wall_s: f64,
}

impl StackRun {
    /// The block that turned most relative to its own slenderness: its
    /// index (0 = bottom), its peak |φ_j| (rad) and that over α_j =
    /// atan(B_j/H_j). The stack's headline rotation (`summary.json`'s
    /// `max_rotation_over_alpha`, a spectrum's `peak_theta_over_alpha`):
    /// one number that reads as the block's does, 1 being a block's own
    /// overturning angle.
    pub(crate) fn most_turned(&self) -> (usize, f64, f64) {
        let (j, phi) = (0..self.geo.k)
            .map(|j| (j, self.tally.max_phi[j]))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        let alpha = (self.geo.size[j][0] / self.geo.size[j][1]).atan();
        (j, phi, phi / alpha)
    }
}

/// Keeps what a stack's run produces.
struct Keep {
    k: usize,
    events: Vec<StackEvent>,
    history: Vec<StackSample>,
    keep_history: bool,
    section: Vec<StackSection>,
    rest_since: Option<f64>,
    rest_tau: f64,
    /// τ in each mode kind, and the kind and start of the current one.
    mode_tau: [f64; 4],
    kind: usize,
    since: f64,
}

/// A running mode's kind: 0 rest, 1 slide, 2 rock, 3 slide-rock.
fn kind_of(mode: &StackMode, k: usize) -> usize {
    let open = mode.contacts[..k]
        .iter()
        .any(|&c| c != crate::model::stack::Contact::Closed);
    usize::from(mode.sliding()) + 2 * usize::from(open)
}

impl Observer<StackMode, StackEvent, NS> for Keep {
    fn sample(&mut self, t: f64, mode: StackMode, y: &[f64; NS]) {
        if self.keep_history {
            self.history.push(StackSample { tau: t, mode, y: *y });
        }
    }

    fn section(&mut self, k: u64, t: f64, mode: StackMode, y: &[f64; NS]) {
        self.section.push(StackSection {
            k,
            at: StackSample { tau: t, mode, y: *y },
        });
    }

    fn event(&mut self, t: f64, _before: StackMode, _y: &[f64; NS], record: StackEvent) {
        let (was, is) = (record.before.at_rest(self.k), record.after.at_rest(self.k));
        if was && !is {
            self.rest_tau += t - self.rest_since.unwrap_or(t);
            self.rest_since = None;
        } else if !was && is {
            self.rest_since = Some(t);
        }
        self.mode_tau[self.kind] += t - self.since;
        self.kind = kind_of(&record.after, self.k);
        self.since = t;
        self.events.push(record);
    }
}

/// Runs the stack `geo` under `excitation` (in the bottom block's τ)
/// from rest with `opts`. `run.method` "taylor" and "dop853" take
/// DOP853's steps, "dopri5" its own; the fixed-step "ralston" is the
/// single block's (refused for a stack before this is called).
pub fn simulate_stack(
    geo: StackGeometry,
    excitation: Excitation,
    zeno_eps: f64,
    opts: &RunOptions,
) -> Result<StackRun, StackError> {
    simulate_stack_watched(geo, excitation, zeno_eps, opts, None)
}

/// What watches a stack's run at each section time: called with the
/// section points and the events so far, it says whether the run may stop
/// there (its class is certain: `analysis::steady`'s early stop).
pub(crate) type StackWatch<'a> = &'a mut dyn FnMut(&[StackSection], &[StackEvent]) -> bool;

/// [`simulate_stack`], asking `watch` (if any) after each forcing period
/// whether to stop. The legs end on the section times with the run's end
/// as their horizon, so a watched run takes the steps of an unwatched one,
/// and one that is never stopped is the same run bit for bit.
pub(crate) fn simulate_stack_watched(
    geo: StackGeometry,
    excitation: Excitation,
    zeno_eps: f64,
    opts: &RunOptions,
    watch: Option<StackWatch<'_>>,
) -> Result<StackRun, StackError> {
    let system = StackSystem::new(geo, excitation, zeno_eps);
    match opts.method {
        super::Method::Dopri5 => run_with(Dopri5::new(opts.tol), system, opts, watch),
        _ => run_with(Dop853::new(opts.tol), system, opts, watch),
    }
}

fn run_with<S: Stepper<NS>>(
    stepper: S,
    system: StackSystem,
    opts: &RunOptions,
    watch: Option<StackWatch<'_>>,
) -> Result<StackRun, StackError> {
    let start = Instant::now();
    let k = system.geo.k;
    let geo = system.geo;
    let mut y0 = [0.0; NS];
    let mode0 = system.settle(StackMode::REST, 0.0, &mut y0);
    let e0 = system.energy(&mode0, &y0);
    let outputs = Outputs {
        sample_dt: opts.output_dt,
        section_period: if opts.section {
            system.excitation.forcing_period()
        } else {
            None
        },
    };
    let mut driver = Driver::new(stepper, system, mode0, 0.0, y0, opts.limits, outputs);
    let mut keep = Keep {
        k,
        events: Vec::new(),
        // Room for the whole history at once (up to 65,536 samples, 10 MB):
        // growing it by doubling copied it about twice over.
        history: Vec::with_capacity(
            opts.output_dt
                .map_or(0, |dt| ((opts.tau_end / dt).ceil() + 2.0).clamp(0.0, 65_536.0) as usize),
        ),
        keep_history: opts.output_dt.is_some(),
        section: Vec::new(),
        rest_since: mode0.at_rest(k).then_some(0.0),
        rest_tau: 0.0,
        mode_tau: [0.0; 4],
        kind: kind_of(&mode0, k),
        since: 0.0,
    };
    let period = outputs.section_period;
    match opts.rest_after {
        None => match (watch, period) {
            (Some(watch), Some(period)) => {
                while driver.t() < opts.tau_end {
                    let next = ((driver.t() / period).floor() + 1.0) * period;
                    let leg = driver.advance_past(next.min(opts.tau_end), opts.tau_end, &mut keep)?;
                    if leg == Advance::Terminal || watch(&keep.section, &keep.events) {
                        break;
                    }
                }
            }
            _ => {
                driver.advance(opts.tau_end, &mut keep)?;
            }
        },
        Some(rest_after) => {
            driver.advance(rest_after.min(opts.tau_end), &mut keep)?;
            // After the record the ground is still: stop at the first leg
            // that ends with every interface closed.
            while driver.t() < opts.tau_end && !driver.mode().at_rest(k) && driver.mode().end.is_none() {
                driver.advance((driver.t() + 1.0).min(opts.tau_end), &mut keep)?;
            }
        }
    }
    let wall_s = start.elapsed().as_secs_f64();
    let mode = driver.mode();
    let y = *driver.y();
    let t = driver.t();
    let system = driver.system();
    let mut tally = system.tally;
    let pose = system.pose(&mode, &y);
    for (j, q) in y.iter().enumerate().take(k) {
        tally.max_phi[j] = tally.max_phi[j].max(pose.phi[j].abs());
        tally.max_q[j] = tally.max_q[j].max(q.abs());
    }
    let e_final = system.energy(&mode, &y);
    tally.max_slide = tally.max_slide.max(y[crate::model::stack::SLIDE].abs());
    let (work, impact, friction) = (y[WORK_S], tally.impact_loss, y[FRICTION_S]);
    let energy = EnergyAudit::new(e0, e_final, work, friction, impact);
    let end = mode.end.map(|e| (e, keep.events.last().map_or(t, |ev| ev.tau)));
    let outcome = match mode.end {
        Some(StackEnd::Overturned(_)) => Outcome::Tumbled,
        Some(StackEnd::Flight(_)) => Outcome::Flight,
        None if mode.at_rest(k) => Outcome::Rest,
        None => Outcome::Running,
    };
    let mut rest_tau = keep.rest_tau;
    if let Some(since) = keep.rest_since {
        rest_tau += t - since;
    }
    let mut mode_tau = keep.mode_tau;
    if mode.end.is_none() {
        mode_tau[keep.kind] += t - keep.since;
    }
    let tau_rest = (outcome == Outcome::Rest).then(|| keep.rest_since.unwrap_or(0.0));
    let mut stats = driver.stepper().stats();
    stats.accepted = stats.accepted.max(driver.steps());
    Ok(StackRun {
        geo,
        outcome,
        end,
        tau_end: t,
        tau_rest,
        rest_tau,
        mode_tau,
        events: keep.events,
        history: keep.history,
        section: keep.section,
        last: StackSample { tau: t, mode, y },
        tally,
        energy,
        stats,
        wall_s,
    })
}
