//! The run configuration: TOML with dotted keys, `--set` overrides, presets,
//! validation with one-line errors, and the resolved form written to
//! `summary.json`.
//!
//! Every key, its unit, default and allowed range is listed in
//! [`KNOWN_KEYS`] and documented on the fields of [`Config`]. A resolved
//! config (every default filled in) round-trips: `rocking --batch --config
//! out/summary.json` repeats the run.

use std::path::{Path, PathBuf};

use serde_json::{Value as Json, json};
use toml::Table;

use super::record;
use super::table::{ConfigError, TableReader, line_of, set_dotted};
use crate::integrate::Tolerances;
use crate::integrate::hybrid::Limits;
use crate::model::excitation::{Excitation, Harmonic, Pulse, PulseShape, RecordExcitation, Series, pulse};
use crate::model::{FlightPolicy, Geometry, ImpactLaw, Model};
use crate::sim::{InitialState, Method, RunOptions};

/// Every section and key the config accepts.
pub const KNOWN_KEYS: &[(&str, &[&str])] = &[
    ("block", &["width", "height"]),
    ("friction", &["static", "kinetic"]),
    ("impact", &["law", "r", "e", "static", "kinetic"]),
    (
        "excitation",
        &[
            "kind", "a_h", "a_v", "omega_h", "omega_v", "phase_h", "phase_v", "shape", "cycles", "file_h", "file_v",
            "scale_h", "scale_v",
        ],
    ),
    ("initial", &["theta", "theta_dot", "x_dot"]),
    (
        "run",
        &[
            "tau_end",
            "method",
            "rtol",
            "atol",
            "step",
            "output_dt",
            "tumble_theta",
            "flight",
            "zeno_eps",
            "max_steps",
            "max_events",
        ],
    ),
    (
        "analysis",
        &["lyapunov", "lyapunov_method", "spectrum", "spectrum_window"],
    ),
];

/// Largest kinetic friction coefficient accepted (exclusive): the
/// slide-rock denominator (1−γ) + γ(sin²φ − sσμ_k sin φ cos φ) stays
/// positive for every block and angle exactly when μ_k < 4/3; beyond it
/// slide-rock has no unique solution (the Painlevé paradox), and the
/// slipping impact's denominator fails at the same bound.
pub const MU_K_LIMIT: f64 = 4.0 / 3.0;

/// Kind of excitation (`excitation.kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExcitationKind {
    /// No base motion.
    None,
    /// 2-D harmonic.
    Harmonic,
    /// Analytic pulse.
    Pulse,
    /// Recorded ground motion.
    Record,
}

/// The fully resolved configuration of one run (all defaults filled in).
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// `block.width`, m, > 0. Default 1 (the paper's B).
    pub width: f64,
    /// `block.height`, m, > 0. Default 4 (the paper's H).
    pub height: f64,
    /// `friction.static` μ_s >= 0 or `inf`. Default `inf`: rocking without
    /// sliding, the paper's sec. 4.1.
    pub mu_s: f64,
    /// `friction.kinetic` μ_k, 0 <= μ_k <= μ_s. Default μ_s.
    pub mu_k: f64,
    /// `impact.law`: `housner`, `ratio` or `impulse`. Default `housner`.
    pub law: String,
    /// `impact.r` for `ratio`, in [0, 1]. Default: Housner's 1 − 1.5 sin²ψ
    /// (0 for blocks squat enough that it is negative).
    pub r: f64,
    /// `impact.e` for `impulse`, vertical restitution in [0, 1]. Default 0.
    pub e: f64,
    /// `impact.static` μ̄_s for `impulse`. Default μ_s (as in the paper).
    pub impact_mu_s: f64,
    /// `impact.kinetic` μ̄_k for `impulse`. Default μ_k.
    pub impact_mu_k: f64,
    /// `excitation.kind`: `harmonic`, `pulse`, `record` or `none`. Default `harmonic`.
    pub kind: ExcitationKind,
    /// `excitation.a_h`: A_h in units of ψ g (harmonic and pulse). Default 0.
    pub a_h: f64,
    /// `excitation.a_v`: A_v in units of ψ g. Default 0.
    pub a_v: f64,
    /// `excitation.omega_h`: Ω_h in units of p, > 0. Default 8 (the paper's).
    pub omega_h: f64,
    /// `excitation.omega_v`: Ω_v in units of p, > 0. Default Ω_h.
    pub omega_v: f64,
    /// `excitation.phase_h`: Φ_h, rad. Default 0.
    pub phase_h: f64,
    /// `excitation.phase_v`: Φ_v, rad. Default 0.
    pub phase_v: f64,
    /// `excitation.shape` for pulses: `one-sine` (Makris type A),
    /// `one-cosine` (type B) or `type-c`. Default `one-sine`.
    pub shape: String,
    /// `excitation.cycles`: n of a type-C_n pulse, 1..=20. Default 1.
    pub cycles: u64,
    /// `excitation.file_h`: horizontal record (PEER `.AT2` or two columns
    /// `time_s accel_g`), relative to the config file.
    pub file_h: Option<PathBuf>,
    /// `excitation.file_v`: optional vertical record.
    pub file_v: Option<PathBuf>,
    /// `excitation.scale_h`: factor on the horizontal record. Default 1.
    pub scale_h: f64,
    /// `excitation.scale_v`: factor on the vertical record. Default 1.
    pub scale_v: f64,
    /// `initial.theta`: Θ at τ = 0, |Θ| < tumble angle. Default 0.
    pub theta0: f64,
    /// `initial.theta_dot`: Θ' at τ = 0. Default 0.
    pub theta_dot0: f64,
    /// `initial.x_dot`: X' at τ = 0. Default: no slip of the contact corner.
    pub x_dot0: Option<f64>,
    /// `run.tau_end`: τ at which the run ends, > 0. Default 800 (the
    /// paper's 200,000 steps of 0.004).
    pub tau_end: f64,
    /// `run.method`: `dop853`, `dopri5`, `ralston` or `taylor`. Default by
    /// tolerance, [`Method::default_for`]: `taylor` at the default rtol.
    pub method: Method,
    /// `run.rtol`, in (0, 1). Default 1e-10.
    pub rtol: f64,
    /// `run.atol`, in (0, 1). Default 1e-12.
    pub atol: f64,
    /// `run.step`: fixed step of `ralston`, in (0, 1). Default 0.004 (the paper's).
    pub step: f64,
    /// `run.output_dt`: spacing of `history.csv`; 0 writes none. Default 0.02.
    pub output_dt: f64,
    /// `run.tumble_theta`: |Θ| at which the block has tumbled, in (0, π/(2ψ)]. Default 1.
    pub tumble_theta: f64,
    /// `run.flight`: `stop` or `ignore`. Default `stop`.
    pub flight: FlightPolicy,
    /// `run.zeno_eps`: impact accumulation threshold on |Θ'|, in [0, 1). Default 1e-5.
    pub zeno_eps: f64,
    /// `run.max_steps`. Default 10⁹.
    pub max_steps: u64,
    /// `run.max_events`. Default 10⁸.
    pub max_events: u64,
    /// `analysis.lyapunov`: `--batch` also computes Lyapunov exponents
    /// (`summary.json` key `lyapunov`). Default false: they need a second,
    /// tangent-augmented integration of the whole run. Harmonic excitation
    /// only (the exponents of the periodically forced system).
    pub lyapunov: bool,
    /// `analysis.lyapunov_method`: `tangent` (the whole spectrum),
    /// `benettin` (two trajectories) or `both` (both on one trajectory,
    /// with their paired difference). Default `tangent`.
    pub lyapunov_method: String,
    /// `analysis.spectrum`: `--batch` also writes `spectrum.csv` (power
    /// spectrum of Θ(τ)) and lists the dominant peaks in `summary.json`.
    /// Default false. Needs `run.output_dt > 0` (it is computed from the
    /// history).
    pub spectrum: bool,
    /// `analysis.spectrum_window`: `all` (the whole history) or `paper`
    /// (the paper's samples 3000–7095 at Δτ = 0.004, i.e. τ 12–28.384).
    /// Default `all`.
    pub spectrum_window: String,
}

/// `section.key` as a boolean, or `None` if absent (a non-table section is
/// reported by [`TableReader::reject_unknown`]).
fn boolean(table: &Table, section: &str, key: &str) -> Result<Option<bool>, ConfigError> {
    match table.get(section).and_then(|s| s.as_table()).and_then(|s| s.get(key)) {
        None => Ok(None),
        Some(toml::Value::Boolean(b)) => Ok(Some(*b)),
        Some(other) => Err(ConfigError::key(
            &format!("{section}.{key}"),
            format!("expected true or false, found {other}"),
        )),
    }
}

/// Where a config came from, for resolving relative record paths.
#[derive(Clone, Debug, Default)]
pub struct Source {
    /// Directory that relative paths are relative to.
    pub base_dir: PathBuf,
}

/// Reads a preset shipped in `assets/presets/NAME.toml`.
pub fn preset_text(name: &str) -> Result<&'static str, ConfigError> {
    super::presets::get(name).ok_or_else(|| {
        ConfigError(format!(
            "--preset {name}: unknown preset (known: {})",
            super::presets::names().join(", ")
        ))
    })
}

/// Parses TOML text, naming `file` and the line in errors.
pub fn parse_toml(text: &str, file: &str) -> Result<Table, ConfigError> {
    text.parse::<Table>().map_err(|e| {
        let line = e.span().map_or(1, |s| line_of(text, s.start));
        let msg = e.message().lines().next().unwrap_or("invalid TOML").to_string();
        ConfigError(format!("{file}:{line}: {msg}"))
    })
}

/// Reads a config file: TOML, or a `summary.json` / JSON config (whose
/// `config` object is used if present).
pub fn read_file(path: &Path) -> Result<(Table, Source), ConfigError> {
    let name = path.display().to_string();
    if path.is_dir() {
        return Err(ConfigError(format!("{name}: is a directory, expected a config file")));
    }
    let text = std::fs::read_to_string(path).map_err(|e| ConfigError(format!("{name}: {e}")))?;
    if text.trim().is_empty() {
        return Err(ConfigError(format!("{name}: empty file")));
    }
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let is_json = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let table = if is_json {
        let v: Json = serde_json::from_str(&text).map_err(|e| ConfigError(format!("{name}:{}: {e}", e.line())))?;
        let v = v.get("config").cloned().unwrap_or(v);
        json_to_table(&v).map_err(|m| ConfigError(format!("{name}: {m}")))?
    } else {
        parse_toml(&text, &name)?
    };
    Ok((table, Source { base_dir }))
}

fn json_to_table(v: &Json) -> Result<Table, String> {
    let Json::Object(map) = v else {
        return Err("expected a JSON object".into());
    };
    let mut t = Table::new();
    for (k, v) in map {
        let tv = match v {
            Json::Object(_) => toml::Value::Table(json_to_table(v)?),
            Json::String(s) => toml::Value::String(s.clone()),
            Json::Bool(b) => toml::Value::Boolean(*b),
            Json::Number(n) => match n.as_i64() {
                Some(i) => toml::Value::Integer(i),
                None => toml::Value::Float(n.as_f64().unwrap_or(f64::NAN)),
            },
            // `null` means "absent / default".
            Json::Null => continue,
            Json::Array(_) => return Err(format!("{k}: arrays are not config values")),
        };
        t.insert(k.clone(), tv);
    }
    Ok(t)
}

/// Applies `--set KEY=VALUE` assignments.
pub fn apply_sets(table: &mut Table, sets: &[String]) -> Result<(), ConfigError> {
    for s in sets {
        set_dotted(table, s)?;
    }
    Ok(())
}

fn check(key: &str, ok: bool, allowed: &str, value: f64) -> Result<(), ConfigError> {
    if ok {
        Ok(())
    } else {
        Err(ConfigError::key(
            key,
            format!("{value} is out of range: must be {allowed}"),
        ))
    }
}

impl Config {
    /// Resolves and validates `table`. Record paths are made relative to
    /// `source.base_dir`.
    pub fn from_table(table: &Table, source: &Source) -> Result<Self, ConfigError> {
        let mut r = TableReader::new(table);
        let width = r.number("block", "width", false)?.unwrap_or(1.0);
        check("block.width", width > 0.0, "> 0 (metres)", width)?;
        let height = r.number("block", "height", false)?.unwrap_or(4.0);
        check("block.height", height > 0.0, "> 0 (metres)", height)?;
        let geo = Geometry::new(width, height);

        let mu_s = r.number("friction", "static", true)?.unwrap_or(f64::INFINITY);
        check("friction.static", mu_s >= 0.0, ">= 0 or inf", mu_s)?;
        let given_k = r.number("friction", "kinetic", true)?;
        let mu_k = given_k.unwrap_or(mu_s);
        // An absent kinetic coefficient takes the static one; an error about
        // it must then say so, or the user is told about a key never written.
        let kinetic_key = if given_k.is_some() {
            "friction.kinetic"
        } else {
            "friction.kinetic (absent, so equal to friction.static)"
        };
        check(kinetic_key, mu_k >= 0.0, ">= 0 or inf", mu_k)?;
        check(kinetic_key, mu_k <= mu_s, &format!("<= friction.static ({mu_s})"), mu_k)?;
        check(
            kinetic_key,
            mu_k.is_finite() || mu_s.is_infinite(),
            "finite when friction.static is finite",
            mu_k,
        )?;
        check(
            kinetic_key,
            mu_k < MU_K_LIMIT || mu_s.is_infinite(),
            "< 4/3 (larger kinetic friction makes slide-rock ill-posed: the Painlevé paradox, docs/model.md §4)",
            mu_k,
        )?;

        let law = r
            .choice("impact", "law", &["housner", "ratio", "impulse"])?
            .unwrap_or("housner")
            .to_string();
        // Housner's ratio is negative for squat blocks (ψ > 54.7°, where a
        // single-corner impact reverses the rotation and the block lands
        // flat, docs/model.md §7.5): the default ratio is then 0.
        let rr = r
            .number("impact", "r", false)?
            .unwrap_or_else(|| geo.housner_r().max(0.0));
        check("impact.r", (0.0..=1.0).contains(&rr), "in [0, 1]", rr)?;
        let e = r.number("impact", "e", false)?.unwrap_or(0.0);
        check("impact.e", (0.0..=1.0).contains(&e), "in [0, 1]", e)?;
        let impact_mu_s = r.number("impact", "static", true)?.unwrap_or(mu_s);
        check("impact.static", impact_mu_s >= 0.0, ">= 0 or inf", impact_mu_s)?;
        let impact_mu_k = r.number("impact", "kinetic", true)?.unwrap_or(mu_k.min(impact_mu_s));
        check("impact.kinetic", impact_mu_k >= 0.0, ">= 0 or inf", impact_mu_k)?;
        check(
            "impact.kinetic",
            impact_mu_k < MU_K_LIMIT || impact_mu_s.is_infinite(),
            "< 4/3 (larger kinetic friction makes the slipping impact ill-posed, docs/model.md §7.2)",
            impact_mu_k,
        )?;
        check(
            "impact.kinetic",
            impact_mu_k <= impact_mu_s,
            &format!("<= impact.static ({impact_mu_s})"),
            impact_mu_k,
        )?;

        let kind = match r.choice("excitation", "kind", &["harmonic", "pulse", "record", "none"])? {
            None | Some("harmonic") => ExcitationKind::Harmonic,
            Some("pulse") => ExcitationKind::Pulse,
            Some("record") => ExcitationKind::Record,
            Some(_) => ExcitationKind::None,
        };
        let a_h = r.number("excitation", "a_h", false)?.unwrap_or(0.0);
        let a_v = r.number("excitation", "a_v", false)?.unwrap_or(0.0);
        let amp_limit = 1e6;
        check(
            "excitation.a_h",
            a_h.abs() <= amp_limit,
            "a finite amplitude |A_h| <= 1e6 (units of ψg)",
            a_h,
        )?;
        check(
            "excitation.a_v",
            a_v.abs() <= amp_limit,
            "a finite amplitude |A_v| <= 1e6 (units of ψg)",
            a_v,
        )?;
        let omega_h = r.number("excitation", "omega_h", false)?.unwrap_or(8.0);
        check(
            "excitation.omega_h",
            omega_h > 0.0 && omega_h <= 1e6,
            "in (0, 1e6] (units of p)",
            omega_h,
        )?;
        let omega_v = r.number("excitation", "omega_v", false)?.unwrap_or(omega_h);
        check(
            "excitation.omega_v",
            omega_v > 0.0 && omega_v <= 1e6,
            "in (0, 1e6] (units of p)",
            omega_v,
        )?;
        let phase_h = r.number("excitation", "phase_h", false)?.unwrap_or(0.0);
        let phase_v = r.number("excitation", "phase_v", false)?.unwrap_or(0.0);
        check("excitation.phase_h", phase_h.abs() <= 1e6, "|Φ_h| <= 1e6 rad", phase_h)?;
        check("excitation.phase_v", phase_v.abs() <= 1e6, "|Φ_v| <= 1e6 rad", phase_v)?;
        let shape = r
            .choice("excitation", "shape", &["one-sine", "one-cosine", "type-c"])?
            .unwrap_or("one-sine")
            .to_string();
        let cycles = r.count("excitation", "cycles")?.unwrap_or(1);
        if !(1..=u64::from(pulse::MAX_TYPE_C_CYCLES)).contains(&cycles) {
            return Err(ConfigError::key(
                "excitation.cycles",
                format!("{cycles} is out of range: must be in 1..={}", pulse::MAX_TYPE_C_CYCLES),
            ));
        }
        let resolve = |p: &str| {
            let p = PathBuf::from(p);
            if p.is_absolute() { p } else { source.base_dir.join(p) }
        };
        let file_h = r.string("excitation", "file_h")?.map(resolve);
        let file_v = r.string("excitation", "file_v")?.map(resolve);
        let scale_h = r.number("excitation", "scale_h", false)?.unwrap_or(1.0);
        let scale_v = r.number("excitation", "scale_v", false)?.unwrap_or(1.0);
        check("excitation.scale_h", scale_h.abs() <= 1e3, "|scale| <= 1000", scale_h)?;
        check("excitation.scale_v", scale_v.abs() <= 1e3, "|scale| <= 1000", scale_v)?;
        if kind == ExcitationKind::Record && file_h.is_none() {
            return Err(ConfigError::key(
                "excitation.file_h",
                "is required when excitation.kind = \"record\"",
            ));
        }

        let rtol = r.number("run", "rtol", false)?.unwrap_or(1e-10);
        check("run.rtol", rtol > 0.0 && rtol < 1.0, "in (0, 1)", rtol)?;
        let run_method = match r.choice("run", "method", &["dop853", "dopri5", "ralston", "taylor"])? {
            None => Method::default_for(rtol),
            Some("dop853") => Method::Dop853,
            Some("dopri5") => Method::Dopri5,
            Some("taylor") => Method::Taylor,
            Some(_) => Method::Ralston,
        };
        let atol = r.number("run", "atol", false)?.unwrap_or(1e-12);
        check("run.atol", atol > 0.0 && atol < 1.0, "in (0, 1)", atol)?;
        let step = r.number("run", "step", false)?.unwrap_or(0.004);
        check("run.step", step > 0.0 && step < 1.0, "in (0, 1)", step)?;
        let tau_end = r.number("run", "tau_end", false)?.unwrap_or(800.0);
        check("run.tau_end", tau_end > 0.0 && tau_end <= 1e9, "in (0, 1e9]", tau_end)?;
        let output_dt = r.number("run", "output_dt", false)?.unwrap_or(0.02);
        check(
            "run.output_dt",
            output_dt >= 0.0,
            ">= 0 (0 writes no history)",
            output_dt,
        )?;
        if output_dt > 0.0 && tau_end / output_dt > 5e7 {
            return Err(ConfigError::key(
                "run.output_dt",
                format!(
                    "{output_dt} gives more than 5e7 history rows over run.tau_end = {tau_end}; use a larger step or 0"
                ),
            ));
        }
        let side = geo.side_theta();
        let tumble_theta = r.number("run", "tumble_theta", false)?.unwrap_or(1.0);
        check(
            "run.tumble_theta",
            tumble_theta > 0.0 && tumble_theta <= side,
            &format!("in (0, π/(2ψ) = {side}]"),
            tumble_theta,
        )?;
        let flight = match r.choice("run", "flight", &["stop", "ignore"])? {
            None | Some("stop") => FlightPolicy::Stop,
            Some(_) => FlightPolicy::Ignore,
        };
        let zeno_eps = r.number("run", "zeno_eps", false)?.unwrap_or(1e-5);
        check("run.zeno_eps", (0.0..1.0).contains(&zeno_eps), "in [0, 1)", zeno_eps)?;
        let limits = Limits::default();
        let max_steps = r.count("run", "max_steps")?.unwrap_or(limits.max_steps);
        let max_events = r.count("run", "max_events")?.unwrap_or(limits.max_events);
        if max_steps == 0 {
            return Err(ConfigError::key("run.max_steps", "must be >= 1"));
        }

        let theta0 = r.number("initial", "theta", false)?.unwrap_or(0.0);
        check(
            "initial.theta",
            theta0.abs() < tumble_theta,
            &format!("|Θ| < run.tumble_theta ({tumble_theta})"),
            theta0,
        )?;
        let theta_dot0 = r.number("initial", "theta_dot", false)?.unwrap_or(0.0);
        check("initial.theta_dot", theta_dot0.abs() <= 1e6, "|Θ'| <= 1e6", theta_dot0)?;
        let x_dot0 = r.number("initial", "x_dot", false)?;
        if let Some(x) = x_dot0 {
            check("initial.x_dot", x.abs() <= 1e6, "|X'| <= 1e6", x)?;
        }

        let lyapunov = boolean(table, "analysis", "lyapunov")?.unwrap_or(false);
        let lyapunov_method = r
            .choice("analysis", "lyapunov_method", &["tangent", "benettin", "both"])?
            .unwrap_or("tangent")
            .to_string();
        if lyapunov && kind != ExcitationKind::Harmonic {
            return Err(ConfigError::key(
                "analysis.lyapunov",
                "needs excitation.kind = \"harmonic\" (the exponents of the periodically forced block)",
            ));
        }

        let spectrum = boolean(table, "analysis", "spectrum")?.unwrap_or(false);
        let spectrum_window = r
            .choice("analysis", "spectrum_window", &["all", "paper"])?
            .unwrap_or("all")
            .to_string();
        if spectrum && output_dt <= 0.0 {
            return Err(ConfigError::key(
                "analysis.spectrum",
                "needs run.output_dt > 0 (the spectrum is computed from the history)",
            ));
        }
        if spectrum && spectrum_window == "paper" && tau_end < 28.384 {
            return Err(ConfigError::key(
                "analysis.spectrum_window",
                "\"paper\" needs run.tau_end >= 28.384 (the paper's window is τ 12–28.384)",
            ));
        }

        r.reject_unknown(KNOWN_KEYS)?;
        Ok(Self {
            width,
            height,
            mu_s,
            mu_k,
            law,
            r: rr,
            e,
            impact_mu_s,
            impact_mu_k,
            kind,
            a_h,
            a_v,
            omega_h,
            omega_v,
            phase_h,
            phase_v,
            shape,
            cycles,
            file_h,
            file_v,
            scale_h,
            scale_v,
            theta0,
            theta_dot0,
            x_dot0,
            tau_end,
            method: run_method,
            rtol,
            atol,
            step,
            output_dt,
            tumble_theta,
            flight,
            zeno_eps,
            max_steps,
            max_events,
            lyapunov,
            lyapunov_method,
            spectrum,
            spectrum_window,
        })
    }

    /// The block's geometry.
    pub fn geometry(&self) -> Geometry {
        Geometry::new(self.width, self.height)
    }

    /// Builds the excitation, reading record files if needed.
    pub fn excitation(&self) -> Result<Excitation, ConfigError> {
        let geo = self.geometry();
        Ok(match self.kind {
            ExcitationKind::None => Excitation::None,
            ExcitationKind::Harmonic => Excitation::Harmonic(Harmonic {
                a_h: self.a_h,
                a_v: self.a_v,
                omega_h: self.omega_h,
                omega_v: self.omega_v,
                phase_h: self.phase_h,
                phase_v: self.phase_v,
                psi: geo.psi,
            }),
            ExcitationKind::Pulse => {
                let shape = match self.shape.as_str() {
                    "one-cosine" => PulseShape::OneCosine,
                    "type-c" => PulseShape::TypeC { n: self.cycles as u32 },
                    _ => PulseShape::OneSine,
                };
                let make = |amp: f64, omega: f64, key: &str| {
                    Pulse::new(shape, amp * geo.psi, omega).map_err(|e| ConfigError::key(key, e))
                };
                let horizontal = make(self.a_h, self.omega_h, "excitation.a_h")?;
                let vertical = if self.a_v != 0.0 {
                    Some(make(self.a_v, self.omega_v, "excitation.a_v")?)
                } else {
                    None
                };
                Excitation::Pulse(crate::model::excitation::PulsePair { horizontal, vertical })
            }
            ExcitationKind::Record => {
                let read = |p: &Option<PathBuf>| -> Result<Option<Series>, ConfigError> {
                    match p {
                        None => Ok(None),
                        Some(p) => record::read_record(p).map(Some).map_err(|e| ConfigError(e.to_string())),
                    }
                };
                let Some(h) = read(&self.file_h)? else {
                    return Err(ConfigError::key(
                        "excitation.file_h",
                        "is required when excitation.kind = \"record\"",
                    ));
                };
                let v = read(&self.file_v)?;
                Excitation::Record(Box::new(RecordExcitation::new(h, v, geo.p, self.scale_h, self.scale_v)))
            }
        })
    }

    /// The impact law.
    pub fn impact_law(&self) -> ImpactLaw {
        match self.law.as_str() {
            "ratio" => ImpactLaw::Ratio { r: self.r },
            "impulse" => ImpactLaw::Impulse {
                e: self.e,
                mu_s: self.impact_mu_s,
                mu_k: self.impact_mu_k,
            },
            _ => ImpactLaw::Housner,
        }
    }

    /// The model (reads record files).
    pub fn model(&self) -> Result<Model, ConfigError> {
        Ok(Model {
            geo: self.geometry(),
            mu_s: self.mu_s,
            mu_k: self.mu_k,
            law: self.impact_law(),
            excitation: self.excitation()?,
            tumble_theta: self.tumble_theta,
            flight: self.flight,
            zeno_eps: self.zeno_eps,
        })
    }

    /// The initial state.
    pub fn initial(&self) -> InitialState {
        InitialState {
            theta: self.theta0,
            theta_dot: self.theta_dot0,
            x_dot: self.x_dot0,
        }
    }

    /// The run options. `section` is on for harmonic excitation.
    pub fn run_options(&self) -> RunOptions {
        RunOptions {
            tau_end: self.tau_end,
            method: self.method,
            tol: Tolerances {
                rtol: self.rtol,
                atol: self.atol,
                h_max: f64::INFINITY,
                h_fixed: self.step,
            },
            output_dt: (self.output_dt > 0.0).then_some(self.output_dt),
            section: self.kind == ExcitationKind::Harmonic,
            limits: Limits {
                max_steps: self.max_steps,
                max_events: self.max_events,
                ..Limits::default()
            },
        }
    }

    /// The resolved config as JSON, in the same sections and keys as the
    /// TOML (infinite friction as the string `"inf"`, an unset
    /// `initial.x_dot` as `null`).
    pub fn to_json(&self) -> Json {
        let num = |x: f64| if x.is_finite() { json!(x) } else { json!("inf") };
        let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
        json!({
            "block": { "width": self.width, "height": self.height },
            "friction": { "static": num(self.mu_s), "kinetic": num(self.mu_k) },
            "impact": {
                "law": self.law, "r": self.r, "e": self.e,
                "static": num(self.impact_mu_s), "kinetic": num(self.impact_mu_k),
            },
            "excitation": {
                "kind": match self.kind {
                    ExcitationKind::None => "none",
                    ExcitationKind::Harmonic => "harmonic",
                    ExcitationKind::Pulse => "pulse",
                    ExcitationKind::Record => "record",
                },
                "a_h": self.a_h, "a_v": self.a_v,
                "omega_h": self.omega_h, "omega_v": self.omega_v,
                "phase_h": self.phase_h, "phase_v": self.phase_v,
                "shape": self.shape, "cycles": self.cycles,
                "file_h": path(&self.file_h), "file_v": path(&self.file_v),
                "scale_h": self.scale_h, "scale_v": self.scale_v,
            },
            "initial": { "theta": self.theta0, "theta_dot": self.theta_dot0, "x_dot": self.x_dot0 },
            "run": {
                "tau_end": self.tau_end, "method": self.method.name(),
                "rtol": self.rtol, "atol": self.atol, "step": self.step,
                "output_dt": self.output_dt, "tumble_theta": self.tumble_theta,
                "flight": match self.flight { FlightPolicy::Stop => "stop", FlightPolicy::Ignore => "ignore" },
                "zeno_eps": self.zeno_eps, "max_steps": self.max_steps, "max_events": self.max_events,
            },
            "analysis": {
                "lyapunov": self.lyapunov, "lyapunov_method": self.lyapunov_method,
                "spectrum": self.spectrum, "spectrum_window": self.spectrum_window,
            },
        })
    }
}

/// Loads a config the way the CLI does: a preset or a file (or the
/// `default` preset), then `--set` overrides, then validation.
pub fn load(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<Config, ConfigError> {
    let (mut table, source) = match (preset, file) {
        (Some(_), Some(_)) => return Err(ConfigError("give either --preset or --config, not both".into())),
        (_, Some(path)) => read_file(path)?,
        (name, None) => {
            let name = name.unwrap_or("default");
            let text = preset_text(name)?;
            (parse_toml(text, &format!("preset {name}"))?, Source::default())
        }
    };
    apply_sets(&mut table, sets)?;
    Config::from_table(&table, &source)
}
