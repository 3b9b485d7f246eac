//! The desktop app, driven headless through egui_kittest: widgets are found
//! by their accessible labels. The label tests need no GPU (the lazy
//! harness gives the app no wgpu state, so it draws the scene with egui's
//! painter); the snapshot tests render on a software wgpu adapter
//! (lavapipe), including the scene's own pipeline.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::{henon, open_menu, open_preset, pointer, pump, scene, set_field};
use rocking::analysis::classify::ClassifyOptions;
use rocking::analysis::lyapunov::{LyapunovOptions, Method, lyapunov};
use rocking::analysis::orbit_diagram::{BlockSweep, Continuation, Grid, Plan, block_sweep};
use rocking::analysis::steady::Window;
use rocking::gui::RockingApp;
use rocking::gui::panels::lyapunov::TRANSIENT_TAU;
use rocking::gui::units::Units;
use rocking::model::units::AccelUnit;
use rocking::sim::Param;
use rocking::sim::protocol::{Batch, GhostState, RunId, SimUpdate, Speed};
use rocking::sim::runner::record;
use rocking::sim::scenario::ExcitationKind;

const SIZE: egui::Vec2 = egui::vec2(1280.0, 800.0);

fn live(paused: bool, speed: Speed) -> Harness<'static, RockingApp> {
    Harness::builder().with_size(SIZE).build_eframe(move |cc| {
        let (s, c) = scene("default", &[]);
        RockingApp::live(cc, s, c, speed, paused)
    })
}

#[test]
fn the_app_opens_on_the_default_preset_and_sets_the_block_moving() {
    let mut h = live(false, Speed::RealTime(1.0));
    assert!(!h.state().gpu(), "the lazy harness has no wgpu state");
    assert!(pump(&mut h, Duration::from_secs(10), |a| a.tau() > 0.5
        && !a.history().samples.is_empty()));
    let info = h.state().run_info().expect("started");
    assert_eq!(info.scenario.excitation.a_h, 2.0);
    assert_eq!(info.scenario.block.mu_s, 0.4);
    let _ = h.get_by_label("Pause");
}

/// Toggles a panel from the View menu, starting with every menu closed.
fn toggle_view(h: &mut Harness<'static, RockingApp>, item: &str) {
    h.key_press(egui::Key::Escape);
    h.step();
    h.step();
    open_menu(h, "View", item);
    h.get_by_label(item).click();
    h.step();
    h.step();
}

#[test]
fn changing_a_parameter_resets_the_simulation_with_it() {
    let mut h = live(false, Speed::RealTime(4.0));
    assert!(pump(&mut h, Duration::from_secs(10), |a| a.tau() > 2.0));
    assert_eq!(h.state().run_id(), RunId(1));
    set_field(&mut h, "A_v", "1.5");
    assert_eq!(
        h.state().config().excitation.a_v,
        1.5,
        "the panel's scene has the new value"
    );
    assert_eq!(h.state().run_id(), RunId(2), "a new run started");
    assert!(pump(&mut h, Duration::from_secs(10), |a| {
        a.run_info().is_some_and(|i| i.scenario.excitation.a_v == 1.5) && !a.history().samples.is_empty()
    }));
    // The new run starts from τ = 0 and none of the old run's data is kept.
    let first = h.state().history().samples.iter().next().expect("samples").tau;
    assert!(first < 0.5, "restarted from τ = 0, first sample at {first}");
    // Defaults that follow other keys still follow them.
    set_field(&mut h, "Ω_h", "5");
    assert_eq!(h.state().config().excitation.omega_v(), 5.0);
}

#[test]
fn a_floor_period_typed_in_the_panel_puts_the_block_on_a_floor_and_the_sliders_follow() {
    let mut h = live(true, Speed::RealTime(1.0));
    h.step();
    assert!(h.state().config().floor.is_none(), "the default scene is on the ground");
    h.get_by_label("Floor").click();
    h.step();
    assert!(
        h.query_by_label("ζ floor slider").is_none(),
        "no floor, no slider to drag one into being"
    );
    set_field(&mut h, "T floor", "0.5");
    let floor = h.state().config().floor.clone().expect("a floor");
    assert_eq!(floor.modes.len(), 1);
    assert_eq!(floor.modes[0].period_s, 0.5);
    assert_eq!(floor.modes[0].damping, 0.05, "the default damping");
    assert_eq!(h.state().run_id(), RunId(2), "a new run on the floor");
    let _ = h.get_by_label("ζ floor slider");
    set_field(&mut h, "ζ floor", "2");
    assert_eq!(
        h.state().config().floor.as_ref().map(|f| f.modes[0].damping),
        Some(0.05),
        "refused"
    );
}

#[test]
fn an_invalid_value_is_refused_with_a_message_naming_the_key() {
    let mut h = live(true, Speed::RealTime(1.0));
    h.step();
    let before = h.state().config().clone();
    set_field(&mut h, "B", "-1");
    assert_eq!(h.state().config(), &before, "the scene is unchanged");
    assert_eq!(h.state().run_id(), RunId(1), "no new run");
    let msg = h.state().message().expect("a message").clone();
    assert!(msg.error);
    assert!(msg.text.starts_with("block.width"), "{}", msg.text);
    let _ = h.get_by_label_contains("block.width");
}

#[test]
fn choosing_a_preset_runs_it() {
    let mut h = live(false, Speed::RealTime(1.0));
    h.step();
    open_preset(&mut h, "The paper's figures", "fig16: Rocking with sliding");
    h.get_by_label("fig16: Rocking with sliding").click();
    h.step();
    let cfg = h.state().config();
    assert_eq!(
        (cfg.excitation.a_h, cfg.excitation.a_v, cfg.excitation.omega_h),
        (3.0, 2.0, 10.0)
    );
    assert_eq!(h.state().run_id(), RunId(2));
    assert!(pump(&mut h, Duration::from_secs(10), |a| {
        a.run_info().is_some_and(|i| i.scenario.excitation.omega_h == 10.0)
    }));
}

#[test]
fn pause_and_step_work() {
    let mut h = live(false, Speed::RealTime(2.0));
    assert!(pump(&mut h, Duration::from_secs(10), |a| a.tau() > 0.5));
    h.get_by_label("Pause").click();
    assert!(pump(&mut h, Duration::from_secs(5), |a| a.paused()));
    // Let the last batches in flight arrive, then the playhead must hold.
    let _ = pump(&mut h, Duration::from_millis(300), |_| false);
    let held = h.state().tau();
    let _ = pump(&mut h, Duration::from_millis(500), |_| false);
    assert_eq!(h.state().tau(), held, "paused: τ holds");
    let _ = h.get_by_label("Play");

    h.get_by_label("Step").click();
    let period = std::f64::consts::TAU / 8.0;
    assert!(pump(&mut h, Duration::from_secs(5), |a| a.tau() > held));
    assert!(
        (h.state().tau() - (held + period)).abs() < 1e-9,
        "a step is one forcing period: {} → {}",
        held,
        h.state().tau()
    );
    assert!(h.state().paused());

    // Keyboard: S steps, space plays, R resets.
    let t = h.state().tau();
    h.key_press(egui::Key::S);
    assert!(pump(&mut h, Duration::from_secs(5), |a| a.tau() > t));
    h.key_press(egui::Key::Space);
    assert!(pump(&mut h, Duration::from_secs(5), |a| !a.paused()));
    h.key_press(egui::Key::R);
    h.step();
    assert_eq!(h.state().run_id(), RunId(2));
}

#[test]
fn a_hidden_panel_does_no_work() {
    let mut h = live(false, Speed::Max);
    assert!(pump(&mut h, Duration::from_secs(20), |a| a
        .history()
        .section
        .points()
        .len()
        > 50));
    let (_, binned, _, _) = h.state().plot_work();
    assert!(binned > 0, "the visible Poincaré plot bins points");

    for item in ["Poincaré points", "Phase portrait", "Power spectrum"] {
        toggle_view(&mut h, item);
    }
    assert!(
        !h.state().show.poincare && !h.state().show.phase && !h.state().show.spectrum,
        "{:?}",
        h.state().show
    );
    let (phase0, binned0, hist0, spectra0) = h.state().plot_work();
    let n0 = h.state().history().section.points().len();
    assert!(pump(&mut h, Duration::from_secs(20), |a| a
        .history()
        .section
        .points()
        .len()
        > n0 + 50));
    let (phase1, binned1, hist1, spectra1) = h.state().plot_work();
    assert_eq!(spectra1, spectra0, "a hidden spectrum computes no FFT");
    assert_eq!(binned1, binned0, "a hidden Poincaré plot bins nothing");
    assert_eq!(phase1, phase0, "a hidden phase portrait builds no trail");
    assert!(hist1 > hist0, "the visible time history still works");

    toggle_view(&mut h, "Poincaré points");
    let _ = pump(&mut h, Duration::from_millis(200), |_| false);
    assert!(h.state().plot_work().1 > binned1, "shown again, it catches up");
}

/// The default scene after 60 τ, from a fixed stream: deterministic.
fn fixed(preset: &str, sets: &[&str], tau: f64) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, sets);
    let updates = record(RunId(1), &c, tau);
    Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
}

#[test]
fn snapshot_of_the_main_window_with_the_wgpu_scene() {
    let mut h = fixed("default", &[], 60.0);
    assert!(h.state().gpu(), "the wgpu harness hands the app a render state");
    h.run();
    let mode = h.state().history().samples.last().expect("samples").mode;
    let img = h.render().expect("render");
    let color = rocking::gui::panels::scene::mode_color(mode);
    let near = |a: u8, b: u8| (a as i32 - b as i32).abs() < 8;
    let block = img
        .pixels()
        .filter(|p| near(p.0[0], color.r()) && near(p.0[1], color.g()) && near(p.0[2], color.b()))
        .count();
    // The paper's block, 4 m tall, fills a good part of the scene's height.
    assert!(block > 5_000, "the block drawn by the wgpu pipeline covers {block} px");
    h.snapshot("main_window");
}

#[test]
fn snapshot_of_a_squat_block() {
    // A squat block (B/H = 1.5) rocking without sliding: uplift needs
    // |a_h| > g B/H, so A_h = 3 (2.9 g); impact.r is set because Housner's
    // default 1 − 1.5 sin²ψ is negative for ψ > 54.7°.
    let sets = [
        "block.width=3",
        "block.height=2",
        "impact.law=ratio",
        "impact.r=0.5",
        "friction.static=inf",
        "excitation.a_h=3",
        "excitation.a_v=0",
        "excitation.omega_h=3",
    ];
    let mut h = fixed("default", &sets, 6.3);
    h.run();
    h.snapshot("squat_block");
}

/// Frame time with 10⁶ Poincaré points and 100 ghost blocks, rendered on the
/// software adapter. A measurement, not a check: run with
/// `cargo test --release --test gui -- --ignored --nocapture measure`.
#[test]
#[ignore]
fn measure_frame_time_with_a_million_points_and_100_ghosts() {
    let (s, c) = scene("default", &[]);
    let mut updates = record(RunId(1), &c, 30.0);
    let last = match &updates[1] {
        SimUpdate::Batch { batch, .. } => *batch.samples.last().expect("samples"),
        other => panic!("expected a batch, got {other:?}"),
    };
    let ghosts: Vec<GhostState> = (0..100)
        .map(|k| GhostState {
            theta: last.theta + 0.003 * k as f64,
            theta_dot: last.theta_dot,
            x: last.x,
            mode: last.mode,
        })
        .collect();
    updates.push(SimUpdate::Batch {
        run: RunId(1),
        batch: Batch {
            ghosts,
            tau: last.tau,
            ..Batch::default()
        },
    });
    let mut h = Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
    h.state_mut().push_section_points(henon(1_000_000));
    h.run();
    let _ = h.render();
    let frames = 30;
    let start = Instant::now();
    for _ in 0..frames {
        h.step();
    }
    let per = start.elapsed().as_secs_f64() * 1000.0 / frames as f64;
    println!("frame without rendering (app + layout + tessellation): {per:.1} ms with 1e6 points, 100 ghosts");
    let start = Instant::now();
    for _ in 0..frames {
        h.step();
        let _ = h.render().expect("render");
    }
    let per = start.elapsed().as_secs_f64() * 1000.0 / frames as f64;
    println!("frame with an offscreen lavapipe render and readback: {per:.1} ms");
    println!("app code per frame: {:.2} ms", h.state().frame_ms());

    // Panning or zooming rebins every point: time that separately.
    let store = h.state().history().section.clone();
    assert!(store.points().len() >= 1_000_000);
    let mut grid = rocking::gui::history::DensityGrid::default();
    let start = Instant::now();
    let rebins = 20;
    for k in 0..rebins {
        let shift = 0.001 * k as f64;
        grid.update(&store, [-0.8 + shift, 0.8, -0.6, 0.6], [700, 500]);
    }
    let per = start.elapsed().as_secs_f64() * 1000.0 / rebins as f64;
    println!("rebinning 1e6 points for a new view: {per:.1} ms");
}

/// The default scene on an empty fixed stream, without a GPU: the
/// bifurcation view's tests need no simulation thread.
fn quiet() -> Harness<'static, RockingApp> {
    let (s, c) = scene("default", &[]);
    Harness::builder()
        .with_size(SIZE)
        .with_step_dt(0.05)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()))
}

/// A sweep of `count` values of A_v from 0 to 2 with a short window (70 τ
/// holds 76 section points at Ω_h = 8; the classifier needs 64).
fn small_sweep(app: &mut RockingApp, count: usize, window: Window) {
    let b = app.bifurcation_mut();
    b.param = "excitation.a_v".into();
    b.from = 0.0;
    b.to = 2.0;
    b.count = count;
    b.window = window;
}

const TINY: Window = Window {
    transient: 10.0,
    tau_end: 70.0,
};

#[test]
fn the_bifurcation_view_sweeps_in_the_background_and_draws_points() {
    let mut h = quiet();
    small_sweep(h.state_mut(), 5, TINY);
    for _ in 0..5 {
        h.step();
    }
    assert_eq!(h.state().bifurcation().sweeps, 0, "hidden: no sweep started");
    toggle_view(&mut h, "Bifurcation diagram");
    assert!(h.state().show.bifurcation);
    let _ = h.get_by_label("Sweep");
    let _ = h.get_by_label("Compute");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.bifurcation().done()));
    h.step();
    let b = h.state().bifurcation();
    assert_eq!(b.sweeps, 1);
    assert_eq!(b.columns().len(), 5);
    assert!(b.drawn > 0, "points are drawn");
    let _ = h.get_by_label_contains("5 values in");

    // What the view drew is what the analysis layer computes.
    let (s, _) = scene("default", &[]);
    let base = s.resolve().unwrap();
    let spec = BlockSweep {
        base: &base,
        param: Param::Av,
        window: TINY,
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let plan = Plan::new(Grid::new(0.0, 2.0, 0.5).unwrap(), Continuation::None, None).unwrap();
    let want = block_sweep(&spec, &plan, &rocking::analysis::silent).unwrap();
    let mut got = b.columns().to_vec();
    got.sort_by(|a, b| a.value.total_cmp(&b.value));
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g.value, w.value);
        assert_eq!(g.response, w.response, "at {}", w.value);
        let thetas: Vec<f64> = w.points.iter().map(|p| p.theta).collect();
        assert_eq!(g.thetas, thetas, "at {}", w.value);
    }
    assert!(
        got.iter().any(|c| !c.thetas.is_empty()),
        "some value has section points"
    );

    // Setting the swept key only moves the marker; any other key restarts.
    assert!(h.state_mut().set_key("excitation.a_v", "1.25"));
    h.step();
    assert_eq!(h.state().bifurcation().sweeps, 1, "the swept key does not restart");
    assert!(h.state_mut().set_key("excitation.a_h", "1.5"));
    h.step();
    assert_eq!(h.state().bifurcation().sweeps, 2, "another key restarts the sweep");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.bifurcation().done()));
}

#[test]
fn a_hidden_bifurcation_view_does_no_work() {
    let mut h = quiet();
    // Long enough that it cannot finish before it is hidden.
    small_sweep(
        h.state_mut(),
        2000,
        Window {
            transient: 600.0,
            tau_end: 800.0,
        },
    );
    for _ in 0..5 {
        h.step();
    }
    assert_eq!(h.state().bifurcation().sweeps, 0);
    assert_eq!(h.state().bifurcation().threads(), 0, "hidden: no thread");
    toggle_view(&mut h, "Bifurcation diagram");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.bifurcation().values > 0));
    toggle_view(&mut h, "Bifurcation diagram");
    assert!(!h.state().show.bifurcation);
    let n = h.state().bifurcation().values;
    // Hidden, the sweep is cancelled: its thread ends long before the
    // 2000 values could have been computed.
    assert!(pump(&mut h, Duration::from_secs(20), |a| a.bifurcation().threads() == 0));
    assert!(!h.state().bifurcation().done());
    let _ = pump(&mut h, Duration::from_millis(300), |_| false);
    assert_eq!(h.state().bifurcation().values, n, "nothing received while hidden");
    assert_eq!(h.state().bifurcation().sweeps, 1);
    // Shown again, it starts over.
    toggle_view(&mut h, "Bifurcation diagram");
    assert_eq!(h.state().bifurcation().sweeps, 2);
    assert!(h.state().bifurcation().threads() > 0);
}

#[test]
fn dragging_a_rectangle_zooms_the_bifurcation_view_at_a_finer_step() {
    let mut h = quiet();
    small_sweep(h.state_mut(), 5, TINY);
    toggle_view(&mut h, "Bifurcation diagram");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.bifurcation().done()));
    // Drag across the middle of the view (the right-most panel).
    let (a, b) = (egui::pos2(980.0, 350.0), egui::pos2(1120.0, 500.0));
    pointer(&mut h, a, None);
    pointer(&mut h, a, Some(true));
    for k in 1..=8 {
        pointer(&mut h, a + (b - a) * (k as f32 / 8.0), None);
    }
    pointer(&mut h, b, Some(false));
    h.step();
    let v = h.state().bifurcation();
    assert_eq!(v.sweeps, 2, "the zoom recomputes");
    assert!(
        0.0 < v.from && v.from < v.to && v.to < 2.0,
        "zoomed into [0, 2]: [{}, {}]",
        v.from,
        v.to
    );
    assert_eq!(v.count, 5, "same number of values over a narrower range");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.bifurcation().done()));
    // Double-click goes back to the full range.
    let c = egui::pos2(1050.0, 420.0);
    // Frames of 0.05 s (the harness's default 0.25 s is longer than a
    // double-click's 0.3 s delay spans two clicks).
    for pressed in [true, false, true, false] {
        pointer(&mut h, c, Some(pressed));
    }
    h.step();
    let v = h.state().bifurcation();
    assert_eq!((v.from, v.to), (0.0, 3.0), "the paper's range for A_v");
    assert_eq!(v.sweeps, 3);
}

/// Time to compute and draw the bifurcation view's default sweep (151
/// values of A_v, τ 200–300) on the default scene. A measurement, not a
/// check: run with `cargo test --release --test gui -- --ignored --nocapture
/// measure_bifurcation`; set `BIFURCATION_PNG=path` to keep a rendering.
#[test]
#[ignore]
fn measure_bifurcation_sweep_time() {
    let (s, c) = scene("default", &[]);
    let mut h = Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()));
    h.state_mut().show.bifurcation = true;
    let start = Instant::now();
    h.step();
    let mut first = None;
    while !h.state().bifurcation().done() {
        h.step();
        if first.is_none() && h.state().bifurcation().drawn > 0 {
            first = Some(start.elapsed());
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    h.step();
    let total = start.elapsed();
    let v = h.state().bifurcation();
    println!(
        "{} values on {} threads: first points drawn after {:.2} s, all drawn after {:.2} s ({} points after decimation)",
        v.columns().len(),
        rayon::current_num_threads(),
        first.unwrap_or(total).as_secs_f64(),
        total.as_secs_f64(),
        v.drawn
    );
    if let Ok(path) = std::env::var("BIFURCATION_PNG") {
        // With the Lyapunov view below it, once its first stage is in.
        h.state_mut().show.lyapunov = true;
        let start = Instant::now();
        while h.state().lyapunov().latest().is_none() {
            h.step();
            std::thread::sleep(Duration::from_millis(5));
        }
        println!("first Lyapunov stage after {:.2} s", start.elapsed().as_secs_f64());
        h.step();
        h.render().expect("render").save(path).expect("png written");
    }
}

#[test]
fn the_lyapunov_view_shows_the_running_largest_exponent() {
    let mut h = quiet();
    for _ in 0..5 {
        h.step();
    }
    assert_eq!(h.state().lyapunov().runs, 0, "hidden: nothing computed");
    toggle_view(&mut h, "Lyapunov exponent");
    assert!(h.state().show.lyapunov);
    assert!(pump(&mut h, Duration::from_secs(120), |a| a
        .lyapunov()
        .latest()
        .is_some()));
    h.step();
    let shown = h.state().lyapunov().value().expect("a finite exponent");
    let _ = h.get_by_label_contains(&format!("λ₁ = {shown:.4} ±"));

    // The number is the analysis layer's, for the scene from its initial state.
    let stage = h.state().lyapunov().latest().expect("a stage").clone();
    let cfg = h.state().config().clone();
    let opts = LyapunovOptions {
        method: Method::Tangent,
        transient_tau: TRANSIENT_TAU,
        total_tau: stage.total_tau,
        ..LyapunovOptions::default()
    };
    let want = lyapunov(&cfg.model().unwrap(), &cfg.initial, &opts).unwrap();
    assert_eq!(stage.answer, Ok(want));

    // Hidden, it stops.
    toggle_view(&mut h, "Lyapunov exponent");
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.lyapunov().threads() == 0));
}

#[test]
fn a_bifurcation_sweep_over_invalid_values_is_refused_naming_the_key() {
    let mut h = quiet();
    {
        let b = h.state_mut().bifurcation_mut();
        b.param = "block.width".into();
        b.from = -1.0;
        b.to = 1.0;
        b.count = 3;
        b.window = TINY;
    }
    toggle_view(&mut h, "Bifurcation diagram");
    assert!(pump(&mut h, Duration::from_secs(30), |a| a
        .bifurcation()
        .invalid()
        .is_some()));
    h.step();
    let msg = h.state().bifurcation().invalid().expect("refused").to_string();
    assert!(msg.contains("block.width"), "{msg}");
    assert!(h.state().bifurcation().columns().is_empty(), "nothing ran");
    let _ = h.get_by_label_contains("block.width");
}

#[test]
fn snapshot_of_ghosts_separating_from_the_block() {
    // Ghost copies spread over a range of Θ, as chaos spreads them: each is
    // outlined in a colour of its own, not in the block's colour.
    let (s, c) = scene("default", &[]);
    let mut updates = record(RunId(1), &c, 20.0);
    let last = updates
        .iter()
        .rev()
        .find_map(|u| match u {
            SimUpdate::Batch { batch, .. } => batch.samples.last().copied(),
            _ => None,
        })
        .expect("samples");
    let ghosts: Vec<GhostState> = (0..8)
        .map(|k| GhostState {
            theta: last.theta + 0.06 * (k as f64 - 3.5),
            theta_dot: last.theta_dot,
            x: last.x,
            mode: last.mode,
        })
        .collect();
    updates.push(SimUpdate::Batch {
        run: RunId(1),
        batch: Batch {
            ghosts,
            tau: last.tau,
            ..Batch::default()
        },
    });
    let mut h = Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates));
    h.run();
    let img = h.render().expect("render");
    // Every ghost's outline in its own colour (0.06 ψ apart: several
    // pixels at the top of the block).
    for k in 0..8 {
        let want = rocking::gui::panels::scene::ghost_color(k, 8).to_array();
        let seen = img
            .as_raw()
            .chunks_exact(4)
            .filter(|p| p.iter().zip(want).all(|(a, b)| a.abs_diff(b) <= 2))
            .count();
        assert!(seen > 100, "ghost {k}: {seen} pixels of its colour");
    }
    h.snapshot("ghosts");
}

#[test]
fn the_contact_force_overlay_draws_the_force_inside_the_cone() {
    // View ▸ Contact force and friction cone: an arrow (255, 90, 90) from the
    // pivot corner, and the cone's two edges. The block rocks about a stuck
    // corner at τ = 20, so the force is drawn and lies inside the cone.
    let mut h = fixed("default", &[], 20.0);
    h.run();
    let arrow = |rgba: &[u8]| {
        rgba.chunks_exact(4)
            .filter(|p| p[0] > 230 && (70..=110).contains(&p[1]) && (70..=110).contains(&p[2]))
            .count()
    };
    let before = arrow(h.render().expect("render").as_raw());
    h.get_by_label("View").click();
    h.run();
    h.get_by_label("Contact force and friction cone").click();
    h.run();
    assert!(h.state().forces_shown(), "the menu item turns the overlay on");
    let after = arrow(h.render().expect("render").as_raw());
    assert!(
        after > before + 100,
        "arrow pixels: {before} without the overlay, {after} with it"
    );
}

// ---- Issue 14: "Will it overturn?" — records in physical units ----

/// The app on `preset` (with `sets`) fed the live run's first `tau` from a
/// fixed stream, without wgpu (labels only).
fn fixed_lazy(preset: &str, sets: &[&str], tau: f64) -> Harness<'static, RockingApp> {
    let (s, c) = scene(preset, sets);
    let updates = record(RunId(1), &c, tau);
    Harness::builder()
        .with_size(SIZE)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, updates))
}

#[test]
fn issue_14_the_kobe_rack_shows_seconds_degrees_its_record_and_the_overturn_banner() {
    // The rack overturns at t = 6.89 s (the batch run's answer, τ = 18.29).
    let mut h = fixed_lazy("kobe-rack", &[], 30.0);
    h.run();
    assert_eq!(h.state().units(), Units::Physical, "a record opens in physical units");
    let _ = h.get_by_label("θ [deg] against t [s]");
    let _ = h.get_by_label("Ground acceleration: kobe-1995.dat · PGA 0.69 g");
    let _ = h.get_by_label("OVERTURNED at t = 6.89 s");
    assert!(
        h.query_by_label("Poincaré points (double-click to fit)").is_none(),
        "a record has no stroboscopic section: no empty Poincaré plot"
    );
}

#[test]
fn the_kobe_rack_on_the_5th_floor_overturns_when_batch_says_and_its_trace_is_the_floors() {
    // --batch --preset kobe-rack-5th-floor: overturned at t = 5.68 s, floor
    // PGA 0.73 g over the ground's 0.69 g. The trace is the floor motion
    // the block feels, titled so, not the ground's.
    let mut h = fixed_lazy("kobe-rack-5th-floor", &[], 30.0);
    h.run();
    let _ = h.get_by_label("Floor acceleration: kobe-1995.dat · floor PGA 0.73 g (ground 0.69 g)");
    let _ = h.get_by_label("OVERTURNED at t = 5.68 s");
    assert!(
        h.query_by_label("Ground acceleration: kobe-1995.dat · PGA 0.69 g")
            .is_none()
    );
}

#[test]
fn issue_14_a_record_run_at_rest_after_the_record_says_survived_with_its_peaks() {
    // The statue rocks to 4.86° (0.39 α) without sliding and is at rest
    // long before El Centro's 53.74 s end (the batch run's answer).
    let (_, c) = scene("elcentro-statue", &[]);
    let end = c.record_end_tau().expect("a record");
    let mut h = fixed_lazy("elcentro-statue", &[], end + 2.0);
    h.run();
    let _ = h.get_by_label("SURVIVED");
    let _ = h.get_by_label("peak rotation 4.9° (0.39 α) · sliding 0.0 cm");
    let _ = h.get_by_label("elcentro-1940-ns.dat · PGA 0.35 g");
}

#[test]
fn issue_14_the_units_switch_is_remembered_across_scenes() {
    let mut h = fixed_lazy("kobe-rack", &[], 5.0);
    h.run();
    h.get_by_label("normalised").click();
    h.run();
    let _ = h.get_by_label("Θ = θ/ψ against τ = p t");
    // A harmonic scene opens in normalised units anyway; the choice of
    // physical units then holds for the next scenes of the session.
    h.get_by_label("physical").click();
    h.run();
    h.state_mut().load_preset("fig16");
    h.run();
    assert_eq!(h.state().units(), Units::Physical, "the user's choice holds");
    let fresh = fixed_lazy("default", &[], 1.0);
    assert_eq!(
        fresh.state().units(),
        Units::Normalised,
        "the paper's scenes open normalised"
    );
}

#[test]
fn issue_14_fields_that_do_not_apply_to_the_excitation_are_hidden() {
    let mut h = fixed_lazy("default", &[], 1.0);
    h.run();
    for shown in ["Ω_h", "A_h", "Φ_h"] {
        assert!(h.query_by_label(shown).is_some(), "harmonic: {shown} shown");
    }
    for hidden in ["record (h)", "scale_h", "unit (h)", "PGA (h)", "pulse shape"] {
        assert!(h.query_by_label(hidden).is_none(), "harmonic: {hidden} hidden");
    }
    h.state_mut().load_preset("kobe-rack");
    h.run();
    for shown in ["record (h)", "unit (h)", "scale_h", "PGA (h)"] {
        assert!(h.query_by_label(shown).is_some(), "record: {shown} shown");
    }
    for hidden in ["Ω_h", "A_h", "Φ_h", "pulse shape"] {
        assert!(h.query_by_label(hidden).is_none(), "record: {hidden} hidden");
    }
}

/// A record file in the temporary folder, unique to this test.
fn temp_record(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rocking-gui-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write record");
    path
}

#[test]
fn issue_14_a_text_record_without_a_unit_is_asked_for_its_unit() {
    let path = temp_record("two-columns.txt", "# t a\n0 0\n0.01 0.8\n0.02 -0.5\n0.03 0\n");
    let mut h = fixed_lazy("default", &[], 1.0);
    h.run();
    h.state_mut().open_record(&path);
    h.run();
    assert!(h.state().record_question().is_some(), "the app asks");
    assert_eq!(
        h.state().config().excitation.kind,
        ExcitationKind::Harmonic,
        "nothing changes before the answer"
    );
    let _ = h.get_by_label_contains("does not say its unit");
    h.get_by_label("m/s²").click();
    h.run();
    assert!(h.state().record_question().is_none(), "answered");
    let cfg = h.state().config();
    assert_eq!(cfg.excitation.kind, ExcitationKind::Record);
    let rec = cfg.excitation.record_h.as_ref().expect("the record");
    assert_eq!(rec.unit, AccelUnit::MetresPerSecond2);
    assert!((rec.series.peak_abs_g() - 0.8 / 9.81).abs() < 1e-12, "read in m/s²");
}

#[test]
fn issue_14_a_one_column_record_is_asked_for_its_unit_and_time_step() {
    let path = temp_record("one-column.txt", "0\n0.2\n-0.1\n0.05\n0\n");
    let mut h = fixed_lazy("default", &[], 1.0);
    h.run();
    h.state_mut().open_record(&path);
    h.run();
    h.get_by_label("g (9.81 m/s²)").click();
    h.run();
    let q = h.state().record_question().expect("the time step is asked next");
    assert!(q.needs_step && q.unit == Some(AccelUnit::G), "{q:?}");
    set_field(&mut h, "time step [s]", "0.02");
    h.get_by_label("Open record").click();
    h.run();
    assert!(h.state().record_question().is_none(), "answered");
    let rec = h
        .state()
        .config()
        .excitation
        .record_h
        .as_ref()
        .expect("the record")
        .clone();
    assert_eq!(rec.dt, Some(0.02));
    assert!((rec.series.duration_s() - 0.08).abs() < 1e-12, "5 samples 0.02 s apart");
}

#[test]
fn issue_14_the_record_presets_are_listed_and_run() {
    let mut h = live(false, Speed::Max);
    h.step();
    for (k, name) in ["kobe-rack", "elcentro-statue"].into_iter().enumerate() {
        h.key_press(egui::Key::Escape);
        h.step();
        let label = format!("{name}: {}", rocking::gui::lessons::figure_title(name));
        open_preset(&mut h, "Engineering", &label);
        h.get_by_label(&label).click();
        h.step();
        assert_eq!(h.state().run_id(), RunId(k as u64 + 2));
        assert!(pump(&mut h, Duration::from_secs(20), |a| {
            a.run_info()
                .is_some_and(|i| i.scenario.excitation.kind == ExcitationKind::Record)
                && a.history().samples.len() > 100
        }));
        assert!(h.state().record_label().is_some(), "{name}: the record is named");
    }
}

#[test]
fn snapshot_of_the_record_unit_question() {
    let path = temp_record("question.txt", "0 0\n0.01 0.8\n0.02 -0.5\n0.03 0\n");
    let mut h = fixed("default", &[], 5.0);
    h.run();
    h.state_mut().open_record(&path);
    h.run();
    let _ = h.get_by_label("Reading the record");
    let _ = h.get_by_label("cm/s² (gal)");
    h.snapshot("record_unit_question");
}
