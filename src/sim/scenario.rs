//! The scenario: everything one run needs — the block, its contact and
//! impact laws, the excitation, the initial state, how to integrate and what
//! to analyse — typed and validated once.
//!
//! A scenario is made by the config layer (which reads TOML, JSON and
//! `--set` into one) or in code; the batch run, the simulation thread and
//! every analysis take one. Analyses that vary a parameter set it through a
//! typed [`Param`](super::param::Param) and call [`Scenario::validate`]
//! again, so a sweep point is checked by exactly the rules a config file is.
//!
//! Values a user may leave out and whose default depends on another value
//! (Ω_v = Ω_h, μ_k = μ_s, Housner's ratio from the block's slenderness, the
//! method from the tolerance, …) are kept as `None`, so that varying the
//! value they follow moves them too; the accessors resolve them.
//!
//! Units are the normalised ones of MODEL-DECISIONS (τ = p t, Θ = θ/ψ,
//! amplitudes in ψ g, frequencies in p) unless a field says otherwise.

use super::method::Method;
use super::run::{InitialState, RunOptions};
use crate::integrate::Tolerances;
use crate::integrate::hybrid::Limits;
use crate::model::stack::StackBlock;
use crate::model::{FlightPolicy, Frame, Geometry, ImpactLaw, Model};

mod block;
mod excitation;
mod floor;
mod kinds;
mod record;

pub use block::{Block, Impact};
pub use excitation::ExcitationSpec;
pub(crate) use floor::{
    FLOOR_DAMPING, FLOOR_PARTICIPATION, MAX_FLOOR_PARTICIPATION, MAX_FLOOR_PERIOD_S, MIN_FLOOR_PERIOD_S,
};
pub use floor::{FloorModeSpec, FloorSpec};
pub use kinds::{ExcitationKind, LawKind, LyapunovChoice, ShapeKind, SpectrumRange};
pub(crate) use record::record_file_name;
pub use record::{Record, SHIPPED_PREFIX};

/// Largest kinetic friction coefficient accepted (exclusive): the
/// slide-rock denominator (1−γ) + γ(sin²φ − sσμ_k sin φ cos φ) stays
/// positive for every block and angle exactly when μ_k < 4/3; beyond it
/// slide-rock has no unique solution (the Painlevé paradox), and the
/// slipping impact's denominator fails at the same bound.
pub(crate) const MU_K_LIMIT: f64 = 4.0 / 3.0;

/// Largest |amplitude| accepted, units of ψ g: a guard against typos far
/// beyond any physical shaking (the block is in flight long before).
pub(crate) const AMPLITUDE_LIMIT: f64 = 1e6;

/// Smallest block size accepted, m (`block.width`, `block.height`).
pub(crate) const MIN_SIZE_M: f64 = 1e-4;

/// Largest block size accepted, m.
pub(crate) const MAX_SIZE_M: f64 = 1e4;

/// Smallest slenderness ψ accepted, rad: amplitudes are in units of ψg, so
/// a block thinner than this makes every amplitude vanish.
pub(crate) const MIN_PSI: f64 = 1e-6;

/// Fewest history samples a power spectrum is taken of.
pub(crate) const MIN_SPECTRUM_SAMPLES: usize = 8;

/// Most rows of the time history one run may keep (`run.output_dt`).
pub(crate) const MAX_HISTORY_ROWS: f64 = 5e7;

/// Default free-vibration tail after a record, s (`run.tail_s`): a record
/// run goes on this long after the last sample unless the block comes to
/// rest or overturns first. 30 s is several free-rocking periods of any
/// block up to tens of metres (the period of free rocking grows only as
/// √R), so a block still moving after it is reported as moving, not missed.
pub(crate) const RECORD_TAIL_S: f64 = 30.0;

/// PGA above which a record's unit is probably wrong, g: the largest peak
/// ground accelerations ever recorded are about 3–4 g.
pub(crate) const IMPLAUSIBLE_PGA_G: f64 = 5.0;

/// PGA below which a record's unit is probably wrong, g: 0.01 g is about
/// the threshold of shaking people feel, so a record an engineer runs is
/// stronger; a record in cm/s² read as m/s² or as g comes out 100 to 1000
/// times too weak and lands below it.
pub(crate) const IMPLAUSIBLY_SMALL_PGA_G: f64 = 0.01;

/// How to integrate and when to stop.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSpec {
    /// End of the run, τ, in (0, 1e9]. Default 800 (the paper's 200,000
    /// steps of 0.004).
    pub tau_end: f64,
    /// Method; `None`: by tolerance, [`Method::default_for`].
    pub method: Option<Method>,
    /// Relative tolerance, in (0, 1). Default 1e-10.
    pub rtol: f64,
    /// Absolute tolerance, in (0, 1). Default 1e-12.
    pub atol: f64,
    /// Fixed step of `ralston`, in (0, 1). Default 0.004 (the paper's).
    pub step: f64,
    /// Spacing of the time history, τ; 0 keeps none. Default 0.02.
    pub output_dt: f64,
    /// |Θ| at which the block has tumbled, in (0, π/(2ψ)]. Default 1.
    pub tumble_theta: f64,
    /// What happens when the normal force vanishes. Default stop.
    pub flight: FlightPolicy,
    /// Impact accumulation threshold on |Θ'|, in [0, 1). Default 1e-5.
    pub zeno_eps: f64,
    /// Most steps. Default 10⁹.
    pub max_steps: u64,
    /// Most events. Default 10⁸.
    pub max_events: u64,
    /// For a record: `Some(tail)` lets the record decide the length (the
    /// whole record, then at most `tail` seconds more until the block is at
    /// rest or overturned; `tau_end` is then unused), `None` runs to
    /// `tau_end` exactly. Default [`RECORD_TAIL_S`]; a config that gives
    /// `run.tau_end` or `run.t_end` sets `None`. Unused by other kinds.
    pub record_tail_s: Option<f64>,
}

impl RunSpec {
    /// The method, resolved.
    pub fn method(&self) -> Method {
        self.method.unwrap_or_else(|| Method::default_for(self.rtol))
    }
}

/// τ at which the paper's spectrum window ends.
pub(crate) const PAPER_SPECTRUM_END: f64 = 28.384;

/// What a batch run computes besides the run itself.
#[derive(Clone, Debug, PartialEq)]
pub struct Analyses {
    /// Lyapunov exponents too. Default false: they need a second,
    /// tangent-augmented integration of the whole run. Harmonic excitation
    /// only (the exponents of the periodically forced system).
    pub lyapunov: bool,
    /// Which Lyapunov method.
    pub lyapunov_method: LyapunovChoice,
    /// The power spectrum of Θ(τ) too. Default false. Needs a history.
    pub spectrum: bool,
    /// Over which part of the history.
    pub spectrum_window: SpectrumRange,
}

/// Everything one run needs. See the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// The block and its friction.
    pub block: Block,
    /// The impact law.
    pub impact: Impact,
    /// The base motion.
    pub excitation: ExcitationSpec,
    /// The initial state.
    pub initial: InitialState,
    /// How to integrate.
    pub run: RunSpec,
    /// What a batch run adds.
    pub analyses: Analyses,
    /// The building the block stands in; `None`: on the ground.
    pub floor: Option<FloorSpec>,
    /// A rocking frame (config `[frame]`) whose columns are `block`'s
    /// width and height; `None`: the single block.
    pub frame: Option<Frame>,
    /// A stack of blocks (config `[[stack]]` with two or more tables),
    /// bottom to top; `block` is then its bottom block, whose p and ψ are
    /// the run's τ and amplitude units. `None`: the single block (a
    /// one-table stack is read as that block).
    pub stack: Option<Vec<StackBlock>>,
}

impl Default for Scenario {
    /// The paper's block (B = 1 m, H = 4 m) at rest under no shaking, with
    /// every default of the config file.
    fn default() -> Self {
        let limits = Limits::default();
        Self {
            block: Block {
                width: 1.0,
                height: 4.0,
                mu_s: f64::INFINITY,
                mu_k: None,
            },
            impact: Impact {
                law: LawKind::Housner,
                r: None,
                e: 0.0,
                mu_s: None,
                mu_k: None,
            },
            excitation: ExcitationSpec {
                kind: ExcitationKind::Harmonic,
                a_h: 0.0,
                a_v: 0.0,
                omega_h: 8.0,
                omega_v: None,
                phase_h: 0.0,
                phase_v: 0.0,
                shape: ShapeKind::OneSine,
                cycles: 1,
                record_h: None,
                record_v: None,
                scale_h: 1.0,
                scale_v: 1.0,
            },
            initial: InitialState {
                theta: 0.0,
                theta_dot: 0.0,
                x_dot: None,
            },
            run: RunSpec {
                tau_end: 800.0,
                method: None,
                rtol: 1e-10,
                atol: 1e-12,
                step: 0.004,
                output_dt: 0.02,
                tumble_theta: 1.0,
                flight: FlightPolicy::Stop,
                zeno_eps: 1e-5,
                max_steps: limits.max_steps,
                max_events: limits.max_events,
                record_tail_s: Some(RECORD_TAIL_S),
            },
            analyses: Analyses {
                lyapunov: false,
                lyapunov_method: LyapunovChoice::Tangent,
                spectrum: false,
                spectrum_window: SpectrumRange::All,
            },
            floor: None,
            frame: None,
            stack: None,
        }
    }
}

/// A scenario that breaks a rule: one line naming the config key.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {message}")]
pub struct ScenarioError {
    /// The key, as the user writes it (e.g. `excitation.a_v`), possibly
    /// with a note (`friction.kinetic (absent, so equal to …)`).
    pub key: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

/// A PGA for a message: three decimals as before where they show it
/// (0.036 g), three significant digits below (0.000357 g), so a tiny peak
/// does not print as 0.000.
pub(crate) fn readable_g(g: f64) -> String {
    if g == 0.0 || g.abs() >= 0.01 {
        format!("{g:.3}")
    } else {
        format!("{g:.2e}")
    }
}

impl ScenarioError {
    /// An error about `key`.
    pub fn new(key: impl Into<String>, message: impl std::fmt::Display) -> Self {
        Self {
            key: key.into(),
            message: message.to_string(),
        }
    }
}

impl Scenario {
    /// The block's geometry.
    pub fn geometry(&self) -> Geometry {
        self.block.geometry()
    }

    /// The ratio r, resolved.
    pub fn impact_r(&self) -> f64 {
        // Housner's ratio is negative for squat blocks (ψ > 54.7°, where a
        // single-corner impact reverses the rotation and the block lands
        // flat, docs/model.md §7.5): the default ratio is then 0.
        // A frame's own coefficient (docs/model.md §16.3) likewise.
        let own = match &self.frame {
            Some(frame) => frame.restitution(&self.geometry()),
            None => self.geometry().housner_r(),
        };
        self.impact.r.unwrap_or_else(|| own.max(0.0))
    }

    /// μ̄_s during impact, resolved.
    pub(crate) fn impact_mu_s(&self) -> f64 {
        self.impact.mu_s.unwrap_or(self.block.mu_s)
    }

    /// μ̄_k during impact, resolved.
    pub(crate) fn impact_mu_k(&self) -> f64 {
        self.impact.mu_k.unwrap_or(self.block.kinetic().min(self.impact_mu_s()))
    }

    /// The impact law with its coefficients.
    pub fn impact_law(&self) -> ImpactLaw {
        match self.impact.law {
            LawKind::Ratio => ImpactLaw::Ratio { r: self.impact_r() },
            LawKind::Impulse => ImpactLaw::Impulse {
                e: self.impact.e,
                mu_s: self.impact_mu_s(),
                mu_k: self.impact_mu_k(),
            },
            LawKind::Housner => ImpactLaw::Housner,
            LawKind::CornerMomentum => ImpactLaw::CornerMomentum,
        }
    }

    /// The model. A stack has none of the block's kind: it is run by
    /// [`stack_run::simulate_stack`](super::stack_run::simulate_stack)
    /// alone, so every study built on the block's model refuses it.
    pub fn model(&self) -> Result<Model, ScenarioError> {
        if self.stack.is_some() {
            return Err(ScenarioError::new(
                "stack",
                "a [[stack]] has its own equations (docs/model.md §18) and runs alone, live, in sweeps, maps, spectra and fragility studies; the studies built on the single block's (Lyapunov exponents) take a [block] or a [frame]",
            ));
        }
        Ok(Model {
            geo: self.geometry(),
            mu_s: self.block.mu_s,
            mu_k: self.block.kinetic(),
            law: self.impact_law(),
            excitation: self.excitation()?,
            tumble_theta: self.run.tumble_theta,
            flight: self.run.flight,
            zeno_eps: self.run.zeno_eps,
            frame: self.frame,
        })
    }

    /// The stack's shape, for a scenario with a `[[stack]]`.
    pub fn stack_geometry(&self) -> Option<crate::model::stack::StackGeometry> {
        self.stack
            .as_ref()
            .and_then(|b| crate::model::stack::StackGeometry::new(b).ok())
    }

    /// The run options. The section is taken for harmonic excitation.
    pub fn run_options(&self) -> RunOptions {
        RunOptions {
            tau_end: self.tau_end(),
            rest_after: match self.run.record_tail_s {
                Some(_) => self.rest_after_tau(),
                None => None,
            },
            method: self.run.method(),
            tol: Tolerances {
                rtol: self.run.rtol,
                atol: self.run.atol,
                h_max: f64::INFINITY,
                h_fixed: self.run.step,
            },
            output_dt: (self.run.output_dt > 0.0).then_some(self.run.output_dt),
            section: self.excitation.kind == ExcitationKind::Harmonic,
            limits: Limits {
                max_steps: self.run.max_steps,
                max_events: self.run.max_events,
                ..Limits::default()
            },
        }
    }

    /// This scenario started from `seed` instead of its own initial state
    /// (continuation).
    pub fn seeded(&self, seed: &InitialState) -> Self {
        let mut s = self.clone();
        s.initial = *seed;
        s
    }
}
