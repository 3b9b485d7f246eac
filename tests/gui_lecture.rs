//! The app in a lecture hall (issue 16): the Presets menu's phenomena and
//! their on-screen sentences, the presentation scale (menu, keyboard,
//! remembered), the layout with every panel open at 1280 × 800, at
//! presentation scale and on a 1920 × 1080 projector, and the drawn fall
//! after a tumble. Driven headless through egui_kittest.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::{open_preset, pump, scene};
use rocking::gui::RockingApp;
use rocking::gui::app::lecture::SideTab;
use rocking::gui::lessons::{self, Note, PHENOMENA};
use rocking::model::Mode;
use rocking::sim::protocol::{RunEnd, RunId, Speed};
use rocking::sim::runner::record;

fn live_at(size: egui::Vec2, preset: &'static str, sets: &'static [&'static str]) -> Harness<'static, RockingApp> {
    Harness::builder().with_size(size).build_eframe(move |cc| {
        let (s, c) = scene(preset, sets);
        RockingApp::live(cc, s, c, Speed::Max, false)
    })
}

#[test]
fn every_phenomenon_loads_from_the_presets_menu_and_says_what_to_look_at() {
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", &[]);
    h.step();
    for (k, lesson) in PHENOMENA.iter().enumerate() {
        open_preset(&mut h, "Phenomena", lesson.title);
        h.get_by_label(lesson.title).click();
        h.step();
        h.step();
        let app = h.state();
        assert_eq!(app.run_id(), RunId(k as u64 + 2), "{}", lesson.title);
        assert_eq!(app.note().map(|n| n.title.as_str()), Some(lesson.title));
        assert_eq!(app.settings_origin(), format!("preset {}", lesson.preset));
        // The sentence is on screen, not only on hover: a label of its own.
        let _ = h.get_by_label(lesson.look);
    }
    // The last loads set their own view: the ghosts of sensitive
    // dependence, the forces of sliding.
    let sensitive = PHENOMENA.iter().find(|l| l.title == "Sensitive dependence").unwrap();
    open_preset(&mut h, "Phenomena", sensitive.title);
    h.get_by_label(sensitive.title).click();
    h.step();
    assert!(pump(&mut h, Duration::from_secs(10), |a| a.ghost_count() == 20
        && a.ghosts().len() == 20));
    let doubling = &PHENOMENA[2];
    open_preset(&mut h, "Phenomena", doubling.title);
    h.get_by_label(doubling.title).click();
    h.step();
    assert_eq!(h.state().config().excitation.a_v, 1.6);
    // Closing the note hides it.
    h.get_by_label("×").click();
    h.step();
    assert!(h.state().note().is_none());
}

/// `rocking --preset sliding` shows the sliding phenomenon's note, which
/// points at the red contact-force arrow: the arrow is on with it.
#[test]
fn a_phenomenon_preset_from_the_command_line_shows_its_note_and_what_it_points_at() {
    let h = live_at(egui::vec2(1280.0, 800.0), "sliding", &[]);
    let sliding = PHENOMENA.iter().find(|l| l.preset == "sliding").unwrap();
    assert_eq!(h.state().note().map(|n| n.title.as_str()), Some(sliding.title));
    assert!(sliding.look.contains("red arrow"));
    assert!(h.state().forces_shown(), "the note's arrow is drawn");
    let h = live_at(egui::vec2(1280.0, 800.0), "period-one", &[]);
    assert!(!h.state().forces_shown());
}

#[test]
fn a_figure_preset_says_what_the_paper_claims_and_what_this_model_shows() {
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", &[]);
    h.step();
    let label = format!("fig7: {}", lessons::figure_title("fig7"));
    open_preset(&mut h, "The paper's figures", &label);
    h.get_by_label(&label).click();
    h.step();
    h.step();
    let note = h.state().note().expect("a note").clone();
    assert!(note.text.starts_with("The paper: chaos that goes on"), "{}", note.text);
    assert!(note.text.contains("tumble"), "the model's tumble is said up front");
    let _ = h.get_by_label(note.text.as_str());
    // And from the command line (`rocking --preset fig7`), the same note.
    let h2 = live_at(egui::vec2(1280.0, 800.0), "fig7", &[]);
    assert_eq!(h2.state().note(), Some(&note));
}

#[test]
fn the_presentation_scale_enlarges_everything_follows_the_keyboard_and_is_remembered() {
    let dir = std::env::temp_dir().join(format!("rocking-scale-{}", std::process::id()));
    let path = dir.join("app.toml");
    let _ = std::fs::remove_dir_all(&dir);
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", &[]);
    let ctx = h.ctx.clone();
    h.state_mut().remember_scale_in(&ctx, path.clone());
    h.step();
    // Widget sizes are in points; the scale sets how many pixels a point
    // takes, so the same button is drawn larger.
    let pixels = |h: &Harness<'static, RockingApp>| h.get_by_label("Pause").rect().width() * h.ctx.pixels_per_point();
    let w1 = pixels(&h);
    assert_eq!(h.state().presentation_scale(), 1.0);

    h.get_by_label("View").click();
    for _ in 0..10 {
        h.step();
        if h.query_by_label("150 %").is_some() {
            break;
        }
    }
    h.get_by_label("150 %").click();
    h.step();
    h.step();
    assert_eq!(h.state().presentation_scale(), 1.5);
    assert_eq!(h.ctx.zoom_factor(), 1.5);
    let ratio = pixels(&h) / w1;
    assert!(
        (ratio - 1.5).abs() < 0.08,
        "text and buttons grow with the scale: {ratio}"
    );
    assert!(std::fs::read_to_string(&path).unwrap().contains("scale = 1.5"));

    // Ctrl + enlarges further, Ctrl − shrinks back, each remembered.
    h.key_press(egui::Key::Escape);
    h.step();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Plus);
    h.step();
    h.step();
    let bigger = h.state().presentation_scale();
    assert!(bigger > 1.5, "{bigger}");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Minus);
    h.step();
    h.step();
    assert!((h.state().presentation_scale() - 1.5).abs() < 1e-3);

    // A new session starts at the remembered scale.
    let mut h2 = live_at(egui::vec2(1280.0, 800.0), "default", &[]);
    let ctx2 = h2.ctx.clone();
    h2.state_mut().remember_scale_in(&ctx2, path.clone());
    h2.step();
    assert!((h2.state().presentation_scale() - 1.5).abs() < 1e-3);
    assert!((h2.ctx.zoom_factor() - 1.5).abs() < 1e-3);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every panel open, the legend whole and the block scene at least 30 %
/// of the window's width: at 1280 × 800, the same at presentation scale
/// 1.5, and on a 1920 × 1080 projector.
#[test]
fn with_every_panel_open_the_block_keeps_a_third_of_the_width_and_the_legend_is_whole() {
    for (size, scale) in [
        (egui::vec2(1280.0, 800.0), 1.0),
        (egui::vec2(1280.0, 800.0), 1.5),
        (egui::vec2(1920.0, 1080.0), 1.0),
    ] {
        // A window of `size` pixels: at scale 1.5 it holds size / 1.5 points.
        let mut h = live_at(size, "default", &[]);
        if scale != 1.0 {
            let ctx = h.ctx.clone();
            h.state_mut().set_presentation_scale(&ctx, scale);
        }
        {
            let show = &mut h.state_mut().show;
            show.bifurcation = true;
            show.lyapunov = true;
            show.map = true;
        }
        assert!(pump(&mut h, Duration::from_secs(10), |a| a.scene_rect().is_some()));
        h.step();
        let window_points = size.x / scale;
        let scene = h.state().scene_rect().expect("the scene is drawn");
        assert!(
            scene.width() >= 0.3 * window_points,
            "{size:?} at {scale}: the scene is {:.0} of {window_points:.0} points",
            scene.width()
        );
        // The legend's last entries lie inside the scene, whole.
        // (kittest's rectangles are in points, like the scene's.)
        let inside =
            |r: egui::Rect| r.min.x >= scene.min.x - 1.0 && r.max.x <= scene.max.x + 1.0 && r.max.y <= size.y / scale;
        // (The outcome map has a legend of its own with some of these.)
        for name in ["rest", "slide-rock", "tumbled", "flight"] {
            let rects: Vec<_> = h.query_all_by_label(name).map(|n| n.rect()).collect();
            assert!(
                rects.iter().any(|&r| inside(r)),
                "{size:?} at {scale}: {name} at {rects:?}, scene {scene:?}"
            );
        }
        // The analyses are tabs beside the plots (narrow) or a column of
        // their own (wide), never a third column squeezing the block.
        if size.x < 1500.0 * scale {
            let _ = h.get_by_label("Phase & Poincaré");
            h.get_by_label("Lyapunov").click();
            h.step();
            assert_eq!(h.state().side_tab(), SideTab::Lyapunov);
            assert!(h.query_all_by_label("Outcome map").count() >= 1, "the map is a tab too");
        }
        let show = &mut h.state_mut().show;
        show.bifurcation = false;
        show.lyapunov = false;
        show.map = false;
        h.step();
    }
}

#[test]
fn after_a_tumble_the_block_visibly_falls_onto_its_side_and_the_status_says_why() {
    // Tilted past half way and thrown outwards: it tumbles at once.
    // Frames 20 ms apart in egui's clock, so the 1.2 s fall takes many.
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_step_dt(0.02)
        .build_eframe(|cc| {
            let (s, c) = scene(
                "default",
                &["initial.theta=0.9", "initial.theta_dot=1.0", "excitation.kind=none"],
            );
            RockingApp::live(cc, s, c, Speed::Max, false)
        });
    assert!(pump(&mut h, Duration::from_secs(10), |a| matches!(
        a.end(),
        Some(RunEnd::Terminal {
            mode: Mode::Tumbled,
            ..
        })
    )));
    h.step();
    let psi = h.state().run_info().unwrap().geometry.psi;
    let first = h.state().shown_sample().unwrap().theta;
    assert!(first * psi < 0.5, "the fall starts at the tumble angle, {first}");
    let _ = h.get_by_label_contains("drawn, not simulated");
    let _ = h.get_by_label("mode: tumbled");
    // Within the fall's time (60 frames of 20 ms), it lies on its side.
    let mut angles = vec![first];
    for _ in 0..80 {
        h.step();
        angles.push(h.state().shown_sample().unwrap().theta);
    }
    assert!(angles.windows(2).all(|w| w[1] >= w[0]), "it falls one way");
    assert!(
        angles.iter().filter(|&&a| a * psi > 0.5 && a * psi < 1.5).count() > 20,
        "visibly, over many frames"
    );
    let last = h.state().shown_sample().unwrap();
    assert!(
        (last.theta * psi - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
        "{}",
        last.theta * psi
    );
    assert_eq!(last.mode, Mode::Tumbled);
}

/// A phenomenon preset with its note, from a fixed stream so the pixels
/// repeat, at presentation scale `scale`.
fn snapshot_period_doubling(name: &str, scale: f32) {
    let (s, c) = scene("period-doubling", &[]);
    let updates = record(RunId(1), &c, 40.0);
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| {
            let mut app = RockingApp::with_stream(cc, s, c, updates);
            app.set_note(Note::of_preset("period-doubling").unwrap());
            app
        });
    // A 1280 × 800 window: at scale 1.5 it holds 853 × 533 points.
    let ctx = h.ctx.clone();
    h.state_mut().set_presentation_scale(&ctx, scale);
    h.run();
    let _ = h.get_by_label(PHENOMENA[2].look);
    h.snapshot(name);
}

#[test]
fn snapshot_of_a_phenomenon_with_its_note() {
    snapshot_period_doubling("period_doubling_note", 1.0);
}

#[test]
fn snapshot_of_a_phenomenon_at_presentation_scale() {
    snapshot_period_doubling("period_doubling_scale_150", 1.5);
}
