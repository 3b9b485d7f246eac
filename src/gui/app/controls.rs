//! The top bar (File, Presets and View menus, playback, perturbation, speed
//! and ghosts) and the keyboard shortcuts that mirror its buttons.

use super::{FileAsk, Message, RockingApp, written};
use crate::gui::export;
use crate::gui::settings::Settings;
use crate::gui::units::Units;
use crate::gui::{glossary, lessons, prefs};
use crate::sim::protocol::{MAX_GHOSTS, Speed};

impl RockingApp {
    /// Space plays or pauses, R resets, S steps, unless a text field has
    /// the keyboard (a parameter slider takes only the arrows).
    pub(super) fn keys(&mut self, ui: &egui::Ui) {
        if ui.ctx().egui_wants_keyboard_input() && !crate::gui::panels::slider::has_keyboard(ui.ctx()) {
            return;
        }
        let (space, r, s) = ui.input(|i| {
            (
                i.key_pressed(egui::Key::Space),
                i.key_pressed(egui::Key::R),
                i.key_pressed(egui::Key::S),
            )
        });
        if space {
            self.toggle_pause();
        }
        if r {
            self.reset();
        }
        if s {
            self.step();
        }
    }

    pub(super) fn controls(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            ui.menu_button("File", |ui| self.file_menu(ui));
            ui.menu_button("Presets", |ui| self.presets_menu(ui));
            ui.menu_button("View", |ui| self.view_menu(ui));
            ui.menu_button("Help", |ui| self.help_menu(ui));
            ui.separator();
            let shown = self.units();
            for units in [Units::Physical, Units::Normalised] {
                let hover = match units {
                    Units::Physical => "t in s, θ in degrees, sliding in cm",
                    Units::Normalised => "the paper's τ = p t, Θ = θ/ψ, X per R (the Help menu says what they mean)",
                };
                if ui
                    .selectable_label(shown == units, units.name())
                    .on_hover_text(hover)
                    .clicked()
                {
                    self.set_units(units);
                }
            }
            ui.separator();
            let label = if self.paused { "Play" } else { "Pause" };
            if ui.button(label).on_hover_text("Space").clicked() {
                self.toggle_pause();
            }
            if ui
                .button("Step")
                .on_hover_text("S: advance one forcing period 2π/Ω_h and pause")
                .clicked()
            {
                self.step();
            }
            if ui.button("Reset").on_hover_text("R: restart from τ = 0").clicked() {
                self.reset();
            }
            if ui
                .button("Reset perturbed")
                .on_hover_text("Restart from the state shown with Θ + ε")
                .clicked()
            {
                self.reset_perturbed();
            }
            let eps_label = ui.label("ε");
            ui.add(
                egui::DragValue::new(&mut self.eps)
                    .range(-0.5..=0.5)
                    .speed(1e-6)
                    .custom_formatter(|v, _| format!("{v:.1e}")),
            )
            .labelled_by(eps_label.id)
            .on_hover_text("Perturbation of Θ for Reset perturbed, units of ψ");
            ui.separator();
            // The speed slider draws its number beside it in a layout of
            // its own, which cannot wrap: start a new row unless label,
            // slider and number all fit (else the bar grows past the
            // window and pushes the right-hand panels off screen).
            if ui.available_size_before_wrap().x < 190.0 {
                ui.end_row();
            }
            let speed_label = ui.label("Speed");
            // Narrower than egui's 100 pt: the whole bar fits one line of a
            // 1280-pixel window.
            ui.spacing_mut().slider_width = 72.0;
            let r = ui
                .add_enabled(
                    !self.max_speed,
                    egui::Slider::new(&mut self.speed, Speed::MIN_MULTIPLE..=Speed::MAX_MULTIPLE)
                        .logarithmic(true)
                        .suffix("×")
                        .max_decimals(2),
                )
                .labelled_by(speed_label.id)
                .on_hover_text("Multiple of real time in the block's physical seconds (1 s = p τ)");
            if r.changed() {
                self.send_speed();
            }
            if ui.checkbox(&mut self.max_speed, "max").changed() {
                self.send_speed();
            }
            ui.separator();
            let ghosts_label = ui.label("Ghosts");
            let r = ui
                .add(egui::DragValue::new(&mut self.ghost_count).range(0..=MAX_GHOSTS))
                .labelled_by(ghosts_label.id)
                .on_hover_text(
                    "Copies started from Θ perturbed by up to the ghost ε, each outlined in a colour of its own",
                );
            let eps_label = ui.label("ghost ε");
            let r2 = ui
                .add(
                    egui::DragValue::new(&mut self.ghost_eps)
                        .range(1e-12..=0.5)
                        .speed(1e-4)
                        .custom_formatter(|v, _| format!("{v:.1e}")),
                )
                .labelled_by(eps_label.id);
            if r.changed() || r2.changed() {
                self.send_ghosts();
            }
        });
    }

    /// Presets ▸ Phenomena (each with its note), The paper's figures (each
    /// saying what the paper claims and what this model shows) and
    /// Engineering (real records).
    fn presets_menu(&mut self, ui: &mut egui::Ui) {
        ui.menu_button("Phenomena", |ui| {
            for lesson in lessons::PHENOMENA {
                if ui.button(lesson.title).on_hover_text(lesson.look).clicked() {
                    self.load_lesson(lesson);
                    ui.close();
                }
            }
        });
        ui.menu_button("The paper's figures", |ui| {
            for (name, says) in lessons::FIGURES {
                let label = format!("{name}: {}", lessons::figure_title(name));
                if ui.button(label).on_hover_text(*says).clicked() {
                    self.load_preset(name);
                    ui.close();
                }
            }
        });
        ui.menu_button("Engineering", |ui| {
            for name in lessons::ENGINEERING {
                let label = format!("{name}: {}", lessons::figure_title(name));
                if ui.button(label).clicked() {
                    self.load_preset(name);
                    ui.close();
                }
            }
        });
        ui.menu_button("Stacks of blocks", |ui| {
            for name in lessons::STACKS {
                let label = format!("{name}: {}", lessons::figure_title(name));
                if ui.button(label).clicked() {
                    self.load_preset(name);
                    ui.close();
                }
            }
        });
        ui.separator();
        if ui
            .button("default: chaotic rocking with sliding")
            .on_hover_text(lessons::figure_title("default"))
            .clicked()
        {
            self.load_preset("default");
            ui.close();
        }
    }

    /// View ▸ panels, the contact force, and the presentation scale.
    fn view_menu(&mut self, ui: &mut egui::Ui) {
        ui.checkbox(&mut self.show.params, "Parameters");
        ui.checkbox(&mut self.show.scene, "Block scene");
        ui.checkbox(&mut self.show.phase, "Phase portrait");
        ui.checkbox(&mut self.show.poincare, "Poincaré points");
        ui.checkbox(&mut self.show.history, "Time history");
        ui.checkbox(&mut self.show.spectrum, "Power spectrum");
        // Opening an analysis brings its tab to the front (side_panel).
        ui.checkbox(&mut self.show.bifurcation, "Bifurcation diagram");
        ui.checkbox(&mut self.show.lyapunov, "Lyapunov exponent");
        ui.checkbox(&mut self.show.map, "Outcome map");
        ui.separator();
        ui.checkbox(&mut self.forces, "Contact force and friction cone");
        ui.separator();
        let mut lecture = self.lecture_presentation();
        if ui
            .checkbox(&mut lecture, "Lecture presentation")
            .on_hover_text("Larger text, plot numbers at 20 px, and the phase portrait and Poincaré points as tabs so each keeps a large plot")
            .changed()
        {
            self.set_lecture_presentation(ui.ctx(), lecture);
        }
        let now = self.presentation_scale();
        ui.label("Presentation scale (Ctrl + / Ctrl − / Ctrl 0)");
        // Only the scales this window holds: at a larger one the panels
        // would not fit beside the block (prefs::MIN_LAYOUT_POINTS).
        let top = self.max_scale(ui.ctx());
        ui.horizontal_wrapped(|ui| {
            for scale in prefs::SCALES {
                let on = (now - scale).abs() < 0.01;
                let fits = scale <= top + 1e-4;
                let r = ui.add_enabled(fits, egui::Button::selectable(on, format!("{:.0} %", 100.0 * scale)));
                let r = if fits {
                    r
                } else {
                    let [w, h] = if lecture {
                        prefs::LECTURE_LAYOUT_POINTS
                    } else {
                        prefs::MIN_LAYOUT_POINTS
                    };
                    r.on_disabled_hover_text(format!(
                        "needs a window of at least {:.0} × {:.0} pixels",
                        w * scale,
                        h * scale
                    ))
                };
                if r.clicked() {
                    self.set_presentation_scale(ui.ctx(), scale);
                }
            }
        });
    }

    /// Help ▸ Symbols: Θ, τ, ψ and p in one sentence each.
    fn help_menu(&mut self, ui: &mut egui::Ui) {
        ui.label(egui::RichText::new("Symbols").strong());
        ui.set_max_width(460.0);
        let geo = self
            .info
            .as_ref()
            .map_or_else(|| self.config.geometry(), |i| i.geometry);
        for (symbol, sentence) in glossary::entries(&geo) {
            ui.horizontal_wrapped(|ui| {
                ui.label(egui::RichText::new(symbol).strong().size(18.0));
                ui.label(sentence);
            });
        }
        ui.separator();
        ui.label("Keys: Space play/pause · S step · R reset · Ctrl +/− presentation scale");
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        if ui.button("Open scene…").clicked() {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::OpenScene);
        }
        if ui.button("Open record…").clicked() {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::OpenRecord);
        }
        if ui.button("Save scene…").clicked() {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::SaveScene);
        }
        if ui.button("Export plots (PNG)…").clicked() {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::ExportPlots);
        }
        if ui.button("Export data (CSV)…").clicked() {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::ExportData);
        }
        ui.separator();
        if ui
            .button("Export view (PNG)…")
            .on_hover_text(
                "The window as it is, at least 1920 × 1080 pixels (a small window is drawn again with more pixels)",
            )
            .clicked()
        {
            ui.close();
            self.ask_file(ui.ctx(), FileAsk::ExportView);
        }
        let busy = self.sharing_busy();
        if ui
            .add_enabled(!busy, egui::Button::new("Record GIF…"))
            .on_hover_text("A few seconds of the window, as it plays, as an animated GIF for slides")
            .clicked()
        {
            ui.close();
            self.open_gif_dialog();
        }
    }

    /// Makes the scene in `path` (TOML or summary.json) the scene, or says
    /// why not; the scene loaded has no unsaved changes.
    pub fn open_scene(&mut self, path: &std::path::Path) {
        match Settings::open(path) {
            Ok((s, c)) => {
                self.apply(s, c);
                self.mark_clean();
            }
            Err(e) => self.message = Some(Message { text: e, error: true }),
        }
    }

    /// Saves the scene's explicit keys to `path` (TOML); once saved, the
    /// scene is that file's, with no unsaved changes.
    pub fn save_scene(&mut self, path: &std::path::Path) {
        let r = self
            .settings
            .to_toml()
            .and_then(|t| export::write_atomic(path, t.as_bytes()));
        if r.is_ok() {
            self.settings.origin = path.display().to_string();
            self.mark_clean();
        }
        self.message = Some(written(r, || format!("saved {}", path.display())));
    }
}
