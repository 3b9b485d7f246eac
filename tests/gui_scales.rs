//! The layout at every presentation scale a window holds: at 1280 × 800
//! and 1920 × 1080, at each scale the View menu offers and each step of
//! Ctrl +/−, with the default scene, the period-doubling lesson, a stack
//! (harmonic, and the tombstone on Kobe) and the rocking frame, no
//! panel covers another, every plot keeps two numbered ticks on each axis,
//! no text is cut at a panel's edge, and the block keeps 30 % of the width.
//! Then the text sizes (at least 14 px at scale 1, plot numbers 20 px in
//! the lecture presentation), the verdict banner and the caption after a
//! tumble, and a panel shown again from the View menu.
//!
//! Measured on what egui painted: the text shapes of the frame's output
//! (their font size and where they lie), and the rectangles the app
//! records for its panels and plots. A lazy harness, without a GPU.
#![cfg(feature = "gui")]

mod gui_common;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use gui_common::scene;
use rocking::gui::RockingApp;
use rocking::gui::lessons::Note;
use rocking::gui::panels::axes;
use rocking::gui::prefs;
use rocking::model::Mode;
use rocking::sim::protocol::{RunEnd, RunId, SimUpdate};
use rocking::sim::runner::record;

/// The two windows a lecture is given on, pixels.
const WINDOWS: [egui::Vec2; 2] = [egui::vec2(1280.0, 800.0), egui::vec2(1920.0, 1080.0)];

/// The app on `preset` with its note (as the Presets menu loads it), fed
/// the first 40 τ of its run and then `tail`, in a window of `size`
/// pixels, without wgpu.
fn fixed(size: egui::Vec2, preset: &str, tail: Vec<SimUpdate>) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let mut updates = record(RunId(1), &c, 40.0);
    updates.extend(tail);
    let note = Note::of_preset(preset);
    Harness::builder().with_size(size).build_eframe(move |cc| {
        let mut app = RockingApp::with_stream(cc, s, c, updates);
        if let Some(n) = note {
            app.set_note(n);
        }
        app
    })
}

/// The scales to check in a window of `size` pixels: those the View menu
/// offers and every 0.1 step Ctrl + reaches from 100 %, up to the largest
/// the window holds.
fn scales_at(size: egui::Vec2, lecture: bool) -> Vec<f32> {
    let top = prefs::max_scale([size.x, size.y], lecture);
    let mut v = prefs::offered([size.x, size.y], lecture);
    let mut s = 1.0_f32;
    while s <= top + 1e-4 {
        v.push(s);
        s = ((s + 0.1) * 10.0).round() / 10.0;
    }
    v.sort_by(f32::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() < 1e-4);
    v
}

/// One text egui painted: the text, where (points), the clip it was drawn
/// in, and its smallest font size (points).
#[derive(Debug)]
struct Text {
    text: String,
    rect: egui::Rect,
    clip: egui::Rect,
    size: f32,
}

fn texts(h: &Harness<'static, RockingApp>) -> Vec<Text> {
    fn walk(shape: &egui::Shape, clip: egui::Rect, out: &mut Vec<Text>) {
        match shape {
            egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, clip, out)),
            egui::Shape::Text(t) => {
                let text = t.galley.text().to_owned();
                if text.trim().is_empty() {
                    return;
                }
                let size = t
                    .galley
                    .job
                    .sections
                    .iter()
                    .map(|s| s.format.font_id.size)
                    .fold(f32::INFINITY, f32::min);
                out.push(Text {
                    text,
                    rect: t.visual_bounding_rect(),
                    clip,
                    size,
                });
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for c in &h.output().shapes {
        walk(&c.shape, c.clip_rect, &mut out);
    }
    out
}

/// Whether `text` is a tick number ("0.25", "−1", "2e-6").
fn is_number(text: &str) -> bool {
    text.replace('−', "-").parse::<f64>().is_ok()
}

/// The numbered ticks drawn whole beside plot `frame`: (x axis, y axis).
fn ticks(texts: &[Text], frame: egui::Rect) -> (Vec<&Text>, Vec<&Text>) {
    let whole = |t: &&Text| t.clip.expand(0.5).contains_rect(t.rect);
    let x = texts
        .iter()
        .filter(|t| is_number(&t.text))
        .filter(|t| {
            t.rect.min.y >= frame.max.y - 1.0
                && t.rect.min.y <= frame.max.y + 8.0
                && (frame.min.x - 1.0..=frame.max.x + 1.0).contains(&t.rect.center().x)
        })
        .filter(whole)
        .collect();
    let y = texts
        .iter()
        .filter(|t| is_number(&t.text))
        .filter(|t| {
            t.rect.max.x <= frame.min.x + 1.0
                && t.rect.max.x >= frame.min.x - 12.0
                && (frame.min.y - 1.0..=frame.max.y + 1.0).contains(&t.rect.center().y)
        })
        .filter(whole)
        .collect();
    (x, y)
}

/// Checks the frame `h` last drew; `what` names the configuration.
/// Returns the plots it checked.
fn check_frame(h: &Harness<'static, RockingApp>, what: &str) -> Vec<&'static str> {
    let layout = h.state().frame_layout().clone();
    let screen = layout.screen;
    assert!(screen.width() > 0.0, "{what}: laid out");
    // No panel covers another, and each is inside the window.
    for (i, (a, ra)) in layout.panels.iter().enumerate() {
        assert!(
            screen.expand(0.5).contains_rect(*ra),
            "{what}: {a} at {ra:?} leaves the window {screen:?}"
        );
        for (b, rb) in &layout.panels[i + 1..] {
            // (Half a point is egui rounding a plot's height, not a cover.)
            let overlap = ra.intersect(*rb);
            assert!(
                overlap.width() <= 0.5 || overlap.height() <= 0.5,
                "{what}: {a} {ra:?} covers {b} {rb:?}"
            );
        }
    }
    // The block keeps 30 % of the width.
    let scene = h.state().scene_rect().expect("the scene is drawn");
    assert!(
        scene.width() >= 0.3 * screen.width(),
        "{what}: the scene is {:.0} of {:.0} points",
        scene.width(),
        screen.width()
    );
    // And at least 150 px of height, to see the block from the back of a
    // hall (a long note once left it 95 px at 150 % in 1280 × 800).
    let ppp = h.ctx.pixels_per_point();
    assert!(
        scene.height() * ppp >= 150.0,
        "{what}: the scene is {:.0} px high",
        scene.height() * ppp
    );
    let texts = texts(h);
    // No text cut at the left or right edge of what it is drawn in.
    for t in &texts {
        if !t.rect.intersects(t.clip) {
            continue;
        }
        assert!(
            t.rect.min.x >= t.clip.min.x - 1.0 && t.rect.max.x <= t.clip.max.x + 1.0,
            "{what}: {:?} at {:?} is cut by {:?}",
            t.text,
            t.rect,
            t.clip
        );
    }
    // Every plot drawn has two whole numbered ticks on each axis.
    let mut seen = Vec::new();
    for plot in axes::recorded(&h.ctx) {
        let (x, y) = ticks(&texts, plot.frame);
        assert!(
            x.len() >= 2 && y.len() >= 2,
            "{what}: {} ({:?}) has {} x and {} y numbers: x {:?} y {:?}",
            plot.name,
            plot.frame,
            x.len(),
            y.len(),
            x.iter().map(|t| &t.text).collect::<Vec<_>>(),
            y.iter().map(|t| &t.text).collect::<Vec<_>>()
        );
        seen.push(plot.name);
    }
    seen
}

/// Lays out `preset` at `scale` in a window of `size` and checks it,
/// showing each plot (through its tab where the plots are tabs).
fn check_config(size: egui::Vec2, preset: &str, scale: f32, lecture: bool) {
    let mut h = fixed(size, preset, Vec::new());
    let ctx = h.ctx.clone();
    h.state_mut().set_lecture_presentation(&ctx, lecture);
    h.state_mut().set_presentation_scale(&ctx, scale);
    for _ in 0..4 {
        h.step();
    }
    let what = format!("{preset} {size:?} at {scale}{}", if lecture { " lecture" } else { "" });
    assert!(
        (h.state().presentation_scale() - scale).abs() < 1e-4,
        "{what}: applied {}",
        h.state().presentation_scale()
    );
    let mut seen = check_frame(&h, &what);
    for tab in [
        "Phase portrait",
        "Poincaré points",
        "Time history",
        "Power spectrum",
        "Ground acceleration",
    ] {
        if let Some(node) = h.query_by_label(tab) {
            node.click();
            h.step();
            h.step();
            seen.extend(check_frame(&h, &format!("{what}, tab {tab}")));
        }
    }
    // A record has no forcing period, so no Poincaré section, and shows
    // the ground's acceleration where a harmonic scene has a spectrum.
    let record = preset == "rocking-frame" || preset == "tombstone";
    let plots: &[&str] = if record {
        &["phase", "history", "ground"]
    } else {
        &["phase", "poincare", "history", "spectrum"]
    };
    for plot in plots {
        assert!(seen.contains(plot), "{what}: {plot} never shown ({seen:?})");
    }
}

#[test]
fn every_offered_scale_lays_out_every_panel_without_overlap_cut_text_or_lost_ticks() {
    for size in WINDOWS {
        for scale in scales_at(size, false) {
            for preset in [
                "default",
                "period-doubling",
                "stack-patterns",
                "rocking-frame",
                "tombstone",
            ] {
                check_config(size, preset, scale, false);
            }
        }
    }
}

#[test]
fn the_lecture_presentation_lays_out_at_every_offered_scale() {
    for size in WINDOWS {
        for scale in scales_at(size, true) {
            for preset in ["period-doubling", "stack-patterns", "rocking-frame"] {
                check_config(size, preset, scale, true);
            }
        }
    }
}

/// The smallest text painted, and the tick numbers of each plot: (font
/// size, row height) in pixels.
fn sizes_px(h: &Harness<'static, RockingApp>) -> (f32, Vec<(&'static str, f32, f32)>) {
    let ppp = h.ctx.pixels_per_point();
    let texts = texts(h);
    let smallest = texts.iter().map(|t| t.size).fold(f32::INFINITY, f32::min) * ppp;
    let mut numbers = Vec::new();
    for plot in axes::recorded(&h.ctx) {
        let (x, y) = ticks(&texts, plot.frame);
        for t in x.into_iter().chain(y) {
            numbers.push((plot.name, t.size * ppp, t.rect.height() * ppp));
        }
    }
    (smallest, numbers)
}

/// At 100 % in a 1280 × 800 window every text painted (plot numbers, axis
/// titles, parameter names and values, the status bar, notes) is at least
/// 14 px; the lecture presentation draws plot numbers at 20 px or more and
/// keeps the Poincaré plot at least 300 × 200 px.
#[test]
fn no_text_is_below_14_px_and_the_lecture_presentation_numbers_plots_at_20_px() {
    for preset in ["default", "period-doubling"] {
        let mut h = fixed(WINDOWS[0], preset, Vec::new());
        for _ in 0..4 {
            h.step();
        }
        let (smallest, numbers) = sizes_px(&h);
        let tallest = numbers.iter().map(|n| n.2).fold(0.0, f32::max);
        eprintln!(
            "{preset} at 100 %: smallest text {smallest} px, plot numbers {:?} px (digits {tallest} px high)",
            numbers.iter().map(|n| n.1).fold(f32::INFINITY, f32::min)
        );
        assert!(smallest >= 14.0, "{preset}: a text of {smallest} px");
        assert!(numbers.len() >= 8, "{preset}: {numbers:?}");

        let ctx = h.ctx.clone();
        h.state_mut().set_lecture_presentation(&ctx, true);
        for _ in 0..4 {
            h.step();
        }
        let mut seen = Vec::new();
        for tab in [None, Some("Poincaré points"), Some("Power spectrum")] {
            if let Some(tab) = tab {
                match h.query_by_label(tab) {
                    Some(node) => node.click(),
                    None => continue,
                }
                h.step();
                h.step();
            }
            let (smallest, numbers) = sizes_px(&h);
            assert!(smallest >= 14.0, "{preset} lecture: a text of {smallest} px");
            for (plot, size, _) in &numbers {
                assert!(*size >= 20.0, "{preset} lecture: {plot} numbers at {size} px");
                seen.push(*plot);
            }
            eprintln!(
                "{preset} lecture: smallest text {smallest} px, plot numbers {:?} px (digits {:?} px high)",
                numbers.iter().map(|n| n.1).fold(f32::INFINITY, f32::min),
                numbers.iter().map(|n| n.2).fold(0.0, f32::max)
            );
        }
        for plot in ["phase", "poincare", "history", "spectrum"] {
            assert!(seen.contains(&plot), "{preset} lecture: {plot} never shown");
        }
        h.get_by_label("Poincaré points").click();
        h.step();
        h.step();
        let ppp = h.ctx.pixels_per_point();
        let poincare = axes::recorded(&h.ctx)
            .into_iter()
            .find(|p| p.name == "poincare")
            .expect("the Poincaré plot");
        let px = poincare.frame.size() * ppp;
        eprintln!("{preset} lecture: Poincaré plot {px:?} px");
        assert!(px.x >= 300.0 && px.y >= 200.0, "{preset} lecture: Poincaré {px:?} px");
    }
}

/// The app on `preset`, its first 40 τ and then `tail`, with frames 0.05 s
/// apart in egui's clock (so the drawn fall after a tumble, 1.2 s, takes
/// 24 frames).
fn fixed_timed(size: egui::Vec2, preset: &str, tail: Vec<SimUpdate>) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let mut updates = record(RunId(1), &c, 40.0);
    updates.extend(tail);
    Harness::builder()
        .with_size(size)
        .with_step_dt(0.05)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
}

/// After a tumble, at every offered scale in both windows: the verdict's
/// text stays inside its plate, and the plate and the "drawn, not
/// simulated" caption lie above the fallen block and the table. The Kobe
/// rack (a record scene, the banner in a strip of its own) and the default
/// scene made to tumble late, at t = 157.53 s (a long headline on a plate
/// over the scene).
#[test]
fn the_banner_fits_its_plate_and_the_caption_clears_the_fallen_block() {
    let (_, c) = scene("default", &[]);
    let p = c.geometry().p;
    let late = vec![SimUpdate::Finished {
        run: RunId(1),
        end: RunEnd::Terminal {
            mode: Mode::Tumbled,
            tau: 157.53 * p,
        },
    }];
    for size in WINDOWS {
        for scale in prefs::offered([size.x, size.y], false) {
            for (preset, tail, headline) in [
                ("kobe-rack", Vec::new(), "OVERTURNED at t = 6.89 s"),
                ("default", late.clone(), "OVERTURNED at t = 157.53 s"),
            ] {
                let what = format!("{preset} {size:?} at {scale}");
                let mut h = fixed_timed(size, preset, tail);
                let ctx = h.ctx.clone();
                h.state_mut().set_presentation_scale(&ctx, scale);
                for _ in 0..40 {
                    h.step();
                }
                let _ = h.get_by_label(headline);
                let layout = h.state().frame_layout().clone();
                let banner = layout.banner.expect("a banner");
                assert!(
                    banner.plate.expand(0.5).contains_rect(banner.text),
                    "{what}: text {:?} leaves its plate {:?}",
                    banner.text,
                    banner.plate
                );
                let caption = layout.caption.expect("the caption");
                let block = layout.block_top.expect("the block");
                let table = layout.table_top.expect("the table");
                assert!(
                    caption.max.y <= block && caption.max.y <= table,
                    "{what}: caption {caption:?} over the block (top {block}) or table ({table})"
                );
                assert!(
                    banner.plate.max.y <= block,
                    "{what}: plate {:?} over the block (top {block})",
                    banner.plate
                );
                assert!(
                    banner.plate.expand(0.5).contains_rect(caption),
                    "{what}: caption {caption:?} off the plate {:?}",
                    banner.plate
                );
                let central = layout.panels.iter().find(|p| p.0 == "central").expect("central").1;
                assert!(
                    central.contains_rect(caption),
                    "{what}: caption {caption:?} outside {central:?}"
                );
            }
        }
    }
}

/// Clicks View ▸ `item` (a panel's checkbox), closes the menu, and lets the
/// layout settle.
fn toggle_view(h: &mut Harness<'static, RockingApp>, item: &str) {
    use egui::accesskit::Role;
    h.key_press(egui::Key::Escape);
    h.step();
    h.get_by_label("View").click();
    for _ in 0..10 {
        h.step();
        if h.query_by_role_and_label(Role::CheckBox, item).is_some() {
            break;
        }
    }
    h.get_by_role_and_label(Role::CheckBox, item).click();
    h.step();
    h.key_press(egui::Key::Escape);
    for _ in 0..4 {
        h.step();
    }
}

fn panel(h: &Harness<'static, RockingApp>, name: &str) -> Option<egui::Rect> {
    h.state()
        .frame_layout()
        .panels
        .iter()
        .find(|p| p.0 == name)
        .map(|p| p.1)
}

/// A panel hidden from the View menu and shown again comes back at the
/// size it had, in both windows.
#[test]
fn a_panel_shown_again_from_the_view_menu_comes_back_at_its_size() {
    for size in WINDOWS {
        let mut h = fixed(size, "period-doubling", Vec::new());
        for _ in 0..4 {
            h.step();
        }
        for (items, name) in [
            (&["Parameters"][..], "params"),
            (&["Time history", "Power spectrum"][..], "history"),
            (&["Phase portrait", "Poincaré points"][..], "side"),
        ] {
            let before = panel(&h, name).expect("shown");
            for item in items {
                toggle_view(&mut h, item);
            }
            assert!(panel(&h, name).is_none(), "{size:?}: {name} hidden");
            for item in items {
                toggle_view(&mut h, item);
            }
            let after = panel(&h, name).expect("shown again");
            eprintln!("{size:?}: {name} {:?} → {:?}", before.size(), after.size());
            assert!(
                (after.width() - before.width()).abs() <= 1.0 && (after.height() - before.height()).abs() <= 1.0,
                "{size:?}: {name} was {:?}, came back {:?}",
                before.size(),
                after.size()
            );
        }
    }
}

/// The View menu offers the scales the window holds (the others greyed
/// out), Ctrl + stops at the largest, and a scale remembered from a larger
/// screen gives way to what this window holds.
#[test]
fn only_the_scales_the_window_holds_are_offered_or_reached() {
    let mut h = fixed(WINDOWS[0], "default", Vec::new());
    h.step();
    h.get_by_label("View").click();
    for _ in 0..10 {
        h.step();
        if h.query_by_label("150 %").is_some() {
            break;
        }
    }
    for scale in prefs::SCALES {
        let label = format!("{:.0} %", 100.0 * scale);
        let enabled = !h.get_by_label(&label).accesskit_node().is_disabled();
        assert_eq!(enabled, scale <= 1.6, "{label} at 1280 × 800");
    }
    h.key_press(egui::Key::Escape);
    h.step();
    let ctx = h.ctx.clone();
    h.state_mut().set_presentation_scale(&ctx, 1.5);
    h.step();
    for _ in 0..5 {
        h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Plus);
        h.step();
        h.step();
    }
    let top = h.state().presentation_scale();
    assert!((top - 1.6).abs() < 1e-4, "Ctrl + stops at 160 %: {top}");
    assert!((h.ctx.zoom_factor() - 1.6).abs() < 1e-4);

    // Remembered at 250 % on a 4K screen, opened in a 1280 × 800 window.
    let dir = std::env::temp_dir().join(format!("rocking-scales-{}", std::process::id()));
    let path = dir.join("app.toml");
    prefs::Prefs {
        scale: 2.5,
        lecture: true,
    }
    .save(&path)
    .unwrap();
    let mut h = fixed(WINDOWS[0], "default", Vec::new());
    let ctx = h.ctx.clone();
    h.state_mut().remember_scale_in(&ctx, path.clone());
    h.step();
    h.step();
    assert!(
        h.state().lecture_presentation(),
        "the lecture presentation is remembered"
    );
    let applied = h.state().presentation_scale();
    assert!(
        (applied - prefs::max_scale([1280.0, 800.0], true)).abs() < 1e-4,
        "{applied}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
