//! Classification of a steady response from its stroboscopic section points.
//!
//! A run's steady response is one of six classes ([`Response`]). The three
//! terminal or trivial ones come from how the run ended:
//! - `tumbled`: |Θ| reached the tumble angle (the paper's blanks);
//! - `flight`: the block left the base (only with `run.flight = "stop"`);
//! - `rest`: the run ended at rest *and* had been at rest for at least one
//!   whole forcing period. Rest is flat and stuck, so its motion does not
//!   depend on the state; if the base could not lift the block during one
//!   whole period it never will, the forcing being periodic. A block that is
//!   at rest at the end but lifted off within the last period is in a
//!   periodic lift-and-land cycle, and is classified from its points.
//!
//! The other three are read off the N section points p_0 … p_{N−1} after the
//! transient (for the block, p = (Θ, Θ', X'); see
//! [`block_coordinates`](super::section::block_coordinates)):
//! 1. **`periodic`, period k** — the smallest k ≤ `k_max` (default 32) with
//!    |p_{j+k,d} − p_{j,d}| ≤ `rel_tol`·a_d + `abs_tol` for every j and every
//!    component d, where a_d = max_j |p_{j,d}| is the amplitude of component
//!    d. The tolerance is relative to the amplitude of the response (its
//!    distance from the upright rest state, the origin), not to the spread
//!    of the points: a fixed point has no spread, and its rounding noise
//!    must not become its own yardstick. Default `rel_tol` = 1e-3, the
//!    resolution of a plotted diagram: points that agree to 0.1 % of the
//!    amplitude are one point on the paper's figures. Slowly converging
//!    responses next to a bifurcation therefore count as periodic once their
//!    residual alternation is below 0.1 % of the amplitude.
//! 2. **`quasiperiodic` or `chaotic`** for points that do not repeat:
//!    - If the caller supplies the largest Lyapunov exponent λ, it decides:
//!      λ > `lyapunov_threshold` is chaotic, otherwise quasiperiodic.
//!    - Otherwise the *invariant-curve test* decides. Quasiperiodic section
//!      points lie on a smooth closed curve on which the map acts like an
//!      irrational rotation, so the map preserves the points' cyclic order
//!      along the curve. The test standardises each component, projects the
//!      points on their two principal axes, orders them by angle about the
//!      centroid (by value when the points lie on a line), and asks:
//!      - (a) is the order rotation-like? The fraction of steps
//!        p_j → p_{j+1} whose shift in cyclic rank is within ±2 of the most
//!        common shift must be at least `min_rotation_fraction` (default
//!        0.9). For an exact rotation it is 1 (the finite orbit's two ends
//!        change a rank by at most one); for chaos it is small (measured on
//!        255 points: 0.04–0.24 for the logistic map at r = 3.6–3.9, 0.03
//!        for the Hénon map, 0.08 for the chaotic block of Fig. 4 at
//!        A_v = 2.5);
//!      - (b) do the points form a curve, not a cloud? The length of the
//!        tour through them in that order must be at most `max_tour_ratio`
//!        (default 6) times their diameter (π for a circle, about 3 for an
//!        ellipse; 10–100 for a cloud).
//!
//!      Both hold: quasiperiodic; otherwise chaotic.
//!
//! Known limits, by construction: an invariant curve that does not wind
//! around its centroid (a crescent folded back on itself) fails (a) and is
//! reported chaotic, and a periodic orbit of period > `k_max` that lies on a
//! curve passes it and is reported quasiperiodic. Supplying λ removes both.
//! An aperiodic section with λ ≤ threshold (a slowly converging or
//! long-period orbit) is reported as quasiperiodic, the non-chaotic
//! aperiodic class.
//!
//! The paper's mode notation: it calls periodic responses "(1,1)", "(1,2)"
//! and "(1,4) modes" and their sequence a period doubling (Fig. 4), without
//! defining the pair. Read from its usage (docs/model.md §13), the second
//! index is the period in excitation cycles (the number of distinct section
//! points) and the first is always 1; so period k is reported as the paper's
//! `(1,k)` mode ([`Response::mode_notation`]).

use std::fmt;

use serde::Serialize;

use super::section::{after_transient, block_coordinates};
use crate::sim::{Outcome, RunResult};

/// Default largest period searched (the paper's diagrams show periods 1, 2
/// and 4; 32 leaves room for longer periodic windows inside chaos).
pub(crate) const K_MAX: u32 = 32;

/// The class of a steady response.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase", tag = "outcome")]
pub enum Response {
    /// The section points repeat with period `period` (in forcing cycles):
    /// the paper's (1, period) mode.
    Periodic {
        /// Smallest period found, 1 ≤ period ≤ `k_max`.
        period: u32,
    },
    /// Aperiodic, on an invariant closed curve (or λ ≤ threshold).
    Quasiperiodic,
    /// Aperiodic and not on a curve (or λ > threshold).
    Chaotic,
    /// The block tumbled.
    Tumbled,
    /// At rest for at least the last forcing period.
    Rest,
    /// The block left the base.
    Flight,
}

impl Response {
    /// The class names as written in `classes.csv` and `map.csv`.
    pub const NAMES: [&'static str; 6] = ["periodic", "quasiperiodic", "chaotic", "tumbled", "rest", "flight"];

    /// The class name.
    pub fn name(self) -> &'static str {
        match self {
            Response::Periodic { .. } => "periodic",
            Response::Quasiperiodic => "quasiperiodic",
            Response::Chaotic => "chaotic",
            Response::Tumbled => "tumbled",
            Response::Rest => "rest",
            Response::Flight => "flight",
        }
    }

    /// The period in forcing cycles, for a periodic response.
    pub fn period(self) -> Option<u32> {
        match self {
            Response::Periodic { period } => Some(period),
            Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Rest | Response::Flight => None,
        }
    }

    /// The paper's mode notation `(1,k)` for a periodic response of period k
    /// (see the module docs for this reading).
    pub(crate) fn mode_notation(self) -> Option<String> {
        self.period().map(|k| format!("(1,{k})"))
    }

    /// Whether the run ended in a terminal state (tumbled or flight): the
    /// paper leaves such values blank.
    pub fn is_terminal(self) -> bool {
        matches!(self, Response::Tumbled | Response::Flight)
    }

    /// The response named `name` (one of [`NAMES`](Self::NAMES)), with its
    /// period for `periodic`. `None` if the name is unknown, a periodic class
    /// has no period ≥ 1, or another class has one.
    pub fn from_name(name: &str, period: Option<u32>) -> Option<Self> {
        let r = match (name, period) {
            ("periodic", Some(k)) if k >= 1 => Response::Periodic { period: k },
            ("quasiperiodic", None) => Response::Quasiperiodic,
            ("chaotic", None) => Response::Chaotic,
            ("tumbled", None) => Response::Tumbled,
            ("rest", None) => Response::Rest,
            ("flight", None) => Response::Flight,
            _ => return None,
        };
        Some(r)
    }
}

impl fmt::Display for Response {
    /// `periodic (1,2)` for periodic responses, the class name otherwise.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.mode_notation() {
            Some(m) => write!(f, "{} {m}", self.name()),
            None => f.write_str(self.name()),
        }
    }
}

/// Thresholds of the classifier (see the module docs for each criterion).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ClassifyOptions {
    /// Largest period searched. Default [`K_MAX`] = 32. At least 2·`k_max`
    /// points are needed, so that every point of a period-`k_max` orbit is
    /// seen repeated.
    pub k_max: u32,
    /// Relative tolerance of the periodicity test, per component amplitude.
    /// Default 1e-3 (the resolution of a plotted diagram).
    pub rel_tol: f64,
    /// Absolute tolerance added to the relative one, in the points' units.
    /// Default 1e-9: far above the 1e-12 scatter of a converged orbit at the
    /// default integration tolerance, far below any response amplitude.
    pub abs_tol: f64,
    /// Smallest fraction of rotation-like steps for an invariant curve.
    /// Default 0.9 (an exact rotation gives 1, chaos at most 0.3 in the
    /// cases measured).
    pub min_rotation_fraction: f64,
    /// Largest tour length through the ordered points over their diameter
    /// for a curve. Default 6 (a circle gives π).
    pub max_tour_ratio: f64,
    /// Largest Lyapunov exponent above which an aperiodic response is
    /// chaotic, in the unit of the exponent the caller supplies (per unit τ
    /// for the block). Default 0.01: a finite-time estimate of a zero
    /// exponent over the paper's 200 τ window scatters by a few 1/T ≈ 0.005.
    pub lyapunov_threshold: f64,
}

impl Default for ClassifyOptions {
    fn default() -> Self {
        Self {
            k_max: K_MAX,
            rel_tol: 1e-3,
            abs_tol: 1e-9,
            min_rotation_fraction: 0.9,
            max_tour_ratio: 6.0,
            lyapunov_threshold: 0.01,
        }
    }
}

impl ClassifyOptions {
    /// Points needed to classify: 2·`k_max`.
    pub(crate) fn min_points(&self) -> usize {
        2 * self.k_max as usize
    }

    fn validate(&self) -> Result<(), ClassifyError> {
        let ok = |c: bool, m: &'static str| if c { Ok(()) } else { Err(ClassifyError::Options(m)) };
        ok(self.k_max >= 1, "k_max must be >= 1")?;
        ok(
            self.rel_tol.is_finite() && self.rel_tol >= 0.0,
            "rel_tol must be finite and >= 0",
        )?;
        ok(
            self.abs_tol.is_finite() && self.abs_tol >= 0.0,
            "abs_tol must be finite and >= 0",
        )?;
        ok(
            self.min_rotation_fraction > 0.0 && self.min_rotation_fraction <= 1.0,
            "min_rotation_fraction must be in (0, 1]",
        )?;
        ok(
            self.max_tour_ratio.is_finite() && self.max_tour_ratio > 0.0,
            "max_tour_ratio must be finite and > 0",
        )?;
        ok(
            self.lyapunov_threshold.is_finite() && self.lyapunov_threshold >= 0.0,
            "lyapunov_threshold must be finite and >= 0",
        )
    }
}

/// Why a point set could not be classified.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ClassifyError {
    /// Fewer points than 2·`k_max`.
    #[error("{have} section points after the transient; at least {need} are needed to classify (2 k_max)")]
    TooFewPoints {
        /// Points given.
        have: usize,
        /// Points needed.
        need: usize,
    },
    /// A point has a NaN or infinite component.
    #[error("section point {index} is not finite")]
    NonFinite {
        /// Index of the first such point.
        index: usize,
    },
    /// The supplied Lyapunov exponent is NaN or infinite.
    #[error("the Lyapunov exponent supplied is not finite")]
    NonFiniteExponent,
    /// An option is out of range.
    #[error("classifier options: {0}")]
    Options(&'static str),
}

/// Classifies a set of section points (see the module docs). `lyapunov`, if
/// given, is the largest Lyapunov exponent and decides between chaotic and
/// quasiperiodic for aperiodic points.
pub fn classify_points<const D: usize>(
    points: &[[f64; D]],
    lyapunov: Option<f64>,
    opts: &ClassifyOptions,
) -> Result<Response, ClassifyError> {
    opts.validate()?;
    if let Some(index) = points.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
        return Err(ClassifyError::NonFinite { index });
    }
    if points.len() < opts.min_points() {
        return Err(ClassifyError::TooFewPoints {
            have: points.len(),
            need: opts.min_points(),
        });
    }
    if let Some(period) = smallest_period(points, opts) {
        return Ok(Response::Periodic { period });
    }
    if let Some(lambda) = lyapunov {
        if !lambda.is_finite() {
            return Err(ClassifyError::NonFiniteExponent);
        }
        return Ok(if lambda > opts.lyapunov_threshold {
            Response::Chaotic
        } else {
            Response::Quasiperiodic
        });
    }
    let curve = curve_test(points);
    Ok(if curve.is_invariant_curve(opts) {
        Response::Quasiperiodic
    } else {
        Response::Chaotic
    })
}

/// The smallest k ≤ `k_max` (and ≤ N/2) with which the points repeat to
/// within the tolerance, or `None`.
pub(crate) fn smallest_period<const D: usize>(points: &[[f64; D]], opts: &ClassifyOptions) -> Option<u32> {
    let mut amplitude = [0.0_f64; D];
    for p in points {
        for (a, x) in amplitude.iter_mut().zip(p) {
            *a = a.max(x.abs());
        }
    }
    let tol: [f64; D] = std::array::from_fn(|d| opts.rel_tol * amplitude[d] + opts.abs_tol);
    let n = points.len();
    (1..=opts.k_max).find(|&k| {
        let k_us = k as usize;
        2 * k_us <= n
            && points
                .iter()
                .zip(&points[k_us..])
                .all(|(a, b)| a.iter().zip(b).zip(&tol).all(|((x, y), t)| (y - x).abs() <= *t))
    })
}

/// The two numbers of the invariant-curve test (module docs, step 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CurveTest {
    /// Fraction of steps p_j → p_{j+1} whose cyclic-rank shift is within ±2
    /// of the most common one (1 for a rotation).
    pub rotation_fraction: f64,
    /// Length of the tour through the points in cyclic order over their
    /// diameter (π for a circle; large for a cloud).
    pub tour_ratio: f64,
}

impl CurveTest {
    /// Whether both criteria of an invariant curve hold.
    pub(crate) fn is_invariant_curve(&self, opts: &ClassifyOptions) -> bool {
        self.rotation_fraction >= opts.min_rotation_fraction && self.tour_ratio <= opts.max_tour_ratio
    }
}

/// Runs the invariant-curve test on finite points. Fewer than 3 points, or
/// points that are all equal, give a fraction of 0 (no curve).
pub(crate) fn curve_test<const D: usize>(points: &[[f64; D]]) -> CurveTest {
    let none = CurveTest {
        rotation_fraction: 0.0,
        tour_ratio: f64::INFINITY,
    };
    let n = points.len();
    if n < 3 {
        return none;
    }
    let z = standardise(points);
    let m = z.first().map_or(0, Vec::len);
    if m == 0 {
        return none;
    }
    // Cyclic order: by angle in the plane of the two principal axes, or by
    // the value along the first one when the points lie on a line.
    let (keys, closed) = if m == 1 {
        (z.iter().map(|p| p[0]).collect::<Vec<_>>(), false)
    } else {
        let (values, vectors) = principal_axes(&z);
        let dot = |p: &[f64], v: &[f64]| p.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let (e1, e2) = (&vectors[0], &vectors[1]);
        if values[1] <= 1e-6 * values[0] {
            (z.iter().map(|p| dot(p, e1)).collect(), false)
        } else {
            (z.iter().map(|p| dot(p, e2).atan2(dot(p, e1))).collect(), true)
        }
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| keys[a].total_cmp(&keys[b]).then(a.cmp(&b)));
    let mut rank = vec![0usize; n];
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r;
    }
    let shifts: Vec<usize> = rank.windows(2).map(|w| (w[1] + n - w[0]) % n).collect();
    let mut counts = vec![0usize; n];
    for &s in &shifts {
        counts[s] += 1;
    }
    // Most common shift; ties go to the smallest shift, deterministically.
    let mode = counts
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)))
        .map_or(0, |(s, _)| s);
    let near = shifts
        .iter()
        .filter(|&&s| {
            let d = (s + n - mode) % n;
            d.min(n - d) <= 2
        })
        .count();
    let rotation_fraction = near as f64 / shifts.len() as f64;

    let dist = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt();
    let mut tour: f64 = order.windows(2).map(|w| dist(&z[w[0]], &z[w[1]])).sum();
    if closed && let (Some(&first), Some(&last)) = (order.first(), order.last()) {
        tour += dist(&z[last], &z[first]);
    }
    let mut diameter = 0.0_f64;
    for (i, a) in z.iter().enumerate() {
        for b in &z[i + 1..] {
            diameter = diameter.max(dist(a, b));
        }
    }
    let tour_ratio = if diameter > 0.0 { tour / diameter } else { f64::INFINITY };
    CurveTest {
        rotation_fraction,
        tour_ratio,
    }
}

/// Each component minus its mean, over its standard deviation; components
/// whose spread is rounding noise (std ≤ 1e-9 of their amplitude) are
/// dropped, because scaling noise to unit variance would swamp the others.
fn standardise<const D: usize>(points: &[[f64; D]]) -> Vec<Vec<f64>> {
    let n = points.len() as f64;
    let mut keep = Vec::new();
    for d in 0..D {
        let mean = points.iter().map(|p| p[d]).sum::<f64>() / n;
        let var = points.iter().map(|p| (p[d] - mean).powi(2)).sum::<f64>() / n;
        let amp = points.iter().map(|p| p[d].abs()).fold(0.0, f64::max);
        let std = var.sqrt();
        if std > 1e-9 * amp && std > 0.0 {
            keep.push((d, mean, std));
        }
    }
    points
        .iter()
        .map(|p| keep.iter().map(|&(d, mean, std)| (p[d] - mean) / std).collect())
        .collect()
}

/// Eigenvalues (descending) and unit eigenvectors of the covariance of the
/// rows of `z` (centred already), by cyclic Jacobi rotations: exact to
/// rounding for the handful of components a section has.
fn principal_axes(z: &[Vec<f64>]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let m = z.first().map_or(0, Vec::len);
    let n = z.len() as f64;
    let mut a = vec![vec![0.0; m]; m];
    for p in z {
        for i in 0..m {
            for j in 0..m {
                a[i][j] += p[i] * p[j] / n;
            }
        }
    }
    let mut v: Vec<Vec<f64>> = (0..m)
        .map(|i| (0..m).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for _sweep in 0..50 {
        let off: f64 = (0..m)
            .flat_map(|i| (0..m).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..m).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag {
            break;
        }
        for p in 0..m {
            for q in p + 1..m {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (upper, lower) = a.split_at_mut(q);
                if let (Some(row_p), Some(row_q)) = (upper.get_mut(p), lower.first_mut()) {
                    for (apk, aqk) in row_p.iter_mut().zip(row_q.iter_mut()) {
                        let (x, y) = (*apk, *aqk);
                        *apk = c * x - s * y;
                        *aqk = s * x + c * y;
                    }
                }
                for row in v.iter_mut() {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut idx: Vec<usize> = (0..m).collect();
    idx.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]).then(i.cmp(&j)));
    let values = idx.iter().map(|&i| a[i][i]).collect();
    let vectors = idx.iter().map(|&i| v.iter().map(|row| row[i]).collect()).collect();
    (values, vectors)
}

/// Classifies a block run: terminal and rest outcomes from how it ended,
/// the rest from its section points at τ ≥ `transient` (module docs).
/// `forcing_period` is 2π/Ω_h, used by the rest criterion.
pub fn classify_run(
    res: &RunResult,
    forcing_period: f64,
    transient: f64,
    lyapunov: Option<f64>,
    opts: &ClassifyOptions,
) -> Result<Response, ClassifyError> {
    match res.outcome {
        Outcome::Tumbled => return Ok(Response::Tumbled),
        Outcome::Flight => return Ok(Response::Flight),
        Outcome::Rest => {
            let last_event = res.events.last().map_or(0.0, |e| e.tau);
            if last_event <= res.tau_end - forcing_period {
                return Ok(Response::Rest);
            }
        }
        Outcome::Running => {}
    }
    let rows = after_transient(&res.section, transient);
    classify_points(&block_coordinates(rows), lyapunov, opts)
}

#[cfg(test)]
mod tests;
