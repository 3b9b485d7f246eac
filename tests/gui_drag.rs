//! A slider drag is a typed edit of the scene shown: every frame of a drag
//! gives the scene a typed value would give (the same refusal too), and on
//! a record scene it reads the record file not once. Driven through the
//! app fed a fixed (empty) stream, and through its settings directly.
#![cfg(feature = "gui")]

mod gui_common;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::{pointer, scene};
use rocking::gui::RockingApp;
use rocking::gui::panels::params::{Commit, slider_range};
use rocking::gui::panels::slider::slider_text;
use rocking::io::config::to_json;
use rocking::io::record::reads_on_this_thread;

/// The keys the parameter panel draws a slider for: B, H, the four
/// friction coefficients, r, e, two amplitudes, two frequencies, two
/// phases, two scales, two PGAs, the floor's three and the initial
/// state's three (the panel's own count is checked in its unit tests).
const SLIDER_KEYS: [&str; 24] = [
    "block.width",
    "block.height",
    "friction.static",
    "friction.kinetic",
    "impact.r",
    "impact.e",
    "impact.static",
    "impact.kinetic",
    "excitation.a_h",
    "excitation.a_v",
    "excitation.omega_h",
    "excitation.omega_v",
    "excitation.phase_h",
    "excitation.phase_v",
    "excitation.scale_h",
    "excitation.scale_v",
    "excitation.pga_h",
    "excitation.pga_v",
    "floor.period",
    "floor.damping",
    "floor.participation",
    "initial.theta",
    "initial.theta_dot",
    "initial.x_dot",
];

fn app(preset: &str) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    // Tall enough that the whole panel is on the screen.
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 1400.0))
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()));
    h.step();
    h
}

/// The value the panel shows for `key` in `json` (the resolved scene as
/// `summary.json` writes it), if it is a finite number.
fn shown(json: &serde_json::Value, key: &str) -> Option<f64> {
    let (section, name) = key.split_once('.')?;
    json.get(section)?.get(name)?.as_f64().filter(|v| v.is_finite())
}

#[test]
fn dragging_a_slider_on_a_record_scene_reads_the_record_file_no_more() {
    let mut h = app("elcentro-statue");
    let reads = reads_on_this_thread();
    assert_eq!(h.state().config().excitation.scale_h, 1.0);
    // A drag of the scale slider in the panel, grabbed near the left end
    // of its rail and moved right one point a frame: one step (0.1) each.
    let rect = h.get_by_label("scale_h slider").rect();
    let start = egui::pos2(rect.left() + 5.0, rect.center().y);
    pointer(&mut h, start, None);
    pointer(&mut h, start, Some(true));
    let mut seen = Vec::new();
    for k in 1..=4 {
        pointer(&mut h, start + egui::vec2(k as f32, 0.0), None);
        seen.push(h.state().config().excitation.scale_h);
    }
    pointer(&mut h, start + egui::vec2(4.0, 0.0), Some(false));
    assert_eq!(seen, [1.1, 1.2, 1.3, 1.4], "one step per point of drag");
    assert_eq!(reads_on_this_thread(), reads, "the drag read the record");

    // Every other slider of the scene, as the panel commits a drag frame:
    // typed keys, the block's size (which re-resolves the table) and the
    // target PGA (which has no typed parameter).
    for (key, raw) in [
        ("friction.static", "0.7"),
        ("friction.kinetic", "0.55"),
        ("impact.kinetic", "0.5"),
        ("block.width", "0.42"),
        ("block.height", "1.9"),
        // A target PGA is given with its unit.
        ("excitation.pga_h", "0.5 g"),
        ("floor.period", "0.8"),
        ("initial.theta", "0.1"),
    ] {
        let applied = h.state_mut().commit(Commit {
            key,
            raw: raw.to_string(),
            dragged: true,
        });
        assert!(applied, "{key} = {raw}: {:?}", h.state().message());
    }
    assert_eq!(reads_on_this_thread(), reads, "a drag read the record");
    let cfg = h.state().config();
    assert_eq!(
        (cfg.block.mu_s, cfg.block.mu_k, cfg.impact.mu_k),
        (0.7, Some(0.55), Some(0.5))
    );
    assert_eq!((cfg.block.width, cfg.block.height, cfg.initial.theta), (0.42, 1.9, 0.1));
    let record = cfg.excitation.record_h.as_ref().expect("a record");
    // PGA 0.5 g from the record's own peak, the scale a typed PGA gives.
    assert!((cfg.excitation.scale_h * record.series.peak_abs_g() - 0.5).abs() < 1e-12);
    assert_eq!(cfg.floor.as_ref().map(|f| f.modes[0].period_s), Some(0.8));

    // The counter counts: a typed value resolves the scene from its file.
    let typed = h.state_mut().commit(Commit {
        key: "friction.static",
        raw: "0.8".to_string(),
        dragged: false,
    });
    assert!(typed && h.state().config().block.mu_s == 0.8);
    assert_eq!(reads_on_this_thread(), reads + 1, "a typed value reads the record once");
}

/// Each drag frame's scene and settings are those the full resolution of
/// the edited table gives (the path a typed value takes), and a refused
/// value is refused with the same message: for every slider key, on two
/// harmonic scenes, a record scene and a record scene on a floor, at two
/// steps either side of the value shown and at both ends of
/// the rail (where some values are refused: μ_s below μ_k, ζ = 0).
#[test]
fn a_drag_gives_the_scene_and_the_refusal_that_resolving_the_table_gives() {
    let mut compared = 0;
    let mut refused = 0;
    for preset in ["default", "fig16", "elcentro-statue", "kobe-rack-5th-floor"] {
        let (settings, cfg) = scene(preset, &[]);
        let json = to_json(&cfg);
        for key in SLIDER_KEYS {
            let range = slider_range(key).expect("a slider");
            let now = shown(&json, key).unwrap_or(0.5 * (range.min + range.max));
            for v in [
                range.moved(now, 2.0, false, now),
                range.moved(now, -2.0, false, now),
                range.min,
                range.max,
            ] {
                let raw = slider_text(v);
                let reads = reads_on_this_thread();
                let dragged = settings.dragged(key, &raw, &cfg);
                assert_eq!(reads_on_this_thread(), reads, "{preset}: {key} = {raw} read a record");
                let resolved = settings.with(key, &raw);
                match (dragged, resolved) {
                    (Ok((s1, c1)), Ok((s2, c2))) => {
                        // The resolved keys first (readable where they
                        // differ), then every field, the records' samples
                        // and the unset defaults included.
                        assert_eq!(to_json(&c1), to_json(&c2), "{preset}: {key} = {raw}");
                        assert!(c1 == c2, "{preset}: {key} = {raw}: the scenes differ");
                        assert!(
                            format!("{c1:?}") == format!("{c2:?}"),
                            "{preset}: {key} = {raw}: the scenes print differently"
                        );
                        assert_eq!(s1.table, s2.table, "{preset}: {key} = {raw}");
                    }
                    (Err(e1), Err(e2)) => {
                        assert_eq!(e1, e2, "{preset}: {key} = {raw}");
                        refused += 1;
                    }
                    (d, r) => panic!("{preset}: {key} = {raw}: drag {:?}, typed {:?}", d.err(), r.err()),
                }
                compared += 1;
            }
        }
    }
    // 4 scenes × 24 keys × 4 values, of which some are refused: the
    // comparison saw both outcomes.
    assert_eq!(compared, 4 * SLIDER_KEYS.len() * 4);
    assert!(refused > 0 && refused < compared / 2, "{refused} of {compared} refused");
}

/// What one drag frame's edit costs in the app ([`RockingApp::commit`],
/// from the value to the new scene handed on), on a harmonic scene and
/// two record scenes, for a typed key, an initial-state key and the
/// block's width (which re-resolves the table). A measurement, not a
/// check: run with
/// `cargo test --test gui_drag -- --ignored --nocapture measure`.
#[test]
#[ignore]
fn measure_the_edit_of_a_drag_frame() {
    for preset in ["default", "elcentro-statue", "kobe-rack"] {
        for (key, from) in [("friction.static", 0.6), ("initial.theta", 0.0), ("block.width", 0.5)] {
            let mut h = app(preset);
            let mut us: Vec<f64> = (0..201)
                .map(|k| {
                    let raw = slider_text(from + 0.001 * (k % 50) as f64);
                    let start = std::time::Instant::now();
                    let applied = h.state_mut().commit(Commit {
                        key,
                        raw,
                        dragged: true,
                    });
                    let elapsed = start.elapsed().as_secs_f64() * 1e6;
                    assert!(applied, "{preset}: {key}: {:?}", h.state().message());
                    elapsed
                })
                .collect();
            us.sort_by(f64::total_cmp);
            println!(
                "{preset:16} {key:16} median {:7.1} µs, 90th percentile {:7.1} µs",
                us[100], us[180]
            );
        }
    }
}
