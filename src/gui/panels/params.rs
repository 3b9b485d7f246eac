//! The parameter panel: every config key, grouped as block, friction,
//! impact, excitation, initial state and solver, each with its unit, range
//! and a tooltip. A value is committed when its field loses focus (or on
//! Enter); the whole scene is then re-validated by `Scenario::from_table`, and
//! a refused value leaves the scene unchanged and shows the one-line reason.
//! Keys that the scene's excitation kind does not use are not shown
//! ([`applies`]): no Ω or amplitudes for a record, no record file for a
//! harmonic scene.
//!
//! Every continuous parameter also has a slider ([`slider_range`]) beside
//! its field, which moves its value by how far the pointer moved (plain or
//! fine, [`super::slider`]) and steps with the arrow keys. A drag or a key
//! step applies each new value as it comes (at most once a frame, the
//! panel's one commit per frame), through the same validation as a typed
//! value; the run restarts from the state shown now or from the
//! initial state, as the toggle at the top of the panel says
//! ([`Edits::drag_from`]). A typed value always starts the scene over from
//! its initial state: it states a scene (the run `rocking run` would
//! compute), where a drag explores around the motion being watched.

use std::collections::HashMap;
use std::sync::LazyLock;

use super::slider::{FINE_DRAG, SliderRange, slider_text};
use crate::sim::Scenario;
use crate::sim::catalogue::{self, Group, KeySpec, Value};
use crate::sim::protocol::StartFrom;
use crate::sim::scenario::ExcitationKind;

/// How a key is edited.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A number typed as text (`inf` where allowed).
    Number,
    /// One of a few words.
    Choice(&'static [&'static str]),
    /// Free text (a file path).
    Text,
}

/// One key of the panel.
#[derive(Clone, Copy, Debug)]
pub struct Key {
    /// `section.key`.
    pub key: &'static str,
    /// What the panel shows (also the field's accessible name).
    pub label: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Range and meaning, shown on hover.
    pub help: &'static str,
    /// Editor.
    pub kind: Kind,
}

impl Key {
    /// The panel's view of a catalogue entry.
    fn of(spec: &'static KeySpec) -> Self {
        Key {
            key: spec.key,
            label: spec.symbol,
            unit: spec.unit,
            help: spec.doc,
            kind: match spec.value {
                Value::Choice(options) => Kind::Choice(options),
                Value::Path => Kind::Text,
                _ => Kind::Number,
            },
        }
    }
}

/// The groups of the panel, in order, with their keys: the catalogue's
/// entries that have a place in the panel ([`catalogue::panel_keys`]).
pub(crate) static GROUPS: LazyLock<Vec<(&'static str, Vec<Key>)>> = LazyLock::new(|| {
    Group::ALL
        .into_iter()
        .map(|g| (g.title(), catalogue::panel_keys(g).into_iter().map(Key::of).collect()))
        .collect()
});

/// Whether `key` (`section.key`) means anything for an excitation of
/// `kind`, as its catalogue entry says: harmonic scenes use amplitudes,
/// frequencies and phases; pulses amplitudes, frequencies and the shape;
/// records their files, units, steps, scales and the tail after the record.
/// Every other key applies to every kind.
pub fn applies(key: &str, kind: ExcitationKind) -> bool {
    catalogue::spec(key).is_none_or(|s| s.applies.to(kind))
}

/// Whether the panel shows `group` for `cfg`'s structure: a frame's
/// columns and beam for a frame, which has no block size and no friction
/// (its columns do not slide); the block's size and friction otherwise.
fn describes(group: &str, cfg: &Scenario) -> bool {
    match group {
        // A stack has its own group (`stack_params`), and neither the
        // block's impact laws nor a start out of rest.
        "Block" | "Friction" => cfg.frame.is_none() && cfg.stack.is_none(),
        "Impact" | "Initial state" => cfg.stack.is_none(),
        "Frame" => cfg.frame.is_some(),
        _ => true,
    }
}

/// The slider of `key`, for the continuous parameters; `None` for the
/// rest (integers, choices, files, solver settings, record time steps),
/// which are typed only. The spans are the catalogue's: they cover every
/// shipped preset and the paper's figures with room to explore; the field
/// beside takes any valid value beyond them.
pub fn slider_range(key: &str) -> Option<SliderRange> {
    let span = catalogue::spec(key)?.slider?;
    Some(SliderRange {
        min: span.min,
        max: span.max,
        log: span.log,
        step: span.step,
    })
}

/// A value the user set in the panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Commit {
    /// `section.key`.
    pub key: &'static str,
    /// The value, as TOML text.
    pub raw: String,
    /// Whether it came from a slider being dragged (else typed or chosen).
    pub dragged: bool,
}

/// The panel's own state: text being typed into fields, by key, until
/// committed, and where a slider drag restarts the run from.
#[derive(Clone, Debug)]
pub struct Edits {
    typing: HashMap<&'static str, String>,
    /// Where a slider drag restarts the run from. Default: the current
    /// state, as DynamicalSystems.jl's interactive apps do, so that
    /// dragging A_v shows the attractor deform (and double) instead of a
    /// transient from rest after every pixel.
    pub drag_from: StartFrom,
}

impl Default for Edits {
    fn default() -> Self {
        Self {
            typing: HashMap::new(),
            drag_from: StartFrom::Current,
        }
    }
}

/// The hover text of the "Drag restarts from" choice.
const DRAG_FROM_HELP: &str = "Where the run restarts when a slider is dragged. A typed value always starts the scene over from its initial state.";

/// Draws the panel: the restart toggle, then the keys that apply to the
/// scene's excitation kind ([`applies`]). `explicit` gives a key's value as
/// the scene states it (`None`: the key is left at its default). Returns
/// the value the user committed or dragged to, if any (at most one a
/// frame).
pub fn show(
    ui: &mut egui::Ui,
    cfg: &Scenario,
    explicit: &dyn Fn(&str) -> Option<String>,
    edits: &mut Edits,
) -> Option<Commit> {
    let mut commit = None;
    // The label, then the two choices kept together on one line: in a
    // narrow panel (a large presentation scale) the choices go to a line
    // of their own rather than one of them alone under the label.
    let label = "Drag restarts from";
    let needed = {
        let font = egui::TextStyle::Body.resolve(ui.style());
        let width = |t: &str| {
            ui.painter()
                .layout_no_wrap(t.to_owned(), font.clone(), egui::Color32::WHITE)
                .size()
                .x
        };
        let spacing = ui.spacing();
        width(label)
            + width("current")
            + width("initial")
            + 4.0 * spacing.button_padding.x
            + 2.0 * spacing.item_spacing.x
    };
    if ui.available_width() < needed {
        ui.label(label).on_hover_text(DRAG_FROM_HELP);
    }
    ui.horizontal(|ui| {
        if ui.available_width() >= needed {
            ui.label(label)
                .on_hover_text("Where the run restarts when a slider is dragged. A typed value always starts the scene over from its initial state.");
        }
        for (from, text, help) in [
            (
                StartFrom::Current,
                "current",
                "Continue from the state shown (Θ, Θ', X, X', mode) with τ running on: the attractor deforms as you drag",
            ),
            (
                StartFrom::Initial,
                "initial",
                "Start over from τ = 0 and the initial state at every new value",
            ),
        ] {
            ui.selectable_value(&mut edits.drag_from, from, text)
                .on_hover_text(help);
        }
    });
    let json = crate::io::config::to_json(cfg);
    for (group, keys) in GROUPS.iter().filter(|(g, _)| describes(g, cfg)) {
        egui::CollapsingHeader::new(*group)
            // The floor opens where the scene stands on one.
            .default_open(
                matches!(*group, "Block" | "Frame" | "Friction" | "Excitation" | "Initial state")
                    || (*group == "Floor" && cfg.floor.is_some()),
            )
            .show(ui, |ui| {
                egui::Grid::new(*group)
                    .num_columns(3)
                    .spacing([6.0, 3.0])
                    .show(ui, |ui| {
                        for k in keys.iter().filter(|k| applies(k.key, cfg.excitation.kind)) {
                            let stated = explicit(k.key);
                            let shown = {
                                let (section, name) = k.key.split_once('.').unwrap_or((k.key, ""));
                                match json.get(section).and_then(|s| s.get(name)) {
                                    Some(serde_json::Value::String(s)) => s.clone(),
                                    // Keys the resolved scene does not
                                    // repeat (a target PGA, t end): as stated.
                                    Some(serde_json::Value::Null) | None => stated.clone().unwrap_or_default(),
                                    // A resolved number (A_h of a scene
                                    // stated in g) to the slider's four
                                    // digits: all seventeen do not fit
                                    // the field.
                                    Some(serde_json::Value::Number(n)) => {
                                        n.as_f64().map_or_else(|| n.to_string(), slider_text)
                                    }
                                    Some(v) => v.to_string(),
                                }
                            };
                            let label = ui.label(k.label).on_hover_text(format!("{}\n{}", k.key, k.help));
                            match k.kind {
                                Kind::Choice(options) => {
                                    let mut chosen = None;
                                    egui::ComboBox::from_id_salt(k.key)
                                        .selected_text(shown.clone())
                                        .width(120.0)
                                        .show_ui(ui, |ui| {
                                            for o in options {
                                                if ui.selectable_label(shown == *o, *o).clicked() {
                                                    chosen = Some(*o);
                                                }
                                            }
                                        })
                                        .response
                                        .labelled_by(label.id)
                                        .on_hover_text(k.help);
                                    if let Some(o) = chosen
                                        && o != shown
                                    {
                                        commit = Some(Commit {
                                            key: k.key,
                                            raw: o.to_string(),
                                            dragged: false,
                                        });
                                    }
                                }
                                Kind::Number if slider_range(k.key).is_some() => {
                                    ui.horizontal(|ui| {
                                        if let Some(c) = slider(ui, k, &shown) {
                                            commit = Some(c);
                                        }
                                        if let Some(c) =
                                            text_field(ui, k, &shown, stated.is_some(), label.id, edits, 60.0)
                                        {
                                            commit = Some(c);
                                        }
                                    });
                                }
                                Kind::Number | Kind::Text => {
                                    if let Some(c) = text_field(ui, k, &shown, stated.is_some(), label.id, edits, 120.0)
                                    {
                                        commit = Some(c);
                                    }
                                }
                            }
                            let unit = if stated.is_some() {
                                k.unit.to_string()
                            } else {
                                format!("{} ·", k.unit)
                            };
                            ui.label(unit)
                                .on_hover_text("· marks a default value (the key is not set in the scene)");
                            ui.end_row();
                        }
                    });
            });
    }
    commit
}

/// The slider of number key `k` (whose value reads `shown`); returns the
/// new value while it is dragged or stepped with the arrow keys. None is
/// drawn for a value that is not a finite number (`inf`, or an empty
/// default).
fn slider(ui: &mut egui::Ui, k: &Key, shown: &str) -> Option<Commit> {
    slider_with(ui, k, shown, slider_range(k.key)?)
}

/// One grid row of number key `k` (whose value reads `shown`, and is
/// stated): its symbol, its slider on `range` if any and its field, and
/// its unit. Returns the value committed or dragged to.
pub(crate) fn slider_row(
    ui: &mut egui::Ui,
    k: &Key,
    shown: &str,
    range: Option<SliderRange>,
    edits: &mut Edits,
) -> Option<Commit> {
    let label = ui.label(k.label).on_hover_text(format!("{}\n{}", k.key, k.help));
    let mut commit = None;
    ui.horizontal(|ui| {
        if let Some(c) = range.and_then(|r| slider_with(ui, k, shown, r)) {
            commit = Some(c);
        }
        if let Some(c) = text_field(ui, k, shown, true, label.id, edits, 60.0) {
            commit = Some(c);
        }
    });
    ui.label(k.unit);
    commit
}

/// The slider of number key `k` on `range`.
fn slider_with(ui: &mut egui::Ui, k: &Key, shown: &str, range: SliderRange) -> Option<Commit> {
    let value = shown.trim().parse::<f64>().ok().filter(|v| v.is_finite())?;
    // With the 60-point field beside it, the row fits the panel's
    // default 300 points.
    ui.spacing_mut().slider_width = 72.0;
    let name = format!("{} slider", k.label);
    let (r, wanted) = super::slider::Slider {
        value,
        range,
        name: &name,
    }
    .show(ui);
    r.on_hover_text(slider_help(k, &range));
    let raw = slider_text(wanted?);
    (raw.parse::<f64>().ok() != Some(value)).then_some(Commit {
        key: k.key,
        raw,
        dragged: true,
    })
}

/// The hover text of `k`'s slider: its range, and the plain and fine
/// steps of a drag and of the arrow keys, with their unit.
pub(crate) fn slider_help(k: &Key, range: &SliderRange) -> String {
    let (plain, fine) = (range.step_text(false, k.unit), range.step_text(true, k.unit));
    let unit = if k.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", k.unit)
    };
    format!(
        "Drag to explore {} from {} to {}{unit}: each point of drag moves it {plain}; hold Shift during the drag for {fine} a point ({FINE_DRAG}× finer). The drag goes on past the ends of the rail. Click it, then the Left and Right (or Down and Up) arrow keys step {plain}, Shift+arrow {fine}. The field beside takes any valid value.",
        k.label,
        slider_text(range.min),
        slider_text(range.max),
    )
}

/// The text field of key `k`, committed when it loses focus (or on Enter).
fn text_field(
    ui: &mut egui::Ui,
    k: &Key,
    shown: &str,
    stated: bool,
    label: egui::Id,
    edits: &mut Edits,
    width: f32,
) -> Option<Commit> {
    let typing = edits.typing.get(k.key).cloned();
    let mut text = typing.unwrap_or_else(|| shown.to_string());
    let hint = match (stated, k.key) {
        (true, _) => "",
        // No period: no floor, the block on the ground.
        (false, "floor.period") => "ground",
        (false, _) => "default",
    };
    // Sized exactly: beside a slider in a grid cell, a field that may
    // shrink to what the cell had last frame would stay too narrow to read.
    // A text (a record's path) widens to show all of it: the panel takes
    // the width its rows need.
    // A number's field holds the slider's four digits and a sign ("−0.9324")
    // in the panel's font, whatever the presentation scale made of it.
    let sample = match k.kind {
        Kind::Text => text.clone(),
        _ => "−0.0000".to_owned(),
    };
    let font = egui::TextStyle::Body.resolve(ui.style());
    let need = ui.painter().layout_no_wrap(sample, font, egui::Color32::WHITE).size().x;
    let width = width.max(need + 2.0 * ui.spacing().button_padding.x + 4.0);
    let height = ui.spacing().interact_size.y;
    let r = ui
        .add_sized(
            [width, height],
            egui::TextEdit::singleline(&mut text)
                .desired_width(width)
                .hint_text(hint),
        )
        .labelled_by(label)
        .on_hover_text(k.help);
    if r.changed() {
        edits.typing.insert(k.key, text.clone());
    }
    if r.lost_focus()
        && let Some(t) = edits.typing.remove(k.key)
        && t.trim() != shown
    {
        return Some(Commit {
            key: k.key,
            raw: t,
            dragged: false,
        });
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A move is a number of steps from where it began, on the rail's
    /// scale, held to the range (widened to take a value typed beyond it).
    #[test]
    fn a_slider_moves_by_steps_and_stops_only_at_its_range() {
        let a_v = slider_range("excitation.a_v").unwrap();
        assert_eq!((a_v.step_of(false), a_v.step_of(true)), (0.1, 0.005));
        assert!((a_v.moved(1.6, 7.0, false, 1.6) - 2.3).abs() < 1e-12);
        assert!((a_v.moved(1.6, 7.0, true, 1.6) - 1.635).abs() < 1e-12);
        assert!((a_v.moved(1.6, -2.5, false, 1.6) - 1.35).abs() < 1e-12);
        assert_eq!(a_v.moved(4.9, 10.0, false, 4.9), 5.0);
        assert_eq!(a_v.moved(0.2, -1000.0, true, 0.2), 0.0);
        // Typed beyond the rail: it stays until moved back.
        assert_eq!(a_v.moved(7.0, 3.0, false, 7.0), 7.0);
        assert!((a_v.moved(7.0, -1.0, false, 7.0) - 6.9).abs() < 1e-12);
        assert_eq!((a_v.place(2.5), a_v.place(-1.0), a_v.place(7.0)), (0.5, 0.0, 1.0));
        // Logarithmic: a fraction of the value per step.
        let omega = slider_range("excitation.omega_h").unwrap();
        assert!((omega.moved(8.0, 2.0, false, 8.0) - 8.0 * 1.05 * 1.05).abs() < 1e-12);
        assert!((omega.moved(8.0, -1.0, true, 8.0) - 8.0 / 1.0025).abs() < 1e-12);
        assert!((omega.place(30f64.sqrt() * 0.5f64.sqrt()) - 0.5).abs() < 1e-12);
        assert_eq!(omega.step_text(false, "p"), "5 %");
        assert_eq!(omega.step_text(true, "p"), "0.25 %");
        assert_eq!(a_v.step_text(true, "ψg"), "0.005 ψg");
        assert_eq!(slider_range("impact.r").unwrap().step_text(false, ""), "0.02");
    }

    #[test]
    fn slider_values_are_applied_with_four_significant_digits() {
        assert_eq!(slider_text(1.83333333), "1.833");
        assert_eq!(slider_text(0.0123456), "0.01235");
        assert_eq!(slider_text(12.5), "12.5");
        assert_eq!(slider_text(2.0), "2");
        assert_eq!(slider_text(-0.5), "-0.5");
        assert_eq!(slider_text(0.0), "0");
    }

    #[test]
    fn every_slider_is_on_a_number_key_of_the_panel_with_a_valid_range() {
        let keys: Vec<&Key> = GROUPS.iter().flat_map(|(_, ks)| ks.iter()).collect();
        let mut sliders = 0;
        for k in &keys {
            if let Some(r) = slider_range(k.key) {
                sliders += 1;
                assert_eq!(k.kind, Kind::Number, "{}", k.key);
                assert!(r.min < r.max && (!r.log || r.min > 0.0), "{}: {r:?}", k.key);
                // The whole range in 20 to 200 points of plain drag: the
                // handle about follows a pointer on the 54-point travel.
                let points = if r.log {
                    (r.max / r.min).ln() / r.step.ln_1p()
                } else {
                    (r.max - r.min) / r.step
                };
                assert!((20.0..=200.0).contains(&points), "{}: {points} points", k.key);
            }
        }
        // B, H, a frame's B, H and beam mass ratio, four friction
        // coefficients, r, e, two amplitudes, two frequencies, two phases,
        // two PGAs, two scales, the floor's period, damping and
        // participation, Θ₀, Θ'₀, X'₀.
        assert_eq!(sliders, 27);
    }
}
