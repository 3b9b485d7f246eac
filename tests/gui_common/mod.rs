//! Helpers shared by the GUI tests (tests/gui*.rs): a scene from a preset,
//! stepping the app until something holds, and a large synthetic section.
#![allow(dead_code)]

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use rocking::gui::{RockingApp, Settings};
use rocking::sim::protocol::SectionPoint;

/// Preset `preset` with the `--set` overrides `sets`, as the command line
/// reads them.
pub fn scene(preset: &str, sets: &[&str]) -> (Settings, rocking::sim::Scenario) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Settings::from_cli(Some(preset), None, &sets).expect("valid scene")
}

/// Steps the harness, sleeping 5 ms between frames so the simulation
/// thread and background jobs get to work, until `done` holds or
/// `timeout` passes. Returns whether it held.
pub fn pump(h: &mut Harness<'static, RockingApp>, timeout: Duration, done: impl Fn(&RockingApp) -> bool) -> bool {
    let start = Instant::now();
    while start.elapsed() < timeout {
        h.step();
        if done(h.state()) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    false
}

/// A strange attractor's worth of section points (the Hénon map scaled to
/// the ranges of Θ and Θ'): the plot's cost depends on how many points and
/// how many pixels they cover, not on where they came from.
pub fn henon(n: usize) -> Vec<SectionPoint> {
    let (mut x, mut y) = (0.1_f64, 0.1_f64);
    (0..n)
        .map(|k| {
            let (nx, ny) = (1.0 - 1.4 * x * x + y, 0.3 * x);
            x = nx;
            y = ny;
            SectionPoint {
                k: k as u64,
                tau: k as f64,
                theta: 0.6 * x,
                theta_dot: 2.0 * y,
                x: 0.0,
                x_dot: 0.0,
                mode: rocking::model::Mode::Rock {
                    pivot: rocking::model::Sign::Pos,
                },
            }
        })
        .collect()
}

/// Clicks menu `menu` and steps until its item `item` is shown.
pub fn open_menu(h: &mut Harness<'static, RockingApp>, menu: &str, item: &str) {
    h.get_by_label(menu).click();
    for _ in 0..10 {
        h.step();
        if h.query_by_label(item).is_some() {
            return;
        }
    }
    panic!("menu {menu} did not show {item}");
}

/// Closes any open menu, opens Presets, then its submenu `group`, until
/// `item` shows.
pub fn open_preset(h: &mut Harness<'static, RockingApp>, group: &str, item: &str) {
    h.key_press(egui::Key::Escape);
    h.step();
    open_menu(h, "Presets", group);
    h.get_by_label(group).click();
    for _ in 0..10 {
        h.step();
        if h.query_by_label(item).is_some() {
            return;
        }
    }
    panic!("Presets > {group} did not show {item}");
}

/// Moves the pointer to `pos` and, if `pressed` says so, presses or
/// releases the primary button there; then one frame.
pub fn pointer(h: &mut Harness<'static, RockingApp>, pos: egui::Pos2, pressed: Option<bool>) {
    h.event(egui::Event::PointerMoved(pos));
    if let Some(pressed) = pressed {
        h.event(egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
    }
    h.step();
}

/// Types `value` into the field named `label` and presses Enter, as a
/// user commits a parameter.
pub fn set_field(h: &mut Harness<'static, RockingApp>, label: &str, value: &str) {
    h.get_by_label(label).focus();
    h.step();
    h.get_by_label(label).set_text_value_accesskit(value);
    h.step();
    h.key_press(egui::Key::Enter);
    h.step();
    h.step();
}
