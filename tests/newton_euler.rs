//! The closed-form mode equations (`model::dynamics`) and impact maps
//! (`model::impact`) against an independent, generic Newton–Euler solve.
//!
//! # The independent method
//!
//! Nothing here reuses the crate's formulas. Each check builds the block as a
//! planar rigid body in **dimensional** units, with its own random mass `m`,
//! gravity `g` and size `B × H`:
//!
//! - `I_G = m(B² + H²)/12` (rectangular lamina), `R = ½√(B² + H²)`,
//!   `I_O = I_G + mR²` (parallel axes), `p² = m g R / I_O` (the frequency
//!   that defines τ = p t), `ψ = atan(B/H)`.
//! - A tilted block: the vector from the contact corner to G is the
//!   body-frame vector `(−s B/2, H/2)` rotated counter-clockwise by `−θ`
//!   (θ > 0 is clockwise), `θ = ψΘ`, `ω = −θ̇ = −pψΘ'` (counter-clockwise).
//! - Unknowns `[ẍ_G, ÿ_G, α, F, N]` of a linear system solved by LU
//!   (nalgebra): `m ẍ_G = F − m a_h`, `m ÿ_G = N − m(g + a_v)`,
//!   `I_G α = (r × (F, N))_z` with `r` = corner − G, and the contact
//!   conditions on the corner acceleration `a_c = a_G + α ẑ × r − ω² r`:
//!   rock `a_c = 0`; slide-rock `a_c,y = 0` and `F + σ μ_k N = 0`. A flat
//!   block (slide, rest) has unknowns `[ẍ_G, ÿ_G, F, N]`.
//! - Impacts at Θ = 0: unknowns `[Δv_x, Δv_y, Δω, P_x, P_y]` with
//!   `m Δv_G = P`, `I_G Δω = (r × P)_z`, and the corner velocity
//!   `v_c = v_G + ω ẑ × r` after the impact: sticking `v_c = (0, −e v_c,y⁻)`;
//!   slipping `v_c,y = −e v_c,y⁻` and `P_x + σ μ_k P_y = 0`, σ the sign of
//!   the corner's horizontal velocity after.
//!
//! Results are then normalised (`Θ'' = θ̈/(p²ψ)`, `X'' = ẍ_G/(Rp²)`,
//! `n = N/(mg)`, `f = F/(mg)`, velocities by `Rp`, `w = θ̇/p`, impulses by
//! `mRp`) and compared with the crate at thousands of random states from a
//! fixed-seed SplitMix64, to `|a − b| <= 1e-12 · max(1, |a|, |b|)`. Each test
//! prints the largest relative discrepancy per quantity (`--nocapture`).
//!
//! Mirror symmetry (Θ, Θ', X', a_h → negated, pivot/slip/striking side
//! flipped) is checked **exactly** (`==`), as the crate promises.
//!
//! Two properties of the impulse law that these tests pin down rather than
//! hide: with μ_s = ∞ it always sticks, even where the sticking impulse is
//! tensile (P_y < 0, a large pre-impact slip towards the old pivot), while a
//! finite μ_s slips there; and with e > 0 *and* pre-impact slip its kinematic
//! restitution can gain kinetic energy (see
//! [`impacts_never_create_kinetic_energy`]).

use std::fmt::Debug;

use nalgebra::{Matrix4, Matrix5, Vector4, Vector5};
use rocking::model::Geometry;
use rocking::model::Sign;
use rocking::model::dynamics::{self, Accel, Forcing};
use rocking::model::impact::{self, PostImpact, PreImpact};

/// Random states per test.
const N_STATES: usize = 5000;
/// Relative tolerance of every closed form against the generic solve.
const TOL: f64 = 1e-12;
/// Relative margin within which a stick/slip branch decision is too close to
/// call (both branches are then accepted); such cases are counted.
const BRANCH_TOL: f64 = 1e-9;

// ---------------------------------------------------------------------------
// Deterministic random numbers
// ---------------------------------------------------------------------------

/// SplitMix64 (Steele, Lea & Flood 2014).
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    fn sign(&mut self) -> Sign {
        if self.next_u64() & 1 == 0 { Sign::Neg } else { Sign::Pos }
    }
}

// ---------------------------------------------------------------------------
// Comparison bookkeeping
// ---------------------------------------------------------------------------

/// |a − b| / max(1, |a|, |b|).
fn rel_diff(a: f64, b: f64) -> f64 {
    (a - b).abs() / 1f64.max(a.abs()).max(b.abs())
}

/// Largest relative discrepancy of each quantity of one test; fails at the
/// first one over [`TOL`].
struct Discrepancies {
    test: &'static str,
    worst: Vec<(&'static str, f64)>,
}

impl Discrepancies {
    fn new(test: &'static str) -> Self {
        Self {
            test,
            worst: Vec::new(),
        }
    }

    fn check(&mut self, what: &'static str, got: f64, want: f64, at: &dyn Debug) {
        let rel = rel_diff(got, want);
        assert!(
            rel <= TOL,
            "{}: {what}: crate {got:e} vs generic {want:e} (rel {rel:e}) at {at:?}",
            self.test
        );
        match self.worst.iter_mut().find(|(w, _)| *w == what) {
            Some(entry) => entry.1 = entry.1.max(rel),
            None => self.worst.push((what, rel)),
        }
    }

    fn accel(&mut self, got: &Accel, want: &Accel, at: &dyn Debug) {
        self.check("theta_ddot", got.theta_ddot, want.theta_ddot, at);
        self.check("x_ddot", got.x_ddot, want.x_ddot, at);
        self.check("normal", got.normal, want.normal, at);
        self.check("friction", got.friction, want.friction, at);
    }

    fn post(&mut self, got: &PostImpact, want: &GenericImpact, at: &dyn Debug) {
        self.check("w", got.w, want.w, at);
        self.check("x_dot", got.x_dot, want.x_dot, at);
        self.check("y_dot", got.y_dot, want.y_dot, at);
        self.check("impulse_x", got.impulse.0, want.px, at);
        self.check("impulse_y", got.impulse.1, want.py, at);
    }

    fn report(&self) {
        for (what, rel) in &self.worst {
            println!("{}: {what}: max rel discrepancy {rel:.3e}", self.test);
        }
    }
}

/// Collects exact-symmetry violations, reported all at once.
struct Mirror {
    test: &'static str,
    failures: Vec<String>,
    checked: usize,
}

impl Mirror {
    fn new(test: &'static str) -> Self {
        Self {
            test,
            failures: Vec::new(),
            checked: 0,
        }
    }

    /// `mirrored` must equal `expected` exactly.
    fn exact(&mut self, what: &str, mirrored: f64, expected: f64, at: &dyn Debug) {
        self.checked += 1;
        if mirrored != expected && self.failures.len() < 20 {
            self.failures.push(format!(
                "{what}: mirrored {mirrored:e} != expected {expected:e} at {at:?}"
            ));
        }
    }

    fn accel(&mut self, what: &str, orig: &Accel, mirrored: &Accel, at: &dyn Debug) {
        self.exact(&format!("{what}.theta_ddot"), mirrored.theta_ddot, -orig.theta_ddot, at);
        self.exact(&format!("{what}.x_ddot"), mirrored.x_ddot, -orig.x_ddot, at);
        self.exact(&format!("{what}.normal"), mirrored.normal, orig.normal, at);
        self.exact(&format!("{what}.friction"), mirrored.friction, -orig.friction, at);
    }

    fn post(&mut self, what: &str, orig: &PostImpact, mirrored: &PostImpact, at: &dyn Debug) {
        self.exact(&format!("{what}.w"), mirrored.w, -orig.w, at);
        self.exact(&format!("{what}.x_dot"), mirrored.x_dot, -orig.x_dot, at);
        self.exact(&format!("{what}.y_dot"), mirrored.y_dot, orig.y_dot, at);
        self.exact(&format!("{what}.impulse_x"), mirrored.impulse.0, -orig.impulse.0, at);
        self.exact(&format!("{what}.impulse_y"), mirrored.impulse.1, orig.impulse.1, at);
        self.checked += 2;
        if (mirrored.slip != orig.slip.map(Sign::flip) || mirrored.lifts_off != orig.lifts_off)
            && self.failures.len() < 20
        {
            self.failures.push(format!(
                "{what}: slip/lifts_off {:?}/{} vs original {:?}/{} at {at:?}",
                mirrored.slip, mirrored.lifts_off, orig.slip, orig.lifts_off
            ));
        }
    }

    fn finish(&self) {
        println!("{}: {} exact mirror comparisons", self.test, self.checked);
        assert!(
            self.failures.is_empty(),
            "{}: mirror symmetry broken:\n{}",
            self.test,
            self.failures.join("\n")
        );
    }
}

// ---------------------------------------------------------------------------
// The block as a dimensional rigid body
// ---------------------------------------------------------------------------

/// A `width` × `height` block of mass `m` under gravity `g`, with every
/// derived quantity computed from first principles.
#[derive(Clone, Copy, Debug)]
struct Block {
    width: f64,
    height: f64,
    m: f64,
    g: f64,
    /// Half-diagonal R.
    half_diag: f64,
    /// ψ = atan(B/H).
    psi: f64,
    /// Moment of inertia about G.
    i_g: f64,
    /// p = √(m g R / I_O).
    p: f64,
}

impl Block {
    fn new(width: f64, height: f64, m: f64, g: f64) -> Self {
        let i_g = m * (width * width + height * height) / 12.0;
        let half_diag = 0.5 * (width * width + height * height).sqrt();
        let i_o = i_g + m * half_diag * half_diag;
        Self {
            width,
            height,
            m,
            g,
            half_diag,
            psi: (width / height).atan(),
            i_g,
            p: (m * g * half_diag / i_o).sqrt(),
        }
    }

    fn random(rng: &mut Rng) -> Self {
        let height = rng.uniform(0.2, 3.0);
        let width = height * rng.uniform(0.05, 1.0);
        Self::new(width, height, rng.uniform(0.1, 10.0), rng.uniform(1.0, 20.0))
    }

    fn geometry(&self) -> Geometry {
        Geometry::new(self.width, self.height)
    }

    /// sin ψ from the sides.
    fn sin_psi(&self) -> f64 {
        self.width / (self.width * self.width + self.height * self.height).sqrt()
    }

    /// G − corner for a block tilted by Θ about corner `s`: the body-frame
    /// vector (−s B/2, H/2) rotated counter-clockwise by −θ.
    fn g_from_corner(&self, s: Sign, theta: f64) -> [f64; 2] {
        let body = [-s.value() * 0.5 * self.width, 0.5 * self.height];
        rotate(body, -self.psi * theta)
    }

    /// Striking corner − G of the flat block (corner on side `s`).
    fn flat_corner(&self, s: Sign) -> [f64; 2] {
        [s.value() * 0.5 * self.width, -0.5 * self.height]
    }

    /// Counter-clockwise angular velocity of normalised rate Θ'.
    fn omega(&self, theta_dot: f64) -> f64 {
        -self.p * self.psi * theta_dot
    }

    /// Normalises a dimensional solution `[ẍ_G, ÿ_G, α, F, N]`.
    fn normalise(&self, sol: [f64; 5]) -> Accel {
        let [xdd, _ydd, alpha, f, n] = sol;
        let p2 = self.p * self.p;
        Accel {
            theta_ddot: -alpha / (p2 * self.psi),
            x_ddot: xdd / (self.half_diag * p2),
            normal: n / (self.m * self.g),
            friction: f / (self.m * self.g),
        }
    }
}

/// Rotates `v` counter-clockwise by `angle`.
fn rotate(v: [f64; 2], angle: f64) -> [f64; 2] {
    let (sn, c) = angle.sin_cos();
    [c * v[0] - sn * v[1], sn * v[0] + c * v[1]]
}

/// z-component of a × b.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// ω ẑ × r.
fn omega_cross(omega: f64, r: [f64; 2]) -> [f64; 2] {
    [-omega * r[1], omega * r[0]]
}

// ---------------------------------------------------------------------------
// Generic Newton–Euler solves
// ---------------------------------------------------------------------------

/// Contact condition of a tilted block's corner.
#[derive(Clone, Copy, Debug)]
enum Contact {
    /// The corner's acceleration is zero both ways.
    Stuck,
    /// The corner stays on the ground and slips in direction `sigma` with
    /// F = −σ μ_k N.
    Slipping { sigma: f64, mu_k: f64 },
}

/// Solves the Newton–Euler equations of a block touching the ground at one
/// corner, `r` = corner − G, for `[ẍ_G, ÿ_G, α, F, N]`.
fn solve_tilted(blk: &Block, r: [f64; 2], omega: f64, fo: Forcing, contact: Contact) -> [f64; 5] {
    let (m, i_g) = (blk.m, blk.i_g);
    let (a_h, a_v) = (fo.a * blk.g, fo.av * blk.g);
    let w2 = omega * omega;
    // Rows: m ẍ − F = −m a_h; m ÿ − N = −m(g + a_v); I_G α − (r_x N − r_y F) = 0.
    let mut mat = Matrix5::new(
        m, 0.0, 0.0, -1.0, 0.0, //
        0.0, m, 0.0, 0.0, -1.0, //
        0.0, 0.0, i_g, r[1], -r[0], //
        0.0, 0.0, 0.0, 0.0, 0.0, //
        0.0, 0.0, 0.0, 0.0, 0.0,
    );
    let mut rhs = Vector5::new(-m * a_h, -m * (blk.g + a_v), 0.0, 0.0, 0.0);
    // a_c,y = ÿ + α r_x − ω² r_y = 0 in both modes.
    mat.set_row(3, &nalgebra::RowVector5::new(0.0, 1.0, r[0], 0.0, 0.0));
    rhs[3] = w2 * r[1];
    match contact {
        Contact::Stuck => {
            // a_c,x = ẍ − α r_y − ω² r_x = 0.
            mat.set_row(4, &nalgebra::RowVector5::new(1.0, 0.0, -r[1], 0.0, 0.0));
            rhs[4] = w2 * r[0];
        }
        Contact::Slipping { sigma, mu_k } => {
            mat.set_row(4, &nalgebra::RowVector5::new(0.0, 0.0, 0.0, 1.0, sigma * mu_k));
            rhs[4] = 0.0;
        }
    }
    let z = mat.lu().solve(&rhs).expect("tilted Newton–Euler system is regular");
    [z[0], z[1], z[2], z[3], z[4]]
}

/// Solves the flat block (no rotation): sliding in direction `slip` with
/// kinetic friction `mu_k`, or stuck to the base (`slip = None`). Unknowns
/// `[ẍ_G, ÿ_G, F, N]`, returned as `[ẍ_G, ÿ_G, α = 0, F, N]`.
fn solve_flat(blk: &Block, fo: Forcing, slip: Option<(f64, f64)>) -> [f64; 5] {
    let m = blk.m;
    let (a_h, a_v) = (fo.a * blk.g, fo.av * blk.g);
    let last = match slip {
        Some((sigma, mu_k)) => [0.0, 0.0, 1.0, sigma * mu_k],
        None => [1.0, 0.0, 0.0, 0.0],
    };
    let mat = Matrix4::new(
        m, 0.0, -1.0, 0.0, //
        0.0, m, 0.0, -1.0, //
        0.0, 1.0, 0.0, 0.0, //
        last[0], last[1], last[2], last[3],
    );
    let rhs = Vector4::new(-m * a_h, -m * (blk.g + a_v), 0.0, 0.0);
    let z = mat.lu().solve(&rhs).expect("flat system is regular");
    [z[0], z[1], 0.0, z[2], z[3]]
}

/// A random tilted state.
#[derive(Clone, Copy, Debug)]
struct Tilted {
    blk: Block,
    pivot: Sign,
    slip: Sign,
    mu_k: f64,
    theta: f64,
    theta_dot: f64,
    fo: Forcing,
}

impl Tilted {
    fn random(rng: &mut Rng) -> Self {
        let blk = Block::random(rng);
        let pivot = rng.sign();
        let slip = rng.sign();
        // sΘ in (0, 1) mostly; one in ten slightly past Θ = 0.
        let u = if rng.unit() < 0.1 {
            rng.uniform(-0.05, 0.0)
        } else {
            rng.uniform(1e-9, 1.0)
        };
        Self {
            blk,
            pivot,
            slip,
            mu_k: rng.uniform(0.0, 1.0),
            theta: pivot.value() * u,
            theta_dot: rng.uniform(-3.0, 3.0),
            fo: Forcing {
                a: rng.uniform(-1.0, 1.0),
                av: rng.uniform(-0.8, 0.8),
            },
        }
    }

    /// Contact corner − G.
    fn r(&self) -> [f64; 2] {
        let g = self.blk.g_from_corner(self.pivot, self.theta);
        [-g[0], -g[1]]
    }

    fn omega(&self) -> f64 {
        self.blk.omega(self.theta_dot)
    }

    fn generic(&self, contact: Contact) -> Accel {
        self.blk
            .normalise(solve_tilted(&self.blk, self.r(), self.omega(), self.fo, contact))
    }

    fn slipping(&self) -> Contact {
        Contact::Slipping {
            sigma: self.slip.value(),
            mu_k: self.mu_k,
        }
    }

    /// Horizontal acceleration of the contact corner / (R p²) from a
    /// normalised acceleration: a_c = a_G + α ẑ × r − ω² r.
    fn corner_accel_x(&self, acc: &Accel) -> f64 {
        let blk = &self.blk;
        let p2 = blk.p * blk.p;
        let r = self.r();
        let alpha = -acc.theta_ddot * p2 * blk.psi;
        let omega = self.omega();
        let a_gx = acc.x_ddot * blk.half_diag * p2;
        let a_cx = a_gx + omega_cross(alpha, r)[0] - omega * omega * r[0];
        a_cx / (blk.half_diag * p2)
    }

    /// The mirror image: Θ, Θ', a_h negated, pivot and slip flipped.
    fn mirrored(&self) -> Self {
        Self {
            pivot: self.pivot.flip(),
            slip: self.slip.flip(),
            theta: -self.theta,
            theta_dot: -self.theta_dot,
            fo: Forcing {
                a: -self.fo.a,
                av: self.fo.av,
            },
            ..*self
        }
    }
}

// ---------------------------------------------------------------------------
// Generic impact solve
// ---------------------------------------------------------------------------

/// Condition at the striking corner during an impact.
#[derive(Clone, Copy, Debug)]
enum ImpactCond {
    /// Corner velocity after = (0, −e v_c,y before).
    Stick { e: f64 },
    /// Vertical corner velocity after = −e v_c,y before, P_x = −σ μ_k P_y.
    Slip { e: f64, sigma: f64, mu_k: f64 },
}

/// Normalised result of the generic impact solve.
#[derive(Clone, Copy, Debug)]
struct GenericImpact {
    w: f64,
    x_dot: f64,
    y_dot: f64,
    px: f64,
    py: f64,
    /// Horizontal velocity of the striking corner after / (R p).
    vcx_after: f64,
}

/// Dimensional velocities (v_G, ω) of normalised pre-impact velocities.
fn dimensional(blk: &Block, w: f64, x_dot: f64, y_dot: f64) -> ([f64; 2], f64) {
    let rp = blk.half_diag * blk.p;
    ([x_dot * rp, y_dot * rp], -blk.p * w)
}

/// Velocity of the point at `r` from G.
fn point_velocity(v_g: [f64; 2], omega: f64, r: [f64; 2]) -> [f64; 2] {
    let oc = omega_cross(omega, r);
    [v_g[0] + oc[0], v_g[1] + oc[1]]
}

/// Solves the impulse–momentum equations for `[Δv_x, Δv_y, Δω, P_x, P_y]`.
fn solve_impact(blk: &Block, pre: &PreImpact, cond: ImpactCond) -> GenericImpact {
    let (m, i_g) = (blk.m, blk.i_g);
    let r = blk.flat_corner(pre.striking);
    let (v_g, omega) = dimensional(blk, pre.w, pre.x_dot, pre.y_dot);
    let v_c = point_velocity(v_g, omega, r);
    // Rows: m Δv − P = 0 (2); I_G Δω − (r_x P_y − r_y P_x) = 0;
    // Δv_c,y = Δv_y + r_x Δω = −(1 + e) v_c,y.
    let mut mat = Matrix5::new(
        m, 0.0, 0.0, -1.0, 0.0, //
        0.0, m, 0.0, 0.0, -1.0, //
        0.0, 0.0, i_g, r[1], -r[0], //
        0.0, 1.0, r[0], 0.0, 0.0, //
        0.0, 0.0, 0.0, 0.0, 0.0,
    );
    let e = match cond {
        ImpactCond::Stick { e } | ImpactCond::Slip { e, .. } => e,
    };
    let mut rhs = Vector5::new(0.0, 0.0, 0.0, -(1.0 + e) * v_c[1], 0.0);
    match cond {
        ImpactCond::Stick { .. } => {
            // Δv_c,x = Δv_x − r_y Δω = −v_c,x.
            mat.set_row(4, &nalgebra::RowVector5::new(1.0, 0.0, -r[1], 0.0, 0.0));
            rhs[4] = -v_c[0];
        }
        ImpactCond::Slip { sigma, mu_k, .. } => {
            mat.set_row(4, &nalgebra::RowVector5::new(0.0, 0.0, 0.0, 1.0, sigma * mu_k));
        }
    }
    let z = mat.lu().solve(&rhs).expect("impact system is regular");
    let v_after = [v_g[0] + z[0], v_g[1] + z[1]];
    let omega_after = omega + z[2];
    let v_c_after = point_velocity(v_after, omega_after, r);
    let rp = blk.half_diag * blk.p;
    let mrp = blk.m * rp;
    GenericImpact {
        w: -omega_after / blk.p,
        x_dot: v_after[0] / rp,
        y_dot: v_after[1] / rp,
        px: z[3] / mrp,
        py: z[4] / mrp,
        vcx_after: v_c_after[0] / rp,
    }
}

/// Kinetic energy / (m R² p²) of normalised velocities, from ½ m v² + ½ I_G ω².
fn kinetic(blk: &Block, w: f64, x_dot: f64, y_dot: f64) -> f64 {
    let (v, omega) = dimensional(blk, w, x_dot, y_dot);
    let t = 0.5 * blk.m * (v[0] * v[0] + v[1] * v[1]) + 0.5 * blk.i_g * omega * omega;
    t / (blk.m * blk.half_diag * blk.half_diag * blk.p * blk.p)
}

/// Angular momentum about the striking corner / (m R² p):
/// H_c = I_G ω + (r_G − r_c) × m v_G.
fn momentum_about_corner(blk: &Block, striking: Sign, w: f64, x_dot: f64, y_dot: f64) -> f64 {
    let (v, omega) = dimensional(blk, w, x_dot, y_dot);
    let r = blk.flat_corner(striking);
    let h = blk.i_g * omega + blk.m * cross([-r[0], -r[1]], v);
    h / (blk.m * blk.half_diag * blk.half_diag * blk.p)
}

/// A random pre-impact state at Θ = 0 with the striking corner approaching
/// the base (v_c,y < 0); one in three has no pre-impact slip (v_c,x = 0).
#[derive(Clone, Copy, Debug)]
struct ImpactCase {
    blk: Block,
    pre: PreImpact,
    e: f64,
    mu_s: f64,
    mu_k: f64,
}

impl ImpactCase {
    /// Random block and impact coefficients; velocities zero.
    fn params(rng: &mut Rng) -> Self {
        let blk = Block::random(rng);
        let striking = rng.sign();
        let e = if rng.unit() < 0.2 { 0.0 } else { rng.unit() };
        let mu_s = if rng.unit() < 0.2 {
            f64::INFINITY
        } else {
            rng.uniform(0.0, 1.0)
        };
        let mu_k = if mu_s.is_finite() {
            mu_s * rng.unit()
        } else {
            rng.uniform(0.0, 1.0)
        };
        Self {
            blk,
            pre: PreImpact {
                striking,
                w: 0.0,
                x_dot: 0.0,
                y_dot: 0.0,
            },
            e,
            mu_s,
            mu_k,
        }
    }

    /// Half the cases: arbitrary w and striking-corner velocity
    /// (v_c,y < 0, v_c,x = 0 one time in three); the other half: the states
    /// the simulator produces, rocking or slide-rocking about the old pivot
    /// towards Θ = 0 ([`ImpactCase::random_slide_rocking`]).
    fn random(rng: &mut Rng) -> Self {
        if rng.unit() < 0.5 {
            return Self::random_slide_rocking(rng);
        }
        let mut case = Self::params(rng);
        let blk = case.blk;
        let striking = case.pre.striking;
        let w = blk.psi * rng.uniform(-3.0, 3.0);
        let scale = w.abs().max(0.05);
        let vcx = if rng.unit() < 1.0 / 3.0 {
            0.0
        } else {
            scale * rng.uniform(-1.5, 1.5)
        };
        let vcy = -scale * rng.uniform(0.01, 1.5);
        // v_G = v_c − ω ẑ × r (normalised: ω/p = −w, r/R).
        let r = blk.flat_corner(striking);
        let oc = omega_cross(-w, [r[0] / blk.half_diag, r[1] / blk.half_diag]);
        case.pre = PreImpact {
            striking,
            w,
            x_dot: vcx - oc[0],
            y_dot: vcy - oc[1],
        };
        case
    }

    /// A block rocking without slip about the old pivot s = −s' towards
    /// Θ = 0, from the rigid-body velocity field about that corner.
    fn random_rocking(rng: &mut Rng) -> Self {
        let mut case = Self::params(rng);
        let blk = case.blk;
        let sp = case.pre.striking;
        let old = sp.flip();
        // Θ has the sign of the old pivot, so moving towards 0: w has sign s'.
        let w = sp.value() * blk.psi * rng.uniform(0.01, 3.0);
        // v_G = ω ẑ × (G − old corner), flat.
        let g = blk.g_from_corner(old, 0.0);
        let v = omega_cross(-w, [g[0] / blk.half_diag, g[1] / blk.half_diag]);
        case.pre = PreImpact {
            striking: sp,
            w,
            x_dot: v[0],
            y_dot: v[1],
        };
        case
    }

    /// [`ImpactCase::random_rocking`] plus a slip velocity of the old pivot
    /// (|slip| <= 3|w|, zero one time in four): slide-rock reaching Θ = 0.
    fn random_slide_rocking(rng: &mut Rng) -> Self {
        let mut case = Self::random_rocking(rng);
        if rng.unit() >= 0.25 {
            case.pre.x_dot += case.pre.w.abs() * rng.uniform(-3.0, 3.0);
        }
        case
    }

    fn mirrored_pre(&self) -> PreImpact {
        PreImpact {
            striking: self.pre.striking.flip(),
            w: -self.pre.w,
            x_dot: -self.pre.x_dot,
            y_dot: self.pre.y_dot,
        }
    }
}

// ---------------------------------------------------------------------------
// Tests: modes
// ---------------------------------------------------------------------------

#[test]
fn rock_matches_newton_euler() {
    let mut rng = Rng::new(0x5EED_0001);
    let mut d = Discrepancies::new("rock");
    for _ in 0..N_STATES {
        let st = Tilted::random(&mut rng);
        let geo = st.blk.geometry();
        let got = dynamics::rock(&geo, st.pivot, st.theta, st.theta_dot, st.fo);
        d.accel(&got, &st.generic(Contact::Stuck), &st);
        // The stuck corner does not accelerate: crate's slip acceleration is 0.
        d.check(
            "pivot_slip_accel(rock)",
            dynamics::pivot_slip_accel(&geo, st.pivot, st.theta, st.theta_dot, &got),
            0.0,
            &st,
        );
    }
    d.report();
}

#[test]
fn slide_rock_matches_newton_euler() {
    let mut rng = Rng::new(0x5EED_0002);
    let mut d = Discrepancies::new("slide_rock");
    for _ in 0..N_STATES {
        let st = Tilted::random(&mut rng);
        let geo = st.blk.geometry();
        let got = dynamics::slide_rock(&geo, st.pivot, st.slip, st.mu_k, st.theta, st.theta_dot, st.fo);
        let want = st.generic(st.slipping());
        d.accel(&got, &want, &st);
        // The corner's slip acceleration, crate vs vector kinematics of the
        // generic solution.
        d.check(
            "pivot_slip_accel(slide_rock)",
            dynamics::pivot_slip_accel(&geo, st.pivot, st.theta, st.theta_dot, &got),
            st.corner_accel_x(&want),
            &st,
        );
    }
    d.report();
}

#[test]
fn slide_and_rest_match_newton_euler() {
    let mut rng = Rng::new(0x5EED_0003);
    let mut d_slide = Discrepancies::new("slide");
    let mut d_rest = Discrepancies::new("rest");
    for _ in 0..N_STATES {
        let st = Tilted::random(&mut rng);
        let got = dynamics::slide(st.slip, st.mu_k, st.fo);
        let want = st
            .blk
            .normalise(solve_flat(&st.blk, st.fo, Some((st.slip.value(), st.mu_k))));
        d_slide.accel(&got, &want, &st);
        let got = dynamics::rest(st.fo);
        let want = st.blk.normalise(solve_flat(&st.blk, st.fo, None));
        d_rest.accel(&got, &want, &st);
    }
    d_slide.report();
    d_rest.report();
}

#[test]
fn pivot_slip_kinematics_match_vectors() {
    let mut rng = Rng::new(0x5EED_0004);
    let mut d = Discrepancies::new("pivot_slip");
    for _ in 0..N_STATES {
        let st = Tilted::random(&mut rng);
        let geo = st.blk.geometry();
        let blk = &st.blk;
        let x_dot = rng.uniform(-3.0, 3.0);
        // v_c = v_G + ω ẑ × r; only the horizontal part is the slip.
        let rp = blk.half_diag * blk.p;
        let v_c = point_velocity([x_dot * rp, 0.0], st.omega(), st.r());
        d.check(
            "velocity",
            dynamics::pivot_slip_velocity(&geo, st.pivot, st.theta, st.theta_dot, x_dot),
            v_c[0] / rp,
            &(st, x_dot),
        );
        // Arbitrary (not necessarily consistent) accelerations.
        let acc = Accel {
            theta_ddot: rng.uniform(-30.0, 30.0),
            x_ddot: rng.uniform(-5.0, 5.0),
            normal: rng.uniform(0.0, 2.0),
            friction: rng.uniform(-1.0, 1.0),
        };
        d.check(
            "accel",
            dynamics::pivot_slip_accel(&geo, st.pivot, st.theta, st.theta_dot, &acc),
            st.corner_accel_x(&acc),
            &(st, acc),
        );
    }
    d.report();
}

#[test]
fn restoring_matches_rock_at_rest() {
    let mut rng = Rng::new(0x5EED_0005);
    let mut d = Discrepancies::new("restoring");
    for _ in 0..N_STATES {
        let st = Tilted {
            theta: 0.0,
            theta_dot: 0.0,
            ..Tilted::random(&mut rng)
        };
        let want = -st.pivot.value() * st.blk.psi * st.generic(Contact::Stuck).theta_ddot;
        d.check(
            "kappa",
            dynamics::restoring(&st.blk.geometry(), st.pivot, st.fo),
            want,
            &st,
        );
    }
    d.report();
}

#[test]
fn modes_are_exactly_mirror_symmetric() {
    let mut rng = Rng::new(0x5EED_0006);
    let mut mir = Mirror::new("mode mirror");
    for _ in 0..N_STATES {
        let st = Tilted::random(&mut rng);
        let mr = st.mirrored();
        let geo = st.blk.geometry();
        let x_dot = rng.uniform(-3.0, 3.0);

        let a = dynamics::rock(&geo, st.pivot, st.theta, st.theta_dot, st.fo);
        let b = dynamics::rock(&geo, mr.pivot, mr.theta, mr.theta_dot, mr.fo);
        mir.accel("rock", &a, &b, &st);

        let a = dynamics::slide_rock(&geo, st.pivot, st.slip, st.mu_k, st.theta, st.theta_dot, st.fo);
        let b = dynamics::slide_rock(&geo, mr.pivot, mr.slip, mr.mu_k, mr.theta, mr.theta_dot, mr.fo);
        mir.accel("slide_rock", &a, &b, &st);
        let pa = dynamics::pivot_slip_accel(&geo, st.pivot, st.theta, st.theta_dot, &a);
        let pb = dynamics::pivot_slip_accel(&geo, mr.pivot, mr.theta, mr.theta_dot, &b);
        mir.exact("pivot_slip_accel", pb, -pa, &st);

        let a = dynamics::slide(st.slip, st.mu_k, st.fo);
        let b = dynamics::slide(mr.slip, mr.mu_k, mr.fo);
        mir.accel("slide", &a, &b, &st);

        let a = dynamics::rest(st.fo);
        let b = dynamics::rest(mr.fo);
        mir.accel("rest", &a, &b, &st);

        let va = dynamics::pivot_slip_velocity(&geo, st.pivot, st.theta, st.theta_dot, x_dot);
        let vb = dynamics::pivot_slip_velocity(&geo, mr.pivot, mr.theta, mr.theta_dot, -x_dot);
        mir.exact("pivot_slip_velocity", vb, -va, &(st, x_dot));

        let ka = dynamics::restoring(&geo, st.pivot, st.fo);
        let kb = dynamics::restoring(&geo, mr.pivot, mr.fo);
        mir.exact("restoring", kb, ka, &st);
    }
    mir.finish();
}

// ---------------------------------------------------------------------------
// Tests: impacts
// ---------------------------------------------------------------------------

/// Solutions of the generic solve the impulse law may return. μ_s = ∞: the
/// sticking impulse, always (even where it is tensile, P_y < 0). Finite μ_s:
/// the sticking impulse if it is inside the static cone |P_x| <= μ_s P_y
/// (so compressive), otherwise each slip direction σ whose post-impact
/// corner velocity has sign σ; both branches are admitted within
/// [`BRANCH_TOL`] of the switch. The second value says whether the sticking
/// impulse is tensile.
fn admissible_impulse_solutions(case: &ImpactCase) -> (Vec<(Option<Sign>, GenericImpact)>, bool) {
    let stick = solve_impact(&case.blk, &case.pre, ImpactCond::Stick { e: case.e });
    let scale = stick.px.abs().max(stick.py.abs()).max(f64::MIN_POSITIVE);
    let tensile = stick.py < 0.0;
    let (stick_ok, slip_ok) = if case.mu_s.is_infinite() {
        (true, false)
    } else if stick.py < -BRANCH_TOL * scale {
        (false, true)
    } else if stick.py <= BRANCH_TOL * scale {
        (true, true)
    } else {
        let margin = (stick.px.abs() - case.mu_s * stick.py) / scale;
        (margin <= BRANCH_TOL, margin > -BRANCH_TOL)
    };
    let mut allowed = Vec::new();
    if stick_ok {
        allowed.push((None, stick));
    }
    if slip_ok {
        let pre = &case.pre;
        let vscale = 1f64.max(pre.x_dot.abs()).max(pre.y_dot.abs()).max(pre.w.abs());
        for sigma in [Sign::Neg, Sign::Pos] {
            let cond = ImpactCond::Slip {
                e: case.e,
                sigma: sigma.value(),
                mu_k: case.mu_k,
            };
            let slip = solve_impact(&case.blk, pre, cond);
            if sigma.value() * slip.vcx_after >= -BRANCH_TOL * vscale {
                allowed.push((Some(sigma), slip));
            }
        }
    }
    (allowed, tensile)
}

/// Largest relative difference between the crate's post-impact velocities
/// and impulse and a generic solution.
fn post_distance(got: &PostImpact, want: &GenericImpact) -> f64 {
    [
        rel_diff(got.w, want.w),
        rel_diff(got.x_dot, want.x_dot),
        rel_diff(got.y_dot, want.y_dot),
        rel_diff(got.impulse.0, want.px),
        rel_diff(got.impulse.1, want.py),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

/// Tallies of [`check_impulse_law`].
#[derive(Default)]
struct Branches {
    stick: usize,
    slip: usize,
    /// More than one admissible solution (branch switch within BRANCH_TOL,
    /// or both slip directions consistent).
    ambiguous: usize,
    /// Sticking impulse tensile (P_y < 0).
    tensile: usize,
}

/// Checks one impulse-law result against the admissible generic solutions.
fn check_impulse_law(case: &ImpactCase, d_stick: &mut Discrepancies, d_slip: &mut Discrepancies, n: &mut Branches) {
    let geo = case.blk.geometry();
    let got = impact::impulse_law(&geo, &case.pre, case.e, case.mu_s, case.mu_k);
    assert_eq!(got.lifts_off, case.e > 0.0, "lifts_off wrong at {case:?}");
    let (allowed, tensile) = admissible_impulse_solutions(case);
    assert!(
        !allowed.is_empty(),
        "no admissible stick or slip solution (generic) at {case:?}; crate gave {got:?}"
    );
    n.tensile += usize::from(tensile);
    n.ambiguous += usize::from(allowed.len() > 1);
    let (branch, want) = allowed
        .iter()
        .min_by(|a, b| post_distance(&got, &a.1).total_cmp(&post_distance(&got, &b.1)))
        .expect("non-empty");
    match branch {
        None => {
            n.stick += 1;
            d_stick.post(&got, want, case);
            assert_eq!(got.slip, None, "crate slips where it should stick at {case:?}");
        }
        Some(sigma) => {
            n.slip += 1;
            d_slip.post(&got, want, case);
            assert!(
                got.slip == Some(*sigma) || (got.slip.is_none() && want.vcx_after.abs() <= BRANCH_TOL),
                "crate slip flag {:?}, generic slips {sigma:?} at {case:?}",
                got.slip
            );
        }
    }
}

#[test]
fn impulse_law_without_friction_limit_is_the_sticking_solve() {
    let mut rng = Rng::new(0x5EED_0007);
    let mut d_stick = Discrepancies::new("impulse (mu_s = inf)");
    let mut d_slip = Discrepancies::new("impulse (mu_s = inf), slipping (must not happen)");
    let mut n = Branches::default();
    for _ in 0..N_STATES {
        let case = ImpactCase {
            mu_s: f64::INFINITY,
            ..ImpactCase::random(&mut rng)
        };
        check_impulse_law(&case, &mut d_stick, &mut d_slip, &mut n);
    }
    println!(
        "impulse (mu_s = inf): {} sticking, of which {} with a tensile impulse (P_y < 0)",
        n.stick, n.tensile
    );
    assert_eq!(n.slip, 0, "slip with mu_s = inf");
    d_stick.report();
}

#[test]
fn impulse_law_with_friction_sticks_or_slips_consistently() {
    let mut rng = Rng::new(0x5EED_0008);
    let mut d_stick = Discrepancies::new("impulse (finite mu_s), sticking");
    let mut d_slip = Discrepancies::new("impulse (finite mu_s), slipping");
    let mut n = Branches::default();
    for _ in 0..N_STATES {
        let mut case = ImpactCase::random(&mut rng);
        if !case.mu_s.is_finite() {
            case.mu_s = rng.uniform(0.0, 1.0);
            case.mu_k = case.mu_s * rng.unit();
        }
        check_impulse_law(&case, &mut d_stick, &mut d_slip, &mut n);
    }
    println!(
        "impulse (finite mu_s): {} sticking, {} slipping, {} tensile sticking impulses, {} ambiguous",
        n.stick, n.slip, n.tensile, n.ambiguous
    );
    assert!(
        n.stick > N_STATES / 10 && n.slip > N_STATES / 10,
        "both branches exercised"
    );
    d_stick.report();
    d_slip.report();
}

#[test]
fn corner_momentum_is_the_plastic_sticking_solve_and_conserves_corner_momentum() {
    let mut rng = Rng::new(0x5EED_0009);
    let mut d = Discrepancies::new("corner-momentum");
    let mut n_tensile = 0usize;
    for _ in 0..N_STATES {
        let case = ImpactCase::random(&mut rng);
        let (blk, pre) = (&case.blk, &case.pre);
        let got = impact::corner_momentum(&blk.geometry(), pre);
        let want = solve_impact(blk, pre, ImpactCond::Stick { e: 0.0 });
        n_tensile += usize::from(want.py < 0.0);
        d.post(&got, &want, &case);
        assert_eq!(got.slip, None, "corner-momentum slips at {case:?}");
        assert!(!got.lifts_off, "corner-momentum lifts off at {case:?}");
        let before = momentum_about_corner(blk, pre.striking, pre.w, pre.x_dot, pre.y_dot);
        let after = momentum_about_corner(blk, pre.striking, got.w, got.x_dot, got.y_dot);
        d.check("H_corner", after, before, &case);
        // The new pivot is at rest after the impact.
        let (v, omega) = dimensional(blk, got.w, got.x_dot, got.y_dot);
        let v_c = point_velocity(v, omega, blk.flat_corner(pre.striking));
        let rp = blk.half_diag * blk.p;
        d.check("corner_vx_after", v_c[0] / rp, 0.0, &case);
        d.check("corner_vy_after", v_c[1] / rp, 0.0, &case);
    }
    println!("corner-momentum: {n_tensile} of {N_STATES} impacts stick with a tensile impulse (P_y < 0)");
    d.report();
}

#[test]
fn rocking_impacts_give_the_closed_form_ratios() {
    let mut rng = Rng::new(0x5EED_000A);
    let mut d = Discrepancies::new("rocking impact ratios");
    for _ in 0..N_STATES {
        let case = ImpactCase::random_rocking(&mut rng);
        let (blk, pre) = (&case.blk, &case.pre);
        let geo = blk.geometry();
        let s2 = blk.sin_psi() * blk.sin_psi();
        // Pre-impact: the striking corner moves straight down.
        let (v, omega) = dimensional(blk, pre.w, pre.x_dot, pre.y_dot);
        let v_c = point_velocity(v, omega, blk.flat_corner(pre.striking));
        assert!(v_c[1] < 0.0, "striking corner not approaching at {case:?}");
        d.check("pre corner_vx", v_c[0] / (blk.half_diag * blk.p), 0.0, &case);

        d.check("housner_r", geo.housner_r(), 1.0 - 1.5 * s2, &case);
        let h = impact::housner(&geo, pre);
        d.check("housner w", h.w, (1.0 - 1.5 * s2) * pre.w, &case);
        let cm = impact::corner_momentum(&geo, pre);
        d.check("corner-momentum w", cm.w, (1.0 - 1.5 * s2) * pre.w, &case);
        let got = impact::impulse_law(&geo, pre, case.e, f64::INFINITY, case.mu_k);
        d.check("impulse w", got.w, (1.0 - 1.5 * (1.0 + case.e) * s2) * pre.w, &case);

        // With a slip velocity V of the old pivot (slide-rock reaching Θ = 0),
        // the corner-momentum law gives w₊ = (1 − 1.5 sin²ψ) w₋ + ¾ cos ψ V,
        // while Housner's law ignores V: w₊ = (1 − 1.5 sin²ψ) w₋, and the
        // new pivot starts at rest.
        let mut slipping = case;
        let slip = pre.w.abs() * rng.uniform(-3.0, 3.0);
        slipping.pre.x_dot += slip;
        let cos_psi = blk.height / blk.width.hypot(blk.height);
        let cm = impact::corner_momentum(&geo, &slipping.pre);
        d.check(
            "corner-momentum w (pre-slip)",
            cm.w,
            (1.0 - 1.5 * s2) * pre.w + 0.75 * cos_psi * slip,
            &slipping,
        );
        let h = impact::housner(&geo, &slipping.pre);
        d.check("housner w (pre-slip)", h.w, (1.0 - 1.5 * s2) * pre.w, &slipping);
        let (v, omega) = dimensional(blk, h.w, h.x_dot, h.y_dot);
        let v_c = point_velocity(v, omega, blk.flat_corner(pre.striking));
        let rp = blk.half_diag * blk.p;
        d.check("housner corner_vx_after (pre-slip)", v_c[0] / rp, 0.0, &slipping);
        d.check("housner corner_vy_after (pre-slip)", v_c[1] / rp, 0.0, &slipping);
    }
    d.report();
}

#[test]
fn ratio_law_scales_w_and_starts_the_new_pivot_at_rest() {
    let mut rng = Rng::new(0x5EED_000B);
    let mut d = Discrepancies::new("ratio");
    for _ in 0..N_STATES {
        let case = ImpactCase::random(&mut rng);
        let (blk, pre) = (&case.blk, &case.pre);
        let r = rng.unit();
        let got = impact::ratio(&blk.geometry(), pre, r);
        d.check("w", got.w, r * pre.w, &case);
        let (v, omega) = dimensional(blk, got.w, got.x_dot, got.y_dot);
        let v_c = point_velocity(v, omega, blk.flat_corner(pre.striking));
        let rp = blk.half_diag * blk.p;
        d.check("corner_vx_after", v_c[0] / rp, 0.0, &case);
        d.check("corner_vy_after", v_c[1] / rp, 0.0, &case);
        // The reported impulse is the momentum change m Δv_G / (m R p).
        d.check("impulse_x", got.impulse.0, got.x_dot - pre.x_dot, &case);
        d.check("impulse_y", got.impulse.1, got.y_dot - pre.y_dot, &case);
        assert_eq!(got.slip, None, "ratio slips at {case:?}");
        assert!(!got.lifts_off, "ratio lifts off at {case:?}");
    }
    d.report();
}

/// Kinetic energy across impacts. Corner-momentum (plastic, sticking) and
/// the impulse law with e = 0 or without pre-impact slip never gain energy;
/// Housner's law (a ratio law) never gains energy without pre-impact slip,
/// and its gains with slip (docs/model.md §7.3) are counted and printed. With
/// e > 0 *and* pre-impact slip the impulse law's kinematic restitution can
/// gain energy: for a sticking impact ΔT = ½(V₊ᵀK⁻¹V₊ − V₋ᵀK⁻¹V₋) in the
/// striking-corner velocities (K the corner's inverse mass matrix), which is
/// positive for some V₋ iff e² > 1/(K_yy (K⁻¹)_yy) = 1/(1 + (9/4) sin²ψ cos²ψ).
/// Those gains are counted, printed, and checked against that bound.
#[test]
fn impacts_never_create_kinetic_energy() {
    let mut rng = Rng::new(0x5EED_000C);
    let mut worst_housner = f64::NEG_INFINITY;
    let mut n_gain_housner = 0usize;
    let mut worst_guaranteed = f64::NEG_INFINITY;
    let (mut n_gain_stick, mut n_gain_slip, mut worst_gain) = (0usize, 0usize, 0f64);
    let mut example = None;
    for _ in 0..N_STATES {
        let case = ImpactCase::random(&mut rng);
        let (blk, pre) = (&case.blk, &case.pre);
        let geo = blk.geometry();
        let before = kinetic(blk, pre.w, pre.x_dot, pre.y_dot);
        let gain_of = |post: &PostImpact| (kinetic(blk, post.w, post.x_dot, post.y_dot) - before) / before;

        let h = impact::corner_momentum(&geo, pre);
        let gain = gain_of(&h);
        assert!(
            gain <= TOL,
            "corner-momentum gains kinetic energy (rel {gain:e}) at {case:?}; post {h:?}"
        );
        worst_housner = worst_housner.max(gain);

        let post = impact::impulse_law(&geo, pre, case.e, case.mu_s, case.mu_k);
        let gain = gain_of(&post);
        let (v, omega) = dimensional(blk, pre.w, pre.x_dot, pre.y_dot);
        let vcx = point_velocity(v, omega, blk.flat_corner(pre.striking))[0] / (blk.half_diag * blk.p);
        let vscale = 1f64.max(pre.x_dot.abs()).max(pre.y_dot.abs()).max(pre.w.abs());
        // Housner's law: passive for a block that rocked without slip about
        // the old pivot (V_cx = 0 and Y' = −s' sin ψ w, docs/model.md §7.3).
        let lit = gain_of(&impact::housner(&geo, pre));
        let grounded = (pre.y_dot + pre.striking.value() * geo.sin_psi * pre.w).abs() <= 1e-12 * vscale;
        if grounded && vcx.abs() <= 1e-12 * vscale {
            assert!(
                lit <= TOL,
                "housner gains kinetic energy (rel {lit:e}) without pre-impact slip at {case:?}"
            );
        } else if grounded && lit > TOL {
            n_gain_housner += 1;
        }
        if case.e == 0.0 || vcx.abs() <= 1e-12 * vscale {
            assert!(
                gain <= TOL,
                "impulse law gains kinetic energy (rel {gain:e}) with e = 0 or no pre-impact slip at {case:?}; \
                 post {post:?}"
            );
            worst_guaranteed = worst_guaranteed.max(gain);
        } else if gain > TOL {
            worst_gain = worst_gain.max(gain);
            if post.slip.is_none() {
                n_gain_stick += 1;
                let sc = blk.sin_psi() * blk.height / (blk.width.hypot(blk.height));
                let bound = 1.0 / (1.0 + 2.25 * sc * sc);
                assert!(
                    case.e * case.e > bound * (1.0 - 1e-9),
                    "sticking impact gains energy below the restitution bound at {case:?}; post {post:?}"
                );
            } else {
                n_gain_slip += 1;
            }
            if example.is_none() {
                example = Some((gain, case, post));
            }
        }
    }
    println!("energy: corner-momentum: largest relative change T+/T- - 1 = {worst_housner:.3e}");
    println!("energy: housner: {n_gain_housner} of {N_STATES} impacts from slide-rock gain energy");
    println!("energy: impulse law, e = 0 or no pre-slip: largest relative change = {worst_guaranteed:.3e}");
    println!(
        "energy: impulse law, e > 0 with pre-slip: {n_gain_stick} sticking and {n_gain_slip} slipping impacts \
         gain energy (largest relative gain {worst_gain:.3e})"
    );
    if let Some((gain, case, post)) = example {
        println!("energy: example gain {gain:.3e} at {case:?} -> {post:?}");
    }
}

#[test]
fn impacts_are_exactly_mirror_symmetric() {
    let mut rng = Rng::new(0x5EED_000D);
    let mut mir = Mirror::new("impact mirror");
    for _ in 0..N_STATES {
        let case = ImpactCase::random(&mut rng);
        let geo = case.blk.geometry();
        let (pre, mpre) = (case.pre, case.mirrored_pre());
        let r = rng.unit();

        let a = impact::impulse_law(&geo, &pre, case.e, case.mu_s, case.mu_k);
        let b = impact::impulse_law(&geo, &mpre, case.e, case.mu_s, case.mu_k);
        mir.post("impulse_law", &a, &b, &case);

        let a = impact::housner(&geo, &pre);
        let b = impact::housner(&geo, &mpre);
        mir.post("housner", &a, &b, &case);

        let a = impact::corner_momentum(&geo, &pre);
        let b = impact::corner_momentum(&geo, &mpre);
        mir.post("corner_momentum", &a, &b, &case);

        let a = impact::ratio(&geo, &pre, r);
        let b = impact::ratio(&geo, &mpre, r);
        mir.post("ratio", &a, &b, &(case, r));

        let ca = impact::corner_velocity(&geo, &pre);
        let cb = impact::corner_velocity(&geo, &mpre);
        mir.exact("corner_velocity.x", cb.0, -ca.0, &case);
        mir.exact("corner_velocity.y", cb.1, ca.1, &case);
    }
    mir.finish();
}
