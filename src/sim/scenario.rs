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

use std::path::PathBuf;

use super::method::Method;
use super::run::{InitialState, RunOptions};
use crate::integrate::Tolerances;
use crate::integrate::hybrid::Limits;
use crate::model::excitation::record::Series;
use crate::model::excitation::{
    Excitation, FloorExcitation, FloorMode, Harmonic, Pulse, PulsePair, PulseShape, RecordExcitation,
};
use crate::model::oscillator::Oscillator;
use crate::model::stack::StackBlock;
use crate::model::units::AccelUnit;
use crate::model::{FlightPolicy, Frame, Geometry, ImpactLaw, Model};

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

/// The block and its contact with the base.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Width B, m, > 0. Default 1 (the paper's).
    pub width: f64,
    /// Height H, m, > 0. Default 4 (the paper's).
    pub height: f64,
    /// Static friction coefficient μ_s ≥ 0, or infinite (no sliding, the
    /// paper's sec. 4.1; the default).
    pub mu_s: f64,
    /// Kinetic friction coefficient μ_k, 0 ≤ μ_k ≤ μ_s; `None`: μ_s.
    pub mu_k: Option<f64>,
}

impl Block {
    /// The block's geometry.
    pub fn geometry(&self) -> Geometry {
        Geometry::new(self.width, self.height)
    }

    /// μ_k, resolved.
    pub fn kinetic(&self) -> f64 {
        self.mu_k.unwrap_or(self.mu_s)
    }
}

/// Which impact law (`impact.law`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// Housner's law as the literature states it: Θ'₊ = (1 − 1.5 sin²ψ) Θ'₋
    /// and the new pivot sticks, stopping any slip (the default).
    Housner,
    /// Angular momentum about the striking corner conserved, pre-impact
    /// slip included (config name `corner-momentum`); equals `housner`
    /// when the block does not slip before the impact.
    #[serde(rename = "corner-momentum")]
    CornerMomentum,
    /// A given angular-velocity ratio r.
    Ratio,
    /// The paper's impulse–momentum law with restitution and friction.
    Impulse,
}

impl LawKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            LawKind::Housner => "housner",
            LawKind::CornerMomentum => "corner-momentum",
            LawKind::Ratio => "ratio",
            LawKind::Impulse => "impulse",
        }
    }
}

/// The impact law and its coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct Impact {
    /// The law.
    pub law: LawKind,
    /// Ratio r of the ratio law, in [0, 1]; `None`: Housner's 1 − 1.5 sin²ψ
    /// (0 for blocks squat enough that it is negative).
    pub r: Option<f64>,
    /// Vertical restitution e of the impulse law, in [0, 1]. Default 0.
    pub e: f64,
    /// Static friction μ̄_s during impact; `None`: the block's μ_s (as in
    /// the paper).
    pub mu_s: Option<f64>,
    /// Kinetic friction μ̄_k during impact; `None`: min(μ_k, μ̄_s).
    pub mu_k: Option<f64>,
}

/// Which excitation (`excitation.kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
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

impl ExcitationKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            ExcitationKind::None => "none",
            ExcitationKind::Harmonic => "harmonic",
            ExcitationKind::Pulse => "pulse",
            ExcitationKind::Record => "record",
        }
    }
}

/// Shape of a pulse (`excitation.shape`); the number of cycles of type C is
/// kept apart, in [`ExcitationSpec::cycles`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShapeKind {
    /// Makris type A (the default).
    OneSine,
    /// Makris type B.
    OneCosine,
    /// Type C_n.
    TypeC,
    /// Constant a_p for π/ω (Housner 1963).
    Rectangular,
    /// a_p sin(ωτ) for π/ω.
    HalfSine,
}

impl ShapeKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::OneSine => "one-sine",
            ShapeKind::OneCosine => "one-cosine",
            ShapeKind::TypeC => "type-c",
            ShapeKind::Rectangular => "rectangular",
            ShapeKind::HalfSine => "half-sine",
        }
    }
}

/// How a record shipped inside the program is named in place of a path
/// (`shipped:kobe-1995.dat`): see `io::shipped`.
pub const SHIPPED_PREFIX: &str = "shipped:";

/// A ground-motion record read by the config layer, with where it came from
/// (for `summary.json`).
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The file, as the config named it (resolved against the config's
    /// folder), or `shipped:NAME` for a record shipped inside the program
    /// ([`SHIPPED_PREFIX`]).
    pub path: PathBuf,
    /// Its samples, accelerations converted to g.
    pub series: Series,
    /// The unit the file's accelerations were in (`excitation.unit_h`, or
    /// read from an AT2 header).
    pub unit: AccelUnit,
    /// The time step of a one-column file, s (`excitation.dt_h`); `None`
    /// for files that hold their times.
    pub dt: Option<f64>,
    /// CRC-32 of the file's bytes (`excitation.crc32_h`, written to
    /// `summary.json` so that a rerun notices a changed file).
    pub crc32: u32,
    /// The channel read, from 1, of a COSMOS file that holds several
    /// (`excitation.channel_h`); `None` for a file of one.
    pub channel: Option<usize>,
}

impl Record {
    /// The record's file name, for answers and labels: `kobe-1995.dat` for
    /// `/data/kobe-1995.dat` and for the shipped `shipped:kobe-1995.dat`.
    pub fn file_name(&self) -> String {
        record_file_name(&self.path.display().to_string())
    }

    /// Why the record's PGA as read (before any scale) suggests a wrong
    /// unit, if it does: `PGA 6.803 g as read in g is implausible for
    /// ground motion (above 5 g); check its unit`. A study scales records
    /// on purpose, so it is their PGA as read that tells a unit mistake.
    pub fn unit_doubt(&self) -> Option<String> {
        let pga = self.series.peak_abs_g();
        Scenario::pga_doubt(pga).map(|doubt| {
            format!(
                "PGA {} g as read in {} is {doubt}; check its unit",
                readable_g(pga),
                self.unit
            )
        })
    }
}

/// The file name in a record's path or `shipped:NAME` reference (the text
/// itself when it has none).
pub(crate) fn record_file_name(path: &str) -> String {
    let path = path.strip_prefix(SHIPPED_PREFIX).unwrap_or(path);
    std::path::Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The [`Record::path`] of a record given as samples (from memory, not
/// from a file): it names no file, so messages that show a record's path
/// say where it came from.
pub(crate) const IN_MEMORY: &str = "(samples in memory)";

impl Record {
    /// A record given as samples rather than read from a file (a caller
    /// that holds them, such as the Python package): `unit` is the unit the
    /// caller's accelerations were in (the series is in g), `dt` their time
    /// step if they were given as one. Its CRC-32 is of the series' bytes
    /// (times then accelerations, little-endian f64), so that two runs can
    /// tell whether they had the same samples; no file can be checked
    /// against it, and a config written from it names no file
    /// ([`Record::is_in_memory`]).
    pub fn in_memory(series: Series, unit: AccelUnit, dt: Option<f64>) -> Self {
        let mut hasher = crc32fast::Hasher::new();
        for x in series.times_s().iter().chain(series.accel_g()) {
            hasher.update(&x.to_le_bytes());
        }
        Self {
            path: PathBuf::from(IN_MEMORY),
            series,
            unit,
            dt,
            crc32: hasher.finalize(),
            channel: None,
        }
    }

    /// Whether the record was given as samples ([`Record::in_memory`]).
    pub fn is_in_memory(&self) -> bool {
        self.path.as_os_str() == IN_MEMORY
    }
}

/// The base motion.
#[derive(Clone, Debug, PartialEq)]
pub struct ExcitationSpec {
    /// Which kind. Default harmonic.
    pub kind: ExcitationKind,
    /// A_h, units of ψ g (harmonic and pulse). Default 0.
    pub a_h: f64,
    /// A_v, units of ψ g. Default 0.
    pub a_v: f64,
    /// Ω_h, units of p, > 0. Default 8 (the paper's).
    pub omega_h: f64,
    /// Ω_v, units of p, > 0; `None`: Ω_h.
    pub omega_v: Option<f64>,
    /// Φ_h, rad. Default 0.
    pub phase_h: f64,
    /// Φ_v, rad. Default 0.
    pub phase_v: f64,
    /// Pulse shape. Default one-sine.
    pub shape: ShapeKind,
    /// n of a type-C_n pulse, 1..=[`MAX_TYPE_C_CYCLES`](crate::model::excitation::pulse::MAX_TYPE_C_CYCLES). Default 1.
    pub cycles: u32,
    /// Horizontal record (required for `Record`).
    pub record_h: Option<Record>,
    /// Optional vertical record.
    pub record_v: Option<Record>,
    /// Factor on the horizontal record. Default 1.
    pub scale_h: f64,
    /// Factor on the vertical record. Default 1.
    pub scale_v: f64,
}

impl ExcitationSpec {
    /// Ω_v, resolved.
    pub fn omega_v(&self) -> f64 {
        self.omega_v.unwrap_or(self.omega_h)
    }

    /// The forcing period 2π/Ω_h of harmonic excitation, τ; `None` for the
    /// other kinds.
    pub fn forcing_period(&self) -> Option<f64> {
        (self.kind == ExcitationKind::Harmonic).then(|| std::f64::consts::TAU / self.omega_h)
    }
}

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

/// Which Lyapunov method a batch run adds (`analysis.lyapunov_method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LyapunovChoice {
    /// Tangent dynamics with saltation matrices: the whole spectrum (the
    /// default: it needs no separation parameter).
    Tangent,
    /// Benettin's two trajectories on the stroboscopic map.
    Benettin,
    /// Both on one trajectory, with their paired difference.
    Both,
}

impl LyapunovChoice {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            LyapunovChoice::Tangent => "tangent",
            LyapunovChoice::Benettin => "benettin",
            LyapunovChoice::Both => "both",
        }
    }
}

/// The part of the history a batch run's spectrum is taken over
/// (`analysis.spectrum_window`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpectrumRange {
    /// The whole history (the default).
    All,
    /// The paper's samples 3000–7095 at Δτ = 0.004 (τ 12–28.384).
    Paper,
}

impl SpectrumRange {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            SpectrumRange::All => "all",
            SpectrumRange::Paper => "paper",
        }
    }
}

/// τ at which the paper's spectrum window ends.
pub(crate) const PAPER_SPECTRUM_END: f64 = 28.384;

/// Default damping ratio of a building mode (`floor.damping`): 5 % of
/// critical, the damping design spectra are written for (ASCE 7-22
/// §11.4, Eurocode 8 §3.2.2.2) and the usual value for reinforced-concrete
/// and steel buildings shaken near their design level.
pub(crate) const FLOOR_DAMPING: f64 = 0.05;

/// Default participation Γφ of a single building mode at the floor
/// (`floor.participation`): 1, the floor as the mass of a one-storey
/// building, which makes the floor acceleration the oscillator's absolute
/// acceleration a_f = −2ζωu̇ − ω²u (the floor-spectrum convention). A
/// uniform shear building has (4/π) sin(πz/2H) at height z (docs/model.md,
/// "Floor motion"); give that for a floor of a taller building.
pub(crate) const FLOOR_PARTICIPATION: f64 = 1.0;

/// Shortest building period accepted, s (`floor.period`): 0.01 s is a
/// 100 Hz mode, above any frequency ground shaking carries (about
/// 0.1–30 Hz), so such a floor is rigid; leave `[floor]` out instead. A
/// shorter period would also force the integrator's steps down to 1/ω.
pub(crate) const MIN_FLOOR_PERIOD_S: f64 = 0.01;

/// Longest building period accepted, s: the tallest buildings have
/// fundamental periods under about 10 s; 20 s is a typo or a wrong unit.
pub(crate) const MAX_FLOOR_PERIOD_S: f64 = 20.0;

/// Largest |Γφ| accepted (`floor.participation`): a uniform shear
/// building's first mode has 4/π ≈ 1.27 at its roof and higher modes less;
/// 10 is a typo, not a building.
pub(crate) const MAX_FLOOR_PARTICIPATION: f64 = 10.0;

/// One mode of the building the block stands in (`[floor]` or one
/// `[[floor.mode]]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorModeSpec {
    /// Period T, s, in [[`MIN_FLOOR_PERIOD_S`], [`MAX_FLOOR_PERIOD_S`]].
    pub period_s: f64,
    /// Damping ratio ζ, fraction of critical, in (0, 1). Default
    /// [`FLOOR_DAMPING`].
    pub damping: f64,
    /// Γφ at the floor. Default [`FLOOR_PARTICIPATION`].
    pub participation: f64,
}

/// The building between the ground and the block (`[floor]`): the block
/// feels the ground's horizontal motion filtered through these modes.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorSpec {
    /// The modes (at least one).
    pub modes: Vec<FloorModeSpec>,
    /// Whether they were given as `[[floor.mode]]` tables (for the config
    /// written back).
    pub as_tables: bool,
}

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

    /// The excitation the block feels: the ground's ([`Scenario::ground_excitation`])
    /// filtered through the building of `[floor]` if there is one. Fails
    /// for a pulse the model refuses (the error names the amplitude's key)
    /// and for a pulse under `[floor]`.
    pub fn excitation(&self) -> Result<Excitation, ScenarioError> {
        let ground = self.ground_excitation()?;
        let Some(floor) = &self.floor else {
            return Ok(ground);
        };
        let mut modes = Vec::with_capacity(floor.modes.len());
        for (k, m) in floor.modes.iter().enumerate() {
            let key = if floor.as_tables {
                format!("floor.mode[{k}].period")
            } else {
                "floor.period".to_string()
            };
            let oscillator = Oscillator::new(m.period_s, m.damping)
                .ok_or_else(|| ScenarioError::new(key, "needs a period > 0 s and a damping in [0, 1)"))?;
            modes.push(FloorMode {
                oscillator,
                participation: m.participation,
            });
        }
        Ok(match ground {
            Excitation::None => Excitation::None,
            Excitation::Harmonic(h) => {
                Excitation::Floor(Box::new(FloorExcitation::harmonic(h, modes, self.geometry().p)))
            }
            Excitation::Record(r) => Excitation::Floor(Box::new(FloorExcitation::record(*r, modes))),
            Excitation::Pulse(_) | Excitation::Floor(_) => {
                return Err(ScenarioError::new(
                    "floor",
                    "filters records and harmonic ground motion only; a pulse stands for near-fault ground motion, remove [floor] or use excitation.kind = \"record\"",
                ));
            }
        })
    }

    /// The ground's excitation, without the building of `[floor]`.
    pub(crate) fn ground_excitation(&self) -> Result<Excitation, ScenarioError> {
        let geo = self.geometry();
        let x = &self.excitation;
        Ok(match x.kind {
            ExcitationKind::None => Excitation::None,
            ExcitationKind::Harmonic => Excitation::Harmonic(Harmonic {
                a_h: x.a_h,
                a_v: x.a_v,
                omega_h: x.omega_h,
                omega_v: x.omega_v(),
                phase_h: x.phase_h,
                phase_v: x.phase_v,
                psi: geo.psi,
            }),
            ExcitationKind::Pulse => {
                let shape = match x.shape {
                    ShapeKind::OneCosine => PulseShape::OneCosine,
                    ShapeKind::TypeC => PulseShape::TypeC { n: x.cycles },
                    ShapeKind::OneSine => PulseShape::OneSine,
                    ShapeKind::Rectangular => PulseShape::Rectangular,
                    ShapeKind::HalfSine => PulseShape::HalfSine,
                };
                let make = |amp: f64, omega: f64, key: &str| {
                    Pulse::new(shape, amp * geo.psi, omega).map_err(|e| ScenarioError::new(key, e))
                };
                let horizontal = make(x.a_h, x.omega_h, "excitation.a_h")?;
                let vertical = if x.a_v != 0.0 {
                    Some(make(x.a_v, x.omega_v(), "excitation.a_v")?)
                } else {
                    None
                };
                Excitation::Pulse(PulsePair { horizontal, vertical })
            }
            ExcitationKind::Record => {
                let Some(h) = &x.record_h else {
                    return Err(ScenarioError::new(
                        "excitation.file_h",
                        "is required when excitation.kind = \"record\"",
                    ));
                };
                let v = x.record_v.as_ref().map(|r| r.series.clone());
                Excitation::Record(Box::new(RecordExcitation::new(
                    h.series.clone(),
                    v,
                    geo.p,
                    x.scale_h,
                    x.scale_v,
                )))
            }
        })
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

    /// The end of the record in τ (the later of its two components' last
    /// samples, times p), for a record scenario.
    pub fn record_end_tau(&self) -> Option<f64> {
        let x = &self.excitation;
        if x.kind != ExcitationKind::Record {
            return None;
        }
        let h = x.record_h.as_ref()?.series.duration_s();
        let v = x.record_v.as_ref().map_or(0.0, |r| r.series.duration_s());
        Some(h.max(v) * self.geometry().p)
    }

    /// For a record, the τ after which a block at rest stays at rest for
    /// ever: the record's end, or on a floor the later time at which the
    /// building's ringing down can no longer lift or slide the block
    /// ([`FloorExcitation::quiet_after`] at min(B/H, μ_s) g, the vertical
    /// being at rest then). `None` for other kinds.
    pub(crate) fn rest_after_tau(&self) -> Option<f64> {
        let end = self.record_end_tau()?;
        if self.floor.is_none() {
            return Some(end);
        }
        let level = (self.block.width / self.block.height).min(self.block.mu_s);
        match self.excitation() {
            Ok(Excitation::Floor(f)) => Some(end.max(f.quiet_after(end, level))),
            _ => Some(end),
        }
    }

    /// Where the run ends, τ: `run.tau_end`, or for a record whose length
    /// decides ([`RunSpec::record_tail_s`]) the record's end plus the tail.
    pub fn tau_end(&self) -> f64 {
        match (self.record_end_tau(), self.run.record_tail_s) {
            (Some(end), Some(tail_s)) => end + tail_s * self.geometry().p,
            _ => self.run.tau_end,
        }
    }

    /// Whether the run covers the whole record (its end is at or after the
    /// record's last sample); `None` for other kinds. A run that overturns
    /// earlier still covered it in this sense: nothing was cut short by the
    /// user.
    pub fn record_complete(&self) -> Option<bool> {
        self.record_end_tau().map(|end| self.tau_end() >= end)
    }

    /// Why a record's PGA of `pga_g` (g) suggests a wrong unit, if it does:
    /// above [`IMPLAUSIBLE_PGA_G`] or below [`IMPLAUSIBLY_SMALL_PGA_G`].
    pub(crate) fn pga_doubt(pga_g: f64) -> Option<String> {
        if pga_g > IMPLAUSIBLE_PGA_G {
            Some(format!("implausible for ground motion (above {IMPLAUSIBLE_PGA_G} g)"))
        } else if pga_g < IMPLAUSIBLY_SMALL_PGA_G {
            Some(format!(
                "implausibly small for a record to run (below {IMPLAUSIBLY_SMALL_PGA_G} g)"
            ))
        } else {
            None
        }
    }

    /// One line per record whose peak suggests a wrong unit (PGA above
    /// [`IMPLAUSIBLE_PGA_G`] or below [`IMPLAUSIBLY_SMALL_PGA_G`] after unit
    /// and scale), naming the file and its PGA: the run goes on, but the
    /// user is told.
    pub fn warnings(&self) -> Vec<String> {
        let x = &self.excitation;
        if x.kind != ExcitationKind::Record {
            return Vec::new();
        }
        [
            ("excitation.unit_h", &x.record_h, x.scale_h),
            ("excitation.unit_v", &x.record_v, x.scale_v),
        ]
        .into_iter()
        .filter_map(|(key, r, scale)| {
            let r = r.as_ref()?;
            let pga = r.series.peak_abs_g() * scale.abs();
            let doubt = Self::pga_doubt(pga)?;
            Some(format!(
                "warning: {}: PGA {} g (read in {}, scaled by {}) is {doubt}; check {key}",
                r.path.display(),
                readable_g(pga),
                r.unit,
                scale,
            ))
        })
        .collect()
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
