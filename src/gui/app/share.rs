//! Sharing what the app shows: the window title (the scene's name and an
//! unsaved-changes mark), recording an animated GIF of the window, and one
//! PNG of it at presentation resolution. The GIF's frames are egui's
//! screenshots ([`egui::Context::request_screenshot`]); the PNG is the app
//! drawn off screen ([`super::offscreen`]). The files are encoded and
//! written by [`crate::gui::capture`] on background threads.
//!
//! Everything here advances once a frame, in [`RockingApp::share_tick`]:
//! the status bar calls it, so it runs in every frame the app draws. The
//! view's PNG is drawn in [`RockingApp::share_logic`], which has the frame.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crossbeam_channel::{Receiver, Sender};

use super::{Message, RockingApp};
use crate::gui::capture::{self, GifOptions, Shot, Written};

/// The width a PNG of the view has at least, physical pixels: a 1080p
/// projector's.
pub(crate) const PRESENTATION_WIDTH: f32 = 1920.0;

/// The height it has at least, physical pixels.
pub(crate) const PRESENTATION_HEIGHT: f32 = 1080.0;

/// The window title for a scene from `origin` (a preset, `preset NAME`, or
/// a file path), with `•` after it while it has unsaved changes:
/// `rocking — fig7`, `rocking — scene.toml •`. A path is shortened to its
/// file name: the title bar has no room for directories.
pub fn window_title(origin: &str, dirty: bool) -> String {
    let name = match origin.strip_prefix("preset ") {
        Some(preset) => preset.to_string(),
        None => Path::new(origin)
            .file_name()
            .map_or_else(|| origin.to_string(), |n| n.to_string_lossy().into_owned()),
    };
    let name = if name.is_empty() { "untitled".to_string() } else { name };
    if dirty {
        format!("rocking — {name} •")
    } else {
        format!("rocking — {name}")
    }
}

/// A GIF being recorded.
struct Recording {
    path: PathBuf,
    options: GifOptions,
    /// The egui pass in which the file was chosen: that frame may still
    /// show the dialog that asked (or come after a desktop dialog held
    /// the app for as long as it was open), so the clock starts in the
    /// next one.
    chosen_pass: u64,
    /// When it started, s of egui time; `None` until the first frame
    /// after the file was chosen.
    start: Option<f64>,
    /// When the next frame is due, s of egui time.
    next: f64,
    /// Frames asked for so far.
    asked: usize,
    tx: Sender<Shot>,
    done: Receiver<Result<Written, String>>,
}

/// A PNG export of the view, drawn off screen in the next frame's
/// [`eframe::App::logic`] ([`super::offscreen`]).
struct ViewExport {
    path: PathBuf,
    /// Pixels per point of the picture over the window's.
    scale: f32,
}

/// The sharing state of the app.
#[derive(Default)]
pub(crate) struct Share {
    /// The title last sent to the window.
    title_sent: Option<String>,
    /// The scene as last loaded or saved: its origin and explicit keys.
    clean: Option<(String, toml::Table)>,
    /// The GIF options window, while open.
    gif_dialog: Option<GifOptions>,
    recording: Option<Recording>,
    /// GIFs whose writer is finishing.
    encoding: Vec<Receiver<Result<Written, String>>>,
    view: Option<ViewExport>,
    /// PNGs being written.
    writing: Vec<Receiver<Result<Written, String>>>,
    /// Whether the app's `ui` is running for the off-screen picture (its
    /// sharing tick then does nothing).
    pub(super) offscreen: bool,
}

impl RockingApp {
    /// Whether the scene has changes not saved since it was loaded or saved.
    pub fn scene_dirty(&self) -> bool {
        match &self.share.clean {
            Some((origin, table)) if *origin == self.settings.origin => *table != self.settings.table,
            // A scene loaded since the last frame is clean.
            Some(_) | None => false,
        }
    }

    /// The window title for the scene now.
    pub fn title(&self) -> String {
        window_title(&self.settings.origin, self.scene_dirty())
    }

    /// Whether a PNG export of the view is under way: its off-screen
    /// pass runs the app's `ui` with another zoom and size, which are not
    /// the user's.
    pub(super) fn exporting_view(&self) -> bool {
        self.share.view.is_some() || self.share.offscreen
    }

    /// Takes the settings now as the clean state (after a load or a save).
    pub(super) fn mark_clean(&mut self) {
        self.share.clean = Some((self.settings.origin.clone(), self.settings.table.clone()));
    }

    /// Whether a GIF is being recorded.
    pub fn recording(&self) -> bool {
        self.share.recording.is_some()
    }

    /// Whether a picture is being taken or written.
    pub fn sharing_busy(&self) -> bool {
        self.share.recording.is_some()
            || !self.share.encoding.is_empty()
            || self.share.view.is_some()
            || !self.share.writing.is_empty()
    }

    /// Opens the GIF options window (File ▸ Record GIF…).
    pub(super) fn open_gif_dialog(&mut self) {
        if self.share.gif_dialog.is_none() {
            self.share.gif_dialog = Some(GifOptions::default());
        }
    }

    /// Starts recording `options.seconds` of the window into a GIF at
    /// `path`, written when the recording ends. The clock starts in the
    /// frame after this call, however long this frame took (a desktop
    /// file dialog blocks the frame that opened it).
    pub fn record_gif(&mut self, ctx: &egui::Context, path: PathBuf, options: GifOptions) {
        if self.sharing_busy() {
            self.message = Some(Message {
                text: "a picture is already being taken".into(),
                error: true,
            });
            return;
        }
        let waker = ctx.clone();
        let (tx, done) = capture::spawn_gif_writer(path.clone(), options, move || waker.request_repaint());
        self.share.recording = Some(Recording {
            path,
            options,
            chosen_pass: ctx.cumulative_pass_nr(),
            start: None,
            next: 0.0,
            asked: 0,
            tx,
            done,
        });
        ctx.request_repaint();
    }

    /// Takes a PNG of the window at `path`, at least
    /// [`PRESENTATION_WIDTH`] × [`PRESENTATION_HEIGHT`] physical pixels:
    /// a smaller window is drawn once more off screen, in its own layout,
    /// with the pixels per point raised by the factor missing (the window
    /// itself is left alone). The status line says the size written.
    pub fn export_view(&mut self, ctx: &egui::Context, path: PathBuf) {
        if self.sharing_busy() {
            self.message = Some(Message {
                text: "a picture is already being taken".into(),
                error: true,
            });
            return;
        }
        let pixels = ctx.content_rect().size() * ctx.pixels_per_point();
        let scale = (PRESENTATION_WIDTH / pixels.x)
            .max(PRESENTATION_HEIGHT / pixels.y)
            .max(1.0);
        self.share.view = Some(ViewExport { path, scale });
        ctx.request_repaint();
    }

    /// The sharing work that needs the frame: the PNG export of the view,
    /// drawn off screen (from [`eframe::App::logic`]).
    pub(super) fn share_logic(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        if self.share.offscreen {
            return;
        }
        let Some(view) = self.share.view.take() else {
            return;
        };
        match self.draw_offscreen(ctx, frame, view.scale) {
            Ok(img) => {
                let waker = ctx.clone();
                self.share
                    .writing
                    .push(capture::spawn_png_writer(view.path, Arc::new(img), move || {
                        waker.request_repaint()
                    }));
            }
            Err(e) => {
                self.message = Some(Message {
                    text: format!("{}: the view could not be drawn: {e}", view.path.display()),
                    error: true,
                });
            }
        }
    }

    /// One frame of sharing: the title, the recording, the view export and
    /// the writers' results.
    pub(super) fn share_tick(&mut self, ctx: &egui::Context) {
        if self.share.offscreen {
            return;
        }
        if self
            .share
            .clean
            .as_ref()
            .is_none_or(|(origin, _)| *origin != self.settings.origin)
        {
            self.mark_clean();
        }
        let title = self.title();
        if self.share.title_sent.as_ref() != Some(&title) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.share.title_sent = Some(title);
        }
        self.gif_window(ctx);
        self.path_window_ui(ctx);
        self.tick_recording(ctx);
        self.collect_written();
    }

    fn tick_recording(&mut self, ctx: &egui::Context) {
        let Some(rec) = self.share.recording.as_mut() else {
            return;
        };
        let now = ctx.input(|i| i.time);
        let start = match rec.start {
            Some(start) => start,
            None if ctx.cumulative_pass_nr() > rec.chosen_pass => {
                rec.next = now;
                *rec.start.insert(now)
            }
            None => {
                ctx.request_repaint();
                return;
            }
        };
        let end = start + f64::from(rec.options.seconds);
        if now >= end {
            // The clip's nominal end: the last frame is held until then.
            let _ = rec.tx.send(Shot::End(end));
            let rec = self.share.recording.take().expect("checked above");
            self.share.encoding.push(rec.done);
            self.message = Some(Message {
                text: format!("writing {}: encoding {} frames…", file_name(&rec.path), rec.asked),
                error: false,
            });
            return;
        }
        let dt = 1.0 / f64::from(rec.options.fps.max(0.1));
        if now >= rec.next {
            let tx = rec.tx.clone();
            let t = now;
            ctx.request_screenshot(move |img| {
                // The writer has gone only after a cancel: nothing to do.
                let _ = tx.send(Shot::Frame(t, img));
            });
            rec.asked += 1;
            // On schedule, but never a burst to catch up after a slow frame.
            rec.next = (rec.next + dt).max(now + 0.5 * dt);
        }
        ctx.request_repaint_after(std::time::Duration::from_secs_f64((rec.next - now).max(0.0)));
    }

    /// Reports the writers that have finished.
    fn collect_written(&mut self) {
        let share = &mut self.share;
        let mut done = Vec::new();
        for list in [&mut share.encoding, &mut share.writing] {
            list.retain(|rx| match rx.try_recv() {
                Ok(r) => {
                    done.push(r);
                    false
                }
                Err(crossbeam_channel::TryRecvError::Empty) => true,
                Err(crossbeam_channel::TryRecvError::Disconnected) => {
                    done.push(Err("the writer stopped without a word".into()));
                    false
                }
            });
        }
        for r in done {
            self.message = Some(match r {
                Ok(w) => Message {
                    text: w.line(),
                    error: false,
                },
                Err(e) => Message { text: e, error: true },
            });
        }
    }

    /// The status-bar text while recording: `recording… 3.2 s of 5.0 s`
    /// (`0.0 s` until the clock starts).
    pub(super) fn recording_label(&self, now: f64) -> Option<String> {
        let rec = self.share.recording.as_ref()?;
        let done = rec.start.map_or(0.0, |start| (now - start).max(0.0));
        Some(format!(
            "recording… {:.1} s of {:.1} s",
            done.min(f64::from(rec.options.seconds)),
            rec.options.seconds
        ))
    }

    /// The GIF options window, while open.
    fn gif_window(&mut self, ctx: &egui::Context) {
        let Some(opts) = self.share.gif_dialog.as_mut() else {
            return;
        };
        let mut start = false;
        let mut close = false;
        egui::Window::new("Record GIF")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
            .show(ctx, |ui| {
                ui.label("Records the whole window, as it plays, into an animated GIF.");
                egui::Grid::new("gif options").num_columns(2).show(ui, |ui| {
                    let l = ui.label("Duration");
                    ui.add(egui::Slider::new(&mut opts.seconds, 1.0..=30.0).suffix(" s"))
                        .labelled_by(l.id);
                    ui.end_row();
                    let l = ui.label("Frames per second");
                    ui.add(egui::Slider::new(&mut opts.fps, 5.0..=30.0).step_by(1.0))
                        .labelled_by(l.id);
                    ui.end_row();
                    let l = ui.label("Width at most");
                    ui.add(egui::Slider::new(&mut opts.max_width, 320..=1920).suffix(" px"))
                        .labelled_by(l.id);
                    ui.end_row();
                });
                ui.horizontal(|ui| {
                    start = ui.button("Record…").clicked();
                    close = ui.button("Cancel").clicked();
                });
            });
        if close {
            self.share.gif_dialog = None;
        } else if start {
            let options = *opts;
            // The file first: the recording starts once it is chosen.
            self.share.gif_dialog = None;
            self.ask_file(ctx, super::FileAsk::RecordGif(options));
        }
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}
