//! The figure of the README's "Stacks of blocks": the `stack-patterns`
//! preset (a 0.6 × 1.8 m block under a 0.4 × 1.2 m block, 0.3 g at 2 Hz)
//! — each block's rotation against time, and under it a strip coloured by
//! the rocking pattern the stack is in.
//!
//! `cargo run --release --example stack_patterns -- docs/stack-patterns.png`

use plotters::coord::Shift;
use plotters::prelude::*;
use rocking::model::stack::{Contact, Pose, StackMode};
use rocking::plot::{Figure, PlotError, titled};
use rocking::sim::stack_run::simulate_stack;

/// A pattern's words and colour.
fn pattern(mode: &StackMode) -> (&'static str, RGBColor) {
    let [base, upper] = [mode.contacts[0], mode.contacts[1]];
    match (base, upper) {
        (Contact::Closed, Contact::Closed) => ("at rest", RGBColor(220, 220, 220)),
        (Contact::Closed, _) => ("top block alone", RGBColor(120, 180, 120)),
        (_, Contact::Closed) => ("as one block", RGBColor(90, 140, 220)),
        (b, u) if b == u => ("both faces open, turning the same way", RGBColor(240, 170, 60)),
        _ => ("both faces open, turning opposite ways", RGBColor(210, 80, 80)),
    }
}

struct Patterns {
    /// (t, φ bottom, φ top) in s and degrees.
    angles: Vec<(f64, f64, f64)>,
    /// (t, pattern) at each change.
    strip: Vec<(f64, StackMode)>,
    t_end: f64,
}

impl Figure for Patterns {
    fn size(&self) -> (u32, u32) {
        (1200, 650)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let e = |x: String| PlotError(x);
        let area = titled(
            root,
            "Two stacked blocks switching rocking patterns (preset stack-patterns)",
            "0.6 × 1.8 m under 0.4 × 1.2 m, base 0.3 g at 2 Hz; colour strip: the pattern",
        )?;
        let (top, bottom) = area.split_vertically(area.dim_in_pixel().1 - 70);
        let peak = self.angles.iter().map(|a| a.1.abs().max(a.2.abs())).fold(0.0, f64::max) * 1.1;
        let mut chart = ChartBuilder::on(&top)
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..self.t_end, -peak..peak)
            .map_err(|x| e(x.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("rotation [deg]")
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 19))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(|x| e(x.to_string()))?;
        for (name, pick, color) in [
            ("bottom block", 1usize, RGBColor(40, 40, 40)),
            ("top block", 2usize, RGBColor(30, 110, 200)),
        ] {
            let points = self
                .angles
                .iter()
                .map(move |a| (a.0, if pick == 1 { a.1 } else { a.2 }));
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|x| e(x.to_string()))?
                .label(name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], color.stroke_width(3)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 16))
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(180, 180, 180))
            .draw()
            .map_err(|x| e(x.to_string()))?;
        // The strip: one rectangle per stretch of one pattern, aligned
        // with the chart's plotting area.
        // Pixel ranges are the backend's; the strip's area counts from its
        // own left edge.
        let plot = chart.plotting_area().get_pixel_range().0;
        let left = bottom.get_pixel_range().0.start;
        let (x0, x1) = (f64::from(plot.start - left), f64::from(plot.end - left));
        let px = |t: f64| (x0 + (x1 - x0) * t / self.t_end) as i32;
        for (k, (t, mode)) in self.strip.iter().enumerate() {
            let t_next = self.strip.get(k + 1).map_or(self.t_end, |s| s.0);
            let (_, color) = pattern(mode);
            bottom
                .draw(&Rectangle::new([(px(*t), 6), (px(t_next), 30)], color.filled()))
                .map_err(|x| e(x.to_string()))?;
        }
        let mut x = x0 as i32;
        for (name, color) in [
            pattern(&with(Contact::Left, Contact::Closed)),
            pattern(&with(Contact::Left, Contact::Left)),
            pattern(&with(Contact::Left, Contact::Right)),
            pattern(&with(Contact::Closed, Contact::Left)),
        ] {
            bottom
                .draw(&Rectangle::new([(x, 40), (x + 18, 56)], color.filled()))
                .map_err(|x| e(x.to_string()))?;
            bottom
                .draw(&Text::new(name, (x + 24, 40), ("sans-serif", 15)))
                .map_err(|x| e(x.to_string()))?;
            x += 30 + 8 * name.len() as i32;
        }
        Ok(())
    }
}

fn with(base: Contact, upper: Contact) -> StackMode {
    let mut m = StackMode::REST;
    m.contacts[0] = base;
    m.contacts[1] = upper;
    m
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "stack-patterns.png".to_string());
    let s = rocking::io::config::load(Some("stack-patterns"), None, &[]).expect("preset");
    let geo = s.stack_geometry().expect("stack");
    let run = simulate_stack(
        geo,
        s.excitation().expect("excitation"),
        s.run.zeno_eps,
        &s.run_options(),
    )
    .expect("run");
    let p = s.geometry().p;
    let angles = run
        .history
        .iter()
        .map(|r| {
            let pose = Pose::new(&geo, &r.mode.contacts, &r.y);
            (r.tau / p, pose.phi[0].to_degrees(), pose.phi[1].to_degrees())
        })
        .collect();
    let mut strip = vec![(0.0, StackMode::REST)];
    for ev in &run.events {
        strip.push((ev.tau / p, ev.after));
    }
    let figure = Patterns {
        angles,
        strip,
        t_end: run.tau_end / p,
    };
    figure.write_png(std::path::Path::new(&out)).expect("png");
    println!("wrote {out}");
}
