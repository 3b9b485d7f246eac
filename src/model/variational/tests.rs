//! Every Jacobian and gradient against central differences of the
//! system it linearises, and the projections of the switches.

#![allow(clippy::needless_range_loop)]

use super::*;
use crate::integrate::hybrid::{HybridSystem, MAX_GUARDS};
use crate::model::dynamics::test_scene::{harmonic, model as scene};
use crate::model::{BlockSystem, FlightPolicy};

fn model(mu_s: f64, mu_k: f64, law: ImpactLaw) -> Model {
    let geo = Geometry::new(1.0, 4.0);
    Model {
        mu_s,
        mu_k,
        law,
        flight: FlightPolicy::Ignore,
        ..scene(geo, harmonic(&geo, 2.5, 8.0, 1.1))
    }
}

fn tilted_modes() -> Vec<Mode> {
    let mut modes = Vec::new();
    for pivot in [Sign::Pos, Sign::Neg] {
        modes.push(Mode::Rock { pivot });
        for slip in [Sign::Pos, Sign::Neg] {
            modes.push(Mode::SlideRock { pivot, slip });
        }
    }
    modes
}

fn state(pivot: Sign) -> [f64; N] {
    let s = pivot.value();
    [0.37 * s, -0.81, 0.02, 0.11, 0.0, 0.0]
}

/// Central difference of `f` in each of the three tangent coordinates.
fn numeric<F: Fn(&[f64; N]) -> [f64; DIM]>(f: F, y: &[f64; N]) -> Matrix {
    let h = 1e-6;
    let mut m = [[0.0; DIM]; DIM];
    for (j, &idx) in COORDS.iter().enumerate() {
        let (mut yp, mut ym) = (*y, *y);
        yp[idx] += h;
        ym[idx] -= h;
        let (fp, fm) = (f(&yp), f(&ym));
        for i in 0..DIM {
            m[i][j] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    m
}

#[test]
fn field_jacobian_matches_central_differences_of_the_rhs() {
    let model = model(0.4, 0.35, ImpactLaw::Ratio { r: 0.925 });
    let sys = BlockSystem::new(model.clone());
    let t = 0.7;
    let fo = model.excitation.forcing(t);
    for mode in tilted_modes() {
        let pivot = match mode {
            Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => pivot,
            _ => unreachable!(),
        };
        let y = state(pivot);
        let exact = field_jacobian(&model, mode, fo, &y);
        let approx = numeric(
            |yy| {
                let mut dy = [0.0; N];
                sys.rhs(mode, t, yy, &mut dy);
                coords(&dy)
            },
            &y,
        );
        for i in 0..DIM {
            for j in 0..DIM {
                assert!(
                    (exact[i][j] - approx[i][j]).abs() < 1e-7 * (1.0 + approx[i][j].abs()),
                    "{mode:?} J[{i}][{j}] = {} vs {}",
                    exact[i][j],
                    approx[i][j]
                );
            }
        }
    }
}

#[test]
fn guard_gradients_match_central_differences_of_the_guards() {
    let model = model(0.4, 0.35, ImpactLaw::Ratio { r: 0.925 });
    let sys = BlockSystem::new(model.clone());
    let t = 0.7;
    let fo = model.excitation.forcing(t);
    let rate = forcing_rate(&model.excitation, t).unwrap();
    let mut modes = tilted_modes();
    modes.extend([
        Mode::Rest,
        Mode::Slide { slip: Sign::Pos },
        Mode::Slide { slip: Sign::Neg },
    ]);
    for mode in modes {
        let y = match mode {
            Mode::Rock { pivot } | Mode::SlideRock { pivot, .. } => state(pivot),
            _ => [0.0, 0.0, 0.02, 0.11, 0.0, 0.0],
        };
        let mut g = [0.0; MAX_GUARDS];
        let n = sys.guards(mode, t, &y, &mut g);
        let approx = |i: usize| {
            let h = 1e-6;
            let mut grad = [0.0; DIM];
            for (j, &idx) in COORDS.iter().enumerate() {
                let (mut yp, mut ym) = (y, y);
                yp[idx] += h;
                ym[idx] -= h;
                let (mut gp, mut gm) = ([0.0; MAX_GUARDS], [0.0; MAX_GUARDS]);
                sys.guards(mode, t, &yp, &mut gp);
                sys.guards(mode, t, &ym, &mut gm);
                grad[j] = (gp[i] - gm[i]) / (2.0 * h);
            }
            let (mut gp, mut gm) = ([0.0; MAX_GUARDS], [0.0; MAX_GUARDS]);
            sys.guards(mode, t + h, &y, &mut gp);
            sys.guards(mode, t - h, &y, &mut gm);
            (grad, (gp[i] - gm[i]) / (2.0 * h))
        };
        for i in 0..n {
            let exact = guard_gradient(&model, mode, i, fo, rate, &y).unwrap();
            let (grad, time) = approx(i);
            for j in 0..DIM {
                assert!(
                    (exact.state[j] - grad[j]).abs() < 1e-7 * (1.0 + grad[j].abs()),
                    "{mode:?} guard {i} ∂/∂z{j}: {} vs {}",
                    exact.state[j],
                    grad[j]
                );
            }
            assert!(
                (exact.time - time).abs() < 1e-7 * (1.0 + time.abs()),
                "{mode:?} guard {i} ∂/∂τ: {} vs {time}",
                exact.time
            );
        }
        assert!(guard_gradient(&model, mode, n, fo, rate, &y).is_none());
    }
}

#[test]
fn rock_tangent_flow_keeps_the_constraint() {
    // d/dτ(δX' − ∂(cψΘ')·δz) = 0 along the rock tangent flow, for any δz
    // on the constraint: J's X'' row equals the derivative of the
    // projection row along the flow.
    let model = model(f64::INFINITY, f64::INFINITY, ImpactLaw::Ratio { r: 0.925 });
    let sys = BlockSystem::new(model.clone());
    let t = 0.4;
    let fo = model.excitation.forcing(t);
    for pivot in [Sign::Pos, Sign::Neg] {
        let mode = Mode::Rock { pivot };
        let y = state(pivot);
        let j = field_jacobian(&model, mode, fo, &y);
        let p = mode_projection(&model.geo, mode, &y);
        let mut dy = [0.0; N];
        sys.rhs(mode, t, &y, &mut dy);
        // Row of the projection one small step along the flow.
        let h = 1e-6;
        let mut y2 = y;
        for (k, v) in y2.iter_mut().enumerate() {
            *v += h * dy[k];
        }
        let p2 = mode_projection(&model.geo, mode, &y2);
        for col in 0..2 {
            let dp = (p2[2][col] - p[2][col]) / h;
            let through_j: f64 = (0..2).map(|k| p[2][k] * j[k][col]).sum();
            assert!((j[2][col] - (dp + through_j)).abs() < 1e-5, "{pivot:?} col {col}");
        }
    }
}

#[test]
fn ratio_impact_jacobian_is_analytic_and_impulse_law_differences_are_exact() {
    let m = model(0.4, 0.35, ImpactLaw::Ratio { r: 0.9 });
    let y = [0.0, -0.5, 0.0, -0.3, 0.0, 0.0];
    let before = Mode::Rock { pivot: Sign::Pos };
    let mut after_y = y;
    after_y[THETA_DOT] = -0.45;
    let rj = reset_jacobian(&m, before, 0, &y, Mode::Rock { pivot: Sign::Neg }, &after_y);
    assert_eq!(rj.dim, 2);
    assert_eq!(rj.matrix[0], [0.0, 0.0, 0.0]);
    assert!((rj.matrix[1][1] - 0.9).abs() < 1e-15);
    assert_eq!(rj.matrix[1][2], 0.0);
    assert_eq!(rj.matrix[2][2], 0.0);

    // Housner's law is the ratio law with r = 1 − 1.5 sin²ψ, whatever the
    // pre-impact slip (docs/model.md §7.3).
    let m = model(0.4, 0.35, ImpactLaw::Housner);
    let (jac, kind) = impact_jacobian(&m, Sign::Pos, -0.5, -0.3);
    assert_eq!(kind, ImpactKind::Stuck);
    let r = m.geo.housner_r();
    assert_eq!((jac[1][1], jac[1][2]), (r, 0.0));
    assert_eq!((jac[2][1], jac[2][2]), (m.geo.cos_psi * m.geo.psi * r, 0.0));

    // The corner-momentum law with pre-impact slip:
    // w₊ = (1 − 1.5 sin²ψ) w₋ + ¾ cos ψ V_cx₋ with V_cx₋ = X'₋ − cos ψ w₋
    // (docs/model.md §7.3): linear.
    let m = model(0.4, 0.35, ImpactLaw::CornerMomentum);
    let geo = m.geo;
    let (jac, kind) = impact_jacobian(&m, Sign::Pos, -0.5, -0.3);
    assert_eq!(kind, ImpactKind::Stuck);
    let r = geo.housner_r();
    let d_theta_dot = (r - 0.75 * geo.cos_psi * geo.cos_psi, 0.75 * geo.cos_psi / geo.psi);
    assert!(
        (jac[1][1] - d_theta_dot.0).abs() < 1e-9,
        "{} vs {}",
        jac[1][1],
        d_theta_dot.0
    );
    assert!(
        (jac[1][2] - d_theta_dot.1).abs() < 1e-9,
        "{} vs {}",
        jac[1][2],
        d_theta_dot.1
    );
}

#[test]
fn projections_and_dimensions_of_the_switches() {
    let m = model(0.4, 0.35, ImpactLaw::Ratio { r: 0.925 });
    let y = state(Sign::Pos);
    let rock = Mode::Rock { pivot: Sign::Pos };
    let slide_rock = Mode::SlideRock {
        pivot: Sign::Pos,
        slip: Sign::Pos,
    };
    // Slip: identity, 3 directions survive the switch itself.
    let slip = reset_jacobian(&m, rock, 4, &y, slide_rock, &y);
    assert_eq!(slip.dim, 2, "rock before: X' was already slaved");
    assert_eq!(slip.matrix[0], [1.0, 0.0, 0.0]);
    // Stick: onto rock's constraint.
    let stick = reset_jacobian(&m, slide_rock, 4, &y, rock, &y);
    assert_eq!(stick.dim, 2);
    assert_eq!(stick.matrix[2][2], 0.0);
    // A slip reversal keeps all three.
    let other = Mode::SlideRock {
        pivot: Sign::Pos,
        slip: Sign::Neg,
    };
    assert_eq!(reset_jacobian(&m, slide_rock, 4, &y, other, &y).dim, 3);
    // Uplift from rest: nothing survives.
    let flat = [0.0; N];
    let up = reset_jacobian(&m, Mode::Rest, 1, &flat, rock, &flat);
    assert_eq!(up.dim, 0);
    assert_eq!(up.matrix, [[0.0; DIM]; DIM]);
}
