//! One block configuration → its steady response: run it over a sampling
//! window, keep the Poincaré points after the transient, classify them.
//!
//! This is where the generic analyses meet the block. The bifurcation
//! diagram and the outcome map vary a scenario through typed
//! [`Param`](crate::sim::Param)s and call [`steady_response`] on each.
//!
//! Contract:
//! - The excitation must be harmonic: the section is defined by Ω_h.
//! - The window's `tau_end` replaces the scenario's `run.tau_end`; the run
//!   keeps no time history (only section points), which is what makes a
//!   sweep cheap in memory.
//! - A tumbled or flight response carries no points (the paper leaves those
//!   values blank) and no seed for continuation.
//! - The optional Lyapunov hook is called only for responses that are
//!   neither terminal nor at rest, with the configuration actually run.
//!   A non-finite exponent is an error, never written.

use super::classify::{ClassifyError, ClassifyOptions, Response, classify_run};
use super::field::{FieldNames, OwnNames, StudyField};
use super::section::{after_transient, points_in_window};
use crate::model::{Mode, Model};
use crate::sim::scenario::ExcitationKind;
use crate::sim::stack_run::StackError;

mod stack;
mod stack_settle;
use crate::sim::{InitialState, RunOptions, Scenario, ScenarioError, SectionRow, SimError, simulate};
pub(crate) use stack::stack_cell;
pub use stack::{check_stack_study, stack_steady};

/// The largest Lyapunov exponent of a configuration, per unit τ, if the
/// caller can compute it (the hook the Lyapunov module is wired into).
pub type LyapunovFn<'a> = dyn Fn(&Scenario) -> Option<f64> + Sync + 'a;

/// The sampling window of a steady-response study, in τ.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Window {
    /// Section points before this τ are discarded. Default 600: the paper's
    /// bifurcation diagrams use steps 150,000–200,000 of 0.004.
    pub transient: f64,
    /// End of each run. Default 800 (the paper's 200,000 steps of 0.004).
    pub tau_end: f64,
}

impl Default for Window {
    fn default() -> Self {
        Self {
            transient: 600.0,
            tau_end: 800.0,
        }
    }
}

impl Window {
    /// Checks that `0 <= transient < tau_end <= 1e9` (the config's limit on
    /// `run.tau_end`).
    pub fn validate(&self) -> Result<(), WindowError> {
        if !self.transient.is_finite() || self.transient < 0.0 {
            return Err(WindowError::Transient(self.transient));
        }
        if !self.tau_end.is_finite() || self.tau_end > 1e9 {
            return Err(WindowError::TauEnd(self.tau_end));
        }
        if self.tau_end <= self.transient {
            return Err(WindowError::Empty(*self));
        }
        Ok(())
    }

    /// Checks that the window holds enough section points to classify for a
    /// forcing period 2π/Ω_h = `forcing_period`.
    pub(crate) fn check_points(&self, forcing_period: f64, opts: &ClassifyOptions) -> Result<(), WindowError> {
        let have = points_in_window(forcing_period, self.transient, self.tau_end);
        let need = opts.min_points() as u64;
        if have < need {
            return Err(WindowError::TooFewPoints {
                window: *self,
                forcing_period,
                have,
                need,
            });
        }
        Ok(())
    }
}

/// A [`Window`] that cannot be sampled, naming its fields by meaning
/// ([`StudyField`]); [`WindowError::render`] words it for a surface.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.render(&OwnNames))]
pub enum WindowError {
    /// `transient` is not finite or is negative.
    Transient(f64),
    /// `tau_end` is not finite or is above 1e9 (the config's limit on
    /// `run.tau_end`).
    TauEnd(f64),
    /// `tau_end <= transient`: nothing to sample.
    Empty(Window),
    /// `tau_end` was not given and the scene's own `run.tau_end` (its
    /// batch run's end, e.g. 55.7 for a 20 s preset) is at or before the
    /// transient: the study needs its own end.
    SceneEnd(Window),
    /// Fewer section points in the window than the classifier needs.
    TooFewPoints {
        /// The window.
        window: Window,
        /// 2π/Ω_h, τ.
        forcing_period: f64,
        /// Section points in the window.
        have: u64,
        /// Section points the classifier needs.
        need: u64,
    },
}

impl WindowError {
    /// The one-line message with the fields named by `names`.
    pub fn render(&self, names: &impl FieldNames) -> String {
        // `{}` of an f64: the value as the user would type it (700, not 700.0).
        let transient = |v: f64| names.valued(StudyField::Transient, &v.to_string());
        let tau_end = |v: f64| names.valued(StudyField::TauEnd, &v.to_string());
        match *self {
            WindowError::Transient(v) => format!("{}: must be finite and >= 0", transient(v)),
            WindowError::TauEnd(v) => format!("{}: must be finite and <= 1e9", tau_end(v)),
            WindowError::Empty(w) => format!("{}: must be larger than {}", tau_end(w.tau_end), transient(w.transient)),
            WindowError::SceneEnd(w) => format!(
                "{}: not given, and the scene's run.tau_end = {:.2} ends before {}: give {} above the transient (the paper's window is 600 to 800)",
                names.name(StudyField::TauEnd),
                w.tau_end,
                transient(w.transient),
                names.name(StudyField::TauEnd)
            ),
            WindowError::TooFewPoints {
                window,
                forcing_period,
                have,
                need,
            } => format!(
                "{} / {}: the window holds {have} section points (period {forcing_period:.6}); at least {need} are needed to classify",
                transient(window.transient),
                tau_end(window.tau_end)
            ),
        }
    }
}

impl Window {
    /// The window of a study of `base` from `transient` and `tau_end`
    /// (default: `base`'s `run.tau_end`), checked; a default end at or
    /// before the transient is reported as the scene's
    /// ([`WindowError::SceneEnd`]).
    pub fn of_study(base: &Scenario, transient: f64, tau_end: Option<f64>) -> Result<Window, SteadyError> {
        let window = Window {
            transient,
            tau_end: tau_end.unwrap_or(base.run.tau_end),
        };
        match window.validate() {
            // The end the user did not give: say where it came from.
            Err(WindowError::Empty(w)) if tau_end.is_none() => return Err(WindowError::SceneEnd(w).into()),
            r => r?,
        }
        Ok(window)
    }
}

/// The steady response of one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Steady {
    /// Its class.
    pub response: Response,
    /// Largest |Θ| over the whole run, transient included (the excursion
    /// that decides tumbling).
    pub max_abs_theta: f64,
    /// Largest Lyapunov exponent per unit τ, when a hook supplied it.
    pub lyapunov: Option<f64>,
    /// Section points at τ ≥ transient (none for tumbled or flight).
    pub points: Vec<SectionRow>,
    /// The state at the last section point (excitation phase 0), to start
    /// the next value of a continuation sweep; `None` after tumbling or
    /// flight.
    pub seed: Option<InitialState>,
}

/// Why a steady response could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SteadyError {
    /// The scenario breaks a rule (a swept value out of range).
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The excitation is not harmonic, so there is no section.
    #[error(
        "excitation.kind: a steady-response study needs harmonic excitation (the section is taken at τ_k = 2πk/Ω_h)"
    )]
    NotHarmonic,
    /// The simulation failed.
    #[error("simulation failed: {0}")]
    Sim(#[from] SimError),
    /// A stack's run stopped at a slip it does not follow (its `static` is
    /// too low for the motion: bad input) or failed.
    #[error(transparent)]
    Stack(#[from] StackError),
    /// The points could not be classified.
    #[error(transparent)]
    Classify(#[from] ClassifyError),
    /// The window cannot be sampled.
    #[error(transparent)]
    Window(#[from] WindowError),
    /// A map was finished before all its cells were computed (a caller's
    /// mistake, reported rather than written as a partial map).
    #[error("the map was not finished (a cell failed or was never computed)")]
    Unfinished,
}

impl SteadyError {
    /// Whether the error is the input's (a value out of range, a window
    /// that cannot be sampled, a stack whose friction cannot hold the
    /// motion: the user's to change) rather than a failure of the run.
    pub fn is_input(&self) -> bool {
        match self {
            SteadyError::Scenario(_) | SteadyError::NotHarmonic | SteadyError::Window(_) => true,
            SteadyError::Stack(e) => e.is_input(),
            SteadyError::Sim(_) | SteadyError::Classify(_) | SteadyError::Unfinished => false,
        }
    }

    /// The one-line message with the study's inputs named by `names` (the
    /// other variants name config keys, the same on every surface).
    pub fn render(&self, names: &impl FieldNames) -> String {
        match self {
            SteadyError::Window(w) => w.render(names),
            SteadyError::Scenario(_)
            | SteadyError::NotHarmonic
            | SteadyError::Sim(_)
            | SteadyError::Stack(_)
            | SteadyError::Classify(_)
            | SteadyError::Unfinished => self.to_string(),
        }
    }
}

/// Checks, before running, that `scenario` has harmonic excitation and that
/// `window` holds enough of its section points to classify.
pub fn check_scenario(scenario: &Scenario, window: &Window, opts: &ClassifyOptions) -> Result<(), SteadyError> {
    if scenario.excitation.kind != ExcitationKind::Harmonic {
        return Err(SteadyError::NotHarmonic);
    }
    window.validate()?;
    Ok(window.check_points(std::f64::consts::TAU / scenario.excitation.omega_h, opts)?)
}

/// The state of a section point as an initial state at τ = 0. A point taken
/// with the pivot stuck (or at rest) gets no `x_dot`, so that the run
/// recomputes the exact no-slip velocity instead of starting with a slip of
/// rounding size; a sliding point keeps its `x_dot`.
pub(crate) fn seed_of(row: &SectionRow) -> Option<InitialState> {
    let x_dot = match row.mode {
        Mode::Rest | Mode::Rock { .. } => None,
        Mode::Slide { .. } | Mode::SlideRock { .. } => Some(row.x_dot),
        Mode::Tumbled | Mode::Flight => return None,
    };
    Some(InitialState {
        theta: row.theta,
        theta_dot: row.theta_dot,
        x_dot,
    })
}

/// `scenario` set up to be run over `window` and classified (harmonic
/// excitation only): the scenario with its end at the window's, its model,
/// the forcing period 2π/Ω_h (the section's spacing, τ) and run options
/// that keep the section points and no time history.
pub(crate) fn section_run(
    scenario: &Scenario,
    window: &Window,
) -> Result<(Scenario, Model, f64, RunOptions), SteadyError> {
    let mut cfg = scenario.clone();
    cfg.run.tau_end = window.tau_end;
    let model = cfg.model()?;
    let Some(period) = model.excitation.forcing_period() else {
        return Err(SteadyError::NotHarmonic);
    };
    let mut run = cfg.run_options();
    run.output_dt = None;
    run.section = true;
    Ok((cfg, model, period, run))
}

/// The largest Lyapunov exponent of `cfg` from the hook, asked only for a
/// response that moves on an attractor (periodic, quasiperiodic, chaotic:
/// rest and the terminal ends have nothing to measure). A non-finite
/// exponent is an error, never written.
pub(crate) fn exponent_of(
    lyapunov: Option<&LyapunovFn<'_>>,
    response: Response,
    cfg: &Scenario,
) -> Result<Option<f64>, SteadyError> {
    let (Some(hook), Response::Periodic { .. } | Response::Quasiperiodic | Response::Chaotic) = (lyapunov, response)
    else {
        return Ok(None);
    };
    match hook(cfg) {
        Some(l) if !l.is_finite() => Err(ClassifyError::NonFiniteExponent.into()),
        exponent => Ok(exponent),
    }
}

/// Runs `scenario` over `window` and classifies its steady response (a
/// stack's: [`stack_steady`]).
pub fn steady_response(
    scenario: &Scenario,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
) -> Result<Steady, SteadyError> {
    if scenario.stack.is_some() {
        check_stack_study(scenario, &[], false)?;
        return stack_steady(scenario, window, opts, lyapunov);
    }
    let (cfg, model, period, run) = section_run(scenario, window)?;
    let res = simulate(model, &cfg.initial, &run)?;
    let mut response = classify_run(&res, period, window.transient, None, opts)?;
    let exponent = exponent_of(lyapunov, response, &cfg)?;
    if exponent.is_some() {
        response = classify_run(&res, period, window.transient, exponent, opts)?;
    }
    let terminal = response.is_terminal();
    let points = if terminal {
        Vec::new()
    } else {
        after_transient(&res.section, window.transient).to_vec()
    };
    let seed = if terminal {
        None
    } else {
        res.section.last().and_then(seed_of)
    };
    Ok(Steady {
        response,
        max_abs_theta: res.max_abs_theta,
        lyapunov: exponent,
        points,
        seed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Param;

    /// The paper's Fig. 4 scenario (the preset's values, written out here
    /// because the analysis layer does not read config files).
    fn fig4() -> Scenario {
        let mut s = Scenario::default();
        s.impact.law = crate::sim::scenario::LawKind::Ratio;
        s.impact.r = Some(0.925);
        s.excitation.a_h = 3.0;
        s.excitation.a_v = 2.0;
        s.run.flight = crate::model::FlightPolicy::Ignore;
        s
    }

    #[test]
    fn window_errors_name_the_field_at_fault_by_meaning() {
        assert!(Window::default().validate().is_ok());
        let w = Window {
            transient: 800.0,
            tau_end: 700.0,
        };
        assert_eq!(w.validate(), Err(WindowError::Empty(w)));
        assert_eq!(
            w.validate().unwrap_err().to_string(),
            "tau_end = 700: must be larger than transient = 800"
        );
        let w = Window {
            transient: f64::NAN,
            tau_end: 700.0,
        };
        assert!(matches!(w.validate(), Err(WindowError::Transient(t)) if t.is_nan()));
        let w = Window {
            transient: 0.0,
            tau_end: 2e9,
        };
        assert_eq!(w.validate(), Err(WindowError::TauEnd(2e9)));
        let short = Window {
            transient: 0.0,
            tau_end: 10.0,
        };
        let period = std::f64::consts::TAU / 8.0;
        let opts = ClassifyOptions::default();
        // τ_k = k·2π/8 ≤ 10 for k = 0 … 12: 13 points, fewer than needed.
        let need = opts.min_points() as u64;
        assert!(need > 13, "the check below needs a window too short");
        assert!(matches!(
            short.check_points(period, &opts),
            Err(WindowError::TooFewPoints { have: 13, need: n, .. }) if n == need
        ));
        assert!(Window::default().check_points(period, &opts).is_ok());
    }

    /// A surface that shouts its names, to see that rendering uses them.
    struct Loud;

    impl FieldNames for Loud {
        fn name(&self, field: StudyField) -> std::borrow::Cow<'static, str> {
            field.name().to_uppercase().into()
        }
        fn valued(&self, field: StudyField, value: &str) -> String {
            format!("{}:={value}", self.name(field))
        }
    }

    #[test]
    fn a_window_error_is_worded_by_the_surface_that_renders_it() {
        let w = Window {
            transient: 800.0,
            tau_end: 700.0,
        };
        let e = SteadyError::from(w.validate().unwrap_err());
        assert_eq!(e.render(&Loud), "TAU_END:=700: must be larger than TRANSIENT:=800");
        assert_eq!(
            SteadyError::NotHarmonic.render(&Loud),
            SteadyError::NotHarmonic.to_string()
        );
    }

    #[test]
    fn a_block_that_is_never_lifted_is_at_rest() {
        let base = fig4();
        // A_h = 0.5 < tan ψ / ψ ≈ 1.02 and A_v = 0: the base cannot lift it.
        let cfg = Param::apply(&base, &[(Param::Ah, 0.5), (Param::Av, 0.0)]).unwrap();
        let w = Window {
            transient: 60.0,
            tau_end: 120.0,
        };
        let s = steady_response(&cfg, &w, &ClassifyOptions::default(), None).unwrap();
        assert_eq!(s.response, Response::Rest);
        assert_eq!(s.max_abs_theta, 0.0);
    }

    #[test]
    fn lyapunov_hook_is_called_and_a_nan_is_an_error() {
        let base = fig4();
        let cfg = Param::apply(&base, &[(Param::Av, 1.0)]).unwrap();
        let w = Window {
            transient: 100.0,
            tau_end: 160.0,
        };
        let hook = |c: &Scenario| Some(-0.1 - c.excitation.a_v);
        let s = steady_response(&cfg, &w, &ClassifyOptions::default(), Some(&hook)).unwrap();
        assert_eq!(s.lyapunov, Some(-1.1));
        assert_eq!(s.response, Response::Periodic { period: 1 });
        let nan = |_: &Scenario| Some(f64::NAN);
        assert_eq!(
            steady_response(&cfg, &w, &ClassifyOptions::default(), Some(&nan)),
            Err(SteadyError::Classify(ClassifyError::NonFiniteExponent))
        );
    }
}
