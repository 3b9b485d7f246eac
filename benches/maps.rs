//! `cargo bench --bench maps`: outcome maps, fast against full, side by
//! side in one run (medians of alternating samples, as divan takes them).
//!
//! - `fig3_map`: the README's A_h × Ω_h ranges of fig3 (A_h 0.1–3, Ω_h
//!   2–12) at N × N cells, the fast plan (early stop and refinement).
//! - `fig3_map_full_row`: one row of that map (Ω_h = 8, N cells) with
//!   every cell over its whole window, the reference's cost per cell; and
//!   the same row with the fast plan.
//! - `fig4_basin`: the basin map of fig4 at A_v = 1 over (Θ₀, Θ'₀), two
//!   coexisting attractors (period 1 and period 6), fast plan.
//!
//! The 1000 × 1000 maps of the closing note are `rocking map` runs, timed
//! as a process (docs/analysis.md).

use std::hint::black_box;

use rocking::analysis::classify::ClassifyOptions;
use rocking::analysis::outcome_map::{Axis, BlockMap, MapPlan, compute_map};
use rocking::analysis::silent;
use rocking::analysis::steady::Window;
use rocking::io::config::load;
use rocking::sim::{Param, Scenario};

fn main() {
    divan::main();
}

fn preset(name: &str, set: &[&str]) -> Scenario {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    load(Some(name), None, &set).expect("preset loads")
}

fn map(base: &Scenario, x: (Param, Axis), y: (Param, Axis), plan: MapPlan) -> usize {
    let spec = BlockMap {
        base,
        x_param: x.0,
        x: &x.1,
        y_param: y.0,
        y: &y.1,
        window: Window::default(),
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    compute_map(&spec, plan, &silent).expect("maps").computed
}

fn axis(key: &str, a: f64, b: f64, n: usize) -> Axis {
    Axis::new("--x", key, a, b, n).expect("axis")
}

#[divan::bench(args = [100, 200], sample_count = 3)]
fn fig3_map(n: usize) {
    let base = preset("fig3", &[]);
    black_box(map(
        &base,
        (Param::Ah, axis("excitation.a_h", 0.1, 3.0, n)),
        (Param::OmegaH, axis("excitation.omega_h", 2.0, 12.0, n)),
        MapPlan::FAST,
    ));
}

#[divan::bench(args = ["fast", "full"], sample_count = 3)]
fn fig3_map_full_row(plan: &str) {
    let base = preset("fig3", &[]);
    let plan = if plan == "full" { MapPlan::FULL } else { MapPlan::FAST };
    black_box(map(
        &base,
        (Param::Ah, axis("excitation.a_h", 0.1, 3.0, 200)),
        (Param::OmegaH, axis("excitation.omega_h", 8.0, 8.0, 1)),
        plan,
    ));
}

#[divan::bench(sample_count = 3)]
fn fig4_basin_100() {
    let base = preset("fig4", &["excitation.a_v=1"]);
    black_box(map(
        &base,
        (Param::Theta0, axis("initial.theta", -0.9, 0.9, 100)),
        (Param::ThetaDot0, axis("initial.theta_dot", -1.0, 1.0, 100)),
        MapPlan::FAST,
    ));
}
