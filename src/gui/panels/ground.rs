//! The ground-acceleration trace of a record scene: a_h in g against time,
//! titled with the record's name and its PGA after the scale factor, with
//! the playhead marked.
//!
//! The trace is drawn from the samples the simulation thread sent (each
//! carries a_h/g); the record's name, PGA and length are read once, when a
//! run starts, from the scenario it runs ([`RecordLabel::of`]).

use crate::gui::panels::axes;
use egui::Color32;
use egui_plot::{Line, Plot, PlotPoint, PlotPoints, VLine};

use crate::gui::history::{RunHistory, decimate_min_max};
use crate::gui::units::Scales;
use crate::sim::Scenario;
use crate::sim::scenario::ExcitationKind;

/// What the app says about a run's horizontal record.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordLabel {
    /// The file's name (without its folder).
    pub name: String,
    /// Peak ground acceleration after the scale factor, g.
    pub pga_g: f64,
    /// The scale factor on the record.
    pub scale: f64,
    /// Length of the record, s (time of its last sample).
    pub duration_s: f64,
    /// The floor's peak horizontal acceleration, g, when the block stands
    /// on a floor (`[floor]`): the trace is then the floor's motion, which
    /// the simulation's samples carry, not the ground's.
    pub floor_pga_g: Option<f64>,
}

impl RecordLabel {
    /// The horizontal record of `scenario`, if it runs one.
    pub fn of(scenario: &Scenario) -> Option<Self> {
        let x = &scenario.excitation;
        if x.kind != ExcitationKind::Record {
            return None;
        }
        let r = x.record_h.as_ref()?;
        let name = r.file_name();
        let floor_pga_g = match scenario.excitation() {
            Ok(crate::model::Excitation::Floor(f)) => Some(f.peaks(scenario.tau_end()).pga_g),
            _ => None,
        };
        Some(Self {
            name,
            pga_g: r.series.peaks(x.scale_h).pga_g,
            scale: x.scale_h,
            duration_s: r.series.duration_s(),
            floor_pga_g,
        })
    }

    /// `kobe-1995.dat · PGA 0.69 g` (and the scale when it is not 1); on a
    /// floor, the floor's PGA with the ground's after it.
    pub fn title(&self) -> String {
        let name = if self.scale == 1.0 {
            self.name.clone()
        } else {
            format!("{} × {}", self.name, self.scale)
        };
        match self.floor_pga_g {
            None => format!("{name} · PGA {:.2} g", self.pga_g),
            Some(f) => format!("{name} · floor PGA {:.2} g (ground {:.2} g)", f, self.pga_g),
        }
    }

    /// What the trace is: the ground's acceleration, or the floor's.
    pub fn what(&self) -> &'static str {
        if self.floor_pga_g.is_some() {
            "Floor acceleration"
        } else {
            "Ground acceleration"
        }
    }
}

/// Ground-trace state.
#[derive(Clone, Debug, Default)]
pub(crate) struct GroundView {
    scratch: Vec<PlotPoint>,
    /// Points passed to the plot over the app's life (work counter).
    pub work: u64,
}

/// Draws the title and the trace of a_h from the start of the run to `now`
/// (τ), over the whole record's length (so it fills in as the record
/// plays), in the time unit of `scales`.
pub(crate) fn ground_plot(
    ui: &mut egui::Ui,
    hist: &RunHistory,
    view: &mut GroundView,
    label: &RecordLabel,
    now: f64,
    scales: &Scales,
) {
    ui.label(egui::RichText::new(format!("{}: {}", label.what(), label.title())).strong());
    let t_record = scales.time(scales.tau_of_seconds(label.duration_s));
    let t_now = scales.time(now);
    // 2 % past the record's end, as the time history's window for a record
    // ([`crate::gui::panels::plots::HistoryView::fit_run`]): the two line up.
    let t1 = (1.02 * t_record).max(t_now);
    let columns = (ui.available_width() * ui.ctx().pixels_per_point()).max(16.0) as usize;
    decimate_min_max(
        hist.samples.iter().map(|s| (scales.time(s.tau), s.a_h)),
        0.0,
        t1,
        columns,
        &mut view.scratch,
    );
    view.work += view.scratch.len() as u64;
    let pts = view.scratch.clone();
    let pga = label.floor_pga_g.unwrap_or(label.pga_g);
    let resp = axes::titled(axes::readable(Plot::new("ground")), ui, scales.time_label(), "a_h [g]")
        .include_x(0.0)
        .include_x(t1)
        .include_y(-pga)
        .include_y(pga)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .show(ui, |plot_ui| {
            plot_ui.line(
                Line::new("a_h [g]", PlotPoints::Owned(pts))
                    .color(Color32::from_rgb(240, 150, 50))
                    .width(1.2),
            );
            plot_ui.vline(
                VLine::new("now", t_now)
                    .color(Color32::from_rgb(255, 230, 60).gamma_multiply(0.8))
                    .width(1.5),
            );
        });
    axes::record(ui, "ground", &resp.transform);
}
