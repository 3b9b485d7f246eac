//! The status bar and the opening frame: one line at every presentation
//! scale and window size, messages that go away, a failure said in τ, and
//! a paused start that shows the block where it starts.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::{pump, scene};
use rocking::gui::RockingApp;
use rocking::sim::protocol::Speed;

fn live_at(size: egui::Vec2, preset: &'static str, paused: bool) -> Harness<'static, RockingApp> {
    Harness::builder().with_size(size).build_eframe(move |cc| {
        let (s, c) = scene(preset, &[]);
        RockingApp::live(cc, s, c, Speed::RealTime(1.0), paused)
    })
}

#[test]
fn a_paused_start_shows_the_block_where_it_starts() {
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", true);
    assert!(
        pump(&mut h, Duration::from_secs(10), |a| !a.history().samples.is_empty()),
        "the first frame arrives while paused"
    );
    h.step();
    assert!(h.state().paused());
    assert_eq!(h.state().tau(), 0.0, "the playhead stays at the start");
    assert!(h.state().scene_rect().is_some(), "the block scene is drawn");
    assert!(h.query_by_label("waiting for the simulation…").is_none());
    // Still paused a while later: one frame, not a run.
    for _ in 0..20 {
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(h.state().history().samples.len(), 1);
    assert_eq!(h.state().tau(), 0.0);
}

/// A long refusal in the status bar, as a user gets from a bad value.
fn refuse(h: &mut Harness<'static, RockingApp>) -> String {
    assert!(!h.state_mut().set_key("block.width", "-1"));
    h.step();
    h.state().message().expect("a message").text.clone()
}

#[test]
fn the_status_bar_is_one_line_at_every_scale_and_size() {
    for size in [egui::vec2(1280.0, 800.0), egui::vec2(1920.0, 1080.0)] {
        for scale in rocking::gui::prefs::offered([size.x, size.y], false) {
            let mut h = live_at(size, "free-rocking", false);
            let ctx = h.ctx.clone();
            h.state_mut().set_presentation_scale(&ctx, scale);
            assert!(pump(&mut h, Duration::from_secs(10), |a| a.tau() > 0.2));
            let text = refuse(&mut h);
            h.step();
            let bar = h.state().status_rect().expect("the status bar is drawn");
            let body = egui::TextStyle::Body.resolve(&h.ctx.global_style());
            let row = h.ctx.fonts_mut(|f| f.row_height(&body));
            assert!(
                bar.height() < 1.5 * row,
                "{size:?} at {scale}: the status bar is {:.1} points tall, a row is {row:.1}",
                bar.height()
            );
            let points = size / scale;
            assert!(bar.max.x <= points.x + 0.5, "{size:?} at {scale}: {bar:?}");
            // The message is there (cut with … if long, whole on hover),
            // inside the window.
            let m = h.get_by_label(&text).rect();
            assert!(
                m.min.x < points.x && m.max.x <= points.x + 0.5 && m.width() > 20.0,
                "{size:?} at {scale}: message at {m:?}"
            );
            // Where the run is, always.
            assert!(
                h.query_all_by_label_contains("τ = ").next().is_some(),
                "{size:?} at {scale}"
            );
        }
    }
}

#[test]
fn a_message_goes_away_after_a_while_and_an_error_stays_longer() {
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", true);
    h.step();
    let now = h.ctx.input(|i| i.time);
    let _ = refuse(&mut h);
    h.input_mut().time = Some(now + 15.0);
    h.step();
    assert!(h.state().message().is_some(), "an error is still shown after 15 s");
    h.input_mut().time = Some(now + 25.0);
    h.step();
    h.step();
    assert!(h.state().message().is_none(), "an error is gone after 25 s");
}

#[test]
fn a_failed_run_says_where_in_tau_in_a_few_digits() {
    use rocking::sim::protocol::{RunEnd, RunId, SimUpdate};
    // A stream that fails: what the user reads in the status bar.
    let (s, c) = scene("free-rocking", &[]);
    let info = rocking::sim::runner::Session::new(RunId(1), &c, rocking::sim::runner::Start::Initial)
        .expect("starts")
        .info()
        .clone();
    let msg = "non-finite state at τ = 21.2169".to_string();
    let updates = vec![
        SimUpdate::Started {
            run: RunId(1),
            info: Box::new(info),
        },
        SimUpdate::Finished {
            run: RunId(1),
            end: RunEnd::Failed(msg.clone()),
        },
    ];
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
    h.step();
    h.step();
    let text = &h.state().message().expect("a message").text;
    assert!(text.ends_with(&msg), "{text}");
    let _ = h.get_by_label("failed");
}

#[test]
fn a_scene_loaded_from_the_outcome_map_closes_the_lessons_note() {
    let mut h = live_at(egui::vec2(1280.0, 800.0), "default", true);
    h.step();
    let lesson = &rocking::gui::lessons::PHENOMENA[0];
    h.state_mut().load_lesson(lesson);
    h.step();
    assert!(h.state().note().is_some(), "the lesson shows its note");
    let cell = [
        ("excitation.a_h".to_string(), 1.5),
        ("excitation.omega_h".to_string(), 3.0),
    ];
    assert!(h.state_mut().load_map_cell(&cell));
    h.step();
    assert!(h.state().note().is_none(), "the note described the scene left behind");
    assert_eq!(h.state().config().excitation.a_h, 1.5);
}
