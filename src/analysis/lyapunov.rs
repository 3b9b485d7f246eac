//! Lyapunov exponents of the block, two independent ways that must agree,
//! both correct across impacts and mode switches.
//!
//! - **Tangent dynamics** ([`Method::Tangent`]): the variational equations
//!   of each mode (`model::variational`) are integrated with the state; at
//!   every event (impact and every mode switch) the tangent vectors are
//!   mapped by the saltation matrix
//!   `S = J_R + (f⁺ − J_R f⁻) n_yᵀ / (n_y·f⁻ + ∂g/∂τ)`
//!   (Müller 1995; Leine & Nijmeijer 2004); once per forcing period they
//!   are re-orthonormalised by QR and `ln R_ii` accumulated (Benettin et
//!   al. 1980). This gives the whole spectrum.
//! - **Two trajectories** ([`Method::Benettin`]): a fiducial and a
//!   perturbed run, renormalised only on the stroboscopic section
//!   `τ_k = 2πk/Ω_h`, where both are smooth. This gives the largest
//!   exponent and is independent of the Jacobians.
//!
//! # Phase space and what the spectrum contains
//!
//! The forced block's state is `(Θ, Θ', X, X')` (plus the phase of the
//! forcing). Exponents are computed in `z = (Θ, Θ', X')`:
//! - `X` is a **neutral** direction: nothing depends on it (translation
//!   along the base), so its exponent is exactly 0. It is not computed and
//!   not listed in [`LyapunovResult::spectrum`].
//! - `X'` is free only while the pivot slips. Rock slaves it to
//!   `cos φ · ψΘ'`, and every sticking impact (the `ratio` and `housner`
//!   laws) resets it from `Θ'` alone, so a perturbation of the slip
//!   velocity is annihilated in finite time: its exponent is −∞. Such
//!   directions are counted in [`LyapunovResult::collapsed`] instead of
//!   being given a number. Without sliding (`μ_s = ∞`) the spectrum is the
//!   two exponents of `(Θ, Θ')`.
//! - A response that passes through rest or flat sliding (an impact
//!   accumulation, a flat landing) forgets every perturbation of `Θ` in
//!   finite time: it has no finite exponent ([`NoExponent::FlatPhases`]).
//!   Tumbling and flight end the motion ([`NoExponent::Tumbled`],
//!   [`NoExponent::Flight`]). These are typed results, never NaN.
//!
//! # Units
//!
//! Exponents are per unit τ (`τ = p t`), natural log
//! ([`LyapunovResult::largest_per_tau`]), and per excitation cycle
//! (`× 2π/Ω_h`, [`LyapunovResult::per_cycle`]). The paper does not state
//! its units.
//!
//! # Error bars
//!
//! The accumulation window (after the transient) is split into batches;
//! the standard error is that of the batch means (`batch.rs`).
//!
//! # Which trajectory
//!
//! [`lyapunov`] integrates its own trajectory from the initial state (the
//! tangent method integrates the state with its tangent vectors, so its
//! steps differ from a plain run's). Several of the paper's presets show
//! transient chaos that ends in a tumble, or chaos beside a stable periodic
//! orbit; round-off then decides where a trajectory goes, and a plain run,
//! a tangent run and a two-trajectory run may end up in different places.
//! [`Method::Both`] computes both estimates on one fiducial trajectory, so
//! they are always comparable.
//!
//! The generic machinery ([`TangentSystem`], [`exponents`] with a
//! [`Request`]) works for any hybrid system that provides Jacobians and is
//! tested on systems with known exponents.
//!
//! # A frame and a stack
//!
//! The frame's tangent equations are generated from its equations
//! (`model/frame/tangent.rs`), so it has its whole spectrum as the block
//! has (`frame.rs`). A stack's are not written, so it has no spectrum: the
//! two-trajectory method needs only [`Perturbable`] (coordinates, the free
//! directions of a mode, a displaced state) and gives its largest exponent
//! ([`two_trajectories`]; `stack.rs`).
//! [`of_scenario`] runs whichever body a scene has; [`method_for`] is the
//! method each body has (the app's choice).

mod batch;
mod benettin;
mod block;
mod frame;
mod qr;
mod report;
mod run;
mod stack;
mod tangent;

pub use batch::{Accumulator, CONVERGENCE_POINTS, Estimate, standard_error};
pub use qr::{Square, qr};
pub use report::{Agreement, Lyapunov, LyapunovError, LyapunovOptions, LyapunovResult, Method, NoExponent};
pub use run::{Outcome, Request, Schedule, exponents, two_trajectories};
pub use tangent::{Augmented, Perturbable, TangentError, TangentSystem};

use crate::integrate::Tolerances;
use crate::model::excitation::Excitation;
use crate::model::stack::{NS, StackEnd, StackGeometry, StackMode, StackSystem};
use crate::model::system::{ModelError, N};
use crate::model::variational::{self, DIM};
use crate::model::{BlockSystem, FRAME_DIM, FrameSystem, Mode, Model, RockerCore};
use crate::sim::Scenario;
use crate::sim::{self, InitialState};
use stack::STACK_DIM;

/// The method a body's exponents are best computed by (the app's, and the
/// default of `analysis.lyapunov_method`): tangent dynamics (the whole
/// spectrum) for the single block and the frame, two trajectories (the
/// largest exponent) for a stack, whose tangent equations are not written.
pub fn method_for(cfg: &Scenario) -> Method {
    if cfg.stack.is_some() {
        Method::Benettin
    } else {
        Method::Tangent
    }
}

/// The Lyapunov exponents of the scene `cfg` (its block, frame or stack)
/// from its initial state, with `opts`: what `analysis.lyapunov`, the app
/// and Python's `lyapunov` compute.
pub fn of_scenario(cfg: &Scenario, opts: &LyapunovOptions) -> Result<Lyapunov, LyapunovError> {
    if cfg.stack.is_some() {
        let geo = cfg
            .stack_geometry()
            .ok_or_else(|| crate::sim::ScenarioError::new("stack", "is not a valid stack"))?;
        return stack_lyapunov(geo, cfg.excitation()?, cfg.run.zeno_eps, opts);
    }
    lyapunov(&cfg.model()?, &cfg.initial, opts)
}

/// The grid a run of `opts` renormalises on, for forcing period `period`.
fn schedule(opts: &LyapunovOptions, period: f64) -> Result<Schedule, LyapunovError> {
    let transient = (opts.transient_tau / period).ceil() as u64;
    let total = (opts.total_tau / period).floor() as u64;
    if total < transient + 2 {
        return Err(LyapunovError::TooShort { period });
    }
    Ok(Schedule {
        period,
        transient,
        total,
        batches: opts.batches,
    })
}

fn tolerances(opts: &LyapunovOptions) -> Tolerances {
    Tolerances {
        rtol: opts.rtol,
        atol: opts.atol,
        ..Tolerances::default()
    }
}

/// How a body's run ended, for [`answer`].
struct Ending {
    /// Why a terminal mode has no exponent.
    terminal: NoExponent,
    /// Whether the final mode is rest (else flat phases) when fewer than
    /// two directions stayed alive.
    at_rest: bool,
}

/// The answer of an [`Outcome`] of `D` tangent coordinates: `ending` says
/// what the body's modes mean, `neutral` names the direction left out.
fn answer<M: Copy, const D: usize>(
    outcome: Outcome<M, D>,
    opts: &LyapunovOptions,
    schedule: &Schedule,
    ending: impl Fn(M) -> Ending,
    neutral: &'static str,
) -> Result<Lyapunov, LyapunovError> {
    let method = opts.method;
    let period = schedule.period;
    let none = |no_exponent, tau| Lyapunov::None {
        method,
        no_exponent,
        tau,
    };
    let (tangent, benettin, min_dim, final_mode) = match outcome {
        Outcome::Estimate {
            tangent,
            benettin,
            min_dim,
            final_mode,
        } => (tangent, benettin, min_dim, final_mode),
        Outcome::Terminal { mode, t } => return Ok(none(ending(mode).terminal, t)),
        Outcome::Collapsed { t } => return Ok(none(NoExponent::FlatPhases, t)),
    };
    // Fewer than the two directions of a rotation and its rate: the
    // response went flat.
    if min_dim < 2 {
        let reason = if ending(final_mode).at_rest {
            NoExponent::Rest
        } else {
            NoExponent::FlatPhases
        };
        return Ok(none(reason, opts.total_tau.min(schedule.total as f64 * period)));
    }
    let finite = min_dim.min(D);
    let result = match (tangent, benettin) {
        (Some(t), b) => {
            let check = b.map(|b| {
                let diffs: Vec<f64> = t.batch_means.iter().zip(&b.batch_means).map(|(x, y)| x - y).collect();
                Agreement {
                    benettin_per_tau: b.exponents[0],
                    benettin_stderr: b.stderr[0],
                    difference: t.exponents[0] - b.exponents[0],
                    difference_stderr: standard_error(&diffs),
                }
            });
            // QR order is the Oseledets order in the limit; finite-time
            // estimates of equal exponents (a complex pair of Floquet
            // multipliers) can come out in either order, so sort.
            let mut pairs: Vec<(f64, f64)> = t.exponents.iter().copied().zip(t.stderr).take(finite).collect();
            pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
            let (largest, stderr) = pairs.first().copied().unwrap_or((t.exponents[0], t.stderr[0]));
            LyapunovResult {
                method,
                largest_per_tau: largest,
                per_cycle: largest * period,
                stderr,
                stderr_per_cycle: stderr * period,
                spectrum: pairs.iter().map(|p| p.0).collect(),
                spectrum_stderr: pairs.iter().map(|p| p.1).collect(),
                collapsed: D - finite,
                convergence: t.convergence,
                tau_start: t.t_start,
                tau_end: t.t_end,
                period,
                renormalisations: t.renormalisations,
                batches: t.batches,
                neutral,
                check,
            }
        }
        // Growth is measured whenever the perturbed copy is in the
        // fiducial's mode; never measuring means no admissible perturbation
        // existed (a flat block), which `min_dim` has already caught.
        (None, Some(b)) if b.span <= 0.0 => return Ok(none(NoExponent::FlatPhases, b.t_end)),
        (None, Some(b)) => LyapunovResult {
            method,
            largest_per_tau: b.exponents[0],
            per_cycle: b.exponents[0] * period,
            stderr: b.stderr[0],
            stderr_per_cycle: b.stderr[0] * period,
            spectrum: Vec::new(),
            spectrum_stderr: Vec::new(),
            collapsed: 0,
            convergence: b.convergence,
            tau_start: b.t_start,
            tau_end: b.t_end,
            period,
            renormalisations: b.renormalisations,
            batches: b.batches,
            neutral,
            check: None,
        },
        (None, None) => {
            return Err(LyapunovError::Option {
                field: "method",
                reason: "asked for no estimate",
            });
        }
    };
    Ok(Lyapunov::Exponents(Box::new(result)))
}

/// The block's (and the frame's) modes, for [`answer`].
fn block_ending(mode: Mode) -> Ending {
    Ending {
        terminal: match mode {
            Mode::Flight => NoExponent::Flight,
            Mode::Tumbled | Mode::Rest | Mode::Slide { .. } | Mode::Rock { .. } | Mode::SlideRock { .. } => {
                NoExponent::Tumbled
            }
        },
        at_rest: mode == Mode::Rest,
    }
}

/// The Lyapunov exponents of `model` started from `init` (see the module
/// docs for the phase space, units and typed non-results): the block's,
/// or the frame's when the model has one.
pub fn lyapunov(model: &Model, init: &InitialState, opts: &LyapunovOptions) -> Result<Lyapunov, LyapunovError> {
    opts.validate()?;
    let period = model.excitation.forcing_period().ok_or(LyapunovError::NotHarmonic)?;
    if model.frame.is_some() {
        let (outcome, schedule) = outcome_of::<_, FRAME_DIM, { N + FRAME_DIM * FRAME_DIM }>(
            FrameSystem::new(model.clone()),
            model,
            init,
            opts,
            period,
        )?;
        return answer(outcome, opts, &schedule, block_ending, "X");
    }
    if variational::forcing_rate(&model.excitation, 0.0).is_none() {
        return Err(LyapunovError::NotHarmonic);
    }
    let (outcome, schedule) =
        outcome_of::<_, DIM, { N + DIM * DIM }>(BlockSystem::new(model.clone()), model, init, opts, period)?;
    answer(outcome, opts, &schedule, block_ending, "X")
}

/// The outcome of `opts.method` on `sys`, the block's or the frame's
/// system of `model`, started from `init`, with its schedule.
fn outcome_of<S, const D: usize, const NA: usize>(
    mut sys: S,
    model: &Model,
    init: &InitialState,
    opts: &LyapunovOptions,
    period: f64,
) -> Result<(Outcome<Mode, D>, Schedule), LyapunovError>
where
    S: TangentSystem<N, D, Mode = Mode, Error = ModelError> + RockerCore + Clone,
    nalgebra::Const<D>: nalgebra::DimMin<nalgebra::Const<D>, Output = nalgebra::Const<D>>,
{
    let (mode0, mut y0) = sim::initial_mode(model, init)?;
    let mode0 = sys.settle_mode(mode0, 0.0, &mut y0);
    let schedule = schedule(opts, period)?;
    let method = opts.method;
    let request = Request {
        tangent: matches!(method, Method::Tangent | Method::Both),
        separation: matches!(method, Method::Benettin | Method::Both).then_some(opts.separation),
    };
    let outcome = exponents::<_, N, D, NA>(sys, mode0, y0, &schedule, tolerances(opts), opts.limits, request)?;
    Ok((outcome, schedule))
}

/// The outcome of the two-trajectory method on `sys`, a body without
/// tangent equations (`body` names it where another method is refused),
/// started in `mode0` at `y0`, with its schedule.
fn two_trajectory_outcome<S, const N: usize, const D: usize>(
    sys: S,
    mode0: S::Mode,
    y0: [f64; N],
    opts: &LyapunovOptions,
    period: f64,
    body: &'static str,
) -> Result<(Outcome<S::Mode, D>, Schedule), LyapunovError>
where
    S: Perturbable<N, D> + Clone,
    LyapunovError: From<TangentError<S::Error>>,
{
    if opts.method != Method::Benettin {
        return Err(LyapunovError::NoTangent {
            body,
            asked: opts.method.name(),
        });
    }
    let schedule = schedule(opts, period)?;
    let tol = tolerances(opts);
    let outcome = two_trajectories::<_, N, D>(sys, mode0, y0, &schedule, tol, opts.limits, opts.separation)?;
    Ok((outcome, schedule))
}

/// The largest exponent of the stack `geo` under `excitation` (in its
/// bottom block's τ), started at rest as every stack run is, by two
/// trajectories in the tangent coordinates of `lyapunov/stack.rs`.
pub(crate) fn stack_lyapunov(
    geo: StackGeometry,
    excitation: Excitation,
    zeno_eps: f64,
    opts: &LyapunovOptions,
) -> Result<Lyapunov, LyapunovError> {
    opts.validate()?;
    let period = excitation.forcing_period().ok_or(LyapunovError::NotHarmonic)?;
    let sys = StackSystem::new(geo, excitation, zeno_eps);
    let mut y0 = [0.0; NS];
    let mode0 = sys.settle(StackMode::REST, 0.0, &mut y0);
    let (outcome, schedule) = two_trajectory_outcome::<_, NS, STACK_DIM>(sys, mode0, y0, opts, period, "[[stack]]")?;
    let k = geo.k;
    let ending = |mode: StackMode| Ending {
        terminal: match mode.end {
            Some(StackEnd::Flight(_)) => NoExponent::Flight,
            Some(StackEnd::Overturned(_)) | None => NoExponent::Tumbled,
        },
        at_rest: mode.at_rest(k),
    };
    answer(outcome, opts, &schedule, ending, "u")
}

/// The largest exponent per τ of a scenario (for sweeps and outcome
/// maps) by [`method_for`] it (tangent dynamics for the block, two
/// trajectories for a frame or a stack), with
/// [`LyapunovOptions::for_scenario`]; `None` when the response has no
/// finite exponent or the run fails.
pub fn largest_for_scenario(cfg: &Scenario) -> Option<f64> {
    let opts = LyapunovOptions::for_scenario(cfg, method_for(cfg));
    of_scenario(cfg, &opts).ok()?.largest_per_tau()
}
