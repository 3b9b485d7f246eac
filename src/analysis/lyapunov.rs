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
mod run;
mod stack;
mod tangent;

use serde::Serialize;
use serde_json::{Value as Json, json};

pub use batch::{Accumulator, CONVERGENCE_POINTS, Estimate, standard_error};
pub use qr::{Square, qr};
pub use run::{Outcome, Request, Schedule, exponents, two_trajectories};
pub use tangent::{Augmented, Perturbable, TangentError, TangentSystem};

use crate::integrate::Tolerances;
use crate::integrate::hybrid::Limits;
use crate::model::excitation::Excitation;
use crate::model::stack::{NS, StackEnd, StackError, StackGeometry, StackMode, StackSystem};
use crate::model::system::{ModelError, N};
use crate::model::variational::{self, DIM};
use crate::model::{BlockSystem, FRAME_DIM, FrameSystem, Mode, Model, RockerCore};
use crate::sim::Scenario;
use crate::sim::{self, InitialState, SimError};
use stack::STACK_DIM;

/// Which way to compute the exponents.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Variational equations with saltation matrices and QR: the whole
    /// spectrum (default: it needs no separation parameter and resolves
    /// every exponent).
    Tangent,
    /// Two trajectories renormalised on the stroboscopic section: the
    /// largest exponent, as an independent check.
    Benettin,
    /// Both, on one fiducial trajectory: the tangent result with the
    /// two-trajectory estimate and their paired difference
    /// ([`LyapunovResult::check`]).
    Both,
}

impl Method {
    /// Name used in configs and outputs: `tangent`, `benettin`, `both`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Tangent => "tangent",
            Method::Benettin => "benettin",
            Method::Both => "both",
        }
    }

    /// The method called `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "tangent" => Some(Method::Tangent),
            "benettin" => Some(Method::Benettin),
            "both" => Some(Method::Both),
            _ => None,
        }
    }
}

/// Options of [`lyapunov`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LyapunovOptions {
    /// Method.
    pub method: Method,
    /// Discarded start, τ (rounded up to whole forcing periods). Default
    /// 600, the paper's own transient before its Poincaré points: the
    /// chaotic transients of its presets last a few hundred τ.
    pub transient_tau: f64,
    /// End of the run, τ (rounded down to whole forcing periods). Default
    /// 2600, i.e. 2000 τ of accumulation: about 2500 periods at Ω = 8,
    /// which brings the batch-means error of a chaotic response to ~0.015.
    pub total_tau: f64,
    /// Relative tolerance of the integrator (DOP853). Default 1e-11: the
    /// two-trajectory method measures separations of `separation` = 1e-7,
    /// so the integration error per period must stay far below that.
    pub rtol: f64,
    /// Absolute tolerance. Default 1e-13 (see `rtol`).
    pub atol: f64,
    /// Batches for the error estimate. Default 16: enough for a usable
    /// standard deviation of the batch means, while each batch stays long
    /// (≥ 100 periods by default) compared with the decorrelation time.
    pub batches: usize,
    /// Separation of the two trajectories in `(Θ, Θ', X')` after each
    /// renormalisation (Benettin only). Default 1e-7: small enough for the
    /// linear regime (the attractor's size is ~1), large enough that the
    /// integration error (~1e-11 relative) is a 1e-4 part of it.
    pub separation: f64,
    /// Loop bounds of the driver.
    pub limits: Limits,
}

impl Default for LyapunovOptions {
    fn default() -> Self {
        Self {
            method: Method::Tangent,
            transient_tau: 600.0,
            total_tau: 2600.0,
            rtol: 1e-11,
            atol: 1e-13,
            batches: 16,
            separation: 1e-7,
            limits: Limits::default(),
        }
    }
}

impl LyapunovOptions {
    /// Options for a configured run: the run's `tau_end` and loop limits,
    /// the transient of [`Default`] or half the run, whichever is shorter,
    /// and `method`.
    pub fn for_scenario(cfg: &Scenario, method: Method) -> Self {
        let d = Self::default();
        Self {
            method,
            transient_tau: d.transient_tau.min(0.5 * cfg.run.tau_end),
            total_tau: cfg.run.tau_end,
            limits: Limits {
                max_steps: cfg.run.max_steps,
                max_events: cfg.run.max_events,
                ..Limits::default()
            },
            ..d
        }
    }

    fn validate(&self) -> Result<(), LyapunovError> {
        let bad = |field: &'static str, reason: &'static str| Err(LyapunovError::Option { field, reason });
        if !(self.transient_tau.is_finite() && self.transient_tau >= 0.0) {
            return bad("transient_tau", "must be a finite number >= 0");
        }
        if !(self.total_tau.is_finite() && self.total_tau > self.transient_tau) {
            return bad("total_tau", "must be finite and greater than transient_tau");
        }
        if !(self.rtol > 0.0 && self.rtol <= 1e-3) {
            return bad("rtol", "must be in (0, 1e-3]");
        }
        if !(self.atol > 0.0 && self.atol.is_finite()) {
            return bad("atol", "must be a finite number > 0");
        }
        if self.batches < 2 {
            return bad("batches", "must be at least 2");
        }
        if !(self.separation > 0.0 && self.separation <= 1e-3) {
            return bad("separation", "must be in (0, 1e-3]");
        }
        Ok(())
    }
}

/// Exponents of a response that has them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LyapunovResult {
    /// How they were computed.
    pub method: Method,
    /// Largest exponent per unit τ (natural log).
    pub largest_per_tau: f64,
    /// Largest exponent per excitation cycle (`× 2π/Ω_h`).
    pub per_cycle: f64,
    /// Standard error of `largest_per_tau` (batch means), per τ.
    pub stderr: f64,
    /// Standard error of `per_cycle`.
    pub stderr_per_cycle: f64,
    /// Tangent only: the finite exponents of `(Θ, Θ', X')` per τ, sorted
    /// largest first. The neutral direction `X` (exponent exactly 0) is not listed;
    /// directions annihilated in finite time are counted in `collapsed`.
    /// Empty for the two-trajectory method.
    pub spectrum: Vec<f64>,
    /// Standard errors of `spectrum`.
    pub spectrum_stderr: Vec<f64>,
    /// Tangent only: directions of `(Θ, Θ', X')` whose exponent is −∞ (the
    /// slip velocity when the pivot sticks at impacts or in rock). 0 for
    /// the two-trajectory method.
    pub collapsed: usize,
    /// `(τ, running estimate of the largest exponent per τ)`.
    pub convergence: Vec<(f64, f64)>,
    /// Start of the accumulation window, τ.
    pub tau_start: f64,
    /// End of the accumulation window, τ.
    pub tau_end: f64,
    /// Renormalisation interval (the forcing period 2π/Ω_h), τ.
    pub period: f64,
    /// Renormalisations in the window.
    pub renormalisations: u64,
    /// Batches behind the error estimates.
    pub batches: usize,
    /// The neutral direction left out of the exponents (exponent exactly
    /// 0): the block's or the frame's X, a stack's slip u.
    pub neutral: &'static str,
    /// [`Method::Both`] only: the two-trajectory estimate on the same
    /// fiducial trajectory and its paired difference from the tangent one.
    pub check: Option<Agreement>,
}

/// The two methods compared on one fiducial trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Agreement {
    /// Two-trajectory largest exponent per τ.
    pub benettin_per_tau: f64,
    /// Its standard error (batch means), per τ.
    pub benettin_stderr: f64,
    /// Tangent minus two-trajectory, per τ.
    pub difference: f64,
    /// Standard error of the difference from the paired batch means (both
    /// estimates share the trajectory, so this is much smaller than either
    /// error alone when the methods agree).
    pub difference_stderr: f64,
}

/// Why a response has no finite exponent.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NoExponent {
    /// The block tumbled.
    Tumbled,
    /// The block left the base (with `flight = stop`).
    Flight,
    /// The block is at rest at the end.
    Rest,
    /// The response passes through rest or flat sliding, where every
    /// perturbation of Θ dies out in finite time (exponent −∞).
    FlatPhases,
}

impl NoExponent {
    /// Name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            NoExponent::Tumbled => "tumbled",
            NoExponent::Flight => "flight",
            NoExponent::Rest => "rest",
            NoExponent::FlatPhases => "flat-phases",
        }
    }
}

/// The answer of [`lyapunov`].
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Lyapunov {
    /// Finite exponents (boxed: the answer without them is a few words).
    Exponents(Box<LyapunovResult>),
    /// None, and why.
    None {
        /// The method that was asked for.
        method: Method,
        /// Why there is no exponent.
        no_exponent: NoExponent,
        /// τ at which this was established (tumble or flight time, or the
        /// end of the window).
        tau: f64,
    },
}

impl Lyapunov {
    /// The largest exponent per τ, if there is one.
    pub fn largest_per_tau(&self) -> Option<f64> {
        match self {
            Lyapunov::Exponents(r) => Some(r.largest_per_tau),
            Lyapunov::None { .. } => None,
        }
    }

    /// Compact JSON for `summary.json`: `method`, `largest_per_tau`,
    /// `per_cycle`, `stderr`, `spectrum` and the window, without the
    /// convergence history; or `method`, `no_exponent`, `tau`.
    pub fn summary(&self) -> Json {
        match self {
            Lyapunov::Exponents(r) => json!({
                "method": r.method.name(),
                "largest_per_tau": r.largest_per_tau,
                "per_cycle": r.per_cycle,
                "stderr": r.stderr,
                "stderr_per_cycle": r.stderr_per_cycle,
                "spectrum": r.spectrum,
                "spectrum_stderr": r.spectrum_stderr,
                "collapsed": r.collapsed,
                "neutral": format!("{} (exponent 0, not listed)", r.neutral),
                "units": "per unit tau, natural log; per_cycle = per_tau * 2pi/omega_h",
                "tau_start": r.tau_start,
                "tau_end": r.tau_end,
                "batches": r.batches,
                "check": r.check,
            }),
            Lyapunov::None {
                method,
                no_exponent,
                tau,
            } => json!({
                "method": method.name(),
                "no_exponent": no_exponent.name(),
                "tau": tau,
            }),
        }
    }
}

/// Why [`lyapunov`] could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LyapunovError {
    /// Exponents of the forced system need a forcing period.
    #[error("lyapunov exponents need harmonic excitation (excitation.kind = \"harmonic\" with omega_h > 0)")]
    NotHarmonic,
    /// An option is out of range.
    #[error("lyapunov option {field} {reason}")]
    Option {
        /// The option.
        field: &'static str,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The window holds fewer than two forcing periods.
    #[error("lyapunov: total_tau - transient_tau must span at least 2 forcing periods ({period} τ each)")]
    TooShort {
        /// The forcing period, τ.
        period: f64,
    },
    /// The model has no tangent equations (a stack): only the
    /// two-trajectory method gives its largest exponent.
    #[error(
        "analysis.lyapunov_method = \"{asked}\" needs tangent equations, which a {body} does not have (yet): \"benettin\" gives its largest exponent by two trajectories"
    )]
    NoTangent {
        /// The body: `[[stack]]`.
        body: &'static str,
        /// The method asked for.
        asked: &'static str,
    },
    /// The scenario has no model of the kind asked for.
    #[error("{0}")]
    Scene(#[from] crate::sim::ScenarioError),
    /// The initial state is not admissible.
    #[error(transparent)]
    Initial(#[from] SimError),
    /// The integration failed.
    #[error("lyapunov run failed: {0}")]
    Run(#[from] TangentError<ModelError>),
    /// A stack's integration failed.
    #[error("lyapunov run failed: {0}")]
    StackRun(#[from] TangentError<StackError>),
}

impl LyapunovError {
    /// Whether the input is at fault (a one-line error naming the key, exit
    /// code 2), not the run.
    pub fn is_input(&self) -> bool {
        match self {
            LyapunovError::NotHarmonic
            | LyapunovError::Option { .. }
            | LyapunovError::TooShort { .. }
            | LyapunovError::NoTangent { .. }
            | LyapunovError::Scene(_) => true,
            LyapunovError::StackRun(TangentError::System(e)) => e.is_input(),
            LyapunovError::Initial(_) | LyapunovError::Run(_) | LyapunovError::StackRun(_) => false,
        }
    }
}

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
pub fn stack_lyapunov(
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
