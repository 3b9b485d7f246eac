//! The rules a request can break, each naming the inputs at fault, and
//! how each surface words them.

use crate::analysis::engineering::rocking_spectrum::{MAX_BLOCKS, SizeRangeError};
use crate::analysis::field::{FieldNames, OwnNames, RequestField, show};
use crate::model::excitation::pulse::MAX_TYPE_C_CYCLES;

/// Most steps of a search's ladder: beyond this a search would take hours
/// and resolve nothing a tenth of the steps would not.
const MAX_LADDER_STEPS: usize = 100_000;

/// A request that breaks a rule, by the input at fault.
#[derive(Clone, Debug, PartialEq)]
pub enum RequestError {
    /// A unit that is not g, m/s2 or cm/s2.
    Unit {
        /// Which unit (of the record or of its vertical).
        field: RequestField,
        /// As given.
        text: String,
    },
    /// The record is all zeros: no scale reaches a PGA.
    ZeroRecord,
    /// Both a scale factor and a PGA.
    ScaleAndPga,
    /// A scale factor that is not finite and > 0.
    Scale(f64),
    /// A PGA that is not finite and > 0, g.
    Pga(f64),
    /// A pulse's peak acceleration or period that is not finite and > 0.
    PulseValue(RequestField, f64),
    /// A pulse without its peak acceleration or period.
    PulseMissing(RequestField),
    /// Type-C cycles outside 1..=[`MAX_TYPE_C_CYCLES`].
    Cycles(u32),
    /// A size range that cannot be stepped through.
    Sizes(SizeRangeError),
    /// `count` sizes from `from` to `from`: the same block `count` times.
    IdenticalSizes {
        /// The size, m.
        from: f64,
        /// Sizes asked.
        count: usize,
    },
    /// Sizes so close that two of them round to the same number.
    SizesTooClose {
        /// Smallest size, m.
        from: f64,
        /// Largest size, m.
        to: f64,
        /// Sizes asked.
        count: usize,
        /// The size given twice, m.
        twice: f64,
    },
    /// A slenderness ratio that is not finite and > 0.
    Ratio(f64),
    /// No slenderness ratio.
    NoRatio,
    /// No block for a fragility study of a block scene.
    NoBlock,
    /// A rocking intensity measure (PGA/(g tan α), PGV·p/(g tan α)) for a
    /// stack, which has no one α.
    StackIntensity,
    /// Slenderness ratios for a stack, which keeps its own.
    StackRatio {
        /// The stack's B/H: its bottom width over its total height.
        own: f64,
        /// Its number of blocks.
        blocks: usize,
    },
    /// Slenderness ratios that do not increase: `(before, after)`.
    RatiosNotIncreasing(f64, f64),
    /// More than [`MAX_BLOCKS`] blocks (sizes × ratios).
    TooManyBlocks,
    /// A search step that is not finite and > 0.
    SearchStep {
        /// The step's input.
        step_field: RequestField,
        /// Its value.
        step: f64,
    },
    /// A search's largest value below its step or not finite.
    SearchMax {
        /// The step's input.
        step_field: RequestField,
        /// Its value.
        step: f64,
        /// The largest value's input.
        max_field: RequestField,
        /// Its value.
        max: f64,
    },
    /// A search of more than [`MAX_LADDER_STEPS`] steps.
    SearchSteps {
        /// The step's input.
        step_field: RequestField,
        /// Its value.
        step: f64,
        /// The largest value's input.
        max_field: RequestField,
        /// Its value.
        max: f64,
    },
    /// A refinement width outside (0, 1).
    RelTol(f64),
    /// Sa(T) without its period.
    SaPeriodMissing,
    /// An Sa period that is not a period > 0, s.
    SaPeriod(f64),
    /// An Sa period with another intensity measure.
    SaPeriodWithoutSa(f64),
    /// A fragility level that is not finite and > 0.
    Level(f64),
    /// No level or no block.
    NoLevelsOrBlocks,
    /// A threshold θ/α that is not finite and > 0.
    Threshold(f64),
    /// A record whose intensity measure at scale 1 is 0: no factor scales
    /// it to a level.
    ZeroIntensity {
        /// The record's file.
        file: String,
        /// The measure's column name (`pga_g`).
        column: &'static str,
    },
}

impl RequestError {
    /// The error in the words of a surface (its names of the inputs).
    pub fn render(&self, names: &impl FieldNames<RequestField>) -> String {
        let valued = |field: RequestField, v: f64| names.valued(field, &show(v));
        let name = |field: RequestField| names.name(field);
        match self {
            RequestError::Unit { field, text } => {
                format!("{}: unknown unit (known: g, m/s2, cm/s2)", names.valued(*field, text))
            }
            RequestError::ZeroRecord => format!("{}: the record is all zeros (PGA 0 g)", name(RequestField::Record)),
            RequestError::ScaleAndPga => {
                format!(
                    "{} and {}: give one",
                    name(RequestField::Scale),
                    name(RequestField::Pga)
                )
            }
            RequestError::Scale(s) => format!("{}: must be > 0", valued(RequestField::Scale, *s)),
            RequestError::Pga(p) => format!("{}: must be > 0 (g)", valued(RequestField::Pga, *p)),
            RequestError::PulseValue(field, v) => format!("{}: must be a finite number > 0", valued(*field, *v)),
            RequestError::PulseMissing(field) => {
                format!("{}: required with {}", name(*field), name(RequestField::Pulse))
            }
            RequestError::Cycles(n) => format!(
                "{}: must be in 1..={MAX_TYPE_C_CYCLES}",
                names.valued(RequestField::Cycles, &n.to_string())
            ),
            RequestError::Sizes(SizeRangeError::From(v)) => {
                format!("{}: must be a size > 0 (m)", valued(RequestField::SizeFrom, *v))
            }
            RequestError::Sizes(SizeRangeError::Reversed { from, to }) => format!(
                "{}: below {}; give from <= to",
                valued(RequestField::SizeTo, *to),
                valued(RequestField::SizeFrom, *from)
            ),
            RequestError::Sizes(SizeRangeError::Count(n)) => format!(
                "{}: must be >= 2 (or 1 when {} = {}) and at most {MAX_BLOCKS}",
                names.valued(RequestField::SizeCount, &n.to_string()),
                name(RequestField::SizeFrom),
                name(RequestField::SizeTo)
            ),
            RequestError::IdenticalSizes { from, count } => format!(
                "{}: {} = {} = {} m gives {count} identical blocks; give {} or a {} above {}",
                names.valued(RequestField::SizeCount, &count.to_string()),
                name(RequestField::SizeFrom),
                name(RequestField::SizeTo),
                show(*from),
                names.valued(RequestField::SizeCount, "1"),
                name(RequestField::SizeTo),
                name(RequestField::SizeFrom)
            ),
            RequestError::SizesTooClose { from, to, count, twice } => format!(
                "{}: {} to {} m are too close for {count} distinct sizes ({} twice); give fewer",
                names.valued(RequestField::SizeCount, &count.to_string()),
                valued(RequestField::SizeFrom, *from),
                valued(RequestField::SizeTo, *to),
                show(*twice)
            ),
            RequestError::Ratio(r) => format!(
                "{}: every ratio must be finite and > 0",
                valued(RequestField::BOverH, *r)
            ),
            RequestError::NoRatio => format!("{}: give at least one ratio", name(RequestField::BOverH)),
            RequestError::NoBlock => format!(
                "{}: give at least one block (its width and height in metres), or a [[stack]] scene",
                name(RequestField::Blocks)
            ),
            RequestError::StackIntensity => format!(
                "{}: a [[stack]] has no one slenderness α (each face lifts at its own acceleration); use pga, pgv or sa",
                name(RequestField::Im)
            ),
            RequestError::StackRatio { own, blocks } => format!(
                "{}: a [[stack]] is scaled as a whole and keeps its own shape (B/H = {own:.4} of its {blocks} blocks: bottom width over total height); leave it out",
                name(RequestField::BOverH)
            ),
            RequestError::RatiosNotIncreasing(a, b) => format!(
                "{}: values must increase ({} then {})",
                name(RequestField::BOverH),
                show(*a),
                show(*b)
            ),
            RequestError::TooManyBlocks => format!(
                "{} × {}: at most {MAX_BLOCKS} blocks",
                name(RequestField::SizeCount),
                name(RequestField::BOverH)
            ),
            RequestError::SearchStep { step_field, step } => {
                format!("{}: must be a finite number > 0", valued(*step_field, *step))
            }
            RequestError::SearchMax {
                step_field,
                step,
                max_field,
                max,
            } => format!(
                "{}: must be finite and >= {}",
                valued(*max_field, *max),
                valued(*step_field, *step)
            ),
            RequestError::SearchSteps {
                step_field,
                step,
                max_field,
                max,
            } => format!(
                "{} up to {}: more than {MAX_LADDER_STEPS} steps; give a larger step",
                valued(*step_field, *step),
                valued(*max_field, *max)
            ),
            RequestError::RelTol(r) => format!("{}: must be in (0, 1)", valued(RequestField::RelTol, *r)),
            RequestError::SaPeriodMissing => format!(
                "{}: give the period with {} S (seconds)",
                names.valued(RequestField::Im, "sa"),
                name(RequestField::SaPeriod)
            ),
            RequestError::SaPeriod(t) => format!("{}: must be a period > 0 (s)", valued(RequestField::SaPeriod, *t)),
            RequestError::SaPeriodWithoutSa(t) => format!(
                "{}: only with {}; remove it or give {}",
                valued(RequestField::SaPeriod, *t),
                names.valued(RequestField::Im, "sa"),
                names.valued(RequestField::Im, "sa")
            ),
            RequestError::Level(v) => format!(
                "{}: every level must be finite and > 0",
                valued(RequestField::Levels, *v)
            ),
            RequestError::NoLevelsOrBlocks => format!(
                "{} and {}: give at least one of each",
                name(RequestField::Levels),
                name(RequestField::Blocks)
            ),
            RequestError::Threshold(t) => format!("{}: must be a θ/α > 0", valued(RequestField::Threshold, *t)),
            RequestError::ZeroIntensity { file, column } => format!("{file}: {column} is 0, it cannot be scaled"),
        }
    }
}

impl std::fmt::Display for RequestError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.render(&OwnNames))
    }
}

impl std::error::Error for RequestError {}
