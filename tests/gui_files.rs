//! The File menu on any desktop: a GIF whose file is chosen first and
//! whose clip is then recorded whole, file dialogs that fall back to a
//! path window inside the app when the desktop has none, and the view
//! exported at presentation resolution without touching the window.
#![cfg(feature = "gui")]

mod gui_common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use gui_common::{open_menu, pump, scene};
use rocking::gui::RockingApp;
use rocking::gui::app::{FileAsk, NO_DIALOG};
use rocking::gui::capture::GifOptions;
use rocking::sim::protocol::RunId;
use rocking::sim::runner::record;

const SIZE: egui::Vec2 = egui::vec2(1280.0, 800.0);

/// A folder in the temporary folder, unique to this test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rocking-files-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// The app on a fixed stream of `preset` (no thread), no GPU.
fn lazy(preset: &str) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let updates = record(RunId(1), &c, 1.0);
    Harness::builder()
        .with_size(SIZE)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
}

/// The same on the software wgpu renderer (screenshots work), stepping
/// 1/60 s of egui time a frame.
fn rendered(preset: &str, size: egui::Vec2) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let updates = record(RunId(1), &c, 30.0);
    Harness::builder()
        .with_size(size)
        .with_step_dt(1.0 / 60.0)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
}

/// A desktop with no portal and no zenity: rfd returns `None` at once.
fn no_desktop_dialog(_: FileAsk, _: &Path) -> Option<PathBuf> {
    None
}

/// A person who opens the desktop's dialog and cancels it.
fn cancelled_dialog(_: FileAsk, _: &Path) -> Option<PathBuf> {
    std::thread::sleep(Duration::from_millis(450));
    None
}

/// The frame count and total play time (s) of the GIF at `path`.
fn gif_frames_and_seconds(path: &Path) -> (usize, f64) {
    let mut dec = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(path).expect("written"))
        .expect("a GIF");
    let (mut n, mut cs) = (0, 0u32);
    while let Some(f) = dec.read_next_frame().expect("a frame") {
        n += 1;
        cs += u32::from(f.delay);
    }
    (n, f64::from(cs) / 100.0)
}

/// Replaces the path window's text with `text` and presses Enter.
fn type_path(h: &mut Harness<'static, RockingApp>, text: &str) {
    h.get_by_label("Path").focus();
    h.step();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.step();
    h.get_by_label("Path").type_text(text);
    h.step();
    h.key_press(egui::Key::Enter);
    h.step();
}

/// The slider labelled `label` (not the number field beside it).
fn slider<'a>(h: &'a Harness<'static, RockingApp>, label: &'a str) -> egui_kittest::Node<'a> {
    h.get_all_by_label(label)
        .find(|n| n.accesskit_node().role() == egui::accesskit::Role::Slider)
        .expect("a slider")
}

fn status_text(h: &Harness<'static, RockingApp>) -> String {
    h.state().message().map(|m| m.text.clone()).unwrap_or_default()
}

// ---- The GIF: the file first, then the whole clip ----

/// The reported failure: a desktop dialog blocks the frame that opened it,
/// so the next frame comes as many seconds later as the dialog was open.
/// The clip's clock used to start before the dialog: any dialog open
/// longer than the clip ended the recording before its first frame ("no
/// frame was captured").
#[test]
fn a_gif_chosen_after_a_long_desktop_dialog_records_its_whole_clip() {
    let mut h = rendered("default", SIZE);
    h.step();
    let dir = temp_dir("slow-dialog");
    let path = dir.join("clip.gif");
    let ctx = h.ctx.clone();
    let options = GifOptions {
        seconds: 1.0,
        fps: 10.0,
        max_width: 640,
    };
    h.state_mut().record_gif(&ctx, path.clone(), options);
    // The dialog was open for 8 s, longer than the 1 s clip.
    let t = h.ctx.input(|i| i.time);
    h.input_mut().time = Some(t + 8.0);
    h.step();
    // From there on, 1/60 s a frame again.
    h.input_mut().time = None;
    assert!(h.state().recording(), "{:?}", h.state().message());
    assert!(
        pump(&mut h, Duration::from_secs(60), |a| !a.sharing_busy()),
        "the recording ends"
    );
    let msg = h.state().message().expect("a message").clone();
    assert!(!msg.error && msg.text.starts_with("wrote clip.gif ("), "{msg:?}");
    let (n, seconds) = gif_frames_and_seconds(&path);
    println!("slow dialog: {n} frames, {seconds:.2} s");
    // 1 s at 10 fps: about ten frames, playing about 1 s.
    assert!((9..=12).contains(&n), "{n} frames");
    assert!((seconds - 1.0).abs() <= 0.15, "{seconds} s");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn record_gif_from_the_menu_asks_for_the_file_first_then_records_with_progress() {
    let mut h = rendered("default", SIZE);
    h.state_mut().set_native_file_dialog(Some(no_desktop_dialog));
    h.step();
    open_menu(&mut h, "File", "Record GIF…");
    h.get_by_label("Record GIF…").click();
    h.step();
    h.step();
    slider(&h, "Duration").set_value_accesskit(1.0);
    slider(&h, "Frames per second").set_value_accesskit(10.0);
    h.step();
    h.get_by_label("Record…").click();
    h.step();
    h.step();
    // No desktop dialog: the status bar says so, and the path window asks.
    assert_eq!(status_text(&h), NO_DIALOG);
    let _ = h.get_by_label_contains("no file dialog could open");
    assert!(matches!(h.state().path_window(), Some(FileAsk::RecordGif(o)) if o.seconds == 1.0));
    let proposed = h.get_by_label("Path").value().unwrap_or_default();
    assert!(proposed.ends_with("rocking.gif"), "{proposed}");

    // The user takes 3 s (longer than the clip) to name the file: nothing
    // is recorded meanwhile.
    for _ in 0..180 {
        h.step();
    }
    assert!(!h.state().recording());
    let dir = temp_dir("menu");
    let path = dir.join("lecture.gif");
    type_path(&mut h, &path.display().to_string());
    assert!(h.state().path_window().is_none());
    assert!(h.state().recording(), "{:?}", h.state().message());

    // The status line shows the clock running.
    let mut shown = Vec::new();
    for _ in 0..40 {
        h.step();
        if let Some(n) = h.query_by_label_contains("recording… ") {
            shown.push(
                n.value()
                    .unwrap_or_else(|| n.accesskit_node().label().unwrap_or_default()),
            );
        }
    }
    println!("progress shown: {:?} … {:?}", shown.first(), shown.last());
    assert!(
        shown.iter().any(|s| s.starts_with("recording… 0.5 s of 1.0 s")),
        "{shown:?}"
    );
    assert!(
        pump(&mut h, Duration::from_secs(60), |a| !a.sharing_busy()),
        "the recording ends"
    );
    let msg = h.state().message().expect("a message").clone();
    assert!(!msg.error && msg.text.starts_with("wrote lecture.gif ("), "{msg:?}");
    let (n, seconds) = gif_frames_and_seconds(&path);
    println!("menu: {n} frames, {seconds:.2} s; {}", msg.text);
    assert!((9..=12).contains(&n), "{n} frames");
    assert!((seconds - 1.0).abs() <= 0.15, "{seconds} s");
    let _ = std::fs::remove_dir_all(dir);
}

// ---- File dialogs without a portal ----

#[test]
fn without_a_desktop_dialog_save_scene_says_so_and_the_path_window_writes_the_file() {
    let mut h = lazy("fig7");
    h.state_mut().set_native_file_dialog(Some(no_desktop_dialog));
    h.step();
    open_menu(&mut h, "File", "Save scene…");
    h.get_by_label("Save scene…").click();
    h.step();
    h.step();
    assert_eq!(status_text(&h), NO_DIALOG);
    assert!(h.state().message().is_some_and(|m| m.error));
    assert_eq!(h.state().path_window(), Some(FileAsk::SaveScene));
    let _ = h.get_by_label("Save the scene");
    let proposed = h.get_by_label("Path").value().unwrap_or_default();
    assert!(proposed.ends_with("scene.toml"), "{proposed}");

    // A folder that does not exist: refused, with the reason, and the
    // window stays.
    type_path(&mut h, "/no/such/folder/talk.toml");
    assert_eq!(h.state().path_window(), Some(FileAsk::SaveScene));
    let _ = h.get_by_label("no such folder: /no/such/folder");

    // A good path without an extension gets .toml and is written.
    let dir = temp_dir("save");
    type_path(&mut h, &dir.join("talk").display().to_string());
    assert!(h.state().path_window().is_none());
    let path = dir.join("talk.toml");
    assert!(path.is_file(), "{:?}", h.state().message());
    assert_eq!(status_text(&h), format!("saved {}", path.display()));
    h.step();
    assert_eq!(h.state().title(), "rocking — talk.toml");

    // Next time the window proposes that folder; Escape closes it and
    // nothing happens.
    open_menu(&mut h, "File", "Save scene…");
    h.get_by_label("Save scene…").click();
    h.step();
    h.step();
    let proposed = h.get_by_label("Path").value().unwrap_or_default();
    assert_eq!(proposed, dir.join("scene.toml").display().to_string());
    h.key_press(egui::Key::Escape);
    h.step();
    assert!(h.state().path_window().is_none());
    assert!(!dir.join("scene.toml").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_path_window_opens_a_record_and_refuses_a_missing_one() {
    let mut h = lazy("default");
    h.state_mut().set_native_file_dialog(None);
    h.step();
    open_menu(&mut h, "File", "Open record…");
    h.get_by_label("Open record…").click();
    h.step();
    h.step();
    // Forced (ROCKING_FILE_DIALOG=app): the window, and no complaint.
    assert_eq!(h.state().path_window(), Some(FileAsk::OpenRecord));
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    type_path(&mut h, &data.join("missing.AT2").display().to_string());
    let _ = h.get_by_label_contains("no such file: ");
    assert_eq!(h.state().path_window(), Some(FileAsk::OpenRecord));
    type_path(&mut h, &data.join("sample.AT2").display().to_string());
    assert!(h.state().path_window().is_none());
    assert_eq!(status_text(&h), "record sample.AT2");
    assert_eq!(
        h.state().config().excitation.kind,
        rocking::sim::scenario::ExcitationKind::Record
    );
}

#[test]
fn a_cancelled_desktop_dialog_is_not_taken_for_a_missing_one() {
    let mut h = lazy("default");
    h.state_mut().set_native_file_dialog(Some(cancelled_dialog));
    h.step();
    open_menu(&mut h, "File", "Open scene…");
    h.get_by_label("Open scene…").click();
    h.step();
    h.step();
    assert!(h.state().path_window().is_none());
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
}
