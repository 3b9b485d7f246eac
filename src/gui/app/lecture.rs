//! The lecture-hall extras: the note above the block saying what to look
//! at, the mode legend kept whole inside the block scene, the side panel's
//! tabs, the presentation scale (remembered between sessions) and the
//! fall drawn after a tumble.

use std::path::PathBuf;

use super::{Message, RockingApp};
use crate::gui::lessons::{Lesson, Note};
use crate::gui::panels::scene;
use crate::gui::prefs::{self, Prefs};
use crate::model::Mode;
use crate::model::geometry::Geometry;
use crate::model::kinematics;
use crate::sim::protocol::Sample;

/// How long the drawn fall after a tumble takes, s of wall-clock time:
/// about what a 2 m block takes to fall over, slow enough to follow.
pub(crate) const FALL_S: f64 = 1.2;

/// What the side panel shows when several analyses are open (a narrow
/// window tabs them instead of squeezing the block between columns).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SideTab {
    /// Phase portrait and Poincaré points.
    Plots,
    /// The bifurcation diagram.
    Bifurcation,
    /// The running Lyapunov exponent.
    Lyapunov,
    /// The outcome map (or basin).
    Map,
}

impl SideTab {
    /// The tab's label.
    pub fn name(self) -> &'static str {
        match self {
            Self::Plots => "Phase & Poincaré",
            Self::Bifurcation => "Bifurcation",
            Self::Lyapunov => "Lyapunov",
            Self::Map => "Outcome map",
        }
    }
}

/// Which of the phase portrait and the Poincaré points the side panel
/// shows where it has room for one only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum PlotTab {
    /// The phase portrait.
    #[default]
    Phase,
    /// The Poincaré points.
    Poincare,
}

/// Which of the time history and the plot beside it (power spectrum, or a
/// record's ground acceleration) the bottom panel shows where it has room
/// for one only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum BottomTab {
    /// The time history.
    #[default]
    History,
    /// The power spectrum or the ground acceleration.
    Other,
}

/// The state of the extras.
#[derive(Debug)]
pub(crate) struct Lecture {
    /// The note above the block, if the scene has one.
    pub note: Option<Note>,
    /// Whether the user closed it.
    pub note_hidden: bool,
    /// The side panel's tab.
    pub tab: SideTab,
    /// The tabs the side panel had last frame.
    pub tabs_seen: Vec<SideTab>,
    /// The plot the side panel shows where it shows one.
    pub plot_tab: PlotTab,
    /// The plot the bottom panel shows where it shows one.
    pub bottom_tab: BottomTab,
    /// The presentation scale chosen (remembered): egui's zoom factor
    /// where the window holds it.
    pub scale: f32,
    /// The zoom factor last set: the scale chosen, capped by the window
    /// ([`prefs::max_scale`]).
    pub applied: f32,
    /// Whether the lecture presentation is on (remembered).
    pub presentation: bool,
    /// Where the scale is remembered; `None`: not remembered (tests,
    /// fixed streams).
    pub prefs_path: Option<PathBuf>,
    /// Wall-clock time (egui's input time, s) the drawn fall started.
    pub fall_t0: Option<f64>,
    /// Where the block scene was drawn last frame, points.
    pub scene_rect: Option<egui::Rect>,
}

impl Default for Lecture {
    fn default() -> Self {
        Self {
            note: None,
            note_hidden: false,
            tab: SideTab::Plots,
            tabs_seen: vec![SideTab::Plots],
            plot_tab: PlotTab::default(),
            bottom_tab: BottomTab::default(),
            scale: 1.0,
            applied: 1.0,
            presentation: false,
            prefs_path: None,
            fall_t0: None,
            scene_rect: None,
        }
    }
}

/// The sample to draw `t` seconds into the fall after a tumble at `end`:
/// the block turned about the corner it tumbled over until it lies on its
/// side (|θ| = π/2), that corner held fixed. This is geometry, not
/// mechanics: the model stops at its tumble criterion, and what comes
/// after is drawn, accelerating like a fall (angle ∝ t²) so it reads as one.
pub fn fallen(geo: &Geometry, end: &Sample, t: f64) -> (Sample, bool) {
    let s = if end.theta == 0.0 { 1.0 } else { end.theta.signum() };
    let progress = (t / FALL_S).clamp(0.0, 1.0);
    let theta = end.theta + (s * geo.side_theta() - end.theta) * progress * progress;
    // The corner it tumbled over stays where it was at the tumble.
    let x = kinematics::turned_about_corner(geo, s, end.theta, end.x, theta);
    let mut shown = *end;
    shown.state.theta = theta;
    shown.state.x = x;
    shown.state.theta_dot = 0.0;
    shown.state.mode = Mode::Tumbled;
    (shown, progress >= 1.0)
}

impl RockingApp {
    /// The note shown above the block, if any (and not closed).
    pub fn note(&self) -> Option<&Note> {
        self.lecture.note.as_ref().filter(|_| !self.lecture.note_hidden)
    }

    /// Shows `note` above the block (a scene loaded some other way than
    /// by its preset's name, e.g. a fixed stream in a snapshot).
    pub fn set_note(&mut self, note: Note) {
        self.lecture.note = Some(note);
        self.lecture.note_hidden = false;
    }

    /// Where the block scene (below the note and legend) was drawn last
    /// frame, points.
    pub fn scene_rect(&self) -> Option<egui::Rect> {
        self.lecture.scene_rect
    }

    /// The state the scene drew last frame: the run's latest sample, or
    /// after a tumble the drawn fall.
    pub fn shown_sample(&self) -> Option<&Sample> {
        self.last_shown.as_ref()
    }

    /// What the scene came from (`preset NAME` or a file).
    pub fn settings_origin(&self) -> &str {
        &self.settings.origin
    }

    /// How many ghost copies the app asked for.
    pub fn ghost_count(&self) -> usize {
        self.ghost_count
    }

    /// The ghost copies' latest states.
    pub fn ghosts(&self) -> &[crate::sim::protocol::GhostState] {
        &self.ghosts
    }

    /// The side panel's tab.
    pub fn side_tab(&self) -> SideTab {
        self.lecture.tab
    }

    /// Shows `tab` in the side panel.
    pub fn set_side_tab(&mut self, tab: SideTab) {
        self.lecture.tab = tab;
    }

    /// The presentation scale in effect (egui's zoom factor): the one
    /// chosen, or less where the window does not hold it.
    pub fn presentation_scale(&self) -> f32 {
        self.lecture.applied
    }

    /// Whether the lecture presentation is on.
    pub fn lecture_presentation(&self) -> bool {
        self.lecture.presentation
    }

    /// Turns the lecture presentation on or off, and remembers it.
    pub fn set_lecture_presentation(&mut self, ctx: &egui::Context, on: bool) {
        self.lecture.presentation = on;
        super::style::apply(ctx, super::style::TextSizes::of(on));
        // Its larger text needs more room: the scale may have to give way.
        self.apply_scale(ctx);
        self.save_prefs();
    }

    /// Remembers the presentation scale in `path` from now on (and uses
    /// the one stored there, if any).
    pub fn remember_scale_in(&mut self, ctx: &egui::Context, path: PathBuf) {
        match Prefs::load(&path) {
            Ok(p) => {
                self.lecture.scale = p.scale;
                self.lecture.presentation = p.lecture;
                super::style::apply(ctx, super::style::TextSizes::of(p.lecture));
                self.apply_scale(ctx);
            }
            Err(e) => self.message = Some(Message { text: e, error: true }),
        }
        self.lecture.prefs_path = Some(path);
    }

    /// Remembers the scale where the user's config lives
    /// ([`prefs::default_path`]): the desktop app does, tests do not.
    pub(crate) fn remember_scale(&mut self, ctx: &egui::Context) {
        if let Some(path) = prefs::default_path() {
            self.remember_scale_in(ctx, path);
        }
    }

    /// Sets the presentation scale (clamped to [`prefs::SCALE_RANGE`] and
    /// to what the window holds), and remembers it.
    pub fn set_presentation_scale(&mut self, ctx: &egui::Context, scale: f32) {
        self.lecture.scale = Prefs::clamp_scale(scale).min(self.max_scale(ctx));
        self.apply_scale(ctx);
        self.save_prefs();
    }

    /// The largest scale the window holds ([`prefs::max_scale`]).
    pub(super) fn max_scale(&self, ctx: &egui::Context) -> f32 {
        let window = ctx.content_rect().size() * ctx.zoom_factor();
        prefs::max_scale([window.x, window.y], self.lecture.presentation)
    }

    /// Sets egui's zoom to the scale chosen, capped by the window.
    fn apply_scale(&mut self, ctx: &egui::Context) {
        let z = self.lecture.scale.min(self.max_scale(ctx));
        self.lecture.applied = z;
        if ctx.zoom_factor() != z {
            ctx.set_zoom_factor(z);
        }
    }

    fn save_prefs(&mut self) {
        let prefs = Prefs {
            scale: self.lecture.scale,
            lecture: self.lecture.presentation,
        };
        if let Some(path) = &self.lecture.prefs_path
            && let Err(e) = prefs.save(path)
        {
            self.message = Some(Message { text: e, error: true });
        }
    }

    /// Picks up a scale changed by egui's own Ctrl +/−/0 and stores it;
    /// keeps the zoom within what the window holds (a window made smaller,
    /// or a scale remembered from a larger screen).
    pub(super) fn follow_scale(&mut self, ctx: &egui::Context) {
        if self.exporting_view() {
            return;
        }
        let z = ctx.zoom_factor();
        if z != self.lecture.applied {
            // The keyboard changed it: that is the scale chosen now.
            self.lecture.scale = Prefs::clamp_scale(z).min(self.max_scale(ctx));
            self.apply_scale(ctx);
            self.save_prefs();
        } else {
            self.apply_scale(ctx);
        }
    }

    /// Shows the note of preset `name` (loaded by name: command line,
    /// menu, file). A phenomenon's note may point at an overlay ("the red
    /// arrow is the contact force"), so that overlay is turned on with it;
    /// speed and ghosts stay as the user set them.
    pub(super) fn show_note_of_preset(&mut self, name: &str) {
        self.lecture.note = Note::of_preset(name);
        self.lecture.note_hidden = false;
        if crate::gui::lessons::lesson_of_preset(name).is_some_and(|l| l.forces) {
            self.forces = true;
        }
    }

    /// Loads phenomenon `lesson`: its preset, its note, and how the app
    /// shows it (ghosts, speed, forces).
    pub fn load_lesson(&mut self, lesson: &Lesson) {
        self.load_preset(lesson.preset);
        if self.message.as_ref().is_some_and(|m| m.error) {
            return;
        }
        self.lecture.note = Some(Note::of_lesson(lesson));
        self.lecture.note_hidden = false;
        (self.ghost_count, self.ghost_eps) = lesson.ghosts;
        self.send_ghosts();
        self.speed = lesson.speed;
        self.max_speed = false;
        self.send_speed();
        self.forces = lesson.forces;
    }

    /// The note strip at the top of `ui`: the title in bold, the sentence
    /// wrapped, and a button to close it.
    pub(super) fn note_strip(&mut self, ui: &mut egui::Ui) {
        let Some(note) = self.note().cloned() else {
            return;
        };
        egui::Frame::new()
            .fill(egui::Color32::from_rgb(28, 44, 66))
            .corner_radius(4.0)
            .inner_margin(egui::Margin::symmetric(10, 6))
            .show(ui, |ui| {
                ui.set_width(ui.available_width());
                ui.horizontal(|ui| {
                    ui.label(egui::RichText::new(&note.title).strong().size(17.0));
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        if ui.small_button("×").on_hover_text("Hide this note").clicked() {
                            self.lecture.note_hidden = true;
                        }
                    });
                });
                ui.label(egui::RichText::new(&note.text).size(15.0));
            });
    }
}

/// The mode legend, one swatch and name per contact mode, wrapped to the
/// width it is given so it is never cut off.
pub fn legend(ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.spacing_mut().item_spacing.x = 4.0;
        let font = egui::TextStyle::Body.resolve(ui.style());
        for (i, name) in Mode::NAMES.iter().enumerate() {
            // A swatch and its name stay on one row: start a new row unless
            // both fit (egui wraps between widgets, so the swatch could end
            // one row and its name begin the next, and spacing never wraps,
            // so a trailing gap pushed the row past the scene).
            let text = ui
                .painter()
                .layout_no_wrap((*name).to_owned(), font.clone(), egui::Color32::WHITE)
                .size()
                .x;
            let gap = if i == 0 { 0.0 } else { 8.0 };
            if i > 0 && ui.available_size_before_wrap().x < gap + 12.0 + 4.0 + text + 4.0 {
                ui.end_row();
            } else {
                ui.add_space(gap);
            }
            let (r, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
            ui.painter().rect_filled(r, 2.0, scene::MODE_COLORS[i]);
            ui.label(*name);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::HistoryRow;

    fn at_tumble() -> Sample {
        Sample::still(
            HistoryRow {
                tau: 10.0,
                theta: 1.0,
                theta_dot: 0.3,
                x: 0.02,
                x_dot: 0.0,
                mode: Mode::Tumbled,
            },
            0.0,
        )
    }

    /// The fall ends lying on the side, its centre of mass B/2 above the
    /// base and H/2 beyond the corner it fell over, which never moves.
    #[test]
    fn the_drawn_fall_ends_on_the_side_about_a_fixed_corner() {
        let geo = Geometry::new(1.0, 4.0);
        let end = at_tumble();
        let corner = |s: &Sample| {
            crate::sim::protocol::pose(&geo, s.theta, s.x, s.mode, 0.0)
                .pivot
                .unwrap()
                .0
        };
        let c0 = corner(&end);
        let (mid, done) = fallen(&geo, &end, 0.5 * FALL_S);
        assert!(!done);
        assert!(mid.theta > 1.0 && mid.theta < geo.side_theta());
        assert!((corner(&mid) - c0).abs() < 1e-12);
        let (last, done) = fallen(&geo, &end, 2.0 * FALL_S);
        assert!(done);
        assert!((last.theta * geo.psi - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let p = crate::sim::protocol::pose(&geo, last.theta, last.x, last.mode, 0.0);
        assert!((p.y - 0.5).abs() < 1e-12, "centre at B/2, got {}", p.y);
        assert!(
            (p.x - c0 - 2.0).abs() < 1e-12,
            "H/2 beyond the corner, got {}",
            p.x - c0
        );
    }
}
