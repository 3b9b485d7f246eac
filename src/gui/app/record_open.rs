//! Opening a ground-motion record (File ▸ Open record…), and asking for
//! what the file does not say.
//!
//! The app reads no record itself: it writes `excitation.kind = "record"`
//! and `excitation.file_h` into the scene's settings and lets the config
//! layer read the file, exactly as `--set` would. When the config layer
//! refuses because the unit is unknown (a text record, or an AT2 header
//! without one: the error is on `excitation.unit_h`) or a one-column file
//! has no time step (on `excitation.dt_h`), the app keeps the question
//! open in a small window; the answer becomes `excitation.unit_h` (and
//! `excitation.dt_h`) and the settings are resolved again.

use std::path::{Path, PathBuf};

use super::{Message, RockingApp};
use crate::io::config::ConfigError;
use crate::model::units::AccelUnit;

/// The key the config layer names when a record's unit is unknown.
const UNIT_KEY: &str = "excitation.unit_h";

/// The key the config layer names when a one-column record has no step.
const STEP_KEY: &str = "excitation.dt_h";

/// A record being opened whose file leaves something unsaid.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordQuestion {
    /// The file.
    pub path: PathBuf,
    /// The unit chosen so far (kept while the time step is asked).
    pub unit: Option<AccelUnit>,
    /// Whether the file has one value per line, so its time step is asked.
    pub needs_step: bool,
    /// The time step as typed, s.
    pub step: String,
    /// Why the last answer was refused, if it was.
    pub error: Option<String>,
}

/// The word a unit button shows.
fn unit_button(unit: AccelUnit) -> &'static str {
    match unit {
        AccelUnit::G => "g (9.81 m/s²)",
        AccelUnit::MetresPerSecond2 => "m/s²",
        AccelUnit::CentimetresPerSecond2 => "cm/s² (gal)",
    }
}

/// The config key a record error is about, if the error names one.
fn key_at_fault(e: &ConfigError) -> Option<&str> {
    match e {
        ConfigError::Key { key, .. } => Some(key),
        ConfigError::Record { key, .. } => Some(key),
        ConfigError::Scenario(_) | ConfigError::Syntax { .. } | ConfigError::File { .. } | ConfigError::Usage(_) => {
            None
        }
    }
}

impl RockingApp {
    /// Makes the record at `path` the scene's horizontal excitation
    /// (what File ▸ Open record… does with the file picked). If the file
    /// does not say its unit or time step, the app asks
    /// ([`RockingApp::record_question`]) instead of guessing.
    pub fn open_record(&mut self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.try_record(path, None, None);
    }

    /// The open question about a record, if any.
    pub fn record_question(&self) -> Option<&RecordQuestion> {
        self.record_question.as_ref()
    }

    /// Answers the open question: the record's accelerations are in
    /// `unit`, and (for a one-column file) sample k is at k·`step` (text:
    /// seconds, or a quantity such as `10 ms`).
    pub(crate) fn answer_record(&mut self, unit: AccelUnit, step: Option<&str>) {
        let Some(q) = self.record_question.take() else {
            return;
        };
        self.try_record(q.path, Some(unit), step.map(str::to_string));
    }

    /// Drops the open question; the scene stays as it was.
    pub(crate) fn cancel_record(&mut self) {
        self.record_question = None;
    }

    fn try_record(&mut self, path: PathBuf, unit: Option<AccelUnit>, step: Option<String>) {
        let file = path.display().to_string();
        let step_value = step.as_deref().map(|t| {
            let t = t.trim();
            // A bare number is seconds; anything else goes to the config's
            // quantity parser as text ("10 ms").
            match t.parse::<f64>() {
                Ok(x) => toml::Value::Float(x),
                Err(_) => toml::Value::String(t.to_string()),
            }
        });
        let next = self.settings.with_values(&[
            ("excitation.kind", Some(toml::Value::String("record".into()))),
            ("excitation.file_h", Some(toml::Value::String(file.clone()))),
            (UNIT_KEY, unit.map(|u| toml::Value::String(u.name().into()))),
            (STEP_KEY, step_value),
        ]);
        match next.resolve_typed() {
            Ok(cfg) => {
                self.record_question = None;
                self.apply(next, cfg);
                let name = path
                    .file_name()
                    .map_or(file.clone(), |n| n.to_string_lossy().into_owned());
                self.message = Some(Message {
                    text: format!("record {name}"),
                    error: false,
                });
            }
            Err(e) => match key_at_fault(&e) {
                Some(UNIT_KEY) => {
                    self.record_question = Some(RecordQuestion {
                        path,
                        unit: None,
                        needs_step: false,
                        step: String::new(),
                        // Asked the first time; refused after an answer.
                        error: unit.map(|_| e.to_string()),
                    });
                }
                Some(STEP_KEY) => {
                    self.record_question = Some(RecordQuestion {
                        path,
                        unit,
                        needs_step: true,
                        step: step.clone().unwrap_or_default(),
                        error: step.map(|_| e.to_string()),
                    });
                }
                Some(_) | None => {
                    self.record_question = None;
                    self.message = Some(Message {
                        text: e.to_string(),
                        error: true,
                    });
                }
            },
        }
    }

    /// The question's window, while a question is open.
    pub(super) fn record_window(&mut self, ctx: &egui::Context) {
        let Some(q) = self.record_question.as_mut() else {
            return;
        };
        let name = q
            .path
            .file_name()
            .map_or_else(|| q.path.display().to_string(), |n| n.to_string_lossy().into_owned());
        let mut answer = None;
        let mut cancel = false;
        egui::Window::new("Reading the record")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
            .show(ctx, |ui| {
                if q.needs_step {
                    ui.label(format!("{name} has one value per line: what is its time step?"));
                } else {
                    ui.label(format!("{name} does not say its unit. Its accelerations are in:"));
                }
                ui.horizontal(|ui| {
                    for unit in AccelUnit::ALL {
                        if ui.selectable_label(q.unit == Some(unit), unit_button(unit)).clicked() {
                            q.unit = Some(unit);
                            if !q.needs_step {
                                answer = Some(unit);
                            }
                        }
                    }
                });
                if q.needs_step {
                    ui.horizontal(|ui| {
                        let label = ui.label("time step [s]");
                        ui.add(egui::TextEdit::singleline(&mut q.step).desired_width(90.0))
                            .labelled_by(label.id);
                    });
                    if ui
                        .add_enabled(
                            q.unit.is_some() && !q.step.trim().is_empty(),
                            egui::Button::new("Open record"),
                        )
                        .clicked()
                    {
                        answer = q.unit;
                    }
                }
                if let Some(e) = &q.error {
                    ui.colored_label(egui::Color32::from_rgb(235, 90, 90), e);
                }
                if ui.button("Cancel").clicked() {
                    cancel = true;
                }
            });
        let step = q.needs_step.then(|| q.step.clone());
        if cancel {
            self.cancel_record();
        } else if let Some(unit) = answer {
            self.answer_record(unit, step.as_deref());
        }
    }
}
