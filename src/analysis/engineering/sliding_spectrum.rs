//! The sliding spectrum: one ground motion, a range of friction
//! coefficients μ; per μ the peak and the residual (final) sliding
//! displacement of two blocks:
//!
//! - the **slide-only** block, which cannot rock: rigid-plastic sliding
//!   (Newmark 1965), the sliding-block displacement engineers read off
//!   OpenSeismoMatlab and the geotechnical literature;
//! - the **given** block (its width and height), which may rock, slide,
//!   slide-rock, overturn or fly, as every other run of the crate.
//!
//! How the slide-only block is realised, and why it is exact: it is the
//! crate's own block model with the half-diagonal R of the given block and
//! the slenderness B/H = [`SLIDE_ONLY_B_OVER_H`] (tan α = 1000). From rest
//! the block lifts only when |a_h| > g tan α (paper eq. 1, no vertical
//! motion here), and a block sliding flat tips only when μ_k > tan α
//! (docs/model.md §5); [`SlidingSpec::check`] refuses any motion whose
//! peak reaches g tan α and any μ_k that reaches tan α, so neither guard
//! can ever fire. What is left are the modes rest and slide, whose
//! equations are exactly the rigid-plastic block's:
//! ẍ = −a_h(t) ∓ μ_k g while it slides, stick when the relative velocity
//! returns to zero, slip again when |a_h| > μ_s g. Neither the block's
//! width nor its height enters them (only R, through the time unit 1/p),
//! so the answer is the slide-only answer itself, not an approximation
//! of it by a squat block.
//!
//! Contract:
//! - Friction per run: μ_s = μ, μ_k = `kinetic_ratio`·μ (1 by default:
//!   one coefficient, as sliding-block analyses assume); the impact's
//!   friction follows the block's unless the base sets its own.
//! - Displacements in metres, signed +x (to the right), the base-relative
//!   displacement caused by slip (`Geometry::sliding`, rocking alone adds
//!   none). The peak is exact: slip keeps one direction between events.
//! - The residual of a block that overturned or flew does not exist
//!   (`None`); its peak is the peak before that event.
//! - Runs go in parallel and are collected by index: the result does not
//!   depend on the number of threads. No NaN leaves this module.

use rayon::prelude::*;

use super::response::{BlockSize, Drive, EndState, ResponseError, scenario_for};
use crate::analysis::field::{FieldNames, RequestField, show};
use crate::analysis::{Progress, ProgressFn};
use crate::sim::{Scenario, ScenarioError, simulate};

/// B/H of the slide-only block: tan α = 1000, far above any ground motion
/// (the strongest recorded PGAs are 3–4 g) and any friction coefficient,
/// so that neither uplift nor tipping can happen (see the module docs).
pub(crate) const SLIDE_ONLY_B_OVER_H: f64 = 1000.0;

/// Most friction coefficients of one spectrum.
pub(crate) const MAX_MU: usize = 100_000;

/// A sliding displacement below this (m) is round-off of a block that did
/// not slip: the sliding displacement of a rocking block is computed from
/// x and θ, whose rounding leaves about 1e-16 R. A nanometre is far below
/// anything an engineer measures and far above that rounding.
pub(crate) const NO_SLIDING_M: f64 = 1e-9;

/// Which of the two blocks of a sliding spectrum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BlockKind {
    /// The block that cannot rock: rigid-plastic sliding.
    SlideOnly,
    /// The given block, which may also rock.
    Given,
}

impl BlockKind {
    /// Both, in output order.
    pub const ALL: [BlockKind; 2] = [BlockKind::SlideOnly, BlockKind::Given];

    /// Output name: `slide-only` or `block`.
    pub fn name(self) -> &'static str {
        match self {
            BlockKind::SlideOnly => "slide-only",
            BlockKind::Given => "block",
        }
    }
}

/// What to compute.
#[derive(Clone, Debug)]
pub struct SlidingSpec<'a> {
    /// Impact law, tolerances, overturning angle, record tail; its block,
    /// friction and excitation are replaced.
    pub base: &'a Scenario,
    /// The ground motion: a record or a pulse in physical units.
    pub drive: &'a Drive,
    /// Its scale factor (1 plays it as given), > 0.
    pub scale: f64,
    /// The given block.
    pub block: BlockSize,
    /// Static friction coefficients μ_s, each finite and > 0, increasing.
    pub mu: Vec<f64>,
    /// μ_k/μ_s, in (0, 1]. Default 1.
    pub kinetic_ratio: f64,
}

/// A spectrum that cannot be computed as asked.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SlidingSpecError {
    /// A friction coefficient is not finite and > 0, or they do not
    /// increase, or there are none or too many.
    #[error("friction coefficients: {0}")]
    Mu(String),
    /// μ_k/μ_s is not in (0, 1].
    #[error("kinetic ratio {0}: must be in (0, 1] (μ_k ≤ μ_s)")]
    KineticRatio(f64),
    /// The motion is a normalised pulse, whose amplitude follows each
    /// block's slenderness: the two blocks would feel different motions.
    #[error("a normalised pulse scales with each block's slenderness; give a record or a pulse in g")]
    NormalisedPulse,
    /// The motion's PGA (g) reaches tan α of the slide-only block
    /// ([`SLIDE_ONLY_B_OVER_H`]), which could then lift.
    #[error("PGA {0} g reaches tan α = 1000 of the slide-only block, which could then lift")]
    MotionTooStrong(f64),
    /// A μ_k reaches tan α of the slide-only block, which could then tip.
    #[error("μ_k = {0} reaches tan α = 1000 of the slide-only block, which could then tip")]
    FrictionTooLarge(f64),
    /// A block's scenario is invalid.
    #[error("{kind} block: {error}", kind = kind.name())]
    Scenario {
        /// Which block.
        kind: BlockKind,
        /// What is wrong.
        error: ScenarioError,
    },
}

impl SlidingSpecError {
    /// The error in the words of a surface (its names of the inputs).
    pub fn render(&self, names: &impl FieldNames<RequestField>) -> String {
        match self {
            SlidingSpecError::Mu(m) => format!("{}: {m}", names.name(RequestField::Mu)),
            SlidingSpecError::KineticRatio(r) => format!(
                "{}: must be in (0, 1] (μ_k ≤ μ_s)",
                names.valued(RequestField::KineticRatio, &show(*r))
            ),
            SlidingSpecError::FrictionTooLarge(mu_k) => format!(
                "{}: μ_k = {} reaches {}, where the block that cannot rock could tip; give coefficients below it",
                names.name(RequestField::Mu),
                show(*mu_k),
                show(SLIDE_ONLY_B_OVER_H)
            ),
            SlidingSpecError::MotionTooStrong(pga) => format!(
                "{}/{}: PGA {} g reaches {} g, where the block that cannot rock could lift; give a smaller scale",
                names.name(RequestField::Scale),
                names.name(RequestField::Pga),
                show(*pga),
                show(SLIDE_ONLY_B_OVER_H)
            ),
            SlidingSpecError::NormalisedPulse | SlidingSpecError::Scenario { .. } => self.to_string(),
        }
    }
}

/// One block's answer at one μ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlidingResponse {
    /// How the run ended.
    pub end: EndState,
    /// Largest |sliding displacement|, m (up to overturning or flight
    /// when it ended so).
    pub peak_sliding_m: f64,
    /// Sliding displacement at the end of the run, m, signed (+x to the
    /// right); `None` when the block overturned or flew.
    pub residual_sliding_m: Option<f64>,
    /// Peak |θ|/α (0 for the slide-only block).
    pub peak_theta_over_alpha: f64,
    /// Time of overturning or flight, s.
    pub t_end_event_s: Option<f64>,
}

/// Both blocks at one friction coefficient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlidingPoint {
    /// μ_s.
    pub mu_s: f64,
    /// μ_k.
    pub mu_k: f64,
    /// The block that cannot rock.
    pub slide_only: SlidingResponse,
    /// The given block.
    pub block: SlidingResponse,
}

impl SlidingPoint {
    /// The answer of block `kind`.
    pub fn of(&self, kind: BlockKind) -> &SlidingResponse {
        match kind {
            BlockKind::SlideOnly => &self.slide_only,
            BlockKind::Given => &self.block,
        }
    }
}

/// A run of the spectrum that failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{kind} block, μ = {mu}: {error}", kind = kind.name())]
pub struct SlidingError {
    /// Which block.
    pub kind: BlockKind,
    /// Its μ_s.
    pub mu: f64,
    /// What failed.
    pub error: ResponseError,
}

impl SlidingSpec<'_> {
    /// The slide-only block: the given block's half-diagonal at B/H =
    /// [`SLIDE_ONLY_B_OVER_H`].
    pub(crate) fn slide_only_block(&self) -> BlockSize {
        BlockSize::from_half_diagonal(self.block.half_diagonal_m(), SLIDE_ONLY_B_OVER_H)
    }

    /// The block of `kind`.
    pub(crate) fn block_of(&self, kind: BlockKind) -> BlockSize {
        match kind {
            BlockKind::SlideOnly => self.slide_only_block(),
            BlockKind::Given => self.block,
        }
    }

    /// μ_k of μ_s = `mu`.
    pub fn kinetic(&self, mu: f64) -> f64 {
        if self.kinetic_ratio == 1.0 {
            mu
        } else {
            self.kinetic_ratio * mu
        }
    }

    /// Peak ground acceleration of the motion as run (scaled), g.
    pub fn pga_g(&self) -> Option<f64> {
        match self.drive {
            Drive::Record(r) | Drive::Paired { horizontal: r, .. } => Some(r.series.peaks(self.scale).pga_g),
            Drive::PhysicalPulse { a_p_g, .. } => Some(self.scale * a_p_g),
            Drive::NormalisedPulse { .. } => None,
        }
    }

    /// Checks everything before anything runs: the coefficients, the ratio,
    /// the motion, and every run's scenario (so a failure names its block).
    pub fn check(&self) -> Result<(), SlidingSpecError> {
        let mu_err = |m: String| Err(SlidingSpecError::Mu(m));
        if self.mu.is_empty() || self.mu.len() > MAX_MU {
            return mu_err(format!("give 1 to {MAX_MU}"));
        }
        if let Some(m) = self.mu.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
            return mu_err(format!("{m} is not a finite number > 0"));
        }
        if let Some(w) = self.mu.windows(2).find(|w| w[1] <= w[0]) {
            return mu_err(format!("must increase ({} then {})", w[0], w[1]));
        }
        if !(self.kinetic_ratio > 0.0 && self.kinetic_ratio <= 1.0) {
            return Err(SlidingSpecError::KineticRatio(self.kinetic_ratio));
        }
        let pga = self.pga_g().ok_or(SlidingSpecError::NormalisedPulse)?;
        if pga >= SLIDE_ONLY_B_OVER_H {
            return Err(SlidingSpecError::MotionTooStrong(pga));
        }
        let mu_k_max = self.mu.iter().map(|&m| self.kinetic(m)).fold(0.0, f64::max);
        if mu_k_max >= SLIDE_ONLY_B_OVER_H {
            return Err(SlidingSpecError::FrictionTooLarge(mu_k_max));
        }
        for kind in BlockKind::ALL {
            for &mu in &self.mu {
                self.scenario(kind, mu)
                    .map_err(|error| SlidingSpecError::Scenario { kind, error })?;
            }
        }
        Ok(())
    }

    /// The scenario of block `kind` at μ_s = `mu`.
    pub fn scenario(&self, kind: BlockKind, mu: f64) -> Result<Scenario, ScenarioError> {
        let mut base = self.base.clone();
        base.block.mu_s = mu;
        base.block.mu_k = Some(self.kinetic(mu));
        scenario_for(&base, self.block_of(kind), self.drive, self.scale)
    }

    /// Runs block `kind` at μ_s = `mu`.
    pub(crate) fn respond(&self, kind: BlockKind, mu: f64) -> Result<SlidingResponse, ResponseError> {
        let s = self.scenario(kind, mu)?;
        let geo = s.geometry();
        let r = simulate(s.model()?, &s.initial, &s.run_options())?;
        let (end, event_tau) = (r.end_state(), r.end_event_tau());
        Ok(SlidingResponse {
            end,
            peak_sliding_m: r.max_abs_sliding * geo.r,
            residual_sliding_m: end.survived().then_some(r.final_sliding * geo.r),
            peak_theta_over_alpha: r.max_abs_theta,
            t_end_event_s: event_tau.map(|tau| tau / geo.p),
        })
    }
}

/// Runs the spectrum (call [`SlidingSpec::check`] first for errors that
/// name the input); progress counts runs, two per μ.
pub fn sliding_spectrum(spec: &SlidingSpec<'_>, progress: &ProgressFn<'_>) -> Result<Vec<SlidingPoint>, SlidingError> {
    let runs: Vec<(BlockKind, f64)> = BlockKind::ALL
        .iter()
        .flat_map(|&kind| spec.mu.iter().map(move |&mu| (kind, mu)))
        .collect();
    progress(Progress::Total(runs.len() as u64));
    let done: Vec<SlidingResponse> = runs
        .par_iter()
        .map(|&(kind, mu)| {
            let r = spec
                .respond(kind, mu)
                .map_err(|error| SlidingError { kind, mu, error })?;
            progress(Progress::Done);
            Ok(r)
        })
        .collect::<Result<_, SlidingError>>()?;
    let (slide_only, block) = done.split_at(spec.mu.len());
    Ok(spec
        .mu
        .iter()
        .zip(slide_only.iter().zip(block))
        .map(|(&mu_s, (&slide_only, &block))| SlidingPoint {
            mu_s,
            mu_k: spec.kinetic(mu_s),
            slide_only,
            block,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant acceleration `a_g` (g) for `dur_s`, then 0, sampled
    /// every 10 ms.
    fn step_record(a_g: f64, dur_s: f64) -> Drive {
        let n = (dur_s / 0.01).round() as usize;
        let t: Vec<f64> = (0..=n + 1).map(|i| i as f64 * 0.01).collect();
        let a: Vec<f64> = (0..=n + 1).map(|i| if i <= n { a_g } else { 0.0 }).collect();
        super::super::test_record("step.txt", t, a)
    }

    #[test]
    fn a_stocky_block_slides_like_the_slide_only_block_and_friction_above_the_pga_stops_both() {
        // A 0.3 g ramp-held record on a stocky block (B/H = 1, tan α = 1):
        // the block cannot rock either (0.3 g < g tan α and μ < tan α), so
        // both blocks are the same rigid-plastic slider; at μ = 0.5 > 0.3
        // neither slips.
        let base = Scenario::default();
        let drive = step_record(0.3, 0.5);
        let spec = SlidingSpec {
            base: &base,
            drive: &drive,
            scale: 1.0,
            block: BlockSize {
                width_m: 1.0,
                height_m: 1.0,
            },
            mu: vec![0.1, 0.2, 0.5],
            kinetic_ratio: 1.0,
        };
        spec.check().unwrap();
        let points = sliding_spectrum(&spec, &crate::analysis::silent).unwrap();
        assert_eq!(points.len(), 3);
        for p in &points[..2] {
            let (a, b) = (p.slide_only, p.block);
            assert!(a.peak_sliding_m > 0.01, "{p:?}");
            assert!(
                (a.peak_sliding_m - b.peak_sliding_m).abs() < 1e-9 * a.peak_sliding_m,
                "{p:?}"
            );
            assert_eq!(b.peak_theta_over_alpha, 0.0);
            assert_eq!(a.end, EndState::Rest);
        }
        assert!(points[0].slide_only.peak_sliding_m > points[1].slide_only.peak_sliding_m);
        assert_eq!(points[2].slide_only.peak_sliding_m, 0.0);
        assert_eq!(points[2].slide_only.residual_sliding_m, Some(0.0));
    }

    #[test]
    fn bad_coefficients_ratios_and_motions_are_refused() {
        let base = Scenario::default();
        let drive = step_record(0.3, 0.5);
        let spec = |mu: Vec<f64>, ratio: f64, drive: &Drive| {
            SlidingSpec {
                base: &base,
                drive,
                scale: 1.0,
                block: BlockSize {
                    width_m: 0.4,
                    height_m: 1.8,
                },
                mu,
                kinetic_ratio: ratio,
            }
            .check()
        };
        assert!(matches!(spec(vec![], 1.0, &drive), Err(SlidingSpecError::Mu(_))));
        assert!(matches!(
            spec(vec![0.2, 0.1], 1.0, &drive),
            Err(SlidingSpecError::Mu(_))
        ));
        assert!(matches!(spec(vec![0.0], 1.0, &drive), Err(SlidingSpecError::Mu(_))));
        assert!(matches!(
            spec(vec![0.2], 1.5, &drive),
            Err(SlidingSpecError::KineticRatio(_))
        ));
        assert!(matches!(
            spec(vec![2000.0], 1.0, &drive),
            Err(SlidingSpecError::FrictionTooLarge(_))
        ));
        let normalised = Drive::NormalisedPulse {
            shape: crate::sim::scenario::ShapeKind::OneSine,
            cycles: 1,
            omega_ratio: 2.0,
        };
        assert_eq!(
            spec(vec![0.2], 1.0, &normalised),
            Err(SlidingSpecError::NormalisedPulse)
        );
        assert_eq!(spec(vec![0.1, 0.6], 0.8, &drive), Ok(()));
    }
}
