//! Property tests over random scenes (issue 5): whatever the block, the
//! friction, the impact law, the excitation (up to the flight limit) and the
//! initial state, a run never panics, never produces a non-finite number,
//! ends in a named outcome, reports events in strictly increasing time, and
//! its energy balance closes.
//!
//! The default case count fits CI; `ROCKING_STRESS=1` runs the extensive
//! tier (10⁵ scenes).

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use rocking::integrate::Tolerances;
use rocking::integrate::hybrid::Limits;
use rocking::model::excitation::Excitation;
use rocking::model::{EventKind, FlightPolicy, Geometry, Harmonic, ImpactLaw, Model};
use rocking::sim::{InitialState, Method, RunOptions, simulate};

fn extensive() -> bool {
    std::env::var("ROCKING_STRESS").is_ok_and(|v| v == "1")
}

/// The CI tier is a fixed sample, so CI is reproducible; the extensive tier
/// draws fresh scenes every time.
fn config() -> ProptestConfig {
    ProptestConfig {
        cases: if extensive() { 100_000 } else { 300 },
        failure_persistence: None,
        rng_seed: if extensive() {
            RngSeed::Random
        } else {
            RngSeed::Fixed(0x726f_636b)
        },
        ..ProptestConfig::default()
    }
}

#[derive(Clone, Debug)]
struct Scene {
    ratio: f64,
    mu: (f64, f64),
    law: ImpactLaw,
    a_h: f64,
    a_v_frac: f64,
    omega_h: f64,
    omega_v: f64,
    phase_v: f64,
    theta0: f64,
    theta_dot0: f64,
    method: Method,
}

fn scene() -> impl Strategy<Value = Scene> {
    let friction = prop_oneof![
        Just((f64::INFINITY, f64::INFINITY)),
        // μ_k < 4/3: beyond it slide-rock is ill-posed and configs reject it.
        (0.0f64..1.5, 0.0f64..=1.0).prop_map(|(s, k)| (s, (s * k).min(1.3))),
        Just((0.0, 0.0)),
    ];
    let law = prop_oneof![
        Just(ImpactLaw::Housner),
        Just(ImpactLaw::CornerMomentum),
        (0.0f64..=1.0).prop_map(|r| ImpactLaw::Ratio { r }),
        (0.0f64..0.5, 0.0f64..1.0, 0.0f64..=1.0).prop_map(|(e, s, k)| ImpactLaw::Impulse {
            e: if e < 0.25 { 0.0 } else { e },
            mu_s: s,
            mu_k: s * k
        }),
    ];
    let method = prop_oneof![
        8 => Just(Method::Dop853),
        1 => Just(Method::Dopri5),
        1 => Just(Method::Ralston),
        2 => Just(Method::Taylor)
    ];
    (
        0.05f64..=1.0,
        friction,
        law,
        -8.0f64..8.0,
        0.0f64..0.99,
        0.5f64..50.0,
        0.5f64..50.0,
        0.0f64..6.3,
        (-0.9f64..0.9, -2.0f64..2.0),
        method,
    )
        .prop_map(
            |(ratio, mu, law, a_h, a_v_frac, omega_h, omega_v, phase_v, (theta0, theta_dot0), method)| Scene {
                ratio,
                mu,
                law,
                a_h,
                a_v_frac,
                omega_h,
                omega_v,
                phase_v,
                theta0,
                theta_dot0,
                method,
            },
        )
}

fn model_of(s: &Scene, excited: bool) -> Model {
    let geo = Geometry::new(s.ratio, 1.0);
    // A_v ψ < 1: the base never accelerates downward faster than g.
    let a_v = s.a_v_frac / geo.psi;
    let excitation = if excited {
        Excitation::Harmonic(Harmonic {
            a_h: s.a_h,
            a_v,
            omega_h: s.omega_h,
            omega_v: s.omega_v,
            phase_h: 0.0,
            phase_v: s.phase_v,
            psi: geo.psi,
        })
    } else {
        Excitation::None
    };
    Model {
        geo,
        mu_s: s.mu.0,
        mu_k: s.mu.1,
        law: s.law,
        excitation,
        tumble_theta: 1.0,
        flight: FlightPolicy::Stop,
        zeno_eps: 1e-5,
        frame: None,
    }
}

fn options(method: Method) -> RunOptions {
    RunOptions {
        tau_end: 20.0,
        method,
        tol: Tolerances {
            rtol: 1e-9,
            atol: 1e-11,
            ..Tolerances::default()
        },
        output_dt: Some(0.05),
        section: true,
        rest_after: None,
        limits: Limits {
            max_steps: 5_000_000,
            max_events: 1_000_000,
            ..Limits::default()
        },
    }
}

fn check(s: &Scene, excited: bool) -> Result<(), TestCaseError> {
    let model = model_of(s, excited);
    let init = InitialState {
        theta: s.theta0,
        theta_dot: s.theta_dot0,
        x_dot: None,
    };
    let res = simulate(model.clone(), &init, &options(s.method));
    let res = match res {
        Ok(r) => r,
        Err(e) => return Err(TestCaseError::fail(format!("run failed: {e}"))),
    };
    let finite = |x: f64| x.is_finite();
    prop_assert!(
        res.final_state.iter().all(|&x| finite(x)),
        "final state {:?}",
        res.final_state
    );
    for e in &res.events {
        prop_assert!(
            [e.tau, e.theta, e.theta_dot_before, e.theta_dot_after, e.x_dot]
                .into_iter()
                .all(finite),
            "{e:?}"
        );
    }
    for w in res.events.windows(2) {
        prop_assert!(w[1].tau > w[0].tau, "event times {} then {}", w[0].tau, w[1].tau);
    }
    for r in &res.history {
        prop_assert!(
            [r.tau, r.theta, r.theta_dot, r.x, r.x_dot].into_iter().all(finite),
            "{r:?}"
        );
        if let rocking::model::Mode::Rock { pivot } | rocking::model::Mode::SlideRock { pivot, .. } = r.mode {
            // Ralston locates impacts only to |Θ| < 1e-6 (the paper's rule).
            let slack = if s.method == Method::Ralston { 1e-5 } else { 1e-9 };
            prop_assert!(
                pivot.value() * r.theta >= -slack,
                "Θ on the wrong side of its pivot: {r:?}"
            );
        }
    }
    let e = res.energy;
    prop_assert!(
        [
            e.initial,
            e.r#final,
            e.work_base,
            e.loss_friction,
            e.loss_impact,
            e.residual
        ]
        .into_iter()
        .all(finite),
        "{e:?}"
    );
    // The balance closes to the integration error: tolerance-controlled for
    // the adaptive methods, O(h²) truncation error for the paper's
    // fixed-step Ralston RK2.
    let closure = if s.method == Method::Ralston { 2e-2 } else { 1e-6 };
    prop_assert!(e.relative_residual < closure, "energy balance does not close: {e:?}");
    // Friction only dissipates. The paper's Ralston evaluates its second
    // stage past an event surface it has not located yet (its rule accepts a
    // crossing once |g| < 1e-6), where the friction power of slide-rock can
    // take either sign; so its friction loss is exact only to its truncation
    // error. The extensive tier found −4.0e-7 against an energy residual of
    // 1.7e-4, and later −1.5e-3 against a residual of only 1.4e-6 (the
    // quadrature's error is not the balance's: both come from the same wrong
    // stages): `ralstons_friction_loss_is_exact_only_to_its_step_error`. So
    // its floor is the accuracy asked of its balance, a fiftieth of the
    // energy scale; the adaptive methods' stays at round-off.
    let friction_floor = if s.method == Method::Ralston {
        -closure * e.initial.abs().max(e.work_base.abs()).max(e.loss_impact.abs())
    } else {
        -1e-9
    };
    prop_assert!(e.loss_friction >= friction_floor, "friction created energy: {e:?}");
    // Ralston accepts a crossing once |g| < 1e-6, the paper's rule.
    let past = if s.method == Method::Ralston { 1e-6 } else { 1e-9 };
    prop_assert!(res.max_abs_theta.is_finite() && res.max_abs_theta <= model.tumble_theta + past);
    if !excited {
        // Passivity: without excitation the energy never rises (the ratio
        // and Housner laws only without pre-impact slip, the impulse law
        // only with e = 0: docs/model.md §7).
        let passive_law = match s.law {
            ImpactLaw::CornerMomentum => true,
            ImpactLaw::Housner | ImpactLaw::Ratio { .. } => s.mu.0.is_infinite(),
            ImpactLaw::Impulse { e, .. } => e == 0.0,
        };
        if passive_law && s.method != Method::Ralston {
            prop_assert!(e.work_base == 0.0);
            prop_assert!(
                e.r#final <= e.initial + 1e-7 * e.initial.abs().max(1.0),
                "energy rose: {e:?}"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_excited_scenes_end_well(s in scene()) {
        check(&s, true)?;
    }

    #[test]
    fn random_free_scenes_are_passive(s in scene()) {
        check(&s, false)?;
    }
}

/// Found by the extensive tier (one scene in about 3·10⁵) while trying a
/// different first step after resets: the uplift moment touches zero and
/// turns back within 10⁻⁴ τ (Ω_h = 36.5), so the block barely lifts (Θ' of
/// order 10⁻¹²) before it is back on its base. With a long first step after
/// the uplift the return fell inside the first guard sample interval, the
/// impact guard was already behind its surface at the first sample, and no
/// impact was found: Θ went on along the wrong side of the pivot. The
/// driver must see the return: the next event, within 10⁻³ τ, puts the
/// block back on its base (Θ = 0: a `Rest` event, or an impact of Θ' of
/// order 10⁻¹² followed by one), and it is at rest again within 10⁻³ τ of
/// the uplift. Which of the two it is depends on round-off (with the first
/// step after a reset capped at the last step, it is an impact at τ
/// 4.782955 then a `Rest` 3·10⁻⁸ τ later; before, a `Rest` at 4.782951).
#[test]
fn a_barely_lifted_block_lands_again() {
    let s = Scene {
        ratio: 0.7604044520066948,
        mu: (f64::INFINITY, f64::INFINITY),
        law: ImpactLaw::Ratio { r: 0.07139104472597675 },
        a_h: -0.8277126183816371,
        a_v_frac: 0.3527088464343627,
        omega_h: 36.48820813877513,
        omega_v: 22.51661337313861,
        phase_v: 3.286143637738209,
        theta0: 0.26269485527986447,
        theta_dot0: 0.0,
        method: Method::Dop853,
    };
    check(&s, true).unwrap();
    let init = InitialState {
        theta: s.theta0,
        theta_dot: s.theta_dot0,
        x_dot: None,
    };
    let res = simulate(model_of(&s, true), &init, &options(s.method)).unwrap();
    let uplift = res
        .events
        .iter()
        .position(|e| e.kind == EventKind::Uplift && (e.tau - 4.7828478).abs() < 1e-6)
        .expect("the uplift at τ 4.78285");
    let t_up = res.events[uplift].tau;
    let next = &res.events[uplift + 1];
    assert!(next.tau - t_up < 1e-3, "{next:?}");
    assert!(
        matches!(next.kind, EventKind::Rest | EventKind::Impact) && next.theta == 0.0,
        "the block is back on its base: {next:?}"
    );
    let rest = res.events[uplift + 1..]
        .iter()
        .find(|e| e.kind == EventKind::Rest)
        .expect("the block comes to rest again");
    assert!(rest.tau - t_up < 1e-3, "{rest:?}");
}

/// Found by the extensive tier (two scenes in 3·10⁵, failing the same way
/// at the start of this session's work): free rocking, a frictionless
/// plastic impact, then slide-rock with μ_k = 1.3 just under the Painlevé
/// limit, where the denominator D is 0.012 at the state and falls through
/// zero a little way off it. A trial step reaching there gave non-finite
/// stages, which ended the run ("non-finite state"); DOP853 now cuts such a
/// step and retries, as Hairer's codes treat a NaN error.
#[test]
fn slide_rock_near_the_painleve_limit_survives_a_bold_trial_step() {
    let scenes = [
        (
            0.5458569771887457,
            1.415671546236458,
            -0.6919251896292482,
            1.5407020122753214,
        ),
        (
            0.4833270370510789,
            1.4087021425323922,
            -0.48416775000170137,
            -0.5129613903249968,
        ),
    ];
    for (ratio, mu_s, theta0, theta_dot0) in scenes {
        let s = Scene {
            ratio,
            mu: (mu_s, 1.3),
            law: ImpactLaw::Impulse {
                e: 0.0,
                mu_s: 0.0,
                mu_k: 0.0,
            },
            a_h: 0.0,
            a_v_frac: 0.0,
            omega_h: 0.5,
            omega_v: 0.5,
            phase_v: 0.0,
            theta0,
            theta_dot0,
            method: Method::Dop853,
        };
        check(&s, false).unwrap();
    }
}

/// Found by the extensive tier (failing the same way at the start of this
/// session): a chain of impacts shrinking towards an accumulation whose last
/// impact before the closed form (`zeno_eps` = 1e-5) leaves Θ' = 1.4e-5.
/// The hop after it lands about 1e-4 τ later, inside the first guard-sample
/// interval (1.9e-3 τ) of a long step, and dips 1e-9 behind the surface
/// before the extended vector field brings Θ back: the impact guard, reset
/// onto its surface and above it at the first sample, was armed there and
/// the landing missed (Θ 1.15e-9 on the wrong side of its pivot at τ 9.5).
#[test]
fn a_hop_shorter_than_a_sample_interval_lands() {
    let s = Scene {
        ratio: 0.433388238307702,
        mu: (0.7180626483329566, 0.3426363050612316),
        law: ImpactLaw::Ratio { r: 0.17832197741590186 },
        a_h: -1.549379180481649,
        a_v_frac: 0.7456559800116073,
        omega_h: 39.706416464093266,
        omega_v: 4.456822569230644,
        phase_v: 0.281406527495883,
        theta0: 0.0,
        theta_dot0: 0.0,
        method: Method::Dop853,
    };
    check(&s, true).unwrap();
}

/// Found by the extensive tier (one scene in about 7·10⁴) with the first
/// step after a reset capped at the last step: Ω_v = 46 on Ω_h = 5.7
/// makes the uplift moment of a block at rest touch zero and turn back at
/// τ 13.14028. The block is lifted at the tangency, and then Θ ∝ −(τ −
/// τ0)⁴: it never leaves its base. The impact guard starts on its surface
/// and is behind it at every sample of the step, with no bump above it, and
/// was never armed: Θ went on behind the pivot (−4.2e-7 at τ 13.15). Now
/// the block lands at once (6e-5 τ later, Θ' = −4e-12) and is at rest.
#[test]
fn an_uplift_where_the_moment_only_touches_zero_lands_at_once() {
    let s = Scene {
        ratio: 0.26306665122551115,
        mu: (f64::INFINITY, f64::INFINITY),
        law: ImpactLaw::Ratio { r: 0.0 },
        a_h: 0.7481935529323833,
        a_v_frac: 0.5382992980455018,
        omega_h: 5.685362121985792,
        omega_v: 46.24585621434724,
        phase_v: 0.08456730912508104,
        theta0: 0.0,
        theta_dot0: 0.0,
        method: Method::Dop853,
    };
    check(&s, true).unwrap();
    let init = InitialState {
        theta: s.theta0,
        theta_dot: s.theta_dot0,
        x_dot: None,
    };
    let res = simulate(model_of(&s, true), &init, &options(s.method)).unwrap();
    let uplift = res
        .events
        .iter()
        .position(|e| e.kind == EventKind::Uplift && (e.tau - 13.1402828).abs() < 1e-6)
        .expect("the uplift at τ 13.14028");
    let t_up = res.events[uplift].tau;
    let next = &res.events[uplift + 1];
    assert!(next.tau - t_up < 1e-3, "{next:?}");
    assert!(next.theta_dot_before.abs() < 1e-9, "it never left its base: {next:?}");
    let rest = &res.events[uplift + 2];
    assert_eq!(rest.kind, EventKind::Rest, "{rest:?}");
    assert!(rest.tau - t_up < 1e-3, "{rest:?}");
}

/// Found by the extensive tier (one scene in about 3·10⁴) with the first
/// step after a reset capped at the last step: at the end of an impact
/// accumulation the block leaves its pivot at Θ' = −4.3e-5 against a
/// restoring Θ'' = +0.059, is back on its base 2.4e-3 τ later (Θ' = 1.5e-5,
/// a landing), and the forcing then carries it off again. The whole hop lay
/// inside the first guard-sample interval (3.9e-3 τ), in its later half,
/// between the probes near the reset: the guard was above its surface at
/// both samples, and Θ went on 6e-9 behind the pivot. The evenly spaced
/// scan of that interval now finds the landing.
#[test]
fn a_hop_in_the_later_half_of_the_first_sample_interval_lands() {
    let s = Scene {
        ratio: 0.12315781966938252,
        mu: (f64::INFINITY, f64::INFINITY),
        law: ImpactLaw::Ratio { r: 0.12252808945186298 },
        a_h: -1.403371247331386,
        a_v_frac: 0.6510315813703813,
        omega_h: 15.78433558370241,
        omega_v: 16.715967633080584,
        phase_v: 1.6995391741969499,
        theta0: 0.0,
        theta_dot0: 0.0,
        method: Method::Dop853,
    };
    check(&s, true).unwrap();
    let init = InitialState {
        theta: s.theta0,
        theta_dot: s.theta_dot0,
        x_dot: None,
    };
    let res = simulate(model_of(&s, true), &init, &options(s.method)).unwrap();
    let departure = res
        .events
        .iter()
        .position(|e| (e.tau - 18.1473090).abs() < 1e-6)
        .expect("the last impact of the accumulation at τ 18.14731");
    let landing = &res.events[departure + 1];
    assert!(landing.tau - res.events[departure].tau < 3e-3, "{landing:?}");
    assert!(landing.theta_dot_before > 1e-5, "lands at Θ' = 1.5e-5: {landing:?}");
}

/// The case the extensive tier found (a slender block, near-flight vertical
/// forcing at Ω_v ≈ 50, slide-rock): at its own step 0.004 (0.2 rad of the
/// vertical forcing per step) the paper's Ralston reports a friction loss
/// of −1.5e-3, energy created, with an energy balance that closes to
/// 1.4e-6. Halving the step gives +6.1e-5, and DOP853 +5.8e-5: the sign is
/// Ralston's step error, not the model's.
#[test]
fn ralstons_friction_loss_is_exact_only_to_its_step_error() {
    let s = Scene {
        ratio: 0.07267960614694102,
        mu: (0.0766701429695886, 0.07572778956054549),
        // Found with the law then called `housner` (issue 14 renamed it).
        law: ImpactLaw::CornerMomentum,
        a_h: 0.7910880425419583,
        a_v_frac: 0.9709332260813388,
        omega_h: 35.85946600520208,
        omega_v: 49.78662130236748,
        phase_v: 1.1390760809606737,
        theta0: 0.0,
        theta_dot0: 0.6881524898938501,
        method: Method::Ralston,
    };
    let model = model_of(&s, true);
    let init = InitialState {
        theta: s.theta0,
        theta_dot: s.theta_dot0,
        x_dot: None,
    };
    let loss = |method: Method, step: f64| {
        let mut o = options(method);
        o.tol.h_fixed = step;
        simulate(model.clone(), &init, &o).expect("runs").energy.loss_friction
    };
    let exact = loss(Method::Dop853, 0.004);
    assert!(exact > 0.0, "DOP853: {exact:e}");
    assert!(loss(Method::Ralston, 0.004) < 0.0, "the case no longer shows the error");
    let halved = loss(Method::Ralston, 0.002);
    assert!(
        halved > 0.0 && (halved - exact).abs() < 0.1 * exact,
        "{halved:e} against {exact:e}"
    );
    check(&s, true).expect("within Ralston's floor");
}
