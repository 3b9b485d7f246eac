//! Early stopping of a stack's map cell: the block's criteria
//! ([`settle`](crate::analysis::settle)), on a stack's section points.
//!
//! - **Rest**: every face closed and the base stuck at a section point τ_n,
//!   with no event since τ_n − T. At rest a stack's guards (each face's
//!   margins, the base's friction) depend on the forcing alone, so a
//!   forcing of period T that lifted or slid nothing for a whole period
//!   never will: the full run would end at rest with the same last event,
//!   which is the stack's rest class.
//! - **Periodic, period k**: the last `2k + CONFIRM` recurrences of the
//!   section points in the coordinates a stack is classified on (every
//!   face's q and q' and the slip rate, `stack.rs`) hold to
//!   [`SETTLE_FRACTION`](crate::analysis::settle::SETTLE_FRACTION) of the
//!   classifier's tolerance, as the block's must: a hundred times tighter
//!   than the class needs, for two whole cycles and `CONFIRM` periods more.
//!   Not when a point of the cycle is at rest: a stack that rests at its
//!   section times and lifts in between (each period a new uplift, often a
//!   chatter of impacts that an accumulation closes) repeats its section
//!   points exactly, however its next period will go. Each period then
//!   starts from rest at a forcing phase known only to round-off, and the
//!   chatter amplifies it: a stack at A_h = 0.7, Ω_h = 3.9 of
//!   `stack-patterns` rests at 190 section times in a row, about 100
//!   impacts a period, and then overturns at τ = 328. Such a run runs its
//!   whole window.
//!
//! A stack starts at rest, so a basin map has nothing to look up and no
//! known attractor is reached: those two criteria are the block's alone.

use std::collections::VecDeque;

use crate::analysis::classify::ClassifyOptions;
use crate::analysis::settle::{CONFIRM, converged_period};
use crate::model::stack::StackEvent;
use crate::sim::stack_run::StackSection;

/// Why a stack's watched run stopped.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum StackVerdict<const D: usize> {
    /// At rest for a whole forcing period at `tau`.
    Rest {
        /// τ of the section point where it was seen.
        tau: f64,
    },
    /// Converged onto a periodic orbit at `tau`.
    Periodic {
        /// τ of the section point where it was seen.
        tau: f64,
        /// The orbit's last cycle in the classified coordinates, oldest
        /// first.
        cycle: Vec<[f64; D]>,
        /// The same cycle as the top block's (Θ, Θ', X') points.
        top: Vec<[f64; 3]>,
    },
}

/// A section point's classified coordinates (`D` of them) and its top
/// block's (Θ, Θ', X').
pub(super) type PointOf<'a, const D: usize> = &'a dyn Fn(&StackSection) -> ([f64; D], [f64; 3]);

/// Watches a stack's section points (module docs), classified in `D`
/// coordinates.
pub(super) struct StackSettle<'a, const D: usize> {
    period: f64,
    k: usize,
    opts: ClassifyOptions,
    /// The section point's classified coordinates and top-block point.
    point: PointOf<'a, D>,
    recent: VecDeque<[f64; D]>,
    recent_top: VecDeque<[f64; 3]>,
    /// Whether each recent point is at rest (every face closed, the base
    /// stuck).
    recent_rest: VecDeque<bool>,
    capacity: usize,
    bound: [f64; D],
    /// Section points already looked at.
    seen: usize,
    verdict: Option<StackVerdict<D>>,
}

impl<'a, const D: usize> StackSettle<'a, D> {
    /// A watcher for a stack of `k` blocks under forcing of period
    /// `period` (τ), whose section points read as `point` says.
    pub(super) fn new(period: f64, k: usize, opts: ClassifyOptions, point: PointOf<'a, D>) -> Self {
        let capacity = 3 * opts.k_max as usize + CONFIRM;
        Self {
            period,
            k,
            opts,
            point,
            recent: VecDeque::with_capacity(capacity),
            recent_top: VecDeque::with_capacity(capacity),
            recent_rest: VecDeque::with_capacity(capacity),
            capacity,
            bound: [0.0; D],
            seen: 0,
            verdict: None,
        }
    }

    /// Why the run stopped, if it did.
    pub(super) fn verdict(&self) -> Option<&StackVerdict<D>> {
        self.verdict.as_ref()
    }

    /// Looks at the section points not seen yet (`events` so far give the
    /// rest criterion its last event); `true` once the class is certain.
    pub(super) fn watch(&mut self, sections: &[StackSection], events: &[StackEvent]) -> bool {
        for s in &sections[self.seen.min(sections.len())..] {
            self.seen += 1;
            if self.verdict.is_some() {
                break;
            }
            let tau = s.at.tau;
            // The last event at or before this section time (a leg's last
            // step may reach past it).
            let since = events.iter().rev().find(|e| e.tau <= tau).map_or(0.0, |e| e.tau);
            let at_rest = s.at.mode.at_rest(self.k);
            if at_rest && since <= tau - self.period {
                self.verdict = Some(StackVerdict::Rest { tau });
                break;
            }
            if self.recent.len() == self.capacity {
                self.recent.pop_front();
                self.recent_top.pop_front();
                self.recent_rest.pop_front();
            }
            let (p, top) = (self.point)(s);
            for (a, x) in self.bound.iter_mut().zip(&p) {
                *a = a.max(x.abs());
            }
            self.recent.push_back(p);
            self.recent_top.push_back(top);
            self.recent_rest.push_back(at_rest);
            if let Some(k) = converged_period(&self.recent, &self.bound, &self.opts) {
                let n = self.recent.len();
                if self.recent_rest.range(n - k..).any(|&r| r) {
                    continue;
                }
                self.verdict = Some(StackVerdict::Periodic {
                    tau,
                    cycle: self.recent.range(n - k..).copied().collect(),
                    top: self.recent_top.range(n - k..).copied().collect(),
                });
            }
        }
        self.verdict.is_some()
    }
}
