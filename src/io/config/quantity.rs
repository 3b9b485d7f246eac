//! Quantities with units in a config: `"0.35 g"`, `"2.5 Hz"`, `"30 s"`,
//! `"2 deg"`, `"60 cm"`, and the bare numbers that keep their normalised
//! meaning.
//!
//! A value is read as a [`Quantity`] (a number and, when given as a string,
//! its unit) without knowing its key; [`Quantity::resolve`] then converts it
//! for one key's [`Dimension`], with the block's ψ, p and R, into the unit
//! the scenario stores. A unit that does not fit the key is an error naming
//! the key and the units that fit.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};

use super::ConfigError;
use crate::model::Geometry;
use crate::model::units::AccelUnit;

/// A unit a config value may carry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unit {
    /// An acceleration unit.
    Accel(AccelUnit),
    /// g·tan α: multiples of the static uplift acceleration (α = ψ).
    Uplift,
    /// Metres.
    Metre,
    /// Centimetres.
    Centimetre,
    /// Millimetres.
    Millimetre,
    /// Hertz (cycles per second).
    Hertz,
    /// Radians per second.
    RadianPerSecond,
    /// Degrees per second.
    DegreePerSecond,
    /// Radians.
    Radian,
    /// Degrees.
    Degree,
    /// Seconds.
    Second,
    /// Milliseconds.
    Millisecond,
    /// Metres per second.
    MetrePerSecond,
    /// Centimetres per second.
    CentimetrePerSecond,
}

/// Every spelling of a non-acceleration unit, exactly as it must be
/// written: SI symbols are case-sensitive (`ms` is a millisecond, `Ms`
/// would be a megasecond; `mm` a millimetre, `Mm` a megametre), so no other
/// case is read. Spaces inside are ignored (`g * tan(alpha)`).
const SPELLINGS: &[(&str, Unit)] = &[
    ("g*tan(alpha)", Unit::Uplift),
    ("g*tan(α)", Unit::Uplift),
    ("g·tan(alpha)", Unit::Uplift),
    ("g·tanα", Unit::Uplift),
    ("g*tanα", Unit::Uplift),
    ("m", Unit::Metre),
    ("cm", Unit::Centimetre),
    ("mm", Unit::Millimetre),
    ("Hz", Unit::Hertz),
    ("rad/s", Unit::RadianPerSecond),
    ("rad/sec", Unit::RadianPerSecond),
    ("deg/s", Unit::DegreePerSecond),
    ("°/s", Unit::DegreePerSecond),
    ("deg/sec", Unit::DegreePerSecond),
    ("rad", Unit::Radian),
    ("radian", Unit::Radian),
    ("radians", Unit::Radian),
    ("deg", Unit::Degree),
    ("°", Unit::Degree),
    ("degree", Unit::Degree),
    ("degrees", Unit::Degree),
    ("s", Unit::Second),
    ("sec", Unit::Second),
    ("second", Unit::Second),
    ("seconds", Unit::Second),
    ("ms", Unit::Millisecond),
    ("m/s", Unit::MetrePerSecond),
    ("cm/s", Unit::CentimetrePerSecond),
];

impl Unit {
    /// Reads a unit as written after the number, case-sensitive (see
    /// [`SPELLINGS`] and [`AccelUnit::parse`]).
    fn parse(text: &str) -> Option<Unit> {
        if let Some(a) = AccelUnit::parse(text) {
            return Some(Unit::Accel(a));
        }
        let t = text.trim().replace(' ', "");
        SPELLINGS
            .iter()
            .find(|(spelling, _)| *spelling == t)
            .map(|&(_, unit)| unit)
    }

    /// The unit `text` would be in another case (`Ms` → `ms`, `HZ` → `Hz`),
    /// for the message refusing it.
    fn case_hint(text: &str) -> Option<&'static str> {
        if let Some(name) = AccelUnit::case_hint(text) {
            return Some(name);
        }
        let t = text.trim().replace(' ', "");
        SPELLINGS
            .iter()
            .map(|&(spelling, unit)| (spelling, unit.name()))
            .find(|(spelling, _)| spelling.to_lowercase() == t.to_lowercase())
            .map(|(_, name)| name)
    }

    /// How the unit is written in messages.
    fn name(self) -> &'static str {
        match self {
            Unit::Accel(a) => a.name(),
            Unit::Uplift => "g*tan(alpha)",
            Unit::Metre => "m",
            Unit::Centimetre => "cm",
            Unit::Millimetre => "mm",
            Unit::Hertz => "Hz",
            Unit::RadianPerSecond => "rad/s",
            Unit::DegreePerSecond => "deg/s",
            Unit::Radian => "rad",
            Unit::Degree => "deg",
            Unit::Second => "s",
            Unit::Millisecond => "ms",
            Unit::MetrePerSecond => "m/s",
            Unit::CentimetrePerSecond => "cm/s",
        }
    }
}

/// A config value: a number, with the unit it was given in (`None`: a bare
/// number, in the key's own unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantity {
    /// The number as written.
    pub value: f64,
    /// Its unit, if one was written.
    pub unit: Option<Unit>,
}

pub use crate::sim::catalogue::Dimension;

impl Quantity {
    /// The value in the unit the scenario stores for a key of dimension
    /// `dim` (see [`Dimension`]), for block `geo`; a unit that does not fit
    /// is an error naming `key`.
    pub fn resolve(self, key: &str, dim: Dimension, geo: &Geometry) -> Result<f64, ConfigError> {
        let v = self.value;
        let deg = std::f64::consts::PI / 180.0;
        let Some(unit) = self.unit else {
            return if dim == Dimension::Pga {
                Err(ConfigError::key(key, format!("needs a unit: {}", dim.fits())))
            } else {
                Ok(v)
            };
        };
        // The unit to the dimension's physical unit (m, g, rad/s, rad,
        // m/s, s), then the one conversion to the model's number.
        let physical = match (dim, unit) {
            (Dimension::Length, Unit::Metre) => Some(v),
            (Dimension::Length, Unit::Centimetre) => Some(v * 0.01),
            (Dimension::Length, Unit::Millimetre) => Some(v * 0.001),
            (Dimension::Amplitude | Dimension::Pga, Unit::Accel(a)) => Some(a.to_g(v)),
            (Dimension::Amplitude | Dimension::Pga, Unit::Uplift) => Some(v * geo.tan_psi),
            (Dimension::Frequency, Unit::Hertz) => Some(std::f64::consts::TAU * v),
            (Dimension::Frequency | Dimension::AngularVelocity, Unit::RadianPerSecond) => Some(v),
            (Dimension::Phase | Dimension::Rotation, Unit::Radian) => Some(v),
            (Dimension::Phase | Dimension::Rotation, Unit::Degree) => Some(v * deg),
            (Dimension::AngularVelocity, Unit::DegreePerSecond) => Some(v * deg),
            (Dimension::Velocity, Unit::MetrePerSecond) => Some(v),
            (Dimension::Velocity, Unit::CentimetrePerSecond) => Some(v * 0.01),
            (Dimension::Tau | Dimension::Seconds, Unit::Second) => Some(v),
            (Dimension::Tau | Dimension::Seconds, Unit::Millisecond) => Some(v * 1e-3),
            _ => None,
        };
        let converted = physical.map(|x| dim.to_bare(x, geo));
        let Some(x) = converted else {
            return Err(ConfigError::key(
                key,
                format!("unit \"{}\" does not fit: {}", unit.name(), dim.fits()),
            ));
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(ConfigError::key(key, format!("{} {} is out of range", v, unit.name())))
        }
    }
}

/// Reads a quantity from a string: a number, optional spaces, a unit.
fn parse_quantity(text: &str) -> Result<Quantity, String> {
    let t = text.trim();
    // The number is the longest prefix that parses; what follows is the
    // unit. Numbers end before the first character that cannot be in one.
    let end = t
        .char_indices()
        .find(|&(_, c)| !(c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'e' | 'E')))
        .map_or(t.len(), |(i, _)| i);
    // "e" may start a unit only if it does not continue a number; no unit
    // here starts with e, so a trailing e belongs to nothing: back off.
    let mut split = end;
    let mut number = None;
    while split > 0 {
        if let Some(head) = t.get(..split)
            && let Ok(v) = head.parse::<f64>()
        {
            number = Some(v);
            break;
        }
        split -= 1;
    }
    let Some(value) = number else {
        return Err(format!(
            "expected a number or a quantity with a unit (e.g. \"0.35 g\", \"2.5 Hz\"), found string \"{text}\""
        ));
    };
    if !value.is_finite() {
        return Err(format!("{text:?} is not a finite number"));
    }
    let unit_text = t.get(split..).unwrap_or("").trim();
    if unit_text.is_empty() {
        return Ok(Quantity { value, unit: None });
    }
    const KNOWN: &str = "g, m/s2, cm/s2, gal, g*tan(alpha), m, cm, mm, Hz, rad/s, deg/s, rad, deg, s, ms, m/s, cm/s";
    match (Unit::parse(unit_text), Unit::case_hint(unit_text)) {
        (Some(unit), _) => Ok(Quantity {
            value,
            unit: Some(unit),
        }),
        (None, Some(hint)) => Err(format!(
            "unknown unit \"{unit_text}\" in \"{text}\": units are case-sensitive, did you mean \"{hint}\"? (known: {KNOWN})"
        )),
        (None, None) => Err(format!("unknown unit \"{unit_text}\" in \"{text}\" (known: {KNOWN})")),
    }
}

struct QuantityVisitor;

impl<'de> Visitor<'de> for QuantityVisitor {
    type Value = Quantity;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or a quantity with a unit")
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Quantity, E> {
        Ok(Quantity {
            value: v as f64,
            unit: None,
        })
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Quantity, E> {
        Ok(Quantity {
            value: v as f64,
            unit: None,
        })
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Quantity, E> {
        if v.is_nan() {
            Err(E::custom("NaN is not allowed"))
        } else if v.is_infinite() {
            Err(E::custom("must be finite"))
        } else {
            Ok(Quantity { value: v, unit: None })
        }
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<Quantity, E> {
        parse_quantity(s).map_err(E::custom)
    }

    fn visit_bool<E: de::Error>(self, b: bool) -> Result<Quantity, E> {
        Err(E::custom(format!(
            "expected a number or a quantity with a unit, found boolean {b}"
        )))
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, _: A) -> Result<Quantity, A::Error> {
        Err(de::Error::custom(
            "expected a number or a quantity with a unit, found an array",
        ))
    }

    fn visit_map<A: de::MapAccess<'de>>(self, _: A) -> Result<Quantity, A::Error> {
        Err(de::Error::custom(
            "expected a number or a quantity with a unit, found a table",
        ))
    }
}

impl<'de> Deserialize<'de> for Quantity {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(QuantityVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(text: &str) -> Quantity {
        parse_quantity(text).unwrap()
    }

    #[test]
    fn numbers_and_units_are_split_with_or_without_a_space() {
        assert_eq!(
            q("0.35 g"),
            Quantity {
                value: 0.35,
                unit: Some(Unit::Accel(AccelUnit::G))
            }
        );
        assert_eq!(q("0.35g").unit, Some(Unit::Accel(AccelUnit::G)));
        assert_eq!(
            q("1e-3 s"),
            Quantity {
                value: 1e-3,
                unit: Some(Unit::Second)
            }
        );
        assert_eq!(q("-2 deg").value, -2.0);
        assert_eq!(q(" 340 gal ").unit, Some(Unit::Accel(AccelUnit::CentimetresPerSecond2)));
        assert_eq!(q("1.2 g*tan(alpha)").unit, Some(Unit::Uplift));
        assert_eq!(q("2.5 Hz").unit, Some(Unit::Hertz));
        assert_eq!(q("7"), Quantity { value: 7.0, unit: None });
        assert!(parse_quantity("abc").unwrap_err().contains("found string \"abc\""));
        assert!(
            parse_quantity("2 furlongs")
                .unwrap_err()
                .contains("unknown unit \"furlongs\"")
        );
        assert!(parse_quantity("1e999 g").is_err());
    }

    #[test]
    fn units_are_case_sensitive_and_a_wrong_case_is_named_with_the_right_one() {
        for (text, right) in [
            ("10 Ms", "ms"),
            ("1000 Mm", "mm"),
            ("2 HZ", "Hz"),
            ("2 hz", "Hz"),
            ("0.3 G", "g"),
            ("3 M/S2", "m/s2"),
            ("4 S", "s"),
            ("5 DEG", "deg"),
            ("1 Rad/s", "rad/s"),
            ("60 CM", "cm"),
        ] {
            let e = parse_quantity(text).unwrap_err();
            assert!(
                e.contains("case-sensitive") && e.contains(&format!("did you mean \"{right}\"")),
                "{text}: {e}"
            );
            assert!(e.contains("known: g, m/s2"), "{text}: {e}");
        }
        assert_eq!(q("10 ms").unit, Some(Unit::Millisecond));
        assert_eq!(q("1000 mm").unit, Some(Unit::Millimetre));
        assert_eq!(q("340 Gal").unit, Some(Unit::Accel(AccelUnit::CentimetresPerSecond2)));
        assert_eq!(q("1 g * tan(alpha)").unit, Some(Unit::Uplift));
    }

    #[test]
    fn each_dimension_converts_its_units_and_refuses_the_others() {
        let geo = Geometry::new(0.6, 2.0);
        let r = |text: &str, dim| q(text).resolve("k.k", dim, &geo);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs().max(1.0);
        assert!(close(r("60 cm", Dimension::Length).unwrap(), 0.6));
        assert!(close(r("600 mm", Dimension::Length).unwrap(), 0.6));
        assert!(close(r("0.35 g", Dimension::Amplitude).unwrap(), 0.35 / geo.psi));
        assert!(close(r("3.4335 m/s2", Dimension::Amplitude).unwrap(), 0.35 / geo.psi));
        assert!(close(r("343.35 cm/s2", Dimension::Amplitude).unwrap(), 0.35 / geo.psi));
        assert!(close(
            r("1 g*tan(alpha)", Dimension::Amplitude).unwrap(),
            geo.tan_psi / geo.psi
        ));
        assert!(close(
            r("2.5 Hz", Dimension::Frequency).unwrap(),
            5.0 * std::f64::consts::PI / geo.p
        ));
        assert!(close(r("15.7 rad/s", Dimension::Frequency).unwrap(), 15.7 / geo.p));
        assert!(close(r("30 s", Dimension::Tau).unwrap(), 30.0 * geo.p));
        assert!(close(
            r("2 deg", Dimension::Rotation).unwrap(),
            2.0_f64.to_radians() / geo.psi
        ));
        assert!(close(r("0.03 rad", Dimension::Rotation).unwrap(), 0.03 / geo.psi));
        assert!(close(
            r("90 deg", Dimension::Phase).unwrap(),
            std::f64::consts::FRAC_PI_2
        ));
        assert!(close(r("0.1 m/s", Dimension::Velocity).unwrap(), 0.1 / (geo.r * geo.p)));
        assert!(close(r("0.4 g", Dimension::Pga).unwrap(), 0.4));
        assert_eq!(r("1.5", Dimension::Amplitude).unwrap(), 1.5);
        let m = r("2 m", Dimension::Frequency).unwrap_err().to_string();
        assert_eq!(
            m,
            "k.k: unit \"m\" does not fit: a frequency: Hz, rad/s (bare: units of p)"
        );
        assert!(r("0.3 g", Dimension::Length).is_err());
        assert!(r("2 Hz", Dimension::Tau).is_err());
        assert!(
            r("0.4", Dimension::Pga)
                .unwrap_err()
                .to_string()
                .contains("needs a unit")
        );
    }
}
