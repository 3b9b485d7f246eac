//! The table of every config key, in the config file's order (sections as
//! a config file writes them; messages list known keys in this order).

use super::Param;
use super::{Applies, Group, KeySpec, Range, Slot, Span, Value};
use crate::sim::scenario::{AMPLITUDE_LIMIT, ExcitationKind as K, MAX_SIZE_M, MIN_SIZE_M};

const fn at(group: Group, order: u8) -> Option<Slot> {
    Some(Slot { group, order })
}

const fn lin(min: f64, max: f64, step: f64) -> Option<Span> {
    Some(Span {
        min,
        max,
        step,
        log: false,
    })
}

const fn log(min: f64, max: f64, step: f64) -> Option<Span> {
    Some(Span {
        min,
        max,
        step,
        log: true,
    })
}

const UNIT_WORDS: &[&str] = &["g", "m/s2", "cm/s2"];
const HARMONIC_OR_PULSE: Applies = Applies::To(&[K::Harmonic, K::Pulse]);
const HARMONIC: Applies = Applies::To(&[K::Harmonic]);
const PULSE: Applies = Applies::To(&[K::Pulse]);
const RECORD: Applies = Applies::To(&[K::Record]);
// A floor filters records and harmonic motion; a pulse refuses it.
const FLOORED: Applies = Applies::To(&[K::Record, K::Harmonic]);

// Sizes from 0.1 mm to 10 km: beyond them ψ, p or 1/p leave the range
// where the run's numbers (τ = p t, amplitudes in ψg) mean anything, or
// overflow (docs/model.md §1.1).
fn size(x: f64) -> bool {
    (MIN_SIZE_M..=MAX_SIZE_M).contains(&x)
}
const SIZE: Option<Range> = Some(Range {
    ok: size,
    allowed: "in [1e-4, 1e4] metres",
});
fn non_negative(x: f64) -> bool {
    x >= 0.0
}
fn non_negative_finite(x: f64) -> bool {
    (0.0..f64::INFINITY).contains(&x)
}
const COEFFICIENT: Option<Range> = Some(Range {
    ok: non_negative,
    allowed: ">= 0 or inf",
});
fn unit_interval(x: f64) -> bool {
    (0.0..=1.0).contains(&x)
}
const UNIT_INTERVAL: Option<Range> = Some(Range {
    ok: unit_interval,
    allowed: "in [0, 1]",
});
fn amplitude(x: f64) -> bool {
    x.abs() <= AMPLITUDE_LIMIT
}
fn frequency(x: f64) -> bool {
    (1e-6..=1e6).contains(&x)
}
const FREQUENCY: Option<Range> = Some(Range {
    ok: frequency,
    allowed: "in [1e-6, 1e6] (units of p; the forcing period 2π/Ω is then at most 6.3e6 τ)",
});
fn phase(x: f64) -> bool {
    x.abs() <= 1e6
}
fn scale(x: f64) -> bool {
    x.abs() <= 1e3
}
const SCALE: Option<Range> = Some(Range {
    ok: scale,
    allowed: "|scale| <= 1000",
});
// Below these the error control asks for more than double precision can
// give and the step size underflows.
fn rtol(x: f64) -> bool {
    (1e-16..1.0).contains(&x)
}
fn atol(x: f64) -> bool {
    (1e-20..1.0).contains(&x)
}
fn open_unit(x: f64) -> bool {
    x > 0.0 && x < 1.0
}
fn tail(x: f64) -> bool {
    (0.0..=1e6).contains(&x)
}
fn spacing(x: f64) -> bool {
    x >= 0.0 && x.is_finite()
}
fn zeno(x: f64) -> bool {
    (0.0..1.0).contains(&x)
}

const B: KeySpec = KeySpec::BLANK;

/// Every key the config accepts, in the config file's order.
pub const CATALOGUE: &[KeySpec] = &[
    // [block]
    KeySpec {
        key: "block.width",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "B",
        unit: "m",
        meaning: "block width B",
        written: "m, or \"60 cm\", \"600 mm\"",
        doc: "Width B > 0. Default 1 (the paper's block).",
        param: Some(Param::Width),
        range: SIZE,
        slot: at(Group::Block, 0),
        // 5 cm (a statuette) to 10 m (a tall tank): three decades of size.
        slider: log(0.05, 10.0, 0.1),
        ..B
    },
    KeySpec {
        key: "block.height",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "H",
        unit: "m",
        meaning: "block height H",
        written: "m, or \"1.8 m\", \"180 cm\"",
        doc: "Height H > 0. Default 4 (the paper's block).",
        param: Some(Param::Height),
        range: SIZE,
        slot: at(Group::Block, 1),
        slider: log(0.05, 10.0, 0.1),
        ..B
    },
    // [[stack]]: one table per block, bottom to top. The app's panel
    // gives each block its own sliders (its "Stack" group), by index.
    KeySpec {
        key: "stack.width",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "B",
        unit: "m",
        meaning: "width of one block of a stack",
        written: "m, or \"60 cm\", \"600 mm\"",
        doc: "Width B > 0 of this block of a [[stack]] (one table per block, bottom to top). Required.",
        range: SIZE,
        ..B
    },
    KeySpec {
        key: "stack.height",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "H",
        unit: "m",
        meaning: "height of one block of a stack",
        written: "m, or \"60 cm\", \"600 mm\"",
        doc: "Height H > 0 of this block of a [[stack]]. Required.",
        range: SIZE,
        ..B
    },
    KeySpec {
        key: "stack.offset",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "e",
        unit: "m",
        meaning: "horizontal offset of a stacked block's centre from the centre of the block below",
        written: "m (+ to the right), or \"5 cm\"",
        doc: "This block's centre relative to the centre of the block below, m (+ right); its face must overlap the one below. Default 0; must be 0 for the bottom block.",
        ..B
    },
    KeySpec {
        key: "stack.static",
        infinite: true,
        symbol: "μ_s",
        meaning: "static friction coefficient at a stacked block's lower face",
        written: "dimensionless, or \"inf\" (no slip)",
        doc: "Static friction at this block's lower face, >= 0 or inf. Default inf. The bottom block's face slides on the base when its friction demand reaches it, as the single block does; between blocks sliding is not simulated: a run whose demand reaches an upper face's static stops with a one-line error (docs/model.md §18.7, §18.8).",
        range: COEFFICIENT,
        ..B
    },
    KeySpec {
        key: "stack.kinetic",
        infinite: true,
        symbol: "μ_k",
        meaning: "kinetic friction coefficient at a stacked block's lower face",
        written: "dimensionless, or \"inf\"",
        doc: "Kinetic friction at this block's lower face, <= static; default the static one. Acts while the bottom block's face slides on the base (< 4/3 there, the Painlevé bound); an upper face never slides, so its value is only echoed.",
        range: COEFFICIENT,
        ..B
    },
    KeySpec {
        key: "stack.glued",
        value: Value::Flag,
        meaning: "whether a stacked block's lower face is glued",
        written: "true or false",
        doc: "Whether this block's lower face is glued (never opens: an anchored object). Default false.",
        ..B
    },
    // [frame]
    KeySpec {
        key: "frame.width",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "B",
        unit: "m",
        meaning: "width B of each column of a rocking frame",
        written: "m, or \"60 cm\", \"600 mm\"",
        doc: "Width B > 0 of each column of a rocking frame. Required with [frame].",
        range: SIZE,
        slot: at(Group::Frame, 0),
        slider: log(0.05, 10.0, 0.1),
        ..B
    },
    KeySpec {
        key: "frame.height",
        value: Value::Quantity(super::Dimension::Length),
        symbol: "H",
        unit: "m",
        meaning: "height H of each column of a rocking frame",
        written: "m, or \"6 m\", \"600 cm\"",
        doc: "Height H > 0 of each column of a rocking frame. Required with [frame].",
        range: SIZE,
        slot: at(Group::Frame, 1),
        slider: log(0.05, 10.0, 0.1),
        ..B
    },
    KeySpec {
        key: "frame.columns",
        value: Value::Count,
        symbol: "columns",
        meaning: "number of columns of a rocking frame",
        written: "an integer",
        doc: "Columns under the cap beam, 2..=1000. Default 2 (a bridge bent).",
        slot: at(Group::Frame, 2),
        ..B
    },
    KeySpec {
        key: "frame.beam_mass_ratio",
        value: Value::Number,
        symbol: "γ_b",
        meaning: "cap beam mass over the columns' total mass",
        written: "a number >= 0",
        doc: "Mass of the cap beam over the columns' total mass, >= 0 (0: lone columns). Required with [frame].",
        range: Some(Range {
            ok: non_negative_finite,
            allowed: ">= 0",
        }),
        slot: at(Group::Frame, 3),
        // Lone columns to a beam ten times their mass (a bridge deck).
        slider: lin(0.0, 10.0, 0.1),
        ..B
    },
    // [friction]
    KeySpec {
        key: "friction.static",
        infinite: true,
        symbol: "μ_s",
        meaning: "static friction coefficient mu_s",
        written: "dimensionless, or \"inf\" (no sliding)",
        doc: "Static friction coefficient ≥ 0, or inf for no sliding (the paper's sec. 4.1). Default inf.",
        param: Some(Param::MuS),
        range: COEFFICIENT,
        slot: at(Group::Friction, 0),
        // Dry friction coefficients of real contacts lie below 1.5; `inf`
        // (no sliding) stays typed only.
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
    KeySpec {
        key: "friction.kinetic",
        infinite: true,
        symbol: "μ_k",
        meaning: "kinetic friction coefficient mu_k <= mu_s",
        written: "dimensionless, or \"inf\"",
        doc: "Kinetic friction coefficient, 0 ≤ μ_k ≤ μ_s. Default μ_s.",
        param: Some(Param::MuK),
        slot: at(Group::Friction, 1),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
    // [impact]
    KeySpec {
        key: "impact.law",
        value: Value::Choice(&["housner", "corner-momentum", "ratio", "impulse"]),
        symbol: "law",
        meaning: "impact law",
        written: "\"housner\", \"corner-momentum\", \"ratio\" or \"impulse\"",
        doc: "housner: Θ'(after) = (1 − 1.5 sin²ψ) Θ'(before), slip stopped; corner-momentum: angular momentum about the striking corner, pre-impact slip included; ratio: Θ'(after) = r Θ'(before); impulse: the paper's eqs. 17–27.",
        slot: at(Group::Impact, 0),
        ..B
    },
    KeySpec {
        key: "impact.r",
        symbol: "r",
        meaning: "angular-velocity ratio of the ratio law",
        written: "in [0, 1] (dimensionless)",
        doc: "Angular-velocity ratio for law = ratio, in [0, 1]. Default Housner's 1 − 1.5 sin²ψ.",
        param: Some(Param::ImpactR),
        range: UNIT_INTERVAL,
        slot: at(Group::Impact, 1),
        slider: lin(0.0, 1.0, 0.02),
        ..B
    },
    KeySpec {
        key: "impact.e",
        symbol: "e",
        meaning: "vertical restitution of the impulse law",
        written: "in [0, 1] (dimensionless)",
        doc: "Vertical restitution of the striking corner for law = impulse, in [0, 1]. Default 0.",
        param: Some(Param::ImpactE),
        range: UNIT_INTERVAL,
        slot: at(Group::Impact, 2),
        slider: lin(0.0, 1.0, 0.02),
        ..B
    },
    KeySpec {
        key: "impact.static",
        infinite: true,
        symbol: "impact μ_s",
        meaning: "static friction during impact",
        written: "dimensionless, or \"inf\"",
        doc: "Static friction at impact (impulse law), ≥ 0 or inf. Default μ_s.",
        param: Some(Param::ImpactMuS),
        range: COEFFICIENT,
        slot: at(Group::Impact, 3),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
    KeySpec {
        key: "impact.kinetic",
        infinite: true,
        symbol: "impact μ_k",
        meaning: "kinetic friction during impact",
        written: "dimensionless, or \"inf\"",
        doc: "Kinetic friction at impact (impulse law), ≤ impact μ_s. Default μ_k.",
        param: Some(Param::ImpactMuK),
        range: COEFFICIENT,
        slot: at(Group::Impact, 4),
        slider: lin(0.0, 2.0, 0.05),
        ..B
    },
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
        value: Value::Quantity(super::Dimension::Amplitude),
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
        value: Value::Quantity(super::Dimension::Amplitude),
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
        value: Value::Quantity(super::Dimension::Frequency),
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
        value: Value::Quantity(super::Dimension::Frequency),
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
        value: Value::Quantity(super::Dimension::Phase),
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
        value: Value::Quantity(super::Dimension::Phase),
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
        value: Value::Quantity(super::Dimension::Seconds),
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
        value: Value::Quantity(super::Dimension::Seconds),
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
        value: Value::Quantity(super::Dimension::Pga),
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
        value: Value::Quantity(super::Dimension::Pga),
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
    // [initial]
    KeySpec {
        key: "initial.theta",
        value: Value::Quantity(super::Dimension::Rotation),
        symbol: "Θ₀",
        unit: "ψ",
        meaning: "initial rotation",
        written: "\"0.01 rad\", \"0.5 deg\"",
        doc: "Θ at τ = 0, |Θ| < tumble angle. Default 0 (flat). Click the phase portrait to set Θ₀ and Θ'₀.",
        param: Some(Param::Theta0),
        slot: at(Group::Initial, 0),
        slider: lin(-1.0, 1.0, 0.05),
        ..B
    },
    KeySpec {
        key: "initial.theta_dot",
        value: Value::Quantity(super::Dimension::AngularVelocity),
        symbol: "Θ'₀",
        unit: "ψ p",
        meaning: "initial angular velocity",
        written: "\"0.1 rad/s\", \"5 deg/s\"",
        doc: "Θ' at τ = 0. Default 0.",
        param: Some(Param::ThetaDot0),
        slot: at(Group::Initial, 1),
        slider: lin(-3.0, 3.0, 0.1),
        ..B
    },
    KeySpec {
        key: "initial.x_dot",
        value: Value::Quantity(super::Dimension::Velocity),
        symbol: "X'₀",
        unit: "R p",
        meaning: "initial velocity of the centre of mass",
        written: "\"0.1 m/s\", \"10 cm/s\"",
        doc: "X' of the centre of mass at τ = 0. Default: no slip of the contact corner.",
        param: Some(Param::XDot0),
        slot: at(Group::Initial, 2),
        slider: lin(-3.0, 3.0, 0.1),
        ..B
    },
    // [run]
    KeySpec {
        key: "run.tau_end",
        value: Value::Quantity(super::Dimension::Tau),
        symbol: "τ end",
        unit: "τ",
        meaning: "end of the run in tau = p*t",
        written: "bare: tau, the name says so; or \"20 s\"",
        doc: "End of a batch run, in (0, 1e9]. The live view runs on until paused. Default 800.",
        param: Some(Param::TauEnd),
        slot: at(Group::Solver, 7),
        ..B
    },
    KeySpec {
        key: "run.t_end",
        value: Value::Quantity(super::Dimension::Seconds),
        symbol: "t end",
        unit: "s",
        meaning: "end of the run",
        written: "s, or \"500 ms\"",
        doc: "End of a batch run in seconds (instead of τ end). A record run lasts the record plus the tail unless this is set.",
        slot: at(Group::Solver, 8),
        ..B
    },
    KeySpec {
        key: "run.tail_s",
        value: Value::Quantity(super::Dimension::Seconds),
        symbol: "tail",
        unit: "s",
        meaning: "time after a record's end to wait for rest or overturning",
        written: "s",
        doc: "A record run goes on after the record until the block is at rest, at most this long. Default 30 s.",
        range: Some(Range {
            ok: tail,
            allowed: "in [0, 1e6] (seconds)",
        }),
        applies: RECORD,
        slot: at(Group::Solver, 9),
        ..B
    },
    KeySpec {
        key: "run.method",
        value: Value::Choice(&["dop853", "dopri5", "ralston", "taylor"]),
        symbol: "method",
        meaning: "integration method",
        written: "\"dop853\", \"dopri5\", \"ralston\" or \"taylor\" (default: by rtol)",
        doc: "taylor (default at rtol ≤ 1e-6: high-order series, fastest at tight tolerances), dop853 (default at looser rtol), dopri5, or ralston (the paper's fixed-step RK2).",
        slot: at(Group::Solver, 0),
        ..B
    },
    KeySpec {
        key: "run.rtol",
        symbol: "rtol",
        meaning: "relative tolerance",
        written: "dimensionless",
        doc: "Relative tolerance, in (0, 1). Default 1e-10.",
        param: Some(Param::Rtol),
        range: Some(Range {
            ok: rtol,
            allowed: "in [1e-16, 1) (below 1e-16, less than double precision's rounding)",
        }),
        slot: at(Group::Solver, 1),
        ..B
    },
    KeySpec {
        key: "run.atol",
        symbol: "atol",
        meaning: "absolute tolerance",
        written: "dimensionless",
        doc: "Absolute tolerance, in (0, 1). Default 1e-12.",
        param: Some(Param::Atol),
        range: Some(Range {
            ok: atol,
            allowed: "in [1e-20, 1) (below 1e-20 the step size underflows near rest)",
        }),
        slot: at(Group::Solver, 2),
        ..B
    },
    KeySpec {
        key: "run.step",
        value: Value::Quantity(super::Dimension::Tau),
        symbol: "step",
        unit: "τ",
        meaning: "fixed step of ralston",
        written: "\"1 ms\"",
        doc: "Fixed step of ralston, in (0, 1). Default 0.004 (the paper's).",
        param: Some(Param::Step),
        range: Some(Range {
            ok: open_unit,
            allowed: "in (0, 1)",
        }),
        slot: at(Group::Solver, 3),
        ..B
    },
    KeySpec {
        key: "run.output_dt",
        value: Value::Quantity(super::Dimension::Tau),
        symbol: "output dt",
        unit: "τ",
        meaning: "spacing of the time history",
        written: "\"10 ms\" (0 keeps none)",
        doc: "History spacing of a batch run; 0 writes none. Default 0.02.",
        param: Some(Param::OutputDt),
        range: Some(Range {
            ok: spacing,
            allowed: ">= 0 (0 writes no history)",
        }),
        slot: at(Group::Solver, 10),
        ..B
    },
    KeySpec {
        key: "run.tumble_theta",
        value: Value::Quantity(super::Dimension::Rotation),
        symbol: "Θ tumble",
        unit: "ψ",
        meaning: "rotation at which the block has tumbled",
        written: "\"0.3 rad\", \"20 deg\"",
        doc: "|Θ| at which the block has tumbled, in (0, π/(2ψ)]. Default 1.",
        param: Some(Param::TumbleTheta),
        slot: at(Group::Solver, 4),
        ..B
    },
    KeySpec {
        key: "run.flight",
        value: Value::Choice(&["stop", "ignore"]),
        symbol: "flight",
        meaning: "what a vanishing normal force does",
        written: "\"stop\" or \"ignore\"",
        doc: "stop: a vanishing normal force ends the run (default); ignore: integrate on, as the paper did.",
        slot: at(Group::Solver, 5),
        ..B
    },
    KeySpec {
        key: "run.zeno_eps",
        symbol: "zeno ε",
        unit: "ψ p",
        meaning: "impact accumulation threshold on |Theta'|",
        written: "normalised, in [0, 1)",
        doc: "Impact accumulation threshold on |Θ'|, in [0, 1). Default 1e-5.",
        param: Some(Param::ZenoEps),
        range: Some(Range {
            ok: zeno,
            allowed: "in [0, 1)",
        }),
        slot: at(Group::Solver, 6),
        ..B
    },
    KeySpec {
        key: "run.max_steps",
        value: Value::Count,
        symbol: "max steps",
        meaning: "most integration steps",
        written: "an integer",
        doc: "Most steps in one run. Default 1e9.",
        slot: at(Group::Solver, 11),
        ..B
    },
    KeySpec {
        key: "run.max_events",
        value: Value::Count,
        symbol: "max events",
        meaning: "most events",
        written: "an integer",
        doc: "Most events in one run. Default 1e8.",
        slot: at(Group::Solver, 12),
        ..B
    },
    // [analysis]
    KeySpec {
        key: "analysis.lyapunov",
        value: Value::Flag,
        meaning: "add Lyapunov exponents to the summary",
        written: "true or false",
        doc: "Add the Lyapunov exponents to summary.json. Default false.",
        ..B
    },
    KeySpec {
        key: "analysis.lyapunov_method",
        value: Value::Choice(&["tangent", "benettin", "both"]),
        meaning: "how the Lyapunov exponents are computed",
        written: "\"tangent\", \"benettin\" or \"both\"",
        doc: "tangent: tangent dynamics with saltation matrices, the whole spectrum (the default for a [block] and a [frame]: it needs no separation parameter); benettin: two trajectories on the stroboscopic map, the largest exponent (the default, and the only method, for a [[stack]], whose tangent equations are not written); both: both on one trajectory, with their paired difference.",
        ..B
    },
    KeySpec {
        key: "analysis.spectrum",
        value: Value::Flag,
        meaning: "add the spectrum of Theta(tau) to the summary",
        written: "true or false",
        doc: "Add the amplitude spectrum of Θ(τ) to summary.json. Default false.",
        ..B
    },
    KeySpec {
        key: "analysis.spectrum_window",
        value: Value::Choice(&["paper", "all"]),
        meaning: "the part of the run the spectrum is taken over",
        written: "\"paper\" or \"all\"",
        doc: "all: the whole history (default); paper: the paper's samples 3000–7095 at Δτ = 0.004 (τ 12–28.384).",
        ..B
    },
    // [floor]
    KeySpec {
        key: "floor.period",
        value: Value::Quantity(super::Dimension::Seconds),
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
