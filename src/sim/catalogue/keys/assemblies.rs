//! The keys of the bodies built of several blocks: a `[[stack]]` and a `[frame]`.

use super::{B, COEFFICIENT, SIZE, at, lin, log, non_negative_finite};
use crate::sim::catalogue::{Dimension, Group, KeySpec, Range, Value};

/// The `[[stack]]` keys: each block of a stack.
pub(super) const STACK: &[KeySpec] = &[
    // [[stack]]: one table per block, bottom to top. The app's panel
    // gives each block its own sliders (its "Stack" group), by index.
    KeySpec {
        key: "stack.width",
        value: Value::Quantity(Dimension::Length),
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
        value: Value::Quantity(Dimension::Length),
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
        value: Value::Quantity(Dimension::Length),
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
];

/// The `[frame]` keys: the rocking frame (its beam and columns).
pub(super) const FRAME: &[KeySpec] = &[
    // [frame]
    KeySpec {
        key: "frame.width",
        value: Value::Quantity(Dimension::Length),
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
        value: Value::Quantity(Dimension::Length),
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
];
