//! What the app keeps of a run, and its decimation to screen resolution.
//!
//! Contract:
//! - Storage is bounded: samples and events live in rings of fixed capacity
//!   (the oldest go first); section points in a store that drops its oldest
//!   half when full. Memory therefore stays bounded however long a run goes.
//! - NaN/inf: nothing non-finite is stored. A sample, event or section point
//!   with a non-finite coordinate is refused and counted in `rejected`
//!   (the simulation thread never sends one; this is the chokepoint that
//!   keeps a bad value from reaching a plot).
//! - Decimation never invents values: [`decimate_min_max`] keeps, per pixel
//!   column, the first, smallest, largest and last sample (in time order),
//!   so spikes survive; [`DensityGrid`] counts points per pixel.

use std::collections::VecDeque;

use egui_plot::PlotPoint;

use crate::gui::ghost_trails::GhostTrails;
use crate::model::Geometry;
use crate::model::stack::{StackEvent, StackEventKind};
use crate::model::system::EventRecord;
use crate::sim::SectionRow;
use crate::sim::protocol::{Sample, StackFrame};

/// A ring buffer of fixed capacity: pushing into a full ring drops the oldest.
#[derive(Clone, Debug)]
pub struct Ring<T> {
    items: VecDeque<T>,
    capacity: usize,
}

impl<T> Ring<T> {
    /// An empty ring holding at most `capacity` (>= 1) items.
    pub fn new(capacity: usize) -> Self {
        Self {
            items: VecDeque::with_capacity(capacity.min(1 << 16)),
            capacity: capacity.max(1),
        }
    }

    /// Appends, dropping the oldest item if full.
    pub fn push(&mut self, item: T) {
        if self.items.len() == self.capacity {
            self.items.pop_front();
        }
        self.items.push_back(item);
    }

    /// Items, oldest first, to change in place.
    pub(crate) fn iter_mut(&mut self) -> impl Iterator<Item = &mut T> {
        self.items.iter_mut()
    }

    /// Items, oldest first.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = &T> + ExactSizeIterator {
        self.items.iter()
    }

    /// The newest item.
    pub fn last(&self) -> Option<&T> {
        self.items.back()
    }

    /// How many items.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether empty.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Empties the ring.
    pub fn clear(&mut self) {
        self.items.clear();
    }
}

/// Samples kept: 2¹⁷ at the live spacing of 0.005 τ is 655 τ, more than
/// the longest time-history window (500 τ). 12 MB.
pub(crate) const SAMPLE_CAPACITY: usize = 1 << 17;

/// Events kept for the CSV export and the counters (the newest).
pub(crate) const EVENT_CAPACITY: usize = 1 << 17;

/// Section points kept: 4·10⁶ (64 MB), four times the 10⁶ the issue asks to
/// stay smooth. When full, the oldest half is dropped.
pub(crate) const SECTION_CAPACITY: usize = 4_000_000;

/// Section points, stored for density plotting.
#[derive(Clone, Debug, Default)]
pub struct SectionStore {
    /// (Θ, Θ') of each kept point, oldest first.
    points: Vec<[f64; 2]>,
    /// Points dropped to stay within [`SECTION_CAPACITY`].
    pub dropped: u64,
    /// Bumped whenever points are removed (a [`DensityGrid`] must rebin).
    pub generation: u64,
    /// Bounding box of the kept points: min Θ, max Θ, min Θ', max Θ'.
    bbox: Option<[f64; 4]>,
}

impl SectionStore {
    /// Adds a point (finite by the caller's check).
    fn push(&mut self, theta: f64, theta_dot: f64) {
        if self.points.len() >= SECTION_CAPACITY {
            let half = SECTION_CAPACITY / 2;
            self.points.drain(..half);
            self.dropped += half as u64;
            self.generation += 1;
            self.bbox = None;
            for p in &self.points {
                grow(&mut self.bbox, p[0], p[1]);
            }
        }
        self.points.push([theta, theta_dot]);
        grow(&mut self.bbox, theta, theta_dot);
    }

    /// The kept points, oldest first.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Bounding box (min Θ, max Θ, min Θ', max Θ'), if any point.
    pub(crate) fn bbox(&self) -> Option<[f64; 4]> {
        self.bbox
    }
}

fn grow(bbox: &mut Option<[f64; 4]>, x: f64, y: f64) {
    match bbox {
        None => *bbox = Some([x, x, y, y]),
        Some(b) => {
            b[0] = b[0].min(x);
            b[1] = b[1].max(x);
            b[2] = b[2].min(y);
            b[3] = b[3].max(y);
        }
    }
}

/// Everything the app keeps of the current run.
#[derive(Clone, Debug)]
pub struct RunHistory {
    /// Samples, oldest first.
    pub samples: Ring<Sample>,
    /// Events, oldest first.
    pub events: Ring<EventRecord>,
    /// Section points.
    pub section: SectionStore,
    /// The impact section: (forcing phase Ω_h τ mod 2π, rad; Θ' just
    /// before the impact) of each impact, for harmonic forcing. Θ itself
    /// is 0 at every impact (the block lands flat), so the phase is the
    /// section's second coordinate, as in the impact maps of the rocking
    /// literature.
    pub impact_section: SectionStore,
    /// Period of the forcing, τ, when it is harmonic (from the run's
    /// [`crate::sim::protocol::RunInfo::section_period`]): what the impact
    /// section's phase is taken over.
    pub forcing_period: Option<f64>,
    /// Section points with mode and τ, for the CSV export (the newest).
    pub section_rows: Ring<SectionRow>,
    /// Impacts seen in this run.
    pub impacts: u64,
    /// Samples the simulation thread dropped because the app fell behind.
    pub dropped_samples: u64,
    /// Items refused for a non-finite value.
    pub rejected: u64,
    /// The ghost copies' recent (Θ, Θ'), one bounded trail each.
    pub ghost_trails: GhostTrails,
    /// A stack's events, oldest first (each with its interface).
    pub stack_events: Ring<StackEvent>,
    /// A stack's section points (k and the whole state), so that the
    /// section can be shown again for another body.
    pub stack_section: Ring<(u64, StackFrame)>,
}

impl Default for RunHistory {
    fn default() -> Self {
        Self {
            samples: Ring::new(SAMPLE_CAPACITY),
            events: Ring::new(EVENT_CAPACITY),
            section: SectionStore::default(),
            impact_section: SectionStore::default(),
            forcing_period: None,
            section_rows: Ring::new(EVENT_CAPACITY),
            impacts: 0,
            dropped_samples: 0,
            rejected: 0,
            ghost_trails: GhostTrails::default(),
            stack_events: Ring::new(EVENT_CAPACITY),
            stack_section: Ring::new(EVENT_CAPACITY),
        }
    }
}

impl RunHistory {
    /// Forgets everything (a new run).
    pub fn clear(&mut self) {
        let generation = self.section.generation.max(self.impact_section.generation);
        *self = Self::default();
        self.section.generation = generation + 1;
        self.impact_section.generation = generation + 1;
    }

    /// Forgets the stroboscopic section points only (their phase changed;
    /// the motion, and so the samples and impacts, go on).
    pub(crate) fn clear_section(&mut self) {
        let generation = self.section.generation;
        self.section = SectionStore::default();
        self.section.generation = generation + 1;
        self.section_rows.clear();
    }

    /// Adds a sample unless it has a non-finite value.
    pub(crate) fn push_sample(&mut self, s: Sample) {
        let finite = [
            s.tau,
            s.theta,
            s.theta_dot,
            s.x,
            s.x_dot,
            s.a_h,
            s.a_v,
            s.base_x,
            s.normal,
            s.friction,
        ]
        .iter()
        .all(|v| v.is_finite())
            && s.stack.is_none_or(|f| f.is_finite());
        if finite {
            self.samples.push(s);
        } else {
            self.rejected += 1;
        }
    }

    /// Adds an event unless it has a non-finite value.
    pub(crate) fn push_event(&mut self, e: EventRecord) {
        let finite = [e.tau, e.theta, e.theta_dot_before, e.theta_dot_after, e.x_dot]
            .iter()
            .all(|v| v.is_finite());
        if !finite {
            self.rejected += 1;
            return;
        }
        if e.kind == crate::model::EventKind::Impact {
            self.impacts += 1;
            if let Some(period) = self.forcing_period.filter(|p| *p > 0.0 && p.is_finite()) {
                let phase = std::f64::consts::TAU * (e.tau.rem_euclid(period) / period);
                self.impact_section.push(phase, e.theta_dot_before);
            }
        }
        self.events.push(e);
    }

    /// Adds a stack's event unless it has a non-finite value; an impact
    /// (on the other corner, or closing the face) counts as the block's.
    pub(crate) fn push_stack_event(&mut self, e: StackEvent) {
        if ![e.tau, e.q_dot_before, e.q_dot_after].iter().all(|v| v.is_finite()) {
            self.rejected += 1;
            return;
        }
        if matches!(e.kind, StackEventKind::Impact | StackEventKind::Close) {
            self.impacts += 1;
        }
        self.stack_events.push(e);
    }

    /// Adds a stack's section point `p` (block `body`'s, whole state
    /// `frame`) unless it has a non-finite value.
    pub(crate) fn push_stack_section(&mut self, p: SectionRow, frame: StackFrame) {
        if frame.is_finite() {
            self.stack_section.push((p.k, frame));
        }
        self.push_section(p);
    }

    /// Shows block `body` of a stack (`geo` the bottom block's) in the
    /// plots: every kept sample's and section point's rotation becomes
    /// that block's, from the whole state each carries.
    pub(crate) fn show_body(&mut self, body: usize, geo: &Geometry) {
        for s in self.samples.iter_mut() {
            if let Some(f) = s.stack {
                s.state = f.body_row(body, geo);
            }
        }
        let kept: Vec<(u64, StackFrame)> = self.stack_section.iter().copied().collect();
        self.clear_section();
        for (k, f) in kept {
            self.push_section(section_row(k, &f, body, geo));
        }
    }

    /// Adds a section point unless it has a non-finite value.
    pub(crate) fn push_section(&mut self, p: SectionRow) {
        if [p.tau, p.theta, p.theta_dot, p.x, p.x_dot]
            .iter()
            .all(|v| v.is_finite())
        {
            self.section.push(p.theta, p.theta_dot);
            self.section_rows.push(p);
        } else {
            self.rejected += 1;
        }
    }
}

/// Block `body`'s section point `k` of a stack in state `f` (`geo` the
/// bottom block's).
pub(crate) fn section_row(k: u64, f: &StackFrame, body: usize, geo: &Geometry) -> SectionRow {
    let row = f.body_row(body, geo);
    SectionRow {
        k,
        tau: row.tau,
        theta: row.theta,
        theta_dot: row.theta_dot,
        x: row.x,
        x_dot: row.x_dot,
        mode: row.mode,
    }
}

/// Decimates `(t, y)` pairs (t increasing) over `[t0, t1]` to at most four
/// points per pixel column (`columns` columns): the first, smallest,
/// largest and last of each column in time order. With few samples, all
/// are passed through. Points outside `[t0, t1]` are skipped except one on
/// each side, so the line reaches the plot's edges. Writes into `out`
/// (cleared first).
pub(crate) fn decimate_min_max(
    points: impl Iterator<Item = (f64, f64)>,
    t0: f64,
    t1: f64,
    columns: usize,
    out: &mut Vec<PlotPoint>,
) {
    out.clear();
    let columns = columns.max(1);
    let width = (t1 - t0).max(f64::MIN_POSITIVE);
    // Per column: first, min, max, last (each as (t, y)).
    let mut current: Option<(usize, [(f64, f64); 4])> = None;
    let mut before: Option<(f64, f64)> = None;
    let flush = |col: [(f64, f64); 4], out: &mut Vec<PlotPoint>| {
        let [first, lo, hi, last] = col;
        let mut pts = [first, lo, hi, last];
        pts[1..3].sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut prev: Option<(f64, f64)> = None;
        for p in pts {
            if prev != Some(p) {
                out.push(PlotPoint::new(p.0, p.1));
                prev = Some(p);
            }
        }
    };
    for (t, y) in points {
        if !(t.is_finite() && y.is_finite()) {
            continue;
        }
        if t < t0 {
            before = Some((t, y));
            continue;
        }
        if let Some(b) = before.take() {
            out.push(PlotPoint::new(b.0, b.1));
        }
        if t > t1 {
            if let Some((_, col)) = current.take() {
                flush(col, out);
            }
            out.push(PlotPoint::new(t, y));
            return;
        }
        let c = (((t - t0) / width) * columns as f64) as usize;
        match &mut current {
            Some((cc, col)) if *cc == c => {
                if y < col[1].1 {
                    col[1] = (t, y);
                }
                if y > col[2].1 {
                    col[2] = (t, y);
                }
                col[3] = (t, y);
            }
            _ => {
                if let Some((_, col)) = current.take() {
                    flush(col, out);
                }
                current = Some((c, [(t, y); 4]));
            }
        }
    }
    if let Some((_, col)) = current.take() {
        flush(col, out);
    }
}

/// Section points rasterised into a count per pixel over a view rectangle:
/// how a million points are drawn as one texture instead of a million
/// markers. New points are binned incrementally; a change of view, size or
/// store generation rebins everything.
#[derive(Clone, Debug, Default)]
pub struct DensityGrid {
    /// Pixels across and down.
    pub size: [usize; 2],
    /// The view: min Θ, max Θ, min Θ', max Θ'.
    pub view: [f64; 4],
    /// Count per pixel, row 0 at the top (largest Θ').
    pub counts: Vec<u32>,
    /// Largest count.
    pub max_count: u32,
    /// How many of the store's points are binned.
    binned: usize,
    generation: u64,
    /// Points binned over the grid's life (the work done; tests use it to
    /// check that a hidden panel does none).
    pub work: u64,
}

impl DensityGrid {
    /// Brings the grid up to date with `store` for `view` at `size` pixels.
    /// Returns whether any count changed.
    pub fn update(&mut self, store: &SectionStore, view: [f64; 4], size: [usize; 2]) -> bool {
        let size = [size[0].clamp(1, 4096), size[1].clamp(1, 4096)];
        let valid = view.iter().all(|v| v.is_finite()) && view[1] > view[0] && view[3] > view[2];
        if !valid {
            return false;
        }
        if size != self.size || view != self.view || store.generation != self.generation {
            self.size = size;
            self.view = view;
            self.generation = store.generation;
            self.counts.clear();
            self.counts.resize(size[0] * size[1], 0);
            self.max_count = 0;
            self.binned = 0;
        }
        let new = &store.points()[self.binned.min(store.points().len())..];
        if new.is_empty() {
            return false;
        }
        let (w, h) = (size[0] as f64, size[1] as f64);
        let sx = w / (view[1] - view[0]);
        let sy = h / (view[3] - view[2]);
        for p in new {
            let fx = (p[0] - view[0]) * sx;
            let fy = (view[3] - p[1]) * sy;
            if fx >= 0.0 && fx < w && fy >= 0.0 && fy < h {
                let i = fy as usize * size[0] + fx as usize;
                if let Some(c) = self.counts.get_mut(i) {
                    *c = c.saturating_add(1);
                    self.max_count = self.max_count.max(*c);
                }
            }
        }
        self.work += new.len() as u64;
        self.binned = store.points().len();
        true
    }

    /// Forgets every count (another store is to be binned), keeping the
    /// work counter.
    pub(crate) fn forget(&mut self) {
        *self = Self {
            work: self.work,
            ..Self::default()
        };
    }

    /// How many of the store's points are binned (in view or not).
    pub fn binned(&self) -> usize {
        self.binned
    }

    /// The grid as an image: empty pixels transparent, occupied ones
    /// coloured by log count (so single points stay visible next to dense
    /// bands).
    pub(crate) fn to_image(&self, low: egui::Color32, high: egui::Color32) -> egui::ColorImage {
        let log_max = (1.0 + self.max_count as f32).ln().max(f32::MIN_POSITIVE);
        let pixels = self
            .counts
            .iter()
            .map(|&c| {
                if c == 0 {
                    egui::Color32::TRANSPARENT
                } else {
                    let f = ((1.0 + c as f32).ln() / log_max).clamp(0.0, 1.0);
                    lerp_color(low, high, f)
                }
            })
            .collect();
        egui::ColorImage::new(self.size, pixels)
    }
}

fn lerp_color(a: egui::Color32, b: egui::Color32, f: f32) -> egui::Color32 {
    let l = |x: u8, y: u8| (x as f32 + (y as f32 - x as f32) * f).round() as u8;
    egui::Color32::from_rgb(l(a.r(), b.r()), l(a.g(), b.g()), l(a.b(), b.b()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_ring_drops_the_oldest() {
        let mut r = Ring::new(3);
        for k in 0..5 {
            r.push(k);
        }
        assert_eq!(r.iter().copied().collect::<Vec<_>>(), vec![2, 3, 4]);
    }

    #[test]
    fn decimation_keeps_spikes_and_bounds_the_point_count() {
        let n = 100_000;
        let pts = (0..n).map(|k| {
            let t = k as f64 / n as f64;
            let y = if k == 54_321 { 10.0 } else { (t * 50.0).sin() };
            (t, y)
        });
        let mut out = Vec::new();
        decimate_min_max(pts, 0.0, 1.0, 200, &mut out);
        assert!(out.len() <= 4 * 200 + 2, "{} points", out.len());
        assert!(out.iter().any(|p| p.y == 10.0), "the spike survives");
        assert!(out.windows(2).all(|w| w[0].x <= w[1].x), "time order kept");
    }

    #[test]
    fn decimation_skips_non_finite_values() {
        let pts = vec![(0.0, 1.0), (0.5, f64::NAN), (0.6, f64::INFINITY), (1.0, 2.0)];
        let mut out = Vec::new();
        decimate_min_max(pts.into_iter(), 0.0, 1.0, 10, &mut out);
        assert!(out.iter().all(|p| p.y.is_finite()));
        assert_eq!(out.len(), 2);
    }

    #[test]
    fn non_finite_items_are_refused_and_counted() {
        let mut h = RunHistory::default();
        h.push_section(SectionRow {
            k: 0,
            tau: 0.0,
            theta: f64::NAN,
            theta_dot: 0.0,
            x: 0.0,
            x_dot: 0.0,
            mode: crate::model::Mode::Rest,
        });
        assert_eq!(h.rejected, 1);
        assert!(h.section.points().is_empty());
    }

    #[test]
    fn the_density_grid_counts_every_point_once_and_bins_incrementally() {
        let mut store = SectionStore::default();
        for k in 0..1000 {
            store.push((k % 10) as f64 / 10.0, 0.5);
        }
        let mut g = DensityGrid::default();
        assert!(g.update(&store, [0.0, 1.0, 0.0, 1.0], [10, 10]));
        assert_eq!(g.counts.iter().map(|&c| c as u64).sum::<u64>(), 1000);
        assert_eq!(g.max_count, 100);
        assert!(!g.update(&store, [0.0, 1.0, 0.0, 1.0], [10, 10]), "nothing new");
        store.push(0.05, 0.05);
        assert!(g.update(&store, [0.0, 1.0, 0.0, 1.0], [10, 10]));
        assert_eq!(g.work, 1001, "only the new point was binned");
    }
}
