//! Fragility of blocks under a suite of records: each record scaled to
//! each intensity level (PGA or PGV), each block run under each; per block
//! and level the fraction overturned and the fraction whose peak rotation
//! reached a threshold θ/α, and lognormal curves fitted to both
//! ([`lognormal`](super::lognormal)).
//!
//! The runs are indexed (block outer, level, record inner) so that a
//! subset — a shard of a cluster array job — can be computed apart and the
//! results joined by index; [`summarise`] and [`fit_block`] take plain
//! run outcomes, so a merge of shards computes the same numbers as one run.
//! Runs that ended in flight are counted but left out of both fractions'
//! denominators: their fate is not computed.

use rayon::prelude::*;

use super::lognormal::{self, FitError, LevelCount, LognormalFit};
use super::response::{BlockResponse, BlockSize, Drive, EndState, ResponseError, respond, scenario_for};
use crate::analysis::{Progress, ProgressFn};
use crate::model::excitation::record::Series;
use crate::model::oscillator::pseudo_acceleration;
use crate::sim::{Scenario, ScenarioError};

/// Most runs (blocks × levels × records) of one fragility study.
pub(crate) const MAX_RUNS: usize = 10_000_000;

/// The intensity measure the records are scaled to.
///
/// PGA and PGV are the ground motion's own; the two rocking measures of
/// Dimitrakopoulos & Paraskeva (2015, EESD 44:2015) are dimensionless and
/// depend on the block: PGA/(g tan α) is the PGA in units of the uplift
/// acceleration (1 = the static uplift threshold), PGV·p/(g tan α) the PGV
/// in units of the velocity scale g tan α / p of rocking. Across blocks of
/// different size and slenderness they gather the curves, which is why
/// the literature prefers them for rocking fragility.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Intensity {
    /// Peak ground acceleration, g.
    #[serde(rename = "pga")]
    Pga,
    /// Peak ground velocity, m/s.
    #[serde(rename = "pgv")]
    Pgv,
    /// PGA/(g tan α), dimensionless.
    #[serde(rename = "pga-tan-alpha")]
    PgaTanAlpha,
    /// PGV·p/(g tan α), dimensionless.
    #[serde(rename = "pgv-p-tan-alpha")]
    PgvPTanAlpha,
    /// Sa(T, 5 %), the pseudo-spectral acceleration of the record at the
    /// study's period T ([`FragilitySpec`]'s caller states it), g.
    #[serde(rename = "sa")]
    Sa,
}

/// Damping ratio of the Sa intensity measure: 5 % of critical, the
/// convention of design spectra and ground-motion models, so that a
/// fragility in Sa(T, 5 %) reads against a hazard curve in the same
/// measure.
pub(crate) const SA_DAMPING: f64 = 0.05;

impl Intensity {
    /// Name with unit, as in the outputs' columns: `pga_g`, `pgv_m_s`,
    /// `pga_over_g_tan_alpha`, `pgv_p_over_g_tan_alpha`.
    pub fn column(self) -> &'static str {
        match self {
            Intensity::Pga => "pga_g",
            Intensity::Pgv => "pgv_m_s",
            Intensity::PgaTanAlpha => "pga_over_g_tan_alpha",
            Intensity::PgvPTanAlpha => "pgv_p_over_g_tan_alpha",
            Intensity::Sa => "sa_g",
        }
    }

    /// Axis label with unit.
    pub fn label(self) -> &'static str {
        match self {
            Intensity::Pga => "PGA (g)",
            Intensity::Pgv => "PGV (m/s)",
            Intensity::PgaTanAlpha => "PGA / (g tan α)",
            Intensity::PgvPTanAlpha => "PGV · p / (g tan α)",
            Intensity::Sa => "Sa(T, 5 %) (g)",
        }
    }

    /// Axis label with unit and, for Sa, the period `sa_period_s` (s).
    pub(crate) fn label_at(self, sa_period_s: Option<f64>) -> String {
        match (self, sa_period_s) {
            (Intensity::Sa, Some(t)) => format!("Sa(T = {t} s, 5 %) (g)"),
            _ => self.label().to_string(),
        }
    }

    /// Unit for text (empty when dimensionless).
    pub fn unit(self) -> &'static str {
        match self {
            Intensity::Pga | Intensity::Sa => "g",
            Intensity::Pgv => "m/s",
            Intensity::PgaTanAlpha | Intensity::PgvPTanAlpha => "",
        }
    }

    /// The record's own value this measure is built on, at scale 1: its
    /// PGA in g, its PGV in m/s, or its Sa(T, 5 %) in g at the period
    /// `sa_period_s` (s; `None` for Sa without a period, or a period the
    /// oscillator refuses). `series` is the (horizontal) record.
    pub(crate) fn record_value(self, series: &Series, sa_period_s: Option<f64>) -> Option<f64> {
        match self {
            Intensity::Pga | Intensity::PgaTanAlpha => Some(series.peak_abs_g()),
            Intensity::Pgv | Intensity::PgvPTanAlpha => Some(series.peaks(1.0).pgv_m_s),
            Intensity::Sa => pseudo_acceleration(series, 1.0, sa_period_s?, SA_DAMPING),
        }
    }

    /// The factor that turns [`record_value`](Self::record_value) into
    /// this measure for `block`: 1 for PGA and PGV, 1/tan α for PGA/(g tan
    /// α) (the PGA is already in g), p/(g tan α) for PGV·p/(g tan α).
    pub(crate) fn block_factor(self, block: BlockSize) -> f64 {
        let tan_alpha = block.width_m / block.height_m;
        match self {
            Intensity::Pga | Intensity::Pgv | Intensity::Sa => 1.0,
            Intensity::PgaTanAlpha => 1.0 / tan_alpha,
            Intensity::PgvPTanAlpha => block.p_per_s() / (crate::model::geometry::G * tan_alpha),
        }
    }

    /// Whether the measure depends on the block (the dimensionless ones).
    pub(crate) fn per_block(self) -> bool {
        matches!(self, Intensity::PgaTanAlpha | Intensity::PgvPTanAlpha)
    }
}

/// One record of the suite.
#[derive(Clone, Debug, PartialEq)]
pub struct SuiteRecord {
    /// The record (a [`Drive::Record`]).
    pub drive: Drive,
    /// The value the study's [`Intensity`] is built on, as recorded
    /// (scale 1), > 0: [`Intensity::record_value`].
    pub intensity: f64,
}

/// What to compute.
#[derive(Clone, Debug)]
pub struct FragilitySpec<'a> {
    /// Friction, impact law, tolerances, overturning angle.
    pub base: &'a Scenario,
    /// The records.
    pub records: &'a [SuiteRecord],
    /// Intensity levels, > 0, in the unit of the intensity measure.
    pub levels: &'a [f64],
    /// The blocks.
    pub blocks: &'a [BlockSize],
    /// The intensity measure of the levels.
    pub im: Intensity,
}

/// Where run `index` sits: (block, level, record).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunIndex {
    /// Block number.
    pub block: usize,
    /// Level number.
    pub level: usize,
    /// Record number.
    pub record: usize,
}

impl FragilitySpec<'_> {
    /// Number of runs.
    pub fn run_count(&self) -> usize {
        self.blocks.len() * self.levels.len() * self.records.len()
    }

    /// The position of run `i` (< [`run_count`](Self::run_count)).
    pub fn index(&self, i: usize) -> RunIndex {
        let (nl, nr) = (self.levels.len(), self.records.len());
        RunIndex {
            block: i / (nl * nr),
            level: (i / nr) % nl,
            record: i % nr,
        }
    }

    /// The scale factor of a run: level / the record's own intensity for
    /// that block.
    pub fn scale(&self, at: RunIndex) -> f64 {
        self.scale_of(at.block, self.levels[at.level], at.record)
    }

    /// The scale factor that brings record `record` to `level` for block
    /// `block`.
    pub(crate) fn scale_of(&self, block: usize, level: f64, record: usize) -> f64 {
        level / (self.records[record].intensity * self.im.block_factor(self.blocks[block]))
    }

    /// Checks the study before anything runs: at most [`MAX_RUNS`] runs,
    /// and every block under every record at the largest level a valid
    /// scenario (a smaller level only scales the motion down).
    pub fn check(&self) -> Result<(), FragilityCheckError> {
        if self.run_count() > MAX_RUNS {
            return Err(FragilityCheckError::TooManyRuns(self.run_count()));
        }
        let top = self.levels.iter().copied().fold(0.0, f64::max);
        for (k, &block) in self.blocks.iter().enumerate() {
            for (j, r) in self.records.iter().enumerate() {
                scenario_for(self.base, block, &r.drive, self.scale_of(k, top, j))
                    .map_err(|error| FragilityCheckError::Scenario { block, error })?;
            }
        }
        Ok(())
    }
}

/// A fragility study refused before it runs.
#[derive(Clone, Debug, thiserror::Error)]
pub enum FragilityCheckError {
    /// More than [`MAX_RUNS`] runs.
    #[error("{0} runs (blocks × levels × records): at most {MAX_RUNS}")]
    TooManyRuns(usize),
    /// A block's scenario at the largest level is invalid.
    #[error("block {} x {} m: {error}", block.width_m, block.height_m)]
    Scenario {
        /// The block.
        block: BlockSize,
        /// What is wrong (its config key names the input).
        error: ScenarioError,
    },
}

/// One run of the study.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragilityRun {
    /// Where it sits.
    pub at: RunIndex,
    /// The record's scale factor.
    pub scale: f64,
    /// What happened.
    pub response: BlockResponse,
}

/// A failed run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("block {block}, record {record}, level {level}: {error}")]
pub struct FragilityError {
    /// Block number (from 0).
    pub block: usize,
    /// Record name.
    pub record: String,
    /// The level.
    pub level: f64,
    /// What failed.
    pub error: ResponseError,
}

/// Runs the runs numbered `indices` (each < `spec.run_count()`), in
/// parallel; results in the order of `indices`. Progress counts runs.
pub fn run_fragility(
    spec: &FragilitySpec<'_>,
    indices: &[usize],
    progress: &ProgressFn<'_>,
) -> Result<Vec<FragilityRun>, FragilityError> {
    progress(Progress::Total(indices.len() as u64));
    indices
        .par_iter()
        .map(|&i| {
            let at = spec.index(i);
            let scale = spec.scale(at);
            let record = &spec.records[at.record];
            let response =
                respond(spec.base, spec.blocks[at.block], &record.drive, scale).map_err(|error| FragilityError {
                    block: at.block,
                    record: record.drive.name(),
                    level: spec.levels[at.level],
                    error,
                })?;
            progress(Progress::Done);
            Ok(FragilityRun { at, scale, response })
        })
        .collect()
}

/// Counts at one level of one block.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct LevelSummary {
    /// Runs.
    pub runs: u64,
    /// Runs that overturned.
    pub overturned: u64,
    /// Runs that ended in flight (left out of both fractions).
    pub flight: u64,
    /// Runs that overturned or whose peak θ/α reached the threshold.
    pub exceeded: u64,
}

impl LevelSummary {
    /// Runs with a computed fate (not flight).
    pub fn decided(&self) -> u64 {
        self.runs - self.flight
    }

    /// Fraction overturned among the decided runs (`None` if none).
    pub fn fraction_overturned(&self) -> Option<f64> {
        (self.decided() > 0).then(|| self.overturned as f64 / self.decided() as f64)
    }

    /// Fraction reaching the threshold among the decided runs.
    pub fn fraction_exceeded(&self) -> Option<f64> {
        (self.decided() > 0).then(|| self.exceeded as f64 / self.decided() as f64)
    }
}

/// Counts per block and level (`[block][level]`) of `runs`, each given as
/// (block, level, end state, peak θ/α); `threshold` is the θ/α whose
/// exceedance is counted.
pub fn summarise(
    blocks: usize,
    levels: usize,
    threshold: f64,
    runs: impl IntoIterator<Item = (usize, usize, EndState, f64)>,
) -> Vec<Vec<LevelSummary>> {
    let mut out = vec![vec![LevelSummary::default(); levels]; blocks];
    for (b, l, end, peak) in runs {
        let Some(s) = out.get_mut(b).and_then(|v| v.get_mut(l)) else {
            continue;
        };
        s.runs += 1;
        match end {
            EndState::Flight => s.flight += 1,
            EndState::Overturned => {
                s.overturned += 1;
                s.exceeded += 1;
            }
            EndState::Rest | EndState::Moving => {
                if peak >= threshold {
                    s.exceeded += 1;
                }
            }
        }
    }
    out
}

/// The two fitted curves of one block.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockFragility {
    /// P(overturning | level).
    pub overturn: Result<LognormalFit, FitError>,
    /// P(peak θ/α ≥ threshold or overturning | level).
    pub exceed: Result<LognormalFit, FitError>,
}

/// Fits both curves of one block from its counts at `levels`.
pub fn fit_block(levels: &[f64], counts: &[LevelSummary]) -> BlockFragility {
    let with = |failures: fn(&LevelSummary) -> u64| -> Vec<LevelCount> {
        levels
            .iter()
            .zip(counts)
            .map(|(&level, c)| LevelCount {
                level,
                runs: c.decided(),
                failures: failures(c),
            })
            .collect()
    };
    BlockFragility {
        overturn: lognormal::fit(&with(|c| c.overturned)),
        exceed: lognormal::fit(&with(|c| c.exceeded)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::excitation::record::Series;
    use crate::sim::scenario::Record;

    #[test]
    fn counts_exclude_flight_and_exceedance_includes_overturning() {
        let runs = [
            (0, 0, EndState::Rest, 0.1),
            (0, 0, EndState::Moving, 0.6),
            (0, 0, EndState::Overturned, 1.0),
            (0, 0, EndState::Flight, 0.3),
            (0, 1, EndState::Overturned, 1.0),
        ];
        let s = summarise(1, 2, 0.5, runs);
        assert_eq!(
            s[0][0],
            LevelSummary {
                runs: 4,
                overturned: 1,
                flight: 1,
                exceeded: 2
            }
        );
        assert_eq!(s[0][0].fraction_overturned(), Some(1.0 / 3.0));
        assert_eq!(s[0][1].fraction_exceeded(), Some(1.0));
    }

    #[test]
    fn runs_are_indexed_block_level_record_and_scaled_to_the_level() {
        let series = Series::new(vec![0.0, 0.5, 1.0], vec![0.0, 0.25, 0.0]).unwrap();
        let records = [
            SuiteRecord {
                drive: Drive::Record(Record {
                    path: "a.txt".into(),
                    series: series.clone(),
                    unit: crate::model::units::AccelUnit::G,
                    dt: None,
                    crc32: 0,
                    channel: None,
                }),
                intensity: 0.25,
            },
            SuiteRecord {
                drive: Drive::Record(Record {
                    path: "b.txt".into(),
                    series,
                    unit: crate::model::units::AccelUnit::G,
                    dt: None,
                    crc32: 0,
                    channel: None,
                }),
                intensity: 0.5,
            },
        ];
        let base = Scenario::default();
        let blocks = [BlockSize::from_height(1.0, 0.25), BlockSize::from_height(2.0, 0.25)];
        let levels = [0.1, 1.0, 2.0];
        let spec = FragilitySpec {
            base: &base,
            records: &records,
            levels: &levels,
            blocks: &blocks,
            im: Intensity::Pga,
        };
        assert_eq!(spec.run_count(), 12);
        assert_eq!(
            spec.index(7),
            RunIndex {
                block: 1,
                level: 0,
                record: 1
            }
        );
        let runs = run_fragility(&spec, &(0..12).collect::<Vec<_>>(), &crate::analysis::silent).unwrap();
        assert_eq!(runs[7].scale, 0.2);
        // 0.1 g < g tan α = 0.25 g: no rocking at the first level.
        assert_eq!(runs[0].response.end, EndState::Rest);
        assert_eq!(runs[0].response.peak_theta_over_alpha, 0.0);
        // A 2 g triangle of one second overturns the 1 m block.
        assert_eq!(runs[4].response.end, EndState::Overturned);
    }
}
