//! A stack preset in the app: the app does not run stacks yet, and says
//! so in the scene and the status bar instead of drawing a wrong model.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::scene;
use rocking::gui::RockingApp;
use rocking::sim::protocol::Speed;

#[test]
fn a_stack_preset_says_in_the_app_that_it_runs_headless_only() {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(|cc| {
            let (s, c) = scene("tombstone", &[]);
            RockingApp::live(cc, s, c, Speed::RealTime(1.0), false)
        });
    let start = std::time::Instant::now();
    let said = loop {
        h.step();
        if let Some(m) = h.state().message() {
            break m.text.clone();
        }
        assert!(start.elapsed() < Duration::from_secs(10), "no message");
        std::thread::sleep(Duration::from_millis(10));
    };
    assert!(said.contains("a [[stack]] is simulated one run at a time"), "{said}");
    h.step();
    assert!(
        h.query_by_label_contains("The run could not start: stack: a [[stack]] is simulated one run at a time")
            .is_some(),
        "the scene says why"
    );
    assert!(h.state().history().samples.is_empty(), "nothing drawn as if it ran");
}
