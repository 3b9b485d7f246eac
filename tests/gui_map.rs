//! The app's outcome-map panel, driven headless through egui_kittest:
//! a small map over A_h × Ω_h of the default scene computes in the
//! background, draws several classes, is the analysis layer's fast map
//! (`compute_map` with early stopping and refinement) cell for cell, and a
//! click on a cell loads that scene; a basin map tells its attractors
//! apart with `rocking map`'s colours and legend.
#![cfg(feature = "gui")]

mod gui_common;

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use gui_common::{pointer, pump};
use rocking::analysis::classify::ClassifyOptions;
use rocking::analysis::map_refine::Source;
use rocking::analysis::outcome_map::{Axis, BlockMap, Label, MapPlan, OutcomeMap, block_map, compute_map};
use rocking::analysis::steady::Window;
use rocking::gui::panels::bifurcation::SHORT_WINDOW;
use rocking::gui::panels::outcome_map::{OutcomeMapView, Slot, attractor_color, default_range, window_for};
use rocking::gui::{RockingApp, Settings};
use rocking::plot::outcome_map::attractor_label;
use rocking::sim::Param;

const SIZE: egui::Vec2 = egui::vec2(1280.0, 800.0);

/// A window short enough for a debug build (70 τ holds 76 section points
/// at Ω_h = 8; the view lengthens it for lower Ω_h).
const TINY: Window = Window {
    transient: 10.0,
    tau_end: 70.0,
};

/// The small map: 16 × 16 cells of A_h 0.5–4 × Ω_h 6–12, coarse level
/// 5 × 5. Over this range the default scene is period 1 at small A_h and
/// chaotic or of longer period above (checked with `rocking map`).
const X: (&str, f64, f64) = ("excitation.a_h", 0.5, 4.0);
const Y: (&str, f64, f64) = ("excitation.omega_h", 6.0, 12.0);
const N: usize = 16;

/// Cells of the coarse level the tests ask for (at least, along an axis).
const COARSE: usize = 4;

/// The plan the panel computes with.
const FAST: MapPlan = MapPlan {
    early_stop: true,
    coarse: Some(COARSE),
};

/// Checks the panel's finished map against the engine's, cell for cell:
/// the same label (class and attractor number), computed where the engine
/// computed, the same attractors, and every cell counted as done.
fn assert_same_map(m: &OutcomeMapView, want: &OutcomeMap, nx: usize) {
    for (c, cell) in want.cells.iter().enumerate() {
        let (i, j) = (c % nx, c / nx);
        let label = m.label(i, j).expect("every cell has a label");
        assert_eq!(
            label,
            Label {
                response: Some(cell.response),
                attractor: cell.attractor
            },
            "cell ({i}, {j})"
        );
        let (_, source) = m.cell(i, j).unwrap();
        assert_eq!(source == Source::Computed, cell.computed, "cell ({i}, {j}) computed");
        if cell.computed {
            assert_eq!(m.response(i, j), Some(Some(cell.response)), "cell ({i}, {j})");
        }
    }
    assert_eq!(m.attractors(), want.attractors.as_slice());
    assert_eq!(m.computed().0, want.computed);
    assert_eq!(m.stopped_early(), want.stopped_early);
    let (done, total) = m.progress();
    assert_eq!(done, total, "inherited cells count as done");
}

fn scene() -> (Settings, rocking::sim::Scenario) {
    Settings::from_cli(Some("default"), None, &[]).expect("valid scene")
}

/// The default scene on an empty fixed stream, without a GPU: the map
/// needs no simulation thread.
fn quiet() -> Harness<'static, RockingApp> {
    let (s, c) = scene();
    Harness::builder()
        .with_size(SIZE)
        .with_step_dt(0.05)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()))
}

fn small_map(app: &mut RockingApp, n: usize, window: Window) {
    let m = app.outcome_map_mut();
    m.set_axes(X, Y);
    m.resolution = n;
    m.coarse = COARSE;
    m.window = window;
}

/// Toggles the map from the View menu, starting with every menu closed.
fn toggle_map(h: &mut Harness<'static, RockingApp>) {
    h.key_press(egui::Key::Escape);
    h.step();
    h.step();
    h.get_by_label("View").click();
    for _ in 0..10 {
        h.step();
        if h.query_by_role_and_label(egui::accesskit::Role::CheckBox, "Outcome map")
            .is_some()
        {
            break;
        }
    }
    // The View menu's checkbox (the side panel has a tab of that name too).
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "Outcome map")
        .click();
    h.step();
    h.step();
    h.key_press(egui::Key::Escape);
    h.step();
}

/// A click at `pos`: the pointer there, pressed, released, a frame each.
fn click(h: &mut Harness<'static, RockingApp>, pos: egui::Pos2) {
    pointer(h, pos, None);
    pointer(h, pos, Some(true));
    pointer(h, pos, Some(false));
}

#[test]
fn the_outcome_map_computes_in_the_background_refines_and_a_click_loads_the_cell() {
    let mut h = quiet();
    small_map(h.state_mut(), N, TINY);
    for _ in 0..3 {
        h.step();
    }
    assert_eq!(h.state().outcome_map().maps, 0, "hidden: no map started");
    toggle_map(&mut h);
    assert!(h.state().show.map);
    let _ = h.get_by_label("Map");
    assert!(pump(&mut h, Duration::from_secs(300), |a| a.outcome_map().done()));
    h.step();
    let m = h.state().outcome_map();
    assert_eq!(m.maps, 1);
    assert!(m.invalid().is_none(), "{:?}", m.invalid());
    let drawn = m.drawn().to_vec();
    assert_eq!(drawn.iter().map(|(_, n)| n).sum::<usize>(), N * N, "every cell drawn");
    assert!(drawn.len() >= 2, "at least two classes drawn: {drawn:?}");
    assert!(!drawn.iter().any(|(s, _)| *s == Slot::Failed), "{drawn:?}");
    let (computed, total) = m.computed();
    assert_eq!(total, N * N);
    assert!(
        computed < total,
        "refinement skipped some cells ({computed} of {total})"
    );
    let _ = h.get_by_label_contains("refined where classes meet");

    // The map is the analysis layer's fast map, exactly.
    let (s, _) = scene();
    let base = s.resolve().unwrap();
    let (ax, ay) = (
        Axis::new("--x", X.0, X.1, X.2, N).unwrap(),
        Axis::new("--y", Y.0, Y.1, Y.2, N).unwrap(),
    );
    let spec = BlockMap {
        base: &base,
        x_param: Param::Ah,
        x: &ax,
        y_param: Param::OmegaH,
        y: &ay,
        window: window_for(TINY, Y.1),
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let fast = compute_map(&spec, FAST, &rocking::analysis::silent).unwrap();
    assert_same_map(m, &fast, N);
    assert!(m.stopped_early() > 0, "some cells stopped once their class was certain");
    println!(
        "{} of {} computed cells stopped early",
        m.stopped_early(),
        m.computed().0
    );

    // The computed cells have the class of the full 16 × 16 `block_map`
    // (every cell over its whole window), and most inherited ones too.
    let full = block_map(&spec, &rocking::analysis::silent).unwrap();
    let (mut inherited, mut agree) = (0, 0);
    for (c, want) in full.iter().enumerate() {
        let (i, j) = (c % N, c / N);
        let (slot, source) = m.cell(i, j).expect("every cell has a class");
        match source {
            Source::Computed => {
                assert_eq!(m.response(i, j), Some(Some(want.response)), "cell ({i}, {j})");
                assert_eq!(slot, Slot::of(Some(want.response)));
            }
            Source::Inherited => {
                inherited += 1;
                agree += usize::from(slot == Slot::of(Some(want.response)));
            }
            Source::Unknown => panic!("cell ({i}, {j}) unknown"),
        }
    }
    println!("{agree} of {inherited} inherited cells have the full grid's class");
    assert!(inherited > 0);
    assert!(
        agree as f64 >= 0.9 * inherited as f64,
        "{agree} of {inherited} inherited cells agree with the full grid"
    );

    // A click on a cell loads its two values; the map does not restart.
    let (i, j) = (11, 4);
    let [(kx, x), (ky, y)] = m.cell_values(i, j).unwrap();
    assert_eq!((kx.as_str(), ky.as_str()), (X.0, Y.0));
    let pos = m.cell_position(i, j).expect("drawn");
    click(&mut h, pos);
    h.step();
    let cfg = h.state().config();
    assert_eq!(cfg.excitation.a_h, x);
    assert_eq!(cfg.excitation.omega_h, y);
    assert!(
        h.state()
            .message()
            .is_some_and(|m| !m.error && m.text.starts_with("from the outcome map")),
        "{:?}",
        h.state().message()
    );
    assert_eq!(h.state().outcome_map().maps, 1, "a mapped key only moves the crosshair");
    // Another key restarts the map.
    assert!(h.state_mut().set_key("excitation.a_v", "2.4"));
    h.step();
    assert_eq!(h.state().outcome_map().maps, 2);
}

/// fig4 at A_v = 1: two periodic attractors coexist, period 1 and period 6
/// (`rocking map --preset fig4 --set excitation.a_v=1.0 --x initial.theta
/// -0.9 0.9 40 --y initial.theta_dot -1 1 40` finds them, with or without
/// `--full`; A_v from 0.5 to 1.7 has the same pair). 12 × 12 cells over
/// the view's default basin ranges and its short window: 137 computed.
const BASIN_AV: &str = "excitation.a_v=1.0";
const BASIN_N: usize = 12;

#[test]
fn a_basin_map_tells_its_attractors_apart_as_rocking_map_does() {
    let (s, c) = gui_common::scene("fig4", &[BASIN_AV]);
    let base = s.resolve().unwrap();
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_step_dt(0.05)
        .build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()));
    let (tx, ty) = (
        default_range("initial.theta", 0.0),
        default_range("initial.theta_dot", 0.0),
    );
    {
        let m = h.state_mut().outcome_map_mut();
        m.set_axes(("initial.theta", tx.0, tx.1), ("initial.theta_dot", ty.0, ty.1));
        m.resolution = BASIN_N;
        m.coarse = COARSE;
        assert_eq!(m.window, SHORT_WINDOW);
    }
    toggle_map(&mut h);
    assert!(pump(&mut h, Duration::from_secs(600), |a| a.outcome_map().done()));
    h.step();
    let m = h.state().outcome_map();
    assert!(m.invalid().is_none(), "{:?}", m.invalid());
    assert!(m.is_basin());

    // The engine's fast map of the same cells, exactly.
    let (ax, ay) = (
        Axis::new("--x", "initial.theta", tx.0, tx.1, BASIN_N).unwrap(),
        Axis::new("--y", "initial.theta_dot", ty.0, ty.1, BASIN_N).unwrap(),
    );
    let spec = BlockMap {
        base: &base,
        x_param: Param::Theta0,
        x: &ax,
        y_param: Param::ThetaDot0,
        y: &ay,
        window: window_for(SHORT_WINDOW, base.excitation.omega_h),
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let fast = compute_map(&spec, FAST, &rocking::analysis::silent).unwrap();
    assert_same_map(m, &fast, BASIN_N);

    // Two attractors, each drawn in its own colour (the figure's) and
    // named in the legend as the figure names it.
    let attractors = m.attractors().to_vec();
    let periods: Vec<u32> = attractors.iter().map(|a| a.period).collect();
    assert_eq!(periods.len(), 2, "{attractors:?}");
    assert!(periods.contains(&1) && periods.contains(&6), "{periods:?}");
    let drawn = m.drawn_attractors().to_vec();
    assert_eq!(
        drawn,
        attractors.iter().map(|a| (a.id, a.cells)).collect::<Vec<_>>(),
        "every cell of each attractor drawn in its colour"
    );
    assert_ne!(attractor_color(attractors[0].id), attractor_color(attractors[1].id));
    for a in &attractors {
        let _ = h.get_by_label(&attractor_label(a));
    }
    // The periodic classes are not in the legend: their cells are
    // coloured by attractor.
    assert!(h.query_by_label("period 1").is_none());
    assert!(h.query_all_by_label("tumbled").next().is_some());

    // The full map (every cell over its whole window) has the same two
    // attractors, and the same class wherever the panel computed a cell.
    let full = compute_map(&spec, MapPlan::FULL, &rocking::analysis::silent).unwrap();
    let periods_full: Vec<u32> = full.attractors.iter().map(|a| a.period).collect();
    assert_eq!(periods_full.len(), 2, "{:?}", full.attractors);
    let mut differ = Vec::new();
    for (c, want) in full.cells.iter().enumerate() {
        let (i, j) = (c % BASIN_N, c / BASIN_N);
        let got = m.label(i, j).unwrap();
        if got.response != Some(want.response) {
            differ.push((i, j, got.response, want.response));
        }
    }
    println!(
        "{} of {} cells differ from the full map: {differ:?}",
        differ.len(),
        BASIN_N * BASIN_N
    );
    assert!(differ.is_empty(), "{differ:?}");
}

#[test]
fn a_hidden_outcome_map_stops_and_a_bad_range_is_refused() {
    let mut h = quiet();
    // Long enough that it cannot finish before it is hidden.
    small_map(
        h.state_mut(),
        256,
        Window {
            transient: 600.0,
            tau_end: 800.0,
        },
    );
    toggle_map(&mut h);
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.outcome_map().threads() > 0));
    toggle_map(&mut h);
    assert!(!h.state().show.map);
    assert!(pump(&mut h, Duration::from_secs(60), |a| a.outcome_map().threads() == 0));
    assert!(!h.state().outcome_map().done());
    let cells = h.state().outcome_map().cells;
    let _ = pump(&mut h, Duration::from_millis(300), |_| false);
    assert_eq!(h.state().outcome_map().cells, cells, "nothing received while hidden");

    // Ω_h down to 0 is not a scene: refused before anything runs, naming
    // the key.
    h.state_mut()
        .outcome_map_mut()
        .set_axes(X, ("excitation.omega_h", 0.0, 8.0));
    toggle_map(&mut h);
    assert!(pump(&mut h, Duration::from_secs(60), |a| a
        .outcome_map()
        .invalid()
        .is_some()));
    let msg = h.state().outcome_map().invalid().unwrap().to_string();
    assert!(msg.contains("excitation.omega_h"), "{msg}");
    assert_eq!(h.state().outcome_map().computed().0, 0, "nothing ran");
}

/// Time to the first drawn level and to the whole 128 × 128 A_h × Ω_h map
/// of the default scene over the view's default ranges and window, and
/// the cells refinement computed. A measurement, not a check: run with
/// `cargo test --release --test gui_map -- --ignored --nocapture` (set
/// `OUTCOME_MAP_PNG=path` to keep a rendering, and
/// `OUTCOME_MAP_SCENE="fig4 excitation.a_v=1.0"` for another preset and
/// overrides).
#[test]
#[ignore]
fn measure_the_default_outcome_map() {
    let scene = || match std::env::var("OUTCOME_MAP_SCENE") {
        Ok(words) => {
            let mut words = words.split_whitespace();
            let preset = words.next().unwrap_or("default").to_string();
            let sets: Vec<&str> = words.collect();
            gui_common::scene(&preset, &sets)
        }
        Err(_) => scene(),
    };
    // With `OUTCOME_MAP_PNG=path`, rendered on wgpu and saved there.
    let png = std::env::var("OUTCOME_MAP_PNG").ok();
    let (s, c) = scene();
    let builder = Harness::builder().with_size(SIZE);
    let builder = if png.is_some() {
        builder.wgpu()
    } else {
        builder.with_step_dt(0.05)
    };
    let mut h = builder.build_eframe(move |cc| RockingApp::with_stream(cc, s, c, Vec::new()));
    // `OUTCOME_MAP_BASIN=1`: the Θ₀ × Θ'₀ basin instead; `OUTCOME_MAP_N=64`:
    // another resolution.
    if std::env::var("OUTCOME_MAP_BASIN").is_ok() {
        let m = h.state_mut().outcome_map_mut();
        let (x, y) = (
            default_range("initial.theta", 0.0),
            default_range("initial.theta_dot", 0.0),
        );
        m.set_axes(("initial.theta", x.0, x.1), ("initial.theta_dot", y.0, y.1));
    }
    if let Some(n) = std::env::var("OUTCOME_MAP_N").ok().and_then(|n| n.parse().ok()) {
        h.state_mut().outcome_map_mut().resolution = n;
    }
    h.state_mut().show.map = true;
    let start = Instant::now();
    h.step();
    let mut last = Instant::now();
    while !h.state().outcome_map().done() {
        h.step();
        std::thread::sleep(Duration::from_millis(20));
        if last.elapsed() > Duration::from_secs(30) {
            last = Instant::now();
            let (c, t) = h.state().outcome_map().progress();
            println!("{:.0} s: {c} of {t} cells done", start.elapsed().as_secs_f64());
        }
    }
    let m = h.state().outcome_map();
    let (first, all) = m.timings();
    let (computed, total) = m.computed();
    println!(
        "{n} × {n} on {threads} threads: first level drawn after {first:.1} s, whole map after {all:.1} s; \
         {computed} of {total} cells computed ({share:.1} %), {stopped} stopped early; classes drawn {drawn:?}; \
         attractors {attractors:?}",
        n = m.resolution,
        threads = rayon::current_num_threads(),
        first = first.unwrap_or_default().as_secs_f64(),
        all = all.unwrap_or_default().as_secs_f64(),
        share = 100.0 * computed as f64 / total as f64,
        drawn = m.drawn(),
        stopped = m.stopped_early(),
        attractors = m.drawn_attractors(),
    );
    if let Some(path) = png {
        h.step();
        h.render().expect("render").save(path).expect("png written");
    }
}
