//! The generated tangent dynamics against the hand-written ones of
//! `variational`, on random states of every mode, pivot and slip sign.

use super::*;
use crate::model::dynamics::test_scene::{harmonic, model as scene, moving_modes};
use crate::model::geometry::Geometry;
use crate::model::impact::ImpactLaw;
use crate::model::params::FlightPolicy;
use crate::model::variational as hand;

fn model(bh: f64, mu_s: f64, mu_k: f64) -> Model {
    let geo = Geometry::new(bh, 1.0);
    Model {
        mu_s,
        mu_k,
        law: ImpactLaw::Ratio { r: 0.9 },
        flight: FlightPolicy::Ignore,
        ..scene(geo, harmonic(&geo, 2.5, 5.0, 1.1))
    }
}

fn modes() -> Vec<Mode> {
    let mut modes = vec![Mode::Rest, Mode::Tumbled, Mode::Flight];
    modes.extend(moving_modes());
    modes
}

/// Round-off: the two forms are different sums of the same terms, each a
/// few operations on numbers of order 1 (the states and forcings below),
/// so they agree to a few ulps of the largest term; 1e-13 relative to
/// (1 + |entry|) leaves a factor of ten over what we measured.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * (1.0 + a.abs().max(b.abs()))
}

proptest::proptest! {
    #[test]
    fn the_generated_jacobians_and_guard_gradients_equal_the_hand_written_ones(
        bh in 0.1f64..1.0,
        mu in 0.1f64..0.9,
        finite in proptest::bool::ANY,
        theta in 0.0f64..0.9,
        theta_dot in -2.0f64..2.0,
        x_dot in -1.0f64..1.0,
        t in 0.0f64..10.0,
    ) {
        let m = model(bh, if finite { mu + 0.05 } else { f64::INFINITY }, if finite { mu } else { f64::INFINITY });
        let fo = m.excitation.forcing(t);
        let rate = hand::forcing_rate(&m.excitation, t).unwrap();
        // Without friction limits the block never slides (no slide guard
        // fires), and the sliding modes' fields are infinite there.
        let reachable = |mode: &Mode| finite || matches!(mode, Mode::Rest | Mode::Rock { .. } | Mode::Tumbled | Mode::Flight);
        for mode in modes().into_iter().filter(reachable) {
            // Θ on the mode's side (sΘ > 0), as the driver keeps it.
            let th = match mode {
                Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => pivot.value() * theta,
                _ => 0.0,
            };
            let y = [th, theta_dot, 0.3, x_dot, 0.1, 0.2];
            let (j_hand, j_gen) = (hand::field_jacobian(&m, mode, fo, &y), field_jacobian(&m, mode, fo, &y));
            for i in 0..DIM {
                for k in 0..DIM {
                    proptest::prop_assert!(close(j_hand[i][k], j_gen[i][k]),
                        "{mode:?} J[{i}][{k}]: {} vs {}", j_hand[i][k], j_gen[i][k]);
                }
            }
            for index in 0..=MAX_GUARDS {
                let (h, g) = (hand::guard_gradient(&m, mode, index, fo, rate, &y), guard_gradient(&m, mode, index, fo, rate, &y));
                proptest::prop_assert_eq!(h.is_some(), g.is_some(), "{:?} guard {}", mode, index);
                if let (Some(h), Some(g)) = (h, g) {
                    for k in 0..DIM {
                        proptest::prop_assert!(close(h.state[k], g.state[k]),
                            "{mode:?} guard {index} ∂/∂z{k}: {} vs {}", h.state[k], g.state[k]);
                    }
                    proptest::prop_assert!(close(h.time, g.time),
                        "{mode:?} guard {index} ∂/∂τ: {} vs {}", h.time, g.time);
                }
            }
        }
    }
}
