//! The keys of the base motion: `[excitation]` and the building of `[floor]` that filters it.

use super::{
    B, FLOORED, FREQUENCY, HARMONIC, HARMONIC_OR_PULSE, PULSE, RECORD, SCALE, UNIT_WORDS, amplitude, at, lin, log,
    phase,
};
use crate::sim::catalogue::{Dimension, Group, KeySpec, Param, Range, Value};

/// The `[excitation]` keys: the base motion.
pub(super) const EXCITATION: &[KeySpec] = &[
    // [excitation]
    KeySpec {
        key: "excitation.kind",
        value: Value::Choice(&["harmonic", "pulse", "record", "none"]),
        symbol: "kind",
        meaning: "the base motion",
        written: "\"harmonic\", \"pulse\", \"record\" or \"none\"",
        doc: "harmonic, pulse, record (a ground-motion file) or none. Default harmonic.",
        slot: at(Group::Excitation, 0),
        ..B
    },
    KeySpec {
        key: "excitation.a_h",
        value: Value::Quantity(Dimension::Amplitude),
        symbol: "A_h",
        unit: "ψg",
        meaning: "horizontal amplitude",
        written: "\"0.35 g\", \"3 m/s2\", \"300 cm/s2\", \"1.2 g*tan(alpha)\"",
        doc: "Horizontal amplitude: a_h/g = A_h ψ sin(Ω_h τ + Φ_h); |A_h| ≤ 1e6. Default 0.",
        param: Some(Param::Ah),
        range: Some(Range {
            ok: amplitude,
            allowed: "a finite amplitude |A_h| <= 1e6 (units of ψg)",
        }),
        applies: HARMONIC_OR_PULSE,
        slot: at(Group::Excitation, 1),
        // Uplift needs A_h > tan ψ/ψ ≈ 1 (ψ g); 5 is five times that and
        // above every preset (the paper's bifurcations run to A_v = 3).
        slider: lin(0.0, 5.0, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.a_v",
        value: Value::Quantity(Dimension::Amplitude),
        symbol: "A_v",
        unit: "ψg",
        meaning: "vertical amplitude",
        written: "as a_h",
        doc: "Vertical amplitude: a_v/g = A_v ψ sin(Ω_v τ + Φ_v); |A_v| ≤ 1e6. Default 0.",
        param: Some(Param::Av),
        range: Some(Range {
            ok: amplitude,
            allowed: "a finite amplitude |A_v| <= 1e6 (units of ψg)",
        }),
        applies: HARMONIC_OR_PULSE,
        slot: at(Group::Excitation, 2),
        slider: lin(0.0, 5.0, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.omega_h",
        value: Value::Quantity(Dimension::Frequency),
        symbol: "Ω_h",
        unit: "p",
        meaning: "horizontal forcing frequency",
        written: "\"2 Hz\", \"12 rad/s\"",
        doc: "Horizontal frequency in units of p, in (0, 1e6]. Default 8 (the paper's).",
        param: Some(Param::OmegaH),
        range: FREQUENCY,
        applies: HARMONIC_OR_PULSE,
        slot: at(Group::Excitation, 3),
        // From slow rocking to far above the block's own frequencies.
        slider: log(0.5, 30.0, 0.05),
        ..B
    },
    KeySpec {
        key: "excitation.omega_v",
        value: Value::Quantity(Dimension::Frequency),
        symbol: "Ω_v",
        unit: "p",
        meaning: "vertical forcing frequency",
        written: "as omega_h",
        doc: "Vertical frequency in units of p, in (0, 1e6]. Default Ω_h.",
        param: Some(Param::OmegaV),
        range: FREQUENCY,
        applies: HARMONIC_OR_PULSE,
        slot: at(Group::Excitation, 4),
        slider: log(0.5, 30.0, 0.05),
        ..B
    },
    KeySpec {
        key: "excitation.phase_h",
        value: Value::Quantity(Dimension::Phase),
        symbol: "Φ_h",
        unit: "rad",
        meaning: "horizontal phase",
        written: "rad, or \"90 deg\"",
        doc: "Horizontal phase. Default 0.",
        param: Some(Param::PhaseH),
        range: Some(Range {
            ok: phase,
            allowed: "|Φ_h| <= 1e6 rad",
        }),
        applies: HARMONIC,
        slot: at(Group::Excitation, 5),
        slider: lin(0.0, std::f64::consts::TAU, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.phase_v",
        value: Value::Quantity(Dimension::Phase),
        symbol: "Φ_v",
        unit: "rad",
        meaning: "vertical phase",
        written: "rad, or \"90 deg\"",
        doc: "Vertical phase. Default 0.",
        param: Some(Param::PhaseV),
        range: Some(Range {
            ok: phase,
            allowed: "|Φ_v| <= 1e6 rad",
        }),
        applies: HARMONIC,
        slot: at(Group::Excitation, 6),
        slider: lin(0.0, std::f64::consts::TAU, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.shape",
        value: Value::Choice(&["one-sine", "one-cosine", "type-c", "rectangular", "half-sine"]),
        symbol: "pulse shape",
        meaning: "pulse shape",
        written: "\"one-sine\", \"one-cosine\", \"type-c\", \"rectangular\", \"half-sine\"",
        doc: "Pulse shape: one-sine (Makris type A), one-cosine (type B), type-c, rectangular (a_p for π/ω) or half-sine (a_p sin ωτ for π/ω). Default one-sine.",
        applies: PULSE,
        slot: at(Group::Excitation, 7),
        ..B
    },
    KeySpec {
        key: "excitation.cycles",
        value: Value::Count,
        symbol: "cycles",
        meaning: "cycles n of a type-C_n pulse",
        written: "an integer",
        doc: "n of a type-C_n pulse, 1..=20. Default 1.",
        applies: PULSE,
        slot: at(Group::Excitation, 8),
        ..B
    },
    KeySpec {
        key: "excitation.file_h",
        value: Value::Path,
        symbol: "record (h)",
        meaning: "horizontal record file",
        written: "a path; or record_h= for samples in memory (Python)",
        doc: "Horizontal record: PEER .AT2, COSMOS .V1/.V2, ESM .ASC, two columns (time in s, acceleration) or one column with dt_h. Required for kind = record. File menu: Open record… picks one.",
        applies: RECORD,
        slot: at(Group::Excitation, 9),
        ..B
    },
    KeySpec {
        key: "excitation.file_v",
        value: Value::Path,
        symbol: "record (v)",
        meaning: "vertical record file",
        written: "a path; or record_v= for samples in memory (Python)",
        doc: "Optional vertical record.",
        applies: RECORD,
        slot: at(Group::Excitation, 14),
        ..B
    },
    KeySpec {
        key: "excitation.unit_h",
        value: Value::Choice(UNIT_WORDS),
        symbol: "unit (h)",
        meaning: "unit of the horizontal record file",
        written: "\"g\", \"m/s2\", \"cm/s2\"",
        doc: "Unit of the horizontal record's accelerations: g, m/s2 or cm/s2. Required for text records; an AT2, COSMOS or ESM header states its own.",
        applies: RECORD,
        slot: at(Group::Excitation, 10),
        ..B
    },
    KeySpec {
        key: "excitation.unit_v",
        value: Value::Choice(UNIT_WORDS),
        symbol: "unit (v)",
        meaning: "unit of the vertical record file",
        written: "\"g\", \"m/s2\", \"cm/s2\"",
        doc: "Unit of the vertical record's accelerations: g, m/s2 or cm/s2.",
        applies: RECORD,
        slot: at(Group::Excitation, 15),
        ..B
    },
    KeySpec {
        key: "excitation.dt_h",
        value: Value::Quantity(Dimension::Seconds),
        symbol: "dt (h)",
        unit: "s",
        meaning: "time step of a one-column horizontal record file",
        written: "s, or \"10 ms\"",
        doc: "Time step of a one-column horizontal record, s (> 0). Leave empty for files that hold their times.",
        applies: RECORD,
        slot: at(Group::Excitation, 11),
        ..B
    },
    KeySpec {
        key: "excitation.dt_v",
        value: Value::Quantity(Dimension::Seconds),
        symbol: "dt (v)",
        unit: "s",
        meaning: "time step of a one-column vertical record file",
        written: "s, or \"10 ms\"",
        doc: "Time step of a one-column vertical record, s (> 0).",
        applies: RECORD,
        slot: at(Group::Excitation, 16),
        ..B
    },
    KeySpec {
        key: "excitation.crc32_h",
        value: Value::Checksum,
        meaning: "expected CRC-32 of the horizontal record file",
        written: "8 hex digits",
        doc: "Expected CRC-32 of the horizontal record file: a run on a changed file is refused.",
        ..B
    },
    KeySpec {
        key: "excitation.crc32_v",
        value: Value::Checksum,
        meaning: "expected CRC-32 of the vertical record file",
        written: "8 hex digits",
        doc: "Expected CRC-32 of the vertical record file.",
        ..B
    },
    KeySpec {
        key: "excitation.channel_h",
        value: Value::Count,
        meaning: "channel of the horizontal record file, from 1, where a COSMOS file holds several",
        written: "an integer",
        doc: "Channel of a COSMOS file that holds several, from 1.",
        ..B
    },
    KeySpec {
        key: "excitation.channel_v",
        value: Value::Count,
        meaning: "channel of the vertical record file, from 1, where a COSMOS file holds several",
        written: "an integer",
        doc: "Channel of the vertical record's COSMOS file, from 1.",
        ..B
    },
    KeySpec {
        key: "excitation.scale_h",
        symbol: "scale_h",
        meaning: "factor on the horizontal record",
        written: "dimensionless",
        doc: "Factor on the horizontal record, |scale| ≤ 1000. Default 1. Give either this or the target PGA.",
        param: Some(Param::ScaleH),
        range: SCALE,
        applies: RECORD,
        slot: at(Group::Excitation, 12),
        slider: lin(0.0, 5.0, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.scale_v",
        symbol: "scale_v",
        meaning: "factor on the vertical record",
        written: "dimensionless",
        doc: "Factor on the vertical record, |scale| ≤ 1000. Default 1.",
        param: Some(Param::ScaleV),
        range: SCALE,
        applies: RECORD,
        slot: at(Group::Excitation, 17),
        slider: lin(0.0, 5.0, 0.1),
        ..B
    },
    KeySpec {
        key: "excitation.pga_h",
        value: Value::Quantity(Dimension::Pga),
        symbol: "PGA (h)",
        unit: "g",
        meaning: "scale the horizontal record to this PGA",
        written: "\"0.4 g\", \"4 m/s2\" (a unit is required)",
        doc: "Scale the horizontal record to this peak ground acceleration, g (e.g. 0.35). Give either this or scale_h.",
        applies: RECORD,
        slot: at(Group::Excitation, 13),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
    KeySpec {
        key: "excitation.pga_v",
        value: Value::Quantity(Dimension::Pga),
        symbol: "PGA (v)",
        unit: "g",
        meaning: "scale the vertical record to this PGA",
        written: "\"0.4 g\" (a unit is required)",
        doc: "Scale the vertical record to this peak acceleration, g. Give either this or scale_v.",
        applies: RECORD,
        slot: at(Group::Excitation, 18),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
];

/// The `[floor]` keys: the building the block stands in.
pub(super) const FLOOR: &[KeySpec] = &[
    // [floor]
    KeySpec {
        key: "floor.period",
        value: Value::Quantity(Dimension::Seconds),
        symbol: "T floor",
        unit: "s",
        meaning: "period of the building mode under the block",
        written: "s, or \"500 ms\"",
        doc: "The block stands on a floor of a building: the period of the building mode that moves it, 0.01–20 s. Empty: on the ground. Records and harmonic motion are filtered exactly; the vertical is not. Several modes: [[floor.mode]] tables in a config file.",
        applies: FLOORED,
        slot: at(Group::Floor, 0),
        // From a stiff low-rise (0.05 s) to a tall tower (5 s).
        slider: log(0.05, 5.0, 0.05),
        ..B
    },
    KeySpec {
        key: "floor.damping",
        symbol: "ζ floor",
        meaning: "damping ratio of the building mode, a fraction of critical",
        written: "dimensionless (default 0.05)",
        doc: "Damping ratio of the building mode, 0 < ζ < 1. Default 0.05 (5 %, a typical building).",
        applies: FLOORED,
        slot: at(Group::Floor, 1),
        slider: lin(0.0, 0.3, 0.01),
        ..B
    },
    KeySpec {
        key: "floor.participation",
        symbol: "Γφ",
        meaning: "participation Gamma*phi of the mode at the floor",
        written: "dimensionless (default 1)",
        doc: "The mode's participation factor times its shape at the floor, |Γφ| ≤ 10. Default 1 (a one-storey building); about 0.9 at mid-height of a uniform shear building.",
        applies: FLOORED,
        slot: at(Group::Floor, 2),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
    KeySpec {
        key: "floor.mode",
        value: Value::Tables,
        meaning: "several modes",
        written: "a list of {period, damping, participation} tables",
        doc: "Several building modes, one [[floor.mode]] table each, summed at the floor.",
        applies: FLOORED,
        ..B
    },
];
