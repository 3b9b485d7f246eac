//! Stroboscopic section points come from DOP853's dense output (the driver
//! no longer stops on every section time). They must agree with stepping
//! onto the section time: a run to `τ_end = k T` takes the same steps as the
//! long run up to the step that contains `k T`, which it shortens to end
//! there, so the two differ only by the dense output's error against a step's.

use rocking::bench::scenes;
use rocking::integrate::Tolerances;
use rocking::integrate::hybrid::Limits;
use rocking::io::config::load;
use rocking::model::Model;
use rocking::sim::{InitialState, Method, RunOptions, simulate};

fn options(tau_end: f64, section: bool) -> RunOptions {
    RunOptions {
        tau_end,
        method: Method::Dop853,
        tol: Tolerances::default(),
        output_dt: None,
        section,
        rest_after: None,
        limits: Limits::default(),
    }
}

/// Largest difference, over Θ, Θ', X, X', between section point `k` of the
/// long run and the end state of a run stopped at its time.
fn worst_difference(model: &Model, init: &InitialState, tau_end: f64, ks: &[u64]) -> f64 {
    let long = simulate(model.clone(), init, &options(tau_end, true)).expect("the long run");
    let period = model.excitation.forcing_period().expect("harmonic");
    let mut worst: f64 = 0.0;
    for &k in ks {
        let row = long.section.iter().find(|r| r.k == k).expect("section point k");
        assert_eq!(row.tau, k as f64 * period, "section time k T, bit for bit");
        let short = simulate(model.clone(), init, &options(row.tau, false)).expect("the short run");
        assert_eq!(short.tau_end, row.tau);
        let y = short.final_state;
        for (a, b) in [row.theta, row.theta_dot, row.x, row.x_dot].iter().zip(&y[..4]) {
            worst = worst.max((a - b).abs());
        }
    }
    worst
}

#[test]
fn section_points_from_dense_output_match_stepping_onto_them() {
    // The paper's sweep point (pure rocking, 2 impacts per period).
    let s = scenes()
        .into_iter()
        .find(|s| s.name == "periodic")
        .expect("periodic scene");
    let w = worst_difference(&s.model, &s.initial, s.tau_end, &[1, 97, 503, 1000]);
    eprintln!("periodic scene: worst section difference {w:.2e}");
    assert!(w < 1e-10, "periodic scene: {w:e}");

    // The app's default scene: chaotic rocking with sliding.
    let cfg = load(Some("default"), None, &["run.tau_end=400".to_string()]).expect("preset");
    let model = cfg.model().expect("model");
    let w = worst_difference(&model, &cfg.initial, 400.0, &[3, 150, 500]);
    eprintln!("default scene: worst section difference {w:.2e}");
    assert!(w < 1e-10, "default scene: {w:e}");
}
