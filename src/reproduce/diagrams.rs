//! The bifurcation diagrams of the paper (Figs. 3–6, 9, 10, 14, 15) and the
//! variants that test why a diagram differs from the paper's, with the
//! comparison of each diagram against the mode ranges the paper gives.
//!
//! Every diagram is a [`block_sweep`] of `excitation.a_v` over the preset
//! of its figure, with the paper's window (Poincaré points of Θ at
//! τ_k = 2πk/Ω_h for 600 ≤ τ_k ≤ 800) and from rest unless the variant
//! says otherwise. The variants change one thing each, through the
//! configuration only (the model's equations are never altered); they are
//! labelled as variants in every output and are never the default.

use rayon::prelude::*;

use super::ReproduceError;
use super::paper::{Expect, PaperFigure, PaperRange};
use super::variant::Variant;
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::orbit_diagram::{
    BifurcationValue, BlockSweep, Continuation, Grid, Plan, ResponseRange, block_sweep, response_ranges,
};
use crate::analysis::steady::{Window, steady_response};
use crate::io::config::load;
use crate::sim::{Param, Scenario, simulate};

/// The swept key of every bifurcation diagram of the paper.
pub(crate) const PARAM: Param = Param::Av;

/// The grid, window and classifier shared by every diagram of a run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct DiagramSettings {
    /// The A_v values.
    pub grid: Grid,
    /// Transient and end of each run, τ.
    pub window: Window,
    /// Classifier thresholds.
    pub classify: ClassifyOptions,
}

/// A computed bifurcation diagram.
#[derive(Clone, Debug)]
pub struct Diagram {
    /// The paper's figure number.
    pub figure: u32,
    /// How it was computed.
    pub variant: Variant,
    /// The base scenario (A_v as in the preset; `run.tau_end` the
    /// window's end).
    pub config: Scenario,
    /// The `--set` assignments of the variant.
    pub sets: Vec<String>,
    /// Grid, window and classifier.
    pub settings: DiagramSettings,
    /// Every value, increasing.
    pub values: Vec<BifurcationValue>,
    /// Wall time of the sweep, s.
    pub wall_s: f64,
}

/// Computes the diagram of `figure` with `variant` (values in parallel on
/// the current rayon pool, unless the variant continues).
pub(crate) fn run_diagram(
    figure: &PaperFigure,
    variant: Variant,
    settings: &DiagramSettings,
) -> Result<Diagram, ReproduceError> {
    let start = std::time::Instant::now();
    let fail = |e: String| ReproduceError::Figure {
        figure: figure.number,
        what: format!("bifurcation diagram ({})", variant.slug()),
        error: e,
    };
    let plain = load(Some(figure.preset), None, &[]).map_err(|e| fail(e.to_string()))?;
    let geo = plain.geometry();
    let sets = variant.sets(&geo);
    let base = load(Some(figure.preset), None, &sets).map_err(|e| fail(e.to_string()))?;
    let mut config = base.clone();
    config.run.tau_end = settings.window.tau_end;
    let plan = Plan::new(settings.grid, variant.continuation(), None).map_err(|e| fail(e.to_string()))?;
    let spec = BlockSweep {
        base: &base,
        param: PARAM,
        window: settings.window,
        classify: settings.classify,
        lyapunov: None,
    };
    let values = block_sweep(&spec, &plan, &crate::analysis::silent)
        .map_err(|e| fail(format!("A_v = {}: {}", e.value, e.error)))?;
    Ok(Diagram {
        figure: figure.number,
        variant,
        config,
        sets,
        settings: *settings,
        values,
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// When each tumbled value of `d` tumbled: `(A_v, τ of the tumble)`, in
/// increasing A_v, by running those values again exactly as the diagram
/// did (deterministic, so the same trajectory). Only for a diagram seeded
/// from rest (not continuation), whose runs depend on the value alone. A tumble
/// long after τ = 0 means the block rocked, possibly chaotically, for that
/// long first: a transient, not an immediate overturn.
pub(crate) fn tumble_times(d: &Diagram) -> Result<Vec<(f64, f64)>, ReproduceError> {
    let fail = |e: String| ReproduceError::Figure {
        figure: d.figure,
        what: format!("tumble times ({})", d.variant.slug()),
        error: e,
    };
    if d.variant.continuation() != Continuation::None {
        return Err(fail(
            "a continuation diagram's runs depend on the previous value".to_string(),
        ));
    }
    let preset = format!("fig{}", d.figure);
    let base = load(Some(&preset), None, &d.sets).map_err(|e| fail(e.to_string()))?;
    let tumbled: Vec<f64> = d
        .values
        .iter()
        .filter(|v| v.response == Response::Tumbled)
        .map(|v| v.value)
        .collect();
    tumbled
        .par_iter()
        .map(|&a_v| {
            let mut cfg = Param::apply(&base, &[(PARAM, a_v)]).map_err(|e| fail(e.to_string()))?;
            cfg.run.tau_end = d.settings.window.tau_end;
            let model = cfg.model().map_err(|e| fail(e.to_string()))?;
            let mut opts = cfg.run_options();
            opts.output_dt = None;
            // As the diagram ran it (with section points; they no longer
            // shape the step sequence, but the run stays the diagram's).
            opts.section = true;
            let res = simulate(model, &cfg.initial, &opts).map_err(|e| fail(format!("A_v = {a_v}: {e}")))?;
            Ok((a_v, res.tumble_tau.unwrap_or(res.tau_end)))
        })
        .collect()
}

/// Neighbouring runs of tumbled values: `(A_v, responses of its
/// neighbours)` per value.
pub(crate) type Neighbours = Vec<(f64, Vec<Response>)>;

/// Neighbouring runs of the tumbled values of `d` with A_v in
/// [`from`, `to`]: for each, `count` runs at A_v·(1 + k·10⁻⁹), k = 1 …
/// `count`, classified over the diagram's window. A tumble that ends a
/// chaotic transient depends on such tiny changes; the share of
/// neighbours that still rock at the window's end is what runs like the
/// paper's could have seen. Deterministic (collected by index).
pub(crate) fn tumbled_neighbours(d: &Diagram, from: f64, to: f64, count: usize) -> Result<Neighbours, ReproduceError> {
    let fail = |e: String| ReproduceError::Figure {
        figure: d.figure,
        what: format!("neighbouring runs ({})", d.variant.slug()),
        error: e,
    };
    let preset = format!("fig{}", d.figure);
    let base = load(Some(&preset), None, &d.sets).map_err(|e| fail(e.to_string()))?;
    let tumbled: Vec<f64> = d
        .values
        .iter()
        .filter(|v| v.response == Response::Tumbled && v.value >= from - 1e-9 && v.value <= to + 1e-9)
        .map(|v| v.value)
        .collect();
    let jobs: Vec<(f64, usize)> = tumbled.iter().flat_map(|&a| (1..=count).map(move |k| (a, k))).collect();
    let responses = jobs
        .par_iter()
        .map(|&(a_v, k)| {
            let value = a_v * (1.0 + k as f64 * super::response::NEIGHBOUR_STEP);
            let cfg = Param::apply(&base, &[(PARAM, value)]).map_err(|e| fail(e.to_string()))?;
            steady_response(&cfg, &d.settings.window, &d.settings.classify, None)
                .map(|s| s.response)
                .map_err(|e| fail(format!("A_v = {value}: {e}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(tumbled
        .iter()
        .zip(responses.chunks(count.max(1)))
        .map(|(a, r)| (*a, r.to_vec()))
        .collect())
}

impl Diagram {
    /// `(A_v, response)` of every value.
    pub fn responses(&self) -> Vec<(f64, Response)> {
        self.values.iter().map(|v| (v.value, v.response)).collect()
    }

    /// Consecutive values with one response.
    pub fn ranges(&self) -> Vec<ResponseRange> {
        response_ranges(&self.responses())
    }

    /// How many values have each response, in a fixed order (rest, periods
    /// increasing, quasiperiodic, chaotic, tumbled, flight).
    pub fn counts(&self) -> Vec<(Response, usize)> {
        counts(self.values.iter().map(|v| v.response))
    }

    /// The share of values that are periodic, chaotic (or quasiperiodic)
    /// and tumbled.
    pub fn shares(&self) -> Shares {
        shares(&self.responses())
    }

    /// First A_v that tumbled, if any.
    pub(crate) fn first_tumble(&self) -> Option<f64> {
        self.values
            .iter()
            .find(|v| v.response == Response::Tumbled)
            .map(|v| v.value)
    }
}

/// Counts of each response in `responses`, in a fixed order.
pub fn counts(responses: impl Iterator<Item = Response>) -> Vec<(Response, usize)> {
    let mut out: Vec<(Response, usize)> = Vec::new();
    for r in responses {
        match out.iter_mut().find(|(x, _)| *x == r) {
            Some((_, n)) => *n += 1,
            None => out.push((r, 1)),
        }
    }
    out.sort_by_key(|(r, _)| order(*r));
    out
}

/// Sort key: rest, periods increasing, quasiperiodic, chaotic, tumbled,
/// flight.
pub fn order(r: Response) -> u32 {
    match r {
        Response::Rest => 0,
        Response::Periodic { period } => period,
        Response::Quasiperiodic => 1000,
        Response::Chaotic => 1001,
        Response::Tumbled => 1002,
        Response::Flight => 1003,
    }
}

/// `period 2 ×12, chaotic ×3, …` for a table cell.
pub(crate) fn counts_text(counts: &[(Response, usize)]) -> String {
    if counts.is_empty() {
        return "none".to_string();
    }
    counts
        .iter()
        .map(|(r, n)| format!("{} ×{n}", short(*r)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A response in a few characters: `(1,2)`, `chaotic`, `tumbled`, …
pub fn short(r: Response) -> String {
    match r {
        Response::Periodic { period } => format!("(1,{period})"),
        Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Rest | Response::Flight => {
            r.name().to_string()
        }
    }
}

/// Shares of the values of a diagram, each in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Shares {
    /// Periodic (any period) or at rest.
    pub periodic: f64,
    /// Chaotic or quasiperiodic (not periodic, still rocking).
    pub aperiodic: f64,
    /// Tumbled.
    pub tumbled: f64,
    /// Flight (only with `flight = "stop"`).
    pub flight: f64,
    /// Number of values.
    pub count: usize,
}

/// The shares of `responses`.
pub fn shares(responses: &[(f64, Response)]) -> Shares {
    let n = responses.len().max(1) as f64;
    let share = |f: &dyn Fn(Response) -> bool| responses.iter().filter(|(_, r)| f(*r)).count() as f64 / n;
    Shares {
        periodic: share(&|r| matches!(r, Response::Periodic { .. } | Response::Rest)),
        aperiodic: share(&|r| matches!(r, Response::Chaotic | Response::Quasiperiodic)),
        tumbled: share(&|r| r == Response::Tumbled),
        flight: share(&|r| r == Response::Flight),
        count: responses.len(),
    }
}

/// How well one of our ranges matches the paper's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Same response over the same range, within the tolerance.
    Agrees,
    /// The same response over part of the range.
    Partly,
    /// A different response.
    Differs,
}

impl Verdict {
    /// The word in the report.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Partly => "partly",
            Verdict::Differs => "differs",
        }
    }
}

/// One of the paper's ranges against our values.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub(crate) struct RangeComparison {
    /// First A_v of the paper's range.
    pub from: f64,
    /// Last A_v of the paper's range.
    pub to: f64,
    /// The paper's response, in words.
    pub paper: String,
    /// Our values in [from, to] with the expected response.
    pub matching: usize,
    /// Our values in [from, to].
    pub total: usize,
    /// Our responses in [from, to], as counts.
    pub ours: String,
    /// For a periodic range: our contiguous run of that period that
    /// overlaps the paper's range most, (first, last) A_v.
    pub run: Option<(f64, f64)>,
    /// The verdict (see [`compare_ranges`]).
    pub verdict: Verdict,
}

/// Whether `r` is what the paper reports.
pub fn matches(expect: Expect, r: Response) -> bool {
    match expect {
        Expect::Period(k) => r == Response::Periodic { period: k },
        Expect::HigherOrChaotic => match r {
            Response::Periodic { period } => period > 2,
            Response::Quasiperiodic | Response::Chaotic => true,
            Response::Tumbled | Response::Rest | Response::Flight => false,
        },
        Expect::Chaotic => r == Response::Chaotic,
    }
}

/// Compares `values` with the paper's `ranges`. Values on a shared
/// boundary count in both ranges (the paper says "about").
///
/// - A periodic range **agrees** when our longest-overlapping run of that
///   period starts and ends within `tol` of the paper's ends, and is
///   **partly** reproduced when at least half of the values in the range
///   have that period.
/// - A chaotic or mixed range agrees when at least 3/4 of its values
///   match, partly when at least 1/4 do.
///
/// Otherwise it differs.
pub(crate) fn compare_ranges(values: &[(f64, Response)], ranges: &[PaperRange], tol: f64) -> Vec<RangeComparison> {
    let eps = 1e-9;
    ranges
        .iter()
        .map(|pr| {
            let inside: Vec<Response> = values
                .iter()
                .filter(|(v, _)| *v >= pr.from - eps && *v <= pr.to + eps)
                .map(|(_, r)| *r)
                .collect();
            let matching = inside.iter().filter(|r| matches(pr.expect, **r)).count();
            let total = inside.len();
            let frac = if total == 0 {
                0.0
            } else {
                matching as f64 / total as f64
            };
            let run = match pr.expect {
                Expect::Period(k) => best_run(values, Response::Periodic { period: k }, pr.from, pr.to),
                Expect::HigherOrChaotic | Expect::Chaotic => None,
            };
            let verdict = match (pr.expect, run) {
                (Expect::Period(_), Some((a, b))) if (a - pr.from).abs() <= tol && (b - pr.to).abs() <= tol => {
                    Verdict::Agrees
                }
                (Expect::Period(_), _) if frac >= 0.5 => Verdict::Partly,
                (Expect::HigherOrChaotic | Expect::Chaotic, _) if frac >= 0.75 => Verdict::Agrees,
                (Expect::HigherOrChaotic | Expect::Chaotic, _) if frac >= 0.25 => Verdict::Partly,
                _ => Verdict::Differs,
            };
            RangeComparison {
                from: pr.from,
                to: pr.to,
                paper: pr.expect.label(),
                matching,
                total,
                ours: counts_text(&counts(inside.into_iter())),
                run,
                verdict,
            }
        })
        .collect()
}

/// The maximal run of consecutive values equal to `target` that overlaps
/// [from, to] most (ties: the first), as (first, last) value.
fn best_run(values: &[(f64, Response)], target: Response, from: f64, to: f64) -> Option<(f64, f64)> {
    let overlap = |a: f64, b: f64| (b.min(to) - a.max(from)).max(-1.0);
    response_ranges(values)
        .into_iter()
        .filter(|r| r.response == target && r.to >= from - 1e-9 && r.from <= to + 1e-9)
        .map(|r| (r.from, r.to))
        .fold(None, |best: Option<(f64, f64)>, r| match best {
            Some(b) if overlap(b.0, b.1) >= overlap(r.0, r.1) => Some(b),
            _ => Some(r),
        })
}

/// The periods of the successive periodic runs from the first value up to
/// the first two consecutive aperiodic, tumbled or flight values, each
/// listed once in order of appearance, e.g. `[1, 2, 4, 8]` for a
/// period-doubling cascade. A single aperiodic value inside a periodic
/// branch is passed over: from rest, a run can land on a coexisting
/// attractor at one value without ending the branch.
pub fn cascade(values: &[(f64, Response)]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::new();
    let mut off_branch = 0;
    for (_, r) in values {
        match r {
            Response::Periodic { period } => {
                off_branch = 0;
                if !out.contains(period) {
                    out.push(*period);
                }
            }
            Response::Rest => off_branch = 0,
            Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Flight => {
                off_branch += 1;
                if off_branch >= 2 {
                    break;
                }
            }
        }
    }
    out
}

/// Whether the start of `values` is a period-doubling cascade: periods 1,
/// 2 and 4 in this order (see [`cascade`]).
pub(crate) fn is_period_doubling(values: &[(f64, Response)]) -> bool {
    cascade(values).starts_with(&[1, 2, 4])
}

/// Switches between periodic and aperiodic (chaotic or quasiperiodic)
/// responses along the sweep, tumbled and flight values skipped: many
/// switches are the paper's "intermittency" (periodic and chaotic values
/// intermingled).
pub(crate) fn intermittency_switches(values: &[(f64, Response)]) -> usize {
    let kinds: Vec<bool> = values
        .iter()
        .filter_map(|(_, r)| match r {
            Response::Periodic { .. } | Response::Rest => Some(true),
            Response::Quasiperiodic | Response::Chaotic => Some(false),
            Response::Tumbled | Response::Flight => None,
        })
        .collect();
    kinds.windows(2).filter(|w| w[0] != w[1]).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::fixtures::{C, P1, P2, P4, T, grid};

    #[test]
    fn ranges_are_compared_by_runs_and_shares() {
        // 0.0..0.4 period 1, 0.5..0.7 period 2, 0.8 period 4, 0.9.. mixed.
        let v = grid(&[P1, P1, P1, P1, P1, P2, P2, P2, P4, C, T, C, T]);
        let ranges = [
            PaperRange {
                from: 0.0,
                to: 0.5,
                expect: Expect::Period(1),
            },
            PaperRange {
                from: 0.5,
                to: 0.8,
                expect: Expect::Period(2),
            },
            PaperRange {
                from: 0.9,
                to: 1.2,
                expect: Expect::Chaotic,
            },
        ];
        let c = compare_ranges(&v, &ranges, 0.1);
        assert_eq!(c[0].run, Some((0.0, 0.4)));
        assert_eq!(c[0].verdict, Verdict::Agrees);
        assert_eq!((c[0].matching, c[0].total), (5, 6));
        assert_eq!(c[1].run.map(|r| (r.0 * 10.0).round()), Some(5.0));
        assert_eq!(c[1].verdict, Verdict::Agrees);
        assert_eq!((c[2].matching, c[2].total), (2, 4));
        assert_eq!(c[2].verdict, Verdict::Partly);
        assert_eq!(c[2].ours, "chaotic ×2, tumbled ×2");
        let far = compare_ranges(
            &v,
            &[PaperRange {
                from: 0.0,
                to: 1.2,
                expect: Expect::Period(2),
            }],
            0.1,
        );
        assert_eq!(far[0].verdict, Verdict::Differs);
    }

    #[test]
    fn cascades_and_intermittency_are_recognised() {
        let doubling = grid(&[P1, P1, P2, P2, P4, C, T]);
        assert_eq!(cascade(&doubling), vec![1, 2, 4]);
        assert!(is_period_doubling(&doubling));
        // One chaotic value on the period-2 branch does not end it.
        let coexisting = grid(&[P1, P2, C, P2, P4, C, T, P2]);
        assert_eq!(cascade(&coexisting), vec![1, 2, 4]);
        let mixed = grid(&[P1, P2, C, T, P4, C]);
        assert_eq!(cascade(&mixed), vec![1, 2]);
        assert!(!is_period_doubling(&mixed));
        let mixed = grid(&[P1, P2, C, P2, C, T, P4, C]);
        assert_eq!(intermittency_switches(&mixed), 5);
        assert_eq!(intermittency_switches(&doubling), 1);
    }

    #[test]
    fn shares_add_up() {
        let s = shares(&grid(&[P1, C, T, T]));
        assert_eq!((s.periodic, s.aperiodic, s.tumbled, s.count), (0.25, 0.25, 0.5, 4));
    }
}
