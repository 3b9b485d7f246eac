//! The choices a config names by a word: the impact law, the excitation's kind, a pulse's shape, the Lyapunov method and the spectrum's window.

/// Which impact law (`impact.law`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// Housner's law as the literature states it: Θ'₊ = (1 − 1.5 sin²ψ) Θ'₋
    /// and the new pivot sticks, stopping any slip (the default).
    Housner,
    /// Angular momentum about the striking corner conserved, pre-impact
    /// slip included (config name `corner-momentum`); equals `housner`
    /// when the block does not slip before the impact.
    #[serde(rename = "corner-momentum")]
    CornerMomentum,
    /// A given angular-velocity ratio r.
    Ratio,
    /// The paper's impulse–momentum law with restitution and friction.
    Impulse,
}

impl LawKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            LawKind::Housner => "housner",
            LawKind::CornerMomentum => "corner-momentum",
            LawKind::Ratio => "ratio",
            LawKind::Impulse => "impulse",
        }
    }
}

/// Which excitation (`excitation.kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ExcitationKind {
    /// No base motion.
    None,
    /// 2-D harmonic.
    Harmonic,
    /// Analytic pulse.
    Pulse,
    /// Recorded ground motion.
    Record,
}

impl ExcitationKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            ExcitationKind::None => "none",
            ExcitationKind::Harmonic => "harmonic",
            ExcitationKind::Pulse => "pulse",
            ExcitationKind::Record => "record",
        }
    }
}

/// Shape of a pulse (`excitation.shape`); the number of cycles of type C is
/// kept apart, in [`ExcitationSpec::cycles`](super::ExcitationSpec::cycles).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShapeKind {
    /// Makris type A (the default).
    OneSine,
    /// Makris type B.
    OneCosine,
    /// Type C_n.
    TypeC,
    /// Constant a_p for π/ω (Housner 1963).
    Rectangular,
    /// a_p sin(ωτ) for π/ω.
    HalfSine,
}

impl ShapeKind {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::OneSine => "one-sine",
            ShapeKind::OneCosine => "one-cosine",
            ShapeKind::TypeC => "type-c",
            ShapeKind::Rectangular => "rectangular",
            ShapeKind::HalfSine => "half-sine",
        }
    }
}

/// Which Lyapunov method a batch run adds (`analysis.lyapunov_method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LyapunovChoice {
    /// Tangent dynamics with saltation matrices: the whole spectrum (the
    /// default: it needs no separation parameter).
    Tangent,
    /// Benettin's two trajectories on the stroboscopic map.
    Benettin,
    /// Both on one trajectory, with their paired difference.
    Both,
}

impl LyapunovChoice {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            LyapunovChoice::Tangent => "tangent",
            LyapunovChoice::Benettin => "benettin",
            LyapunovChoice::Both => "both",
        }
    }
}

/// The part of the history a batch run's spectrum is taken over
/// (`analysis.spectrum_window`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpectrumRange {
    /// The whole history (the default).
    All,
    /// The paper's samples 3000–7095 at Δτ = 0.004 (τ 12–28.384).
    Paper,
}

impl SpectrumRange {
    /// Config name.
    pub fn name(self) -> &'static str {
        match self {
            SpectrumRange::All => "all",
            SpectrumRange::Paper => "paper",
        }
    }
}
