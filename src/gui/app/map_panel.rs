//! The outcome map in the analyses panel, and loading the scene of a
//! clicked cell.

use super::{Message, RockingApp};
use crate::gui::panels::outcome_map::OutcomeMapView;
use crate::gui::settings::format_number;

impl RockingApp {
    /// The outcome-map view (its axes and resolution are public fields).
    pub fn outcome_map(&self) -> &OutcomeMapView {
        &self.outcome_map
    }

    /// The outcome-map view, to change its axes.
    pub fn outcome_map_mut(&mut self) -> &mut OutcomeMapView {
        &mut self.outcome_map
    }

    /// Draws the outcome map; a click on a cell loads its scene.
    pub(super) fn outcome_map_panel(&mut self, ui: &mut egui::Ui) {
        ui.label("Outcome map (click a cell to load its scene)");
        if let Some(cell) = self.outcome_map.show(ui, &self.settings, &self.config) {
            self.load_map_cell(&cell);
        }
    }

    /// Sets both keys of a map cell at once (one restart, through the same
    /// validation as the parameter panel), says so in the status bar and
    /// closes the lesson's note (it described the scene left behind);
    /// refuses with a message naming the key, changing nothing.
    pub fn load_map_cell(&mut self, cell: &[(String, f64); 2]) -> bool {
        let [(kx, vx), (ky, vy)] = cell;
        let next = self
            .settings
            .with(kx, &format_number(*vx))
            .and_then(|(s, _)| s.with(ky, &format_number(*vy)));
        match next {
            Ok((s, c)) => {
                self.apply(s, c);
                // Another scene: the lesson's note (what to look for in
                // the preset's motion) no longer describes it.
                self.lecture.note = None;
                self.message = Some(Message {
                    text: format!(
                        "from the outcome map: {kx} = {}, {ky} = {}",
                        format_number(*vx),
                        format_number(*vy)
                    ),
                    error: false,
                });
                true
            }
            Err(e) => {
                self.message = Some(Message { text: e, error: true });
                false
            }
        }
    }
}
