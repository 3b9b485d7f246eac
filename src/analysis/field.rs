//! The inputs of a study (a sweep's grid, shard and continuation; the
//! sampling window; an engineering spectrum's motion, sizes and searches)
//! named by what they mean, and how a surface spells them in its messages.
//!
//! Contract: the analysis layer never writes a surface's word for an input
//! (a CLI flag, a Python keyword). Its errors carry a [`StudyField`] with
//! the value and the rule broken; each surface renders them through its own
//! [`FieldNames`]: the CLI as `--tau-end 700`, the Python package as
//! `tau_end=700`. [`OwnNames`], the field names of the core's own structs
//! (`tau_end = 700`), is what `Display` prints for anyone else (the app).

use std::borrow::Cow;

/// One input of a sweep or map, by meaning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StudyField {
    /// A sweep's first value ([`Grid::from`](super::orbit_diagram::Grid)).
    From,
    /// A sweep's last value ([`Grid::to`](super::orbit_diagram::Grid)).
    To,
    /// A sweep's spacing ([`Grid::step`](super::orbit_diagram::Grid)).
    Step,
    /// Which share of a sweep's values to compute
    /// ([`Shard`](super::orbit_diagram::Shard), `K/N`).
    Shard,
    /// How each value of a sweep is seeded
    /// ([`Continuation`](super::orbit_diagram::Continuation)).
    Continuation,
    /// Where the sampling window starts, τ
    /// ([`Window::transient`](super::steady::Window)).
    Transient,
    /// Where each run ends, τ ([`Window::tau_end`](super::steady::Window)).
    TauEnd,
}

impl StudyField {
    /// The name of the field in the core's structs and in `sweep.json` /
    /// `map.json` (`from`, `tau_end`).
    pub fn name(self) -> &'static str {
        match self {
            StudyField::From => "from",
            StudyField::To => "to",
            StudyField::Step => "step",
            StudyField::Shard => "shard",
            StudyField::Continuation => "continuation",
            StudyField::Transient => "transient",
            StudyField::TauEnd => "tau_end",
        }
    }
}

/// One input of an engineering study (a spectrum's motion, sizes and
/// searches; [`request`](super::engineering::request)), by meaning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RequestField {
    /// The ground-motion record (its file).
    Record,
    /// The unit of a text record's accelerations.
    Unit,
    /// The unit of a text vertical record's accelerations.
    UnitV,
    /// The factor on the motion.
    Scale,
    /// The peak ground acceleration the motion is scaled to, g.
    Pga,
    /// An analytic pulse's shape.
    Pulse,
    /// A pulse's peak acceleration, g.
    PulseAccel,
    /// A pulse's period, s.
    PulsePeriod,
    /// The main cycles of a type-C pulse.
    Cycles,
    /// A spectrum's smallest block size, m.
    SizeFrom,
    /// A spectrum's largest block size, m.
    SizeTo,
    /// A spectrum's number of block sizes.
    SizeCount,
    /// Slenderness ratios B/H.
    BOverH,
    /// Step of the scales an overturning-scale search tries.
    SearchStep,
    /// Largest scale an overturning-scale search tries.
    SearchMax,
    /// Step of the amplitudes a pulse map's search tries.
    AmpStep,
    /// Largest amplitude a pulse map's search tries.
    AmpMax,
    /// Relative width to which a search's boundaries are refined.
    RelTol,
    /// Friction coefficients μ_s of a sliding spectrum.
    Mu,
    /// μ_k/μ_s of a sliding spectrum.
    KineticRatio,
    /// A fragility study's intensity measure.
    Im,
    /// The period of the spectral acceleration Sa(T), s.
    SaPeriod,
    /// A fragility study's intensity levels.
    Levels,
    /// A fragility study's blocks.
    Blocks,
    /// The θ/α whose exceedance a fragility study counts.
    Threshold,
}

impl RequestField {
    /// The name of the field in the core's structs (`scale`, `from_m`).
    pub fn name(self) -> &'static str {
        match self {
            RequestField::Record => "record",
            RequestField::Unit => "unit",
            RequestField::UnitV => "unit_v",
            RequestField::Scale => "scale",
            RequestField::Pga => "pga",
            RequestField::Pulse => "pulse",
            RequestField::PulseAccel => "pulse_accel",
            RequestField::PulsePeriod => "pulse_period",
            RequestField::Cycles => "cycles",
            RequestField::SizeFrom => "from_m",
            RequestField::SizeTo => "to_m",
            RequestField::SizeCount => "count",
            RequestField::BOverH => "b_over_h",
            RequestField::SearchStep => "search_step",
            RequestField::SearchMax => "search_max",
            RequestField::AmpStep => "amp_step",
            RequestField::AmpMax => "amp_max",
            RequestField::RelTol => "rel_tol",
            RequestField::Mu => "mu",
            RequestField::KineticRatio => "kinetic_ratio",
            RequestField::Im => "im",
            RequestField::SaPeriod => "sa_period",
            RequestField::Levels => "levels",
            RequestField::Blocks => "blocks",
            RequestField::Threshold => "threshold",
        }
    }
}

/// A number for a message: as typed when it is of everyday size
/// (`0.35`, `120`), else in scientific form (`1e-300`, `2.5e12`), so no
/// message prints a 300-digit decimal.
pub fn show(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !a.is_finite() || (1e-4..1e9).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// How a surface names study inputs in its messages: the inputs of a
/// sweep or map ([`StudyField`], the default) or of an engineering study
/// ([`RequestField`]).
pub trait FieldNames<F = StudyField> {
    /// `field` alone, e.g. `--tau-end` or `tau_end`.
    fn name(&self, field: F) -> Cow<'static, str>;

    /// `field` given as `value`, e.g. `--tau-end 700` or `tau_end=700`.
    fn valued(&self, field: F, value: &str) -> String;
}

/// The core's own names ([`StudyField::name`]), a value after ` = `: what
/// the errors' `Display` prints.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct OwnNames;

impl FieldNames for OwnNames {
    fn name(&self, field: StudyField) -> Cow<'static, str> {
        Cow::Borrowed(field.name())
    }

    fn valued(&self, field: StudyField, value: &str) -> String {
        format!("{} = {value}", field.name())
    }
}

impl FieldNames<RequestField> for OwnNames {
    fn name(&self, field: RequestField) -> Cow<'static, str> {
        Cow::Borrowed(field.name())
    }

    fn valued(&self, field: RequestField, value: &str) -> String {
        format!("{} = {value}", field.name())
    }
}
