//! The figure of the README's "Rocking frames": the `rocking-frame` preset
//! (two 0.7 × 4.2 m columns under a beam twice their mass, Kobe 1995), the
//! single block it is equivalent to (Makris & Vassiliou 2013: the same α,
//! size divided by κ = (1 + 2γ)/(1 + 3γ), impact coefficient r of the
//! frame), and the same columns standing alone. θ against t, in degrees
//! and seconds.
//!
//! `cargo run --release --example frame_equivalence -- docs/frame-equivalence.png`

use plotters::coord::Shift;
use plotters::prelude::*;
use rocking::plot::{Figure, PlotError, titled};
use rocking::sim::{Scenario, simulate};

/// θ (degrees) against t (s) of `s`.
fn history(s: &Scenario) -> Vec<(f64, f64)> {
    let res = simulate(s.model().expect("model"), &s.initial, &s.run_options()).expect("run");
    let (p, psi) = (s.geometry().p, s.geometry().psi);
    res.history
        .iter()
        .map(|r| (r.tau / p, (psi * r.theta).to_degrees()))
        .collect()
}

/// One curve: its legend, (t, θ) points, colour and width.
type Line = (String, Vec<(f64, f64)>, RGBColor, u32);

struct Compared {
    lines: Vec<Line>,
    alpha_deg: f64,
}

impl Figure for Compared {
    fn size(&self) -> (u32, u32) {
        (1200, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = |x: String| PlotError(x);
        let area = titled(
            root,
            "A rocking frame and the single block it is equivalent to, Kobe 1995",
            "two 0.7 × 4.2 m columns under a beam of twice their mass; the block: same α, size ÷ κ = 5/7, the frame's r",
        )?;
        let a = self.alpha_deg;
        let mut chart = ChartBuilder::on(&area)
            .margin(16)
            .x_label_area_size(52)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..30.0, -1.15 * a..1.15 * a)
            .map_err(|x| e(x.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("θ [deg]")
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 19))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(|x| e(x.to_string()))?;
        for level in [a, -a] {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    [(0.0, level), (30.0, level)],
                    RGBColor(200, 60, 60).stroke_width(1),
                )))
                .map_err(|x| e(x.to_string()))?;
        }
        for (name, points, color, width) in &self.lines {
            let c = *color;
            chart
                .draw_series(LineSeries::new(points.iter().copied(), c.stroke_width(*width)))
                .map_err(|x| e(x.to_string()))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], c.stroke_width(3)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .label_font(("sans-serif", 16))
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(180, 180, 180))
            .draw()
            .map_err(|x| e(x.to_string()))?;
        Ok(())
    }
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "frame-equivalence.png".to_string());
    let load = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        rocking::io::config::load(Some("rocking-frame"), None, &sets).expect("scene")
    };
    let frame = load(&[]);
    let (gamma, geo) = (2.0f64, frame.geometry());
    let kappa = (1.0 + 2.0 * gamma) / (1.0 + 3.0 * gamma);
    let r = (1.0 - 1.5 * geo.sin_psi.powi(2) + 3.0 * gamma * (2.0 * geo.psi).cos()) / (1.0 + 3.0 * gamma);
    let table = format!(
        "[block]\nwidth = {:?}\nheight = {:?}\n[impact]\nlaw = \"ratio\"\nr = {r:?}\n\
         [excitation]\nkind = \"record\"\nfile_h = \"shipped:kobe-1995.dat\"\nunit_h = \"m/s2\"\n\
         [run]\noutput_dt = \"0.01 s\"\nzeno_eps = {:?}\n",
        geo.width / kappa,
        geo.height / kappa,
        1e-5 / kappa.sqrt()
    );
    let block = rocking::io::config::from_table(
        &rocking::io::config::parse_toml(&table, "equivalent.toml").expect("toml"),
        &rocking::io::config::Source::default(),
    )
    .expect("block");
    let lone = load(&["frame.beam_mass_ratio=0"]);
    let figure = Compared {
        lines: vec![
            (
                "columns alone: overturn at 11.09 s".to_string(),
                history(&lone),
                RGBColor(150, 150, 150),
                2,
            ),
            ("frame, γ_b = 2".to_string(), history(&frame), RGBColor(31, 119, 180), 5),
            (
                "equivalent block 0.98 × 5.88 m".to_string(),
                history(&block),
                RGBColor(255, 127, 14),
                2,
            ),
        ],
        alpha_deg: geo.psi.to_degrees(),
    };
    for (name, points, _, _) in &figure.lines {
        let last = points.last().copied().unwrap_or_default();
        println!("{name}: {} samples to t = {:.2} s", points.len(), last.0);
    }
    figure.write_png(std::path::Path::new(&out)).expect("png");
    println!("wrote {out}");
}
