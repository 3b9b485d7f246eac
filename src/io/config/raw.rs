//! The config file's shape as serde types: every section and key, with the
//! type of its value. Deserialising a TOML table into [`RawConfig`] checks
//! the types (a number where a number belongs, `inf` only where friction may
//! be infinite, one of the named choices); the scenario then checks the
//! ranges ([`Scenario::validate`](crate::sim::Scenario::validate)).
//!
//! Absent keys are `None`: the scenario's defaults fill them, and a default
//! that follows another value stays free to follow it.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};

use super::quantity::Quantity;
use crate::model::FlightPolicy;
use crate::sim::Method;
use crate::sim::scenario::{ExcitationKind, LawKind, LyapunovChoice, ShapeKind, SpectrumRange};

/// The whole file: every section optional.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawConfig {
    /// `[block]`.
    pub block: RawBlock,
    /// `[friction]`.
    pub friction: RawFriction,
    /// `[impact]`.
    pub impact: RawImpact,
    /// `[excitation]`.
    pub excitation: RawExcitation,
    /// `[initial]`.
    pub initial: RawInitial,
    /// `[run]`.
    pub run: RawRun,
    /// `[analysis]`.
    pub analysis: RawAnalysis,
    /// `[floor]`: the building the block stands in, if any.
    pub floor: Option<RawFloor>,
    /// `[frame]`: a rocking frame instead of the single block.
    pub frame: Option<RawFrame>,
    /// `[[stack]]`: stacked blocks instead of the single block.
    pub stack: Option<Vec<RawStackBlock>>,
}

/// One `[[stack]]` table: a block of a stack, bottom to top.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawStackBlock {
    pub width: Option<Quantity>,
    pub height: Option<Quantity>,
    pub offset: Option<Quantity>,
    #[serde(rename = "static")]
    pub mu_s: Option<Coefficient>,
    #[serde(rename = "kinetic")]
    pub mu_k: Option<Coefficient>,
    pub glued: Option<bool>,
}

/// `[frame]`: the columns' size, their number and the cap beam's mass.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawFrame {
    pub width: Option<Quantity>,
    pub height: Option<Quantity>,
    pub columns: Option<Count>,
    pub beam_mass_ratio: Option<Finite>,
}

/// `[floor]`: one building mode's keys, or `[[floor.mode]]` tables.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawFloor {
    pub period: Option<Quantity>,
    pub damping: Option<Finite>,
    pub participation: Option<Finite>,
    pub mode: Option<Vec<RawFloorMode>>,
}

/// One `[[floor.mode]]` table.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawFloorMode {
    pub period: Option<Quantity>,
    pub damping: Option<Finite>,
    pub participation: Option<Finite>,
}

/// `[block]`: width and height (bare: metres).
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawBlock {
    pub width: Option<Quantity>,
    pub height: Option<Quantity>,
}

/// `[friction]`: μ_s and μ_k, either may be `inf`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawFriction {
    #[serde(rename = "static")]
    pub mu_s: Option<Coefficient>,
    #[serde(rename = "kinetic")]
    pub mu_k: Option<Coefficient>,
}

/// `[impact]`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawImpact {
    pub law: Option<LawKind>,
    pub r: Option<Finite>,
    pub e: Option<Finite>,
    #[serde(rename = "static")]
    pub mu_s: Option<Coefficient>,
    #[serde(rename = "kinetic")]
    pub mu_k: Option<Coefficient>,
}

/// `[excitation]`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawExcitation {
    pub kind: Option<ExcitationKind>,
    pub a_h: Option<Quantity>,
    pub a_v: Option<Quantity>,
    pub omega_h: Option<Quantity>,
    pub omega_v: Option<Quantity>,
    pub phase_h: Option<Quantity>,
    pub phase_v: Option<Quantity>,
    pub shape: Option<ShapeKind>,
    pub cycles: Option<Count>,
    pub file_h: Option<String>,
    pub file_v: Option<String>,
    pub unit_h: Option<String>,
    pub unit_v: Option<String>,
    pub dt_h: Option<Quantity>,
    pub dt_v: Option<Quantity>,
    pub crc32_h: Option<String>,
    pub crc32_v: Option<String>,
    pub channel_h: Option<Count>,
    pub channel_v: Option<Count>,
    pub scale_h: Option<Finite>,
    pub scale_v: Option<Finite>,
    pub pga_h: Option<Quantity>,
    pub pga_v: Option<Quantity>,
}

/// `[initial]`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawInitial {
    pub theta: Option<Quantity>,
    pub theta_dot: Option<Quantity>,
    pub x_dot: Option<Quantity>,
}

/// `[run]`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawRun {
    pub tau_end: Option<Quantity>,
    pub t_end: Option<Quantity>,
    pub tail_s: Option<Quantity>,
    pub method: Option<Method>,
    pub rtol: Option<Finite>,
    pub atol: Option<Finite>,
    pub step: Option<Quantity>,
    pub output_dt: Option<Quantity>,
    pub tumble_theta: Option<Quantity>,
    pub flight: Option<Flight>,
    pub zeno_eps: Option<Finite>,
    pub max_steps: Option<Count>,
    pub max_events: Option<Count>,
}

/// `[analysis]`.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct RawAnalysis {
    pub lyapunov: Option<bool>,
    pub lyapunov_method: Option<LyapunovChoice>,
    pub spectrum: Option<bool>,
    pub spectrum_window: Option<SpectrumRange>,
}

/// `run.flight`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Flight {
    /// End the run.
    Stop,
    /// Count it and go on with the grounded equations.
    Ignore,
}

impl From<Flight> for FlightPolicy {
    fn from(f: Flight) -> Self {
        match f {
            Flight::Stop => FlightPolicy::Stop,
            Flight::Ignore => FlightPolicy::Ignore,
        }
    }
}

/// How an unexpected value is named in an error (`string "abc"`).
struct Found<'a>(de::Unexpected<'a>);

impl fmt::Display for Found<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            de::Unexpected::Str(s) => write!(f, "string \"{s}\""),
            de::Unexpected::Bool(b) => write!(f, "boolean {b}"),
            de::Unexpected::Map => f.write_str("a table"),
            de::Unexpected::Seq => f.write_str("an array"),
            other => write!(f, "{other}"),
        }
    }
}

/// Reads a number: an integer or a float, and with `allow_inf` the strings
/// `inf`, `+inf`, `infinity` (any case). NaN is refused, and so is an
/// infinite value where none is allowed.
struct NumberVisitor {
    allow_inf: bool,
}

impl NumberVisitor {
    fn wrong<E: de::Error>(&self, found: de::Unexpected<'_>) -> E {
        let inf = if self.allow_inf { " or \"inf\"" } else { "" };
        E::custom(format!("expected a number{inf}, found {}", Found(found)))
    }

    fn check<E: de::Error>(&self, x: f64) -> Result<f64, E> {
        if x.is_nan() {
            Err(E::custom("NaN is not allowed"))
        } else if x.is_infinite() && !self.allow_inf {
            Err(E::custom("must be finite"))
        } else {
            Ok(x)
        }
    }
}

impl<'de> Visitor<'de> for NumberVisitor {
    type Value = f64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.allow_inf {
            "a number or \"inf\""
        } else {
            "a number"
        })
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        self.check(v)
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<f64, E> {
        let word = s.trim().to_ascii_lowercase();
        if self.allow_inf && matches!(word.as_str(), "inf" | "infinity" | "+inf") {
            Ok(f64::INFINITY)
        } else {
            Err(self.wrong(de::Unexpected::Str(s)))
        }
    }

    fn visit_bool<E: de::Error>(self, b: bool) -> Result<f64, E> {
        Err(self.wrong(de::Unexpected::Bool(b)))
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(self.wrong(de::Unexpected::Seq))
    }

    fn visit_map<A: de::MapAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(self.wrong(de::Unexpected::Map))
    }
}

/// A finite number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finite(pub f64);

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NumberVisitor { allow_inf: false }).map(Finite)
    }
}

/// A friction coefficient: a number, or `inf` (no sliding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Coefficient(pub f64);

impl<'de> Deserialize<'de> for Coefficient {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NumberVisitor { allow_inf: true }).map(Coefficient)
    }
}

/// A non-negative integer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Count(pub u64);

struct CountVisitor;

impl<'de> Visitor<'de> for CountVisitor {
    type Value = u64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a non-negative integer")
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
        Ok(v)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
        u64::try_from(v).map_err(|_| E::custom(format!("expected a non-negative integer, found integer {v}")))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<u64, E> {
        Err(E::custom(format!("expected a non-negative integer, found number {v}")))
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<u64, E> {
        Err(E::custom(format!(
            "expected a non-negative integer, found {}",
            Found(de::Unexpected::Str(s))
        )))
    }

    fn visit_bool<E: de::Error>(self, b: bool) -> Result<u64, E> {
        Err(E::custom(format!("expected a non-negative integer, found boolean {b}")))
    }
}

impl<'de> Deserialize<'de> for Count {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(CountVisitor).map(Count)
    }
}
