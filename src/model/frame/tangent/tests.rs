//! The frame's generated Jacobian and guard gradients against central
//! differences of the system they linearise (its `rhs` and `guards` over
//! `f64`), and its impact's reset against the impact itself.

use super::*;
use crate::integrate::hybrid::HybridSystem;
use crate::model::dynamics::test_scene::{harmonic, model as scene};
use crate::model::frame::Frame;
use crate::model::geometry::Geometry;
use crate::model::mode::Sign;
use crate::model::params::{FlightPolicy, Model};
use crate::model::variational::forcing_rate;

/// A frame of 1 × 4 m columns under a beam of mass ratio 0.7, shaken
/// both ways (the shared test scene), not stopped at flight, so that
/// every guard of rock is a guard.
fn model() -> Model {
    let geo = Geometry::new(1.0, 4.0);
    Model {
        flight: FlightPolicy::Ignore,
        frame: Some(Frame {
            columns: 2,
            beam_mass_ratio: 0.7,
        }),
        ..scene(geo, harmonic(&geo, 0.6, 8.0, 0.3))
    }
}

fn state(pivot: Sign) -> [f64; N] {
    [0.37 * pivot.value(), -0.81, 0.02, 0.11, 0.0, 0.0]
}

const H: f64 = 1e-6;

fn close(exact: f64, approx: f64) -> bool {
    (exact - approx).abs() < 1e-7 * (1.0 + approx.abs())
}

#[test]
fn the_field_jacobian_is_central_differences_of_the_rhs() {
    let model = model();
    let sys = FrameSystem::new(model.clone());
    let t = 0.7;
    for pivot in [Sign::Pos, Sign::Neg] {
        let mode = Mode::Rock { pivot };
        let y = state(pivot);
        let exact = sys.field_jacobian(mode, model.excitation.forcing(t), &y);
        for (j, &idx) in FRAME_COORDS.iter().enumerate() {
            let (mut yp, mut ym) = (y, y);
            yp[idx] += H;
            ym[idx] -= H;
            let (mut fp, mut fm) = ([0.0; N], [0.0; N]);
            sys.rhs(mode, t, &yp, &mut fp);
            sys.rhs(mode, t, &ym, &mut fm);
            for (i, &row) in FRAME_COORDS.iter().enumerate() {
                let approx = (fp[row] - fm[row]) / (2.0 * H);
                assert!(
                    close(exact[i][j], approx),
                    "{mode:?} ∂f{i}/∂z{j}: {} vs {approx}",
                    exact[i][j]
                );
            }
        }
        // Θ'' reads Θ alone: the trace is 0 (the flow keeps area).
        assert_eq!(exact[0], [0.0, 1.0]);
        assert_eq!(exact[1][1], 0.0);
    }
    let rest = sys.field_jacobian(Mode::Rest, model.excitation.forcing(t), &[0.0; N]);
    assert_eq!(rest, [[0.0; FRAME_DIM]; FRAME_DIM]);
}

#[test]
fn guard_gradients_are_central_differences_of_the_guards() {
    let model = model();
    let sys = FrameSystem::new(model.clone());
    let t = 0.7;
    let fo = model.excitation.forcing(t);
    let rate = forcing_rate(&model.excitation, t).expect("harmonic");
    for mode in [
        Mode::Rest,
        Mode::Rock { pivot: Sign::Pos },
        Mode::Rock { pivot: Sign::Neg },
    ] {
        let y = match mode {
            Mode::Rock { pivot } => state(pivot),
            _ => [0.0; N],
        };
        let mut g = [0.0; MAX_GUARDS];
        let n = sys.guards(mode, t, &y, &mut g);
        assert!(n > 0);
        for i in 0..n {
            let (exact, time) = sys.guard_gradient(mode, i, fo, rate, &y).expect("a guard");
            for (j, &idx) in FRAME_COORDS.iter().enumerate() {
                let (mut yp, mut ym) = (y, y);
                yp[idx] += H;
                ym[idx] -= H;
                let (mut gp, mut gm) = ([0.0; MAX_GUARDS], [0.0; MAX_GUARDS]);
                sys.guards(mode, t, &yp, &mut gp);
                sys.guards(mode, t, &ym, &mut gm);
                let approx = (gp[i] - gm[i]) / (2.0 * H);
                assert!(
                    close(exact[j], approx),
                    "{mode:?} guard {i} ∂/∂z{j}: {} vs {approx}",
                    exact[j]
                );
            }
            let (mut gp, mut gm) = ([0.0; MAX_GUARDS], [0.0; MAX_GUARDS]);
            sys.guards(mode, t + H, &y, &mut gp);
            sys.guards(mode, t - H, &y, &mut gm);
            let approx = (gp[i] - gm[i]) / (2.0 * H);
            assert!(close(time, approx), "{mode:?} guard {i} ∂/∂τ: {time} vs {approx}");
        }
        assert!(sys.guard_gradient(mode, n, fo, rate, &y).is_none());
    }
}

#[test]
fn the_impact_reset_is_the_impacts_own_derivative() {
    let model = model();
    let mut sys = FrameSystem::new(model.clone());
    let t = 0.7;
    let pivot = Sign::Pos;
    let before = Mode::Rock { pivot };
    // At the impact surface, moving towards it.
    let at = |theta_dot: f64| [0.0, theta_dot, 0.02, 0.11, 0.0, 0.0];
    let jump = |sys: &mut FrameSystem, theta_dot: f64| sys.jump(before, 0, t, &at(theta_dot)).expect("impact");
    let v = -0.81;
    let centre = jump(&mut sys, v);
    let (m, dim) = sys.reset_jacobian(before, 0, &at(v), centre.mode);
    assert_eq!(centre.mode, Mode::Rock { pivot: Sign::Neg });
    assert_eq!(dim, FRAME_DIM);
    let (plus, minus) = (jump(&mut sys, v + H), jump(&mut sys, v - H));
    let approx = (plus.y[THETA_DOT] - minus.y[THETA_DOT]) / (2.0 * H);
    assert!(close(m[1][1], approx), "{} vs {approx}", m[1][1]);
    assert_eq!([m[0], [m[1][0], 0.0]], [[0.0; 2]; 2], "Θ⁺ = 0 whatever z⁻");
    // Slow enough to accumulate: no direction survives.
    let slow = jump(&mut sys, -1e-7);
    assert_eq!(sys.reset_jacobian(before, 0, &at(-1e-7), slow.mode).1, 0);
    // Tumbling ends the frame's rocking.
    assert_eq!(sys.reset_jacobian(before, 1, &state(pivot), Mode::Tumbled).1, 0);
}
