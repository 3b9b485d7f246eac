//! Axis labels with units, titles naming the fixed parameters, and the
//! colour of each response class, shared by every figure.

use plotters::style::RGBColor;

use super::hues;
use crate::analysis::classify::Response;
use crate::sim::scenario::{ExcitationKind, LawKind};
use crate::sim::{Param, Scenario};

/// A number as short as it can be written without losing its value
/// (`8`, `0.925`, `2.5`).
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// Decimal places that write every value of a grid `from + i·step`
/// exactly as typed (`0.02` → 2), at most 12.
pub(crate) fn grid_decimals(from: f64, step: f64) -> usize {
    let exact = |x: f64, d: i32| {
        let scaled = x * 10f64.powi(d);
        (scaled - scaled.round()).abs() <= 1e-6 * scaled.abs().max(1.0)
    };
    (0..=12).find(|&d| exact(step, d) && exact(from, d)).unwrap_or(12) as usize
}

/// A grid value with `decimals` places (`1.7000000000000002` → `1.70`):
/// for titles and summaries; files keep the exact value.
pub(crate) fn grid_num(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}")
}

/// The axis label of a parameter, with its unit.
pub(crate) fn param_label(param: Param) -> String {
    let label = match param {
        Param::Av => "A_v, vertical amplitude (units of ψ g)",
        Param::Ah => "A_h, horizontal amplitude (units of ψ g)",
        Param::OmegaH => "Ω_h, horizontal frequency (units of p)",
        Param::OmegaV => "Ω_v, vertical frequency (units of p)",
        Param::PhaseH => "Φ_h, horizontal phase (rad)",
        Param::PhaseV => "Φ_v, vertical phase (rad)",
        Param::MuS => "μ_s, static friction coefficient",
        Param::MuK => "μ_k, kinetic friction coefficient",
        Param::ImpactR => "r, angular-velocity ratio at impact",
        Param::ImpactE => "e, vertical restitution at impact",
        Param::Width => "B, block width (m)",
        Param::Height => "H, block height (m)",
        Param::Theta0 => "Θ(0) = θ(0)/ψ",
        Param::ThetaDot0 => "Θ'(0) = dΘ/dτ at τ = 0",
        other => other.key(),
    };
    label.to_string()
}

/// The short symbol of a parameter, for titles (`A_v`, `Ω_h`, …).
pub(crate) fn param_symbol(param: Param) -> String {
    let s = match param {
        Param::Av => "A_v",
        Param::Ah => "A_h",
        Param::OmegaH => "Ω_h",
        Param::OmegaV => "Ω_v",
        Param::MuS => "μ_s",
        Param::MuK => "μ_k",
        Param::ImpactR => "r",
        Param::ImpactE => "e",
        Param::Width => "B",
        Param::Height => "H",
        Param::Theta0 => "Θ(0)",
        Param::ThetaDot0 => "Θ'(0)",
        other => other.key(),
    };
    s.to_string()
}

/// What a section point's Θ is, as an axis label: the block's θ/ψ, or a
/// stack's top block's rotation over its own α
/// ([`stack_steady`](crate::analysis::steady::stack_steady)).
pub(crate) fn section_theta(cfg: &Scenario) -> &'static str {
    if cfg.stack.is_some() {
        "Θ = φ/α of the top block at τ_k = 2πk/Ω_h"
    } else {
        "Θ = θ/ψ at τ_k = 2πk/Ω_h"
    }
}

/// What a sweep's or a map's `theta` and `theta_dot` are, for its JSON's
/// `units` line.
pub(crate) fn section_units(cfg: &Scenario) -> &'static str {
    if cfg.stack.is_some() {
        "theta = φ/α of the top block (its rotation φ = q_1 + … + q_K over its own α = atan(B/H)), theta_dot = dΘ/dτ, τ the bottom block's; max_abs_theta the top block's; x, x_dot the stack's slip on its floor and its rate per the bottom block's R"
    } else {
        "theta = θ/ψ, theta_dot = dΘ/dτ"
    }
}

/// A number with at most 4 decimals, trailing zeros dropped.
pub fn short_num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.is_empty() || s == "-" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// The parameters of `cfg` that define a harmonic response, except those in
/// `varied`: block, excitation, friction and impact law, e.g.
/// `B × H = 1 × 4 m, Ω_h = Ω_v = 8, A_h = 3, no sliding, impact ratio r = 0.925`.
pub(crate) fn fixed_parameters(cfg: &Scenario, varied: &[Param]) -> String {
    let free = |p: Param| !varied.contains(&p);
    let x = &cfg.excitation;
    // A stack's normalised values come from the physical ones it is given
    // in (its presets': g, Hz), so they are shown to 4 decimals.
    let num = |v: f64| if cfg.stack.is_some() { short_num(v) } else { num(v) };
    let mut parts = Vec::new();
    if let Some(blocks) = &cfg.stack {
        // A stack's own sizes, impact law and friction (it does not slide).
        let sizes: Vec<String> = blocks
            .iter()
            .map(|b| format!("{} × {}", num(b.width), num(b.height)))
            .collect();
        parts.push(format!("{}-block stack {} m", blocks.len(), sizes.join(" + ")));
    } else if free(Param::Width) && free(Param::Height) {
        parts.push(format!(
            "B × H = {} × {} m",
            num(cfg.block.width),
            num(cfg.block.height)
        ));
    }
    if x.kind == ExcitationKind::Harmonic {
        let (oh, ov) = (free(Param::OmegaH), free(Param::OmegaV));
        if oh && ov && x.omega_h == x.omega_v() {
            parts.push(format!("Ω_h = Ω_v = {}", num(x.omega_h)));
        } else {
            if oh {
                parts.push(format!("Ω_h = {}", num(x.omega_h)));
            }
            if ov && x.omega_v.is_none() && !oh {
                // Ω_v follows Ω_h, which is varied: it varies with it.
                parts.push("Ω_v = Ω_h".to_string());
            } else if ov {
                parts.push(format!("Ω_v = {}", num(x.omega_v())));
            }
        }
        if free(Param::Ah) {
            parts.push(format!("A_h = {}", num(x.a_h)));
        }
        if free(Param::Av) {
            parts.push(format!("A_v = {}", num(x.a_v)));
        }
        if free(Param::PhaseH) && x.phase_h != 0.0 {
            parts.push(format!("Φ_h = {}", num(x.phase_h)));
        }
        if free(Param::PhaseV) && x.phase_v != 0.0 {
            parts.push(format!("Φ_v = {}", num(x.phase_v)));
        }
    }
    if cfg.stack.is_some() {
        parts.push("no sliding".to_string());
        return parts.join(", ");
    }
    if free(Param::MuS) && free(Param::MuK) {
        parts.push(friction_text(cfg));
    }
    match cfg.impact.law {
        LawKind::Ratio if free(Param::ImpactR) => parts.push(format!("impact ratio r = {}", num(cfg.impact_r()))),
        LawKind::Impulse if free(Param::ImpactE) => parts.push(format!("impulse impact, e = {}", num(cfg.impact.e))),
        LawKind::Housner => parts.push(format!("Housner impact (r = {:.4})", cfg.geometry().housner_r())),
        LawKind::CornerMomentum => parts.push("corner-momentum impact".to_string()),
        _ => {}
    }
    parts.join(", ")
}

/// The block's friction for a title: `no sliding` or `μ_s = 0.4, μ_k = 0.35`.
pub(crate) fn friction_text(cfg: &Scenario) -> String {
    if cfg.block.mu_s.is_infinite() {
        "no sliding".to_string()
    } else {
        format!("μ_s = {}, μ_k = {}", num(cfg.block.mu_s), num(cfg.block.kinetic()))
    }
}

/// The colour of a response class: periods 1, 2, 3, 4 in distinct hues,
/// longer periods teal, quasiperiodic olive, chaotic red, tumbled near
/// black, rest light grey, flight pink (colour-blind-safe-ish: the classes
/// that matter most, period 1/2, chaos and tumbling, differ in lightness
/// too).
pub(crate) fn response_colour(r: Response) -> RGBColor {
    match r {
        Response::Periodic { period: 1 } => hues::BLUE,
        Response::Periodic { period: 2 } => hues::GREEN,
        Response::Periodic { period: 3 } => hues::PURPLE,
        Response::Periodic { period: 4 } => hues::ORANGE,
        Response::Periodic { .. } => hues::CYAN,
        Response::Quasiperiodic => hues::OLIVE,
        Response::Chaotic => hues::RED,
        Response::Tumbled => RGBColor(45, 45, 45),
        Response::Rest => RGBColor(200, 200, 200),
        Response::Flight => hues::PINK,
    }
}

/// The legend text of a response class: `period 2 (1,2)`, `chaotic`, …
/// Periods above 4 share one colour, so `period k > 4` names them together.
pub(crate) fn response_label(r: Response) -> String {
    match r {
        Response::Periodic { period } if period <= 4 => format!("period {period} (1,{period})"),
        Response::Periodic { .. } => "period > 4".to_string(),
        Response::Quasiperiodic | Response::Chaotic | Response::Tumbled | Response::Rest | Response::Flight => {
            r.name().to_string()
        }
    }
}

/// The legend group of a response: periods above 4 share one entry.
pub(crate) fn legend_key(r: Response) -> Response {
    match r {
        Response::Periodic { period } if period > 4 => Response::Periodic { period: 5 },
        other => other,
    }
}

/// Legend groups present in `responses`, in a fixed order (rest, periods,
/// quasiperiodic, chaotic, tumbled, flight).
pub(crate) fn legend_entries(responses: impl Iterator<Item = Response>) -> Vec<Response> {
    let order = |r: &Response| match r {
        Response::Rest => 0,
        Response::Periodic { period } => *period,
        Response::Quasiperiodic => 100,
        Response::Chaotic => 101,
        Response::Tumbled => 102,
        Response::Flight => 103,
    };
    let mut v: Vec<Response> = responses.map(legend_key).collect();
    v.sort_by_key(order);
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::config::load;

    #[test]
    fn a_vertical_frequency_that_follows_a_varied_horizontal_one_is_not_shown_fixed() {
        let cfg = load(Some("fig3"), None, &[]).unwrap();
        let t = fixed_parameters(&cfg, &[Param::Ah, Param::OmegaH]);
        assert!(t.contains("Ω_v = Ω_h") && !t.contains("Ω_v = 8"), "{t}");
        let set = vec!["excitation.omega_v=8".to_string()];
        let cfg = load(Some("fig3"), None, &set).unwrap();
        assert!(fixed_parameters(&cfg, &[Param::OmegaH]).contains("Ω_v = 8"));
    }

    #[test]
    fn fig4_title_names_its_fixed_parameters() {
        let cfg = load(Some("fig4"), None, &[]).unwrap();
        assert_eq!(
            fixed_parameters(&cfg, &[Param::Av]),
            "B × H = 1 × 4 m, Ω_h = Ω_v = 8, A_h = 3, no sliding, impact ratio r = 0.925"
        );
        let cfg = load(Some("fig9"), None, &[]).unwrap();
        let t = fixed_parameters(&cfg, &[Param::Av]);
        assert!(t.contains("μ_s = 0.4, μ_k = 0.35"), "{t}");
    }

    #[test]
    fn legend_groups_long_periods() {
        let e = legend_entries(
            [
                Response::Chaotic,
                Response::Periodic { period: 7 },
                Response::Periodic { period: 1 },
                Response::Periodic { period: 9 },
                Response::Rest,
            ]
            .into_iter(),
        );
        assert_eq!(
            e,
            vec![
                Response::Rest,
                Response::Periodic { period: 1 },
                Response::Periodic { period: 5 },
                Response::Chaotic
            ]
        );
        assert_eq!(response_label(Response::Periodic { period: 2 }), "period 2 (1,2)");
        assert_eq!(param_label(Param::Av), "A_v, vertical amplitude (units of ψ g)");
        assert_eq!(param_label(Param::ZenoEps), "run.zeno_eps");
    }

    #[test]
    fn grid_values_print_as_typed() {
        assert_eq!(grid_decimals(0.0, 0.02), 2);
        assert_eq!(grid_decimals(1.5, 0.25), 2);
        assert_eq!(grid_decimals(2.0, 1.0), 0);
        assert_eq!(grid_num(85.0 * 0.02, grid_decimals(0.0, 0.02)), "1.70");
    }
}
