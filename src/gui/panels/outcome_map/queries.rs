//! What the map view shows and where it stands: its cells, classes,
//! attractors, progress and timings, for the app's panel and the tests.

use std::time::Duration;

use egui_plot::PlotPoint;

use super::mapper::Class;
use super::{AxisChoice, OutcomeMapView, Slot};
use crate::analysis::attractor::Attractor;
use crate::analysis::map_refine::{Refiner, Source};
use crate::analysis::outcome_map::Label;

impl OutcomeMapView {
    /// Sets both axes (key, first and last value), as the controls do.
    pub fn set_axes(&mut self, x: (&str, f64, f64), y: (&str, f64, f64)) {
        let axis = |(key, from, to): (&str, f64, f64)| AxisChoice {
            key: key.to_string(),
            from,
            to,
        };
        self.x = axis(x);
        self.y = axis(y);
        self.edit = (self.x.clone(), self.y.clone());
        self.ranged = true;
    }

    /// Whether the current map has every level in.
    pub fn done(&self) -> bool {
        self.done
    }

    /// Why the current map was refused, if it was.
    pub fn invalid(&self) -> Option<&str> {
        self.invalid.as_deref()
    }

    /// Whether a map thread is still working.
    pub fn busy(&self) -> bool {
        self.mapper.as_ref().is_some_and(|m| !m.finished())
    }

    /// Map threads still running, cancelled ones included.
    pub fn threads(&self) -> usize {
        self.retired
            .iter()
            .chain(self.mapper.iter())
            .filter(|m| !m.finished())
            .count()
    }

    /// Cells drawn in the last picture, per class (classes with none left
    /// out), in legend order.
    pub fn drawn(&self) -> &[(Slot, usize)] {
        &self.counts
    }

    /// Cells of the current map computed so far (their batch recorded),
    /// and its total cells.
    pub fn computed(&self) -> (usize, usize) {
        let total = self.axes.as_ref().map_or(0, |(x, y)| x.n * y.n);
        (self.refiner.as_ref().map_or(0, Refiner::computed), total)
    }

    /// Cells of the current map done (computed as they arrive, and
    /// inherited), and its total cells: the progress line.
    pub fn progress(&self) -> (usize, usize) {
        let total = self.axes.as_ref().map_or(0, |(x, y)| x.n * y.n);
        let inherited = self.refiner.as_ref().map_or(0, Refiner::inherited);
        (self.received.0 + inherited, total)
    }

    /// Computed cells of the current map whose run stopped early (their
    /// class was certain before the end of the window).
    pub fn stopped_early(&self) -> usize {
        self.received.1
    }

    /// Whether the current map tells attractors apart (both keys are
    /// initial-state keys).
    pub fn is_basin(&self) -> bool {
        self.basin
    }

    /// A basin map's attractors so far, numbered from 1 by their first
    /// cell in row order (as `rocking map` numbers them).
    pub fn attractors(&self) -> &[Attractor] {
        &self.attractors.0
    }

    /// Cells drawn in the last picture per attractor (id, cells), by id.
    pub fn drawn_attractors(&self) -> &[(u32, usize)] {
        &self.attractor_counts
    }

    /// The label of cell (i, j) if known (computed or inherited), with a
    /// basin map's attractor numbered as [`attractors`](Self::attractors)
    /// numbers it.
    pub fn label(&self, i: usize, j: usize) -> Option<Label> {
        let r = self.refiner.as_ref()?;
        let (x, y) = self.axes.as_ref()?;
        if i >= x.n || j >= y.n {
            return None;
        }
        let label = r.class(j * x.n + i)?;
        Some(Label {
            response: label.response,
            attractor: label.attractor.map(|d| self.attractor_id(d)),
        })
    }

    /// The id of discovery number `d` (0 before the attractors arrive).
    pub(super) fn attractor_id(&self, d: u32) -> u32 {
        self.attractors.1.get(d as usize).copied().unwrap_or(0)
    }

    /// Time from the start of the current map to its coarse level drawn
    /// complete, and to the whole map.
    pub fn timings(&self) -> (Option<Duration>, Option<Duration>) {
        (self.first_level, self.took)
    }

    /// The class of cell (i, j) of the current map (column i from the
    /// left, row j from the bottom), if known, and whether it was computed
    /// or inherited.
    pub fn cell(&self, i: usize, j: usize) -> Option<(Slot, Source)> {
        let r = self.refiner.as_ref()?;
        let (x, y) = self.axes.as_ref()?;
        if i >= x.n || j >= y.n {
            return None;
        }
        let c = j * x.n + i;
        r.class(c).map(|k| (Slot::of(k.response), r.source(c)))
    }

    /// The exact class of cell (i, j) if it was computed (`Some(None)`:
    /// its run failed).
    pub fn response(&self, i: usize, j: usize) -> Option<Class> {
        let (x, y) = self.axes.as_ref()?;
        if i >= x.n || j >= y.n {
            return None;
        }
        self.responses.get(j * x.n + i).copied().flatten()
    }

    /// The values of cell (i, j): the pair of (key, value) a click on it
    /// loads.
    pub fn cell_values(&self, i: usize, j: usize) -> Option<[(String, f64); 2]> {
        let (x, y) = self.axes.as_ref()?;
        (i < x.n && j < y.n).then(|| [(x.key.clone(), x.value(i)), (y.key.clone(), y.value(j))])
    }

    /// Where the centre of cell (i, j) was drawn in the last frame, in
    /// screen points (for tests that click it).
    pub fn cell_position(&self, i: usize, j: usize) -> Option<egui::Pos2> {
        let t = self.transform.as_ref()?;
        let [(_, x), (_, y)] = self.cell_values(i, j)?;
        Some(t.position_from_point(&PlotPoint::new(x, y)))
    }
}
