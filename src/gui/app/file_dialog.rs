//! Asking for a path (every File menu item): through the desktop's file
//! dialog when one can open, else through a path window inside the app.
//!
//! The desktop's dialog is rfd's xdg-desktop-portal backend (no GTK: see
//! ECOSYSTEM.md §2), which falls back to `zenity`. When neither can open
//! (no D-Bus session bus, no `org.freedesktop.portal.Desktop` on it, no
//! zenity) rfd logs the failure and returns `None` at once, the same
//! `None` as a cancel. How the two are told apart: a dialog a person
//! opens and then cancels stays on screen longer than [`NO_DIALOG_S`]; a
//! `None` sooner than that means no dialog was shown. The app then says so
//! in the status bar and opens the path window in its place. The check
//! is made at every ask (a failed one costs a few milliseconds), so a
//! portal started later is used, and a mistaken verdict costs nothing
//! worse than the path window.
//!
//! `ROCKING_FILE_DIALOG=app` skips the desktop's dialog for the whole
//! session (a remote session whose portal would open the dialog on
//! another screen, a kiosk, the tests).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::{Message, RockingApp, written};
use crate::gui::capture::GifOptions;
use crate::gui::export;

/// A `None` from the desktop's dialog sooner than this, s, means no
/// dialog opened: the portal's window takes a few tenths of a second to
/// appear and a person another few to press Cancel, while a missing
/// portal or zenity answers in milliseconds.
pub(crate) const NO_DIALOG_S: f64 = 0.3;

/// The environment variable that chooses the dialog: `app` for the path
/// window only; anything else, or unset, for the desktop's dialog first.
pub(crate) const ENV: &str = "ROCKING_FILE_DIALOG";

/// The status-bar line when the desktop's dialog could not open (short:
/// one line of the status bar; the path window says why).
pub const NO_DIALOG: &str = "no file dialog could open: type the path instead";

/// Why, in the path window.
const NO_DIALOG_WHY: &str = "No file dialog could open: the desktop has no xdg-desktop-portal and no zenity.";

/// What a path is asked for: one per File menu item.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FileAsk {
    /// File ▸ Open scene… (TOML or summary.json).
    OpenScene,
    /// File ▸ Open record… (a ground-motion record, any extension).
    OpenRecord,
    /// File ▸ Save scene… (TOML).
    SaveScene,
    /// File ▸ Export plots (PNG)…
    ExportPlots,
    /// File ▸ Export data (CSV)…: a folder for the three CSV files.
    ExportData,
    /// File ▸ Export view (PNG)…
    ExportView,
    /// File ▸ Record GIF… ▸ Record…, with the options chosen.
    RecordGif(GifOptions),
}

/// What kind of path an ask wants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathKind {
    /// An existing file to read.
    Open,
    /// A file to write, new or replaced, in an existing folder.
    Save,
    /// An existing folder.
    Folder,
}

impl FileAsk {
    /// The dialog's title.
    pub fn title(self) -> &'static str {
        match self {
            Self::OpenScene => "Open a scene",
            Self::OpenRecord => "Open a ground-motion record",
            Self::SaveScene => "Save the scene",
            Self::ExportPlots => "Export the plots as PNG",
            Self::ExportData => "Export the data as CSV into a folder",
            Self::ExportView => "Export the view as PNG",
            Self::RecordGif(_) => "Record a GIF",
        }
    }

    /// The kind of path it wants.
    pub fn kind(self) -> PathKind {
        match self {
            Self::OpenScene | Self::OpenRecord => PathKind::Open,
            Self::SaveScene | Self::ExportPlots | Self::ExportView | Self::RecordGif(_) => PathKind::Save,
            Self::ExportData => PathKind::Folder,
        }
    }

    /// The file name proposed for a file to write, with its extension.
    pub(crate) fn proposed_name(self) -> Option<&'static str> {
        match self {
            Self::SaveScene => Some("scene.toml"),
            Self::ExportPlots => Some("plots.png"),
            Self::ExportView => Some("rocking.png"),
            Self::RecordGif(_) => Some("rocking.gif"),
            Self::OpenScene | Self::OpenRecord | Self::ExportData => None,
        }
    }

    /// The file filter: its name and extensions. None for a record
    /// (records come as .AT2, .V1, .V2, .V2c, .ASC, .dat, .txt, .acc, .csv,
    /// …) and a folder.
    fn filter(self) -> Option<(&'static str, &'static [&'static str])> {
        match self {
            Self::OpenScene => Some(("scene", &["toml", "json"])),
            Self::SaveScene => Some(("scene", &["toml"])),
            Self::ExportPlots | Self::ExportView => Some(("PNG", &["png"])),
            Self::RecordGif(_) => Some(("GIF", &["gif"])),
            Self::OpenRecord | Self::ExportData => None,
        }
    }
}

/// A desktop dialog: asks for `ask`'s path starting in the folder given;
/// `None` when cancelled or when no dialog could open.
pub type NativeDialog = fn(FileAsk, &Path) -> Option<PathBuf>;

/// The desktop's dialog through rfd (blocks until it closes).
pub(crate) fn rfd_dialog(ask: FileAsk, dir: &Path) -> Option<PathBuf> {
    let mut d = rfd::FileDialog::new().set_title(ask.title()).set_directory(dir);
    if let Some((name, exts)) = ask.filter() {
        d = d.add_filter(name, exts);
    }
    if let Some(name) = ask.proposed_name() {
        d = d.set_file_name(name);
    }
    match ask.kind() {
        PathKind::Open => d.pick_file(),
        PathKind::Save => d.save_file(),
        PathKind::Folder => d.pick_folder(),
    }
}

/// The dialog an environment value of [`ENV`] chooses: `app` (any case)
/// for none (the path window only), else rfd's.
pub(crate) fn native_from_env(value: Option<&str>) -> Option<NativeDialog> {
    match value {
        Some(v) if v.trim().eq_ignore_ascii_case("app") => None,
        Some(_) | None => Some(rfd_dialog),
    }
}

/// `text` typed for `ask` as the path it names, or why it cannot be used.
/// A relative path is taken from `base`; a leading `~` is the home
/// folder. A file to write without an extension gets the proposed one.
pub(crate) fn check_path(ask: FileAsk, text: &str, base: &Path) -> Result<PathBuf, String> {
    let text = text.trim();
    if text.is_empty() {
        return Err("type a path".into());
    }
    let home = std::env::var_os("HOME").map(PathBuf::from);
    let path = match (text.strip_prefix('~'), home) {
        (Some(rest), Some(home)) if rest.is_empty() || rest.starts_with('/') => home.join(rest.trim_start_matches('/')),
        _ => PathBuf::from(text),
    };
    let path = if path.is_relative() { base.join(path) } else { path };
    let shown = path.display();
    match ask.kind() {
        PathKind::Open => {
            if path.is_dir() {
                Err(format!("{shown} is a folder: add the file's name"))
            } else if !path.is_file() {
                Err(format!("no such file: {shown}"))
            } else {
                Ok(path)
            }
        }
        PathKind::Folder => {
            if path.is_dir() {
                Ok(path)
            } else if path.exists() {
                Err(format!("{shown} is a file: the CSV files go into a folder"))
            } else {
                Err(format!("no such folder: {shown}"))
            }
        }
        PathKind::Save => {
            if path.is_dir() || text.ends_with('/') {
                return Err(format!("{shown} is a folder: add a file name"));
            }
            let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
            if let Some(parent) = parent
                && !parent.is_dir()
            {
                return Err(format!("no such folder: {}", parent.display()));
            }
            let ext = ask
                .proposed_name()
                .and_then(|n| Path::new(n).extension())
                .map(|e| e.to_os_string());
            match ext {
                Some(ext) if path.extension().is_none() => Ok(path.with_extension(ext)),
                Some(_) | None => Ok(path),
            }
        }
    }
}

/// The text the path window starts with: the proposed file in `dir`, or
/// `dir` itself (with a separator, ready for a file name).
pub(crate) fn proposed_text(ask: FileAsk, dir: &Path) -> String {
    match (ask.kind(), ask.proposed_name()) {
        (PathKind::Save, Some(name)) => dir.join(name).display().to_string(),
        (PathKind::Folder, _) => dir.display().to_string(),
        (PathKind::Open | PathKind::Save, _) => {
            let mut s = dir.display().to_string();
            if !s.ends_with('/') {
                s.push('/');
            }
            s
        }
    }
}

/// The path window, while open.
struct PathWindow {
    ask: FileAsk,
    text: String,
    /// Why the last OK was refused.
    error: Option<String>,
    /// Whether the text field has been given the keyboard yet.
    focused: bool,
    /// Whether it stands in for a desktop dialog that could not open.
    fallback: bool,
}

/// How the app asks for paths.
pub(crate) struct FileDialogs {
    /// The desktop's dialog, tried first; `None`: the path window only.
    native: Option<NativeDialog>,
    /// The folder proposed: the last one a path was chosen in, at first
    /// the working folder.
    dir: PathBuf,
    window: Option<PathWindow>,
}

impl Default for FileDialogs {
    fn default() -> Self {
        let dir = std::env::current_dir()
            .ok()
            .or_else(|| std::env::var_os("HOME").map(PathBuf::from))
            .unwrap_or_else(|| PathBuf::from("."));
        Self {
            native: native_from_env(std::env::var(ENV).ok().as_deref()),
            dir,
            window: None,
        }
    }
}

impl RockingApp {
    /// Asks for the path `ask` needs, then does what the menu item does
    /// with it. The desktop's dialog first (blocking, as desktop dialogs
    /// are); if it could not open, the status bar says so and the path
    /// window opens.
    pub(crate) fn ask_file(&mut self, ctx: &egui::Context, ask: FileAsk) {
        let mut fallback = false;
        if let Some(native) = self.files.native {
            let asked = Instant::now();
            let dir = self.files.dir.clone();
            match native(ask, &dir) {
                Some(path) => {
                    self.file_chosen(ctx, ask, path);
                    return;
                }
                None if asked.elapsed() >= Duration::from_secs_f64(NO_DIALOG_S) => return,
                None => {
                    fallback = true;
                    self.message = Some(Message {
                        text: NO_DIALOG.into(),
                        error: true,
                    });
                }
            }
        }
        self.files.window = Some(PathWindow {
            ask,
            text: proposed_text(ask, &self.files.dir),
            error: None,
            focused: false,
            fallback,
        });
        ctx.request_repaint();
    }

    /// Sets the desktop dialog tried first (`None`: the path window only,
    /// as `ROCKING_FILE_DIALOG=app` does).
    pub fn set_native_file_dialog(&mut self, native: Option<NativeDialog>) {
        self.files.native = native;
    }

    /// What the open path window asks for, if one is open.
    pub fn path_window(&self) -> Option<FileAsk> {
        self.files.window.as_ref().map(|w| w.ask)
    }

    /// Does with `path` what `ask`'s menu item does.
    fn file_chosen(&mut self, ctx: &egui::Context, ask: FileAsk, path: PathBuf) {
        let dir = match ask.kind() {
            PathKind::Folder => Some(path.as_path()),
            PathKind::Open | PathKind::Save => path.parent(),
        };
        if let Some(dir) = dir.filter(|d| d.is_dir()) {
            self.files.dir = dir.to_path_buf();
        }
        match ask {
            FileAsk::OpenScene => self.open_scene(&path),
            FileAsk::OpenRecord => self.open_record(&path),
            FileAsk::SaveScene => self.save_scene(&path),
            FileAsk::ExportPlots => {
                let r = export::plots_png(
                    &path,
                    &self.hist,
                    self.tau,
                    self.history_view.window,
                    self.phase.trail_tau,
                );
                self.message = Some(written(r, || format!("wrote {}", path.display())));
            }
            FileAsk::ExportData => match &self.info {
                // The block's CSV columns would hold one block of the
                // stack and none of its events: a wrong file.
                Some(info) if info.stack.is_some() => {
                    self.message = Some(Message {
                        text: "a stack's data come from rocking --batch (every block's history.csv and events.csv with its body); the app exports a block's".into(),
                        error: false,
                    });
                }
                Some(info) => {
                    let r = export::data_csv(&path, &self.hist, &info.geometry);
                    self.message = Some(written(r, || {
                        format!("wrote history.csv, poincare.csv, events.csv in {}", path.display())
                    }));
                }
                None => {
                    self.message = Some(Message {
                        text: "nothing to export yet: the run has not started".into(),
                        error: true,
                    });
                }
            },
            FileAsk::ExportView => self.export_view(ctx, path),
            FileAsk::RecordGif(options) => self.record_gif(ctx, path, options),
        }
    }

    /// The path window, while open: a text field with the path, OK
    /// (Enter) and Cancel (Escape), and why a path was refused.
    pub(super) fn path_window_ui(&mut self, ctx: &egui::Context) {
        let Some(w) = self.files.window.as_mut() else {
            return;
        };
        let mut ok = false;
        let mut cancel = ctx.input(|i| i.key_pressed(egui::Key::Escape));
        let base = self.files.dir.clone();
        egui::Window::new(w.ask.title())
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
            .show(ctx, |ui| {
                if w.fallback {
                    ui.label(egui::RichText::new(NO_DIALOG_WHY).weak());
                }
                let what = match w.ask.kind() {
                    PathKind::Open => "The file to open:",
                    PathKind::Save => "The file to write:",
                    PathKind::Folder => "The folder to write into:",
                };
                ui.label(what);
                let label = ui.label("Path");
                let r = ui
                    .add(egui::TextEdit::singleline(&mut w.text).desired_width(520.0))
                    .labelled_by(label.id);
                if !w.focused {
                    r.request_focus();
                    w.focused = true;
                }
                if r.changed() {
                    w.error = None;
                }
                if r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                    ok = true;
                }
                if w.ask.kind() == PathKind::Save
                    && let Ok(p) = check_path(w.ask, &w.text, &base)
                    && p.is_file()
                {
                    ui.label(egui::RichText::new(format!("{} exists: OK replaces it", file_name(&p))).weak());
                }
                if let Some(e) = &w.error {
                    ui.colored_label(egui::Color32::from_rgb(235, 90, 90), e);
                }
                ui.horizontal(|ui| {
                    ok |= ui.button("OK").on_hover_text("Enter").clicked();
                    cancel |= ui.button("Cancel").on_hover_text("Escape").clicked();
                });
            });
        if cancel {
            self.files.window = None;
        } else if ok {
            let ask = w.ask;
            match check_path(ask, &w.text, &base) {
                Ok(path) => {
                    self.files.window = None;
                    self.file_chosen(ctx, ask, path);
                }
                Err(e) => {
                    w.error = Some(e);
                    // Back to the field, to correct it.
                    w.focused = false;
                }
            }
        }
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rocking-path-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        dir
    }

    #[test]
    fn a_path_to_write_needs_an_existing_folder_and_gets_its_extension() {
        let dir = temp("save");
        let ask = FileAsk::SaveScene;
        assert_eq!(check_path(ask, "talk", &dir), Ok(dir.join("talk.toml")));
        assert_eq!(check_path(ask, " talk.toml ", &dir), Ok(dir.join("talk.toml")));
        let abs = dir.join("b.toml").display().to_string();
        assert_eq!(check_path(ask, &abs, Path::new("/elsewhere")), Ok(dir.join("b.toml")));
        let e = check_path(ask, "no/such/folder/a.toml", &dir).expect_err("no folder");
        assert!(e.starts_with("no such folder: ") && e.contains("no/such/folder"), "{e}");
        let e = check_path(ask, &dir.display().to_string(), &dir).expect_err("a folder");
        assert!(e.contains("is a folder"), "{e}");
        assert_eq!(check_path(ask, "  ", &dir), Err("type a path".into()));
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_path_to_open_must_be_an_existing_file_and_a_folder_an_existing_folder() {
        let dir = temp("open");
        std::fs::write(dir.join("a.toml"), "").expect("write");
        assert_eq!(check_path(FileAsk::OpenScene, "a.toml", &dir), Ok(dir.join("a.toml")));
        let e = check_path(FileAsk::OpenScene, "b.toml", &dir).expect_err("missing");
        assert!(e.starts_with("no such file: "), "{e}");
        let e = check_path(FileAsk::OpenRecord, ".", &dir).expect_err("a folder");
        assert!(e.contains("is a folder"), "{e}");
        assert_eq!(check_path(FileAsk::ExportData, ".", &dir), Ok(dir.join(".")));
        let e = check_path(FileAsk::ExportData, "a.toml", &dir).expect_err("a file");
        assert!(e.contains("is a file"), "{e}");
        let e = check_path(FileAsk::ExportData, "nope", &dir).expect_err("missing");
        assert!(e.starts_with("no such folder: "), "{e}");
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn the_window_proposes_the_file_name_in_the_last_folder() {
        let dir = Path::new("/talks");
        assert_eq!(
            proposed_text(FileAsk::RecordGif(GifOptions::default()), dir),
            "/talks/rocking.gif"
        );
        assert_eq!(proposed_text(FileAsk::OpenRecord, dir), "/talks/");
        assert_eq!(proposed_text(FileAsk::ExportData, dir), "/talks");
    }

    #[test]
    fn only_app_turns_the_desktop_dialog_off() {
        assert!(native_from_env(Some("app")).is_none());
        assert!(native_from_env(Some(" APP ")).is_none());
        assert!(native_from_env(Some("native")).is_some());
        assert!(native_from_env(None).is_some());
    }
}
