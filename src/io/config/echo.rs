//! The resolved scenario written back as config keys (`summary.json`'s
//! `config`, which repeats the run), key by key from the catalogue: every
//! numeric parameter through its typed getter ([`Param::get`], the value as
//! run), the other keys by what they are.

use serde_json::{Map, Value as Json, json};

use crate::model::FlightPolicy;
use crate::sim::Scenario;
use crate::sim::catalogue::{CATALOGUE, KeySpec, Param};
use crate::sim::scenario::Record;

/// Keys the echo leaves out: a record's PGA and `run.t_end` are other
/// ways of writing `scale_*` and `run.tau_end`, which it writes; the floor's
/// keys are written as they were given ([`floor_json`]), a stack's as its
/// tables ([`stack_json`]).
const NOT_ECHOED: [&str; 13] = [
    "stack.width",
    "stack.height",
    "stack.offset",
    "stack.static",
    "stack.kinetic",
    "stack.glued",
    "excitation.pga_h",
    "excitation.pga_v",
    "run.t_end",
    "floor.period",
    "floor.damping",
    "floor.participation",
    "floor.mode",
];

/// The resolved scenario as JSON, in the same sections and keys as the
/// TOML (infinite friction as the string `"inf"`, an unset
/// `initial.x_dot` as `null`): `summary.json`'s `config`, which repeats the
/// run.
pub fn to_json(s: &Scenario) -> Json {
    let mut sections: Map<String, Json> = Map::new();
    for k in CATALOGUE
        .iter()
        .filter(|k| !NOT_ECHOED.contains(&k.key) && describes(k.section(), s))
    {
        if let Json::Object(section) = sections.entry(k.section()).or_insert_with(|| Json::Object(Map::new())) {
            section.insert(k.name().to_string(), value(k, s));
        }
    }
    if let Some(floor) = &s.floor {
        sections.insert("floor".to_string(), floor_json(floor));
    }
    if let Some(blocks) = &s.stack {
        sections.insert("stack".to_string(), stack_json(blocks));
    }
    Json::Object(sections)
}

/// Whether `section` describes `s`'s structure: a frame is written as the
/// `[frame]` it was read from (its columns' size, no block, no friction:
/// its columns do not slide), a block as `[block]` and `[friction]`.
fn describes(section: &str, s: &Scenario) -> bool {
    match section {
        "block" | "friction" => s.frame.is_none() && s.stack.is_none(),
        // A stack's impacts are its own law (docs/model.md §18.5).
        "impact" => s.stack.is_none(),
        "frame" => s.frame.is_some(),
        _ => true,
    }
}

/// The value of key `k` in `s`, as the config writes it.
fn value(k: &KeySpec, s: &Scenario) -> Json {
    // A record that decides the run's length writes its tail and no end;
    // any other run writes its end (and no tail, which would conflict).
    let (tau_end, tail_s) = match (s.record_end_tau(), s.run.record_tail_s) {
        (Some(_), Some(tail)) => (None, Some(tail)),
        _ => (Some(s.run.tau_end), None),
    };
    match k.param {
        Some(Param::TauEnd) => json!(tau_end),
        // Unset means "whatever keeps the base still", not 0.
        Some(Param::XDot0) => json!(s.initial.x_dot),
        Some(p) => {
            let v = p.get(s);
            if k.infinite && !v.is_finite() {
                json!("inf")
            } else {
                json!(v)
            }
        }
        // Every key has its arm (tested): null is never a silent default.
        None => other(k, s, tail_s).unwrap_or(Json::Null),
    }
}

/// The value of a key that is not a numeric parameter; `None` for a key
/// this does not know.
fn other(k: &KeySpec, s: &Scenario, tail_s: Option<f64>) -> Option<Json> {
    let x = &s.excitation;
    let record = |name: &str| match name.rsplit_once('_') {
        Some((_, "h")) => x.record_h.as_ref(),
        _ => x.record_v.as_ref(),
    };
    // A record given as samples names no file: its keys are null, so a
    // config written from it cannot claim to repeat the run (reading it
    // back asks for excitation.file_h).
    let file = |name: &str| record(name).filter(|r| !r.is_in_memory());
    let name = k.name();
    Some(match k.key {
        "frame.width" => json!(s.block.width),
        "frame.height" => json!(s.block.height),
        "frame.columns" => json!(s.frame.map(|f| f.columns)),
        "frame.beam_mass_ratio" => json!(s.frame.map(|f| f.beam_mass_ratio)),
        "impact.law" => json!(s.impact.law.name()),
        "excitation.kind" => json!(x.kind.name()),
        "excitation.shape" => json!(x.shape.name()),
        "excitation.cycles" => json!(x.cycles),
        "excitation.file_h" | "excitation.file_v" => json!(file(name).map(|r| r.path.display().to_string())),
        "excitation.unit_h" | "excitation.unit_v" => json!(file(name).map(|r| r.unit.name())),
        "excitation.dt_h" | "excitation.dt_v" => json!(file(name).and_then(|r: &Record| r.dt)),
        "excitation.crc32_h" | "excitation.crc32_v" => json!(file(name).map(|r| format!("{:08x}", r.crc32))),
        "excitation.channel_h" | "excitation.channel_v" => json!(file(name).and_then(|r: &Record| r.channel)),
        "run.tail_s" => json!(tail_s),
        "run.method" => json!(s.run.method().name()),
        "run.flight" => json!(match s.run.flight {
            FlightPolicy::Stop => "stop",
            FlightPolicy::Ignore => "ignore",
        }),
        "run.max_steps" => json!(s.run.max_steps),
        "run.max_events" => json!(s.run.max_events),
        "analysis.lyapunov" => json!(s.analyses.lyapunov),
        "analysis.lyapunov_method" => json!(s.analyses.lyapunov_method.name()),
        "analysis.spectrum" => json!(s.analyses.spectrum),
        "analysis.spectrum_window" => json!(s.analyses.spectrum_window.name()),
        // A key added to the catalogue and not yet here: the test below
        // fails until it is written or listed in NOT_ECHOED.
        _ => return None,
    })
}

/// `[[stack]]` as the config writes it back: one table per block, infinite
/// friction as `"inf"`, an absent kinetic coefficient as `null`.
fn stack_json(blocks: &[crate::model::stack::StackBlock]) -> Json {
    let coefficient = |x: f64| if x.is_finite() { json!(x) } else { json!("inf") };
    Json::Array(
        blocks
            .iter()
            .map(|b| {
                json!({
                    "width": b.width,
                    "height": b.height,
                    "offset": b.offset,
                    "static": coefficient(b.mu_s),
                    "kinetic": b.mu_k.map(coefficient),
                    "glued": b.glued,
                })
            })
            .collect(),
    )
}

/// `[floor]` as the config writes it back: one mode's keys, or the
/// `[[floor.mode]]` tables as they were given.
fn floor_json(floor: &crate::sim::scenario::FloorSpec) -> Json {
    let mode = |m: &crate::sim::scenario::FloorModeSpec| json!({ "period": m.period_s, "damping": m.damping, "participation": m.participation });
    match floor.modes.as_slice() {
        [one] if !floor.as_tables => mode(one),
        modes => json!({ "mode": modes.iter().map(mode).collect::<Vec<_>>() }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_that_is_not_a_parameter_is_echoed_or_left_out_by_name() {
        let s = Scenario::default();
        for k in CATALOGUE
            .iter()
            .filter(|k| k.param.is_none() && !NOT_ECHOED.contains(&k.key))
        {
            assert!(other(k, &s, None).is_some(), "{} has no value in the echo", k.key);
        }
        // The left-out keys are keys.
        for key in NOT_ECHOED {
            assert!(CATALOGUE.iter().any(|k| k.key == key), "{key}");
        }
    }

    #[test]
    fn infinite_friction_is_the_word_inf_and_an_unset_start_velocity_is_null() {
        let mut s = Scenario::default();
        s.block.mu_s = f64::INFINITY;
        s.initial.x_dot = None;
        let j = to_json(&s);
        assert_eq!(j["friction"]["static"], json!("inf"));
        assert!(j["initial"]["x_dot"].is_null());
        assert_eq!(j["block"]["width"], json!(s.block.width));
        // Every section but the floor, which only a floored scene has.
        let sections: Vec<&str> = j.as_object().unwrap().keys().map(String::as_str).collect();
        assert_eq!(
            sections,
            [
                "analysis",
                "block",
                "excitation",
                "friction",
                "impact",
                "initial",
                "run"
            ]
        );
    }
}
