//! The fast outcome map against the full one: early stopping never
//! changes a cell's class, refinement finds a boundary the coarse grid
//! straddles, coexisting attractors get their own labels, and the map does
//! not depend on the thread count.

use rocking::analysis::classify::{ClassifyOptions, Response};
use rocking::analysis::outcome_map::{Axis, BlockMap, MapPlan, compute_map};
use rocking::analysis::settle::cell_response;
use rocking::analysis::silent;
use rocking::analysis::steady::{Window, steady_response};
use rocking::io::config::load;
use rocking::sim::{Param, Scenario};

fn preset(name: &str, set: &[&str]) -> Scenario {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    load(Some(name), None, &set).unwrap()
}

/// fig3 at (A_h, Ω_h) (Ω_v follows Ω_h).
fn fig3(a_h: f64, omega_h: f64) -> Scenario {
    Param::apply(&preset("fig3", &[]), &[(Param::Ah, a_h), (Param::OmegaH, omega_h)]).unwrap()
}

#[test]
fn early_stopping_never_changes_a_cells_class_across_every_class() {
    let w = Window::default();
    let o = ClassifyOptions::default();
    // (scene, what it is, the τ its run must stop by, if it stops early):
    // cells of the
    // fig3 A_h × Ω_h map in the middle of each class's region (the values
    // are cells of the 200 × 200 map), a chattering lift-and-land cycle
    // next to the rest threshold, and fig7, whose chaotic transient
    // tumbles late, at τ = 514: a run that looks settled for a while must
    // not be stopped as periodic.
    let cases: Vec<(Scenario, &str, Option<f64>)> = vec![
        (fig3(0.3, 8.0), "rest", Some(10.0)),
        (fig3(2.5, 10.0), "period 1", Some(200.0)),
        (fig3(1.6, 9.0), "period 2", Some(200.0)),
        (fig3(0.8723618090452261, 4.060301507537688), "period 3", Some(800.0)),
        (fig3(1.5427135678391959, 4.5125628140703515), "period 4", Some(800.0)),
        (fig3(1.7613065326633166, 5.21608040201005), "period 6", Some(800.0)),
        (fig3(1.6010050251256283, 4.6633165829145735), "chaotic", None),
        (fig3(1.6010050251256283, 4.060301507537688), "tumbled", None),
        (fig3(0.8, 8.0), "chattering period 1", Some(200.0)),
        (preset("fig7", &[]), "fig7: late tumble", None),
        (
            preset("fig4", &["run.flight=\"stop\"", "excitation.a_v=6"]),
            "flight",
            None,
        ),
    ];
    let mut seen = Vec::new();
    for (cfg, what, stops) in cases {
        let full = steady_response(&cfg, &w, &o, None).unwrap();
        let unwatched = cell_response(&cfg, &w, &o, None, false, &[], None).unwrap();
        let fast = cell_response(&cfg, &w, &o, None, true, &[], None).unwrap();
        assert_eq!(
            unwatched.response, full.response,
            "{what}: the unwatched run is the full run"
        );
        assert_eq!(unwatched.max_abs_theta, full.max_abs_theta, "{what}");
        assert_eq!(fast.response, full.response, "{what}: early stopping changed the class");
        assert_eq!(
            fast.stopped_at.is_some(),
            stops.is_some(),
            "{what}: stopped at {:?} ({})",
            fast.stopped_at,
            full.response
        );
        if let (Some(t), Some(by)) = (fast.stopped_at, stops) {
            assert!(t < by, "{what}: stopped only at τ = {t}");
        }
        if stops.is_none() {
            assert_eq!(
                fast.max_abs_theta, full.max_abs_theta,
                "{what}: the whole run is the full run"
            );
        }
        seen.push(full.response.name());
    }
    for class in ["rest", "periodic", "chaotic", "tumbled", "flight"] {
        assert!(seen.contains(&class), "no {class} case");
    }
    // The late tumble really is late: the early stop had 500 τ to be fooled.
    let fig7 = preset("fig7", &[]);
    let r = rocking::sim::simulate(fig7.model().unwrap(), &fig7.initial, &fig7.run_options()).unwrap();
    assert!(r.tumble_tau.is_some_and(|t| t > 500.0), "{:?}", r.tumble_tau);
}

#[test]
fn refinement_finds_a_boundary_that_the_coarse_grid_straddles() {
    // The rest threshold of fig3 at Ω_h = 8 lies near A_h = 0.78, between
    // two lattice columns of the coarse grid (stride 8 over 65 columns):
    // the fast map must find the same boundary column as the full one.
    let base = preset("fig3", &[]);
    let x = Axis::new("--x", "excitation.a_h", 0.5, 0.82, 65).unwrap();
    let y = Axis::new("--y", "excitation.omega_h", 8.0, 8.0, 1).unwrap();
    let window = Window::default();
    let spec = BlockMap {
        base: &base,
        x_param: Param::Ah,
        x: &x,
        y_param: Param::OmegaH,
        y: &y,
        window,
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let plan = MapPlan {
        early_stop: true,
        coarse: Some(9),
    };
    let fast = compute_map(&spec, plan, &silent).unwrap();
    let full = compute_map(&spec, MapPlan::FULL, &silent).unwrap();
    let classes = |m: &[rocking::analysis::outcome_map::Cell]| m.iter().map(|c| c.response).collect::<Vec<_>>();
    assert_eq!(classes(&fast.cells), classes(&full.cells));
    let first_moving = |m: &[rocking::analysis::outcome_map::Cell]| m.iter().position(|c| c.response != Response::Rest);
    let edge = first_moving(&full.cells).unwrap();
    assert!(edge % 8 != 0, "the boundary (column {edge}) is between coarse columns");
    assert!(
        fast.computed < fast.cells.len() / 2,
        "{} of {} run",
        fast.computed,
        fast.cells.len()
    );
    assert!(fast.cells[edge].computed && fast.cells[edge - 1].computed);
}

/// The basin map of fig4 at A_v = 1 over (Θ₀, Θ'₀): a period-1 and a
/// period-6 attractor coexist.
fn basin_spec<'a>(base: &'a Scenario, x: &'a Axis, y: &'a Axis) -> BlockMap<'a> {
    BlockMap {
        base,
        x_param: Param::Theta0,
        x,
        y_param: Param::ThetaDot0,
        y,
        window: Window::default(),
        classify: ClassifyOptions::default(),
        lyapunov: None,
    }
}

#[test]
fn two_coexisting_attractors_get_different_labels() {
    let base = preset("fig4", &["excitation.a_v=1"]);
    let x = Axis::new("--x", "initial.theta", -0.3, 0.3, 7).unwrap();
    let y = Axis::new("--y", "initial.theta_dot", -0.2, 0.4, 7).unwrap();
    let map = compute_map(&basin_spec(&base, &x, &y), MapPlan::FAST, &silent).unwrap();
    let periods: Vec<u32> = map.attractors.iter().map(|a| a.period).collect();
    assert!(
        periods.contains(&1) && periods.contains(&6),
        "attractors {:?}",
        map.attractors
    );
    for (i, a) in map.attractors.iter().enumerate() {
        assert_eq!(a.id as usize, i + 1);
        let cells = map.cells.iter().filter(|c| c.attractor == Some(a.id)).count();
        assert_eq!(cells, a.cells);
        assert!(cells > 0);
    }
    // Every periodic cell has an attractor whose period is its own.
    for c in &map.cells {
        match c.response {
            Response::Periodic { period } => {
                let a = &map.attractors[c.attractor.unwrap() as usize - 1];
                assert_eq!(a.period, period);
            }
            _ => assert_eq!(c.attractor, None),
        }
    }
    // A parameter map has no attractors: its cells are different systems.
    let ah = Axis::new("--x", "excitation.a_h", 2.5, 3.0, 2).unwrap();
    let spec = BlockMap {
        x_param: Param::Ah,
        x: &ah,
        ..basin_spec(&base, &ah, &y)
    };
    let m = compute_map(&spec, MapPlan::FAST, &silent).unwrap();
    assert!(m.attractors.is_empty() && m.cells.iter().all(|c| c.attractor.is_none()));
}

#[test]
fn the_map_is_the_same_for_any_thread_count() {
    // A basin map with two attractors and a parameter map, both refined.
    let base = preset("fig4", &["excitation.a_v=1"]);
    // 9 × 9 cells on a coarse lattice of stride 2: the second level's
    // runs may stop on reaching the attractors the first level found.
    let x = Axis::new("--x", "initial.theta", -0.3, 0.3, 9).unwrap();
    let y = Axis::new("--y", "initial.theta_dot", -0.2, 0.4, 9).unwrap();
    let basin = basin_spec(&base, &x, &y);
    let fig3 = preset("fig3", &[]);
    let ah = Axis::new("--x", "excitation.a_h", 0.3, 1.1, 40).unwrap();
    let om = Axis::new("--y", "excitation.omega_h", 7.5, 8.5, 3).unwrap();
    let spec = BlockMap {
        base: &fig3,
        x_param: Param::Ah,
        x: &ah,
        y_param: Param::OmegaH,
        y: &om,
        ..basin
    };
    let plan = |coarse| MapPlan {
        early_stop: true,
        coarse: Some(coarse),
    };
    // The parameter map's coarse lattice has stride 4, the basin's 2.
    let on = |spec: &BlockMap<'_>, coarse, threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| compute_map(spec, plan(coarse), &silent).unwrap())
    };
    let (one, basin_one) = (on(&spec, 6, 1), on(&basin, 5, 1));
    assert!(one.computed < one.cells.len(), "the map was refined");
    assert!(basin_one.attractors.len() >= 2, "{:?}", basin_one.attractors);
    assert!(basin_one.reached_known > 0, "some runs stopped on a known attractor");
    for threads in [2, 3] {
        assert_eq!(on(&spec, 6, threads), one, "{threads} threads");
        assert_eq!(on(&basin, 5, threads), basin_one, "{threads} threads");
    }
}

#[test]
fn a_run_that_reaches_a_known_attractor_stops_with_its_full_runs_class() {
    // fig4 at A_v = 1: a period-1 and a period-6 attractor coexist. Their
    // cycles, as runs converged onto them to 1e-5 of their amplitude,
    // are what a basin map knows after its first level.
    let base = preset("fig4", &["excitation.a_v=1"]);
    let (w, o) = (Window::default(), ClassifyOptions::default());
    let at = |theta: f64, theta_dot: f64| {
        Param::apply(&base, &[(Param::Theta0, theta), (Param::ThetaDot0, theta_dot)]).unwrap()
    };
    let axis = |n: usize, a: f64, b: f64| (0..n).map(move |i| a + (b - a) * i as f64 / (n - 1) as f64);
    let starts: Vec<(f64, f64)> = axis(5, -0.3, 0.3)
        .flat_map(|t| axis(4, -0.2, 0.4).map(move |d| (t, d)))
        .collect();
    let mut known: Vec<Vec<[f64; 3]>> = Vec::new();
    for &(t, d) in &starts {
        let c = cell_response(&at(t, d), &w, &o, None, true, &[], None).unwrap();
        if !c.cycle.is_empty() && !known.iter().any(|k| k.len() == c.cycle.len()) {
            known.push(c.cycle);
        }
    }
    let mut periods: Vec<usize> = known.iter().map(Vec::len).collect();
    periods.sort();
    assert_eq!(periods, vec![1, 6], "the two attractors");
    // The same cells again, knowing both: each class is the full run's,
    // and a run that stops on a known cycle has the full run's last cycle
    // (at some phase) to the classifier's tolerance, 1e-3 of the
    // amplitude (the known cycle was converged to 1e-5, the full run's
    // window to better than that).
    let (mut reached, mut saved) = (0, 0.0);
    for &(t, d) in &starts {
        let cfg = at(t, d);
        let full = steady_response(&cfg, &w, &o, None).unwrap();
        let alone = cell_response(&cfg, &w, &o, None, true, &[], None).unwrap();
        let knowing = cell_response(&cfg, &w, &o, None, true, &known, None).unwrap();
        assert_eq!(knowing.response, full.response, "({t}, {d})");
        if !knowing.reached_known {
            assert_eq!(knowing, alone, "({t}, {d}): not reached, the same run");
            continue;
        }
        reached += 1;
        let (stop, before) = (knowing.stopped_at.unwrap(), alone.stopped_at.unwrap());
        assert!(stop <= before, "({t}, {d}): stopped at {stop}, not before {before}");
        saved += before - stop;
        let k = knowing.cycle.len();
        let last: Vec<[f64; 3]> = full.points[full.points.len() - k..]
            .iter()
            .map(|r| [r.theta, r.theta_dot, r.x_dot])
            .collect();
        let amp = (0..3)
            .map(|d| last.iter().map(|p| p[d].abs()).fold(0.0, f64::max))
            .collect::<Vec<_>>();
        let agrees = (0..k).any(|s| {
            (0..k).all(|i| (0..3).all(|d| (knowing.cycle[(i + s) % k][d] - last[i][d]).abs() <= 1e-3 * amp[d] + 1e-9))
        });
        assert!(agrees, "({t}, {d}): {:?} against {:?}", knowing.cycle, last);
    }
    assert!(reached >= starts.len() / 2, "{reached} of {} reached", starts.len());
    assert!(saved > 10.0 * reached as f64, "saved {saved} τ over {reached} runs");
    // A cycle nowhere near the trajectory (the period-1 point moved by a
    // tenth of its amplitude) is never reached: the run is the one alone.
    let far: Vec<Vec<[f64; 3]>> = vec![
        known
            .iter()
            .find(|k| k.len() == 1)
            .unwrap()
            .iter()
            .map(|p| p.map(|x| 1.1 * x))
            .collect(),
    ];
    for &(t, d) in &starts[..6] {
        let cfg = at(t, d);
        let alone = cell_response(&cfg, &w, &o, None, true, &[], None).unwrap();
        assert_eq!(cell_response(&cfg, &w, &o, None, true, &far, None).unwrap(), alone);
    }
}

#[test]
fn a_basin_map_whose_runs_stop_on_known_attractors_is_the_full_map() {
    // fig4 at A_v = 1 over 13 × 13 initial states, a coarse lattice of
    // stride 4: the cells of the finer levels may stop on reaching the
    // cycles the coarser ones found, or on landing in their labelled
    // cells, and must still reach the full map's class and attractor.
    let base = preset("fig4", &["excitation.a_v=1"]);
    let x = Axis::new("--x", "initial.theta", -0.6, 0.6, 13).unwrap();
    let y = Axis::new("--y", "initial.theta_dot", -0.6, 0.6, 13).unwrap();
    let spec = BlockMap {
        window: Window {
            transient: 100.0,
            tau_end: 200.0,
        },
        ..basin_spec(&base, &x, &y)
    };
    let plan = MapPlan {
        early_stop: true,
        coarse: Some(3),
    };
    let fast = compute_map(&spec, plan, &silent).unwrap();
    let full = compute_map(&spec, MapPlan::FULL, &silent).unwrap();
    assert!(fast.reached_known > 0, "no run stopped on a known attractor");
    assert!(fast.attractors.len() >= 2, "{:?}", fast.attractors);
    let cycle_of = |m: &rocking::analysis::outcome_map::OutcomeMap, id: Option<u32>| {
        id.map(|a| m.attractors[a as usize - 1].cycle.clone())
    };
    for (i, (a, b)) in fast.cells.iter().zip(&full.cells).enumerate() {
        assert_eq!(a.response, b.response, "cell {i}");
        // The same attractor: numbers may differ only if discovered in
        // another order, so compare their cycles' periods and points.
        let (ca, cb) = (cycle_of(&fast, a.attractor), cycle_of(&full, b.attractor));
        assert_eq!(ca.as_ref().map(Vec::len), cb.as_ref().map(Vec::len), "cell {i}");
        if let (Some(ca), Some(cb)) = (ca, cb) {
            let near = ca
                .iter()
                .zip(&cb)
                .all(|(p, q)| (0..3).all(|d| (p[d] - q[d]).abs() < 1e-3));
            assert!(near, "cell {i}: {ca:?} against {cb:?}");
        }
    }
}
