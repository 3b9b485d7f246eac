//! The layout at every presentation scale a window holds: at 1280 × 800
//! and 1920 × 1080, at each scale the View menu offers and each step of
//! Ctrl +/−, with the default scene and the period-doubling lesson, no
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
use egui_kittest::kittest::Queryable as _;
use gui_common::scene;
use rocking::gui::RockingApp;
use rocking::gui::panels::axes;
use rocking::gui::prefs;
use rocking::model::Mode;
use rocking::sim::protocol::{RunEnd, RunId, SimUpdate};
use rocking::sim::runner::record;

/// The two windows a lecture is given on, pixels.
const WINDOWS: [egui::Vec2; 2] = [egui::vec2(1280.0, 800.0), egui::vec2(1920.0, 1080.0)];

/// The app on `preset`, fed the first 40 τ of its run and then `tail`,
/// in a window of `size` pixels, without wgpu.
fn fixed(size: egui::Vec2, preset: &str, tail: Vec<SimUpdate>) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, &[]);
    let mut updates = record(RunId(1), &c, 40.0);
    updates.extend(tail);
    Harness::builder()
        .with_size(size)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
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
    if std::env::var_os("LAYOUT_DEBUG").is_some() {
        eprintln!("{what}: {:?} params need {}", layout.panels, layout.params_need);
        for t in texts(h).iter().filter(|t| t.rect.max.x > screen.max.x - 40.0 || std::env::var_os("LAYOUT_ALL").is_some()) {
            eprintln!("  {:?} {:?} clip {:?}", t.text, t.rect, t.clip);
        }
    }
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
    for tab in ["Phase portrait", "Poincaré points", "Time history", "Power spectrum"] {
        if let Some(node) = h.query_by_label(tab) {
            node.click();
            h.step();
            h.step();
            seen.extend(check_frame(&h, &format!("{what}, tab {tab}")));
        }
    }
    for plot in ["phase", "poincare", "history", "spectrum"] {
        assert!(seen.contains(&plot), "{what}: {plot} never shown ({seen:?})");
    }
}

#[test]
fn every_offered_scale_lays_out_every_panel_without_overlap_cut_text_or_lost_ticks() {
    for size in WINDOWS {
        for scale in scales_at(size, false) {
            for preset in ["default", "period-doubling"] {
                check_config(size, preset, scale, false);
            }
        }
    }
}

#[test]
fn the_lecture_presentation_lays_out_at_every_offered_scale() {
    for size in WINDOWS {
        for scale in scales_at(size, true) {
            check_config(size, "period-doubling", scale, true);
        }
    }
}
