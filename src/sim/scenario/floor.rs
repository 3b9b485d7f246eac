//! The building between the ground and the block (`[floor]`): its modes and the bounds and defaults they are read with.

/// Default damping ratio of a building mode (`floor.damping`): 5 % of
/// critical, the damping design spectra are written for (ASCE 7-22
/// §11.4, Eurocode 8 §3.2.2.2) and the usual value for reinforced-concrete
/// and steel buildings shaken near their design level.
pub(crate) const FLOOR_DAMPING: f64 = 0.05;

/// Default participation Γφ of a single building mode at the floor
/// (`floor.participation`): 1, the floor as the mass of a one-storey
/// building, which makes the floor acceleration the oscillator's absolute
/// acceleration a_f = −2ζωu̇ − ω²u (the floor-spectrum convention). A
/// uniform shear building has (4/π) sin(πz/2H) at height z (docs/model.md,
/// "Floor motion"); give that for a floor of a taller building.
pub(crate) const FLOOR_PARTICIPATION: f64 = 1.0;

/// Shortest building period accepted, s (`floor.period`): 0.01 s is a
/// 100 Hz mode, above any frequency ground shaking carries (about
/// 0.1–30 Hz), so such a floor is rigid; leave `[floor]` out instead. A
/// shorter period would also force the integrator's steps down to 1/ω.
pub(crate) const MIN_FLOOR_PERIOD_S: f64 = 0.01;

/// Longest building period accepted, s: the tallest buildings have
/// fundamental periods under about 10 s; 20 s is a typo or a wrong unit.
pub(crate) const MAX_FLOOR_PERIOD_S: f64 = 20.0;

/// Largest |Γφ| accepted (`floor.participation`): a uniform shear
/// building's first mode has 4/π ≈ 1.27 at its roof and higher modes less;
/// 10 is a typo, not a building.
pub(crate) const MAX_FLOOR_PARTICIPATION: f64 = 10.0;

/// One mode of the building the block stands in (`[floor]` or one
/// `[[floor.mode]]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorModeSpec {
    /// Period T, s, in [[`MIN_FLOOR_PERIOD_S`], [`MAX_FLOOR_PERIOD_S`]].
    pub period_s: f64,
    /// Damping ratio ζ, fraction of critical, in (0, 1). Default
    /// [`FLOOR_DAMPING`].
    pub damping: f64,
    /// Γφ at the floor. Default [`FLOOR_PARTICIPATION`].
    pub participation: f64,
}

/// The building between the ground and the block (`[floor]`): the block
/// feels the ground's horizontal motion filtered through these modes.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorSpec {
    /// The modes (at least one).
    pub modes: Vec<FloorModeSpec>,
    /// Whether they were given as `[[floor.mode]]` tables (for the config
    /// written back).
    pub as_tables: bool,
}
