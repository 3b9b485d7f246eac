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

/// A slow renderer (a software GPU at 4 frames a second): the GIF still
/// plays for the clip's length, its last frame held until the clip's end.
#[test]
fn a_gif_recorded_at_four_frames_a_second_still_lasts_its_clip() {
    let (s, c) = scene("default", &[]);
    let updates = record(RunId(1), &c, 30.0);
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_step_dt(0.25)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
    h.step();
    let dir = temp_dir("slow-frames");
    let path = dir.join("slow.gif");
    let ctx = h.ctx.clone();
    let options = GifOptions {
        seconds: 2.0,
        fps: 15.0,
        max_width: 640,
    };
    h.state_mut().record_gif(&ctx, path.clone(), options);
    assert!(
        pump(&mut h, Duration::from_secs(60), |a| !a.sharing_busy()),
        "the recording ends"
    );
    let (n, seconds) = gif_frames_and_seconds(&path);
    println!("4 frames a second: {n} frames, {seconds:.2} s");
    assert_eq!(n, 8, "one frame a step for 2 s");
    assert!((seconds - 2.0).abs() < 0.02, "{seconds} s");
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
    let _ = h.get_by_label(NO_DIALOG);
    let _ = h.get_by_label_contains("no xdg-desktop-portal and no zenity");
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

// ---- Export view: at least 1920 px wide, whatever the window manager ----

/// The PNG at `path`: width, height and RGB bytes.
fn read_png(path: &Path) -> (usize, usize, Vec<u8>) {
    let mut reader = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).expect("written")))
        .read_info()
        .expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("pixels");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// Exports the view to `path` while a window manager keeps the window
/// at `physical` pixels (as it does a maximised window, or one as large
/// as the screen): after every frame the window is put back to that size.
/// (The harness draws its size in points times the zoom, so a window of
/// fixed pixels is `physical / zoom` points.) Returns the status line.
fn export_with_a_firm_window_manager(
    h: &mut Harness<'static, RockingApp>,
    physical: egui::Vec2,
    path: &Path,
) -> String {
    let ctx = h.ctx.clone();
    h.state_mut().export_view(&ctx, path.to_path_buf());
    let start = std::time::Instant::now();
    while h.state().sharing_busy() && start.elapsed() < Duration::from_secs(120) {
        h.step();
        let zoom = h.ctx.zoom_factor();
        h.set_size(physical / zoom);
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(!h.state().sharing_busy(), "the export ends");
    let msg = h.state().message().expect("a message").clone();
    assert!(!msg.error, "{msg:?}");
    msg.text
}

/// Mean absolute difference per channel between the window as drawn
/// (`window`, RGBA) and the export (RGB) scaled down to the window's size.
fn mean_difference(window: ([u32; 2], &[u8]), export: (usize, usize, Vec<u8>)) -> f64 {
    let ([ww, wh], rgba) = window;
    let (w, h, rgb) = export;
    let pixels = rgb
        .chunks_exact(3)
        .map(|c| egui::Color32::from_rgb(c[0], c[1], c[2]))
        .collect();
    let img = egui::ColorImage::new([w, h], pixels);
    let size = [ww as usize, wh as usize];
    let small = rocking::gui::capture::resample(&img, size);
    let total: u64 = rgba
        .chunks_exact(4)
        .zip(small.chunks_exact(3))
        .map(|(p, q)| (0..3).map(|k| u64::from(p[k].abs_diff(q[k]))).sum::<u64>())
        .sum();
    total as f64 / (3 * size[0] * size[1]) as f64
}

/// The reported failure: with a window manager that keeps the window's
/// size, Export view wrote the window as it was, 1280 × 800.
#[test]
fn the_view_exports_1920_wide_when_the_window_manager_keeps_the_window_size() {
    let mut h = rendered("default", SIZE);
    // The stream drained and the last impact's flash (0.18 s) faded.
    for _ in 0..30 {
        h.step();
    }
    let dir = temp_dir("firm-wm");
    let path = dir.join("view.png");
    let line = export_with_a_firm_window_manager(&mut h, SIZE, &path);
    let (w, hgt, rgb) = read_png(&path);
    println!("firm window manager: {w} × {hgt} px; {line}");
    assert!(w >= 1920 && hgt >= 1080, "{w} × {hgt}");
    assert_eq!((w, hgt), (1920, 1200), "1280 × 800 points at 1.5 pixels a point");
    assert!(line.starts_with("wrote view.png (1920 × 1200 px"), "{line}");
    // The window was never touched, and the picture is its layout.
    assert_eq!(h.ctx.zoom_factor(), 1.0);
    assert_eq!(h.ctx.content_rect().size(), SIZE);
    h.step();
    let window = h.render().expect("rendered");
    // To look at them: VIEW_OUT=/tmp/view (writes view.png and window.png there).
    if let Some(out) = std::env::var_os("VIEW_OUT") {
        let out = PathBuf::from(out);
        std::fs::create_dir_all(&out).expect("folder");
        std::fs::copy(&path, out.join("view.png")).expect("copied");
        window.save(out.join("window.png")).expect("saved");
    }
    let diff = mean_difference(([window.width(), window.height()], window.as_raw()), (w, hgt, rgb));
    println!("mean difference from the window: {diff:.2} levels");
    assert!(diff < 8.0, "{diff}");
    // The measure sees a layout change: the same picture against the
    // window at the next presentation scale differs by far more.
    let ctx = h.ctx.clone();
    h.state_mut().set_presentation_scale(&ctx, 1.25);
    h.set_size(SIZE / 1.25);
    for _ in 0..30 {
        h.step();
    }
    let other = h.render().expect("rendered");
    let (w, hgt, rgb) = read_png(&path);
    let control = mean_difference(([other.width(), other.height()], other.as_raw()), (w, hgt, rgb));
    println!("mean difference from the window at 125 %: {control:.2} levels");
    assert!(control > 2.0 * diff && control > 8.0, "{control}");
    let _ = std::fs::remove_dir_all(dir);
}

/// Every presentation scale, in both window sizes a lecture uses.
#[test]
fn the_view_exports_at_least_1920_by_1080_at_every_scale_and_window_size() {
    let dir = temp_dir("scales");
    for size in [SIZE, egui::vec2(1920.0, 1080.0)] {
        let mut h = rendered("default", size);
        h.step();
        for scale in rocking::gui::prefs::offered([size.x, size.y], false) {
            let ctx = h.ctx.clone();
            h.state_mut().set_presentation_scale(&ctx, scale);
            // A window of `size` pixels at this scale.
            h.set_size(size / scale);
            for _ in 0..30 {
                h.step();
            }
            let path = dir.join(format!("view-{}-{}.png", size.x, (scale * 100.0) as u32));
            let line = export_with_a_firm_window_manager(&mut h, size, &path);
            let (w, hgt, rgb) = read_png(&path);
            h.step();
            let window = h.render().expect("rendered");
            let diff = mean_difference(([window.width(), window.height()], window.as_raw()), (w, hgt, rgb));
            println!("{size:?} at {scale}: {w} × {hgt} px, mean difference {diff:.2}; {line}");
            assert!(w >= 1920 && hgt >= 1080, "{size:?} at {scale}: {w} × {hgt}");
            assert!(diff < 8.0, "{size:?} at {scale}: {diff}");
            assert_eq!(h.ctx.zoom_factor(), scale);
            assert_eq!(
                (h.ctx.content_rect().size() * h.ctx.pixels_per_point()).round(),
                size.round()
            );
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_view_export_without_a_gpu_renderer_says_why_and_writes_nothing() {
    let mut h = lazy("default");
    h.step();
    let dir = temp_dir("no-gpu");
    let path = dir.join("view.png");
    let ctx = h.ctx.clone();
    h.state_mut().export_view(&ctx, path.clone());
    assert!(pump(&mut h, Duration::from_secs(10), |a| !a.sharing_busy()));
    let msg = h.state().message().expect("a message").clone();
    assert!(
        msg.error && msg.text.contains("view.png: the view could not be drawn"),
        "{msg:?}"
    );
    assert!(!path.exists());
    let _ = std::fs::remove_dir_all(dir);
}
