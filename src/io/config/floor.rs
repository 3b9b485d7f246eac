//! `[floor]`: the building between the ground and the block, as one mode's
//! keys (`period`, `damping`, `participation`) or as `[[floor.mode]]`
//! tables with the same keys. Ranges are checked by the scenario
//! ([`Scenario::validate`](crate::sim::Scenario::validate)); here only the
//! shape: a period for every mode, and not both forms at once.

use super::ConfigError;
use super::quantity::Dimension;
use super::raw::{Finite, RawFloor};
use crate::model::Geometry;
use crate::sim::scenario::{FLOOR_DAMPING, FLOOR_PARTICIPATION, FloorModeSpec, FloorSpec};

/// The floor the raw keys describe; `None` without `[floor]`.
pub fn resolve(raw: &Option<RawFloor>, geo: &Geometry) -> Result<Option<FloorSpec>, ConfigError> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let num = |x: Option<Finite>, default: f64| x.map_or(default, |v| v.0);
    match &raw.mode {
        Some(modes) => {
            if let Some(key) = [
                ("period", raw.period.is_some()),
                ("damping", raw.damping.is_some()),
                ("participation", raw.participation.is_some()),
            ]
            .iter()
            .find_map(|(k, given)| given.then_some(k))
            {
                return Err(ConfigError::key(
                    &format!("floor.{key}"),
                    "give the modes either as floor.period/damping/participation or as [[floor.mode]] tables, not both",
                ));
            }
            if modes.is_empty() {
                return Err(ConfigError::key(
                    "floor.mode",
                    "needs at least one [[floor.mode]] table",
                ));
            }
            let mut out = Vec::with_capacity(modes.len());
            for (k, m) in modes.iter().enumerate() {
                let key = format!("floor.mode[{k}].period");
                let Some(period) = m.period else {
                    return Err(ConfigError::key(&key, "is required: the mode's period, e.g. \"0.5 s\""));
                };
                out.push(FloorModeSpec {
                    period_s: period.resolve(&key, Dimension::Seconds, geo)?,
                    damping: num(m.damping, FLOOR_DAMPING),
                    // Several modes need their participations: the default
                    // 1 is that of a single mode only.
                    participation: match m.participation {
                        Some(p) => p.0,
                        None if modes.len() == 1 => FLOOR_PARTICIPATION,
                        None => {
                            return Err(ConfigError::key(
                                &format!("floor.mode[{k}].participation"),
                                "is required when [floor] has several modes (Γφ of this mode at the floor)",
                            ));
                        }
                    },
                });
            }
            Ok(Some(FloorSpec {
                modes: out,
                as_tables: true,
            }))
        }
        None => {
            let Some(period) = raw.period else {
                return Err(ConfigError::key(
                    "floor.period",
                    "is required in [floor]: the building mode's period, e.g. \"0.5 s\"",
                ));
            };
            Ok(Some(FloorSpec {
                modes: vec![FloorModeSpec {
                    period_s: period.resolve("floor.period", Dimension::Seconds, geo)?,
                    damping: num(raw.damping, FLOOR_DAMPING),
                    participation: num(raw.participation, FLOOR_PARTICIPATION),
                }],
                as_tables: false,
            }))
        }
    }
}
