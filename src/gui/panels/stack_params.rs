//! The parameter panel's group for a stack of blocks: each block's width,
//! height and offset (`stack[i].width`, `stack[i].height`,
//! `stack[i].offset`, as `--set` spells them, i from 0 at the bottom),
//! each with a slider and a field as the block's size has, and the
//! floor's friction under the bottom block (`stack[0].static`,
//! `stack[0].kinetic`) as the block's friction has. A drag restarts the
//! stack from rest with the new value, as any drag of a stack does (a
//! stack has no start but rest).

use super::params::{Commit, Edits, Key, Kind, slider_range, slider_row};
use super::slider::SliderRange;
use crate::model::stack::MAX_BLOCKS;
use crate::sim::Scenario;
use crate::sim::stack_answer::body_name;

/// The keys of block `i`: width, height, offset.
const KEYS: [[&str; 3]; MAX_BLOCKS] = [
    ["stack[0].width", "stack[0].height", "stack[0].offset"],
    ["stack[1].width", "stack[1].height", "stack[1].offset"],
    ["stack[2].width", "stack[2].height", "stack[2].offset"],
    ["stack[3].width", "stack[3].height", "stack[3].offset"],
    ["stack[4].width", "stack[4].height", "stack[4].offset"],
];

/// Their symbols, numbered from 1 at the bottom as docs/model.md §18
/// numbers the blocks (also each field's and slider's accessible name).
const LABELS: [[&str; 3]; MAX_BLOCKS] = [
    ["B₁", "H₁", "e₁"],
    ["B₂", "H₂", "e₂"],
    ["B₃", "H₃", "e₃"],
    ["B₄", "H₄", "e₄"],
    ["B₅", "H₅", "e₅"],
];

const HELP: [&str; 3] = [
    "Width of this block of the stack, m (stack[i].width).",
    "Height of this block of the stack, m (stack[i].height).",
    "This block's centre relative to the centre of the block below, m (+ right; stack[i].offset); its face must overlap the one below.",
];

/// The floor's friction: keys, symbols, help and the block's friction
/// keys whose slider spans they take.
const FLOOR: [(&str, &str, &str, &str); 2] = [
    (
        "stack[0].static",
        "μ_s",
        "Static friction between the bottom block and the floor (stack[0].static; inf: the stack never slides). The stack slides on the floor when the friction it needs reaches it.",
        "friction.static",
    ),
    (
        "stack[0].kinetic",
        "μ_k",
        "Kinetic friction while the stack slides on the floor (stack[0].kinetic; <= the static one, < 4/3).",
        "friction.kinetic",
    ),
];

/// The span of an offset's slider, m: ±1 m in centimetres covers a
/// tombstone's or a statue's stones with room to push one off.
const OFFSET_SPAN: SliderRange = SliderRange {
    min: -1.0,
    max: 1.0,
    log: false,
    step: 0.01,
};

/// Draws the group for the stack of `cfg`, top block first (as it stands);
/// returns the value committed or dragged to, if any.
pub fn show(ui: &mut egui::Ui, cfg: &Scenario, edits: &mut Edits) -> Option<Commit> {
    let blocks = cfg.stack.as_ref()?;
    let mut commit = None;
    egui::CollapsingHeader::new("Stack").default_open(true).show(ui, |ui| {
        // A grid per block, its name above it: a name in the grid's first
        // column would widen every row's label by "bottom block".
        let grid = |ui: &mut egui::Ui, id: usize, rows: &mut dyn FnMut(&mut egui::Ui)| {
            egui::Grid::new(("stack", id))
                .num_columns(3)
                .spacing([6.0, 3.0])
                .show(ui, |ui| rows(ui));
        };
        for (i, b) in blocks.iter().enumerate().take(MAX_BLOCKS).rev() {
            ui.label(egui::RichText::new(body_name(i, blocks.len())).strong());
            grid(ui, i, &mut |ui| {
                // The bottom block's offset is 0 by definition.
                let n = if i == 0 { 2 } else { 3 };
                for (c, value) in [b.width, b.height, b.offset].into_iter().enumerate().take(n) {
                    let k = Key {
                        key: KEYS[i][c],
                        label: LABELS[i][c],
                        unit: "m",
                        help: HELP[c],
                        kind: Kind::Number,
                    };
                    let range = if c == 2 {
                        Some(OFFSET_SPAN)
                    } else {
                        slider_range(if c == 0 { "block.width" } else { "block.height" })
                    };
                    if let Some(got) = slider_row(ui, &k, &format!("{value}"), range, edits) {
                        commit = Some(got);
                    }
                    ui.end_row();
                }
            });
        }
        ui.label(egui::RichText::new("floor friction").strong());
        let bottom = blocks[0];
        let values = [bottom.mu_s, bottom.mu_k.unwrap_or(bottom.mu_s)];
        grid(ui, MAX_BLOCKS, &mut |ui| {
            for ((key, label, help, like), value) in FLOOR.into_iter().zip(values) {
                let k = Key {
                    key,
                    label,
                    unit: "",
                    help,
                    kind: Kind::Number,
                };
                if let Some(got) = slider_row(ui, &k, &format!("{value}"), slider_range(like), edits) {
                    commit = Some(got);
                }
                ui.end_row();
            }
        });
    });
    commit
}
