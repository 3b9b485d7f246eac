//! Short text shared by the files and the report: file-name stems and
//! the parameters and numbers of titles and tables. Here rather than in
//! [`super::write`] so that the report ([`super::report`]), which
//! `write` runs, does not import from it in turn.

use super::diagrams::Diagram;
use super::variant::Variant;
pub(crate) use crate::plot::labels::short_num;
use crate::plot::labels::{friction_text, num};
use crate::sim::Scenario;
use crate::sim::scenario::LawKind;

/// `figNN_` for figure `n`.
pub fn prefix(n: u32) -> String {
    format!("fig{n:02}_")
}

/// The base name of a diagram's files: `fig04_` or `fig04_variant_ralston_`.
pub(crate) fn diagram_stem(d: &Diagram) -> String {
    match d.variant {
        Variant::Paper => prefix(d.figure),
        Variant::Ralston
        | Variant::ContinuationUp
        | Variant::Housner
        | Variant::PrintedEq20
        | Variant::TumbleAtSide
        | Variant::FlightStop
        | Variant::ImpulseLaw
        | Variant::ImpactRatio(_) => format!("{}variant_{}_", prefix(d.figure), d.variant.slug()),
    }
}

/// The parameters that define a response in a short line:
/// `Ω_h = Ω_v = 8, A_h = 2, A_v = 2.5, no sliding`.
pub(crate) fn short_params(cfg: &Scenario, with_a_v: bool) -> String {
    let x = &cfg.excitation;
    let mut parts = Vec::new();
    if x.omega_h == x.omega_v() {
        parts.push(format!("Ω_h = Ω_v = {}", num(x.omega_h)));
    } else {
        parts.push(format!("Ω_h = {}, Ω_v = {}", num(x.omega_h), num(x.omega_v())));
    }
    parts.push(format!("A_h = {}", num(x.a_h)));
    if with_a_v {
        parts.push(format!("A_v = {}", num(x.a_v)));
    }
    parts.push(friction_text(cfg));
    parts.join(", ")
}

/// The impact law and block in a short line: `B × H = 1 × 4 m, impact ratio r = 0.925`.
pub(crate) fn block_and_impact(cfg: &Scenario) -> String {
    let law = match cfg.impact.law {
        LawKind::Housner => format!("Housner impact r = {:.4}", cfg.geometry().housner_r()),
        LawKind::CornerMomentum => "corner-momentum impact".to_string(),
        LawKind::Impulse => format!("impulse impact e = {}", num(cfg.impact.e)),
        LawKind::Ratio => format!("impact ratio r = {}", short_num(cfg.impact_r())),
    };
    format!("B × H = {} × {} m, {law}", num(cfg.block.width), num(cfg.block.height))
}
