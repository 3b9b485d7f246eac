//! `summary.json`'s `resolved` block: every resolved input both ways,
//! normalised (as the scenario stores it) and physical. Each value's
//! physical forms follow from its catalogue key's dimension
//! ([`Dimension::to_physical`], the one conversion), and each value is the
//! key's typed getter ([`Param::get`]); only the block's derived numbers and
//! the few values named otherwise are written here by hand.

use serde_json::{Value as Json, json};

use crate::model::Geometry;
use crate::model::geometry::G;
use crate::sim::Scenario;
use crate::sim::catalogue::{Dimension, Param, spec};

/// The keys given both ways, with the name each has in the block, by
/// section. The run's end is its resolved length (a record's run ends
/// after the record and its tail), hence its own name.
const BOTH_WAYS: [(&str, &str); 10] = [
    ("excitation.a_h", "a_h"),
    ("excitation.a_v", "a_v"),
    ("excitation.omega_h", "omega_h"),
    ("excitation.omega_v", "omega_v"),
    ("initial.theta", "theta"),
    ("initial.theta_dot", "theta_dot"),
    ("initial.x_dot", "x_dot"),
    ("run.tau_end", "end"),
    ("run.output_dt", "output_dt"),
    ("run.tumble_theta", "tumble_theta"),
];

/// A bare value of dimension `d` with its physical forms, for block `geo`:
/// accelerations in g, m/s² and multiples of the uplift acceleration;
/// frequencies in rad/s, Hz and as a period; angles in rad and degrees;
/// velocities and times in SI.
pub(crate) fn both_ways(d: Dimension, bare: f64, geo: &Geometry) -> Json {
    let si = d.to_physical(bare, geo);
    match d {
        Dimension::Amplitude => {
            json!({ "normalised": bare, "g": si, "m_s2": si * G, "over_g_tan_alpha": si / geo.tan_psi })
        }
        Dimension::Frequency => {
            json!({ "normalised": bare, "rad_s": si, "hz": si / std::f64::consts::TAU, "period_s": std::f64::consts::TAU / si })
        }
        Dimension::Rotation => json!({ "normalised": bare, "rad": si, "deg": si.to_degrees() }),
        Dimension::AngularVelocity => json!({ "normalised": bare, "rad_s": si }),
        Dimension::Velocity => json!({ "normalised": bare, "m_s": si }),
        Dimension::Tau => json!({ "tau": bare, "s": si }),
        // Already physical: one number.
        Dimension::Length | Dimension::Pga | Dimension::Phase | Dimension::Seconds => json!(si),
    }
}

/// The key of the structure's section: `block`, or `frame` (whose
/// columns the sizes are).
pub(crate) fn structure_key(cfg: &Scenario) -> &'static str {
    if cfg.frame.is_some() {
        "frame"
    } else if cfg.stack.is_some() {
        "stack"
    } else {
        "block"
    }
}

/// Every resolved input both ways, normalised (as the scenario stores it)
/// and physical (seconds, radians and degrees, metres, g, Hz), so that a
/// run is understood without arithmetic.
pub fn resolved_json(cfg: &Scenario) -> Json {
    let geo = cfg.geometry();
    let x = &cfg.excitation;
    let mut sections = json!({
        structure_key(cfg): {
            "width_m": cfg.block.width,
            "height_m": cfg.block.height,
            "half_diagonal_m": geo.r,
            "alpha_rad": geo.psi,
            "alpha_deg": geo.psi.to_degrees(),
            "p_rad_s": geo.p,
            "seconds_per_tau": 1.0 / geo.p,
            "uplift_acceleration_g": geo.tan_psi,
        },
        "excitation": {
            "kind": x.kind.name(),
            "phase_h_deg": x.phase_h.to_degrees(),
            "phase_v_deg": x.phase_v.to_degrees(),
        },
        "initial": {},
        "run": { "record_tail_s": cfg.record_end_tau().and(cfg.run.record_tail_s) },
    });
    for (key, name) in BOTH_WAYS {
        let Some((k, d)) = spec(key).and_then(|k| Some((k, k.dimension()?))) else {
            continue;
        };
        let bare = match k.param {
            Some(Param::TauEnd) => Some(cfg.tau_end()),
            // Unset is not 0: it follows the base.
            Some(Param::XDot0) => cfg.initial.x_dot,
            Some(p) => Some(p.get(cfg)),
            None => None,
        };
        // A key that means nothing for this excitation (an amplitude of a
        // record run) is null.
        let value = bare
            .filter(|_| k.applies.to(x.kind))
            .map_or(Json::Null, |v| both_ways(d, v, &geo));
        if let Some(section) = sections.get_mut(k.section()).and_then(Json::as_object_mut) {
            section.insert(name.to_string(), value);
        }
    }
    // A stack: each block's size, slenderness and own frequency, bottom to
    // top (the bottom one's p is the run's time unit).
    if let (Some(blocks), Some(obj)) = (&cfg.stack, sections.as_object_mut()) {
        let list: Vec<Json> = blocks
            .iter()
            .map(|b| {
                let g = crate::model::Geometry::new(b.width, b.height);
                json!({
                    "width_m": b.width,
                    "height_m": b.height,
                    "offset_m": b.offset,
                    "half_diagonal_m": g.r,
                    "alpha_rad": g.psi,
                    "alpha_deg": g.psi.to_degrees(),
                    "p_rad_s": g.p,
                    "uplift_acceleration_g": g.tan_psi,
                    "static": if b.mu_s.is_finite() { json!(b.mu_s) } else { json!("inf") },
                    "glued": b.glued,
                })
            })
            .collect();
        obj.insert("stack".to_string(), Json::Array(list));
    }
    sections
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::scenario::ExcitationKind;

    /// The block's numbers and each key's physical forms against the
    /// definitions written out (θ = ψΘ, ω = pΩ, t = τ/p, a = ψgA) for a
    /// 1 × 4 m block under harmonic forcing.
    #[test]
    fn each_value_is_given_with_its_physical_forms() {
        let mut s = Scenario::default();
        s.block.width = 1.0;
        s.block.height = 4.0;
        s.excitation.kind = ExcitationKind::Harmonic;
        s.excitation.a_h = 2.0;
        s.excitation.omega_h = 3.0;
        s.initial.theta = 0.5;
        s.initial.x_dot = None;
        let r2 = 0.25f64 + 4.0;
        let (psi, half_diag) = (0.25f64.atan(), r2.sqrt());
        let p = (3.0 * 9.81 / (4.0 * half_diag)).sqrt();
        let j = resolved_json(&s);
        let close = |v: &Json, want: f64| (v.as_f64().unwrap() - want).abs() <= 1e-12 * want.abs().max(1.0);
        assert!(close(&j["block"]["p_rad_s"], p), "{}", j["block"]);
        assert!(close(&j["excitation"]["a_h"]["g"], 2.0 * psi), "{}", j["excitation"]);
        assert!(close(&j["excitation"]["a_h"]["over_g_tan_alpha"], 2.0 * psi / 0.25));
        assert!(close(
            &j["excitation"]["omega_h"]["hz"],
            3.0 * p / std::f64::consts::TAU
        ));
        assert!(close(&j["initial"]["theta"]["deg"], (0.5 * psi).to_degrees()));
        assert!(close(&j["run"]["end"]["s"], s.tau_end() / p));
        assert!(j["initial"]["x_dot"].is_null());
        // Ten keys both ways, plus the hand-written ones.
        let count = |section: &str| j[section].as_object().map_or(0, serde_json::Map::len);
        assert_eq!((count("excitation"), count("initial"), count("run")), (7, 3, 4));
    }

    #[test]
    fn amplitudes_and_frequencies_are_null_without_harmonic_or_pulse_forcing() {
        let mut s = Scenario::default();
        s.excitation.kind = ExcitationKind::None;
        let j = resolved_json(&s);
        assert!(j["excitation"]["a_h"].is_null() && j["excitation"]["omega_v"].is_null());
        assert!(j["initial"]["theta"].is_object());
    }
}
