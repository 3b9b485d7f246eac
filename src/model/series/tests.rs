//! The fused expansions against the plain recurrences of `reference`.

use super::*;
use crate::model::dynamics::test_scene::{model as scene, two_sines};
use crate::model::mode::Sign;

/// The largest difference between the fused and the reference
/// coefficients of every component and order, relative to the largest
/// term `|c_k| h^k` of that component's polynomial over a step `h`.
fn worst_difference(mode: Mode, exc: Excitation, y: [f64; N], order: usize, h: f64) -> f64 {
    let (geo, t) = (Geometry::new(1.0, 4.0), 2.7);
    let model = scene(geo, exc);
    let mu_k = model.mu_k;
    let mut fused = vec![[0.0; N]; order + 1];
    assert!(taylor(&model, mode, t, &y, order, &mut fused));
    let mut f = ForcingSeries::none();
    assert!(f.fill(&model.excitation, t, order));
    let mut r = reference::Work::new(&y);
    match mode {
        Mode::Rock { pivot } => reference::rock(
            &geo,
            pivot.value(),
            Tilt::new(&geo, pivot, y[THETA]),
            &f.a,
            &f.av,
            order,
            &mut r,
        ),
        Mode::SlideRock { pivot, slip } => reference::slide_rock(
            &geo,
            pivot.value(),
            slip.value(),
            mu_k,
            Tilt::new(&geo, pivot, y[THETA]),
            &f.a,
            &f.av,
            order,
            &mut r,
        ),
        _ => unreachable!("rocking modes only"),
    }
    let mut worst: f64 = 0.0;
    for n in 0..N {
        let scale = (0..=order)
            .map(|k| r.row(k)[n].abs() * h.powi(k as i32))
            .fold(0.0, f64::max)
            .max(1e-300);
        for (k, row) in fused.iter().enumerate() {
            let d = (row[n] - r.row(k)[n]).abs() * h.powi(k as i32) / scale;
            worst = worst.max(d);
        }
    }
    worst
}

#[test]
fn fused_expansions_match_the_plain_recurrences() {
    let (p, m) = (Sign::Pos, Sign::Neg);
    let modes = [
        Mode::Rock { pivot: p },
        Mode::Rock { pivot: m },
        Mode::SlideRock { pivot: p, slip: p },
        Mode::SlideRock { pivot: p, slip: m },
        Mode::SlideRock { pivot: m, slip: p },
        Mode::SlideRock { pivot: m, slip: m },
    ];
    let states = [
        [0.05, -0.2, 0.1, 0.01, 0.3, 0.02],
        [-0.12, 0.4, -0.3, -0.05, 1.0, 0.5],
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    ];
    let geo = Geometry::new(1.0, 4.0);
    for mode in modes {
        for y in states {
            for shared in [true, false] {
                for order in [8, 20, 28] {
                    let d = worst_difference(mode, two_sines(&geo, shared), y, order, 0.3);
                    assert!(d < 1e-13, "{mode:?} at {y:?}, shared {shared}, order {order}: {d:e}");
                }
            }
        }
    }
}

#[test]
fn free_rocking_has_no_forcing_terms() {
    for mode in [
        Mode::Rock { pivot: Sign::Pos },
        Mode::SlideRock {
            pivot: Sign::Neg,
            slip: Sign::Pos,
        },
    ] {
        let d = worst_difference(mode, Excitation::None, [0.1, -0.3, 0.0, 0.02, 0.0, 0.0], 20, 0.3);
        assert!(d < 1e-13, "{mode:?}: {d:e}");
    }
}
