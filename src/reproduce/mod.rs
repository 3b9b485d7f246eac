//! `rocking reproduce`: every figure of the paper's section 4 (Figs. 3–19)
//! recomputed, and a report that sets each beside the paper's statements.
//!
//! - The bifurcation diagrams (Figs. 3–6, 9, 10, 14, 15) are
//!   [`block_sweep`](crate::analysis::orbit_diagram::block_sweep)s of A_v
//!   over the figure's preset ([`diagrams`]).
//! - The response examples (Figs. 7, 8, 11–13, 16–19) get their time
//!   history, two power spectra, Poincaré map and largest Lyapunov exponent
//!   by both methods ([`response`]).
//! - Where a diagram does not reproduce (Figs. 3 and 4), clearly labelled
//!   **variants** test the candidate reasons one at a time: the paper's
//!   integrator, continuation, other impact ratios (including the paper's
//!   eq. 20 as printed), the tumble criterion and the flight policy
//!   ([`variant::Variant`]). They change the configuration only, never
//!   the model's equations, and are never the default.
//! - The report ([`report`]) quotes the paper ([`paper`]), tabulates paper
//!   against ours, and says where they agree and where they differ.
//!
//! Contract: the computation is deterministic (every parallel loop collects
//! by index), so the figures and CSV files are the same bytes for any
//! number of threads; only the timings in the report vary. Nothing here
//! writes files except through a [`write::Sink`], which the CLI backs with
//! a staging directory (all files appear at once or none do). Failures are
//! typed errors naming the figure; a response without an exponent (e.g. one
//! that tumbles) is a reported outcome, never NaN.

pub mod diagrams;
#[cfg(test)]
mod fixtures;
pub mod format;
pub mod paper;
pub mod report;
pub mod response;
pub mod scan;
pub mod variant;
pub mod write;

use rayon::prelude::*;

use crate::analysis::classify::ClassifyOptions;
use crate::analysis::orbit_diagram::Grid;
use crate::analysis::steady::Window;
use crate::analysis::{Progress, ProgressFn};
use crate::io::output_error::OutputError;
use crate::plot::PlotError;
use crate::sim::Scenario;
use crate::sim::scenario::LawKind;
use diagrams::{Diagram, DiagramSettings, run_diagram, tumble_times, tumbled_neighbours};
use paper::{FIGURES, FigureKind, PaperFigure};
use response::{
    ResponseExample, ResponseSettings, ResponseVariant, response_variants, run_response, run_response_variant,
};
use scan::{Scan, lyapunov_scan};
use variant::{R_SCAN, Variant};

/// The figures whose diagrams are investigated with the variants: the
/// paper's Figs. 3 and 4, the only ones for which it gives mode ranges.
pub(crate) const INVESTIGATED: [u32; 2] = [3, 4];

/// The figure whose diagram gets a Lyapunov scan: Fig. 10, whose quoted
/// exponent (0.51) the paper gives without its A_v.
pub(crate) const SCANNED: u32 = 10;

/// What to compute.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// CI-sized: A_v step 0.25 instead of 0.02, shorter long runs and
    /// Lyapunov windows. For tests and a first look; the report says so.
    pub quick: bool,
    /// Only these figures (numbers 3–19), or all.
    pub only: Option<Vec<u32>>,
}

impl Options {
    /// The A_v grid: the paper's 0 to 3 in steps of 0.02, or 0.25 (quick).
    pub fn grid(&self) -> Result<Grid, ReproduceError> {
        let step = if self.quick { 0.25 } else { 0.02 };
        Grid::new(0.0, 3.0, step).map_err(|e| ReproduceError::Options(e.to_string()))
    }

    /// The response run lengths.
    pub(crate) fn response_settings(&self) -> ResponseSettings {
        if self.quick {
            ResponseSettings::quick()
        } else {
            ResponseSettings::full()
        }
    }

    /// The Lyapunov scan window, τ: (600, 1600) or (200, 500) quick.
    pub(crate) fn scan_window(&self) -> (f64, f64) {
        if self.quick { (200.0, 500.0) } else { (600.0, 1600.0) }
    }

    /// Whether figure `number` is computed.
    pub(crate) fn wants(&self, number: u32) -> bool {
        self.only.as_ref().is_none_or(|o| o.contains(&number))
    }
}

/// Why a reproduction failed.
#[derive(Debug, thiserror::Error)]
pub enum ReproduceError {
    /// A computation for one figure failed.
    #[error("Fig. {figure}, {what}: {error}")]
    Figure {
        /// The paper's figure number.
        figure: u32,
        /// What was being computed.
        what: String,
        /// The error.
        error: String,
    },
    /// Bad options.
    #[error("{0}")]
    Options(String),
    /// Writing a file failed.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// Drawing a figure failed.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// Serialising `reproduce.json` failed.
    #[error("reproduce.json: {0}")]
    Json(String),
}

/// Everything computed.
#[derive(Clone, Debug)]
pub struct Reproduction {
    /// The options it was computed with.
    pub options: Options,
    /// Grid, window and classifier of the diagrams.
    pub diagram_settings: DiagramSettings,
    /// Run lengths of the response examples.
    pub response_settings: ResponseSettings,
    /// The diagrams: each figure's [`Variant::Paper`] diagram, then the
    /// variants of the investigated figures, in figure then variant order.
    pub diagrams: Vec<Diagram>,
    /// The response examples, in figure order.
    pub responses: Vec<ResponseExample>,
    /// The response examples recomputed with impact-law variants, in
    /// figure then variant order.
    pub response_variants: Vec<ResponseVariant>,
    /// Lyapunov scans along diagrams.
    pub scans: Vec<Scan>,
    /// For each investigated figure's preset diagram: when each tumbled
    /// value tumbled, `(A_v, τ)`.
    pub tumbles: Vec<(u32, Vec<(f64, f64)>)>,
    /// For each investigated figure's preset diagram: the neighbouring runs
    /// (A_v·(1 + k·10⁻⁹)) of its tumbled values in the paper's last range.
    pub survivals: Vec<(u32, diagrams::Neighbours)>,
    /// Wall time of the computation, s.
    pub wall_s: f64,
    /// Summed wall times of the parts (diagrams, response examples with
    /// their variants, then the Lyapunov scan, tumble times and
    /// neighbouring runs), s; they overlap in parallel, so
    /// they add up to more than `wall_s` on several threads.
    pub part_s: [f64; 3],
}

impl Reproduction {
    /// The diagram of `figure` with the paper's own impact law (eqs.
    /// 17–27, e = 0; see [`paper_law`]).
    pub(crate) fn paper_law_diagram(&self, figure: u32) -> Option<&Diagram> {
        let d = self.diagram(figure, Variant::Paper)?;
        self.diagram(figure, paper_law(&d.config))
    }

    /// The diagram of `figure` computed with `variant`.
    pub fn diagram(&self, figure: u32, variant: Variant) -> Option<&Diagram> {
        self.diagrams
            .iter()
            .find(|d| d.figure == figure && d.variant == variant)
    }

    /// The response example of `figure`.
    pub fn response(&self, figure: u32) -> Option<&ResponseExample> {
        self.responses.iter().find(|r| r.figure == figure)
    }

    /// The Lyapunov scan of `figure`.
    pub fn scan(&self, figure: u32) -> Option<&Scan> {
        self.scans.iter().find(|s| s.figure == figure)
    }

    /// The impact-law variants of `figure`'s response example.
    pub fn response_variants(&self, figure: u32) -> Vec<&ResponseVariant> {
        self.response_variants.iter().filter(|r| r.figure == figure).collect()
    }

    /// The neighbouring runs of `figure`'s tumbled values.
    pub(crate) fn survivals(&self, figure: u32) -> Option<&diagrams::Neighbours> {
        self.survivals.iter().find(|t| t.0 == figure).map(|t| &t.1)
    }

    /// The tumble times of `figure`'s preset diagram.
    pub fn tumbles(&self, figure: u32) -> Option<&[(f64, f64)]> {
        self.tumbles.iter().find(|t| t.0 == figure).map(|t| t.1.as_slice())
    }

    /// The diagrams of `figure`'s impact-ratio scan, with the preset's,
    /// Housner's and the printed eq. 20's, in increasing r: `(r, diagram)`.
    pub(crate) fn ratio_scan(&self, figure: u32) -> Vec<(f64, &Diagram)> {
        let mut out: Vec<(f64, &Diagram)> = self
            .diagrams
            .iter()
            .filter(|d| d.figure == figure)
            .filter_map(|d| match d.variant {
                Variant::Paper | Variant::Housner | Variant::PrintedEq20 | Variant::ImpactRatio(_) => {
                    let r = d.config.geometry().housner_r();
                    let law = d.config.impact.law;
                    Some((
                        if law == LawKind::Housner {
                            r
                        } else {
                            d.config.impact_r()
                        },
                        d,
                    ))
                }
                Variant::Ralston
                | Variant::ContinuationUp
                | Variant::TumbleAtSide
                | Variant::FlightStop
                | Variant::ImpulseLaw => None,
            })
            .collect();
        out.sort_by(|a, b| a.0.total_cmp(&b.0));
        out
    }
}

/// One unit of work.
#[derive(Clone, Copy, Debug)]
enum Job {
    Diagram(&'static PaperFigure, Variant),
    Response(&'static PaperFigure),
    ResponseVariant(&'static PaperFigure, Variant),
}

enum Done {
    Diagram(Box<Diagram>),
    Response(Box<ResponseExample>),
    ResponseVariant(Box<ResponseVariant>),
}

/// The preset configuration of `f`.
fn config_of(f: &PaperFigure) -> Result<Scenario, ReproduceError> {
    crate::io::config::load(Some(f.preset), None, &[]).map_err(|e| ReproduceError::Figure {
        figure: f.number,
        what: "configuration".to_string(),
        error: e.to_string(),
    })
}

/// The paper's own impact law (its eqs. 17–27 with e = 0) as a variant of
/// `cfg`: [`Variant::ImpulseLaw`] where the block can slide, and
/// [`Variant::Housner`] (the same law without slip) where it cannot.
pub(crate) fn paper_law(cfg: &Scenario) -> Variant {
    if cfg.block.mu_s.is_finite() {
        Variant::ImpulseLaw
    } else {
        Variant::Housner
    }
}

/// The jobs of `options`: continuation sweeps first (they are sequential,
/// so they should not be the last to start), then every other diagram,
/// then the response examples and their variants.
fn jobs(options: &Options) -> Result<Vec<Job>, ReproduceError> {
    let wanted: Vec<&'static PaperFigure> = FIGURES.iter().filter(|f| options.wants(f.number)).collect();
    let mut slow = Vec::new();
    let mut rest = Vec::new();
    for f in &wanted {
        match f.kind {
            FigureKind::Bifurcation => {
                rest.push(Job::Diagram(f, Variant::Paper));
                if INVESTIGATED.contains(&f.number) {
                    for v in Variant::INVESTIGATION {
                        if v == Variant::ContinuationUp {
                            slow.push(Job::Diagram(f, v));
                        } else {
                            rest.push(Job::Diagram(f, v));
                        }
                    }
                    for r in R_SCAN {
                        rest.push(Job::Diagram(f, Variant::ImpactRatio(r)));
                    }
                } else {
                    // Every diagram also with the paper's own impact law
                    // (eqs. 17–27, e = 0), which is Housner's without
                    // sliding; the investigated figures have it already.
                    let cfg = config_of(f)?;
                    rest.push(Job::Diagram(f, paper_law(&cfg)));
                }
            }
            FigureKind::Response => {
                rest.push(Job::Response(f));
                let cfg = config_of(f)?;
                for v in response_variants(&cfg) {
                    rest.push(Job::ResponseVariant(f, v));
                }
            }
        }
    }
    slow.extend(rest);
    Ok(slow)
}

/// Computes every wanted figure on the current rayon pool; `progress`
/// advances once per diagram, response example and scan.
pub fn reproduce(options: &Options, progress: &ProgressFn<'_>) -> Result<Reproduction, ReproduceError> {
    if let Some(only) = &options.only
        && let Some(bad) = only.iter().find(|n| paper::figure(**n).is_none())
    {
        return Err(ReproduceError::Options(format!(
            "--only: Fig. {bad} is not one of the paper's Figs. 3–19"
        )));
    }
    let start = std::time::Instant::now();
    let diagram_settings = DiagramSettings {
        grid: options.grid()?,
        window: Window::default(),
        classify: ClassifyOptions::default(),
    };
    let response_settings = options.response_settings();
    let classify = diagram_settings.classify;
    let jobs = jobs(options)?;
    progress(Progress::Total(jobs.len() as u64 + u64::from(options.wants(SCANNED))));
    let done = jobs
        .par_iter()
        .map(|job| {
            let out = match *job {
                Job::Diagram(f, v) => run_diagram(f, v, &diagram_settings).map(|d| Done::Diagram(Box::new(d))),
                Job::Response(f) => run_response(f, &response_settings, &classify).map(|r| Done::Response(Box::new(r))),
                Job::ResponseVariant(f, v) => run_response_variant(f, v, &response_settings, &classify)
                    .map(|r| Done::ResponseVariant(Box::new(r))),
            };
            progress(Progress::Done);
            out
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut diagrams = Vec::new();
    let mut responses = Vec::new();
    let mut variants = Vec::new();
    for d in done {
        match d {
            Done::Diagram(d) => diagrams.push(*d),
            Done::Response(r) => responses.push(*r),
            Done::ResponseVariant(r) => variants.push(*r),
        }
    }
    let variant_index = |v: Variant| {
        std::iter::once(Variant::Paper)
            .chain(Variant::INVESTIGATION)
            .chain([Variant::ImpulseLaw])
            .chain(R_SCAN.map(Variant::ImpactRatio))
            .position(|x| x == v)
            .unwrap_or(usize::MAX)
    };
    diagrams.sort_by_key(|d| (d.variant != Variant::Paper, d.figure, variant_index(d.variant)));
    responses.sort_by_key(|r| r.figure);
    // Jobs were collected in order, so the variants already are in figure
    // then variant order.

    let part_s = [
        diagrams.iter().map(|d| d.wall_s).sum(),
        responses.iter().map(|r| r.wall_s).sum::<f64>() + variants.iter().map(|r| r.wall_s).sum::<f64>(),
        0.0,
    ];
    let after = std::time::Instant::now();
    let mut scans = Vec::new();
    if let Some(d) = diagrams
        .iter()
        .find(|d| d.figure == SCANNED && d.variant == Variant::Paper)
    {
        scans.push(lyapunov_scan(
            d,
            options.scan_window(),
            if options.quick { 4 } else { 8 },
        )?);
        progress(Progress::Done);
    }
    let tumbles = diagrams
        .iter()
        .filter(|d| INVESTIGATED.contains(&d.figure) && d.variant == Variant::Paper)
        .map(|d| tumble_times(d).map(|t| (d.figure, t)))
        .collect::<Result<Vec<_>, _>>()?;
    let neighbours = if options.quick { 2 } else { 8 };
    let survivals = diagrams
        .iter()
        .filter(|d| INVESTIGATED.contains(&d.figure) && d.variant == Variant::Paper)
        .filter_map(|d| {
            let last = paper::figure(d.figure)?.ranges.last()?;
            Some(tumbled_neighbours(d, last.from, last.to, neighbours).map(|t| (d.figure, t)))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Reproduction {
        options: options.clone(),
        diagram_settings,
        response_settings,
        diagrams,
        responses,
        response_variants: variants,
        scans,
        tumbles,
        survivals,
        wall_s: start.elapsed().as_secs_f64(),
        part_s: [part_s[0], part_s[1], after.elapsed().as_secs_f64()],
    })
}
