//! The power spectrum of the last stretch of Θ.

use egui::Color32;
use egui_plot::{Line, Plot, PlotPoints};

use crate::gui::history::RunHistory;
use crate::gui::panels::axes;
use crate::gui::units::Scales;

/// Samples of the last stretch of Θ the spectrum is taken from: 2¹³ at the
/// live spacing of 0.005 τ is 41 τ, about 52 forcing periods at Ω = 8, a
/// resolution Δω = 2π/41 ≈ 0.15 p.
pub(crate) const SPECTRUM_SAMPLES: usize = 1 << 13;

/// Power-spectrum plot state: the last spectrum, recomputed at most every
/// [`SpectrumView::EVERY_TAU`] of playback.
#[derive(Clone, Debug, Default)]
pub(crate) struct SpectrumView {
    /// (ω in units of p, log₁₀ PSD) of the last spectrum.
    points: Vec<[f64; 2]>,
    /// τ of the last sample it was computed at.
    at: f64,
    /// Why there is none, if there is none.
    note: Option<String>,
    /// Spectra computed over the app's life (work counter).
    pub work: u64,
}

impl SpectrumView {
    /// Playback τ between recomputations: a spectrum of 41 τ changes little
    /// in 1 τ, and this keeps the FFT off most frames.
    pub(crate) const EVERY_TAU: f64 = 1.0;

    /// Forget (new run).
    pub fn reset(&mut self) {
        *self = Self {
            work: self.work,
            ..Self::default()
        };
    }
}

/// Draws the power spectrum of Θ over the last [`SPECTRUM_SAMPLES`]
/// samples, computed by [`crate::analysis::spectrum::power_spectrum`], with
/// the forcing frequency Ω_h marked; frequencies in the units of `scales`
/// (Hz or ω/p).
pub(crate) fn spectrum_plot(
    ui: &mut egui::Ui,
    hist: &RunHistory,
    view: &mut SpectrumView,
    sample_dt: f64,
    omega_h: f64,
    scales: &Scales,
) {
    let last = hist.samples.last().map_or(0.0, |s| s.tau);
    if view.points.is_empty() || (last - view.at).abs() >= SpectrumView::EVERY_TAU {
        // Only a gap-free stretch on the sample grid is a valid FFT input.
        let n = hist.samples.len();
        let take = n.min(SPECTRUM_SAMPLES);
        let tail: Vec<(f64, f64)> = hist.samples.iter().skip(n - take).map(|s| (s.tau, s.theta)).collect();
        let start = tail
            .windows(2)
            .rposition(|w| ((w[1].0 - w[0].0) / sample_dt - 1.0).abs() > 1e-6)
            .map_or(0, |i| i + 1);
        let values: Vec<f64> = tail[start..].iter().map(|p| p.1).collect();
        view.at = last;
        match crate::analysis::spectrum::power_spectrum(&values, sample_dt, &Default::default()) {
            Ok(sp) => {
                let top = sp.psd.iter().copied().fold(0.0_f64, f64::max).max(f64::MIN_POSITIVE);
                view.points = sp
                    .omega()
                    .into_iter()
                    .zip(&sp.psd)
                    .skip(1)
                    .filter(|(w, _)| *w <= 4.0 * omega_h.max(1.0))
                    .map(|(w, s)| [w, (s / top).max(1e-16).log10()])
                    .collect();
                view.note = None;
                view.work += 1;
            }
            Err(e) => {
                view.points.clear();
                view.note = Some(e.to_string());
            }
        }
    }
    if let Some(note) = &view.note {
        ui.label(egui::RichText::new(note).weak());
    }
    let pts: Vec<[f64; 2]> = view.points.iter().map(|p| [scales.frequency(p[0]), p[1]]).collect();
    let resp = axes::titled(
        axes::readable(Plot::new("spectrum")),
        ui,
        scales.frequency_label(),
        "log10 S/S_max",
    )
    .include_y(0.0)
    .include_y(-8.0)
    .show(ui, |plot_ui| {
        plot_ui.line(
            Line::new("S(ω)", PlotPoints::new(pts))
                .color(Color32::from_rgb(110, 170, 255))
                .width(1.2),
        );
        plot_ui.vline(
            egui_plot::VLine::new("Ω_h", scales.frequency(omega_h))
                .color(Color32::from_rgb(240, 150, 50).gamma_multiply(0.7))
                .width(1.0),
        );
    });
    axes::record(ui, "spectrum", &resp.transform);
}
