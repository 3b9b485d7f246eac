//! What a Lyapunov computation is asked (its method and options) and
//! what it answers (the exponents, a typed non-result, or an error).

use serde::Serialize;
use serde_json::{Value as Json, json};

use super::TangentError;
use crate::integrate::hybrid::Limits;
use crate::model::stack::StackError;
use crate::model::system::ModelError;
use crate::sim::{Scenario, SimError};

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

    pub(super) fn validate(&self) -> Result<(), LyapunovError> {
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
