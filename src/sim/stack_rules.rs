//! The rules a scenario with a `[[stack]]` must satisfy (docs/model.md
//! §18): each block's size, offset and friction, that every block rests on
//! the one below, and what a stack does not run (the single block's
//! impact laws and its fixed-step method, a tilted start, the analyses
//! built on the block's angle, and Lyapunov exponents other than the
//! two-trajectory estimate).

use super::method::Method;
use super::scenario::{LawKind, MIN_PSI, MU_K_LIMIT, Scenario, ScenarioError};
use super::validate::check;
use crate::model::stack::{MAX_BLOCKS, StackGeometry, StackShapeError};

impl Scenario {
    /// A stack's blocks and what a stack cannot do.
    pub(super) fn validate_stack(&self) -> Result<(), ScenarioError> {
        let Some(blocks) = &self.stack else {
            return Ok(());
        };
        check(
            "stack",
            (2..=MAX_BLOCKS).contains(&blocks.len()),
            &format!("2 to {MAX_BLOCKS} [[stack]] tables (one table is a single block)"),
            blocks.len() as f64,
        )?;
        let size_ok = |x: f64| (super::scenario::MIN_SIZE_M..=super::scenario::MAX_SIZE_M).contains(&x);
        for (i, b) in blocks.iter().enumerate() {
            let key = |name: &str| format!("stack[{i}].{name}");
            check(&key("width"), size_ok(b.width), "in [1e-4, 1e4] metres", b.width)?;
            check(&key("height"), size_ok(b.height), "in [1e-4, 1e4] metres", b.height)?;
            check(
                &key("width"),
                (b.width / b.height).atan() >= MIN_PSI,
                "at least 1e-6 of its height",
                b.width,
            )?;
            check(&key("offset"), b.offset.is_finite(), "a finite length", b.offset)?;
            if i == 0 && b.offset != 0.0 {
                return Err(ScenarioError::new(
                    key("offset"),
                    "must be 0 for the bottom block: it has no block below it to be offset from",
                ));
            }
            check(&key("static"), b.mu_s >= 0.0, ">= 0 or inf", b.mu_s)?;
            let mu_k = b.mu_k.unwrap_or(b.mu_s);
            // An absent kinetic coefficient takes the static one: say so.
            let kinetic = if b.mu_k.is_some() {
                key("kinetic")
            } else {
                format!("stack[{i}].kinetic (absent, so equal to stack[{i}].static)")
            };
            check(&kinetic, mu_k >= 0.0, ">= 0 or inf", mu_k)?;
            check(
                &kinetic,
                mu_k.is_finite() || b.mu_s.is_infinite(),
                "finite when the static one is finite",
                mu_k,
            )?;
            // The base face slides with it: the single block's Painlevé
            // bound (docs/model.md §4.2, §18.7).
            check(
                &kinetic,
                i > 0 || mu_k < MU_K_LIMIT || b.mu_s.is_infinite(),
                "< 4/3 (larger kinetic friction makes the base face's slide-rock ill-posed: the Painlevé paradox, docs/model.md §18.7)",
                mu_k,
            )?;
        }
        if blocks.iter().all(|b| b.glued) {
            return Err(ScenarioError::new(
                "stack[0].glued",
                "every face of the stack is glued, so nothing can move: unglue at least one",
            ));
        }
        if let Err(e) = StackGeometry::new(blocks) {
            return Err(match e {
                StackShapeError::NoOverlap { index } => ScenarioError::new(
                    format!("stack[{}].offset", index - 1),
                    "puts this block beside the one below: their faces must overlap",
                ),
                StackShapeError::Count(n) => ScenarioError::new("stack", format!("has {n} tables")),
            });
        }
        let refuse = |key: &str, why: &str| Err(ScenarioError::new(key, why));
        if self.impact.law != LawKind::Housner || self.impact.r.is_some() {
            return refuse(
                "impact.law",
                "a [[stack]]'s impacts follow its own impulse law, each new pivot stuck (docs/model.md §18.5): remove [impact]",
            );
        }
        if self.run.method() == Method::Ralston {
            return refuse(
                "run.method",
                "\"ralston\" (the paper's fixed step) is the single block's; a [[stack]] takes \"dop853\", \"dopri5\" or \"taylor\" (DOP853's steps)",
            );
        }
        let i = &self.initial;
        if i.theta != 0.0 || i.theta_dot != 0.0 || i.x_dot.is_some_and(|x| x != 0.0) {
            return refuse("initial", "a [[stack]] starts at rest on its base: remove [initial]");
        }
        if self.run.flight != crate::model::FlightPolicy::Stop {
            return refuse(
                "run.flight",
                "a [[stack]] stops at flight (\"stop\"): its grounded equations do not hold without contact",
            );
        }
        if self.run.tumble_theta != 1.0 {
            return refuse(
                "run.tumble_theta",
                "a [[stack]] overturns where the blocks above an interface pass over its pivot (docs/model.md §18.6): remove run.tumble_theta",
            );
        }
        if self.analyses.lyapunov {
            self.two_trajectories_only("[[stack]]")?;
        }
        if self.analyses.spectrum {
            return refuse(
                "analysis.spectrum",
                "is the single block's (it reads the block's angle); not available for a [[stack]]",
            );
        }
        if self.frame.is_some() {
            return refuse("frame", "a config has one of [block], [[stack]] and [frame]");
        }
        Ok(())
    }
}
