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

use super::slider::{FINE_DRAG, SliderRange, slider_text};
use crate::sim::Scenario;
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

const fn num(key: &'static str, label: &'static str, unit: &'static str, help: &'static str) -> Key {
    Key {
        key,
        label,
        unit,
        help,
        kind: Kind::Number,
    }
}

/// The groups of the panel, in order, with their keys (all of
/// `io::config::KNOWN_KEYS`).
pub const GROUPS: &[(&str, &[Key])] = &[
    (
        "Block",
        &[
            num("block.width", "B", "m", "Width B > 0. Default 1 (the paper's block)."),
            num("block.height", "H", "m", "Height H > 0. Default 4 (the paper's block)."),
        ],
    ),
    (
        "Friction",
        &[
            num(
                "friction.static",
                "μ_s",
                "",
                "Static friction coefficient ≥ 0, or inf for no sliding (the paper's sec. 4.1). Default inf.",
            ),
            num(
                "friction.kinetic",
                "μ_k",
                "",
                "Kinetic friction coefficient, 0 ≤ μ_k ≤ μ_s. Default μ_s.",
            ),
        ],
    ),
    (
        "Impact",
        &[
            Key {
                key: "impact.law",
                label: "law",
                unit: "",
                help: "housner: Θ'(after) = (1 − 1.5 sin²ψ) Θ'(before), slip stopped; corner-momentum: angular momentum about the striking corner, pre-impact slip included; ratio: Θ'(after) = r Θ'(before); impulse: the paper's eqs. 17–27.",
                kind: Kind::Choice(&["housner", "corner-momentum", "ratio", "impulse"]),
            },
            num(
                "impact.r",
                "r",
                "",
                "Angular-velocity ratio for law = ratio, in [0, 1]. Default Housner's 1 − 1.5 sin²ψ.",
            ),
            num(
                "impact.e",
                "e",
                "",
                "Vertical restitution of the striking corner for law = impulse, in [0, 1]. Default 0.",
            ),
            num(
                "impact.static",
                "impact μ_s",
                "",
                "Static friction at impact (impulse law), ≥ 0 or inf. Default μ_s.",
            ),
            num(
                "impact.kinetic",
                "impact μ_k",
                "",
                "Kinetic friction at impact (impulse law), ≤ impact μ_s. Default μ_k.",
            ),
        ],
    ),
    (
        "Excitation",
        &[
            Key {
                key: "excitation.kind",
                label: "kind",
                unit: "",
                help: "harmonic, pulse, record (a ground-motion file) or none. Default harmonic.",
                kind: Kind::Choice(&["harmonic", "pulse", "record", "none"]),
            },
            num(
                "excitation.a_h",
                "A_h",
                "ψg",
                "Horizontal amplitude: a_h/g = A_h ψ sin(Ω_h τ + Φ_h); |A_h| ≤ 1e6. Default 0.",
            ),
            num(
                "excitation.a_v",
                "A_v",
                "ψg",
                "Vertical amplitude: a_v/g = A_v ψ sin(Ω_v τ + Φ_v); |A_v| ≤ 1e6. Default 0.",
            ),
            num(
                "excitation.omega_h",
                "Ω_h",
                "p",
                "Horizontal frequency in units of p, in (0, 1e6]. Default 8 (the paper's).",
            ),
            num(
                "excitation.omega_v",
                "Ω_v",
                "p",
                "Vertical frequency in units of p, in (0, 1e6]. Default Ω_h.",
            ),
            num("excitation.phase_h", "Φ_h", "rad", "Horizontal phase. Default 0."),
            num("excitation.phase_v", "Φ_v", "rad", "Vertical phase. Default 0."),
            Key {
                key: "excitation.shape",
                label: "pulse shape",
                unit: "",
                help: "Pulse shape: one-sine (Makris type A), one-cosine (type B), type-c, rectangular (a_p for π/ω) or half-sine (a_p sin ωτ for π/ω). Default one-sine.",
                kind: Kind::Choice(&["one-sine", "one-cosine", "type-c", "rectangular", "half-sine"]),
            },
            num(
                "excitation.cycles",
                "cycles",
                "",
                "n of a type-C_n pulse, 1..=20. Default 1.",
            ),
            Key {
                key: "excitation.file_h",
                label: "record (h)",
                unit: "",
                help: "Horizontal record: PEER .AT2, COSMOS .V1/.V2, ESM .ASC, two columns (time in s, acceleration) or one column with dt_h. Required for kind = record. File menu: Open record… picks one.",
                kind: Kind::Text,
            },
            Key {
                key: "excitation.unit_h",
                label: "unit (h)",
                unit: "",
                help: "Unit of the horizontal record's accelerations: g, m/s2 or cm/s2. Required for text records; an AT2, COSMOS or ESM header states its own.",
                kind: Kind::Choice(&["g", "m/s2", "cm/s2"]),
            },
            num(
                "excitation.dt_h",
                "dt (h)",
                "s",
                "Time step of a one-column horizontal record, s (> 0). Leave empty for files that hold their times.",
            ),
            num(
                "excitation.scale_h",
                "scale_h",
                "",
                "Factor on the horizontal record, |scale| ≤ 1000. Default 1. Give either this or the target PGA.",
            ),
            num(
                "excitation.pga_h",
                "PGA (h)",
                "g",
                "Scale the horizontal record to this peak ground acceleration, g (e.g. 0.35). Give either this or scale_h.",
            ),
            Key {
                key: "excitation.file_v",
                label: "record (v)",
                unit: "",
                help: "Optional vertical record.",
                kind: Kind::Text,
            },
            Key {
                key: "excitation.unit_v",
                label: "unit (v)",
                unit: "",
                help: "Unit of the vertical record's accelerations: g, m/s2 or cm/s2.",
                kind: Kind::Choice(&["g", "m/s2", "cm/s2"]),
            },
            num(
                "excitation.dt_v",
                "dt (v)",
                "s",
                "Time step of a one-column vertical record, s (> 0).",
            ),
            num(
                "excitation.scale_v",
                "scale_v",
                "",
                "Factor on the vertical record, |scale| ≤ 1000. Default 1.",
            ),
            num(
                "excitation.pga_v",
                "PGA (v)",
                "g",
                "Scale the vertical record to this peak acceleration, g. Give either this or scale_v.",
            ),
        ],
    ),
    (
        "Floor",
        &[
            num(
                "floor.period",
                "T floor",
                "s",
                "The block stands on a floor of a building: the period of the building mode that moves it, 0.01–20 s. Empty: on the ground. Records and harmonic motion are filtered exactly; the vertical is not. Several modes: [[floor.mode]] tables in a config file.",
            ),
            num(
                "floor.damping",
                "ζ floor",
                "",
                "Damping ratio of the building mode, 0 < ζ < 1. Default 0.05 (5 %, a typical building).",
            ),
            num(
                "floor.participation",
                "Γφ",
                "",
                "The mode's participation factor times its shape at the floor, |Γφ| ≤ 10. Default 1 (a one-storey building); about 0.9 at mid-height of a uniform shear building.",
            ),
        ],
    ),
    (
        "Initial state",
        &[
            num(
                "initial.theta",
                "Θ₀",
                "ψ",
                "Θ at τ = 0, |Θ| < tumble angle. Default 0 (flat). Click the phase portrait to set Θ₀ and Θ'₀.",
            ),
            num("initial.theta_dot", "Θ'₀", "ψ p", "Θ' at τ = 0. Default 0."),
            num(
                "initial.x_dot",
                "X'₀",
                "R p",
                "X' of the centre of mass at τ = 0. Default: no slip of the contact corner.",
            ),
        ],
    ),
    (
        "Solver",
        &[
            Key {
                key: "run.method",
                label: "method",
                unit: "",
                help: "taylor (default at rtol ≤ 1e-6: high-order series, fastest at tight tolerances), dop853 (default at looser rtol), dopri5, or ralston (the paper's fixed-step RK2).",
                kind: Kind::Choice(&["dop853", "dopri5", "ralston", "taylor"]),
            },
            num("run.rtol", "rtol", "", "Relative tolerance, in (0, 1). Default 1e-10."),
            num("run.atol", "atol", "", "Absolute tolerance, in (0, 1). Default 1e-12."),
            num(
                "run.step",
                "step",
                "τ",
                "Fixed step of ralston, in (0, 1). Default 0.004 (the paper's).",
            ),
            num(
                "run.tumble_theta",
                "Θ tumble",
                "ψ",
                "|Θ| at which the block has tumbled, in (0, π/(2ψ)]. Default 1.",
            ),
            Key {
                key: "run.flight",
                label: "flight",
                unit: "",
                help: "stop: a vanishing normal force ends the run (default); ignore: integrate on, as the paper did.",
                kind: Kind::Choice(&["stop", "ignore"]),
            },
            num(
                "run.zeno_eps",
                "zeno ε",
                "ψ p",
                "Impact accumulation threshold on |Θ'|, in [0, 1). Default 1e-5.",
            ),
            num(
                "run.tau_end",
                "τ end",
                "τ",
                "End of a batch run, in (0, 1e9]. The live view runs on until paused. Default 800.",
            ),
            num(
                "run.t_end",
                "t end",
                "s",
                "End of a batch run in seconds (instead of τ end). A record run lasts the record plus the tail unless this is set.",
            ),
            num(
                "run.tail_s",
                "tail",
                "s",
                "A record run goes on after the record until the block is at rest, at most this long. Default 30 s.",
            ),
            num(
                "run.output_dt",
                "output dt",
                "τ",
                "History spacing of a batch run; 0 writes none. Default 0.02.",
            ),
            num("run.max_steps", "max steps", "", "Most steps in one run. Default 1e9."),
            num(
                "run.max_events",
                "max events",
                "",
                "Most events in one run. Default 1e8.",
            ),
        ],
    ),
];

/// Whether `key` (`section.key`) means anything for an excitation of
/// `kind`: harmonic scenes use amplitudes, frequencies and phases; pulses
/// amplitudes, frequencies and the shape; records their files, units,
/// steps, scales and the tail after the record. Every other key applies
/// to every kind.
pub fn applies(key: &str, kind: ExcitationKind) -> bool {
    use ExcitationKind as K;
    let name = match key.split_once('.') {
        Some(("excitation", name)) => name,
        Some(("run", "tail_s")) => return kind == K::Record,
        // A floor filters records and harmonic motion; a pulse refuses it.
        Some(("floor", _)) => return matches!(kind, K::Record | K::Harmonic),
        _ => return true,
    };
    match name {
        "a_h" | "a_v" | "omega_h" | "omega_v" => matches!(kind, K::Harmonic | K::Pulse),
        "phase_h" | "phase_v" => kind == K::Harmonic,
        "shape" | "cycles" => kind == K::Pulse,
        "file_h" | "file_v" | "unit_h" | "unit_v" | "dt_h" | "dt_v" | "scale_h" | "scale_v" | "pga_h" | "pga_v" => {
            kind == K::Record
        }
        _ => true,
    }
}

const fn lin(min: f64, max: f64, step: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: false,
        step,
    })
}

const fn log(min: f64, max: f64, step: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: true,
        step,
    })
}

/// The slider of `key`, for the continuous parameters; `None` for the
/// rest (integers, choices, files, solver settings, record time steps),
/// which are typed only. The ranges cover every shipped preset and the
/// paper's figures with room to explore; the field beside takes any valid
/// value beyond them.
pub fn slider_range(key: &str) -> Option<SliderRange> {
    match key {
        // 5 cm (a statuette) to 10 m (a tall tank): three decades of size.
        "block.width" | "block.height" => log(0.05, 10.0, 0.1),
        // Dry friction coefficients of real contacts lie below 1.5; `inf`
        // (no sliding) stays typed only.
        "friction.static" | "friction.kinetic" | "impact.static" | "impact.kinetic" => lin(0.0, 2.0, 0.05),
        "impact.r" | "impact.e" => lin(0.0, 1.0, 0.02),
        // Uplift needs A_h > tan ψ/ψ ≈ 1 (ψ g); 5 is five times that and
        // above every preset (the paper's bifurcations run to A_v = 3).
        "excitation.a_h" | "excitation.a_v" => lin(0.0, 5.0, 0.1),
        // From slow rocking to far above the block's own frequencies.
        "excitation.omega_h" | "excitation.omega_v" => log(0.5, 30.0, 0.05),
        "excitation.phase_h" | "excitation.phase_v" => lin(0.0, std::f64::consts::TAU, 0.1),
        "excitation.pga_h" | "excitation.pga_v" => lin(0.0, 2.0, 0.05),
        "excitation.scale_h" | "excitation.scale_v" => lin(0.0, 5.0, 0.1),
        // From a stiff low-rise (0.05 s) to a tall tower (5 s).
        "floor.period" => log(0.05, 5.0, 0.05),
        "floor.damping" => lin(0.0, 0.3, 0.01),
        "floor.participation" => lin(0.0, 2.0, 0.05),
        "initial.theta" => lin(-1.0, 1.0, 0.05),
        "initial.theta_dot" | "initial.x_dot" => lin(-3.0, 3.0, 0.1),
        _ => None,
    }
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
    for (group, keys) in GROUPS {
        egui::CollapsingHeader::new(*group)
            // The floor opens where the scene stands on one.
            .default_open(
                matches!(*group, "Block" | "Friction" | "Excitation" | "Initial state")
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
    let range = slider_range(k.key)?;
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
pub fn slider_help(k: &Key, range: &SliderRange) -> String {
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
        // B, H, four friction coefficients, r, e, two amplitudes, two
        // frequencies, two phases, two PGAs, two scales, the floor's
        // period, damping and participation, Θ₀, Θ'₀, X'₀.
        assert_eq!(sliders, 24);
    }
}
