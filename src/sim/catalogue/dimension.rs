//! What a key measures: the units that fit it, what a bare number means,
//! and the one conversion between the model's normalised numbers and
//! physical units. The config parser converts with it
//! (`io::config::quantity`), `summary.json`'s `resolved` block
//! (`io::output`) and the app's units switch (`gui::units`) too; the Python
//! package states it in `help(rocking.Scene)`.
//!
//! The physical unit of each dimension: m, g (accelerations), rad/s
//! (frequencies, angular velocities), rad, m/s, s. The bare number is the
//! model's: Θ = θ/ψ, Θ' = θ̇/(ψ p), X' = ẋ/(R p), Ω = ω/p, τ = p t, A = a/(ψ g).

use crate::model::Geometry;

/// What a key measures, which decides the units that fit it and what a bare
/// number means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// A block size; bare: m.
    Length,
    /// A base amplitude; bare: units of ψ g (the scenario's A).
    Amplitude,
    /// A peak ground acceleration; stored in g; a unit is required.
    Pga,
    /// A forcing frequency; bare: units of p (the scenario's Ω).
    Frequency,
    /// A phase; bare: rad.
    Phase,
    /// A rotation; bare: Θ = θ/ψ.
    Rotation,
    /// An angular velocity; bare: Θ' = θ̇/(ψ p).
    AngularVelocity,
    /// A velocity of the centre of mass; bare: X' = ẋ/(R p).
    Velocity,
    /// A duration in τ; bare: τ = p t.
    Tau,
    /// A duration in seconds; bare: s.
    Seconds,
}

impl Dimension {
    /// The units that fit, and what a bare number means, for messages.
    pub fn fits(self) -> &'static str {
        match self {
            Dimension::Length => "a length: m, cm, mm (bare: m)",
            Dimension::Amplitude => "an acceleration: g, m/s2, cm/s2 (gal), g*tan(alpha) (bare: units of psi*g)",
            Dimension::Pga => "an acceleration with its unit: g, m/s2, cm/s2, g*tan(alpha), e.g. \"0.4 g\"",
            Dimension::Frequency => "a frequency: Hz, rad/s (bare: units of p)",
            Dimension::Phase => "an angle: rad, deg (bare: rad)",
            Dimension::Rotation => "an angle: rad, deg (bare: theta/psi)",
            Dimension::AngularVelocity => "an angular velocity: rad/s, deg/s (bare: units of psi*p)",
            Dimension::Velocity => "a velocity: m/s, cm/s (bare: units of R*p)",
            Dimension::Tau => "a time: s, ms (bare: tau = p*t)",
            Dimension::Seconds => "a time: s, ms (bare: s)",
        }
    }

    /// For a dimension whose bare number is normalised by the block (ψ,
    /// p, R): a physical unit to suggest, and what the bare number is.
    /// `None` where a bare number is SI (m, rad, s) or not allowed (a PGA).
    pub fn normalised(self) -> Option<(&'static str, &'static str)> {
        Some(match self {
            Dimension::Amplitude => ("g", "units of psi*g"),
            Dimension::Frequency => ("Hz", "units of p"),
            Dimension::Rotation => ("rad", "theta/psi"),
            Dimension::AngularVelocity => ("rad/s", "units of psi*p"),
            Dimension::Velocity => ("m/s", "units of R*p"),
            Dimension::Tau => ("s", "tau = p*t"),
            Dimension::Length | Dimension::Pga | Dimension::Phase | Dimension::Seconds => return None,
        })
    }

    /// The model's (bare) number of a value in this dimension's physical
    /// unit, for block `geo`.
    pub(crate) fn to_bare(self, physical: f64, geo: &Geometry) -> f64 {
        match self {
            Dimension::Length | Dimension::Pga | Dimension::Phase | Dimension::Seconds => physical,
            Dimension::Amplitude | Dimension::Rotation => physical / geo.psi,
            Dimension::Frequency => physical / geo.p,
            Dimension::AngularVelocity => physical / (geo.psi * geo.p),
            Dimension::Velocity => physical / (geo.r * geo.p),
            Dimension::Tau => physical * geo.p,
        }
    }

    /// The inverse of [`Dimension::to_bare`]: a bare number in this
    /// dimension's physical unit.
    pub(crate) fn to_physical(self, bare: f64, geo: &Geometry) -> f64 {
        match self {
            Dimension::Length | Dimension::Pga | Dimension::Phase | Dimension::Seconds => bare,
            Dimension::Amplitude | Dimension::Rotation => bare * geo.psi,
            Dimension::Frequency => bare * geo.p,
            Dimension::AngularVelocity => bare * geo.psi * geo.p,
            Dimension::Velocity => bare * geo.r * geo.p,
            Dimension::Tau => bare / geo.p,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each conversion against the model's definitions written out: a
    /// 0.6 × 2 m block, θ = ψΘ, θ̇ = ψpΘ', ẋ = RpX', ω = pΩ, t = τ/p, a = ψgA.
    #[test]
    fn bare_and_physical_are_the_models_definitions_both_ways() {
        let geo = Geometry::new(0.6, 2.0);
        let (psi, p, r) = (
            (0.3f64).atan(),
            (3.0 * 9.81 / (4.0 * (0.3f64.powi(2) + 1.0).sqrt())).sqrt(),
            (0.3f64.powi(2) + 1.0).sqrt(),
        );
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
        assert!(close(geo.psi, psi) && close(geo.p, p) && close(geo.r, r));
        let cases = [
            (Dimension::Length, 1.0),
            (Dimension::Pga, 1.0),
            (Dimension::Phase, 1.0),
            (Dimension::Seconds, 1.0),
            (Dimension::Amplitude, psi),
            (Dimension::Rotation, psi),
            (Dimension::Frequency, p),
            (Dimension::AngularVelocity, psi * p),
            (Dimension::Velocity, r * p),
            (Dimension::Tau, 1.0 / p),
        ];
        for (d, physical_per_bare) in cases {
            assert!(close(d.to_physical(0.7, &geo), 0.7 * physical_per_bare), "{d:?}");
            assert!(close(d.to_bare(d.to_physical(0.7, &geo), &geo), 0.7), "{d:?}");
        }
    }
}
