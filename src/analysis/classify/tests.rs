//! Tests of the classifier on systems with known answers.

use super::*;
use crate::analysis::section::map_orbit;

fn logistic(r: f64) -> Vec<[f64; 1]> {
    map_orbit(|x: &[f64; 1]| [r * x[0] * (1.0 - x[0])], [0.3], 2000, 256)
}

fn golden_circle(n: usize) -> Vec<[f64; 2]> {
    let rho = (5.0_f64.sqrt() - 1.0) / 2.0;
    map_orbit(
        |p: &[f64; 2]| {
            let phi = p[1].atan2(p[0]) + std::f64::consts::TAU * rho;
            [phi.cos(), phi.sin()]
        },
        [1.0, 0.0],
        0,
        n,
    )
}

#[test]
fn logistic_periods_and_chaos() {
    let o = ClassifyOptions::default();
    let c = |r| classify_points(&logistic(r), None, &o).unwrap();
    assert_eq!(c(2.8), Response::Periodic { period: 1 });
    assert_eq!(c(3.2), Response::Periodic { period: 2 });
    assert_eq!(c(3.5), Response::Periodic { period: 4 });
    assert_eq!(c(3.55), Response::Periodic { period: 8 });
    // The period-3 window.
    assert_eq!(c(3.83), Response::Periodic { period: 3 });
    assert_eq!(c(3.9), Response::Chaotic);
    assert_eq!(c(4.0), Response::Chaotic);
}

#[test]
fn golden_rotation_is_quasiperiodic() {
    let o = ClassifyOptions::default();
    for n in [64, 255, 1000] {
        let pts = golden_circle(n);
        let t = curve_test(&pts);
        assert!(t.rotation_fraction > 0.99, "{t:?}");
        assert!((t.tour_ratio - std::f64::consts::PI).abs() < 0.1, "{t:?}");
        assert_eq!(classify_points(&pts, None, &o).unwrap(), Response::Quasiperiodic);
    }
}

#[test]
fn rotation_on_a_deformed_curve_in_three_dimensions_is_quasiperiodic() {
    // A torus section embedded in 3-D with unequal scales per component,
    // as (Θ, Θ', X') are.
    let pts: Vec<[f64; 3]> = golden_circle(255)
        .iter()
        .map(|p| [0.05 * (p[0] + 0.3 * p[1] * p[1]), 0.6 * p[1], 0.02 * p[0] + 0.1 * p[1]])
        .collect();
    assert_eq!(
        classify_points(&pts, None, &ClassifyOptions::default()).unwrap(),
        Response::Quasiperiodic
    );
}

#[test]
fn henon_attractor_is_chaotic() {
    let pts = map_orbit(
        |p: &[f64; 2]| [1.0 - 1.4 * p[0] * p[0] + p[1], 0.3 * p[0]],
        [0.1, 0.1],
        1000,
        255,
    );
    let t = curve_test(&pts);
    assert!(t.rotation_fraction < 0.5, "{t:?}");
    assert_eq!(
        classify_points(&pts, None, &ClassifyOptions::default()).unwrap(),
        Response::Chaotic
    );
}

#[test]
fn lyapunov_exponent_decides_for_aperiodic_points() {
    let o = ClassifyOptions::default();
    let circle = golden_circle(255);
    assert_eq!(classify_points(&circle, Some(0.5), &o).unwrap(), Response::Chaotic);
    assert_eq!(
        classify_points(&circle, Some(0.0), &o).unwrap(),
        Response::Quasiperiodic
    );
    // A periodic set stays periodic whatever exponent is supplied.
    assert_eq!(
        classify_points(&logistic(3.2), Some(0.5), &o).unwrap(),
        Response::Periodic { period: 2 }
    );
    assert_eq!(
        classify_points(&circle, Some(f64::NAN), &o),
        Err(ClassifyError::NonFiniteExponent)
    );
}

#[test]
fn bad_input_is_an_error() {
    let o = ClassifyOptions::default();
    assert_eq!(
        classify_points(&logistic(2.8)[..63], None, &o),
        Err(ClassifyError::TooFewPoints { have: 63, need: 64 })
    );
    let mut pts = logistic(2.8);
    pts[5][0] = f64::NAN;
    assert_eq!(
        classify_points(&pts, None, &o),
        Err(ClassifyError::NonFinite { index: 5 })
    );
    let bad = ClassifyOptions { k_max: 0, ..o };
    assert!(matches!(
        classify_points(&logistic(2.8), None, &bad),
        Err(ClassifyError::Options(_))
    ));
}

#[test]
fn tolerance_is_relative_to_the_amplitude() {
    // Period 2 whose points differ by 1e-4 of the amplitude: one point
    // (period 1) at the default rel_tol 1e-3, period 2 at 1e-6.
    let pts: Vec<[f64; 1]> = (0..100).map(|j| [1.0 + if j % 2 == 0 { 0.0 } else { 1e-4 }]).collect();
    assert_eq!(
        classify_points(&pts, None, &ClassifyOptions::default()).unwrap(),
        Response::Periodic { period: 1 }
    );
    let tight = ClassifyOptions {
        rel_tol: 1e-6,
        ..ClassifyOptions::default()
    };
    assert_eq!(
        classify_points(&pts, None, &tight).unwrap(),
        Response::Periodic { period: 2 }
    );
    // A fixed point at the origin with rounding noise: period 1 thanks to abs_tol.
    let noisy: Vec<[f64; 1]> = (0..100).map(|j| [1e-14 * f64::from(j % 3)]).collect();
    assert_eq!(
        classify_points(&noisy, None, &ClassifyOptions::default()).unwrap(),
        Response::Periodic { period: 1 }
    );
}

#[test]
fn names_round_trip_and_mode_notation() {
    let all = [
        Response::Periodic { period: 4 },
        Response::Quasiperiodic,
        Response::Chaotic,
        Response::Tumbled,
        Response::Rest,
        Response::Flight,
    ];
    for r in all {
        assert_eq!(Response::from_name(r.name(), r.period()), Some(r));
        assert!(Response::NAMES.contains(&r.name()));
    }
    assert_eq!(
        Response::Periodic { period: 2 }.mode_notation().as_deref(),
        Some("(1,2)")
    );
    assert_eq!(Response::Periodic { period: 2 }.to_string(), "periodic (1,2)");
    assert_eq!(Response::Chaotic.mode_notation(), None);
    assert_eq!(Response::from_name("periodic", None), None);
    assert_eq!(Response::from_name("chaotic", Some(2)), None);
    assert_eq!(Response::from_name("wobbly", None), None);
}

#[test]
fn principal_axes_of_a_tilted_ellipse() {
    let z: Vec<Vec<f64>> = (0..400)
        .map(|j| {
            let t = f64::from(j) * 0.1;
            let (a, b) = (3.0 * t.cos(), 1.0 * t.sin());
            let c = std::f64::consts::FRAC_1_SQRT_2;
            vec![c * a - c * b, c * a + c * b]
        })
        .collect();
    let (values, vectors) = principal_axes(&z);
    assert!(values[0] > values[1]);
    assert!((vectors[0][0].abs() - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-2);
    assert!((vectors[0][1].abs() - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-2);
}
