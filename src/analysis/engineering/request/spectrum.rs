//! A rocking spectrum's request: its sizes, slendernesses and
//! overturning-scale search, checked in that order.

use super::{RequestError, search_ladder};
use crate::analysis::engineering::rocking_spectrum::{MAX_BLOCKS, OverturnOptions, SizeAxis, SizeRange};
use crate::analysis::engineering::stack_response::stack_size;
use crate::analysis::field::RequestField;
use crate::sim::Scenario;

/// A rocking spectrum's overturning-scale search, as asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverturnRequest {
    /// Step of the scales tried.
    pub search_step: f64,
    /// Largest scale tried.
    pub search_max: f64,
    /// Relative width of a refined boundary, in (0, 1).
    pub rel_tol: f64,
}

/// A rocking spectrum's blocks and search, as asked (the motion apart).
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumRequest {
    /// What the sizes step through.
    pub axis: SizeAxis,
    /// Smallest size, m.
    pub from_m: f64,
    /// Largest size, m.
    pub to_m: f64,
    /// Number of log-spaced sizes.
    pub count: usize,
    /// Slenderness ratios B/H, increasing.
    pub b_over_h: Vec<f64>,
    /// The overturning-scale search, if asked.
    pub overturn: Option<OverturnRequest>,
}

/// The slenderness ratio of a block spectrum without ratios given: a
/// slender cabinet or statue (B/H = 1/4, α ≈ 14°), which rocks under
/// ground motion of 0.25 g and more.
pub const SPECTRUM_B_OVER_H: f64 = 0.25;

/// The ratios of a spectrum of `base`'s body: those `given`, or
/// [`SPECTRUM_B_OVER_H`]; a stack is scaled as a whole, so its one ratio
/// is its own (bottom width over total height) and ratios given for it
/// are refused.
pub fn spectrum_ratios(base: &Scenario, given: Option<Vec<f64>>) -> Result<Vec<f64>, RequestError> {
    match (&base.stack, given) {
        (None, given) => Ok(given.unwrap_or_else(|| vec![SPECTRUM_B_OVER_H])),
        (Some(blocks), given) => {
            let size = stack_size(blocks);
            let own = size.width_m / size.height_m;
            match given {
                None => Ok(vec![own]),
                Some(_) => Err(RequestError::StackRatio {
                    own,
                    blocks: blocks.len(),
                }),
            }
        }
    }
}

/// A checked spectrum request.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumBlocks {
    /// The sizes.
    pub sizes: SizeRange,
    /// The ratios.
    pub b_over_h: Vec<f64>,
    /// The search.
    pub overturn: Option<OverturnOptions>,
}

impl SpectrumRequest {
    /// The sizes, ratios and search, or the first input at fault: sizes,
    /// then ratios, then their product, then the search.
    pub fn checked(&self) -> Result<SpectrumBlocks, RequestError> {
        let sizes = self.size_range()?;
        if let Some(&r) = self.b_over_h.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
            return Err(RequestError::Ratio(r));
        }
        if self.b_over_h.is_empty() {
            return Err(RequestError::NoRatio);
        }
        if let Some(w) = self.b_over_h.windows(2).find(|w| w[1] <= w[0]) {
            return Err(RequestError::RatiosNotIncreasing(w[0], w[1]));
        }
        if sizes.count * self.b_over_h.len() > MAX_BLOCKS {
            return Err(RequestError::TooManyBlocks);
        }
        let overturn = match self.overturn {
            None => None,
            Some(o) => {
                let ladder = search_ladder(
                    RequestField::SearchStep,
                    o.search_step,
                    RequestField::SearchMax,
                    o.search_max,
                )?;
                if !(o.rel_tol > 0.0 && o.rel_tol < 1.0) {
                    return Err(RequestError::RelTol(o.rel_tol));
                }
                Some(OverturnOptions {
                    ladder,
                    rel_tol: o.rel_tol,
                })
            }
        };
        Ok(SpectrumBlocks {
            sizes,
            b_over_h: self.b_over_h.clone(),
            overturn,
        })
    }

    /// The size range alone: `count` distinct log-spaced sizes (a surface
    /// that parses its ratios itself checks the sizes first with this).
    pub(crate) fn size_range(&self) -> Result<SizeRange, RequestError> {
        let (from, to, count) = (self.from_m, self.to_m, self.count);
        if from == to && count > 1 {
            return Err(RequestError::IdenticalSizes { from, count });
        }
        let range = SizeRange::new(self.axis, from, to, count).map_err(RequestError::Sizes)?;
        // Sizes so close that they round to one value are the same block twice.
        if let Some(w) = range.values().windows(2).find(|w| w[1] <= w[0]) {
            return Err(RequestError::SizesTooClose {
                from,
                to,
                count,
                twice: w[0],
            });
        }
        Ok(range)
    }
}
