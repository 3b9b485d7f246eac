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
//!   ([`diagrams::Variant`]). They change the configuration only, never
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
pub mod paper;
pub mod report;
pub mod response;
pub mod scan;
pub mod write;

use indicatif::ProgressBar;
use rayon::prelude::*;

use crate::analysis::classify::ClassifyOptions;
use crate::analysis::orbit_diagram::Grid;
use crate::analysis::steady::Window;
use crate::io::output::OutputError;
use crate::plot::PlotError;
use diagrams::{Diagram, DiagramSettings, Variant, run_diagram};
use paper::{FIGURES, FigureKind, PaperFigure};
use response::{ResponseExample, ResponseSettings, run_response};
use scan::{Scan, lyapunov_scan};

/// The figures whose diagrams are investigated with the variants: the
/// paper's Figs. 3 and 4, the only ones for which it gives mode ranges.
pub const INVESTIGATED: [u32; 2] = [3, 4];

/// The figure whose diagram gets a Lyapunov scan: Fig. 10, whose quoted
/// exponent (0.51) the paper gives without its A_v.
pub const SCANNED: u32 = 10;

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
        Grid::new(0.0, 3.0, step).map_err(|e| ReproduceError::Options(e.0))
    }

    /// The response run lengths.
    pub fn response_settings(&self) -> ResponseSettings {
        if self.quick {
            ResponseSettings::quick()
        } else {
            ResponseSettings::full()
        }
    }

    /// The Lyapunov scan window, τ: (600, 1600) or (200, 500) quick.
    pub fn scan_window(&self) -> (f64, f64) {
        if self.quick { (200.0, 500.0) } else { (600.0, 1600.0) }
    }

    /// Whether figure `number` is computed.
    pub fn wants(&self, number: u32) -> bool {
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
    /// Lyapunov scans along diagrams.
    pub scans: Vec<Scan>,
    /// Wall time of the computation, s.
    pub wall_s: f64,
}

impl Reproduction {
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
}

/// One unit of work.
#[derive(Clone, Copy, Debug)]
enum Job {
    Diagram(&'static PaperFigure, Variant),
    Response(&'static PaperFigure),
}

enum Done {
    Diagram(Box<Diagram>),
    Response(Box<ResponseExample>),
}

/// The jobs of `options`: continuation sweeps first (they are sequential,
/// so they should not be the last to start), then every other diagram,
/// then the response examples.
fn jobs(options: &Options) -> Vec<Job> {
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
                }
            }
            FigureKind::Response => rest.push(Job::Response(f)),
        }
    }
    slow.extend(rest);
    slow
}

/// Computes every wanted figure on the current rayon pool; `progress`
/// advances once per diagram, response example and scan.
pub fn reproduce(options: &Options, progress: &ProgressBar) -> Result<Reproduction, ReproduceError> {
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
    let jobs = jobs(options);
    progress.set_length(jobs.len() as u64 + u64::from(options.wants(SCANNED)));
    let done = jobs
        .par_iter()
        .map(|job| {
            let out = match *job {
                Job::Diagram(f, v) => run_diagram(f, v, &diagram_settings).map(|d| Done::Diagram(Box::new(d))),
                Job::Response(f) => {
                    run_response(f, &response_settings, &classify).map(|r| Done::Response(Box::new(r)))
                }
            };
            progress.inc(1);
            out
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut diagrams = Vec::new();
    let mut responses = Vec::new();
    for d in done {
        match d {
            Done::Diagram(d) => diagrams.push(*d),
            Done::Response(r) => responses.push(*r),
        }
    }
    let variant_index = |v: Variant| {
        std::iter::once(Variant::Paper)
            .chain(Variant::INVESTIGATION)
            .position(|x| x == v)
            .unwrap_or(usize::MAX)
    };
    diagrams.sort_by_key(|d| (d.variant != Variant::Paper, d.figure, variant_index(d.variant)));
    responses.sort_by_key(|r| r.figure);

    let mut scans = Vec::new();
    if let Some(d) = diagrams
        .iter()
        .find(|d| d.figure == SCANNED && d.variant == Variant::Paper)
    {
        scans.push(lyapunov_scan(d, options.scan_window(), if options.quick { 4 } else { 8 })?);
        progress.inc(1);
    }
    Ok(Reproduction {
        options: options.clone(),
        diagram_settings,
        response_settings,
        diagrams,
        responses,
        scans,
        wall_s: start.elapsed().as_secs_f64(),
    })
}
