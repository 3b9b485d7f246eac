//! The variants of a bifurcation diagram: each changes one thing of the
//! paper's computation, through the configuration only (the model's
//! equations are never altered), to test why a diagram differs from the
//! paper's. Shared by the diagrams ([`super::diagrams`]) and the response
//! examples ([`super::response`]), which run the impact-law variants too.

use crate::analysis::orbit_diagram::Continuation;
use crate::model::Geometry;

/// The paper's vertical restitution e = 0.925 (its section 4.1), used by
/// the `printed-eq20` variant.
pub(crate) const PAPER_E: f64 = 0.925;

/// One way of computing a bifurcation diagram.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Variant {
    /// The preset as it is: ratio law r = 0.925, DOP853, from rest, tumble
    /// at |Θ| = 1, flight ignored (the project's reading of the paper).
    Paper,
    /// The paper's integrator: Ralston's RK2 with fixed step 0.004
    /// (`run.method = "ralston"`).
    Ralston,
    /// Each A_v seeded from the previous smaller A_v's final state
    /// (continuation upwards) instead of from rest.
    ContinuationUp,
    /// Housner's impact law, r = 1 − 1.5 sin²ψ = 0.9118 (the paper's
    /// eq. 22) instead of r = 0.925.
    Housner,
    /// The paper's eq. 20 as printed, with its e = 0.925 as the vertical
    /// restitution and λ_x = −1 (no sliding): δ_i = 1 − 1.5 (1 + e) sin²ψ
    /// = 0.830, used as the angular-velocity ratio.
    PrintedEq20,
    /// Tumbling only when the block lies on its side (|θ| = π/2, i.e.
    /// `run.tumble_theta` = π/(2ψ)) instead of when the centre of mass
    /// passes over the pivot (|Θ| = 1).
    TumbleAtSide,
    /// The run stops when the normal force vanishes (`run.flight = "stop"`)
    /// instead of integrating the grounded equations on, as the paper did.
    FlightStop,
    /// The paper's own impact law with friction at impact, its eqs. 17–27
    /// (`impact.law = "impulse"`, e = 0, μ̄ = μ): for a block that does not
    /// slip it is Housner's law; a slipping corner loses energy to friction.
    ImpulseLaw,
    /// The `ratio` impact law with this angular-velocity ratio r instead of
    /// 0.925: a scan over r, to see whether any r reproduces the paper's
    /// ranges.
    ImpactRatio(f64),
}

/// The ratios r of the impact-ratio scan, besides those of the preset
/// (0.925), Housner (0.9118) and the printed eq. 20 (0.830): between and
/// around them.
pub(crate) const R_SCAN: [f64; 5] = [0.85, 0.87, 0.89, 0.94, 0.96];

impl Variant {
    /// The variants run for the investigation of a diagram that differs.
    pub(crate) const INVESTIGATION: [Variant; 6] = [
        Variant::Ralston,
        Variant::ContinuationUp,
        Variant::Housner,
        Variant::PrintedEq20,
        Variant::TumbleAtSide,
        Variant::FlightStop,
    ];

    /// Name used in file names and JSON (`paper`, `ralston`, `r0.85`, …).
    pub(crate) fn slug(self) -> String {
        match self {
            Variant::Paper => "paper".to_string(),
            Variant::Ralston => "ralston".to_string(),
            Variant::ContinuationUp => "continuation-up".to_string(),
            Variant::Housner => "housner".to_string(),
            Variant::PrintedEq20 => "printed-eq20".to_string(),
            Variant::TumbleAtSide => "tumble-at-side".to_string(),
            Variant::FlightStop => "flight-stop".to_string(),
            Variant::ImpulseLaw => "impulse".to_string(),
            Variant::ImpactRatio(r) => format!("r{r}"),
        }
    }

    /// What the variant changes, in a few words, for titles and tables.
    pub fn title(self) -> String {
        match self {
            Variant::Paper => "preset (r = 0.925, DOP853, from rest, tumble at |Θ| = 1, flight ignored)".to_string(),
            Variant::Ralston => "VARIANT: the paper's Ralston RK2, step 0.004".to_string(),
            Variant::ContinuationUp => "VARIANT: continuation upwards in A_v".to_string(),
            Variant::Housner => "VARIANT: Housner's r = 0.9118 (eq. 22)".to_string(),
            Variant::PrintedEq20 => "VARIANT: eq. 20 as printed with e = 0.925 (r = 0.830)".to_string(),
            Variant::TumbleAtSide => "VARIANT: tumble only at |θ| = π/2".to_string(),
            Variant::FlightStop => "VARIANT: stop at flight (N ≤ 0)".to_string(),
            Variant::ImpulseLaw => "VARIANT: the paper's impact law with friction, eqs. 17–27 (e = 0)".to_string(),
            Variant::ImpactRatio(r) => format!("VARIANT: impact ratio r = {r}"),
        }
    }

    /// What the variant changes, shortest form, for figure titles.
    pub(crate) fn short_label(self) -> String {
        match self {
            Variant::Paper => "preset".to_string(),
            Variant::Ralston => "Ralston RK2, fixed step 0.004 (the paper's integrator)".to_string(),
            Variant::ContinuationUp => "continuation upwards in A_v".to_string(),
            Variant::Housner => "Housner impact, r = 0.9118 (eq. 22)".to_string(),
            Variant::PrintedEq20 => "eq. 20 as printed, e = 0.925 → r = 0.830".to_string(),
            Variant::TumbleAtSide => "tumble only at |θ| = π/2".to_string(),
            Variant::FlightStop => "stop at flight (N ≤ 0)".to_string(),
            Variant::ImpulseLaw => "impact law of eqs. 17–27 with friction, e = 0".to_string(),
            Variant::ImpactRatio(r) => format!("impact ratio r = {r}"),
        }
    }

    /// The `--set` assignments of the variant for a block of geometry `geo`.
    pub fn sets(self, geo: &Geometry) -> Vec<String> {
        match self {
            Variant::Paper | Variant::ContinuationUp => Vec::new(),
            Variant::Ralston => vec!["run.method=ralston".to_string()],
            Variant::Housner => vec!["impact.law=housner".to_string()],
            Variant::PrintedEq20 => vec![
                "impact.law=ratio".to_string(),
                format!("impact.r={:?}", printed_eq20_ratio(geo, PAPER_E)),
            ],
            Variant::TumbleAtSide => vec![format!("run.tumble_theta={:?}", geo.side_theta())],
            Variant::FlightStop => vec!["run.flight=stop".to_string()],
            Variant::ImpulseLaw => vec!["impact.law=impulse".to_string(), "impact.e=0".to_string()],
            Variant::ImpactRatio(r) => vec!["impact.law=ratio".to_string(), format!("impact.r={r:?}")],
        }
    }

    /// How the values are seeded.
    pub fn continuation(self) -> Continuation {
        match self {
            Variant::ContinuationUp => Continuation::Up,
            Variant::Paper
            | Variant::Ralston
            | Variant::Housner
            | Variant::PrintedEq20
            | Variant::TumbleAtSide
            | Variant::FlightStop
            | Variant::ImpulseLaw
            | Variant::ImpactRatio(_) => Continuation::None,
        }
    }
}

/// The paper's eq. 20 for an impact without sliding (λ_x = −1):
/// δ_i = 1 − (3/2)(1 + e) sin²ψ, with `e` its vertical restitution.
pub(crate) fn printed_eq20_ratio(geo: &Geometry, e: f64) -> f64 {
    1.0 - 1.5 * (1.0 + e) * geo.sin_psi * geo.sin_psi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::config::load;

    #[test]
    fn variants_set_what_they_say() {
        let geo = Geometry::new(1.0, 4.0);
        let r = printed_eq20_ratio(&geo, PAPER_E);
        assert!((r - (1.0 - 1.5 * 1.925 / 17.0)).abs() < 1e-12, "{r}");
        for v in Variant::INVESTIGATION {
            let cfg = load(Some("fig4"), None, &v.sets(&geo)).unwrap();
            match v {
                Variant::Ralston => assert_eq!(cfg.run.method().name(), "ralston"),
                Variant::Housner => assert_eq!(cfg.impact.law.name(), "housner"),
                Variant::PrintedEq20 => assert_eq!(cfg.impact_r(), r),
                Variant::TumbleAtSide => assert_eq!(cfg.run.tumble_theta, geo.side_theta()),
                Variant::FlightStop => assert_eq!(cfg.run.flight, crate::model::FlightPolicy::Stop),
                Variant::ContinuationUp => assert_eq!(v.continuation(), Continuation::Up),
                Variant::Paper | Variant::ImpulseLaw | Variant::ImpactRatio(_) => unreachable!(),
            }
        }
    }

    #[test]
    fn an_impact_ratio_variant_sets_the_ratio_law() {
        let geo = Geometry::new(1.0, 4.0);
        let cfg = load(Some("fig4"), None, &Variant::ImpactRatio(0.87).sets(&geo)).unwrap();
        assert_eq!((cfg.impact.law.name(), cfg.impact_r()), ("ratio", 0.87));
        assert_eq!(Variant::ImpactRatio(0.87).slug(), "r0.87");
    }
}
