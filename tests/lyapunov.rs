//! Lyapunov exponents (issue 3): the tangent-dynamics and two-trajectory
//! machinery on systems with known exponents, the Floquet exponents of
//! periodic block responses from an independently computed monodromy
//! matrix, and the agreement of the two methods on chaotic responses.

// Small matrices read best with explicit indices.
#![allow(clippy::needless_range_loop)]

use rocking::analysis::lyapunov::{
    Lyapunov, LyapunovError, LyapunovOptions, LyapunovResult, Method, NoExponent, Outcome, Perturbable, Request,
    Schedule, Square, TangentSystem, exponents, lyapunov,
};
use rocking::integrate::hybrid::{
    Advance, Driver, DriverError, HybridSystem, Jump, Limits, MAX_GUARDS, Observer, Outputs,
};
use rocking::integrate::{Dop853, Tolerances};
use rocking::io::config;
use rocking::model::{BlockSystem, EventKind, ImpactLaw, Mode, Model};
use rocking::sim::{InitialState, Scenario, SectionRow, initial_mode, simulate};

// ---------------------------------------------------------------------------
// Small systems with known exponents.

#[derive(Clone, Copy, Debug, PartialEq)]
struct Only;

/// x'' + 2ζx' + x = cos(Ωτ): both exponents are −ζ (the eigenvalues of the
/// homogeneous part are −ζ ± i√(1−ζ²)).
#[derive(Clone, Debug)]
struct ForcedOscillator {
    zeta: f64,
    omega: f64,
}

impl HybridSystem<2> for ForcedOscillator {
    type Mode = Only;
    type Record = ();
    type Error = DriverError;
    fn rhs(&self, _m: Only, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = -2.0 * self.zeta * y[1] - y[0] + (self.omega * t).cos();
    }
    fn guards(&self, _m: Only, _t: f64, _y: &[f64; 2], _g: &mut [f64; MAX_GUARDS]) -> usize {
        0
    }
    fn is_observer(&self, _m: Only, _i: usize) -> bool {
        false
    }
    fn observe(&mut self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) {}
    fn jump(&mut self, m: Only, _i: usize, t: f64, y: &[f64; 2]) -> Result<Jump<Only, (), 2>, DriverError> {
        Ok(Jump {
            mode: m,
            t,
            y: *y,
            records: [None, None],
        })
    }
    fn is_terminal(&self, _m: Only) -> bool {
        false
    }
    fn next_breakpoint(&self, _t: f64) -> Option<f64> {
        None
    }
}

impl Perturbable<2, 2> for ForcedOscillator {
    fn coords(&self, y: &[f64; 2]) -> [f64; 2] {
        *y
    }
    fn tangent_dim(&self, _m: Only) -> usize {
        2
    }
    fn displaced(&self, _m: Only, _t: f64, y: &[f64; 2], dz: &[f64; 2]) -> Option<[f64; 2]> {
        Some([y[0] + dz[0], y[1] + dz[1]])
    }
}

impl TangentSystem<2, 2> for ForcedOscillator {
    fn jacobian(&self, _m: Only, _t: f64, _y: &[f64; 2]) -> Square<2> {
        [[0.0, 1.0], [-1.0, -2.0 * self.zeta]]
    }
    fn guard_gradient(&self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) -> Option<([f64; 2], f64)> {
        None
    }
    fn reset_jacobian(&self, _b: Only, _i: usize, _y: &[f64; 2], _a: Only, _ya: &[f64; 2]) -> (Square<2>, usize) {
        ([[1.0, 0.0], [0.0, 1.0]], 2)
    }
}

/// x' = diag(a, b) x: exponents a and b.
#[derive(Clone, Debug)]
struct Diagonal {
    a: f64,
    b: f64,
}

impl HybridSystem<2> for Diagonal {
    type Mode = Only;
    type Record = ();
    type Error = DriverError;
    fn rhs(&self, _m: Only, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = self.a * y[0];
        dy[1] = self.b * y[1];
    }
    fn guards(&self, _m: Only, _t: f64, _y: &[f64; 2], _g: &mut [f64; MAX_GUARDS]) -> usize {
        0
    }
    fn is_observer(&self, _m: Only, _i: usize) -> bool {
        false
    }
    fn observe(&mut self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) {}
    fn jump(&mut self, m: Only, _i: usize, t: f64, y: &[f64; 2]) -> Result<Jump<Only, (), 2>, DriverError> {
        Ok(Jump {
            mode: m,
            t,
            y: *y,
            records: [None, None],
        })
    }
    fn is_terminal(&self, _m: Only) -> bool {
        false
    }
    fn next_breakpoint(&self, _t: f64) -> Option<f64> {
        None
    }
}

impl Perturbable<2, 2> for Diagonal {
    fn coords(&self, y: &[f64; 2]) -> [f64; 2] {
        *y
    }
    fn tangent_dim(&self, _m: Only) -> usize {
        2
    }
    fn displaced(&self, _m: Only, _t: f64, y: &[f64; 2], dz: &[f64; 2]) -> Option<[f64; 2]> {
        Some([y[0] + dz[0], y[1] + dz[1]])
    }
}

impl TangentSystem<2, 2> for Diagonal {
    fn jacobian(&self, _m: Only, _t: f64, _y: &[f64; 2]) -> Square<2> {
        [[self.a, 0.0], [0.0, self.b]]
    }
    fn guard_gradient(&self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) -> Option<([f64; 2], f64)> {
        None
    }
    fn reset_jacobian(&self, _b: Only, _i: usize, _y: &[f64; 2], _a: Only, _ya: &[f64; 2]) -> (Square<2>, usize) {
        ([[1.0, 0.0], [0.0, 1.0]], 2)
    }
}

/// An impact oscillator: x'' = −x while x > 0, and at x = 0 the velocity
/// is reversed with restitution e (v⁺ = −e v⁻). Every flight from x = 0
/// lasts exactly π whatever its amplitude, the flow over it maps tangent
/// vectors by −I, and the saltation matrix of the impact is
/// S = diag(1, −e) + (f⁺ − J_R f⁻) n_yᵀ/(n_y·f⁻) = −e I. So the tangent map
/// over each flight is e I and both exponents are ln(e)/π exactly — a test
/// that fails without the saltation correction (J_R alone has det −e, not e²).
#[derive(Clone, Debug)]
struct ImpactOscillator {
    e: f64,
}

impl HybridSystem<2> for ImpactOscillator {
    type Mode = Only;
    type Record = ();
    type Error = DriverError;
    fn rhs(&self, _m: Only, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }
    fn guards(&self, _m: Only, _t: f64, y: &[f64; 2], g: &mut [f64; MAX_GUARDS]) -> usize {
        g[0] = y[0];
        1
    }
    fn is_observer(&self, _m: Only, _i: usize) -> bool {
        false
    }
    fn observe(&mut self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) {}
    fn jump(&mut self, m: Only, _i: usize, t: f64, y: &[f64; 2]) -> Result<Jump<Only, (), 2>, DriverError> {
        Ok(Jump {
            mode: m,
            t,
            y: [0.0, -self.e * y[1]],
            records: [None, None],
        })
    }
    fn is_terminal(&self, _m: Only) -> bool {
        false
    }
    fn next_breakpoint(&self, _t: f64) -> Option<f64> {
        None
    }
}

impl Perturbable<2, 2> for ImpactOscillator {
    fn coords(&self, y: &[f64; 2]) -> [f64; 2] {
        *y
    }
    fn tangent_dim(&self, _m: Only) -> usize {
        2
    }
    fn displaced(&self, _m: Only, _t: f64, y: &[f64; 2], dz: &[f64; 2]) -> Option<[f64; 2]> {
        let yp = [y[0] + dz[0], y[1] + dz[1]];
        (yp[0] > 0.0).then_some(yp)
    }
}

impl TangentSystem<2, 2> for ImpactOscillator {
    fn jacobian(&self, _m: Only, _t: f64, _y: &[f64; 2]) -> Square<2> {
        [[0.0, 1.0], [-1.0, 0.0]]
    }
    fn guard_gradient(&self, _m: Only, _i: usize, _t: f64, _y: &[f64; 2]) -> Option<([f64; 2], f64)> {
        Some(([1.0, 0.0], 0.0))
    }
    fn reset_jacobian(&self, _b: Only, _i: usize, _y: &[f64; 2], _a: Only, _ya: &[f64; 2]) -> (Square<2>, usize) {
        ([[1.0, 0.0], [0.0, -self.e]], 2)
    }
}

fn tight() -> Tolerances {
    Tolerances {
        rtol: 1e-12,
        atol: 1e-15,
        ..Tolerances::default()
    }
}

const BOTH: Request = Request {
    tangent: true,
    separation: Some(1e-7),
};

fn estimates<M: std::fmt::Debug>(o: Outcome<M, 2>) -> ([f64; 2], [f64; 2], f64, f64) {
    match o {
        Outcome::Estimate {
            tangent: Some(t),
            benettin: Some(b),
            min_dim,
            ..
        } => {
            assert_eq!(min_dim, 2);
            (t.exponents, t.stderr, b.exponents[0], b.stderr[0])
        }
        other => panic!("no estimate: {other:?}"),
    }
}

#[test]
fn linear_forced_oscillator_has_both_exponents_minus_zeta() {
    for zeta in [0.05, 0.2] {
        let sys = ForcedOscillator { zeta, omega: 1.3 };
        let period = std::f64::consts::TAU / 1.3;
        let schedule = Schedule {
            period,
            transient: 20,
            total: 1500,
            batches: 16,
        };
        let out = exponents::<_, 2, 2, 6>(sys, Only, [0.3, -0.2], &schedule, tight(), Limits::default(), BOTH).unwrap();
        let (tangent, _, benettin, _) = estimates(out);
        // Finite-time QR estimates of a complex pair oscillate about −ζ with
        // amplitude O(1/T); T ≈ 7000 here.
        for l in tangent {
            assert!((l + zeta).abs() < 1e-3, "ζ = {zeta}: tangent {tangent:?}");
        }
        assert!(
            (tangent[0] + tangent[1] + 2.0 * zeta).abs() < 1e-6,
            "trace: {tangent:?}"
        );
        assert!((benettin + zeta).abs() < 1e-3, "ζ = {zeta}: two-trajectory {benettin}");
    }
}

#[test]
fn diagonal_linear_system_has_its_eigenvalues_as_exponents() {
    let sys = Diagonal { a: 0.1, b: -0.35 };
    // 30 time units of transient align the perturbation with the first
    // axis to e^(−0.45·15) ≈ 1e-3 after seeding half-way through.
    let schedule = Schedule {
        period: 0.5,
        transient: 60,
        total: 300,
        batches: 10,
    };
    let out = exponents::<_, 2, 2, 6>(sys, Only, [1e-3, 1.0], &schedule, tight(), Limits::default(), BOTH).unwrap();
    let (tangent, stderr, benettin, _) = estimates(out);
    assert!((tangent[0] - 0.1).abs() < 1e-9, "{tangent:?}");
    assert!((tangent[1] + 0.35).abs() < 1e-9, "{tangent:?}");
    assert!(stderr[0] < 1e-9 && stderr[1] < 1e-9);
    assert!((benettin - 0.1).abs() < 1e-5, "{benettin}");
}

#[test]
fn impact_oscillator_exponents_are_ln_e_over_pi() {
    for e in [0.8, 0.95] {
        let sys = ImpactOscillator { e };
        let schedule = Schedule {
            period: 1.0,
            transient: 10,
            total: 160,
            batches: 10,
        };
        let out = exponents::<_, 2, 2, 6>(sys, Only, [0.0, 1.0], &schedule, tight(), Limits::default(), BOTH).unwrap();
        let (tangent, _, benettin, _) = estimates(out);
        let exact = e.ln() / std::f64::consts::PI;
        // The tangent map over each flight is exactly e·I, so over the
        // window of 150 it is e^n·(rotation) with n the number of impacts in
        // it: 150/π = 47.7 flights, hence an error below |ln e|/150.
        for l in tangent {
            assert!(
                (l - exact).abs() < e.ln().abs() / 150.0,
                "e = {e}: {tangent:?} vs {exact}"
            );
        }
        assert!((tangent[0] - tangent[1]).abs() < 1e-9, "equal exponents: {tangent:?}");
        assert!(
            (benettin - exact).abs() < e.ln().abs() / 150.0,
            "e = {e}: {benettin} vs {exact}"
        );
    }
}

// ---------------------------------------------------------------------------
// The block.

struct Quiet;

impl<M, R, const N: usize> Observer<M, R, N> for Quiet {
    fn sample(&mut self, _t: f64, _m: M, _y: &[f64; N]) {}
    fn section(&mut self, _k: u64, _t: f64, _m: M, _y: &[f64; N]) {}
    fn event(&mut self, _t: f64, _b: M, _y: &[f64; N], _r: R) {}
}

fn preset(name: &str, sets: &[&str]) -> Scenario {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    config::load(Some(name), None, &sets).unwrap()
}

fn exponents_of(res: &Lyapunov) -> &LyapunovResult {
    match res {
        Lyapunov::Exponents(r) => r,
        Lyapunov::None { .. } => panic!("no exponent: {res:?}"),
    }
}

/// The smallest p <= 16 for which the section points repeat after p
/// periods to `tol` (Θ and Θ').
fn section_period(rows: &[SectionRow], tol: f64) -> Option<usize> {
    (1..=16).find(|&p| {
        rows.windows(p + 1)
            .all(|w| (w[0].theta - w[p].theta).abs() < tol && (w[0].theta_dot - w[p].theta_dot).abs() < tol)
    })
}

/// A point of the steady periodic response of `cfg` where the pivot
/// sticks, its period in forcing periods, and the event kinds of one period
/// of the orbit.
fn periodic_orbit(cfg: &Scenario) -> (SectionRow, usize, Vec<EventKind>) {
    let model = cfg.model().unwrap();
    let mut opts = cfg.run_options();
    opts.tau_end = 2000.0;
    opts.output_dt = None;
    let res = simulate(model, &cfg.initial, &opts).unwrap();
    let tail: Vec<SectionRow> = res.section.iter().filter(|r| r.tau > 1500.0).copied().collect();
    let p = section_period(&tail, 1e-8).expect("a periodic response");
    let start = tail
        .iter()
        .position(|r| matches!(r.mode, Mode::Rock { .. }))
        .expect("a section point with the pivot stuck");
    let row = tail[start];
    let t_end = row.tau + p as f64 * cfg.model().unwrap().excitation.forcing_period().unwrap();
    let kinds = res
        .events
        .iter()
        .filter(|e| e.tau > row.tau && e.tau < t_end)
        .map(|e| e.kind)
        .collect();
    (row, p, kinds)
}

/// Floquet exponents (per τ) of the periodic orbit through `row` (pivot
/// stuck, so X' is slaved and the map acts on (Θ, Θ')), from the monodromy
/// matrix of the stroboscopic map over `p` periods computed by central
/// differences with the ordinary driver — no Jacobians, no saltation
/// matrices — Richardson-extrapolated over the steps h and h/2.
fn floquet(model: &Model, row: &SectionRow, p: usize) -> [f64; 2] {
    let period = model.excitation.forcing_period().unwrap();
    let tol = Tolerances {
        rtol: 1e-13,
        atol: 1e-15,
        ..Tolerances::default()
    };
    let outputs = Outputs {
        sample_dt: None,
        section_period: None,
    };
    let image = |theta: f64, theta_dot: f64| -> [f64; 2] {
        // The section time is excitation phase 0, the same as τ = 0.
        let init = InitialState {
            theta,
            theta_dot,
            x_dot: None,
        };
        let (mode, y) = initial_mode(model, &init).unwrap();
        let mut d = Driver::new(
            Dop853::new(tol),
            BlockSystem::new(model.clone()),
            mode,
            0.0,
            y,
            Limits::default(),
            outputs,
        );
        assert_eq!(d.advance(p as f64 * period, &mut Quiet).unwrap(), Advance::Reached);
        [d.y()[0], d.y()[1]]
    };
    let jacobian = |h: f64| -> [[f64; 2]; 2] {
        let mut m = [[0.0; 2]; 2];
        for j in 0..2 {
            let dz = |s: f64| if j == 0 { (s * h, 0.0) } else { (0.0, s * h) };
            let (a, b) = (dz(1.0), dz(-1.0));
            let plus = image(row.theta + a.0, row.theta_dot + a.1);
            let minus = image(row.theta + b.0, row.theta_dot + b.1);
            for i in 0..2 {
                m[i][j] = (plus[i] - minus[i]) / (2.0 * h);
            }
        }
        m
    };
    let (m1, m2) = (jacobian(1e-5), jacobian(5e-6));
    let mut m = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            m[i][j] = (4.0 * m2[i][j] - m1[i][j]) / 3.0;
        }
    }
    // Eigenvalue moduli of the 2×2 monodromy matrix.
    let tr = m[0][0] + m[1][1];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let disc = tr * tr - 4.0 * det;
    let t = p as f64 * period;
    if disc < 0.0 {
        let l = det.abs().ln() / (2.0 * t);
        [l, l]
    } else {
        let (a, b) = ((tr + disc.sqrt()) / 2.0, (tr - disc.sqrt()) / 2.0);
        let (hi, lo) = if a.abs() >= b.abs() { (a, b) } else { (b, a) };
        [hi.abs().ln() / t, lo.abs().ln() / t]
    }
}

fn on_orbit_options() -> LyapunovOptions {
    LyapunovOptions {
        transient_tau: 100.0,
        total_tau: 1100.0,
        ..LyapunovOptions::default()
    }
}

#[test]
fn fig4_period_one_response_has_its_floquet_exponents() {
    // Fig. 4 sweep at A_v = 1.0: period 1 (paper: period 1 below A_v ≈ 1.7),
    // rocking without sliding, two impacts per period.
    let cfg = preset("fig4", &["excitation.a_v=1.0"]);
    let model = cfg.model().unwrap();
    let (row, p, kinds) = periodic_orbit(&cfg);
    assert_eq!(p, 1, "period from the Poincaré points");
    assert!(
        kinds.iter().all(|&k| k == EventKind::Impact) && kinds.len() == 2,
        "{kinds:?}"
    );
    let floquet = floquet(&model, &row, p);
    let init = InitialState {
        theta: row.theta,
        theta_dot: row.theta_dot,
        x_dot: None,
    };
    let res = lyapunov(&model, &init, &on_orbit_options()).unwrap();
    let r = exponents_of(&res);
    assert_eq!(r.spectrum.len(), 2, "(Θ, Θ') without sliding");
    assert_eq!(r.collapsed, 1, "X' is slaved to Θ' when the pivot sticks");
    for i in 0..2 {
        assert!(
            (r.spectrum[i] - floquet[i]).abs() < 1e-3 + 3.0 * r.spectrum_stderr[i],
            "exponent {i}: tangent {} ± {} vs Floquet {}",
            r.spectrum[i],
            r.spectrum_stderr[i],
            floquet[i]
        );
    }
    assert!(r.largest_per_tau < -0.1, "a stable orbit: {}", r.largest_per_tau);
    // Without sliding the rock flow preserves area and each `ratio` impact
    // multiplies it by r²: λ₁ + λ₂ = 2 ln r · (impacts per τ) = 2 ln r · 2/T.
    let ImpactLaw::Ratio { r: ratio } = model.law else {
        panic!("fig4 uses the ratio law")
    };
    let sum = 2.0 * ratio.ln() * 2.0 / r.period;
    assert!(
        (r.spectrum[0] + r.spectrum[1] - sum).abs() < 1e-6,
        "{:?} vs sum {sum}",
        r.spectrum
    );
    // The two-trajectory method on the same orbit.
    let b = lyapunov(
        &model,
        &init,
        &LyapunovOptions {
            method: Method::Benettin,
            ..on_orbit_options()
        },
    )
    .unwrap();
    let b = exponents_of(&b);
    assert!(
        (b.largest_per_tau - floquet[0]).abs() < 1e-3 + 3.0 * b.stderr,
        "{} vs {}",
        b.largest_per_tau,
        floquet[0]
    );
}

#[test]
fn fig12_period_four_response_with_slip_and_stick_has_its_floquet_exponents() {
    // In this model the paper's Fig. 12 has period-4 orbits whose cycle
    // holds every switch of a sliding block: slip, stick and impacts into
    // slip. From rest it first wanders on a chaotic transient, so which
    // attractor a run from rest ends on depends on round-off (a change of
    // the step sequence alone decides between this orbit, another period-4
    // orbit and a tumble). The run therefore starts on the orbit: a section
    // point of it, found from rest with rtol 1e-11 (forcing phase 0 at τ = 0
    // as at every section time). The orbit attracts (Floquet exponents
    // below), so the start need only be near it.
    let cfg = preset(
        "fig12",
        &[
            "initial.theta=0.08690659236895766",
            "initial.theta_dot=0.47715899856722",
        ],
    );
    let model = cfg.model().unwrap();
    let (row, p, kinds) = periodic_orbit(&cfg);
    assert_eq!(p, 4, "period from the Poincaré points");
    for kind in [EventKind::Impact, EventKind::Slip, EventKind::Stick] {
        assert!(kinds.contains(&kind), "{kind:?} missing from {kinds:?}");
    }
    let floquet = floquet(&model, &row, p);
    let init = InitialState {
        theta: row.theta,
        theta_dot: row.theta_dot,
        x_dot: None,
    };
    let res = lyapunov(
        &model,
        &init,
        &LyapunovOptions {
            method: Method::Both,
            ..on_orbit_options()
        },
    )
    .unwrap();
    let r = exponents_of(&res);
    // The numbers docs/analysis.md quotes (`--nocapture` shows them).
    eprintln!(
        "fig12 period-4 orbit: Floquet {floquet:?}, tangent {:?} ± {:?}",
        r.spectrum, r.spectrum_stderr
    );
    assert_eq!(r.spectrum.len(), 2);
    assert_eq!(r.collapsed, 1, "the slip velocity is reset at every sticking impact");
    for i in 0..2 {
        assert!(
            (r.spectrum[i] - floquet[i]).abs() < 1e-3 + 3.0 * r.spectrum_stderr[i],
            "exponent {i}: tangent {} ± {} vs Floquet {}",
            r.spectrum[i],
            r.spectrum_stderr[i],
            floquet[i]
        );
    }
    let check = r.check.unwrap();
    assert!((check.benettin_per_tau - floquet[0]).abs() < 1e-3 + 3.0 * check.benettin_stderr);
}

/// Both methods on one fiducial trajectory agree within the paired error
/// (3σ of the batch-mean differences) plus 1e-3 for the two-trajectory
/// method's own bias (separation 1e-7 and integration error ~1e-11
/// relative make each renormalised growth uncertain by ~1e-4); and they
/// track each other batch by batch, so the paired error is far below the
/// error of either estimate (with a wrong saltation matrix it is not).
fn assert_paired_agreement(r: &LyapunovResult, what: &str) {
    let c = r.check.unwrap();
    assert!(
        c.difference.abs() < 3.0 * c.difference_stderr + 1e-3,
        "{what}: tangent {} vs two-trajectory {} (difference {} ± {})",
        r.largest_per_tau,
        c.benettin_per_tau,
        c.difference,
        c.difference_stderr
    );
    assert!(
        c.difference_stderr < 0.1 * r.stderr,
        "{what}: paired error {} vs tangent error {}",
        c.difference_stderr,
        r.stderr
    );
    assert!((r.largest_per_tau - c.benettin_per_tau).abs() < 3.0 * (r.stderr.hypot(c.benettin_stderr)));
}

#[test]
fn methods_agree_on_the_papers_chaotic_cases() {
    // Fig. 7 (no sliding): in this model the chaotic motion is a transient
    // that ends in a tumble (τ ≈ 250–700 depending on round-off: 299 at
    // the present numerics), so the exponent is measured over τ 50–240 of
    // the chaotic transient.
    let cfg = preset("fig7", &[]);
    let opts = LyapunovOptions {
        method: Method::Both,
        transient_tau: 50.0,
        total_tau: 240.0,
        ..LyapunovOptions::default()
    };
    let res = lyapunov(&cfg.model().unwrap(), &cfg.initial, &opts).unwrap();
    let r = exponents_of(&res);
    assert!(
        r.largest_per_tau > 0.3,
        "fig7 transient is chaotic: {}",
        r.largest_per_tau
    );
    assert_paired_agreement(r, "fig7");

    // Fig. 19 (sliding): chaos, which on some trajectories gives way to a
    // coexisting period-4 orbit; both methods share the trajectory.
    let cfg = preset("fig19", &[]);
    let opts = LyapunovOptions {
        method: Method::Both,
        ..LyapunovOptions::default()
    };
    let res = lyapunov(&cfg.model().unwrap(), &cfg.initial, &opts).unwrap();
    let r = exponents_of(&res);
    assert_paired_agreement(r, "fig19");
}

#[test]
fn independent_runs_agree_on_a_persistent_chaotic_attractor() {
    // Fig. 19's block and friction at A_h = 2.5, A_v = 2.25: chaotic for
    // every tolerance tried (1e-10 … 1e-12), so two separate runs — the
    // tangent one integrating the augmented system, the two-trajectory one
    // the plain system — follow different trajectories on the same
    // attractor and must agree within their combined error bars.
    let cfg = preset("fig19", &["excitation.a_h=2.5", "excitation.a_v=2.25"]);
    let model = cfg.model().unwrap();
    let run = |method| {
        let opts = LyapunovOptions {
            method,
            total_tau: 3200.0,
            ..LyapunovOptions::default()
        };
        lyapunov(&model, &cfg.initial, &opts).unwrap()
    };
    let (t, b) = (run(Method::Tangent), run(Method::Benettin));
    let (t, b) = (exponents_of(&t), exponents_of(&b));
    assert!(t.largest_per_tau > 0.3, "chaotic: {}", t.largest_per_tau);
    assert!(
        (t.largest_per_tau - b.largest_per_tau).abs() < 3.0 * t.stderr.hypot(b.stderr),
        "tangent {} ± {} vs two-trajectory {} ± {}",
        t.largest_per_tau,
        t.stderr,
        b.largest_per_tau,
        b.stderr
    );
    assert!(
        t.spectrum[1] < 0.0 && t.spectrum[0] + t.spectrum[1] < 0.0,
        "dissipative: {:?}",
        t.spectrum
    );
    assert!((t.per_cycle - t.largest_per_tau * t.period).abs() < 1e-15);
}

#[test]
fn tumbling_and_flat_responses_have_no_exponent() {
    // A strong push tumbles the block: at A_h = 10 in the first swing
    // (τ = 1.28, no impact), so the outcome does not hang on how a chaotic
    // transient ends (A_h = 6 tumbled after a transient at one rounding
    // and settled on a periodic orbit at another).
    let cfg = preset("fig7", &["excitation.a_h=10"]);
    let res = lyapunov(&cfg.model().unwrap(), &cfg.initial, &LyapunovOptions::default()).unwrap();
    assert!(
        matches!(
            res,
            Lyapunov::None {
                no_exponent: NoExponent::Tumbled,
                ..
            }
        ),
        "{res:?}"
    );
    // Too weak to lift the block: it never leaves rest.
    let cfg = preset("fig4", &["excitation.a_h=0.5", "excitation.a_v=0"]);
    let res = lyapunov(&cfg.model().unwrap(), &cfg.initial, &LyapunovOptions::default()).unwrap();
    assert!(
        matches!(
            res,
            Lyapunov::None {
                no_exponent: NoExponent::Rest,
                ..
            }
        ),
        "{res:?}"
    );
    let json = res.summary().to_string();
    assert!(json.contains("\"no_exponent\":\"rest\""), "{json}");
    // Just above the uplift threshold the block rocks, its impacts
    // accumulate, it rests and is lifted again: perturbations die out at
    // every rest (both methods see it).
    let cfg = preset("fig4", &["excitation.a_h=1.05", "excitation.a_v=0", "run.tau_end=1200"]);
    for method in [Method::Tangent, Method::Benettin] {
        let opts = LyapunovOptions::for_scenario(&cfg, method);
        let res = lyapunov(&cfg.model().unwrap(), &cfg.initial, &opts).unwrap();
        assert!(
            matches!(
                res,
                Lyapunov::None {
                    no_exponent: NoExponent::FlatPhases,
                    ..
                }
            ),
            "{method:?}: {res:?}"
        );
    }
}

/// A fresh, empty output directory for one test.
fn out_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rocking-lyapunov-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn batch_writes_the_exponents_into_summary_json() {
    let out = out_dir("batch");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["--batch", "--preset", "fig4", "-q"])
        .args(["--set", "excitation.a_v=1.0", "--set", "run.tau_end=600"])
        .args([
            "--set",
            "analysis.lyapunov=true",
            "--set",
            "analysis.lyapunov_method=both",
        ])
        .arg("--out")
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let l = &summary["lyapunov"];
    assert_eq!(l["method"], "both");
    let largest = l["largest_per_tau"].as_f64().unwrap();
    assert!((largest + 0.1985).abs() < 0.01, "{l}");
    assert!((l["per_cycle"].as_f64().unwrap() - largest * std::f64::consts::TAU / 8.0).abs() < 1e-12);
    assert!(l["stderr"].as_f64().unwrap() >= 0.0);
    assert_eq!(l["spectrum"].as_array().unwrap().len(), 2);
    assert!(l["check"]["difference"].as_f64().unwrap().abs() < 0.01, "{l}");
    assert_eq!(summary["config"]["analysis"]["lyapunov"], true);
    let _ = std::fs::remove_dir_all(&out);

    // Bad input: exit 2, nothing written.
    let out = out_dir("bad");
    for set in ["analysis.lyapunov=3", "analysis.lyapunov_method=fast"] {
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args(["--batch", "--preset", "fig4", "-q", "--set", set])
            .arg("--out")
            .arg(&out)
            .status()
            .unwrap();
        assert_eq!(status.code(), Some(2), "{set}");
        assert!(!out.join("summary.json").exists());
    }
}

#[test]
fn bad_options_and_excitations_are_errors() {
    let cfg = preset("fig4", &[]);
    let model = cfg.model().unwrap();
    let opts = LyapunovOptions {
        total_tau: 100.0,
        transient_tau: 200.0,
        ..LyapunovOptions::default()
    };
    assert!(matches!(
        lyapunov(&model, &cfg.initial, &opts),
        Err(LyapunovError::Option { field: "total_tau", .. })
    ));
    let cfg = preset("fig4", &["excitation.kind=\"none\""]);
    assert!(matches!(
        lyapunov(&cfg.model().unwrap(), &cfg.initial, &LyapunovOptions::default()),
        Err(LyapunovError::NotHarmonic)
    ));
}
