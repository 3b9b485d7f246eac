//! The units the app shows numbers in: the model's normalised variables
//! (τ, Θ = θ/ψ, X per R), as the paper plots them, or an engineer's
//! physical ones (t in s, θ in degrees, sliding in cm).
//!
//! Contract: this is the app's one place that converts between the two,
//! through the core's one conversion ([`Dimension`]). Every conversion is
//! a scale of a value the simulation thread sent, with
//! the block's geometry from [`crate::sim::protocol::RunInfo`] (τ = p t,
//! θ = ψΘ, x = R X); the sliding displacement itself is the core's
//! ([`Geometry::sliding`]). Axis titles come from here too, so an axis and
//! its numbers cannot disagree about the unit.

use crate::model::geometry::Geometry;
use crate::sim::catalogue::Dimension;
use crate::sim::scenario::ExcitationKind;

/// Which units numbers are shown in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// t in s, θ in degrees, θ' in deg/s, sliding in cm, frequencies in Hz.
    Physical,
    /// The model's τ, Θ, Θ', X and ω/p (MODEL-DECISIONS).
    Normalised,
}

impl Units {
    /// What a scene of `kind` opens in: physical for a recorded earthquake
    /// (its audience thinks in seconds and degrees), normalised for the
    /// paper's harmonic and pulse scenes (the paper's figures are in τ and Θ).
    pub fn default_for(kind: ExcitationKind) -> Self {
        match kind {
            ExcitationKind::Record => Units::Physical,
            ExcitationKind::Harmonic | ExcitationKind::Pulse | ExcitationKind::None => Units::Normalised,
        }
    }

    /// The switch's word for it.
    pub fn name(self) -> &'static str {
        match self {
            Units::Physical => "physical",
            Units::Normalised => "normalised",
        }
    }
}

/// Centimetres per metre.
const CM_PER_M: f64 = 100.0;

/// Conversions from the model's variables to the shown ones, for one block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// The units shown.
    pub units: Units,
    geo: Geometry,
    /// The block of a stack the rotation is (its name, as the outputs
    /// spell it); `None`: the single block.
    pub body: Option<&'static str>,
    /// The rotation the ±α lines mark, in Θ: 1 for the block (its α = ψ);
    /// a stack's block its own α_j over the bottom block's ψ.
    tip: f64,
}

/// The names a stack's blocks go by (`sim::stack_answer::body_name`).
const BODY_NAMES: [&str; 6] = [
    "bottom block",
    "block 2",
    "middle block",
    "block 3",
    "block 4",
    "top block",
];

/// Each body's rotation and rate titles (physical, then normalised),
/// made once: the axis titles are borrowed for the life of the app.
static BODY_LABELS: std::sync::LazyLock<Vec<[String; 4]>> = std::sync::LazyLock::new(|| {
    BODY_NAMES
        .iter()
        .map(|b| {
            [
                // The quantity first: a title cut short in a small plot
                // keeps what the axis measures.
                format!("φ [deg], {b}"),
                format!("φ' [deg/s], {b}"),
                format!("φ/ψ₁, {b}"),
                format!("dφ/dτ / ψ₁, {b}"),
            ]
        })
        .collect()
});

/// Title `which` (0 φ, 1 φ' physical; 2, 3 normalised) of body `name`.
fn body_label(name: &str, which: usize) -> Option<&'static str> {
    let i = BODY_NAMES.iter().position(|b| *b == name)?;
    BODY_LABELS.get(i).map(|l| l[which].as_str())
}

impl Scales {
    /// Conversions for a block of geometry `geo` shown in `units`.
    pub fn new(units: Units, geo: Geometry) -> Self {
        Self {
            units,
            geo,
            body: None,
            tip: 1.0,
        }
    }

    /// These conversions for block `name` of a stack (`top block`): the
    /// same numbers (a stack's Θ is a block's φ over the bottom block's
    /// ψ, its τ the bottom block's), titled with the block's name.
    /// `alpha` is the block's own slenderness atan(B/H), rad: where its
    /// ±α lines go.
    pub(crate) fn with_body(self, name: &'static str, alpha: f64) -> Self {
        Self {
            body: Some(name),
            tip: alpha / self.geo.psi,
            ..self
        }
    }

    /// Time: τ → t in s (t = τ/p), or τ.
    pub fn time(&self, tau: f64) -> f64 {
        match self.units {
            Units::Physical => Dimension::Tau.to_physical(tau, &self.geo),
            Units::Normalised => tau,
        }
    }

    /// The inverse of [`Scales::time`]: a shown time → τ.
    pub(crate) fn tau_of(&self, shown: f64) -> f64 {
        match self.units {
            Units::Physical => Dimension::Tau.to_bare(shown, &self.geo),
            Units::Normalised => shown,
        }
    }

    /// Seconds → τ, whatever the units shown (a record's length is in s).
    pub(crate) fn tau_of_seconds(&self, t_s: f64) -> f64 {
        Dimension::Tau.to_bare(t_s, &self.geo)
    }

    /// τ → seconds, whatever the units shown (the banner speaks seconds).
    pub fn seconds(&self, tau: f64) -> f64 {
        Dimension::Tau.to_physical(tau, &self.geo)
    }

    /// Title of a time axis.
    pub(crate) fn time_label(&self) -> &'static str {
        match self.units {
            Units::Physical => "t [s]",
            Units::Normalised => "τ = p t",
        }
    }

    /// Unit suffix of a shown time (for value fields).
    pub(crate) fn time_suffix(&self) -> &'static str {
        match self.units {
            Units::Physical => " s",
            Units::Normalised => " τ",
        }
    }

    /// Rotation: Θ → θ in degrees (θ = ψΘ), or Θ.
    pub fn theta(&self, theta: f64) -> f64 {
        match self.units {
            Units::Physical => Dimension::Rotation.to_physical(theta, &self.geo).to_degrees(),
            Units::Normalised => theta,
        }
    }

    /// Title of a rotation axis.
    pub(crate) fn theta_label(&self) -> &'static str {
        let which = if self.units == Units::Physical { 0 } else { 2 };
        if let Some(l) = self.body.and_then(|b| body_label(b, which)) {
            return l;
        }
        match self.units {
            Units::Physical => "θ [deg]",
            Units::Normalised => "Θ = θ/ψ",
        }
    }

    /// Angular velocity: Θ' (per τ) → θ' in deg/s (θ' = ψ p Θ'), or Θ'.
    pub fn theta_dot(&self, theta_dot: f64) -> f64 {
        match self.units {
            Units::Physical => Dimension::AngularVelocity
                .to_physical(theta_dot, &self.geo)
                .to_degrees(),
            Units::Normalised => theta_dot,
        }
    }

    /// Title of an angular-velocity axis.
    pub(crate) fn theta_dot_label(&self) -> &'static str {
        let which = if self.units == Units::Physical { 1 } else { 3 };
        if let Some(l) = self.body.and_then(|b| body_label(b, which)) {
            return l;
        }
        match self.units {
            Units::Physical => "θ' [deg/s]",
            Units::Normalised => "Θ' = dΘ/dτ",
        }
    }

    /// The inverse of [`Scales::theta`] and [`Scales::theta_dot`]: a shown
    /// (rotation, angular velocity) → (Θ, Θ').
    pub(crate) fn state_of(&self, theta: f64, theta_dot: f64) -> (f64, f64) {
        match self.units {
            Units::Physical => (
                Dimension::Rotation.to_bare(theta.to_radians(), &self.geo),
                Dimension::AngularVelocity.to_bare(theta_dot.to_radians(), &self.geo),
            ),
            Units::Normalised => (theta, theta_dot),
        }
    }

    /// The horizontal coordinate the history draws: the sliding
    /// displacement in cm ([`Geometry::sliding`] × R), or X (the centre of
    /// mass relative to the base, per R) as the paper plots it.
    pub fn horizontal(&self, theta: f64, x: f64) -> f64 {
        match self.units {
            Units::Physical => self.geo.sliding(theta, x) * self.geo.r * CM_PER_M,
            Units::Normalised => x,
        }
    }

    /// The name of [`Scales::horizontal`] in a legend.
    pub(crate) fn horizontal_label(&self) -> &'static str {
        match self.units {
            Units::Physical => "sliding [cm]",
            Units::Normalised => "X (per R)",
        }
    }

    /// A sliding displacement per R → cm.
    pub(crate) fn sliding_cm(&self, per_r: f64) -> f64 {
        per_r * self.geo.r * CM_PER_M
    }

    /// The overturning angle of a block at rest (|Θ| = 1, θ = α = ψ), shown.
    pub(crate) fn tip_angle(&self) -> f64 {
        self.theta(self.tip)
    }

    /// Frequency: ω/p → f in Hz (f = ω p/2π), or ω/p.
    pub fn frequency(&self, omega_over_p: f64) -> f64 {
        match self.units {
            Units::Physical => Dimension::Frequency.to_physical(omega_over_p, &self.geo) / std::f64::consts::TAU,
            Units::Normalised => omega_over_p,
        }
    }

    /// Title of a frequency axis.
    pub(crate) fn frequency_label(&self) -> &'static str {
        match self.units {
            Units::Physical => "f [Hz]",
            Units::Normalised => "ω / p",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rack() -> Geometry {
        Geometry::new(0.6, 2.0)
    }

    #[test]
    fn physical_units_are_seconds_degrees_and_centimetres() {
        let geo = rack();
        let s = Scales::new(Units::Physical, geo);
        assert!((s.time(geo.p * 2.5) - 2.5).abs() < 1e-12, "τ = p t");
        assert!((s.theta(1.0) - geo.psi.to_degrees()).abs() < 1e-12, "Θ = 1 is α");
        assert!((s.tip_angle() - 16.699).abs() < 1e-3, "atan(0.3) = 16.70°");
        assert!((s.sliding_cm(1.0) - 100.0 * geo.r).abs() < 1e-12);
        // Flat and sliding: the sliding displacement is X.
        assert!((s.horizontal(0.0, 0.01) - geo.r).abs() < 1e-12);
        assert_eq!(s.time_label(), "t [s]");
        assert_eq!(s.theta_label(), "θ [deg]");
    }

    #[test]
    fn shown_values_convert_back_to_the_models() {
        let s = Scales::new(Units::Physical, rack());
        let (theta, theta_dot) = s.state_of(s.theta(0.37), s.theta_dot(-1.25));
        assert!((theta - 0.37).abs() < 1e-12 && (theta_dot + 1.25).abs() < 1e-12);
        assert!((s.tau_of(s.time(12.5)) - 12.5).abs() < 1e-12);
    }

    #[test]
    fn normalised_units_show_the_models_numbers() {
        let s = Scales::new(Units::Normalised, rack());
        assert_eq!((s.time(3.0), s.theta(0.5), s.theta_dot(2.0)), (3.0, 0.5, 2.0));
        assert_eq!(s.horizontal(0.2, 0.3), 0.3);
        assert_eq!(s.time_label(), "τ = p t");
    }

    #[test]
    fn records_open_in_physical_units_and_the_papers_scenes_in_normalised() {
        assert_eq!(Units::default_for(ExcitationKind::Record), Units::Physical);
        assert_eq!(Units::default_for(ExcitationKind::Harmonic), Units::Normalised);
    }
}
