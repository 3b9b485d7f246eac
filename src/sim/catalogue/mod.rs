//! The parameter catalogue: every config key declared once, with its
//! section, what it measures, how a value is written, its range and its
//! default, and where the app shows it.
//!
//! Every surface reads this declaration: the config parser's list of known
//! keys and its unit conversions (`io::config`), the validation messages of
//! simple ranges ([`Range`], used by `Scenario::validate`), the typed
//! [`Param`]s of sweeps and maps ([`Param::key`]), the app's parameter panel
//! (labels, units, tooltips, sliders, which keys apply to which excitation),
//! the Python package's keywords and `help(rocking.Scene)`, and the README's
//! key table (a test compares it with [`markdown_table`]).
//!
//! A new key is one entry in [`keys::CATALOGUE`], plus its field in the
//! serde shape (`io::config::raw`) and in [`Scenario`](super::Scenario);
//! a test fails until the three agree.

mod dimension;
mod keys;
mod param;

pub use dimension::Dimension;
pub use keys::CATALOGUE;
pub use param::Param;

use super::scenario::ExcitationKind;

/// What a key's value is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A number that may carry a unit ("0.35 g"); a bare one means what
    /// the dimension says.
    Quantity(Dimension),
    /// A dimensionless number (a coefficient, a factor, a tolerance);
    /// `inf` where [`KeySpec::infinite`] says so.
    Number,
    /// A whole number.
    Count,
    /// One of a few words.
    Choice(&'static [&'static str]),
    /// A file path.
    Path,
    /// An 8-digit hexadecimal checksum.
    Checksum,
    /// `true` or `false`.
    Flag,
    /// A list of tables (`[[floor.mode]]`).
    Tables,
}

/// A simple range of a numeric key, checked by `Scenario::validate` with
/// the message "`key`: `value` is out of range: must be `allowed`".
#[derive(Clone, Copy, Debug)]
pub struct Range {
    /// Whether a (resolved) value is allowed.
    pub ok: fn(f64) -> bool,
    /// What is allowed, with the reason where the bound is not obvious.
    pub allowed: &'static str,
}

/// The excitation kinds a key means something for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Applies {
    /// Every kind.
    Always,
    /// Only these.
    To(&'static [ExcitationKind]),
}

impl Applies {
    /// Whether a key that applies so means anything for `kind`.
    pub fn to(self, kind: ExcitationKind) -> bool {
        match self {
            Applies::Always => true,
            Applies::To(kinds) => kinds.contains(&kind),
        }
    }
}

/// The groups of the app's parameter panel, in the order it shows them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// The block's size.
    Block,
    /// A rocking frame's columns and beam.
    Frame,
    /// Sliding.
    Friction,
    /// The impact law.
    Impact,
    /// The base motion.
    Excitation,
    /// The building floor under the block.
    Floor,
    /// Where the run starts.
    Initial,
    /// The integrator and the run's length.
    Solver,
}

impl Group {
    /// Every group, in the panel's order.
    pub const ALL: [Group; 8] = [
        Group::Block,
        Group::Frame,
        Group::Friction,
        Group::Impact,
        Group::Excitation,
        Group::Floor,
        Group::Initial,
        Group::Solver,
    ];

    /// The group's heading in the panel.
    pub fn title(self) -> &'static str {
        match self {
            Group::Block => "Block",
            Group::Frame => "Frame",
            Group::Friction => "Friction",
            Group::Impact => "Impact",
            Group::Excitation => "Excitation",
            Group::Floor => "Floor",
            Group::Initial => "Initial state",
            Group::Solver => "Solver",
        }
    }
}

/// Where the panel shows a key: its group and its place in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Slot {
    /// The group.
    pub group: Group,
    /// Its place in the group (ascending).
    pub order: u8,
}

/// A slider's span: from `min` to `max` in the key's bare unit, on a
/// logarithmic scale if `log`, moved by `step` a point of drag (for a
/// logarithmic slider a fraction of the value: 0.05 is 5 %).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    /// Left end.
    pub min: f64,
    /// Right end.
    pub max: f64,
    /// What one point of a plain drag adds.
    pub step: f64,
    /// Logarithmic (sizes and frequencies).
    pub log: bool,
}

/// One config key.
#[derive(Clone, Copy, Debug)]
pub struct KeySpec {
    /// `section.name`, as config files (as a table), messages, tables and
    /// `--set` write it: `excitation.a_v`.
    pub key: &'static str,
    /// What its value is.
    pub value: Value,
    /// Whether `inf` is allowed (friction: no sliding).
    pub infinite: bool,
    /// What the app labels it (`A_v`).
    pub symbol: &'static str,
    /// The unit of its bare number, as the app shows it (`ψg`; empty for
    /// none).
    pub unit: &'static str,
    /// What it is, in plain ASCII words (`vertical amplitude`).
    pub meaning: &'static str,
    /// How a value is written, with its units and examples (ASCII).
    pub written: &'static str,
    /// One line: meaning, range and default (the app's tooltip).
    pub doc: &'static str,
    /// The sweepable parameter it is, if numeric and continuous.
    pub param: Option<Param>,
    /// Its simple range, where `Scenario::validate` checks one.
    pub range: Option<Range>,
    /// The excitation kinds it means something for.
    pub applies: Applies,
    /// Where the app's panel shows it (`None`: config files only).
    pub slot: Option<Slot>,
    /// The app's slider over it (`None`: typed only).
    pub slider: Option<Span>,
}

impl KeySpec {
    /// The blank entry the table's entries fill in.
    pub(crate) const BLANK: KeySpec = KeySpec {
        key: "",
        value: Value::Number,
        infinite: false,
        symbol: "",
        unit: "",
        meaning: "",
        written: "",
        doc: "",
        param: None,
        range: None,
        applies: Applies::Always,
        slot: None,
        slider: None,
    };

    /// The section: `excitation` of `excitation.a_v`.
    pub fn section(&self) -> &'static str {
        self.key.split_once('.').map_or(self.key, |(s, _)| s)
    }

    /// The key within its section: `a_v` of `excitation.a_v`.
    pub fn name(&self) -> &'static str {
        self.key.split_once('.').map_or(self.key, |(_, n)| n)
    }

    /// The dimension of a quantity key.
    pub fn dimension(&self) -> Option<Dimension> {
        match self.value {
            Value::Quantity(d) => Some(d),
            _ => None,
        }
    }
}

/// The entry of `key` (`section.name`).
pub fn spec(key: &str) -> Option<&'static KeySpec> {
    CATALOGUE.iter().find(|k| k.key == key)
}

/// The entry of parameter `p`.
pub(crate) fn spec_of(p: Param) -> &'static KeySpec {
    CATALOGUE
        .iter()
        .find(|k| k.param == Some(p))
        .expect("every Param has a catalogue entry (tested)")
}

/// The sections, in the config file's order.
pub fn sections() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for k in CATALOGUE {
        if !out.contains(&k.section()) {
            out.push(k.section());
        }
    }
    out
}

/// The keys of `section`, in the config file's order.
pub(crate) fn keys_of(section: &str) -> Vec<&'static str> {
    CATALOGUE
        .iter()
        .filter(|k| k.section() == section)
        .map(|k| k.name())
        .collect()
}

/// The keys the panel shows in `group`, in its order.
pub fn panel_keys(group: Group) -> Vec<&'static KeySpec> {
    let mut keys: Vec<&'static KeySpec> = CATALOGUE
        .iter()
        .filter(|k| k.slot.is_some_and(|s| s.group == group))
        .collect();
    keys.sort_by_key(|k| k.slot.map(|s| s.order));
    keys
}

/// The README's table of keys, one row a key: the key, its units (what a
/// bare number means) or how it is written, and its doc line.
pub fn markdown_table() -> String {
    let mut out = String::from("| key | value | meaning, range, default |\n|---|---|---|\n");
    for k in CATALOGUE {
        // A quantity's units and what its bare number means (the config's
        // rule); any other value as it is written.
        let value = k.dimension().map_or(k.written, Dimension::fits);
        out.push_str(&format!(
            "| `{}` | {} | {} |\n",
            k.key,
            value.replace('|', "\\|"),
            k.doc.replace('|', "\\|")
        ));
    }
    out
}

#[cfg(test)]
mod tests;
