//! A stack's steady response (config `[[stack]]`): its run over a sampling
//! window, its section points classified over every interface.
//!
//! The same study as the block's [`steady_response`](super::steady_response), with
//! what a stack has instead of the block's one angle:
//! - **Classified on the whole state.** A section point is every
//!   interface's rotation q_i and rate q_i' and the rate u' of its slip on
//!   the floor (u'/R₁, each over the top block's α, so that the
//!   classifier's relative tolerance reads as on the block's Θ = θ/ψ); a
//!   stack is periodic only when every interface and the slip's rate
//!   repeat (the slip itself may drift, as the block's X does).
//! - **Reported as its top block.** The points a sweep writes and a map
//!   keeps (`theta`, `theta_dot`, `max_abs_theta`) are the top block's
//!   rotation φ_K = q_1 + … + q_K over its own α_K = atan(B_K/H_K), and its
//!   rate: the body an owner of a statue or a tombstone watches, whose
//!   rotation carries every interface below it. `x` and `x_dot` are the
//!   slip u on the floor and its rate, per the bottom block's R₁.
//! - **No seed.** A stack starts at rest on its base, so a continuation
//!   sweep cannot start it where the previous value ended; it is refused
//!   before anything runs ([`check_stack_study`]).
//! - **Its exponent by two trajectories.** Asked for Lyapunov exponents,
//!   a stack's moving response gets its largest one from the hook, as the
//!   block's does (`largest_for_scenario` computes a stack's by two
//!   trajectories: its tangent equations are not written), and an
//!   aperiodic response is classified with it.
//! - **Its own early stop.** A map cell stops as soon as it is at rest for
//!   a whole period or has converged onto a periodic orbit, by the block's
//!   criteria on the stack's section points (`stack_settle.rs`); a
//!   sweep's points run their whole window, as the block's do.

use super::stack_settle::{StackSettle, StackVerdict};
use super::{LyapunovFn, Steady, SteadyError, Window, exponent_of};
use crate::analysis::classify::{ClassifyOptions, Response, classify_points};
use crate::analysis::section::points_in_window;
use crate::analysis::settle::CellResponse;
use crate::analysis::settle::forcing_is_periodic;
use crate::model::excitation::Excitation;
use crate::model::stack::StackEvent;
use crate::model::stack::{Contact, MAX_BLOCKS, Pose, SLIDE, SLIDE_RATE, StackGeometry};
use crate::sim::stack_run::{StackRun, StackSection, StackWatch, simulate_stack, simulate_stack_watched};
use crate::sim::{Param, RunOptions, Scenario, ScenarioError, SectionRow};

/// The stack's classified coordinates: q_1 … q_K, q_1' … q_K' (padded),
/// u'.
const D: usize = 2 * MAX_BLOCKS + 1;

/// Refuses, before anything runs, what a study cannot do with the stack of
/// `base`: a swept key the stack does not read (its blocks' sizes and
/// friction are the `[[stack]]` tables'; it starts at rest) and a
/// continuation (`continued`).
pub fn check_stack_study(base: &Scenario, params: &[Param], continued: bool) -> Result<(), SteadyError> {
    if base.stack.is_none() {
        return Ok(());
    }
    let refuse = |key: &str, why: &str| Err(SteadyError::Scenario(ScenarioError::new(key, why)));
    for &p in params {
        if !p.applies_to_stack() {
            return refuse(
                p.key(),
                "is not read by a [[stack]] (its blocks' sizes and friction are its tables', and it starts at rest): vary an excitation key",
            );
        }
    }
    if continued {
        return refuse(
            "stack",
            "a [[stack]] starts at rest on its base, so a sweep cannot continue from the previous value's state: sweep without continuation",
        );
    }
    Ok(())
}

/// The top block's section point as the block's [`SectionRow`] (module
/// docs): Θ = φ_K/α_K and its rate, the slip and its rate per R₁, and
/// the mode: `rest` with every interface closed, otherwise rocking on the
/// side of the topmost open interface, each sliding while the floor slips.
fn top_row(geo: &StackGeometry, s: &StackSection) -> SectionRow {
    let (theta, theta_dot) = top_angle(geo, &s.at.mode.contacts, &s.at.y);
    let open = s.at.mode.contacts[..geo.k]
        .iter()
        .rev()
        .find(|c| **c != Contact::Closed)
        .copied()
        .unwrap_or(Contact::Closed);
    let mode = crate::sim::protocol::face_mode(open, s.at.mode.slip);
    SectionRow {
        k: s.k,
        tau: s.at.tau,
        theta,
        theta_dot,
        x: s.at.y[SLIDE] / geo.r1,
        x_dot: s.at.y[SLIDE_RATE] / geo.r1,
        mode,
    }
}

/// The top block's rotation and rate over its α (rad over rad, per τ).
fn top_angle(geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS], y: &[f64; crate::model::stack::NS]) -> (f64, f64) {
    let top = geo.k - 1;
    let alpha = top_alpha(geo);
    let pose = Pose::new(geo, contacts, y);
    (pose.phi[top] / alpha, pose.omega[top] / alpha)
}

/// α_K = atan(B_K/H_K) of the top block, rad.
fn top_alpha(geo: &StackGeometry) -> f64 {
    let [b, h] = geo.size[geo.k - 1];
    (b / h).atan()
}

/// The section point's classified coordinates (module docs).
fn coordinates(geo: &StackGeometry, s: &StackSection) -> [f64; D] {
    let alpha = top_alpha(geo);
    std::array::from_fn(|d| {
        if d < 2 * MAX_BLOCKS {
            s.at.y[d] / alpha
        } else {
            s.at.y[SLIDE_RATE] / (geo.r1 * alpha)
        }
    })
}

/// The class of a stack's run sampled over `window` with forcing period
/// `period` (τ), as [`classify_run`](super::classify::classify_run) gives
/// the block's: the terminal ends and rest (nothing happening in the last
/// forcing period) first, then the points after the transient.
fn classify_stack(
    run: &StackRun,
    period: f64,
    transient: f64,
    exponent: Option<f64>,
    opts: &ClassifyOptions,
) -> Result<Response, SteadyError> {
    use crate::sim::Outcome;
    match run.outcome {
        Outcome::Tumbled => return Ok(Response::Tumbled),
        Outcome::Flight => return Ok(Response::Flight),
        Outcome::Rest => {
            let last_event = run.events.last().map_or(0.0, |e| e.tau);
            if last_event <= run.tau_end - period {
                return Ok(Response::Rest);
            }
        }
        Outcome::Running => {}
    }
    let points: Vec<[f64; D]> = run
        .section
        .iter()
        .filter(|s| s.at.tau >= transient)
        .map(|s| coordinates(&run.geo, s))
        .collect();
    Ok(classify_points(&points, exponent, opts)?)
}

/// Runs the stack of `scenario` over `window` and classifies its steady
/// response (module docs), with its largest exponent from `lyapunov` if
/// given. The scenario must have a `[[stack]]` and harmonic excitation.
pub fn stack_steady(
    scenario: &Scenario,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
) -> Result<Steady, SteadyError> {
    Ok(run_and_classify(scenario, window, opts, lyapunov)?.0)
}

/// A map cell of a stack: [`stack_steady`]'s run, as the map keeps it (its
/// cycle is the top block's last `period` points), stopped as soon as its
/// class is certain when `early` is set and the forcing has the section's
/// period (module docs); otherwise run out, with the same class.
pub(crate) fn stack_cell(
    scenario: &Scenario,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
    early: bool,
) -> Result<CellResponse, SteadyError> {
    let w = StackWindow::new(scenario, window)?;
    let point = |s: &StackSection| {
        let row = top_row(&w.geo, s);
        (coordinates(&w.geo, s), [row.theta, row.theta_dot, row.x_dot])
    };
    let mut settle = StackSettle::new(w.period, w.geo.k, *opts, &point);
    let mut watch = |sections: &[StackSection], events: &[StackEvent]| settle.watch(sections, events);
    let watch: Option<StackWatch<'_>> = (early && forcing_is_periodic(scenario)).then_some(&mut watch);
    let run = simulate_stack_watched(w.geo, w.excitation.clone(), w.cfg.run.zeno_eps, &w.run, watch)?;
    let (response, cycle, stopped_at) = match settle.verdict() {
        Some(StackVerdict::Rest { tau }) => (Response::Rest, Vec::new(), Some(*tau)),
        Some(StackVerdict::Periodic { tau, cycle, top }) => {
            // The window's points as the full run would have them (as the
            // block's cell builds them): those taken after the transient,
            // then the converged cycle repeated.
            let n = points_in_window(w.period, window.transient, window.tau_end) as usize;
            let taken: Vec<&StackSection> = run.section.iter().filter(|s| s.at.tau >= window.transient).collect();
            let mut points: Vec<[f64; D]> = taken.iter().map(|s| coordinates(&w.geo, s)).collect();
            let mut tops: Vec<[f64; 3]> = taken.iter().map(|s| point(s).1).collect();
            let k = cycle.len();
            for j in 0..n.max(opts.min_points()).saturating_sub(points.len()) {
                points.push(cycle[j % k]);
                tops.push(top[j % k]);
            }
            let response = classify_points(&points, None, opts)?;
            let cycle = match response {
                Response::Periodic { period } => tops[tops.len() - period as usize..].to_vec(),
                _ => Vec::new(),
            };
            (response, cycle, Some(*tau))
        }
        None => {
            // Run out: classified as a sweep's point is.
            let steady = w.steady(&run, window, opts, lyapunov)?;
            return Ok(CellResponse {
                cycle: top_cycle(&steady.response, &steady.points),
                response: steady.response,
                max_abs_theta: steady.max_abs_theta,
                lyapunov: steady.lyapunov,
                stopped_at: None,
                reached_known: false,
                settled_at: run.tau_end,
            });
        }
    };
    Ok(CellResponse {
        lyapunov: exponent_of(lyapunov, response, &w.cfg)?,
        response,
        max_abs_theta: run.tally.max_phi[w.geo.k - 1] / top_alpha(&w.geo),
        cycle,
        stopped_at,
        reached_known: false,
        settled_at: stopped_at.unwrap_or(run.tau_end),
    })
}

/// A periodic response's cycle: the top block's last `period` points.
fn top_cycle(response: &Response, points: &[SectionRow]) -> Vec<[f64; 3]> {
    match *response {
        Response::Periodic { period } => points[points.len() - period as usize..]
            .iter()
            .map(|r| [r.theta, r.theta_dot, r.x_dot])
            .collect(),
        _ => Vec::new(),
    }
}

/// A stack's run over a window: the scenario with the window's end, its
/// shape, forcing period and excitation, and the run's options (section
/// points, no history).
struct StackWindow {
    cfg: Scenario,
    geo: StackGeometry,
    period: f64,
    excitation: Excitation,
    run: RunOptions,
}

impl StackWindow {
    fn new(scenario: &Scenario, window: &Window) -> Result<Self, SteadyError> {
        let mut cfg = scenario.clone();
        cfg.run.tau_end = window.tau_end;
        let geo = cfg.stack_geometry().ok_or_else(|| {
            SteadyError::Scenario(ScenarioError::new("stack", "its blocks do not stand on each other"))
        })?;
        let excitation = cfg.excitation()?;
        let Some(period) = excitation.forcing_period() else {
            return Err(SteadyError::NotHarmonic);
        };
        let mut run = cfg.run_options();
        run.output_dt = None;
        run.section = true;
        Ok(Self {
            cfg,
            geo,
            period,
            excitation,
            run,
        })
    }

    /// The steady response of `run`, a whole run over `window`, with its
    /// exponent from `lyapunov` if given.
    fn steady(
        &self,
        run: &StackRun,
        window: &Window,
        opts: &ClassifyOptions,
        lyapunov: Option<&LyapunovFn<'_>>,
    ) -> Result<Steady, SteadyError> {
        let mut response = classify_stack(run, self.period, window.transient, None, opts)?;
        let exponent = exponent_of(lyapunov, response, &self.cfg)?;
        if exponent.is_some() {
            response = classify_stack(run, self.period, window.transient, exponent, opts)?;
        }
        let points = if response.is_terminal() {
            Vec::new()
        } else {
            run.section
                .iter()
                .filter(|s| s.at.tau >= window.transient)
                .map(|s| top_row(&self.geo, s))
                .collect()
        };
        Ok(Steady {
            response,
            max_abs_theta: run.tally.max_phi[self.geo.k - 1] / top_alpha(&self.geo),
            lyapunov: exponent,
            points,
            seed: None,
        })
    }
}

/// The steady response and the τ at which the run ended.
fn run_and_classify(
    scenario: &Scenario,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
) -> Result<(Steady, f64), SteadyError> {
    let w = StackWindow::new(scenario, window)?;
    let run = simulate_stack(w.geo, w.excitation.clone(), w.cfg.run.zeno_eps, &w.run)?;
    Ok((w.steady(&run, window, opts, lyapunov)?, run.tau_end))
}
