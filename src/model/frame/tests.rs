//! The frame's equations against a generic rigid-body solve written here:
//! two columns and a beam as three free planar bodies, every contact force
//! (or impulse) an unknown, the constraints imposed on accelerations (or
//! velocities), the whole linear system solved by Gaussian elimination. It
//! knows nothing of κ, the frame's restitution or the normal formulas.

use super::*;
use crate::model::geometry::G;

/// Solves `a x = b` (n × n, partial pivoting).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        b.swap(col, piv);
        assert!(a[col][col].abs() > 1e-12, "singular system");
        let (top, rest) = a.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for (k, row) in rest.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            b[col + 1 + k] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    x
}

/// The two columns' and the beam's equations, one row each: 17 unknowns
/// (each column's and the beam's (ẍ, ÿ, angular) at 0, 3 and 6, each base
/// force at 9 + 2k, the force on the beam from column k at 13 + 2k), or the
/// same with velocities and impulses.
#[derive(Default)]
struct Linear {
    rows: Vec<Vec<f64>>,
    rhs: Vec<f64>,
}

impl Linear {
    fn eq(&mut self, coef: &[(usize, f64)], value: f64) {
        let mut row = vec![0.0; 17];
        for &(j, c) in coef {
            row[j] += c;
        }
        self.rows.push(row);
        self.rhs.push(value);
    }

    /// The beam's balance: mass `mb`, inertia `i_b`, the forces from the
    /// columns at `rb` from its centre, `free` its right-hand sides.
    fn beam(&mut self, mb: f64, i_b: f64, rb: [[f64; 2]; 2], free: [f64; 2]) {
        self.eq(&[(6, mb), (13, -1.0), (15, -1.0)], free[0]);
        self.eq(&[(7, mb), (14, -1.0), (16, -1.0)], free[1]);
        let torque = [
            (8, i_b),
            (13, rb[0][1]),
            (14, -rb[0][0]),
            (15, rb[1][1]),
            (16, -rb[1][0]),
        ];
        self.eq(&torque, 0.0);
    }

    fn solve(self) -> Vec<f64> {
        solve(self.rows, self.rhs)
    }
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// `p` rotated by `phi` (counter-clockwise) about `o`.
fn rotate(o: [f64; 2], p: [f64; 2], phi: f64) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    let d = sub(p, o);
    [o[0] + c * d[0] - s * d[1], o[1] + s * d[0] + c * d[1]]
}

/// A two-column frame, columns `2b × 2h` of mass 1 centred at x = 0 and
/// x = `span`, tilted by the project's θ about their right corners (a
/// clockwise rotation, so the test's counter-clockwise angle is −θ).
struct Layout {
    centre: [[f64; 2]; 2],
    pivot: [[f64; 2]; 2],
    top: [[f64; 2]; 2],
    beam: [f64; 2],
}

fn layout(b: f64, h: f64, span: f64, theta: f64) -> Layout {
    let mut l = Layout {
        centre: [[0.0; 2]; 2],
        pivot: [[0.0; 2]; 2],
        top: [[0.0; 2]; 2],
        beam: [0.0; 2],
    };
    for k in 0..2 {
        let x = k as f64 * span;
        let o = [x + b, 0.0];
        l.pivot[k] = o;
        l.centre[k] = rotate(o, [x, h], -theta);
        // The beam rests on the corner diagonally opposite the pivot.
        l.top[k] = rotate(o, [x - b, 2.0 * h], -theta);
    }
    // The beam's centre of mass at the level of its supports, midway.
    l.beam = [(l.top[0][0] + l.top[1][0]) / 2.0, l.top[0][1]];
    l
}

/// The generic Newton–Euler solve at tilt θ and rate θ̇ (physical, rad and
/// rad/s) under base acceleration (a, a_v) per g: returns θ̈ (rad/s²), the
/// first column's centre ẍ (m/s²), each base's normal force per column
/// weight and the beam's total support force per beam weight.
fn newton_euler(
    b: f64,
    h: f64,
    beam_mass: f64,
    theta: f64,
    theta_dot: f64,
    a: f64,
    av: f64,
) -> (f64, f64, [f64; 2], f64) {
    let (m, i_c) = (1.0, (4.0 * b * b + 4.0 * h * h) / 12.0);
    let (mb, i_b) = (beam_mass, beam_mass * 10.0);
    let l = layout(b, h, 5.0, theta);
    let w = -theta_dot; // counter-clockwise
    // Unknowns: column k (ax, ay, α) at 3k, beam (ax, ay, α) at 6, base
    // force k at 9 + 2k, force on the beam from column k at 13 + 2k.
    let mut sys = Linear::default();
    for k in 0..2 {
        let (c, f, q) = (3 * k, 9 + 2 * k, 13 + 2 * k);
        let ro = sub(l.pivot[k], l.centre[k]);
        let rt = sub(l.top[k], l.centre[k]);
        sys.eq(&[(c, m), (f, -1.0), (q, 1.0)], -m * G * a);
        sys.eq(&[(c + 1, m), (f + 1, -1.0), (q + 1, 1.0)], -m * G * (1.0 + av));
        // I α = ro × F − rt × Q.
        sys.eq(
            &[(c + 2, i_c), (f, ro[1]), (f + 1, -ro[0]), (q, -rt[1]), (q + 1, rt[0])],
            0.0,
        );
        // The pivot does not accelerate: a + α × ro − w² ro = 0.
        sys.eq(&[(c, 1.0), (c + 2, -ro[1])], w * w * ro[0]);
        sys.eq(&[(c + 1, 1.0), (c + 2, ro[0])], w * w * ro[1]);
        // The beam's support moves with the column's corner.
        let rb = sub(l.top[k], l.beam);
        sys.eq(&[(6, 1.0), (8, -rb[1]), (c, -1.0), (c + 2, rt[1])], -w * w * rt[0]);
        sys.eq(&[(7, 1.0), (8, rb[0]), (c + 1, -1.0), (c + 2, -rt[0])], -w * w * rt[1]);
    }
    let rb = [sub(l.top[0], l.beam), sub(l.top[1], l.beam)];
    sys.beam(mb, i_b, rb, [-mb * G * a, -mb * G * (1.0 + av)]);
    let x = sys.solve();
    let normals = [x[10] / (m * G), x[12] / (m * G)];
    (-x[2], x[0], normals, (x[14] + x[16]) / (mb * G))
}

#[test]
fn rocking_accelerations_and_forces_match_a_newton_euler_solve_of_columns_and_beam() {
    for &(bw, hh, beam_ratio) in &[(1.0, 6.0, 0.5), (0.6, 2.0, 0.0), (2.0, 5.0, 3.0), (1.0, 1.5, 10.0)] {
        let geo = Geometry::new(bw, hh);
        let frame = Frame {
            columns: 2,
            beam_mass_ratio: beam_ratio,
        };
        for &(big_theta, big_w, a, av) in &[(0.3, 0.2, 0.1, 0.0), (0.7, -0.4, -0.3, 0.2), (0.05, 1.1, 0.0, -0.4)] {
            let fo = Forcing { a, av };
            let tilt = Tilt::new(&geo, Sign::Pos, big_theta);
            let acc = rock(&frame, frame.kappa(), Sign::Pos, tilt, big_w, fo);
            let theta = geo.psi * big_theta;
            let theta_dot = big_w * geo.p;
            // Beam mass: γ_b times both columns' (each of mass 1).
            let (theta_ddot, x_ddot, normals, beam) =
                newton_euler(bw / 2.0, hh / 2.0, 2.0 * beam_ratio, theta, theta_dot, a, av);
            let p2 = geo.p * geo.p;
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-11 * (1.0 + y.abs());
            assert!(
                close(acc.wdd, theta_ddot / p2),
                "ψΘ'' {} vs {}",
                acc.wdd,
                theta_ddot / p2
            );
            assert!(
                close(acc.x_ddot, x_ddot / (p2 * geo.r)),
                "X'' {} vs {}",
                acc.x_ddot,
                x_ddot / (p2 * geo.r)
            );
            // A beam whose centre is level with its supports loads both
            // columns alike.
            for n in normals {
                assert!(close(acc.base_normal, n), "base normal {} vs {n}", acc.base_normal);
            }
            if beam_ratio > 0.0 {
                assert!(
                    close(acc.beam_normal, beam),
                    "beam normal {} vs {beam}",
                    acc.beam_normal
                );
            }
        }
    }
}

/// The generic impulse solve of the impact at θ = 0: every column's left
/// corner and the beam's supports on the columns' right top corners strike
/// and stick, the old contacts release. Returns the ratio of the columns'
/// angular velocities after and before, for each column, and the beam's.
fn impact_ratio(b: f64, h: f64, beam_mass: f64) -> ([f64; 2], f64, [f64; 2]) {
    let (m, i_c) = (1.0, (4.0 * b * b + 4.0 * h * h) / 12.0);
    let (mb, i_b) = (beam_mass, beam_mass * 10.0);
    let span = 5.0;
    let l = layout(b, h, span, 0.0);
    let w0 = 1.0; // counter-clockwise: back towards upright from θ > 0
    let mut sys = Linear::default();
    // Velocities before: each column about its right corner, the beam with
    // the corner it rested on.
    let vel = |o: [f64; 2], p: [f64; 2]| {
        let r = sub(p, o);
        [-w0 * r[1], w0 * r[0]]
    };
    let beam_before = vel(l.pivot[0], l.top[0]);
    for k in 0..2 {
        let (c, f, q) = (3 * k, 9 + 2 * k, 13 + 2 * k);
        let x = k as f64 * span;
        let v_before = vel(l.pivot[k], l.centre[k]);
        let new_pivot = [x - b, 0.0];
        let new_top = [x + b, 2.0 * h];
        let ro = sub(new_pivot, l.centre[k]);
        let rt = sub(new_top, l.centre[k]);
        sys.eq(&[(c, m), (f, -1.0), (q, 1.0)], m * v_before[0]);
        sys.eq(&[(c + 1, m), (f + 1, -1.0), (q + 1, 1.0)], m * v_before[1]);
        sys.eq(
            &[(c + 2, i_c), (f, ro[1]), (f + 1, -ro[0]), (q, -rt[1]), (q + 1, rt[0])],
            i_c * w0,
        );
        sys.eq(&[(c, 1.0), (c + 2, -ro[1])], 0.0);
        sys.eq(&[(c + 1, 1.0), (c + 2, ro[0])], 0.0);
        let rb = sub(new_top, l.beam);
        sys.eq(&[(6, 1.0), (8, -rb[1]), (c, -1.0), (c + 2, rt[1])], 0.0);
        sys.eq(&[(7, 1.0), (8, rb[0]), (c + 1, -1.0), (c + 2, -rt[0])], 0.0);
    }
    let rb = [sub([b, 2.0 * h], l.beam), sub([span + b, 2.0 * h], l.beam)];
    sys.beam(mb, i_b, rb, [mb * beam_before[0], mb * beam_before[1]]);
    let x = sys.solve();
    ([x[2] / w0, x[5] / w0], x[8], [x[10], x[12]])
}

#[test]
fn the_impact_coefficient_matches_a_generic_impulse_solve_and_is_housners_without_a_beam() {
    for &(bw, hh) in &[(1.0, 6.0), (0.6, 2.0), (2.0, 5.0), (1.0, 1.2)] {
        let geo = Geometry::new(bw, hh);
        for beam_ratio in [0.0, 0.25, 1.0, 4.0] {
            let frame = Frame {
                columns: 2,
                beam_mass_ratio: beam_ratio,
            };
            // A massless beam: the generic solve needs a mass; a tiny one.
            let mass = (2.0 * beam_ratio).max(1e-12);
            let (ratios, beam_spin, base_impulses) = impact_ratio(bw / 2.0, hh / 2.0, mass);
            let r = frame.restitution(&geo);
            for ratio in ratios {
                assert!((ratio - r).abs() < 1e-10, "{bw}×{hh}, γ_b {beam_ratio}: {ratio} vs {r}");
            }
            assert!(beam_spin.abs() < 1e-10, "the beam does not spin: {beam_spin}");
            // The new pivots push (a contact cannot pull) wherever r > 0.
            if r > 0.0 {
                assert!(base_impulses.iter().all(|&p| p > 0.0), "{base_impulses:?}");
            }
        }
        let lone = Frame {
            columns: 2,
            beam_mass_ratio: 0.0,
        };
        assert_eq!(lone.restitution(&geo), geo.housner_r());
        assert_eq!(lone.kappa(), 1.0);
    }
}

#[test]
fn without_a_beam_the_frame_equations_are_a_lone_columns_bit_for_bit() {
    let geo = Geometry::new(0.8, 3.0);
    let lone = Frame {
        columns: 2,
        beam_mass_ratio: 0.0,
    };
    for &(th, w, a, av) in &[(0.2, 0.3, 0.1, 0.0), (-0.6, -0.1, -0.2, 0.3)] {
        let fo = Forcing { a, av };
        let s = Sign::of(th);
        let tilt = Tilt::new(&geo, s, th);
        let frame = rock(&lone, lone.kappa(), s, tilt, w, fo);
        let block = crate::model::dynamics::rock_at(&geo, s, tilt, w / geo.psi, fo);
        assert_eq!(frame.wdd * geo.inv_psi, block.theta_ddot);
        assert_eq!(frame.x_ddot, block.x_ddot);
        assert_eq!(frame.base_normal, block.normal);
    }
}

#[test]
fn a_column_and_the_beam_move_as_their_corners_turned_about_the_pivot() {
    let geo = Geometry::new(0.7, 4.2);
    let frame = Frame {
        columns: 2,
        beam_mass_ratio: 2.0,
    };
    let (b, h) = (0.35, 2.1);
    // Clockwise rotation by θ of a point about a pivot, written out.
    let turn = |p: [f64; 2], pivot: [f64; 2], t: f64| {
        let (u, v) = (p[0] - pivot[0], p[1] - pivot[1]);
        [
            pivot[0] + u * t.cos() + v * t.sin(),
            pivot[1] - u * t.sin() + v * t.cos(),
        ]
    };
    for theta in [0.0, 0.05, -0.05, 0.2, -0.31] {
        let s: f64 = if theta < 0.0 { -1.0 } else { 1.0 };
        let pivot = [s * b, 0.0];
        let centre = turn([0.0, h], pivot, theta);
        // The beam rests on the top corner opposite the pivot.
        let support = [-s * b, 2.0 * h];
        let moved = turn(support, pivot, theta);
        let [column, beam] = frame.bodies(&geo, theta);
        assert_eq!(column[0], theta);
        assert!((column[1] - centre[0]).abs() < 1e-15 && (column[2] - (centre[1] - h)).abs() < 1e-15);
        assert_eq!(beam[0], 0.0);
        assert!((beam[1] - (moved[0] - support[0])).abs() < 1e-14, "{theta}");
        assert!((beam[2] - (moved[1] - support[1])).abs() < 1e-14, "{theta}");
        let rise = 2.0 * geo.r * ((geo.psi - theta.abs()).cos() - geo.cos_psi);
        assert!((beam[2] - rise).abs() < 1e-14, "{theta}: {} against {rise}", beam[2]);
    }
}
