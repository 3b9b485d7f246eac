//! Sensitive dependence on screen: the ghost copies of Presets ▸ Phenomena ▸
//! Sensitive dependence drawn in colours of their own in the block scene and
//! as trails in the phase portrait, and a run that has ended keeping its
//! phase portrait. Driven headless through egui_kittest; the render test
//! draws on a software wgpu adapter (lavapipe).
#![cfg(feature = "gui")]

mod gui_common;

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use gui_common::scene;
use rocking::gui::block_view::Shape;
use rocking::gui::lessons::{Lesson, PHENOMENA};
use rocking::gui::panels::scene::{Camera, SceneInput, build};
use rocking::gui::{RockingApp, Settings};
use rocking::model::Mode;
use rocking::sim::Scenario;
use rocking::sim::protocol::{Batch, RunEnd, RunId, SimUpdate, Speed};
use rocking::sim::runner::{SimHandle, record};

const SMALL: egui::Vec2 = egui::vec2(1280.0, 800.0);
const LARGE: egui::Vec2 = egui::vec2(1920.0, 1080.0);

fn ghost_lesson() -> &'static Lesson {
    PHENOMENA
        .iter()
        .find(|l| l.title == "Sensitive dependence")
        .expect("the ghost lesson")
}

/// The ghost lesson's run, as the simulation thread streams it: its preset
/// with its ghosts (started at τ = 0, as loading the lesson starts them),
/// played at 5× until `apart` of its ghosts differ from the block's Θ by
/// 0.02 ψ or more (about 2 px at the top of the block at 1280 × 800).
/// Returns the scene, the updates and that τ.
fn ghost_stream(apart: usize) -> (Settings, Scenario, Vec<SimUpdate>, f64) {
    let lesson = ghost_lesson();
    let (s, c) = scene(lesson.preset, &[]);
    let h = SimHandle::spawn(c.clone(), Speed::RealTime(5.0), true, Box::new(|| {})).expect("thread");
    h.set_ghosts(lesson.ghosts.0, lesson.ghosts.1);
    h.resume();
    let mut updates = Vec::new();
    let mut theta = 0.0;
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(120) {
        let Some(u) = h.recv_timeout(Duration::from_millis(100)) else {
            continue;
        };
        if u.run() != RunId(1) {
            continue;
        }
        let reached = match &u {
            SimUpdate::Batch { batch, .. } => {
                if let Some(last) = batch.samples.last() {
                    theta = last.theta;
                }
                let far = batch.ghosts.iter().filter(|g| (g.theta - theta).abs() >= 0.02).count();
                // Apart from each other too: started from ε·(k+1)/20 the
                // ghosts first leave the block together, as one group.
                let (lo, hi) = batch
                    .ghosts
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| {
                        (lo.min(g.theta), hi.max(g.theta))
                    });
                (far >= apart && hi - lo >= 0.05).then_some(batch.tau)
            }
            _ => None,
        };
        updates.push(u);
        if let Some(tau) = reached {
            return (s, c, updates, tau);
        }
    }
    panic!("{apart} ghosts did not drift 0.02 ψ from the block within 120 s");
}

fn app(size: egui::Vec2, s: Settings, c: Scenario, updates: Vec<SimUpdate>) -> Harness<'static, RockingApp> {
    let mut h = Harness::builder()
        .with_size(size)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
    h.step();
    h.step();
    h
}

/// The shapes in `with` that are not in `without` (each matched once).
fn extra(with: &[Shape], without: &[Shape]) -> Vec<Shape> {
    let mut rest = without.to_vec();
    with.iter()
        .filter(|s| match rest.iter().position(|r| r == *s) {
            Some(i) => {
                rest.swap_remove(i);
                false
            }
            None => true,
        })
        .copied()
        .collect()
}

/// The corners of a rectangle shape, in metres.
fn corners(s: &Shape) -> [[f64; 2]; 4] {
    let [cx, cy] = s.center.map(f64::from);
    let [hx, hy] = s.half_size.map(f64::from);
    let (sn, cs) = f64::from(s.angle_shape[0]).sin_cos();
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(a, b)| {
        let (lx, ly) = (a * hx, b * hy);
        [cx + lx * cs + ly * sn, cy - lx * sn + ly * cs]
    })
}

/// Ghost shapes the scene builds for the app's state: (their distinct
/// colours, largest distance between the same corner of two ghosts'
/// rectangles in physical pixels, ghosts whose rectangle is 2 px or more
/// from the block's).
fn ghost_shapes(h: &Harness<'static, RockingApp>) -> (Vec<egui::Color32>, f64, usize) {
    let app = h.state();
    let info = app.run_info().expect("started");
    let sample = app.shown_sample().expect("drawn");
    let rect = app.scene_rect().expect("scene");
    let input = |ghosts| SceneInput {
        geometry: info.geometry,
        sample,
        ghosts,
        mu_s: info.scenario.block.mu_s,
        terminal: None,
        flash: 0.0,
        forces: false,
        frame: None,
    };
    let (with, scale, _) = build(&input(app.ghosts()), rect, &mut Camera::default());
    let (without, _, _) = build(&input(&[]), rect, &mut Camera::default());
    let ghosts = extra(&with, &without);
    let mut colours: Vec<egui::Color32> = ghosts
        .iter()
        .map(|s| {
            let [r, g, b, a] = s.color.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
            egui::Color32::from_rgba_premultiplied(r, g, b, a)
        })
        .collect();
    colours.sort_unstable_by_key(|c| c.to_array());
    colours.dedup();
    let half = [0.5 * info.geometry.width, 0.5 * info.geometry.height].map(|v| v as f32);
    let rects: Vec<[[f64; 2]; 4]> = ghosts
        .iter()
        .filter(|s| s.angle_shape[1] != 1.0 && s.half_size == half)
        .map(corners)
        .collect();
    let block = without
        .iter()
        .rev()
        .find(|s| s.half_size == half)
        .map(corners)
        .expect("the block");
    let px = scale * f64::from(h.ctx.pixels_per_point());
    let dist = |a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]| {
        (0..4)
            .map(|k| (a[k][0] - b[k][0]).hypot(a[k][1] - b[k][1]) * px)
            .fold(0.0, f64::max)
    };
    let mut spread = 0.0_f64;
    for (i, a) in rects.iter().enumerate() {
        for b in &rects[i + 1..] {
            spread = spread.max(dist(a, b));
        }
    }
    let apart = rects.iter().filter(|r| dist(r, &block) >= 2.0).count();
    (colours, spread, apart)
}

#[test]
fn twenty_ghosts_are_drawn_in_twenty_colours_and_spread_apart_at_every_scale() {
    let (s, c, updates, tau) = ghost_stream(10);
    println!("10 of 20 ghosts 0.02 ψ or more from the block at τ = {tau:.1}");
    for size in [SMALL, LARGE] {
        let mut h = app(size, s.clone(), c.clone(), updates.clone());
        assert_eq!(h.state().ghosts().len(), 20);
        for scale in rocking::gui::prefs::offered([size.x, size.y], false) {
            let ctx = h.ctx.clone();
            h.state_mut().set_presentation_scale(&ctx, scale);
            h.step();
            h.step();
            let (colours, spread, apart) = ghost_shapes(&h);
            let colours = colours.len();
            let rect = h.state().scene_rect().expect("scene");
            println!(
                "{}×{} at {:.0} %: scene {:.0}×{:.0} pt, {colours} ghost colours, ghosts up to {spread:.1} px apart, {apart} of 20 at least 2 px from the block",
                size.x,
                size.y,
                100.0 * scale,
                rect.width(),
                rect.height()
            );
            assert!(colours >= 20, "{colours} colours for 20 ghosts");
            // A scene the layout squeezes to a strip shows no block to speak
            // of (the layout's own tests hold it to its share of the window).
            if rect.height() < 60.0 {
                println!("  (scene {:.0} pt tall: spread not checked)", rect.height());
                continue;
            }
            assert!(spread > 2.0, "ghosts within {spread:.2} px of each other");
        }
    }
}

#[test]
fn the_phase_portrait_draws_one_trail_per_ghost_in_its_scene_colour() {
    let (s, c, updates, tau) = ghost_stream(10);
    let h = app(SMALL, s, c, updates);
    let (scene_colours, _, _) = ghost_shapes(&h);
    let drawn = &h.state().phase_view().ghosts_drawn;
    println!(
        "τ = {tau:.1}: {} ghost trails, points {:?}",
        drawn.len(),
        drawn.iter().map(|d| d.1).collect::<Vec<_>>()
    );
    assert_eq!(drawn.len(), 20, "one trail per ghost");
    for (k, (colour, points)) in drawn.iter().enumerate() {
        assert!(*points >= 4, "ghost {k}: {points} trail points");
        assert!(
            scene_colours.contains(colour),
            "ghost {k}'s trail colour {colour:?} is not in the scene"
        );
    }
    let mut trail_colours: Vec<egui::Color32> = drawn.iter().map(|d| d.0).collect();
    trail_colours.sort_unstable_by_key(|c| c.to_array());
    trail_colours.dedup();
    assert_eq!(trail_colours.len(), 20, "a colour per ghost");
}

/// Free rocking on a method that reaches rest (the live Taylor session's
/// impact accumulation is the simulation's own fix): up to `tau` τ, and
/// ended at rest there if `ended`.
fn free_rocking(tau: f64, ended: bool) -> (Settings, Scenario, Vec<SimUpdate>) {
    let (s, c) = scene("free-rocking", &["run.method=dop853"]);
    let mut updates = record(RunId(1), &c, tau);
    if ended {
        updates.retain(|u| !matches!(u, SimUpdate::Finished { .. }));
        updates.push(SimUpdate::Finished {
            run: RunId(1),
            end: RunEnd::Rest {
                tau,
                max_abs_theta: 0.5,
                max_abs_sliding: 0.0,
            },
        });
    }
    (s, c, updates)
}

/// Trail points drawn away from the origin (the spiral, not the rest point).
fn spiral_points(h: &Harness<'static, RockingApp>) -> usize {
    h.state()
        .phase_view()
        .drawn
        .iter()
        .filter(|p| p[0].hypot(p[1]) > 0.02)
        .count()
}

#[test]
fn a_free_rocking_run_that_ended_at_rest_keeps_its_spiral_in_the_phase_portrait() {
    // When the block comes to rest.
    let (_, _, full) = free_rocking(60.0, false);
    let rest = full
        .iter()
        .find_map(|u| match u {
            SimUpdate::Batch { batch, .. } => batch.samples.iter().find(|s| s.mode == Mode::Rest).map(|s| s.tau),
            _ => None,
        })
        .expect("comes to rest");
    let (s, c, at_rest) = free_rocking(rest + 1.0, false);
    let before = spiral_points(&app(SMALL, s, c, at_rest));
    // The run goes on at rest and ends there 60 τ in.
    let (s, c, ended) = free_rocking(60.0, true);
    let h = app(SMALL, s, c, ended);
    assert!(h.state().end().is_some());
    let after = spiral_points(&h);
    println!("rest at τ = {rest:.2}; spiral points 1 τ after rest {before}, after the end at τ = 60 {after}");
    assert!(before > 100, "{before}");
    assert!(after >= before, "the spiral faded: {before} -> {after} points");
    // The whole spiral, from the release at Θ = 0.5 (the preset's Θ₀).
    let widest = h
        .state()
        .phase_view()
        .drawn
        .iter()
        .map(|p| p[0].abs())
        .fold(0.0, f64::max);
    assert!(
        widest >= 0.49,
        "the held trail reaches back to Θ = {widest}, not the release at 0.5"
    );
}

/// Pixels of two renders that differ, and how many distinct colours among
/// them cover 20 pixels or more.
fn differing(a: &[u8], b: &[u8]) -> (usize, usize) {
    let mut counts = std::collections::HashMap::new();
    let mut n = 0;
    for (p, q) in a.chunks_exact(4).zip(b.chunks_exact(4)) {
        if p != q {
            n += 1;
            *counts.entry(p).or_insert(0usize) += 1;
        }
    }
    (n, counts.values().filter(|&&c| c >= 20).count())
}

#[test]
fn the_ghost_lesson_renders_every_ghost_visibly() {
    let (s, c, updates, tau) = ghost_stream(10);
    let no_ghosts: Vec<SimUpdate> = updates
        .iter()
        .cloned()
        .map(|u| match u {
            SimUpdate::Batch { run, batch } => SimUpdate::Batch {
                run,
                batch: Batch {
                    ghosts: Vec::new(),
                    ..batch
                },
            },
            other => other,
        })
        .collect();
    let render = |updates: Vec<SimUpdate>| {
        let (s, c) = (s.clone(), c.clone());
        let mut h = Harness::builder()
            .with_size(SMALL)
            .wgpu()
            .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
        h.step();
        h.step();
        h.render().expect("render")
    };
    let with = render(updates);
    let without = render(no_ghosts);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    with.save(dir.join("ghost_lesson.png")).expect("save");
    let (pixels, colours) = differing(with.as_raw(), without.as_raw());
    println!(
        "τ = {tau:.1}: the ghosts change {pixels} pixels, in {colours} colours of 20 pixels or more; {}",
        dir.join("ghost_lesson.png").display()
    );
    // Before the ghosts had colours of their own: 1,500 to 1,900 pixels
    // changed, in one or two colours (a pale sliver at the block's edge).
    assert!(pixels >= 5_000, "the ghosts change {pixels} pixels");
    assert!(colours >= 10, "{colours} ghost colours on screen");
    // Each ghost's own colour, where its outline covers whole pixels.
    let seen: Vec<usize> = (0..20)
        .map(|k| {
            let want = rocking::gui::panels::scene::ghost_color(k, 20).to_array();
            with.as_raw()
                .chunks_exact(4)
                .filter(|p| p.iter().zip(want).all(|(a, b)| a.abs_diff(b) <= 2))
                .count()
        })
        .collect();
    println!("pixels of each ghost's colour: {seen:?}");
    // How many show depends on where chaos has taken them: ghosts still
    // within a pixel of each other cover each other.
    let visible = seen.iter().filter(|&&n| n >= 20).count();
    assert!(
        visible >= 5,
        "{visible} of 20 ghosts show 20 pixels or more of their colour"
    );
}
