//! The classes the outcome map tells apart, with their legend names and
//! colours, and the colours of a basin map's attractors (the figure's, from
//! [`crate::plot::outcome_map`], so the panel and `rocking map` agree).

use egui::Color32;

use super::mapper::Class;
use crate::analysis::classify::Response;

/// The classes the map tells apart, in legend order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Slot {
    /// At rest.
    Rest,
    /// Period 1.
    Period1,
    /// Period 2.
    Period2,
    /// Period k ≥ 3.
    PeriodK,
    /// Quasiperiodic.
    Quasiperiodic,
    /// Chaotic.
    Chaotic,
    /// Tumbled.
    Tumbled,
    /// Left the base.
    Flight,
    /// The run failed.
    Failed,
}

/// The colour of attractor `id` (from 1): the one `rocking map`'s figure
/// gives it.
pub fn attractor_color(id: u32) -> Color32 {
    let c = crate::plot::outcome_map::attractor_colour(id);
    Color32::from_rgb(c.0, c.1, c.2)
}

impl Slot {
    /// Every slot, in legend order.
    pub const ALL: [Slot; 9] = [
        Slot::Rest,
        Slot::Period1,
        Slot::Period2,
        Slot::PeriodK,
        Slot::Quasiperiodic,
        Slot::Chaotic,
        Slot::Tumbled,
        Slot::Flight,
        Slot::Failed,
    ];

    /// The slot of a cell's class.
    pub fn of(class: Class) -> Slot {
        match class {
            None => Slot::Failed,
            Some(Response::Rest) => Slot::Rest,
            Some(Response::Periodic { period: 1 }) => Slot::Period1,
            Some(Response::Periodic { period: 2 }) => Slot::Period2,
            Some(Response::Periodic { .. }) => Slot::PeriodK,
            Some(Response::Quasiperiodic) => Slot::Quasiperiodic,
            Some(Response::Chaotic) => Slot::Chaotic,
            Some(Response::Tumbled) => Slot::Tumbled,
            Some(Response::Flight) => Slot::Flight,
        }
    }

    /// Whether the slot is a periodic class (coloured by attractor in a
    /// basin map).
    pub(crate) fn is_periodic(self) -> bool {
        match self {
            Slot::Period1 | Slot::Period2 | Slot::PeriodK => true,
            Slot::Rest | Slot::Quasiperiodic | Slot::Chaotic | Slot::Tumbled | Slot::Flight | Slot::Failed => false,
        }
    }

    /// Legend name.
    pub fn name(self) -> &'static str {
        match self {
            Slot::Rest => "rest",
            Slot::Period1 => "period 1",
            Slot::Period2 => "period 2",
            Slot::PeriodK => "period k ≥ 3",
            Slot::Quasiperiodic => "quasiperiodic",
            Slot::Chaotic => "chaotic",
            Slot::Tumbled => "tumbled",
            Slot::Flight => "flight",
            Slot::Failed => "failed",
        }
    }

    /// Fill colour: blues for the periodic family (darker for longer
    /// periods), green quasiperiodic, orange chaotic, grey rest, dark red
    /// tumbled (the overturned region, the map's point), purple flight.
    pub fn color(self) -> Color32 {
        match self {
            Slot::Rest => Color32::from_gray(150),
            Slot::Period1 => Color32::from_rgb(150, 200, 255),
            Slot::Period2 => Color32::from_rgb(80, 140, 235),
            Slot::PeriodK => Color32::from_rgb(35, 75, 170),
            Slot::Quasiperiodic => Color32::from_rgb(120, 220, 140),
            Slot::Chaotic => Color32::from_rgb(255, 170, 80),
            Slot::Tumbled => Color32::from_rgb(150, 30, 40),
            Slot::Flight => Color32::from_rgb(190, 110, 230),
            Slot::Failed => Color32::from_rgb(255, 60, 200),
        }
    }
}
