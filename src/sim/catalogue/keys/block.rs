//! The keys of the block and its contact with the base: `[block]`, `[friction]` and `[impact]`.

use super::{B, COEFFICIENT, SIZE, UNIT_INTERVAL, at, lin, log};
use crate::sim::catalogue::{Dimension, Group, KeySpec, Param, Value};

/// The `[block]` keys: the block's size.
pub(super) const BLOCK: &[KeySpec] = &[
    // [block]
    KeySpec {
        key: "block.width",
        value: Value::Quantity(Dimension::Length),
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
        value: Value::Quantity(Dimension::Length),
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
];

/// The `[friction]` keys: the block's friction on the base.
pub(super) const FRICTION: &[KeySpec] = &[
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
];

/// The `[impact]` keys: the impact law and its coefficients.
pub(super) const IMPACT: &[KeySpec] = &[
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
];
