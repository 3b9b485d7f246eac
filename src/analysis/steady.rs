//! One block configuration → its steady response: run it over a sampling
//! window, keep the Poincaré points after the transient, classify them.
//!
//! This is where the generic analyses meet the block. It also holds
//! [`ParamBase`], a configuration with keys left free to vary, used by the
//! bifurcation diagram and the outcome map.
//!
//! Contract:
//! - The excitation must be harmonic: the section is defined by Ω_h.
//! - The window's `tau_end` replaces the config's `run.tau_end`; the run
//!   keeps no time history (only section points), which is what makes a
//!   sweep cheap in memory.
//! - A tumbled or flight response carries no points (the paper leaves those
//!   values blank) and no seed for continuation.
//! - The optional Lyapunov hook is called only for responses that are
//!   neither terminal nor at rest, with the configuration actually run.
//!   A non-finite exponent is an error, never written.

use std::path::Path;

use toml::{Table, Value};

use super::classify::{ClassifyError, ClassifyOptions, Response, classify_run};
use super::section::{after_transient, points_in_window};
use crate::io::config::{self, Config, ExcitationKind, KNOWN_KEYS, Source};
use crate::io::table::ConfigError;
use crate::model::Mode;
use crate::sim::{InitialState, SectionRow, SimError, simulate};

/// The largest Lyapunov exponent of a configuration, per unit τ, if the
/// caller can compute it (the hook the Lyapunov module is wired into).
pub type LyapunovFn<'a> = dyn Fn(&Config) -> Option<f64> + Sync + 'a;

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
    /// `run.tau_end`), naming the CLI flags in the message.
    pub fn validate(&self) -> Result<(), String> {
        if !self.transient.is_finite() || self.transient < 0.0 {
            return Err(format!("--transient {}: must be finite and >= 0", self.transient));
        }
        if !self.tau_end.is_finite() || self.tau_end > 1e9 {
            return Err(format!("--tau-end {}: must be finite and <= 1e9", self.tau_end));
        }
        if self.tau_end <= self.transient {
            return Err(format!(
                "--tau-end {}: must be larger than --transient {}",
                self.tau_end, self.transient
            ));
        }
        Ok(())
    }

    /// Checks that the window holds enough section points to classify for a
    /// forcing period 2π/Ω_h = `forcing_period`.
    pub fn check_points(&self, forcing_period: f64, opts: &ClassifyOptions) -> Result<(), String> {
        let have = points_in_window(forcing_period, self.transient, self.tau_end);
        let need = opts.min_points() as u64;
        if have < need {
            return Err(format!(
                "--transient {} / --tau-end {}: the window holds {have} section points (period {forcing_period:.6}); at least {need} are needed to classify",
                self.transient, self.tau_end
            ));
        }
        Ok(())
    }
}

/// A configuration (a preset or file plus `--set` overrides) whose keys can
/// be set to numbers one run at a time.
#[derive(Clone, Debug)]
pub struct ParamBase {
    table: Table,
    source: Source,
}

impl ParamBase {
    /// Loads a preset or a config file (or the `default` preset) and applies
    /// `--set` overrides, as `rocking --batch` does; the result is validated
    /// once here so that a bad base is reported before any sweep starts.
    pub fn load(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<Self, ConfigError> {
        let (mut table, source) = match (preset, file) {
            (Some(_), Some(_)) => return Err(ConfigError("give either --preset or --config, not both".into())),
            (_, Some(path)) => config::read_file(path)?,
            (name, None) => {
                let name = name.unwrap_or("default");
                let text = config::preset_text(name)?;
                (config::parse_toml(text, &format!("preset {name}"))?, Source::default())
            }
        };
        config::apply_sets(&mut table, sets)?;
        let base = Self { table, source };
        base.resolve(&[])?;
        Ok(base)
    }

    /// A base from an already parsed table.
    pub fn from_table(table: Table, source: Source) -> Self {
        Self { table, source }
    }

    /// The configuration with each `(key, value)` set, resolved and validated.
    /// Keys are dotted `section.key` names from
    /// [`KNOWN_KEYS`](crate::io::config::KNOWN_KEYS); a key that is not
    /// numeric fails validation with the key named.
    pub fn resolve(&self, assignments: &[(&str, f64)]) -> Result<Config, ConfigError> {
        let mut table = self.table.clone();
        for &(key, value) in assignments {
            let (section, name) = check_key(key)?;
            let entry = table
                .entry(section.to_string())
                .or_insert_with(|| Value::Table(Table::new()));
            let Value::Table(sec) = entry else {
                return Err(ConfigError::key(section, "is not a table"));
            };
            sec.insert(name.to_string(), Value::Float(value));
        }
        Config::from_table(&table, &self.source)
    }
}

/// Splits a dotted key and checks it is a known config key.
pub fn check_key(key: &str) -> Result<(&str, &str), ConfigError> {
    let Some((section, name)) = key.split_once('.') else {
        return Err(ConfigError(format!(
            "{key}: a parameter must be SECTION.KEY, e.g. excitation.a_v"
        )));
    };
    let Some((_, keys)) = KNOWN_KEYS.iter().find(|(s, _)| *s == section) else {
        let sections: Vec<&str> = KNOWN_KEYS.iter().map(|(s, _)| *s).collect();
        return Err(ConfigError::key(
            key,
            format!("unknown section (known: {})", sections.join(", ")),
        ));
    };
    if !keys.contains(&name) {
        return Err(ConfigError::key(
            key,
            format!("unknown key (known in [{section}]: {})", keys.join(", ")),
        ));
    }
    Ok((section, name))
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
    /// The configuration is invalid (or a record file unreadable).
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The excitation is not harmonic, so there is no section.
    #[error(
        "excitation.kind: a steady-response study needs harmonic excitation (the section is taken at τ_k = 2πk/Ω_h)"
    )]
    NotHarmonic,
    /// The simulation failed.
    #[error("simulation failed: {0}")]
    Sim(#[from] SimError),
    /// The points could not be classified.
    #[error(transparent)]
    Classify(#[from] ClassifyError),
    /// The window holds too few section points.
    #[error("{0}")]
    Window(String),
}

/// Checks, before running, that `cfg` has harmonic excitation and that
/// `window` holds enough of its section points to classify.
pub fn check_config(cfg: &Config, window: &Window, opts: &ClassifyOptions) -> Result<(), SteadyError> {
    if cfg.kind != ExcitationKind::Harmonic {
        return Err(SteadyError::NotHarmonic);
    }
    window.validate().map_err(SteadyError::Window)?;
    window
        .check_points(std::f64::consts::TAU / cfg.omega_h, opts)
        .map_err(SteadyError::Window)
}

/// The configuration `cfg` started from `seed` instead of its own initial
/// state (continuation).
pub fn seeded(cfg: &Config, seed: &InitialState) -> Config {
    let mut c = cfg.clone();
    c.theta0 = seed.theta;
    c.theta_dot0 = seed.theta_dot;
    c.x_dot0 = seed.x_dot;
    c
}

/// The state of a section point as an initial state at τ = 0. A point taken
/// with the pivot stuck (or at rest) gets no `x_dot`, so that the run
/// recomputes the exact no-slip velocity instead of starting with a slip of
/// rounding size; a sliding point keeps its `x_dot`.
pub fn seed_of(row: &SectionRow) -> Option<InitialState> {
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

/// Runs `cfg` over `window` and classifies its steady response.
pub fn steady_response(
    cfg: &Config,
    window: &Window,
    opts: &ClassifyOptions,
    lyapunov: Option<&LyapunovFn<'_>>,
) -> Result<Steady, SteadyError> {
    let mut cfg = cfg.clone();
    cfg.tau_end = window.tau_end;
    let model = cfg.model()?;
    let Some(period) = model.excitation.forcing_period() else {
        return Err(SteadyError::NotHarmonic);
    };
    let mut run = cfg.run_options();
    run.output_dt = None;
    run.section = true;
    let res = simulate(model, &cfg.initial(), &run)?;
    let mut response = classify_run(&res, period, window.transient, None, opts)?;
    let mut exponent = None;
    if let (Some(hook), Response::Periodic { .. } | Response::Quasiperiodic | Response::Chaotic) = (lyapunov, response)
    {
        exponent = hook(&cfg);
        if let Some(l) = exponent {
            if !l.is_finite() {
                return Err(ClassifyError::NonFiniteExponent.into());
            }
            response = classify_run(&res, period, window.transient, exponent, opts)?;
        }
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

    #[test]
    fn resolve_sets_numeric_keys_and_names_bad_ones() {
        let base = ParamBase::load(Some("fig4"), None, &[]).unwrap();
        let cfg = base.resolve(&[("excitation.a_v", 1.25)]).unwrap();
        assert_eq!(cfg.a_v, 1.25);
        let e = base.resolve(&[("excitation.nope", 1.0)]).unwrap_err();
        assert!(e.0.starts_with("excitation.nope: unknown key"), "{e}");
        let e = base.resolve(&[("nope.a_v", 1.0)]).unwrap_err();
        assert!(e.0.starts_with("nope.a_v: unknown section"), "{e}");
        let e = base.resolve(&[("impact.law", 1.0)]).unwrap_err();
        assert!(e.0.starts_with("impact.law"), "{e}");
        let e = base.resolve(&[("excitation.omega_h", -1.0)]).unwrap_err();
        assert!(e.0.starts_with("excitation.omega_h"), "{e}");
        assert!(check_key("a_v").is_err());
    }

    #[test]
    fn window_validation_names_the_flags() {
        assert!(Window::default().validate().is_ok());
        let w = Window {
            transient: 800.0,
            tau_end: 700.0,
        };
        assert!(w.validate().unwrap_err().starts_with("--tau-end"));
        let w = Window {
            transient: f64::NAN,
            tau_end: 700.0,
        };
        assert!(w.validate().unwrap_err().starts_with("--transient"));
        let short = Window {
            transient: 0.0,
            tau_end: 10.0,
        };
        let period = std::f64::consts::TAU / 8.0;
        assert!(short.check_points(period, &ClassifyOptions::default()).is_err());
        assert!(
            Window::default()
                .check_points(period, &ClassifyOptions::default())
                .is_ok()
        );
    }

    #[test]
    fn a_block_that_is_never_lifted_is_at_rest() {
        let base = ParamBase::load(Some("fig4"), None, &[]).unwrap();
        // A_h = 0.5 < tan ψ / ψ ≈ 1.02 and A_v = 0: the base cannot lift it.
        let cfg = base
            .resolve(&[("excitation.a_h", 0.5), ("excitation.a_v", 0.0)])
            .unwrap();
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
        let base = ParamBase::load(Some("fig4"), None, &[]).unwrap();
        let cfg = base.resolve(&[("excitation.a_v", 1.0)]).unwrap();
        let w = Window {
            transient: 100.0,
            tau_end: 160.0,
        };
        let hook = |c: &Config| Some(-0.1 - c.a_v);
        let s = steady_response(&cfg, &w, &ClassifyOptions::default(), Some(&hook)).unwrap();
        assert_eq!(s.lyapunov, Some(-1.1));
        assert_eq!(s.response, Response::Periodic { period: 1 });
        let nan = |_: &Config| Some(f64::NAN);
        assert_eq!(
            steady_response(&cfg, &w, &ClassifyOptions::default(), Some(&nan)),
            Err(SteadyError::Classify(ClassifyError::NonFiniteExponent))
        );
    }
}
