//! A stack's equations of motion, the loads its interfaces carry and the
//! impulse of an impact (docs/model.md §18.3–18.5).
//!
//! With the open interfaces' rotations q_f as coordinates, the partial
//! velocity of block j's centre is v_jf = J(c_j − P_f) (f ≤ j) and of its
//! rotation 1, so Lagrange's equations read M q'' = b with
//! M_fg = Σ_{j ≥ max(f, g)} (m_j v_jf·v_jg + I_j) and
//! b_f = −Σ_{j ≥ f} m_j v_jf·(κ_j − g_e), where κ_j = Σ_f q_f' J(c_j' − P_f')
//! is the part of c_j'' that does not depend on q'' and g_e the effective
//! gravity in the base frame, (−a_h, −(g + a_v)). Contact forces at stuck
//! pivots and closed faces do no work in these coordinates, so they do
//! not appear.
//!
//! While the base face slides (§18.7) its slip u is a coordinate too: its
//! row is the stack's horizontal momentum balance with the friction
//! −s μ_k N, and N is itself linear in the accelerations, so the system
//! is the symmetric mass matrix of (q_F, u) plus s μ_k times a rank-one
//! term, solved by Sherman–Morrison; its determinant ratio
//! D = 1 + s μ_k c·M⁻¹e_u is the Painlevé margin (D ≤ 0: no unique motion).

// Linear algebra over interfaces and blocks: indices name them.
#![allow(clippy::needless_range_loop)]

use super::pose::{Pose, V2, dot, quarter, sub};
use super::{Contact, MAX_BLOCKS, StackGeometry};

/// Accelerations of a stack at one state.
#[derive(Clone, Copy, Debug)]
pub struct StackAccel {
    /// Each interface's q_i'', rad per τ² (0 when closed or glued).
    pub q_ddot: [f64; MAX_BLOCKS],
    /// Each block's centre's acceleration, m per τ².
    pub centre_acc: [V2; MAX_BLOCKS],
    /// Each block's angular acceleration φ_j'', rad per τ².
    pub alpha: [f64; MAX_BLOCKS],
    /// The base face's slip acceleration u'', m per τ² (0 when stuck).
    pub slide_acc: f64,
    /// The Painlevé ratio D of the sliding system (1 when stuck).
    pub painleve: f64,
}

/// What the vector field needs: each interface's q_i'' and the slip's u''.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rates {
    /// Each interface's q_i'', rad per τ² (0 when closed or glued).
    pub q_ddot: [f64; MAX_BLOCKS],
    /// u'', m per τ² (0 when stuck).
    pub slide_acc: f64,
    /// The base's normal force while sliding, mass times m per τ² (0 when
    /// stuck: the field does not need it then).
    pub normal: f64,
}

/// What interface i carries, per weight of the blocks above it
/// (M_i G, G = g/p²): the resultant of the contact forces on the blocks
/// above, and its generalised force about each end of the overlap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterfaceLoad {
    /// Normal force, along the lower face's normal (> 0: pressing).
    pub normal: f64,
    /// Tangential force, along the lower face.
    pub tangential: f64,
    /// Λ_L/(M_i G), m: −N times the resultant's distance from the left
    /// corner. ≤ 0 while the resultant is right of the left corner.
    pub about_left: f64,
    /// Λ_R/(M_i G), m: N times the resultant's distance from the right
    /// corner. ≥ 0 while the resultant is left of the right corner.
    pub about_right: f64,
}

impl InterfaceLoad {
    /// How far a closed face is from opening on its right corner (≥ 0:
    /// the resultant is inside), per weight times m.
    pub(crate) fn right_margin(&self) -> f64 {
        self.about_right
    }

    /// How far a closed face is from opening on its left corner.
    pub(crate) fn left_margin(&self) -> f64 {
        -self.about_left
    }
}

/// Whether interface `i` is a coordinate in `contacts`.
#[inline]
pub(crate) fn is_open(geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS], i: usize) -> bool {
    contacts[i] != Contact::Closed && !geo.glued[i]
}

/// Solves the symmetric positive definite `a x = b` of size `n` in place
/// (Cholesky; n ≤ [`MAX_BLOCKS`]).
#[inline(always)]
fn solve_spd(a: &mut [[f64; MAX_BLOCKS]; MAX_BLOCKS], b: &mut [f64; MAX_BLOCKS], n: usize) {
    // One or two open faces (most of a two- or three-block stack's time):
    // the closed forms, which cost a tenth of the general loop.
    match n {
        1 => {
            b[0] /= a[0][0];
            return;
        }
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            let (b0, b1) = (b[0], b[1]);
            b[0] = (a[1][1] * b0 - a[0][1] * b1) / det;
            b[1] = (a[0][0] * b1 - a[1][0] * b0) / det;
            return;
        }
        _ => {}
    }
    cholesky(a, n);
    back_substitute(a, b, n);
}

/// Factors the symmetric positive definite leading `n` × `n` block of `a`
/// in place: its lower triangle becomes L, a = L Lᵀ.
#[inline(always)]
fn cholesky<const M: usize>(a: &mut [[f64; M]; M], n: usize) {
    for j in 0..n {
        let mut d = a[j][j];
        for k in 0..j {
            d -= a[j][k] * a[j][k];
        }
        let d = d.sqrt();
        a[j][j] = d;
        for i in j + 1..n {
            let mut s = a[i][j];
            for k in 0..j {
                s -= a[i][k] * a[j][k];
            }
            a[i][j] = s / d;
        }
    }
}

/// Solves L Lᵀ x = `b` in place with the factor [`cholesky`] left in `l`.
#[inline(always)]
fn back_substitute<const M: usize>(l: &[[f64; M]; M], b: &mut [f64; M], n: usize) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i][k] * b[k];
        }
        b[i] = s / l[i][i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k][i] * b[k];
        }
        b[i] = s / l[i][i];
    }
}

/// The open interfaces of `contacts`, bottom to top, and their count.
#[inline]
fn open_set(geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS]) -> ([usize; MAX_BLOCKS], usize) {
    let mut free = [0; MAX_BLOCKS];
    let mut n = 0;
    for i in 0..geo.blocks() {
        if is_open(geo, contacts, i) {
            free[n] = i;
            n += 1;
        }
    }
    (free, n)
}

/// The partial velocity v_jf = J(c_j − P_f) of block j's centre for the
/// open coordinate of interface `f` (j ≥ f). Recomputed where it is used
/// rather than tabulated: two subtractions cost less than filling and
/// copying a K × K table of vectors at every evaluation.
#[inline]
fn partial(pose: &Pose, f: usize, j: usize) -> V2 {
    quarter(sub(pose.centre[j], pose.pivot[f]))
}

/// The mass matrix of the open coordinates `free[..n]` (lower triangle
/// and diagonal filled, mirrored).
#[inline(always)]
fn mass_matrix(
    geo: &StackGeometry,
    pose: &Pose,
    free: &[usize; MAX_BLOCKS],
    n: usize,
) -> [[f64; MAX_BLOCKS]; MAX_BLOCKS] {
    let mut m = [[0.0; MAX_BLOCKS]; MAX_BLOCKS];
    for a in 0..n {
        for b in 0..=a {
            let lo = free[a].max(free[b]);
            let mut s = 0.0;
            for j in lo..geo.blocks() {
                s += geo.mass[j] * dot(partial(pose, free[a], j), partial(pose, free[b], j)) + geo.inertia[j];
            }
            m[a][b] = s;
            m[b][a] = s;
        }
    }
    m
}

/// κ_j: each block's centre's acceleration at q'' = 0.
#[inline(always)]
fn centripetal(geo: &StackGeometry, pose: &Pose) -> [V2; MAX_BLOCKS] {
    let mut kappa = [[0.0; 2]; MAX_BLOCKS];
    for (j, kj) in kappa.iter_mut().enumerate().take(geo.blocks()) {
        for i in 0..=j {
            let qd = pose.q_dot[i];
            if qd != 0.0 {
                let u = quarter(sub(pose.centre_vel[j], pose.pivot_vel[i]));
                kj[0] += qd * u[0];
                kj[1] += qd * u[1];
            }
        }
    }
    kappa
}

/// The open coordinates' accelerations, solved from M q'' = b, in the
/// open set's order (`free[..n]`), with κ.
#[inline(always)]
fn solve_open(
    geo: &StackGeometry,
    pose: &Pose,
    free: &[usize; MAX_BLOCKS],
    n: usize,
    kappa: &[V2; MAX_BLOCKS],
    g_e: V2,
) -> [f64; MAX_BLOCKS] {
    let mut m = mass_matrix(geo, pose, free, n);
    let mut b = [0.0; MAX_BLOCKS];
    for a in 0..n {
        let mut s = 0.0;
        for j in free[a]..geo.blocks() {
            s -= geo.mass[j] * dot(partial(pose, free[a], j), sub(kappa[j], g_e));
        }
        b[a] = s;
    }
    solve_spd(&mut m, &mut b, n);
    b
}

/// Rows of the sliding system: the open coordinates, then u.
const ROWS: usize = MAX_BLOCKS + 1;

/// The generalised mass matrix of (q_F, u) (symmetric positive definite)
/// and c, each open coordinate's weight in the base's normal force:
/// c_f = Σ_{j ≥ f} m_j v_jf,y.
#[inline(always)]
fn slide_matrix(
    geo: &StackGeometry,
    pose: &Pose,
    free: &[usize; MAX_BLOCKS],
    n: usize,
) -> ([[f64; ROWS]; ROWS], [f64; ROWS]) {
    let mm = mass_matrix(geo, pose, free, n);
    let mut a = [[0.0; ROWS]; ROWS];
    let mut c = [0.0; ROWS];
    for r in 0..n {
        a[r][..n].copy_from_slice(&mm[r][..n]);
        let (mut ax, mut cy) = (0.0, 0.0);
        for j in free[r]..geo.blocks() {
            let v = partial(pose, free[r], j);
            ax += geo.mass[j] * v[0];
            cy += geo.mass[j] * v[1];
        }
        a[r][n] = ax;
        a[n][r] = ax;
        c[r] = cy;
    }
    a[n][n] = geo.total_mass;
    (a, c)
}

/// Solves (A₀ + s μ e_u cᵀ) x = `rhs` (size n + 1, u last): A₀ by
/// Cholesky, the rank-one friction term by Sherman–Morrison. Returns x and
/// the Painlevé ratio D = det(A)/det(A₀) = 1 + s μ c·A₀⁻¹e_u.
#[inline(always)]
fn solve_sliding(
    mut a: [[f64; ROWS]; ROWS],
    c: &[f64; ROWS],
    mut rhs: [f64; ROWS],
    n: usize,
    smu: f64,
) -> ([f64; ROWS], f64) {
    let m = n + 1;
    cholesky(&mut a, m);
    let mut w = [0.0; ROWS];
    w[n] = 1.0;
    back_substitute(&a, &mut rhs, m);
    back_substitute(&a, &mut w, m);
    let (mut cx, mut cw) = (0.0, 0.0);
    for f in 0..n {
        cx += c[f] * rhs[f];
        cw += c[f] * w[f];
    }
    let d = 1.0 + smu * cw;
    let t = smu * cx / d;
    for i in 0..m {
        rhs[i] -= t * w[i];
    }
    (rhs, d)
}

/// The accelerations of the open set `free[..n]` and u while the base
/// face slides with s μ_k = `smu`: (q'' in the open set's order, u'', N,
/// D), N the base's normal force (mass times m per τ²).
#[inline(always)]
fn solve_slide(
    geo: &StackGeometry,
    pose: &Pose,
    free: &[usize; MAX_BLOCKS],
    n: usize,
    kappa: &[V2; MAX_BLOCKS],
    g_e: V2,
    smu: f64,
) -> ([f64; MAX_BLOCKS], f64, f64, f64) {
    let (a, c) = slide_matrix(geo, pose, free, n);
    let mut rhs = [0.0; ROWS];
    for f in 0..n {
        let mut s = 0.0;
        for j in free[f]..geo.blocks() {
            s -= geo.mass[j] * dot(partial(pose, free[f], j), sub(kappa[j], g_e));
        }
        rhs[f] = s;
    }
    // Horizontal momentum: Σ m_j (u'' + c_jx'') = Σ m_j g_ex − s μ_k N,
    // N = Σ m_j (c_jy'' − g_ey).
    let (mut hx, mut vy) = (0.0, 0.0);
    for j in 0..geo.blocks() {
        hx += geo.mass[j] * (g_e[0] - kappa[j][0]);
        vy += geo.mass[j] * (kappa[j][1] - g_e[1]);
    }
    rhs[n] = hx - smu * vy;
    let (x, d) = solve_sliding(a, &c, rhs, n, smu);
    let mut q = [0.0; MAX_BLOCKS];
    q[..n].copy_from_slice(&x[..n]);
    let mut normal = vy;
    for f in 0..n {
        normal += c[f] * x[f];
    }
    (q, x[n], normal, d)
}

/// Each interface's q_i'' (0 when closed or glued), rad per τ², and the
/// slip's u'': the part of [`accelerations`] that the vector field needs,
/// the same numbers bit for bit without the blocks' accelerations.
/// `friction` is s μ_k while the base face slides (s the sense of u').
pub(crate) fn rotation_rates(
    geo: &StackGeometry,
    contacts: &[Contact; MAX_BLOCKS],
    friction: Option<f64>,
    pose: &Pose,
    g_e: V2,
) -> Rates {
    let mut q_ddot = [0.0; MAX_BLOCKS];
    let (free, n) = open_set(geo, contacts);
    if let Some(smu) = friction {
        let kappa = centripetal(geo, pose);
        let (b, u, normal, _) = solve_slide(geo, pose, &free, n, &kappa, g_e, smu);
        for a in 0..n {
            q_ddot[free[a]] = b[a];
        }
        return Rates {
            q_ddot,
            slide_acc: u,
            normal,
        };
    }
    let stuck = Rates {
        q_ddot,
        slide_acc: 0.0,
        normal: 0.0,
    };
    if n == 0 {
        return stuck;
    }
    let kappa = centripetal(geo, pose);
    let b = solve_open(geo, pose, &free, n, &kappa, g_e);
    for a in 0..n {
        q_ddot[free[a]] = b[a];
    }
    Rates { q_ddot, ..stuck }
}

/// The accelerations of `pose` with contacts `contacts` under the
/// effective gravity `g_e` (m per τ², base frame), the base face sliding
/// with s μ_k = `friction` if it is `Some`.
pub fn accelerations(
    geo: &StackGeometry,
    contacts: &[Contact; MAX_BLOCKS],
    friction: Option<f64>,
    pose: &Pose,
    g_e: V2,
) -> StackAccel {
    let k = geo.k;
    let kappa = centripetal(geo, pose);
    let (free, n) = open_set(geo, contacts);
    let mut q_ddot = [0.0; MAX_BLOCKS];
    let mut centre_acc = kappa;
    let mut alpha = [0.0; MAX_BLOCKS];
    let (b, slide_acc, painleve) = match friction {
        Some(smu) => {
            let (b, u, _, d) = solve_slide(geo, pose, &free, n, &kappa, g_e, smu);
            (b, u, d)
        }
        None if n == 0 => {
            // Every face shut: the stack moves with the base.
            return StackAccel {
                q_ddot,
                centre_acc,
                alpha,
                slide_acc: 0.0,
                painleve: 1.0,
            };
        }
        None => (solve_open(geo, pose, &free, n, &kappa, g_e), 0.0, 1.0),
    };
    if friction.is_some() {
        for c in centre_acc.iter_mut().take(k) {
            c[0] += slide_acc;
        }
    }
    for a in 0..n {
        q_ddot[free[a]] = b[a];
        for j in free[a]..k {
            let v = partial(pose, free[a], j);
            centre_acc[j][0] += b[a] * v[0];
            centre_acc[j][1] += b[a] * v[1];
        }
    }
    let mut turn = 0.0;
    for j in 0..k {
        turn += q_ddot[j];
        alpha[j] = turn;
    }
    StackAccel {
        q_ddot,
        centre_acc,
        alpha,
        slide_acc,
        painleve,
    }
}

/// The load on interface `i` at `pose` with accelerations `acc`, per
/// weight of the blocks above at gravity `g_unit` (g/p², m per τ²).
pub(crate) fn interface_load(
    geo: &StackGeometry,
    pose: &Pose,
    acc: &StackAccel,
    g_e: V2,
    g_unit: f64,
    i: usize,
) -> InterfaceLoad {
    let (normal_dir, along, left, right) = if i == 0 {
        // The base face's corners slide with it.
        let at = |c: V2| [c[0] + pose.slide, c[1]];
        ([0.0, 1.0], [1.0, 0.0], at(geo.corners[0][0]), at(geo.corners[0][1]))
    } else {
        (
            pose.direction(i - 1, [0.0, 1.0]),
            pose.direction(i - 1, [1.0, 0.0]),
            pose.place(i - 1, geo.corners[i][0]),
            pose.place(i - 1, geo.corners[i][1]),
        )
    };
    let mut force = [0.0; 2];
    let (mut about_left, mut about_right) = (0.0, 0.0);
    for j in i..geo.blocks() {
        let f = [
            geo.mass[j] * (acc.centre_acc[j][0] - g_e[0]),
            geo.mass[j] * (acc.centre_acc[j][1] - g_e[1]),
        ];
        force[0] += f[0];
        force[1] += f[1];
        let spin = geo.inertia[j] * acc.alpha[j];
        about_left += dot(f, quarter(sub(pose.centre[j], left))) + spin;
        about_right += dot(f, quarter(sub(pose.centre[j], right))) + spin;
    }
    let weight = geo.mass_above(i) * g_unit;
    InterfaceLoad {
        normal: dot(force, normal_dir) / weight,
        tangential: dot(force, along) / weight,
        about_left: about_left / weight,
        about_right: about_right / weight,
    }
}

/// The interface rates and the slip rate just after an impact, in which
/// the contacts become `after` (the impacting interfaces' new pivots stick
/// and do not bounce, every other contact holds): the velocities in
/// `after`'s coordinates that keep the generalised momentum of each of
/// them, M(after) q'⁺ = Σ_j (m_j v_jf·c_j'⁻ + I_j φ_j'⁻) (docs/model.md
/// §18.5). `before` is the pose just before (its velocities), `at` the
/// same positions with `after`'s pivots. With `friction` = s μ_k the base
/// face goes on sliding through the impact, its friction impulse −s μ_k
/// times the base's normal impulse (§18.7); otherwise it sticks (u'⁺ = 0).
pub(crate) fn impact_rates(
    geo: &StackGeometry,
    after: &[Contact; MAX_BLOCKS],
    friction: Option<f64>,
    before: &Pose,
    at: &Pose,
) -> ([f64; MAX_BLOCKS], f64) {
    let (free, n) = open_set(geo, after);
    let momentum = |f: usize| {
        let mut s = 0.0;
        for j in free[f]..geo.k {
            s += geo.mass[j] * dot(partial(at, free[f], j), before.centre_vel[j]) + geo.inertia[j] * before.omega[j];
        }
        s
    };
    let mut q_dot = [0.0; MAX_BLOCKS];
    if let Some(smu) = friction {
        let (a, c) = slide_matrix(geo, at, &free, n);
        let mut rhs = [0.0; ROWS];
        for f in 0..n {
            rhs[f] = momentum(f);
        }
        // Σ m_j c_jx'⁺ − Σ m_j c_jx'⁻ = −s μ_k P_N, P_N = Σ m_j (c_jy'⁺ − c_jy'⁻).
        let (mut px, mut py) = (0.0, 0.0);
        for j in 0..geo.k {
            px += geo.mass[j] * before.centre_vel[j][0];
            py += geo.mass[j] * before.centre_vel[j][1];
        }
        rhs[n] = px + smu * py;
        let (x, _) = solve_sliding(a, &c, rhs, n, smu);
        for f in 0..n {
            q_dot[free[f]] = x[f];
        }
        return (q_dot, x[n]);
    }
    let mut m = mass_matrix(geo, at, &free, n);
    let mut b = [0.0; MAX_BLOCKS];
    for (f, bf) in b.iter_mut().enumerate().take(n) {
        *bf = momentum(f);
    }
    solve_spd(&mut m, &mut b, n);
    for a in 0..n {
        q_dot[free[a]] = b[a];
    }
    (q_dot, 0.0)
}

/// Kinetic energy of `pose`, m² per τ² times mass.
pub fn kinetic(geo: &StackGeometry, pose: &Pose) -> f64 {
    (0..geo.k)
        .map(|j| {
            0.5 * (geo.mass[j] * dot(pose.centre_vel[j], pose.centre_vel[j])
                + geo.inertia[j] * pose.omega[j] * pose.omega[j])
        })
        .sum()
}

/// Potential energy of `pose` at gravity `g_unit`, relative to rest.
pub(crate) fn potential(geo: &StackGeometry, pose: &Pose, g_unit: f64) -> f64 {
    (0..geo.k)
        .map(|j| geo.mass[j] * g_unit * (pose.centre[j][1] - geo.centre[j][1]))
        .sum()
}
