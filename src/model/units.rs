//! Physical units of ground acceleration, and the one value of g.
//!
//! The model works in g (accelerations per unit g, [`G`] = 9.81 m/s²). A
//! record arrives in whatever unit its source used; [`AccelUnit`] names the
//! three in common use and converts them to g exactly once, when the record
//! is read, so nothing downstream ever sees another unit.

use super::geometry::G;

/// A unit of acceleration a record or an input may be given in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AccelUnit {
    /// Multiples of g = [`G`] m/s² (PEER NGA files, El Centro as
    /// commonly distributed).
    G,
    /// m/s² (Kobe 1995 as commonly distributed).
    MetresPerSecond2,
    /// cm/s², also called gal.
    CentimetresPerSecond2,
}

impl AccelUnit {
    /// Every unit, in the order the docs list them.
    pub const ALL: [AccelUnit; 3] = [
        AccelUnit::G,
        AccelUnit::MetresPerSecond2,
        AccelUnit::CentimetresPerSecond2,
    ];

    /// The unit's name in configs and outputs: `g`, `m/s2`, `cm/s2`.
    pub fn name(self) -> &'static str {
        match self {
            AccelUnit::G => "g",
            AccelUnit::MetresPerSecond2 => "m/s2",
            AccelUnit::CentimetresPerSecond2 => "cm/s2",
        }
    }

    /// Reads a unit name, case-sensitive as SI symbols are (`g` is the
    /// unit, `G` the gravitational constant; `Ms` would be megaseconds):
    /// `g`; `m/s2` (or `m/s^2`, `m/s/s`, `m/s²`, `m/sec2`, ...); `cm/s2`
    /// (the same spellings, or `Gal`, the SI-accepted symbol, or `gal`,
    /// engineers' usual spelling, which names no other unit). No spaces
    /// inside. Formats that define upper-case names (AT2 headers' `G`,
    /// `CM/S/S`) read them with [`AccelUnit::parse_upper_case`].
    pub fn parse(text: &str) -> Option<AccelUnit> {
        let t = text.trim().replace('²', "2");
        match t.as_str() {
            "g" => Some(AccelUnit::G),
            "m/s2" | "m/s^2" | "m/s/s" | "m/sec2" | "m/sec/sec" | "m/sec^2" => Some(AccelUnit::MetresPerSecond2),
            "cm/s2" | "cm/s^2" | "cm/s/s" | "cm/sec2" | "cm/sec/sec" | "cm/sec^2" | "Gal" | "gal" => {
                Some(AccelUnit::CentimetresPerSecond2)
            }
            _ => None,
        }
    }

    /// Reads a unit name as a format that writes names in upper case
    /// defines them (PEER AT2 headers: `UNITS OF G`, `CM/S/S`, `CM/SEC/SEC`):
    /// any case, otherwise as [`AccelUnit::parse`]. Not for what users type.
    pub(crate) fn parse_upper_case(text: &str) -> Option<AccelUnit> {
        let lower = text.to_ascii_lowercase();
        AccelUnit::parse(&lower)
    }

    /// The accepted spelling `text` differs from only in case (`G` → `g`),
    /// for a message that says units are case-sensitive.
    pub(crate) fn case_hint(text: &str) -> Option<&'static str> {
        let t = text.trim().replace('²', "2");
        ["g", "m/s2", "cm/s2"]
            .into_iter()
            .find(|name| name.eq_ignore_ascii_case(&t) && *name != t)
    }

    /// How many g one of this unit is: multiply a value in this unit by it
    /// to get g.
    pub fn in_g(self) -> f64 {
        match self {
            AccelUnit::G => 1.0,
            AccelUnit::MetresPerSecond2 => 1.0 / G,
            AccelUnit::CentimetresPerSecond2 => 0.01 / G,
        }
    }

    /// `value` (in this unit) in g. Division by the unit's size in m/s²
    /// rather than multiplication by [`AccelUnit::in_g`], so that a value
    /// given as exactly 9.81 m/s² is exactly 1 g.
    pub fn to_g(self, value: f64) -> f64 {
        match self {
            AccelUnit::G => value,
            AccelUnit::MetresPerSecond2 => value / G,
            AccelUnit::CentimetresPerSecond2 => value / (100.0 * G),
        }
    }
}

impl std::fmt::Display for AccelUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_unit_parses_from_its_name_and_converts_to_g() {
        for unit in AccelUnit::ALL {
            assert_eq!(AccelUnit::parse(unit.name()), Some(unit));
        }
        assert_eq!(AccelUnit::MetresPerSecond2.to_g(9.81), 1.0);
        assert_eq!(AccelUnit::CentimetresPerSecond2.to_g(981.0), 1.0);
        assert_eq!(AccelUnit::parse("gal"), Some(AccelUnit::CentimetresPerSecond2));
        assert_eq!(AccelUnit::parse("Gal"), Some(AccelUnit::CentimetresPerSecond2));
        assert_eq!(AccelUnit::parse("m/s²"), Some(AccelUnit::MetresPerSecond2));
        assert_eq!(AccelUnit::parse("ft/s2"), None);
        assert_eq!(AccelUnit::parse(""), None);
    }

    #[test]
    fn unit_names_are_case_sensitive_except_where_a_format_defines_upper_case() {
        for text in ["G", "GAL", "M/S2", "Cm/s2", "M/s/s"] {
            assert_eq!(AccelUnit::parse(text), None, "{text}");
        }
        assert_eq!(AccelUnit::case_hint("G"), Some("g"));
        assert_eq!(AccelUnit::case_hint("M/S2"), Some("m/s2"));
        assert_eq!(AccelUnit::case_hint("g"), None);
        assert_eq!(AccelUnit::parse_upper_case("G"), Some(AccelUnit::G));
        assert_eq!(
            AccelUnit::parse_upper_case("CM/SEC/SEC"),
            Some(AccelUnit::CentimetresPerSecond2)
        );
        assert_eq!(AccelUnit::parse_upper_case("M/S/S"), Some(AccelUnit::MetresPerSecond2));
    }
}
