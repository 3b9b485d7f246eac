//! The parameter panel: every config key, grouped as block, friction,
//! impact, excitation, initial state and solver, each with its unit, range
//! and a tooltip. A value is committed when its field loses focus (or on
//! Enter); the whole scene is then re-validated by `Scenario::from_table`, and
//! a refused value leaves the scene unchanged and shows the one-line reason.
//! Keys that the scene's excitation kind does not use are not shown
//! ([`applies`]): no Ω or amplitudes for a record, no record file for a
//! harmonic scene.

use std::collections::HashMap;

use crate::sim::Scenario;
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
                help: "Horizontal record: PEER .AT2, two columns (time in s, acceleration) or one column with dt_h. Required for kind = record. File menu: Open record… picks one.",
                kind: Kind::Text,
            },
            Key {
                key: "excitation.unit_h",
                label: "unit (h)",
                unit: "",
                help: "Unit of the horizontal record's accelerations: g, m/s2 or cm/s2. Required for text records; an AT2 header states its own.",
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

/// Text being typed into fields, by key, until committed.
#[derive(Clone, Debug, Default)]
pub struct Edits {
    typing: HashMap<&'static str, String>,
}

/// Draws the panel: the keys that apply to the scene's excitation kind
/// ([`applies`]). `explicit` gives a key's value as the scene states it
/// (`None`: the key is left at its default). Returns the `(key, raw
/// value)` the user committed, if any.
pub fn show(
    ui: &mut egui::Ui,
    cfg: &Scenario,
    explicit: &dyn Fn(&str) -> Option<String>,
    edits: &mut Edits,
) -> Option<(&'static str, String)> {
    let mut commit = None;
    let json = crate::io::config::to_json(cfg);
    for (group, keys) in GROUPS {
        egui::CollapsingHeader::new(*group)
            .default_open(matches!(*group, "Block" | "Friction" | "Excitation" | "Initial state"))
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
                                        commit = Some((k.key, o.to_string()));
                                    }
                                }
                                Kind::Number | Kind::Text => {
                                    let typing = edits.typing.get(k.key).cloned();
                                    let mut text = typing.clone().unwrap_or_else(|| shown.clone());
                                    let hint = if stated.is_some() { "" } else { "default" };
                                    let r = ui
                                        .add(
                                            egui::TextEdit::singleline(&mut text)
                                                .desired_width(120.0)
                                                .hint_text(hint),
                                        )
                                        .labelled_by(label.id)
                                        .on_hover_text(k.help);
                                    if r.changed() {
                                        edits.typing.insert(k.key, text.clone());
                                    }
                                    if r.lost_focus()
                                        && let Some(t) = edits.typing.remove(k.key)
                                        && t.trim() != shown
                                    {
                                        commit = Some((k.key, t));
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
