//! A stack of blocks (`[[stack]]`) in the app: every stack preset opens
//! and plays; the scene draws each block where the core puts it; the live
//! stream is the batch run's trajectory; a slider resizes one block; the
//! verdict names the block that overturned; the block-only analyses say
//! so instead of drawing a wrong picture.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use gui_common::{pointer, pump, scene, set_field};
use rocking::gui::RockingApp;
use rocking::model::stack::{Contact, MAX_BLOCKS, SLIDE, StackBlock};
use rocking::sim::protocol::{RunEnd, Speed};
use rocking::sim::runner::LIVE_SAMPLE_DT;
use rocking::sim::stack_run::simulate_stack;
use rocking::sim::{Physical, RunOptions, Scenario};

fn live(preset: &str, speed: Speed) -> Harness<'static, RockingApp> {
    live_with(preset, &[], speed)
}

fn live_with(preset: &str, sets: &[&str], speed: Speed) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, sets);
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RockingApp::live(cc, s, c, speed, false))
}

/// The stack's blocks of `preset`, bottom to top.
fn blocks(c: &Scenario) -> Vec<StackBlock> {
    c.stack.clone().expect("a stack preset")
}

#[test]
fn every_stack_preset_opens_and_plays_in_the_app() {
    for preset in ["tombstone", "statue-on-pedestal", "stack-patterns"] {
        let mut h = live(preset, Speed::Max);
        // Played: τ past 10 (3 s of the tombstone), or the run ended.
        let played = pump(&mut h, Duration::from_secs(60), |a| {
            a.tau() > 10.0 && a.stack_drawn().is_some() || a.end().is_some()
        });
        assert!(played, "{preset}: the stack did not play");
        h.step();
        let app = h.state();
        assert!(app.message().is_none_or(|m| !m.error), "{preset}: {:?}", app.message());
        assert!(
            !matches!(app.end(), Some(RunEnd::Failed(_))),
            "{preset}: {:?}",
            app.end()
        );
        assert!(app.history().samples.len() > 100, "{preset}: samples streamed");
        let (_, drawn) = app.stack_drawn().expect("the stack drawn");
        assert_eq!(drawn.len(), blocks(app.config()).len(), "{preset}: every block drawn");
    }
}

/// The corners of every block, computed here from the config's sizes and
/// offsets: each block's rest rectangle turned, from the top interface
/// down, by each interface's relative rotation q_i about that interface's
/// pivot at rest (the right or left end of the faces' overlap), then moved
/// with the base.
fn corners_by_hand(b: &[StackBlock], contacts: &[Contact], q: &[f64], base_x: f64) -> Vec<[[f64; 2]; 4]> {
    let turn = |p: [f64; 2], c: [f64; 2], a: f64| {
        let (s, co) = f64::sin_cos(a);
        let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
        [c[0] + dx * co + dy * s, c[1] - dx * s + dy * co]
    };
    let (mut x, mut floor) = (0.0, 0.0);
    let mut rest = Vec::new();
    let mut pivots = Vec::new();
    for (j, blk) in b.iter().enumerate() {
        let below = if j == 0 { None } else { Some((x, b[j - 1].width)) };
        if j > 0 {
            x += blk.offset;
        }
        let (l, r) = (x - 0.5 * blk.width, x + 0.5 * blk.width);
        let (l, r) = match below {
            None => (l, r),
            Some((xb, wb)) => (l.max(xb - 0.5 * wb), r.min(xb + 0.5 * wb)),
        };
        pivots.push(if contacts[j] == Contact::Right {
            [r, floor]
        } else {
            [l, floor]
        });
        let h = blk.height;
        let (a, c) = (x - 0.5 * blk.width, x + 0.5 * blk.width);
        rest.push([[a, floor], [c, floor], [c, floor + h], [a, floor + h]]);
        floor += h;
    }
    rest.iter()
        .enumerate()
        .map(|(j, cs)| {
            cs.map(|mut p| {
                for i in (0..=j).rev() {
                    p = turn(p, pivots[i], q[i]);
                }
                [p[0] + base_x, p[1]]
            })
        })
        .collect()
}

#[test]
fn the_drawn_blocks_corners_are_the_core_pose_of_the_streamed_state() {
    let mut h = live("stack-patterns", Speed::RealTime(20.0));
    let rocking = |a: &RockingApp| {
        a.stack_drawn()
            .is_some_and(|(f, _)| f.mode.contacts.iter().filter(|c| **c != Contact::Closed).count() >= 1)
    };
    assert!(pump(&mut h, Duration::from_secs(60), rocking), "the stack never rocked");
    let app = h.state();
    let (frame, drawn) = app.stack_drawn().expect("drawn");
    let b = blocks(app.config());
    let r1 = 0.5 * b[0].width.hypot(b[0].height);
    let base_x = app.shown_sample().expect("a sample shown").base_x * r1;
    let q = &frame.y[..b.len()];
    let want = corners_by_hand(&b, &frame.mode.contacts, q, base_x);
    // Round-off of a few turns of metre-sized corners.
    for (j, (w, d)) in want.iter().zip(drawn).enumerate() {
        for (wc, dc) in w.iter().zip(d) {
            assert!(
                (wc[0] - dc[0]).abs() < 1e-12 && (wc[1] - dc[1]).abs() < 1e-12,
                "block {j}: drawn {dc:?}, by hand {wc:?} (q = {q:?}, contacts {:?})",
                frame.mode.contacts
            );
        }
    }
}

#[test]
fn a_stack_sliding_on_its_floor_is_drawn_where_it_slid() {
    // The statue's pedestal on friction 0.2 under El Centro: it slides
    // 11 mm and nothing lifts.
    let sets = ["stack[0].static=0.2", "stack[0].kinetic=0.16"];
    let mut h = live_with("statue-on-pedestal", &sets, Speed::RealTime(4.0));
    let slid = |a: &RockingApp| {
        a.stack_drawn()
            .is_some_and(|(f, _)| f.mode.sliding() && f.y[SLIDE].abs() > 1e-3)
    };
    assert!(pump(&mut h, Duration::from_secs(90), slid), "the stack never slid 1 mm");
    let app = h.state();
    let (frame, drawn) = app.stack_drawn().expect("drawn");
    let b = blocks(app.config());
    let r1 = 0.5 * b[0].width.hypot(b[0].height);
    let base_x = app.shown_sample().expect("a sample shown").base_x * r1;
    // Every block closed, moved with the base and by the slip.
    let want = corners_by_hand(&b, &frame.mode.contacts, &[0.0; 2], base_x + frame.y[SLIDE]);
    for (j, (w, d)) in want.iter().zip(drawn).enumerate() {
        for (wc, dc) in w.iter().zip(d) {
            assert!(
                (wc[0] - dc[0]).abs() < 1e-12 && (wc[1] - dc[1]).abs() < 1e-12,
                "block {j}: drawn {dc:?}, by hand {wc:?}"
            );
        }
    }
    assert_eq!(frame.mode.name(2), "slide/closed");
    // The plots' sliding displacement is the slip, at every sample.
    let geo = app.config().geometry();
    let mut checked = 0;
    for s in app.history().samples.iter() {
        let f = s.stack.expect("a stack's sample carries its state");
        let shown = geo.sliding(s.state.theta, s.state.x) * geo.r;
        assert!(
            (shown - f.y[SLIDE]).abs() < 1e-12,
            "τ {}: {shown} vs {}",
            f.tau,
            f.y[SLIDE]
        );
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn the_live_app_streams_the_batch_runs_states() {
    for (preset, sets, tau) in [
        ("stack-patterns", &[][..], 40.0),
        ("tombstone", &[][..], 9.0),
        // Sliding on the floor while the statue rocks.
        (
            "statue-on-pedestal",
            &["stack[0].static=0.3", "stack[0].kinetic=0.24"][..],
            25.0,
        ),
    ] {
        let mut h = live_with(preset, sets, Speed::Max);
        assert!(
            pump(&mut h, Duration::from_secs(60), |a| a.tau() >= tau || a.end().is_some()),
            "{preset}: no progress"
        );
        let app = h.state();
        let c = app.config().clone();
        let geo = c.stack_geometry().expect("a stack");
        // The whole batch run (the live steps end on its end at the latest,
        // as its do): sampled on the live grid.
        let opts = RunOptions {
            output_dt: Some(LIVE_SAMPLE_DT),
            ..c.run_options()
        };
        let batch = simulate_stack(geo, c.excitation().expect("excitation"), c.run.zeno_eps, &opts).expect("batch");
        let k = geo.k;
        let mut compared = 0;
        for s in app.history().samples.iter() {
            let f = s.stack.expect("a stack's sample carries its state");
            let i = (f.tau / LIVE_SAMPLE_DT).round() as usize;
            let Some(row) = batch.history.get(i) else { continue };
            assert!((row.tau - f.tau).abs() < 1e-12, "{preset}: τ {} vs {}", row.tau, f.tau);
            assert_eq!(row.mode, f.mode, "{preset}: mode at τ {}", f.tau);
            // The plots' sliding displacement is the slip, tilted or not.
            let unit = c.geometry();
            let shown = unit.sliding(s.state.theta, s.state.x) * unit.r;
            assert!(
                (shown - f.y[SLIDE]).abs() < 1e-12,
                "{preset}: sliding {shown} vs {}",
                f.y[SLIDE]
            );
            for c in (0..k).chain(MAX_BLOCKS..MAX_BLOCKS + k).chain([SLIDE, SLIDE + 1]) {
                assert!(
                    (row.y[c] - f.y[c]).abs() <= 1e-9,
                    "{preset}: y[{c}] at τ {}: batch {}, live {}",
                    f.tau,
                    row.y[c],
                    f.y[c]
                );
            }
            compared += 1;
        }
        assert!(compared > 1000, "{preset}: only {compared} samples compared");
    }
}

#[test]
fn the_banner_names_the_block_that_overturned_on_the_tombstone() {
    let (_, c) = scene("tombstone", &[]);
    let geo = c.stack_geometry().expect("a stack");
    let run = simulate_stack(
        geo,
        c.excitation().expect("excitation"),
        c.run.zeno_eps,
        &c.run_options(),
    )
    .expect("run");
    let answer = Physical::of_stack(&c, &run).line();
    assert!(answer.starts_with("top block overturned at t = 5.30 s"), "{answer}");
    let mut h = live("tombstone", Speed::Max);
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.end().is_some()), "no end");
    assert!(matches!(
        h.state().end(),
        Some(RunEnd::Terminal {
            mode: rocking::model::Mode::Tumbled,
            ..
        })
    ));
    h.step();
    h.step();
    assert_eq!(
        h.query_all_by_label("top block overturned at t = 5.30 s").count(),
        2,
        "the banner and the status bar say the batch run's answer"
    );
}

#[test]
fn a_drag_of_a_blocks_width_slider_resizes_that_block_in_the_next_run() {
    let mut h = live("stack-patterns", Speed::RealTime(1.0));
    assert!(
        pump(&mut h, Duration::from_secs(30), |a| a.stack_drawn().is_some()),
        "drawn"
    );
    let before = blocks(h.state().config());
    let rect = h.get_by_label("B₂ slider").rect();
    let start = egui::pos2(rect.center().x, rect.center().y);
    pointer(&mut h, start, None);
    pointer(&mut h, start, Some(true));
    for k in 1..=5 {
        pointer(&mut h, start + egui::vec2(k as f32, 0.0), None);
    }
    pointer(&mut h, start + egui::vec2(5.0, 0.0), Some(false));
    let after = blocks(h.state().config());
    assert!(
        after[1].width > before[1].width,
        "{} → {}",
        before[1].width,
        after[1].width
    );
    assert_eq!(after[0], before[0], "the other block keeps its size");
    assert_eq!(after[1].height, before[1].height);
    // The next run draws the new width: the top block's lower edge.
    let w = after[1].width;
    let resized = |a: &RockingApp| {
        a.stack().is_some_and(|g| g.size[1][0] == w)
            && a.stack_drawn().is_some_and(|(_, d)| {
                let [l, r, ..] = d[1];
                ((r[0] - l[0]).hypot(r[1] - l[1]) - w).abs() < 1e-12
            })
    };
    assert!(
        pump(&mut h, Duration::from_secs(30), resized),
        "the next run has B₂ = {w}"
    );
}

#[test]
fn the_floors_friction_typed_in_the_panel_makes_the_next_run_slide() {
    let mut h = live("statue-on-pedestal", Speed::RealTime(4.0));
    assert!(
        pump(&mut h, Duration::from_secs(30), |a| a.stack_drawn().is_some()),
        "drawn"
    );
    assert!(
        h.state().config().stack.as_ref().expect("a stack")[0]
            .mu_s
            .is_infinite()
    );
    set_field(&mut h, "μ_s", "0.2");
    set_field(&mut h, "μ_k", "0.16");
    let bottom = h.state().config().stack.as_ref().expect("a stack")[0];
    assert_eq!((bottom.mu_s, bottom.mu_k), (0.2, Some(0.16)));
    let slid = |a: &RockingApp| a.stack_drawn().is_some_and(|(f, _)| f.mode.sliding());
    assert!(pump(&mut h, Duration::from_secs(60), slid), "the next run never slid");
}

#[test]
fn the_plots_show_the_block_chosen_and_the_lyapunov_tab_estimates_the_stacks_exponent() {
    let mut h = live("stack-patterns", Speed::Max);
    assert!(pump(&mut h, Duration::from_secs(30), |a| a.tau() > 5.0), "played");
    assert_eq!(h.state().chosen_body(), Some(1), "the top block by default");
    h.state_mut().choose_body(0);
    h.step();
    let c = h.state().config().clone();
    let b = blocks(&c);
    // Θ = φ/ψ with ψ the bottom block's atan(B/H), φ of the bottom block
    // its own interface's q.
    let psi = (b[0].width / b[0].height).atan();
    for s in h.state().history().samples.iter() {
        let f = s.stack.expect("state");
        assert!((s.theta - f.y[0] / psi).abs() < 1e-12, "τ {}", s.tau);
    }
    // The stack's largest exponent, by two trajectories (its tangent
    // equations are not written): stack-patterns settles onto a stable
    // orbit, so it is negative.
    h.state_mut().show.lyapunov = true;
    assert!(
        pump(&mut h, Duration::from_secs(60), |a| a.lyapunov().value().is_some()),
        "an estimate: {:?}",
        h.state().lyapunov().latest()
    );
    assert!(h.state().lyapunov().value().is_some_and(|l| l < 0.0));
    h.step();
    assert!(
        h.query_by_label_contains("by two trajectories").is_some(),
        "the method is named"
    );
    assert!(h.query_by_label_contains("λ₁ = -").is_some(), "the estimate is shown");
}

#[test]
fn the_outcome_map_of_a_stack_offers_its_excitation_and_maps_it() {
    let mut h = live("stack-patterns", Speed::RealTime(1.0));
    h.state_mut().show.map = true;
    let m = h.state_mut().outcome_map_mut();
    m.set_axes(("excitation.a_h", 0.6, 1.6), ("excitation.omega_h", 3.5, 5.5));
    m.resolution = 8;
    h.step();
    let mut waited = 0;
    while !h.state().outcome_map().done() && waited < 1200 {
        h.step();
        std::thread::sleep(Duration::from_millis(50));
        waited += 1;
    }
    let m = h.state().outcome_map();
    assert_eq!(m.invalid(), None);
    assert!(m.done(), "the map finished");
    // Rest at the lowest amplitude, rocking cycles and tumbling above.
    let classes: std::collections::BTreeSet<String> = (0..8)
        .flat_map(|i| (0..8).map(move |j| (i, j)))
        .filter_map(|(i, j)| m.response(i, j).map(|c| format!("{c:?}")))
        .collect();
    assert!(classes.len() >= 2, "{classes:?}");
    // The menus list what a stack reads; the basin button is off.
    let keys = rocking::gui::panels::outcome_map::keys(h.state().config());
    assert!(keys.contains(&"excitation.a_h") && !keys.contains(&"initial.theta") && !keys.contains(&"friction.static"));
    assert!(h.get_by_label("Θ₀ × Θ'₀").accesskit_node().is_disabled());
}

#[test]
fn a_stack_chosen_from_the_presets_menu_plays_and_a_block_after_it() {
    let (s, c) = scene("default", &[]);
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RockingApp::live(cc, s, c, Speed::Max, false));
    gui_common::open_preset(
        &mut h,
        "Stacks of blocks",
        "tombstone: Does a Japanese three-stone tombstone survive the 1995 Kobe earthquake?",
    );
    h.get_by_label("tombstone: Does a Japanese three-stone tombstone survive the 1995 Kobe earthquake?")
        .click();
    let stack_drawn = |a: &RockingApp| a.stack_drawn().is_some_and(|(_, d)| d.len() == 3);
    assert!(
        pump(&mut h, Duration::from_secs(30), stack_drawn),
        "the three stones drawn"
    );
    assert_eq!(h.state().settings_origin(), "preset tombstone");
    h.state_mut().load_preset("default");
    let block = |a: &RockingApp| a.stack().is_none() && a.tau() > 1.0 && a.history().samples.len() > 10;
    assert!(
        pump(&mut h, Duration::from_secs(30), block),
        "the block runs after the stack"
    );
    assert!(h.state().history().samples.iter().all(|s| s.stack.is_none()));
}

#[test]
fn a_stack_opened_paused_shows_its_first_frame() {
    let (s, c) = scene("statue-on-pedestal", &[]);
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RockingApp::live(cc, s, c, Speed::RealTime(1.0), true));
    assert!(
        pump(&mut h, Duration::from_secs(30), |a| a.stack_drawn().is_some()),
        "the stack stands on the table before Play"
    );
    let (frame, drawn) = h.state().stack_drawn().expect("drawn");
    assert_eq!(frame.tau, 0.0);
    assert!(h.state().paused());
    // At rest: the pedestal's lower corners on the table, the statue's on
    // the pedestal's top (0.9 m up).
    assert!(
        drawn[0][0][1].abs() < 1e-12 && (drawn[1][0][1] - 0.9).abs() < 1e-12,
        "{drawn:?}"
    );
}

#[test]
fn a_perturbed_restart_of_a_stack_says_it_is_for_one_block_and_the_stack_plays_on() {
    let mut h = live("stack-patterns", Speed::RealTime(1.0));
    assert!(
        pump(&mut h, Duration::from_secs(30), |a| a.stack_drawn().is_some()),
        "drawn"
    );
    let run = h.state().run_id();
    h.get_by_label("Reset perturbed").click();
    h.step();
    let said = h.state().message().expect("a note").clone();
    assert!(!said.error && said.text.contains("is for one block"), "{said:?}");
    assert_eq!(h.state().run_id(), run, "the run goes on");
    let tau = h.state().tau();
    assert!(
        pump(&mut h, Duration::from_secs(30), |a| a.tau() > tau + 0.5),
        "still playing"
    );
    assert!(h.state().end().is_none());
}

#[test]
fn the_lyapunov_tab_of_a_harmonic_frame_estimates_its_largest_exponent() {
    // The bridge bent under harmonic shaking: a frame has tangent dynamics
    // (generated from its equations), so the tab runs them, as the
    // block's, and names no other method.
    let sets = [
        "excitation.kind=harmonic",
        "excitation.a_h=\"0.5 g\"",
        "excitation.omega_h=\"1.5 Hz\"",
    ];
    let mut h = live_with("rocking-frame", &sets, Speed::RealTime(1.0));
    h.state_mut().show.lyapunov = true;
    assert!(
        pump(&mut h, Duration::from_secs(60), |a| a.lyapunov().value().is_some()),
        "an estimate: {:?}",
        h.state().lyapunov().latest()
    );
    h.step();
    assert!(
        h.query_by_label_contains("Largest Lyapunov exponent (from the initial state)")
            .is_some(),
        "the block's heading"
    );
    assert!(h.query_by_label_contains("by two trajectories").is_none());
    assert!(h.query_by_label_contains("λ₁ = ").is_some(), "the estimate is shown");
    // The number shown is the library's for the scene and the tab's window.
    let cfg = h.state().config().clone();
    let stage = h.state().lyapunov().latest().expect("a stage").clone();
    let opts = rocking::analysis::lyapunov::LyapunovOptions {
        method: rocking::analysis::lyapunov::Method::Tangent,
        transient_tau: rocking::gui::panels::lyapunov::TRANSIENT_TAU,
        total_tau: stage.total_tau,
        ..Default::default()
    };
    let own = rocking::analysis::lyapunov::of_scenario(&cfg, &opts).expect("lyapunov");
    assert_eq!(Ok(own), stage.answer);
}
