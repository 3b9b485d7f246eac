//! What a key measures: the units that fit it and what a bare number
//! means. The config parser converts with it (`io::config::quantity`), the
//! Python package states it in `help(rocking.Scene)`, and the app shows the
//! bare number's unit from it.

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
}
