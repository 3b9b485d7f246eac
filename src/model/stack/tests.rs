//! The stack's equations against a generic constrained Newton–Euler
//! solve, and its impacts against a generic impulse solve, both written
//! here: every block a free rigid body with three unknowns, every contact
//! force (and a closed face's couple) an unknown, the constraints of each
//! contact written on the accelerations (or the velocities just after an
//! impact) of the two points that meet.

// The generic solves index unknowns, blocks and interfaces.
#![allow(clippy::needless_range_loop)]

use super::dynamics::{self, accelerations, impact_rates, interface_load};
use super::pose::{Pose, V2};
use super::{Contact, MAX_BLOCKS, NS, SLIDE, SLIDE_RATE, StackBlock, StackGeometry};

/// Solves a dense `a x = b` by Gaussian elimination with partial pivoting.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs())).unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    x
}

fn block(width: f64, height: f64, offset: f64) -> StackBlock {
    StackBlock::new(width, height, offset)
}

/// Clockwise cross product: the clockwise moment about the origin of a
/// force `f` at `r`: −(r × f)_z.
fn moment_cw(r: V2, f: V2) -> f64 {
    -(r[0] * f[1] - r[1] * f[0])
}

/// The generic system: unknowns [a_jx, a_jy, α_j for each block] then, per
/// interface, the force on the block above at its pivot (closed: at its
/// left corner) and, for a closed face, the clockwise couple.
struct Generic {
    accel: Vec<(V2, f64)>,
    force: Vec<V2>,
    couple: Vec<f64>,
}

/// Current world positions every test needs, computed here from the
/// absolute angles: block j's placement x ↦ Rot(φ_j)(x − p_j⁰) + P_j.
struct World {
    centre: Vec<V2>,
    pivot: Vec<V2>,
    left: Vec<V2>,
    omega: Vec<f64>,
}

fn rot(phi: f64, v: V2) -> V2 {
    let (s, c) = phi.sin_cos();
    [v[0] * c + v[1] * s, -v[0] * s + v[1] * c]
}

fn world(geo: &StackGeometry, contacts: &[Contact], q: &[f64], qd: &[f64]) -> World {
    let k = geo.k;
    let (mut centre, mut pivot, mut left, mut omega) = (vec![], vec![], vec![], vec![]);
    let mut placements: Vec<(f64, V2, V2)> = vec![]; // (φ, rest pivot, world pivot)
    let (mut phi, mut w) = (0.0, 0.0);
    let place = |pl: &(f64, V2, V2), x: V2| {
        let r = rot(pl.0, [x[0] - pl.1[0], x[1] - pl.1[1]]);
        [r[0] + pl.2[0], r[1] + pl.2[1]]
    };
    for j in 0..k {
        phi += q[j];
        w += qd[j];
        let corner = geo.corners[j][usize::from(contacts[j] == Contact::Right)];
        let p = if j == 0 {
            corner
        } else {
            place(&placements[j - 1], corner)
        };
        let l = if j == 0 {
            geo.corners[0][0]
        } else {
            place(&placements[j - 1], geo.corners[j][0])
        };
        placements.push((phi, corner, p));
        centre.push(place(&placements[j], geo.centre[j]));
        pivot.push(p);
        left.push(l);
        omega.push(w);
    }
    World {
        centre,
        pivot,
        left,
        omega,
    }
}

/// The unknowns' layout of a generic solve of `k` blocks in `contacts`:
/// each block's three accelerations (or impulses) first, then per
/// interface its force's two components (`fcol[i]`) and, for a closed
/// one, its couple (`ccol[i]`); and their count.
fn unknowns(contacts: &[Contact], k: usize) -> (Vec<usize>, Vec<Option<usize>>, usize) {
    let mut col = 3 * k;
    let mut fcol = vec![0; k];
    let mut ccol = vec![None; k];
    for i in 0..k {
        fcol[i] = col;
        col += 2;
        if contacts[i] == Contact::Closed {
            ccol[i] = Some(col);
            col += 1;
        }
    }
    (fcol, ccol, col)
}

/// A row of a generic solve, for its right-hand side.
#[derive(Clone, Copy)]
enum Row {
    /// Block `j`'s Newton row, component `d`.
    Newton(usize, usize),
    /// Block `j`'s Euler row about its centre.
    Euler(usize),
    /// Component `d` of the meeting of interface `i`'s two points.
    Meet(usize, usize),
    /// A closed interface turning with the block below.
    Turn,
}

impl World {
    /// Where interface `i`'s force acts: its pivot, or a closed face's left
    /// corner.
    fn force_point(&self, contacts: &[Contact], i: usize) -> V2 {
        if contacts[i] == Contact::Closed {
            self.left[i]
        } else {
            self.pivot[i]
        }
    }

    /// Block `j`'s arm to `p`.
    fn arm(&self, j: usize, p: V2) -> V2 {
        [p[0] - self.centre[j][0], p[1] - self.centre[j][1]]
    }
}

/// The generic system of the stack in `contacts` at `w`, on the unknowns
/// of [`unknowns`]: Newton's and Euler's rows of each block (forces or
/// impulses alike), then the rows that make the two points of each
/// interface meet (and a closed face turn with the block below), each row's
/// right-hand side from `rhs`. With `slide` = s μ_k the base contact slips:
/// its horizontal meeting row becomes Coulomb's law F_x = −s μ_k F_y. The
/// matrix, the right-hand sides and the force and couple columns.
#[allow(clippy::type_complexity)]
fn generic_system(
    geo: &StackGeometry,
    contacts: &[Contact],
    w: &World,
    slide: Option<f64>,
    mut rhs: impl FnMut(Row) -> f64,
) -> (Vec<Vec<f64>>, Vec<f64>, Vec<usize>, Vec<Option<usize>>) {
    let k = geo.k;
    let (fcol, ccol, n) = unknowns(contacts, k);
    let mut a = vec![];
    let mut b = vec![];
    let row = || vec![0.0; n];
    let at = |i: usize| w.force_point(contacts, i);
    for j in 0..k {
        // Newton: m a_j − F_j + F_{j+1} = m g_e (or the momentum change).
        for d in 0..2 {
            let mut r = row();
            r[3 * j + d] = geo.mass[j];
            r[fcol[j] + d] = -1.0;
            if j + 1 < k {
                r[fcol[j + 1] + d] = 1.0;
            }
            a.push(r);
            b.push(rhs(Row::Newton(j, d)));
        }
        // Euler (clockwise): I α_j = M_cw(F_j at its point) − M_cw(F_{j+1}) + C_j − C_{j+1}.
        let mut r = row();
        r[3 * j + 2] = geo.inertia[j];
        let below = w.arm(j, at(j));
        // M_cw(r, F) = −(r_x F_y − r_y F_x): coefficient of F_x is r_y, of F_y is −r_x.
        r[fcol[j]] -= below[1];
        r[fcol[j] + 1] += below[0];
        if let Some(c) = ccol[j] {
            r[c] -= 1.0;
        }
        if j + 1 < k {
            let above = w.arm(j, at(j + 1));
            r[fcol[j + 1]] += above[1];
            r[fcol[j + 1] + 1] -= above[0];
            if let Some(c) = ccol[j + 1] {
                r[c] += 1.0;
            }
        }
        a.push(r);
        b.push(rhs(Row::Euler(j)));
    }
    // Constraints: the point where interface i's force acts has the same
    // acceleration (velocity) on both blocks; a closed face also turns with
    // the block below. A point at arm r of block j accelerates at
    // a_j + α_j J r − ω_j² r.
    for i in 0..k {
        let p = at(i);
        for d in 0..2 {
            if let (0, 0, Some(smu)) = (i, d, slide) {
                let mut r = row();
                r[fcol[0]] = 1.0;
                r[fcol[0] + 1] = smu;
                a.push(r);
                b.push(0.0);
                continue;
            }
            let mut r = row();
            for (j, sign) in [(i, 1.0), (i.wrapping_sub(1), -1.0)] {
                if j >= k {
                    continue;
                }
                let arm = w.arm(j, p);
                let jr = [arm[1], -arm[0]];
                r[3 * j + d] += sign;
                r[3 * j + 2] += sign * jr[d];
            }
            a.push(r);
            b.push(rhs(Row::Meet(i, d)));
        }
        if contacts[i] == Contact::Closed {
            let mut r = row();
            r[3 * i + 2] = 1.0;
            if i > 0 {
                r[3 * (i - 1) + 2] = -1.0;
            }
            a.push(r);
            b.push(rhs(Row::Turn));
        }
    }
    (a, b, fcol, ccol)
}

/// The generic Newton–Euler solve of the stack in `contacts` at the given
/// angles and rates, under effective gravity `g_e`, the base contact
/// slipping with s μ_k = `slide` if given.
fn newton_euler(
    geo: &StackGeometry,
    contacts: &[Contact],
    q: &[f64],
    qd: &[f64],
    g_e: V2,
    slide: Option<f64>,
) -> Generic {
    let k = geo.k;
    let w = world(geo, contacts, q, qd);
    let (a, b, fcol, ccol) = generic_system(geo, contacts, &w, slide, |row| match row {
        Row::Newton(j, d) => geo.mass[j] * g_e[d],
        // The centripetal terms, −ω_j² r on each side, moved right.
        Row::Meet(i, d) => {
            let p = w.force_point(contacts, i);
            let mut rhs = 0.0;
            for (j, sign) in [(i, 1.0), (i.wrapping_sub(1), -1.0)] {
                if j < k {
                    rhs += sign * w.omega[j] * w.omega[j] * w.arm(j, p)[d];
                }
            }
            rhs
        }
        Row::Euler(_) | Row::Turn => 0.0,
    });
    let x = solve(a, b);
    Generic {
        accel: (0..k).map(|j| ([x[3 * j], x[3 * j + 1]], x[3 * j + 2])).collect(),
        force: (0..k).map(|i| [x[fcol[i]], x[fcol[i] + 1]]).collect(),
        couple: (0..k).map(|i| ccol[i].map_or(0.0, |c| x[c])).collect(),
    }
}

fn state(q: &[f64], qd: &[f64]) -> [f64; NS] {
    let mut y = [0.0; NS];
    for (j, (&a, &b)) in q.iter().zip(qd).enumerate() {
        y[j] = a;
        y[MAX_BLOCKS + j] = b;
    }
    y
}

fn contacts_of(c: &[Contact]) -> [Contact; MAX_BLOCKS] {
    let mut out = [Contact::Closed; MAX_BLOCKS];
    out[..c.len()].copy_from_slice(c);
    out
}

/// Stacks of 2 and 3 blocks of different widths, offsets and slenderness.
fn shapes() -> Vec<Vec<StackBlock>> {
    vec![
        vec![block(1.2, 0.5, 0.0), block(0.4, 1.6, 0.1)],
        vec![block(0.6, 1.0, 0.0), block(0.9, 0.4, -0.05)],
        vec![block(0.9, 0.35, 0.0), block(0.6, 0.3, 0.05), block(0.3, 0.9, -0.04)],
        vec![block(0.5, 2.0, 0.0), block(0.5, 2.0, 0.0), block(0.5, 2.0, 0.0)],
    ]
}

/// Every combination of contacts at states with the open interfaces
/// turned on their own side.
fn cases(k: usize) -> Vec<(Vec<Contact>, Vec<f64>, Vec<f64>)> {
    let mut out = vec![];
    let choices = [Contact::Closed, Contact::Left, Contact::Right];
    for code in 0..3usize.pow(k as u32) {
        let cs: Vec<Contact> = (0..k).map(|i| choices[(code / 3usize.pow(i as u32)) % 3]).collect();
        for (amp, rate) in [(0.0, 0.0), (0.03, 0.4), (0.11, -0.7)] {
            let q: Vec<f64> = cs
                .iter()
                .enumerate()
                .map(|(i, c)| c.sign() * amp * (1.0 + 0.3 * i as f64))
                .collect();
            let qd: Vec<f64> = cs
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    if *c == Contact::Closed {
                        0.0
                    } else {
                        rate * (1.0 - 0.4 * i as f64)
                    }
                })
                .collect();
            out.push((cs.clone(), q, qd));
        }
    }
    out
}

/// Every test shape at three effective gravities (m per τ²: the base
/// still, and shaken either way with a vertical part), with every contact
/// combination and state of [`cases`].
fn each_case(mut check: impl FnMut(&StackGeometry, V2, &[Contact], &[f64], &[f64])) {
    for blocks in shapes() {
        let geo = StackGeometry::new(&blocks).unwrap();
        let g_unit = 4.0 * geo.r1 / 3.0;
        for g_e in [
            [0.0, -g_unit],
            [0.37 * g_unit, -1.2 * g_unit],
            [-0.8 * g_unit, -0.6 * g_unit],
        ] {
            for (cs, q, qd) in cases(geo.k) {
                check(&geo, g_e, &cs, &q, &qd);
            }
        }
    }
}

#[test]
fn every_contact_combination_accelerates_as_a_generic_newton_euler_solve_says() {
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    each_case(|geo, g_e, cs, q, qd| {
        let g_unit = 4.0 * geo.r1 / 3.0;
        let contacts = contacts_of(cs);
        let y = state(q, qd);
        let pose = Pose::new(geo, &contacts, &y);
        let acc = accelerations(geo, &contacts, None, &pose, g_e);
        let generic = newton_euler(geo, cs, q, qd, g_e, None);
        let w = world(geo, cs, q, qd);
        let scale = g_unit;
        for j in 0..geo.k {
            for d in 0..2 {
                assert!((pose.centre[j][d] - w.centre[j][d]).abs() < 1e-13, "{cs:?} centre {j}");
                worst = worst.max((acc.centre_acc[j][d] - generic.accel[j].0[d]).abs() / scale);
            }
            worst = worst.max((acc.alpha[j] - generic.accel[j].1).abs() * geo.r1 / scale);
        }
        for i in 0..geo.k {
            let load = interface_load(geo, &pose, &acc, g_e, g_unit, i);
            let weight = geo.mass_above(i) * g_unit;
            let n = if i == 0 {
                [0.0, 1.0]
            } else {
                rot(pose.phi[i - 1], [0.0, 1.0])
            };
            let t = if i == 0 {
                [1.0, 0.0]
            } else {
                rot(pose.phi[i - 1], [1.0, 0.0])
            };
            let f = generic.force[i];
            worst = worst.max((load.normal - (f[0] * n[0] + f[1] * n[1]) / weight).abs());
            worst = worst.max((load.tangential - (f[0] * t[0] + f[1] * t[1]) / weight).abs());
            if cs[i] == Contact::Closed {
                // About the left corner: the couple alone (the force
                // acts there); about the right one, the force's arm too.
                let right = if i == 0 { geo.corners[0][1] } else { w.left[i] };
                let right = if i == 0 {
                    right
                } else {
                    let span = rot(pose.phi[i - 1], [geo.span(i), 0.0]);
                    [w.left[i][0] + span[0], w.left[i][1] + span[1]]
                };
                let lever = [w.left[i][0] - right[0], w.left[i][1] - right[1]];
                let about_right = generic.couple[i] + f[0] * lever[1] - f[1] * lever[0];
                worst = worst.max((load.about_left - generic.couple[i] / weight).abs() / geo.r1);
                worst = worst.max((load.about_right - about_right / weight).abs() / geo.r1);
                // A test of the test: the generic couple is the clockwise moment.
                let _ = moment_cw;
            }
        }
        checked += 1;
    });
    assert!(checked > 300, "{checked}");
    assert!(worst < 1e-11, "largest difference {worst:e}");
}

/// The generic impulse solve: velocities just after the impact, each
/// block's momentum changed only by contact impulses, which act at the
/// contacts of `after`; the constraints of `after` hold on the velocities.
fn impulse(geo: &StackGeometry, before: &[Contact], after: &[Contact], q: &[f64], qd: &[f64]) -> Vec<f64> {
    let k = geo.k;
    let w0 = world(geo, before, q, qd);
    // Velocities before, from the chain: a point at p of block j moves at
    // Σ_{i ≤ j} q_i' J(p − P_i).
    let vel = |p: V2, j: usize| {
        let mut v = [0.0; 2];
        for i in 0..=j {
            v[0] += qd[i] * (p[1] - w0.pivot[i][1]);
            v[1] += qd[i] * -(p[0] - w0.pivot[i][0]);
        }
        v
    };
    let w1 = world(geo, after, q, qd);
    let (a, b, _, _) = generic_system(geo, after, &w1, None, |row| match row {
        Row::Newton(j, d) => geo.mass[j] * vel(w0.centre[j], j)[d],
        Row::Euler(j) => geo.inertia[j] * w0.omega[j],
        Row::Meet(..) | Row::Turn => 0.0,
    });
    let x = solve(a, b);
    (0..k)
        .map(|j| x[3 * j + 2] - if j > 0 { x[3 * (j - 1) + 2] } else { 0.0 })
        .collect()
}

/// Every impact of the test stacks: for each shape, contact case and open
/// interface i, interface i hitting (q_i = 0, moving towards it) into its
/// other corner or closed; `check` gets the shape, the contacts before
/// and after, and the angles and rates.
fn each_impact(mut check: impl FnMut(&StackGeometry, &[Contact], &[Contact], &[f64], &[f64])) {
    for blocks in shapes() {
        let geo = StackGeometry::new(&blocks).unwrap();
        for (cs, q, qd) in cases(geo.k) {
            for i in 0..geo.k {
                if cs[i] == Contact::Closed {
                    continue;
                }
                let (mut q, mut qd) = (q.clone(), qd.clone());
                q[i] = 0.0;
                qd[i] = -cs[i].sign() * qd[i].abs().max(0.3);
                let flipped = if cs[i] == Contact::Right {
                    Contact::Left
                } else {
                    Contact::Right
                };
                for new in [flipped, Contact::Closed] {
                    let mut after = cs.clone();
                    after[i] = new;
                    check(&geo, &cs, &after, &q, &qd);
                }
            }
        }
    }
}

#[test]
fn every_impact_matches_a_generic_impulse_solve() {
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    each_impact(|geo, cs, after, q, qd| {
        let y = state(q, qd);
        let before = Pose::new(geo, &contacts_of(cs), &y);
        let at = Pose::new(geo, &contacts_of(after), &y);
        let (rates, _) = impact_rates(geo, &contacts_of(after), None, &before, &at);
        let generic = impulse(geo, cs, after, q, qd);
        for j in 0..geo.k {
            worst = worst.max((rates[j] - generic[j]).abs());
        }
        checked += 1;
    });
    assert!(checked > 100, "{checked}");
    assert!(worst < 1e-11, "largest difference {worst:e}");
}

/// Two blocks of width `b` and heights `h1` (bottom) and `h2`, glued: one
/// block of height h1 + h2.
fn glued_pair(b: f64, h1: f64, h2: f64) -> StackGeometry {
    let mut blocks = vec![block(b, h1, 0.0), block(b, h2, 0.0)];
    blocks[1].glued = true;
    StackGeometry::new(&blocks).unwrap()
}

#[test]
fn a_glued_stack_of_equal_widths_impacts_with_housners_coefficient() {
    // Two glued blocks of width B are one block of their summed height H:
    // r = 1 − (3/2) sin²α with tan α = B/H.
    let (b, h1, h2) = (0.4, 0.7, 1.1);
    let geo = glued_pair(b, h1, h2);
    let before = contacts_of(&[Contact::Right, Contact::Closed]);
    let after = contacts_of(&[Contact::Left, Contact::Closed]);
    let y = state(&[0.0, 0.0], &[-0.6, 0.0]);
    let (rates, _) = impact_rates(
        &geo,
        &after,
        None,
        &Pose::new(&geo, &before, &y),
        &Pose::new(&geo, &after, &y),
    );
    let alpha = (b / (h1 + h2)).atan();
    let r = 1.0 - 1.5 * alpha.sin().powi(2);
    assert!((rates[0] / -0.6 - r).abs() < 1e-14, "{} vs {r}", rates[0] / -0.6);
    // And its energy is the block's: ½ I_O θ'², I_O = m (B² + H²)/3.
    let pose = Pose::new(&geo, &after, &state(&[0.0, 0.0], &[rates[0], 0.0]));
    let m = b * (h1 + h2);
    let io = m * (b * b + (h1 + h2).powi(2)) / 3.0;
    let kinetic = dynamics::kinetic(&geo, &pose);
    assert!((kinetic - 0.5 * io * rates[0] * rates[0]).abs() < 1e-14 * kinetic.max(1e-300));
}

/// s μ_k of a sliding base face: either sense, and no friction.
const SLIDES: [f64; 3] = [0.35, -0.6, 0.0];

#[test]
fn every_contact_combination_sliding_on_the_base_accelerates_as_a_generic_newton_euler_solve_says() {
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    each_case(|geo, g_e, cs, q, qd| {
        let g_unit = 4.0 * geo.r1 / 3.0;
        for smu in SLIDES {
            let contacts = contacts_of(cs);
            let mut y = state(q, qd);
            // The slip moves everything, and its rate nothing
            // that accelerates.
            y[SLIDE] = 0.07;
            y[SLIDE_RATE] = 0.2 * smu.signum();
            let pose = Pose::new(geo, &contacts, &y);
            let acc = accelerations(geo, &contacts, Some(smu), &pose, g_e);
            let generic = newton_euler(geo, cs, q, qd, g_e, Some(smu));
            let w = world(geo, cs, q, qd);
            for j in 0..geo.k {
                assert!((pose.centre[j][0] - 0.07 - w.centre[j][0]).abs() < 1e-13);
                for d in 0..2 {
                    worst = worst.max((acc.centre_acc[j][d] - generic.accel[j].0[d]).abs() / g_unit);
                }
                worst = worst.max((acc.alpha[j] - generic.accel[j].1).abs() * geo.r1 / g_unit);
            }
            for i in 0..geo.k {
                let load = interface_load(geo, &pose, &acc, g_e, g_unit, i);
                let weight = geo.mass_above(i) * g_unit;
                let f = generic.force[i];
                let n = if i == 0 {
                    [0.0, 1.0]
                } else {
                    rot(pose.phi[i - 1], [0.0, 1.0])
                };
                worst = worst.max((load.normal - (f[0] * n[0] + f[1] * n[1]) / weight).abs());
                if i == 0 {
                    // Coulomb: the base's friction is −s μ_k N.
                    worst = worst.max((load.tangential + smu * load.normal).abs());
                    worst = worst.max((load.tangential - f[0] / weight).abs());
                }
            }
            // The slip's acceleration is the base contact point's.
            let p = w.force_point(cs, 0);
            let arm = w.arm(0, p);
            let (a0, al0) = generic.accel[0];
            let point = a0[0] + al0 * arm[1] - w.omega[0] * w.omega[0] * arm[0];
            worst = worst.max((acc.slide_acc - point).abs() / g_unit);
            checked += 1;
        }
    });
    assert!(checked > 900, "{checked}");
    assert!(worst < 1e-11, "largest difference {worst:e}");
}

/// The generic impulse solve with the base sliding through the impact
/// (`slide` = s μ_k: its friction impulse −s μ_k times its normal one) or
/// its contact point stopped (None): each block's centre velocity and
/// angular velocity after.
fn impulse_on_base(
    geo: &StackGeometry,
    before: &[Contact],
    after: &[Contact],
    q: &[f64],
    qd: &[f64],
    u_dot: f64,
    slide: Option<f64>,
) -> Vec<(V2, f64)> {
    let k = geo.k;
    let w0 = world(geo, before, q, qd);
    let vel = |p: V2, j: usize| {
        let mut v = [u_dot, 0.0];
        for i in 0..=j {
            v[0] += qd[i] * (p[1] - w0.pivot[i][1]);
            v[1] += qd[i] * -(p[0] - w0.pivot[i][0]);
        }
        v
    };
    let w1 = world(geo, after, q, qd);
    let (a, b, _, _) = generic_system(geo, after, &w1, slide, |row| match row {
        Row::Newton(j, d) => geo.mass[j] * vel(w0.centre[j], j)[d],
        Row::Euler(j) => geo.inertia[j] * w0.omega[j],
        Row::Meet(..) | Row::Turn => 0.0,
    });
    let x = solve(a, b);
    (0..k).map(|j| ([x[3 * j], x[3 * j + 1]], x[3 * j + 2])).collect()
}

#[test]
fn every_impact_with_the_base_sliding_or_stopped_matches_a_generic_impulse_solve() {
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    each_impact(|geo, cs, after, q, qd| {
        for slide in [None, Some(0.4), Some(-0.3)] {
            let mut y = state(q, qd);
            let u_dot = -0.25;
            y[SLIDE_RATE] = u_dot;
            let before = Pose::new(geo, &contacts_of(cs), &y);
            let at = Pose::new(geo, &contacts_of(after), &y);
            let (rates, u) = impact_rates(geo, &contacts_of(after), slide, &before, &at);
            let generic = impulse_on_base(geo, cs, after, q, qd, u_dot, slide);
            let mut y_after = state(q, &rates[..geo.k]);
            y_after[SLIDE_RATE] = u;
            let pose = Pose::new(geo, &contacts_of(after), &y_after);
            for j in 0..geo.k {
                for d in 0..2 {
                    worst = worst.max((pose.centre_vel[j][d] - generic[j].0[d]).abs());
                }
                worst = worst.max((pose.omega[j] - generic[j].1).abs() * geo.r1);
            }
            checked += 1;
        }
    });
    assert!(checked > 300, "{checked}");
    assert!(worst < 1e-11, "largest difference {worst:e}");
}

#[test]
fn a_glued_stacks_painleve_ratio_is_the_single_blocks_denominator_over_its_frictionless_value() {
    // docs/model.md §4.2: a slide-rocking block's D = ¼(1 + 3 sn² − 3 s σ μ_k sn c),
    // sn and c of φ = α − |θ| (the diagonal's angle from the vertical),
    // s the pivot's side and σ the slip's sense; the stack's ratio is
    // D over its value without friction.
    let (b, h1, h2) = (0.5, 0.9, 0.7);
    let geo = glued_pair(b, h1, h2);
    let alpha = (b / (h1 + h2)).atan();
    let g_e = [0.1, -4.0 * geo.r1 / 3.0];
    let mut checked = 0;
    for theta in [0.02, 0.1, 0.25, -0.05, -0.2] {
        let contact = Contact::of_sign(theta);
        let contacts = contacts_of(&[contact, Contact::Closed]);
        let pose = Pose::new(&geo, &contacts, &state(&[theta, 0.0], &[0.3, 0.0]));
        for smu in [0.3, -0.3, 1.2, -1.25] {
            let d = accelerations(&geo, &contacts, Some(smu), &pose, g_e).painleve;
            let (sn, c) = (alpha - theta.abs()).sin_cos();
            let s = theta.signum();
            let want = (1.0 + 3.0 * sn * sn - 3.0 * s * smu * sn * c) / (1.0 + 3.0 * sn * sn);
            assert!((d - want).abs() < 1e-13, "θ {theta}, sμ {smu}: {d} vs {want}");
            checked += 1;
        }
    }
    assert_eq!(checked, 20);
}
