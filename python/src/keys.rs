//! The Python spelling of the config keys: what each key measures, the
//! units it takes, and the units rule of the Python API.
//!
//! The rule: a bare Python number is accepted only where its meaning
//! cannot be mistaken, i.e. where it is in SI units (sizes in m, times in
//! s, phases in rad), dimensionless (friction and impact coefficients,
//! scale factors, tolerances, counts), or given under a name that says it
//! is normalised: `tau_end` (τ = p·t) and the `_norm` spelling of every
//! key whose bare config number is normalised (`a_h_norm=0.35` is
//! A_h = 0.35, i.e. 0.35·ψ·g). Anything else takes a string with its unit
//! (`a_h="0.35 g"`). The config files and the CLI's `--set` keep their own
//! rule (bare numbers normalised); only Python values are checked here.

use rocking::io::config::KNOWN_KEYS;
use rocking::sim::catalogue::{self, Dimension, KeySpec, Value};

/// Suffix of the normalised spelling of a key (`a_h_norm`).
pub const NORM_SUFFIX: &str = "_norm";

/// Keys whose name says their bare number is normalised (τ), so a bare
/// Python number is accepted.
const NAMED_NORMALISED: &[&str] = &["run.tau_end"];

/// What a bare number means for a key, as far as the Python API goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bare {
    /// In SI units, or dimensionless: accepted as it is.
    Plain,
    /// In normalised units that the name does not state: refused; the
    /// `_norm` spelling takes it.
    Normalised,
    /// Not a number (a name, a path, a bool, a checksum).
    NotANumber,
    /// A number needs its unit (a peak ground acceleration).
    NeedsUnit,
}

/// What a bare Python number means for the key `spec`, from what the
/// catalogue says it measures.
fn bare_of(spec: &KeySpec) -> Bare {
    match spec.value {
        Value::Quantity(Dimension::Pga) => Bare::NeedsUnit,
        Value::Quantity(d) if d.normalised().is_some() && !NAMED_NORMALISED.contains(&spec.key) => Bare::Normalised,
        Value::Quantity(_) | Value::Number | Value::Count => Bare::Plain,
        Value::Choice(_) | Value::Path | Value::Checksum | Value::Flag | Value::Tables => Bare::NotANumber,
    }
}

/// One key as the Python API documents it: what a bare number means, and
/// its one line for `help(rocking.Scene)`.
pub struct KeyDoc {
    pub bare: Bare,
    /// Meaning, units and examples, one line.
    pub doc: String,
}

/// The documentation of `section.name`, from its catalogue entry.
pub fn doc_of(section: &str, name: &str) -> Option<KeyDoc> {
    let spec = catalogue::spec(&format!("{section}.{name}"))?;
    let bare = bare_of(spec);
    let mut doc = format!("{}: {}", spec.meaning, spec.written);
    if bare == Bare::Normalised
        && let Some((_, meaning)) = spec.dimension().and_then(Dimension::normalised)
    {
        doc.push_str(&format!("; {name}{NORM_SUFFIX}: {meaning}"));
    }
    Some(KeyDoc { bare, doc })
}

/// Keys the config knows whose catalogue entry lacks the words the Python
/// help needs, as `section.key` (a test asserts there are none).
pub fn undocumented() -> Vec<String> {
    KNOWN_KEYS
        .iter()
        .flat_map(|(s, keys)| keys.iter().map(move |k| (*s, *k)))
        .filter(|(s, k)| {
            catalogue::spec(&format!("{s}.{k}")).is_none_or(|d| d.meaning.is_empty() || d.written.is_empty())
        })
        .map(|(s, k)| format!("{s}.{k}"))
        .collect()
}

/// A key as typed in Python, split into the config key it sets and
/// whether it was the `_norm` spelling: `a_h_norm` → (`a_h`, true). Only a
/// key whose bare number is normalised has a `_norm` spelling.
pub fn strip_norm<'a>(section: Option<&str>, name: &'a str) -> (&'a str, bool) {
    if let Some(base) = name.strip_suffix(NORM_SUFFIX) {
        let normalised = catalogue::CATALOGUE
            .iter()
            .any(|k| k.name() == base && bare_of(k) == Bare::Normalised && section.is_none_or(|s| s == k.section()));
        if normalised {
            return (base, true);
        }
    }
    (name, false)
}

/// The text of `help(rocking.Scene)`'s key list: every key with its units,
/// by section, and the units rule.
pub fn keys_help() -> String {
    let mut out = String::from(
        "Units: a bare number is accepted only where it is in SI units (sizes in m, times in s,\n\
         phases in rad), dimensionless, or given under a name that says it is normalised\n\
         (tau_end, and the _norm spelling of the keys below that have one: a_h_norm=0.35 is\n\
         A_h = 0.35, i.e. 0.35*psi*g). Anything else takes a string with its unit: a_h=\"0.35 g\".\n\
         Keys are given as keywords (a key unique to one section, or a section with a dict)\n\
         or in config= as \"section.key\".\n",
    );
    for (section, keys) in KNOWN_KEYS.iter() {
        out.push_str(&format!("\n[{section}]\n"));
        for key in keys {
            let doc = doc_of(section, key).map_or_else(|| "(no unit documented)".to_string(), |d| d.doc);
            out.push_str(&format!("    {key}: {doc}\n"));
        }
    }
    out
}

/// For a key whose bare config number is normalised: a unit to show in
/// the example of an error, and what the normalised number is.
pub fn normalised_meaning(section: &str, name: &str) -> Option<(&'static str, &'static str)> {
    catalogue::spec(&format!("{section}.{name}"))?.dimension()?.normalised()
}
