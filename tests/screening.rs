//! The driver's cheap screening of guards (cubic Hermite samples instead of
//! the high-order dense output, on steps where no guard can be near zero,
//! and no samples at all for a costly guard the system bounds away from zero
//! over a step, `HybridSystem::guard_stays_positive`; no root for an observer
//! whose root cannot change its record, `HybridSystem::observer_may_record`)
//! is an optimisation only: with it and without it, every run must give the same events,
//! section points, tallies and final state, bit for bit.
//!
//! Random scenes around the paper's presets, from loose tolerances (long
//! steps, where a heuristic is most likely to slip) to tight ones. The
//! default count (600 scenes of τ 60, under 2 s) fits CI; `ROCKING_STRESS=1`
//! runs 6000 of τ 200 (about a minute). A change to the screening that
//! passes every other test fails here: screening steps up to 3/Ω instead of
//! 1/Ω changed scene 540's events (and 5 of 6000 in another sample).

use rocking::integrate::hybrid::HybridSystem;
use rocking::io::config;
use rocking::model::system::{N, THETA, THETA_DOT};
use rocking::model::{BlockSystem, Mode, Sign};
use rocking::sim::{Method, RunResult, simulate};

fn extensive() -> bool {
    std::env::var("ROCKING_STRESS").is_ok_and(|v| v == "1")
}

/// A fixed-seed generator (64-bit LCG, Knuth's MMIX constants), so every
/// run tests the same scenes.
struct Lcg(u64);

impl Lcg {
    /// Uniform in [0, 1).
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Everything a run reports that the screening could change, as text:
/// `{:?}` of an f64 prints the shortest string that reads back to the same
/// bits, so equal text is equal bits.
fn fingerprint(r: &RunResult) -> String {
    format!(
        "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
        r.outcome, r.tau_end, r.events, r.section, r.tally, r.final_mode, r.final_state, r.max_abs_theta
    )
}

#[test]
fn screening_changes_no_result_bit_for_bit() {
    let presets = ["default", "fig4", "fig7", "fig8", "fig12", "fig14", "fig17"];
    let (count, tau_end) = if extensive() { (6000, 200.0) } else { (600, 60.0) };
    let mut rng = Lcg(12_345);
    let mut events = 0;
    for k in 0..count {
        let preset = presets[k % presets.len()];
        // rtol from 1e-3 to 1e-10, log-uniform; atol a hundredth of it.
        let rtol = 10f64.powf(-3.0 - 7.0 * rng.next());
        let omega_h = 0.5 + 20.0 * rng.next();
        let omega_v = if rng.next() < 0.5 {
            omega_h
        } else {
            0.5 + 20.0 * rng.next()
        };
        let a_h = 0.5 + 5.0 * rng.next();
        let a_v = 3.0 * rng.next();
        let sets = [
            format!("run.rtol={rtol:e}"),
            format!("run.atol={:e}", rtol * 1e-2),
            format!("run.tau_end={tau_end}"),
            format!("excitation.omega_h={omega_h}"),
            format!("excitation.omega_v={omega_v}"),
            format!("excitation.a_h={a_h}"),
            format!("excitation.a_v={a_v}"),
        ];
        let cfg = config::load(Some(preset), None, &sets).unwrap_or_else(|e| panic!("scene {k}: {e}"));
        let model = cfg.model().expect("valid model");
        let mut opts = cfg.run_options();
        opts.output_dt = None;
        opts.section = true;
        // Every third scene with the Taylor method: its long steps are
        // screened by the bounds alone.
        if k % 3 == 2 {
            opts.method = Method::Taylor;
        }
        let screened = simulate(model.clone(), &cfg.initial, &opts);
        opts.limits.screening = false;
        let full = simulate(model, &cfg.initial, &opts);
        match (screened, full) {
            (Ok(a), Ok(b)) => {
                assert_eq!(fingerprint(&a), fingerprint(&b), "scene {k}: {preset} {sets:?}");
                events += a.events.len();
            }
            (a, b) => assert_eq!(
                a.map(|r| fingerprint(&r)).err(),
                b.map(|r| fingerprint(&r)).err(),
                "scene {k}: {preset} {sets:?}"
            ),
        }
    }
    // The scenes do something: thousands of impacts and mode switches.
    assert!(events > 10 * count, "only {events} events in {count} scenes");
}

/// The bound on the flight guard clears a long step of the paper's periodic
/// scene (what makes it worth having: no forcing at the guard samples of
/// loose tolerances), and refuses near flight, in other modes and for other
/// guards.
#[test]
fn the_flight_guard_is_bounded_on_long_steps_of_the_paper_scene_only() {
    let sys_for = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let cfg = config::load(Some("fig4"), None, &sets).expect("preset");
        BlockSystem::new(cfg.model().expect("model"))
    };
    let rock = Mode::Rock { pivot: Sign::Pos };
    let mut y0 = [0.0; N];
    let mut y1 = [0.0; N];
    (y0[THETA], y0[THETA_DOT]) = (0.05, 0.4);
    (y1[THETA], y1[THETA_DOT]) = (0.12, 0.2);
    // A_h = 2, A_v = 0.5 (the bench's periodic scene), a step of 0.2 τ:
    // 1.6 rad of forcing, longer than the Hermite screening looks at.
    let paper = sys_for(&["excitation.a_h=2", "excitation.a_v=0.5"]);
    assert!(paper.guard_stays_positive(rock, 2, 0.2, &y0, &y1));
    // Not the other guards, not slide-rock.
    assert!(!paper.guard_stays_positive(rock, 0, 0.2, &y0, &y1));
    let slide_rock = Mode::SlideRock {
        pivot: Sign::Pos,
        slip: Sign::Pos,
    };
    assert!(!paper.guard_stays_positive(slide_rock, 2, 0.2, &y0, &y1));
    // Near flight (A_v ψ = 0.98 g) the bound cannot clear it.
    let psi = (1.0f64).atan2(4.0);
    let near = format!("excitation.a_v={}", 0.98 / psi);
    let near_flight = sys_for(&["excitation.a_h=2", &near]);
    assert!(!near_flight.guard_stays_positive(rock, 2, 0.2, &y0, &y1));
}

/// A body at rest on its base steps without evaluating its field
/// (`HybridSystem::is_still`, `Limits::still`): an optimisation only, as
/// the screening is. The block's record presets (where the Taylor method
/// hands its steps to DOP853), the floor of a building, the rocking frame
/// and a harmonic block that slides (the Taylor series itself, which a
/// still step leaves as it is) give the same
/// events, history, tallies, energy and final state bit for bit both ways;
/// on the El Centro statue, which rests 37 of the record's 54 s, the field
/// is evaluated 2.5 times less.
#[test]
fn a_body_at_rest_steps_without_its_field_and_changes_nothing_bit_for_bit() {
    for name in [
        "elcentro-statue",
        "kobe-rack",
        "kobe-rack-5th-floor",
        "rocking-frame",
        "sliding",
    ] {
        let s = config::load(Some(name), None, &[]).expect("preset");
        let run = |still: bool| {
            let mut opts = s.run_options();
            opts.limits.still = still;
            simulate(s.model().expect("model"), &s.initial, &opts).expect("run")
        };
        let (fast, slow) = (run(true), run(false));
        let print = |r: &RunResult| {
            format!(
                "{} {:?} {:?} {:?} {:?} {:?}",
                fingerprint(r),
                r.history,
                r.energy,
                r.mode_time,
                r.max_abs_sliding,
                r.final_sliding
            )
        };
        assert!(print(&fast) == print(&slow), "{name}: the still steps changed the run");
        assert_eq!(fast.stats.accepted, slow.stats.accepted, "{name}: the same steps");
        eprintln!(
            "{name}: {} steps, field evaluated {} times instead of {}",
            fast.stats.accepted, fast.stats.rhs_evals, slow.stats.rhs_evals
        );
        if name == "elcentro-statue" {
            assert!(5 * fast.stats.rhs_evals < 2 * slow.stats.rhs_evals, "{:?}", fast.stats);
        }
    }
}
