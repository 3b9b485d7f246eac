//! The inputs of a steady-response study (a sweep's grid, shard and
//! continuation; the sampling window) named by what they mean, and how a
//! surface spells them in its messages.
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

/// How a surface names study inputs in its messages.
pub trait FieldNames {
    /// `field` alone, e.g. `--tau-end` or `tau_end`.
    fn name(&self, field: StudyField) -> Cow<'static, str>;

    /// `field` given as `value`, e.g. `--tau-end 700` or `tau_end=700`.
    fn valued(&self, field: StudyField, value: &str) -> String;
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
