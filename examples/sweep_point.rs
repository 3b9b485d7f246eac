//! Times one sweep point of the paper (the `periodic` bench scene at rtol
//! 1e-10, section only) and prints the integrator's counters: the numbers
//! to look at when profiling (`perf record` this example). Then the
//! throughput, τ per wall-clock second, of the app's default scene (chaotic
//! rocking with sliding) over τ 0–20000, section only.
//!
//! `cargo run --release --example sweep_point [repeats] [periodic]`, with
//! `RTOL=…` in the environment for a tolerance other than 1e-10 (both
//! scenes, atol = rtol/100), `ATOL=…` for the sweep point's atol, and
//! `METHOD=dop853` or `METHOD=taylor` for a method other than the default
//! for the tolerance (`Method::default_for`: Taylor at 1e-10).

use std::time::Instant;

use rocking::bench::scenes;
use rocking::integrate::Tolerances;
use rocking::integrate::hybrid::Limits;
use rocking::sim::{Method, RunOptions, simulate};

/// `METHOD=dop853` or `METHOD=taylor`, if set.
fn method_from_env() -> Option<Method> {
    match std::env::var("METHOD").as_deref() {
        Ok("dop853") => Some(Method::Dop853),
        Ok("taylor") => Some(Method::Taylor),
        _ => None,
    }
}

fn main() {
    let repeats: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    // `RTOL=1e-6` runs the sweep point at another tolerance (the paper's
    // sweeps use 1e-10).
    let rtol: f64 = std::env::var("RTOL").ok().and_then(|s| s.parse().ok()).unwrap_or(1e-10);
    let s = scenes()
        .into_iter()
        .find(|s| s.name == "periodic")
        .expect("periodic scene");
    let opts = RunOptions {
        tau_end: s.tau_end,
        method: method_from_env().unwrap_or(Method::default_for(rtol)),
        tol: Tolerances {
            rtol,
            // As the bench does: a hundredth of rtol.
            atol: std::env::var("ATOL")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(rtol * 1e-2),
            h_max: f64::INFINITY,
            h_fixed: 0.004,
        },
        output_dt: None,
        section: true,
        rest_after: None,
        limits: Limits::default(),
    };
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let r = simulate(s.model.clone(), &s.initial, &opts).expect("the periodic scene runs");
        walls.push(start.elapsed().as_secs_f64());
        last = Some(r);
    }
    walls.sort_by(f64::total_cmp);
    let r = last.expect("at least one run");
    println!(
        "periodic sweep point: median {:.3} ms, best {:.3} ms over {} runs",
        walls[walls.len() / 2] * 1e3,
        walls[0] * 1e3,
        walls.len()
    );
    println!(
        "steps {} (rejected {}), rhs evals {}, impacts {}, events {}, section points {}, final {:?}",
        r.stats.accepted,
        r.stats.rejected,
        r.stats.rhs_evals,
        r.tally.impacts,
        r.events.len(),
        r.section.len(),
        &r.final_state[..2]
    );

    // Throughput on the default scene (skipped with a second argument
    // `periodic`, to profile the sweep point alone).
    if std::env::args().nth(2).as_deref() == Some("periodic") {
        return;
    }
    let cfg = rocking::io::config::load(Some("default"), None, &["run.tau_end=20000".to_string()])
        .expect("the default preset loads");
    let mut opts = cfg.run_options();
    if std::env::var("RTOL").is_ok() {
        opts.tol.rtol = rtol;
        opts.tol.atol = rtol * 1e-2;
    }
    if let Some(m) = method_from_env() {
        opts.method = m;
    }
    opts.output_dt = None;
    opts.section = true;
    let mut walls = Vec::new();
    let mut last_default = None;
    // `DEFAULT_REPEATS=…` for more runs of the default scene (3).
    let default_repeats: usize = std::env::var("DEFAULT_REPEATS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    for _ in 0..default_repeats.max(1) {
        let start = Instant::now();
        let r = simulate(cfg.model().expect("model"), &cfg.initial, &opts).expect("the default scene runs");
        walls.push((start.elapsed().as_secs_f64(), r.tau_end, r.tally.impacts));
        last_default = Some(r);
    }
    walls.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (wall, tau, impacts) = walls[walls.len() / 2];
    println!(
        "default scene: {tau} τ in {:.3} s (median of {}): {:.0} τ/s (best {:.0}), {impacts} impacts",
        wall,
        walls.len(),
        tau / wall,
        tau / walls[0].0
    );
    if let Some(r) = last_default {
        println!(
            "steps {} (rejected {}), rhs evals {}, events {}, section points {}",
            r.stats.accepted,
            r.stats.rejected,
            r.stats.rhs_evals,
            r.events.len(),
            r.section.len()
        );
    }
}
