//! `[[stack]]`: one table per block, bottom to top (docs/model.md §18). A
//! one-table stack is the single block (its `[block]` and `[friction]`),
//! so it runs bit for bit as one.

use toml::Table;

use super::error::ConfigError;
use super::quantity::{Dimension, Quantity};
use super::raw::RawStackBlock;
use crate::model::Geometry;
use crate::model::stack::StackBlock;
use crate::sim::scenario::Block;

/// The sections a stack replaces, refused beside it.
fn stack_alone(table: &Table) -> Result<(), ConfigError> {
    for (section, why) in [
        (
            "block",
            "a config has one of [block], [[stack]] and [frame] (a stack's blocks are its [[stack]] tables)",
        ),
        (
            "friction",
            "a [[stack]] gives each face's friction in its tables (stack[i].static, stack[i].kinetic): remove [friction]",
        ),
        ("frame", "a config has one of [block], [[stack]] and [frame]"),
    ] {
        if table.contains_key(section) {
            return Err(ConfigError::key(section, why));
        }
    }
    if matches!(table.get("stack"), Some(toml::Value::Table(_))) {
        return Err(ConfigError::key(
            "stack",
            "write each block as a [[stack]] table (double brackets), bottom to top",
        ));
    }
    Ok(())
}

/// The stack `tables` describe: the block the run's units come from (the
/// bottom one, or the only one) and, for two or more tables, the stack.
pub(super) fn resolve(
    table: &Table,
    tables: &[RawStackBlock],
) -> Result<(Block, Option<Vec<StackBlock>>), ConfigError> {
    stack_alone(table)?;
    if tables.is_empty() {
        return Err(ConfigError::key(
            "stack",
            "has no tables: give one [[stack]] table per block",
        ));
    }
    let unit = Geometry::new(1.0, 1.0);
    let mut blocks = Vec::with_capacity(tables.len());
    for (i, t) in tables.iter().enumerate() {
        let key = |name: &str| format!("stack[{i}].{name}");
        let size = |name: &str, q: Option<Quantity>| -> Result<f64, ConfigError> {
            let q = q.ok_or_else(|| {
                ConfigError::key(&key(name), "is required in every [[stack]] table (m, or \"60 cm\")")
            })?;
            q.resolve(&key(name), Dimension::Length, &unit)
        };
        let offset = match t.offset {
            Some(q) => q.resolve(&key("offset"), Dimension::Length, &unit)?,
            None => 0.0,
        };
        let mu_s = t.mu_s.map_or(f64::INFINITY, |c| c.0);
        if let Some(k) = t.mu_k
            && k.0 > mu_s
        {
            return Err(ConfigError::key(
                &key("kinetic"),
                format!("{:?} must be <= stack[{i}].static ({mu_s:?})", k.0),
            ));
        }
        blocks.push(StackBlock {
            width: size("width", t.width)?,
            height: size("height", t.height)?,
            offset,
            mu_s,
            mu_k: t.mu_k.map(|c| c.0),
            glued: t.glued.unwrap_or(false),
        });
    }
    let bottom = blocks[0];
    let block = Block {
        width: bottom.width,
        height: bottom.height,
        mu_s: bottom.mu_s,
        mu_k: bottom.mu_k,
    };
    if blocks.len() == 1 {
        if bottom.glued {
            return Err(ConfigError::key(
                "stack[0].glued",
                "a single glued block never moves: nothing to simulate",
            ));
        }
        if bottom.offset != 0.0 {
            return Err(ConfigError::key(
                "stack[0].offset",
                "must be 0 for the bottom block: it has no block below it to be offset from",
            ));
        }
        return Ok((block, None));
    }
    Ok((block, Some(blocks)))
}
