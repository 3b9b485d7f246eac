//! Work–precision benchmarks: run time against error for every method, as
//! in DifferentialEquations.jl's benchmarks.
//!
//! For each scene a reference solution is computed with DOP853 at the
//! tightest tolerance (rtol 1e-14) and checked against one at rtol 1e-13;
//! every method is then run over a range of tolerances (adaptive methods)
//! or steps (Ralston), and each record holds the median wall time of
//! repeated runs, the work counters, the error of the state at τ_end and the
//! error of the impact times. Runs keep no history (the Poincaré section is
//! off too), so the timings are the solver's.

pub mod quadrature;

use std::time::Instant;

use serde::Serialize;

use crate::integrate::Tolerances;
use crate::integrate::hybrid::Limits;
use crate::io::csv::{self, Num, Row};
use crate::model::excitation::Excitation;
use crate::model::{EventKind, FlightPolicy, Geometry, Harmonic, ImpactLaw, Model};
use crate::plot::work_precision::WorkPoint;
use crate::sim::{InitialState, Method, RunOptions, RunResult, SimError, simulate};

/// A benchmark scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name (`free`, `periodic`, `sliding`, `chaotic`).
    pub name: &'static str,
    /// What it is, for reports.
    pub description: &'static str,
    /// The model.
    pub model: Model,
    /// Initial state.
    pub initial: InitialState,
    /// End of the run, τ.
    pub tau_end: f64,
}

fn paper_block(mu: (f64, f64), law: ImpactLaw, excitation: impl Fn(f64) -> Excitation) -> Model {
    let geo = Geometry::new(1.0, 4.0);
    Model {
        geo,
        mu_s: mu.0,
        mu_k: mu.1,
        law,
        excitation: excitation(geo.psi),
        tumble_theta: 1.0,
        flight: FlightPolicy::Ignore,
        zeno_eps: 1e-5,
        frame: None,
    }
}

fn harmonic(a_h: f64, a_v: f64, omega: f64) -> impl Fn(f64) -> Excitation {
    move |psi| {
        Excitation::Harmonic(Harmonic {
            a_h,
            a_v,
            omega_h: omega,
            omega_v: omega,
            phase_h: 0.0,
            phase_v: 0.0,
            psi,
        })
    }
}

const NO_SLIDING: (f64, f64) = (f64::INFINITY, f64::INFINITY);
const FROM_REST: InitialState = InitialState {
    theta: 0.0,
    theta_dot: 0.0,
    x_dot: None,
};

/// The four scenes of the benchmark: free rocking, a periodic orbit,
/// sliding and chaos (docs/performance.md).
pub fn scenes() -> Vec<Scene> {
    vec![
        Scene {
            name: "free",
            description: "free rocking from Θ = 0.5, Housner impacts, B × H = 1 × 4 m, τ 0–8; \
                          impact times against the energy quadrature",
            model: paper_block(NO_SLIDING, ImpactLaw::Housner, |_| Excitation::None),
            initial: InitialState {
                theta: 0.5,
                theta_dot: 0.0,
                x_dot: None,
            },
            // Before the impacts accumulate (τ ≈ 24): the final state still moves.
            tau_end: 8.0,
        },
        Scene {
            name: "periodic",
            description: "the paper's Ω = 8, A_h = 2, A_v = 0.5, no sliding, r = 0.925, τ 0–800",
            model: paper_block(NO_SLIDING, ImpactLaw::Ratio { r: 0.925 }, harmonic(2.0, 0.5, 8.0)),
            initial: FROM_REST,
            tau_end: 800.0,
        },
        Scene {
            name: "sliding",
            description: "slide-rock: Fig. 12 conditions (Ω = 8, A_h = 2, A_v = 2.5, μ_s = 0.4, μ_k = 0.35), τ 0–20",
            model: paper_block((0.4, 0.35), ImpactLaw::Ratio { r: 0.925 }, harmonic(2.0, 2.5, 8.0)),
            initial: FROM_REST,
            tau_end: 20.0,
        },
        Scene {
            name: "chaotic",
            description: "chaotic rocking, Fig. 7 conditions (Ω = 8, A_h = 2, A_v = 2.5, no sliding), \
                          τ 0–15: short enough that errors are not yet amplified",
            model: paper_block(NO_SLIDING, ImpactLaw::Ratio { r: 0.925 }, harmonic(2.0, 2.5, 8.0)),
            initial: FROM_REST,
            tau_end: 15.0,
        },
    ]
}

/// One point of a work–precision curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Record {
    /// Scene name.
    pub scene: String,
    /// Method name.
    pub method: String,
    /// rtol (adaptive methods) or the fixed step (Ralston).
    pub setting: f64,
    /// Median wall time of the repeats, s.
    pub wall_s: f64,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Max-norm error of (Θ, Θ', X') at τ_end against the reference.
    pub error: f64,
    /// Largest error of the impact times, over the impacts both runs share;
    /// `None` if the impact counts differ (the error is then the count's).
    pub impact_time_error: Option<f64>,
    /// Impacts in this run.
    pub impacts: u64,
}

impl Record {
    /// The record as the work–precision figure draws it.
    pub fn point(&self) -> WorkPoint<'_> {
        WorkPoint {
            scene: &self.scene,
            method: &self.method,
            wall_s: self.wall_s,
            error: self.error,
        }
    }
}

/// The reference of a scene and its self-check.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    /// Scene name.
    pub scene: String,
    /// Max-norm difference of the final state between rtol 1e-14 and 1e-13:
    /// an upper estimate of the reference's own error.
    pub self_check: f64,
    /// Impacts in the reference run.
    pub impacts: u64,
    /// For `free`: the largest difference between the reference's impact
    /// times and the quadrature's.
    pub quadrature_impact_error: Option<f64>,
}

/// Settings of a benchmark.
#[derive(Clone, Debug)]
pub struct BenchOptions {
    /// Repeats per record, at least (the median is reported; short runs
    /// are repeated until they add up to [`MIN_MEASURED_S`]). Default 5.
    pub repeats: usize,
    /// rtols of the adaptive methods. Default 1e-2 … 1e-13, one per decade
    /// (the loose end reaches the error of the paper's method).
    pub rtols: Vec<f64>,
    /// Steps of Ralston. Default 0.004 (the paper's) halved four times.
    pub steps: Vec<f64>,
}

impl Default for BenchOptions {
    fn default() -> Self {
        Self {
            repeats: 5,
            rtols: (2..=13).map(|e| 10f64.powi(-e)).collect(),
            steps: vec![0.004, 0.002, 0.001, 0.0005, 0.00025],
        }
    }
}

fn options(method: Method, rtol: f64, step: f64, tau_end: f64) -> RunOptions {
    RunOptions {
        tau_end,
        method,
        tol: Tolerances {
            rtol,
            // atol a hundredth of rtol: Θ and Θ' are of order 0.01–1.
            atol: rtol * 1e-2,
            h_max: f64::INFINITY,
            h_fixed: step,
        },
        output_dt: None,
        section: false,
        rest_after: None,
        limits: Limits::default(),
    }
}

fn final_error(a: &RunResult, b: &RunResult) -> f64 {
    [0usize, 1, 3]
        .iter()
        .map(|&i| (a.final_state[i] - b.final_state[i]).abs())
        .fold(0.0, f64::max)
}

fn impact_times(r: &RunResult) -> Vec<f64> {
    r.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .map(|e| e.tau)
        .collect()
}

/// For the `free` scene, the impact times of the energy quadrature, which
/// do not depend on the integrator at all.
fn quadrature_times(scene: &Scene) -> Option<Vec<f64>> {
    match (scene.name, &scene.model.excitation, scene.model.law) {
        ("free", Excitation::None, ImpactLaw::Housner) if scene.initial.theta_dot == 0.0 => {
            let geo = &scene.model.geo;
            Some(quadrature::impact_times(
                geo.psi,
                geo.housner_r(),
                scene.initial.theta.abs(),
                scene.tau_end,
            ))
        }
        _ => None,
    }
}

/// The reference solution of `scene` and its self-check.
pub fn reference(scene: &Scene) -> Result<(RunResult, Reference), SimError> {
    let fine = simulate(
        scene.model.clone(),
        &scene.initial,
        &options(Method::Dop853, 1e-14, 0.004, scene.tau_end),
    )?;
    let check = simulate(
        scene.model.clone(),
        &scene.initial,
        &options(Method::Dop853, 1e-13, 0.004, scene.tau_end),
    )?;
    let quadrature_impact_error = quadrature_times(scene).map(|q| {
        let t = impact_times(&fine);
        if q.len() == t.len() {
            q.iter().zip(&t).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
        } else {
            f64::INFINITY
        }
    });
    let r = Reference {
        scene: scene.name.to_string(),
        self_check: final_error(&fine, &check),
        impacts: fine.tally.impacts,
        quadrature_impact_error,
    };
    Ok((fine, r))
}

/// Repeats of a record add up to at least this much wall time, s.
pub(crate) const MIN_MEASURED_S: f64 = 0.05;

/// Most repeats of one record (a free-rocking run takes 15 µs).
pub(crate) const MAX_REPEATS: usize = 2000;

/// Runs one method at one setting `repeats` times against `reference`
/// (more for a short run: see [`MIN_MEASURED_S`]); the median wall time is
/// reported.
pub fn record(
    scene: &Scene,
    reference: &RunResult,
    method: Method,
    setting: f64,
    repeats: usize,
) -> Result<Record, SimError> {
    let (rtol, step) = match method {
        Method::Ralston => (1e-10, setting),
        Method::Dop853 | Method::Dopri5 | Method::Taylor => (setting, 0.004),
    };
    let opts = options(method, rtol, step, scene.tau_end);
    let mut walls = Vec::with_capacity(repeats.max(1));
    let start = Instant::now();
    let mut res = simulate(scene.model.clone(), &scene.initial, &opts)?;
    walls.push(start.elapsed().as_secs_f64());
    let mut total = walls[0];
    // At least `repeats`, and more for a short run, until the repeats add up
    // to MIN_MEASURED_S (as criterion and divan sample for a fixed time):
    // a median of 9 runs of 0.1 ms moved the ratios by ±0.5 from one
    // benchmark to the next on the shared VM.
    while walls.len() < repeats.max(1) || (total < MIN_MEASURED_S && walls.len() < MAX_REPEATS) {
        let start = Instant::now();
        res = simulate(scene.model.clone(), &scene.initial, &opts)?;
        let wall = start.elapsed().as_secs_f64();
        walls.push(wall);
        total += wall;
    }
    walls.sort_by(f64::total_cmp);
    let wall_s = walls[walls.len() / 2];
    let tr = quadrature_times(scene).unwrap_or_else(|| impact_times(reference));
    let ti = impact_times(&res);
    let impact_time_error =
        (ti.len() == tr.len()).then(|| ti.iter().zip(&tr).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max));
    Ok(Record {
        scene: scene.name.to_string(),
        method: method.name().to_string(),
        setting,
        wall_s,
        rhs_evals: res.stats.rhs_evals,
        steps: res.stats.accepted,
        error: final_error(&res, reference),
        impact_time_error,
        impacts: res.tally.impacts,
    })
}

/// All records of `scene`.
pub fn work_precision(scene: &Scene, opts: &BenchOptions) -> Result<(Reference, Vec<Record>), SimError> {
    let (fine, reference) = reference(scene)?;
    let mut out = Vec::new();
    for method in [Method::Dop853, Method::Dopri5, Method::Taylor] {
        for &rtol in &opts.rtols {
            out.push(record(scene, &fine, method, rtol, opts.repeats)?);
        }
    }
    for &h in &opts.steps {
        // The smallest Ralston steps take long on the periodic scene: one
        // repeat is enough for a point that is seconds, not milliseconds.
        let repeats = if h < 0.001 { 1 } else { opts.repeats };
        out.push(record(scene, &fine, Method::Ralston, h, repeats)?);
    }
    Ok((reference, out))
}

/// Time of `method` at `error`, by log–log interpolation of its records;
/// if every record is more accurate than `error`, the fastest record's time
/// (an upper bound); `None` if none is accurate enough.
pub(crate) fn time_at_error(records: &[Record], method: &str, error: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = records
        .iter()
        .filter(|r| r.method == method && r.error > 0.0 && r.wall_s > 0.0)
        .map(|r| (r.error.ln(), r.wall_s.ln()))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let e = error.ln();
    let inside = pts.windows(2).find(|w| w[0].0 <= e && e <= w[1].0).map(|w| {
        let f = if w[1].0 > w[0].0 {
            (e - w[0].0) / (w[1].0 - w[0].0)
        } else {
            0.0
        };
        (w[0].1 + f * (w[1].1 - w[0].1)).exp()
    });
    // Every record more accurate than asked: the fastest of them is an
    // upper bound on the time that error needs.
    let all_better = pts.last().is_some_and(|p| p.0 <= e);
    inside.or_else(|| all_better.then(|| pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min).exp()))
}

/// The speed targets of one scene (docs/performance.md), from its records.
#[derive(Clone, Debug, Serialize)]
pub struct Targets {
    /// Scene name.
    pub scene: String,
    /// Error of Ralston at the paper's step 0.004.
    pub ralston_error_at_paper_step: Option<f64>,
    /// Ralston's time at that step, s.
    pub ralston_time_at_paper_step: Option<f64>,
    /// DOP853's time to reach the same error (interpolated; the fastest
    /// DOP853 run if all are more accurate), s.
    pub dop853_time_at_that_error: Option<f64>,
    /// Ralston time / DOP853 time at Ralston's own error (target ≥ 5).
    pub speedup_at_paper_error: Option<f64>,
    /// DOP853's time at error 1e-9 (interpolated), s.
    pub dop853_time_at_1e9: Option<f64>,
    /// Ralston's time at error 1e-9, extrapolated along an order-2 curve
    /// (time ∝ error^(−1/2)) from its most accurate point, s. A lower bound:
    /// with the paper's event rule (|Θ| < 1e-6) its error plateaus near
    /// 1e-6 and 1e-9 is not reached at any step.
    pub ralston_time_at_1e9_extrapolated: Option<f64>,
    /// The ratio of the two (target ≥ 100).
    pub speedup_at_1e9: Option<f64>,
}

/// Evaluates the targets for `scene` from `records`.
pub fn targets(scene: &str, records: &[Record]) -> Targets {
    let paper = records.iter().find(|r| r.method == "ralston" && r.setting == 0.004);
    let e0 = paper.map(|r| r.error);
    let t0 = paper.map(|r| r.wall_s);
    let d0 = e0.and_then(|e| time_at_error(records, "dop853", e));
    let best = records
        .iter()
        .filter(|r| r.method == "ralston" && r.error > 0.0)
        .min_by(|a, b| a.error.total_cmp(&b.error));
    let r9 = best.map(|b| b.wall_s * (b.error / 1e-9).sqrt());
    let d9 = time_at_error(records, "dop853", 1e-9);
    Targets {
        scene: scene.to_string(),
        ralston_error_at_paper_step: e0,
        ralston_time_at_paper_step: t0,
        dop853_time_at_that_error: d0,
        speedup_at_paper_error: t0.zip(d0).map(|(a, b)| a / b),
        dop853_time_at_1e9: d9,
        ralston_time_at_1e9_extrapolated: r9,
        speedup_at_1e9: r9.zip(d9).map(|(a, b)| a / b),
    }
}

/// A row of `work_precision.csv`.
#[derive(serde::Serialize)]
struct CsvRecord<'a> {
    scene: &'a str,
    method: &'a str,
    setting: Num,
    wall_s: Num,
    rhs_evals: u64,
    steps: u64,
    error: Num,
    impact_time_error: Option<Num>,
    impacts: u64,
}

impl Row for CsvRecord<'_> {
    const HEADER: &'static [&'static str] = &[
        "scene",
        "method",
        "setting",
        "wall_s",
        "rhs_evals",
        "steps",
        "error",
        "impact_time_error",
        "impacts",
    ];
}

/// Records as CSV (`scene,method,setting,wall_s,rhs_evals,steps,error,impact_time_error,impacts`).
pub(crate) fn to_csv(records: &[Record]) -> String {
    csv::to_string(records.iter().map(|r| CsvRecord {
        scene: &r.scene,
        method: &r.method,
        setting: Num(r.setting),
        wall_s: Num(r.wall_s),
        rhs_evals: r.rhs_evals,
        steps: r.steps,
        error: Num(r.error),
        impact_time_error: r.impact_time_error.map(Num),
        impacts: r.impacts,
    }))
}
