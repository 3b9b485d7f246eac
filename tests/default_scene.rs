//! The scene the app opens on (`assets/presets/default.toml`) is there to
//! show chaos in a lecture: it must stay chaotic, not settle on an orbit
//! after a chaotic transient, and never tumble. Until 2026-11-23 it used
//! r = 0.87, which settles on a period-2 orbit by τ = 70; this test fails
//! with that value.

use rocking::analysis::classify::{ClassifyOptions, Response, classify_run};
use rocking::io::config::load;
use rocking::sim::{Outcome, simulate};

#[test]
fn the_default_scene_stays_chaotic_and_never_tumbles() {
    // From rest at the default tolerance, at another tolerance, and from
    // another initial state: round-off and a small change of start move a
    // chaotic run onto other paths, and none of them may find an orbit.
    for extra in ["run.rtol=1e-10", "run.rtol=1e-9", "initial.theta_dot=0.01"] {
        let sets = ["run.tau_end=3000".to_string(), extra.to_string()];
        let cfg = load(Some("default"), None, &sets).expect("the default preset loads");
        let model = cfg.model().expect("model");
        let period = model.excitation.forcing_period().expect("harmonic");
        let mut opts = cfg.run_options();
        opts.output_dt = None;
        opts.section = true;
        let run = simulate(model, &cfg.initial, &opts).expect("runs");
        assert_eq!(run.outcome, Outcome::Running, "{extra}: the run ended early");
        assert!(
            run.tally.max_abs_theta < 0.3,
            "{extra}: |Θ| reached {}, near tumbling",
            run.tally.max_abs_theta
        );
        // Section points of τ 1000–3000 (2,546 of them): no period up to 32
        // forcing cycles, and not on an invariant curve.
        let class = classify_run(&run, period, 1000.0, None, &ClassifyOptions::default()).expect("classifies");
        assert_eq!(
            class,
            Response::Chaotic,
            "{extra}: the response after τ = 1000 is {class:?}"
        );
        // The block slides as well as rocks: the scene shows every grounded mode.
        let slips = run.events.iter().filter(|e| e.kind.name() == "slip").count();
        assert!(slips > 500, "{extra}: {slips} slips");
    }
}
