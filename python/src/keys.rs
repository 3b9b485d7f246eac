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

/// Suffix of the normalised spelling of a key (`a_h_norm`).
pub const NORM_SUFFIX: &str = "_norm";

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

/// One key: its section and name, what a bare number means, and its unit
/// for `help(rocking.Scene)`.
pub struct KeyDoc {
    pub section: &'static str,
    pub name: &'static str,
    pub bare: Bare,
    /// Units and meaning, one line.
    pub doc: &'static str,
}

/// Every config key with its unit. [`undocumented`] lists the keys of
/// [`KNOWN_KEYS`] missing here (a test asserts there are none).
pub const KEY_DOCS: &[KeyDoc] = &[
    KeyDoc {
        section: "block",
        name: "width",
        bare: Bare::Plain,
        doc: "block width B: m, or \"60 cm\", \"600 mm\"",
    },
    KeyDoc {
        section: "block",
        name: "height",
        bare: Bare::Plain,
        doc: "block height H: m, or \"1.8 m\", \"180 cm\"",
    },
    KeyDoc {
        section: "friction",
        name: "static",
        bare: Bare::Plain,
        doc: "static friction coefficient mu_s (dimensionless, or \"inf\": no sliding)",
    },
    KeyDoc {
        section: "friction",
        name: "kinetic",
        bare: Bare::Plain,
        doc: "kinetic friction coefficient mu_k <= mu_s (dimensionless, or \"inf\")",
    },
    KeyDoc {
        section: "impact",
        name: "law",
        bare: Bare::NotANumber,
        doc: "impact law: \"housner\", \"corner-momentum\", \"ratio\" or \"impulse\"",
    },
    KeyDoc {
        section: "impact",
        name: "r",
        bare: Bare::Plain,
        doc: "angular-velocity ratio of the ratio law, in [0, 1] (dimensionless)",
    },
    KeyDoc {
        section: "impact",
        name: "e",
        bare: Bare::Plain,
        doc: "vertical restitution of the impulse law, in [0, 1] (dimensionless)",
    },
    KeyDoc {
        section: "impact",
        name: "static",
        bare: Bare::Plain,
        doc: "static friction during impact (dimensionless, or \"inf\")",
    },
    KeyDoc {
        section: "impact",
        name: "kinetic",
        bare: Bare::Plain,
        doc: "kinetic friction during impact (dimensionless, or \"inf\")",
    },
    KeyDoc {
        section: "excitation",
        name: "kind",
        bare: Bare::NotANumber,
        doc: "\"harmonic\", \"pulse\", \"record\" or \"none\"",
    },
    KeyDoc {
        section: "excitation",
        name: "a_h",
        bare: Bare::Normalised,
        doc: "horizontal amplitude: \"0.35 g\", \"3 m/s2\", \"300 cm/s2\", \"1.2 g*tan(alpha)\"; a_h_norm: units of psi*g",
    },
    KeyDoc {
        section: "excitation",
        name: "a_v",
        bare: Bare::Normalised,
        doc: "vertical amplitude: as a_h; a_v_norm: units of psi*g",
    },
    KeyDoc {
        section: "excitation",
        name: "omega_h",
        bare: Bare::Normalised,
        doc: "horizontal forcing frequency: \"2 Hz\", \"12 rad/s\"; omega_h_norm: units of p",
    },
    KeyDoc {
        section: "excitation",
        name: "omega_v",
        bare: Bare::Normalised,
        doc: "vertical forcing frequency: as omega_h; omega_v_norm: units of p",
    },
    KeyDoc {
        section: "excitation",
        name: "phase_h",
        bare: Bare::Plain,
        doc: "horizontal phase: rad, or \"90 deg\"",
    },
    KeyDoc {
        section: "excitation",
        name: "phase_v",
        bare: Bare::Plain,
        doc: "vertical phase: rad, or \"90 deg\"",
    },
    KeyDoc {
        section: "excitation",
        name: "shape",
        bare: Bare::NotANumber,
        doc: "pulse shape: \"one-sine\", \"one-cosine\", \"type-c\", \"rectangular\", \"half-sine\"",
    },
    KeyDoc {
        section: "excitation",
        name: "cycles",
        bare: Bare::Plain,
        doc: "cycles n of a type-C_n pulse (an integer)",
    },
    KeyDoc {
        section: "excitation",
        name: "file_h",
        bare: Bare::NotANumber,
        doc: "horizontal record file (a path); or record_h= for samples in memory",
    },
    KeyDoc {
        section: "excitation",
        name: "file_v",
        bare: Bare::NotANumber,
        doc: "vertical record file (a path); or record_v= for samples in memory",
    },
    KeyDoc {
        section: "excitation",
        name: "unit_h",
        bare: Bare::NotANumber,
        doc: "unit of the horizontal record file: \"g\", \"m/s2\", \"cm/s2\"",
    },
    KeyDoc {
        section: "excitation",
        name: "unit_v",
        bare: Bare::NotANumber,
        doc: "unit of the vertical record file: \"g\", \"m/s2\", \"cm/s2\"",
    },
    KeyDoc {
        section: "excitation",
        name: "dt_h",
        bare: Bare::Plain,
        doc: "time step of a one-column horizontal record file: s, or \"10 ms\"",
    },
    KeyDoc {
        section: "excitation",
        name: "dt_v",
        bare: Bare::Plain,
        doc: "time step of a one-column vertical record file: s, or \"10 ms\"",
    },
    KeyDoc {
        section: "excitation",
        name: "crc32_h",
        bare: Bare::NotANumber,
        doc: "expected CRC-32 of the horizontal record file (8 hex digits)",
    },
    KeyDoc {
        section: "excitation",
        name: "crc32_v",
        bare: Bare::NotANumber,
        doc: "expected CRC-32 of the vertical record file (8 hex digits)",
    },
    KeyDoc {
        section: "excitation",
        name: "channel_h",
        bare: Bare::Plain,
        doc: "channel of the horizontal record file, from 1, where a COSMOS file holds several (an integer)",
    },
    KeyDoc {
        section: "excitation",
        name: "channel_v",
        bare: Bare::Plain,
        doc: "channel of the vertical record file, from 1, where a COSMOS file holds several (an integer)",
    },
    KeyDoc {
        section: "excitation",
        name: "scale_h",
        bare: Bare::Plain,
        doc: "factor on the horizontal record (dimensionless)",
    },
    KeyDoc {
        section: "excitation",
        name: "scale_v",
        bare: Bare::Plain,
        doc: "factor on the vertical record (dimensionless)",
    },
    KeyDoc {
        section: "excitation",
        name: "pga_h",
        bare: Bare::NeedsUnit,
        doc: "scale the horizontal record to this PGA: \"0.4 g\", \"4 m/s2\" (a unit is required)",
    },
    KeyDoc {
        section: "excitation",
        name: "pga_v",
        bare: Bare::NeedsUnit,
        doc: "scale the vertical record to this PGA: \"0.4 g\" (a unit is required)",
    },
    KeyDoc {
        section: "initial",
        name: "theta",
        bare: Bare::Normalised,
        doc: "initial rotation: \"0.01 rad\", \"0.5 deg\"; theta_norm: theta/psi",
    },
    KeyDoc {
        section: "initial",
        name: "theta_dot",
        bare: Bare::Normalised,
        doc: "initial angular velocity: \"0.1 rad/s\", \"5 deg/s\"; theta_dot_norm: units of psi*p",
    },
    KeyDoc {
        section: "initial",
        name: "x_dot",
        bare: Bare::Normalised,
        doc: "initial velocity of the centre of mass: \"0.1 m/s\", \"10 cm/s\"; x_dot_norm: units of R*p",
    },
    KeyDoc {
        section: "run",
        name: "tau_end",
        bare: Bare::Plain,
        doc: "end of the run in tau = p*t (bare: tau, the name says so), or \"20 s\"",
    },
    KeyDoc {
        section: "run",
        name: "t_end",
        bare: Bare::Plain,
        doc: "end of the run: s, or \"500 ms\"",
    },
    KeyDoc {
        section: "run",
        name: "tail_s",
        bare: Bare::Plain,
        doc: "time after a record's end to wait for rest or overturning: s",
    },
    KeyDoc {
        section: "run",
        name: "method",
        bare: Bare::NotANumber,
        doc: "\"dop853\", \"dopri5\", \"ralston\" or \"taylor\" (default: by rtol)",
    },
    KeyDoc {
        section: "run",
        name: "rtol",
        bare: Bare::Plain,
        doc: "relative tolerance (dimensionless)",
    },
    KeyDoc {
        section: "run",
        name: "atol",
        bare: Bare::Plain,
        doc: "absolute tolerance (dimensionless)",
    },
    KeyDoc {
        section: "run",
        name: "step",
        bare: Bare::Normalised,
        doc: "fixed step of ralston: \"1 ms\"; step_norm: tau",
    },
    KeyDoc {
        section: "run",
        name: "output_dt",
        bare: Bare::Normalised,
        doc: "spacing of the time history: \"10 ms\"; output_dt_norm: tau (0 keeps none)",
    },
    KeyDoc {
        section: "run",
        name: "tumble_theta",
        bare: Bare::Normalised,
        doc: "rotation at which the block has tumbled: \"0.3 rad\", \"20 deg\"; tumble_theta_norm: theta/psi",
    },
    KeyDoc {
        section: "run",
        name: "flight",
        bare: Bare::NotANumber,
        doc: "\"stop\" or \"ignore\" when the normal force vanishes",
    },
    KeyDoc {
        section: "run",
        name: "zeno_eps",
        bare: Bare::Plain,
        doc: "impact accumulation threshold on |Theta'| (normalised, in [0, 1))",
    },
    KeyDoc {
        section: "run",
        name: "max_steps",
        bare: Bare::Plain,
        doc: "most integration steps (an integer)",
    },
    KeyDoc {
        section: "run",
        name: "max_events",
        bare: Bare::Plain,
        doc: "most events (an integer)",
    },
    KeyDoc {
        section: "analysis",
        name: "lyapunov",
        bare: Bare::NotANumber,
        doc: "add Lyapunov exponents to the summary (bool)",
    },
    KeyDoc {
        section: "analysis",
        name: "lyapunov_method",
        bare: Bare::NotANumber,
        doc: "\"tangent\", \"benettin\" or \"both\"",
    },
    KeyDoc {
        section: "analysis",
        name: "spectrum",
        bare: Bare::NotANumber,
        doc: "add the spectrum of Theta(tau) to the summary (bool)",
    },
    KeyDoc {
        section: "analysis",
        name: "spectrum_window",
        bare: Bare::NotANumber,
        doc: "\"paper\" or \"all\"",
    },
    KeyDoc {
        section: "floor",
        name: "period",
        bare: Bare::Plain,
        doc: "period of the building mode under the block: s, or \"500 ms\"",
    },
    KeyDoc {
        section: "floor",
        name: "damping",
        bare: Bare::Plain,
        doc: "damping ratio of the building mode, fraction of critical (default 0.05)",
    },
    KeyDoc {
        section: "floor",
        name: "participation",
        bare: Bare::Plain,
        doc: "participation Gamma*phi of the mode at the floor, dimensionless (default 1)",
    },
    KeyDoc {
        section: "floor",
        name: "mode",
        bare: Bare::NotANumber,
        doc: "several modes: a list of {period, damping, participation} tables",
    },
];

/// The documentation of `section.name`.
pub fn doc_of(section: &str, name: &str) -> Option<&'static KeyDoc> {
    KEY_DOCS.iter().find(|k| k.section == section && k.name == name)
}

/// Keys the config knows that [`KEY_DOCS`] does not document, as
/// `section.key`.
pub fn undocumented() -> Vec<String> {
    KNOWN_KEYS
        .iter()
        .flat_map(|(s, keys)| keys.iter().map(move |k| (*s, *k)))
        .filter(|(s, k)| doc_of(s, k).is_none())
        .map(|(s, k)| format!("{s}.{k}"))
        .collect()
}

/// A key as typed in Python, split into the config key it sets and
/// whether it was the `_norm` spelling: `a_h_norm` → (`a_h`, true). Only a
/// key whose bare number is normalised has a `_norm` spelling.
pub fn strip_norm<'a>(section: Option<&str>, name: &'a str) -> (&'a str, bool) {
    if let Some(base) = name.strip_suffix(NORM_SUFFIX) {
        let normalised = KEY_DOCS
            .iter()
            .any(|k| k.name == base && k.bare == Bare::Normalised && section.is_none_or(|s| s == k.section));
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
    for (section, keys) in KNOWN_KEYS {
        out.push_str(&format!("\n[{section}]\n"));
        for key in *keys {
            let doc = doc_of(section, key).map_or("(no unit documented)", |d| d.doc);
            out.push_str(&format!("    {key}: {doc}\n"));
        }
    }
    out
}

/// For a key whose bare config number is normalised: a unit to show in
/// the example of an error, and what the normalised number is.
pub fn normalised_meaning(name: &str) -> Option<(&'static str, &'static str)> {
    Some(match name {
        "a_h" | "a_v" => ("g", "units of psi*g"),
        "omega_h" | "omega_v" => ("Hz", "units of p"),
        "theta" | "tumble_theta" => ("rad", "theta/psi"),
        "theta_dot" => ("rad/s", "units of psi*p"),
        "x_dot" => ("m/s", "units of R*p"),
        "step" | "output_dt" => ("s", "tau = p*t"),
        _ => return None,
    })
}
