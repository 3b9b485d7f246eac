//! The generated series against the hand-written expansions of `series`,
//! on random states of every mode, pivot and slip sign.

use super::*;
use crate::model::dynamics::test_scene::{model as scene, moving_modes, two_sines};
use crate::model::excitation::Excitation;
use crate::model::geometry::Geometry;
use crate::model::mode::Sign;

fn model(shared: bool, mu_k: f64) -> Model {
    let geo = Geometry::new(1.0, 4.0);
    Model {
        mu_s: mu_k + 0.05,
        mu_k,
        ..scene(geo, two_sines(&geo, shared))
    }
}

fn modes() -> Vec<Mode> {
    let mut modes = vec![Mode::Rest];
    modes.extend(moving_modes());
    modes
}

proptest::proptest! {
    /// The two agree to round-off: measured as in `series::tests`, the
    /// difference of each coefficient times h^k relative to the largest
    /// term |c_k| h^k of its component over a step h = 0.3 (the size of a
    /// Taylor step on these scenes). The hand-written form adds the same
    /// terms in another order and takes X from the tilt instead of
    /// integrating X'', so a few hundred ulps of the largest term at
    /// order 28 is round-off; 1e-13 is the bound `series::tests` uses.
    #[test]
    fn the_generated_series_equal_the_hand_written_ones(
        theta in 0.0f64..0.9,
        theta_dot in -2.0f64..2.0,
        x_dot in -1.0f64..1.0,
        t in 0.0f64..10.0,
        mu_k in 0.1f64..0.8,
        shared in proptest::bool::ANY,
        order in 1usize..MAX_ORDER,
    ) {
        let m = model(shared, mu_k);
        let h: f64 = 0.3;
        for mode in modes() {
            let th = match mode {
                Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => pivot.value() * theta,
                _ => 0.0,
            };
            let y = [th, theta_dot, 0.2, x_dot, 0.1, 0.05];
            let (mut hand, mut generated) = (vec![[0.0; N]; order + 1], vec![[0.0; N]; order + 1]);
            proptest::prop_assert!(super::super::taylor(&m, mode, t, &y, order, &mut hand));
            proptest::prop_assert!(taylor(&m, mode, t, &y, order, &mut generated));
            for n in 0..N {
                let scale = (0..=order).map(|k| hand[k][n].abs() * h.powi(k as i32)).fold(0.0, f64::max).max(1e-300);
                for k in 0..=order {
                    let d = (hand[k][n] - generated[k][n]).abs() * h.powi(k as i32) / scale;
                    proptest::prop_assert!(d < 1e-13, "{mode:?} order {order}, component {n}, coefficient {k}: {} vs {} ({d:e})", hand[k][n], generated[k][n]);
                }
            }
        }
    }
}

#[test]
fn the_generated_series_refuse_what_the_hand_written_ones_refuse() {
    let m = model(true, 0.3);
    let y = [0.1, 0.2, 0.0, 0.0, 0.0, 0.0];
    let mode = Mode::Rock { pivot: Sign::Pos };
    let mut c = vec![[0.0; N]; MAX_ORDER + 1];
    assert!(
        !taylor(&m, mode, 0.0, &y, MAX_ORDER, &mut c),
        "an order without reserve"
    );
    assert!(!taylor(&m, mode, 0.0, &y, 5, &mut c[..5]), "too few rows");
    let mut pulse = m.clone();
    pulse.excitation = Excitation::None;
    assert!(taylor(&pulse, mode, 0.0, &y, 5, &mut c), "no forcing: a series");
}
