//! The block scene: the shake table with its displacement, the block at its
//! true angle and sliding position with the pivot corner marked, the mode
//! by colour, a flash at each impact, ghost copies, and optionally the
//! contact force with the friction cone.
//!
//! Everything is placed from [`crate::sim::protocol::pose`], which the
//! simulation layer computes from the model's own geometry: this module
//! only chooses colours, sizes on screen and the camera. The shapes go to
//! the wgpu pipeline of [`crate::gui::block_view`] when there is one, and to
//! egui's painter otherwise (a headless harness).

use egui::{Color32, Rect};

use crate::gui::block_view::{SceneCallback, Shape, ViewUniform};
use crate::model::geometry::Geometry;
use crate::model::{Frame, Mode};
use crate::sim::protocol::{GhostState, Sample, pose};

/// Colour of each mode (index order of [`Mode::index`]).
pub(crate) const MODE_COLORS: [Color32; 6] = [
    Color32::from_rgb(120, 144, 170), // rest
    Color32::from_rgb(64, 190, 200),  // slide
    Color32::from_rgb(90, 190, 100),  // rock
    Color32::from_rgb(240, 150, 50),  // slide-rock
    Color32::from_rgb(220, 60, 60),   // tumbled
    Color32::from_rgb(170, 100, 230), // flight
];

/// Colour of ghost `k` of `n`: hues spread evenly from red through green
/// and blue to violet (stopping short of red again, so the first and the
/// last differ), bright and opaque. Twenty ghosts are 15° of hue apart,
/// so each can be told from its neighbours; the phase portrait draws each
/// ghost's trail in the same colour.
pub fn ghost_color(k: usize, n: usize) -> Color32 {
    let hue = 0.83 * k as f32 / n.max(1) as f32;
    Color32::from(egui::ecolor::HsvaGamma {
        h: hue,
        s: 0.8,
        v: 1.0,
        a: 1.0,
    })
}

/// Width of a ghost's outline, points: wide enough to see a colour in,
/// narrow enough that twenty outlines a few pixels apart stay apart.
pub(crate) const GHOST_OUTLINE: f64 = 2.0;

/// The largest |Θ_ghost − Θ| over `ghosts`, units of ψ; `None` without
/// ghosts. Shown beside the block, it grows by orders of magnitude while
/// the ghosts are still hidden behind it.
pub(crate) fn ghost_spread(sample: &Sample, ghosts: &[GhostState]) -> Option<f64> {
    ghosts.iter().map(|g| (g.theta - sample.theta).abs()).reduce(f64::max)
}

/// The colour of `mode`.
pub fn mode_color(mode: Mode) -> Color32 {
    MODE_COLORS[mode.index()]
}

/// What the scene needs from the app.
pub struct SceneInput<'a> {
    /// The block.
    pub geometry: Geometry,
    /// The state shown.
    pub sample: &'a Sample,
    /// Ghost copies' latest states.
    pub ghosts: &'a [GhostState],
    /// Static friction coefficient (∞: no cone drawn).
    pub mu_s: f64,
    /// The terminal mode the run ended in, if it has (drawn instead of the
    /// last sample's mode).
    pub terminal: Option<Mode>,
    /// Impact flash strength in [0, 1].
    pub flash: f32,
    /// Whether to draw the contact force and the friction cone.
    pub forces: bool,
    /// A rocking frame: its columns are drawn side by side under the beam,
    /// each with `geometry`; `None`: the single block.
    pub frame: Option<Frame>,
}

/// Spacing of a frame's columns on screen, in column widths (the
/// dynamics do not depend on it, docs/model.md §16).
const COLUMN_SPACING: f64 = 3.0;

/// Depth of a frame's cap beam on screen, in column heights.
const BEAM_DEPTH: f64 = 0.12;

/// Horizontal offsets of the bodies drawn from the simulated pose, m: one
/// block at 0, or a frame's columns spread evenly about it.
fn column_offsets(geo: &Geometry, frame: Option<&Frame>) -> Vec<f64> {
    match frame {
        None => vec![0.0],
        Some(f) => {
            let n = f.columns as usize;
            let step = COLUMN_SPACING * geo.width;
            (0..n).map(|k| (k as f64 - 0.5 * (n as f64 - 1.0)) * step).collect()
        }
    }
}

/// The cap beam of a frame in pose `p`: its centre and half size, m. It
/// rides on the columns' top corners diagonally opposite their pivots
/// (docs/model.md §16.1), so it moves as those corners do and never turns.
fn beam(geo: &Geometry, offsets: &[f64], p: &crate::sim::protocol::Pose) -> ([f64; 2], [f64; 2]) {
    let depth = BEAM_DEPTH * geo.height;
    let span = offsets.last().copied().unwrap_or(0.0) - offsets.first().copied().unwrap_or(0.0);
    let half = [0.5 * span + 0.75 * geo.width, 0.5 * depth];
    let (flat_x, shift) = match p.pivot {
        Some((pivot_x, s)) => {
            let s = s.value();
            // The support corner, (−sB/2, H/2) in the column, turned
            // clockwise by the tilt about the column's centre.
            let (sn, cs) = p.angle.sin_cos();
            let (u, v) = (-s * 0.5 * geo.width, 0.5 * geo.height);
            let corner = [p.x + u * cs + v * sn, p.y - u * sn + v * cs];
            let flat = pivot_x - s * 0.5 * geo.width;
            (flat, [corner[0] - (flat + u), corner[1] - geo.height])
        }
        None => (p.x, [0.0, 0.0]),
    };
    ([flat_x + shift[0], geo.height + 0.5 * depth + shift[1]], half)
}

/// The camera: follows the block horizontally with a dead zone, so a block
/// that slides away stays in view while a rocking block holds still.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Camera {
    /// Horizontal centre of the view, m.
    pub x: f64,
}

/// The world-to-screen fit: pixels (points) per metre and the world
/// rectangle shown, for a block of half-diagonal `r` in a `rect`.
pub(crate) fn fit(rect: Rect, r: f64, half_span: f64) -> (f64, f64) {
    // Room for the block standing on a corner (height up to 2R), the table
    // below, and sideways sliding; a frame's columns side by side.
    let world_h = 2.5 * r;
    let world_w = (3.2 * r).max(2.0 * half_span + 1.6 * r);
    let scale = (rect.height() as f64 / world_h).min(rect.width() as f64 / world_w);
    // World y at the rect's vertical centre: the table top sits 15 % above
    // the bottom edge.
    let y_mid = rect.height() as f64 / scale * 0.5 - 0.15 * rect.height() as f64 / scale;
    (scale, y_mid)
}

/// The floor (fixed) and the shake table (moved by `base_x`, m) across
/// the view centred at `camera_x` (`half_w` m each side), sized for a
/// body of half-diagonal `r`, m; `px` is one point in metres.
pub(crate) fn stage(shapes: &mut Vec<Shape>, camera_x: f64, half_w: f64, r: f64, base_x: f64, px: f64) {
    // The floor (fixed) and the shake table (moves with the base).
    let left = camera_x - half_w - r;
    let right = camera_x + half_w + r;
    let table_h = 0.12 * r;
    shapes.push(Shape::rect(
        [0.5 * (left + right), -table_h - 0.5 * r],
        [0.5 * (right - left), 0.5 * r],
        0.0,
        Color32::from_rgb(38, 40, 46),
    ));
    shapes.push(Shape::rect(
        [0.5 * (left + right) + base_x, -0.5 * table_h],
        [0.5 * (right - left), 0.5 * table_h],
        0.0,
        Color32::from_rgb(92, 96, 108),
    ));
    // Ticks every R/4 on both, so the table's displacement relative to the
    // floor is visible.
    let tick = 0.25 * r;
    let k0 = (left / tick).floor() as i64;
    let k1 = (right / tick).ceil() as i64;
    for k in k0..=k1 {
        let x = k as f64 * tick;
        shapes.push(Shape::rect(
            [x + base_x, -0.5 * table_h],
            [0.75 * px, 0.35 * table_h],
            0.0,
            Color32::from_rgb(150, 154, 166),
        ));
        shapes.push(Shape::rect(
            [x, -table_h - 0.04 * r],
            [0.75 * px, 0.04 * r],
            0.0,
            Color32::from_rgb(90, 92, 100),
        ));
    }
}

/// Builds the shapes of one frame, back to front, and moves the camera.
pub fn build(input: &SceneInput<'_>, rect: Rect, camera: &mut Camera) -> (Vec<Shape>, f64, f64) {
    let geo = &input.geometry;
    let s = input.sample;
    let offsets = column_offsets(geo, input.frame.as_ref());
    // A frame's outer columns' far edges; the single block keeps its own
    // framing.
    let half_span = match input.frame {
        Some(_) => offsets.last().copied().unwrap_or(0.0) + 0.5 * geo.width,
        None => 0.0,
    };
    let (scale, y_mid) = fit(rect, geo.r, half_span);
    let half_w = rect.width() as f64 / scale * 0.5;
    let p = pose(geo, s.theta, s.x, s.mode, s.base_x);
    let dead = 0.3 * half_w;
    if (p.x - camera.x).abs() > dead {
        camera.x = p.x - dead * (p.x - camera.x).signum();
    }
    let px = 1.0 / scale; // one point, in metres
    let mut shapes = Vec::with_capacity(32 + input.ghosts.len());

    stage(&mut shapes, camera.x, half_w, geo.r, p.base_x, px);

    let half = [0.5 * geo.width, 0.5 * geo.height];
    let mode = input.terminal.unwrap_or(s.mode);
    if input.flash > 0.0 {
        let grow = 0.06 * geo.width.min(geo.height) + 4.0 * px;
        for dx in &offsets {
            shapes.push(Shape::rect(
                [p.x + dx, p.y],
                [half[0] + grow, half[1] + grow],
                p.angle,
                Color32::from_rgb(255, 245, 200).gamma_multiply(0.85 * input.flash),
            ));
        }
    }
    for dx in &offsets {
        shapes.push(Shape::rect([p.x + dx, p.y], half, p.angle, mode_color(mode)));
    }
    if input.frame.is_some() {
        // The beam in the mode's colour, darker: it moves with the columns
        // but is a body of its own.
        let (centre, beam_half) = beam(geo, &offsets, &p);
        shapes.push(Shape::rect(
            centre,
            beam_half,
            0.0,
            mode_color(mode).gamma_multiply(0.7),
        ));
    }
    // Ghosts over the block, as outlines in colours of their own: a ghost
    // that still follows the block outlines it, and once chaos separates
    // them each shows as its own coloured frame (filled, or in one shared
    // tint, twenty copies read as a blur at the block's edge). The farthest
    // are drawn first, so the ones still near the block are not hidden
    // under them.
    let n = input.ghosts.len();
    let mut order: Vec<(usize, &GhostState)> = input.ghosts.iter().enumerate().collect();
    order.sort_by(|a, b| (b.1.theta - s.theta).abs().total_cmp(&(a.1.theta - s.theta).abs()));
    for (k, g) in order {
        let gp = pose(geo, g.theta, g.x, g.mode, s.base_x);
        for dx in &offsets {
            shapes.push(Shape::outline(
                [gp.x + dx, gp.y],
                half,
                gp.angle,
                GHOST_OUTLINE * px,
                ghost_color(k, n),
            ));
        }
    }

    // The centre of mass.
    shapes.push(Shape::circle([p.x, p.y], 3.0 * px, Color32::from_rgb(30, 30, 36)));

    let contact = match p.pivot {
        Some((x, _)) => [x, 0.0],
        None => [p.x, 0.0],
    };
    if input.forces && !s.mode.is_terminal() {
        let len = 0.5 * geo.height.min(2.0 * geo.r);
        if input.mu_s.is_finite() {
            let n = len * 1.2;
            let (sn, cs) = input.mu_s.atan().sin_cos();
            for side in [-1.0, 1.0] {
                shapes.push(Shape::segment(
                    contact,
                    [contact[0] + side * n * sn, n * cs],
                    1.5 * px,
                    Color32::from_rgba_unmultiplied(255, 220, 120, 110),
                ));
            }
        }
        let tip = [contact[0] + len * s.friction, len * s.normal];
        shapes.push(Shape::segment(contact, tip, 3.0 * px, Color32::from_rgb(255, 90, 90)));
        shapes.push(Shape::circle(tip, 3.5 * px, Color32::from_rgb(255, 90, 90)));
    }
    if let Some((x, _)) = p.pivot {
        for dx in &offsets {
            shapes.push(Shape::circle([x + dx, 0.0], 6.0 * px, Color32::from_rgb(255, 230, 60)));
            shapes.push(Shape::circle([x + dx, 0.0], 3.0 * px, Color32::from_rgb(40, 30, 10)));
        }
    }
    (shapes, scale, y_mid)
}

/// The view uniform for `rect` at `scale` points per metre.
pub fn view(rect: Rect, scale: f64, camera: &Camera, y_mid: f64, pixels_per_point: f32) -> ViewUniform {
    let sx = 2.0 * scale / rect.width() as f64;
    let sy = 2.0 * scale / rect.height() as f64;
    ViewUniform {
        scale: [sx as f32, sy as f32],
        offset: [(-camera.x * sx) as f32, (-y_mid * sy) as f32],
        px_per_m: [(scale * pixels_per_point as f64) as f32; 2],
        _pad: [0.0; 2],
    }
}

/// Writes how far the ghosts have drifted from the block in the top left
/// corner of `rect`, while there are ghosts and the run goes on: the
/// number grows from ε by orders of magnitude long before the drift shows
/// as pixels.
pub(crate) fn ghost_caption(ui: &mut egui::Ui, rect: Rect, input: &SceneInput<'_>) {
    if input.terminal.is_some() {
        return;
    }
    let Some(spread) = ghost_spread(input.sample, input.ghosts) else {
        return;
    };
    let text = format!(
        "{} ghosts: tilts differ from the block's by up to {spread:.1e} ψ",
        input.ghosts.len()
    );
    let at = Rect::from_min_max(rect.min + egui::vec2(8.0, 6.0), rect.max - egui::vec2(8.0, 0.0));
    let label = egui::Label::new(egui::RichText::new(text).color(Color32::from_rgb(220, 224, 235))).truncate();
    ui.scope_builder(
        egui::UiBuilder::new()
            .max_rect(at)
            .layout(egui::Layout::top_down(egui::Align::Min)),
        |ui| ui.add(label),
    );
}

/// Draws the shapes with wgpu (if `gpu`) or with egui's painter.
pub(crate) fn paint(ui: &egui::Ui, rect: Rect, shapes: Vec<Shape>, view: ViewUniform, gpu: bool) {
    if gpu {
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            rect,
            SceneCallback { view, shapes },
        ));
        return;
    }
    let painter = ui.painter_at(rect);
    let to_screen = |x: f64, y: f64| {
        let nx = x as f32 * view.scale[0] + view.offset[0];
        let ny = y as f32 * view.scale[1] + view.offset[1];
        egui::pos2(
            rect.center().x + 0.5 * nx * rect.width(),
            rect.center().y - 0.5 * ny * rect.height(),
        )
    };
    for s in shapes {
        let c = s.color.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
        let color = Color32::from_rgba_premultiplied(c[0], c[1], c[2], c[3]);
        let [cx, cy] = s.center.map(f64::from);
        let [hx, hy] = s.half_size.map(f64::from);
        let stroke = s.stroke[0] * view.px_per_m[0] / ui.ctx().pixels_per_point();
        if s.angle_shape[1] > 0.5 {
            let r = hx as f32 * view.px_per_m[0] / ui.ctx().pixels_per_point();
            painter.circle_filled(to_screen(cx, cy), r, color);
        } else {
            let (sn, cs) = f64::from(s.angle_shape[0]).sin_cos();
            let corner = |a: f64, b: f64| {
                let (lx, ly) = (a * hx, b * hy);
                to_screen(cx + lx * cs + ly * sn, cy - lx * sn + ly * cs)
            };
            let pts = vec![
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            if stroke > 0.0 {
                painter.add(egui::Shape::closed_line(pts, egui::Stroke::new(stroke, color)));
            } else {
                painter.add(egui::Shape::convex_polygon(pts, color, egui::Stroke::NONE));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Sign;

    /// The beam drawn on a tilted frame lies on the columns' support
    /// corners: its underside at their height, its ends beyond them, and it
    /// moves with them (docs/model.md §16.1), computed here from the
    /// column's corners turned about its pivot.
    #[test]
    fn a_frames_beam_rests_on_the_support_corners_of_its_tilted_columns() {
        let geo = Geometry::new(0.7, 4.2);
        let frame = Frame {
            columns: 3,
            beam_mass_ratio: 1.0,
        };
        let offsets = column_offsets(&geo, Some(&frame));
        assert_eq!(offsets.len(), 3);
        assert!((offsets[0] + offsets[2]).abs() < 1e-12 && offsets[1].abs() < 1e-12);
        for theta in [0.4, -0.7, 0.0] {
            let p = pose(&geo, theta, 0.0, Mode::Rock { pivot: Sign::of(theta) }, 0.0);
            let (centre, half) = beam(&geo, &offsets, &p);
            if theta == 0.0 {
                assert!((centre[1] - half[1] - geo.height).abs() < 1e-12);
                continue;
            }
            // The support corner: opposite the pivot, on the diagonal, at
            // 2R from it, turned by θ = ψΘ clockwise for θ > 0.
            let (pivot_x, s) = p.pivot.expect("tilted");
            let s = s.value();
            let rest = [-s * geo.width, geo.height];
            let a = geo.psi * theta;
            let corner = [
                pivot_x + rest[0] * a.cos() + rest[1] * a.sin(),
                -rest[0] * a.sin() + rest[1] * a.cos(),
            ];
            assert!(
                (centre[1] - half[1] - corner[1]).abs() < 1e-12,
                "θ {theta}: underside at the corners"
            );
            for dx in &offsets {
                let x = corner[0] + dx;
                assert!(
                    centre[0] - half[0] < x && x < centre[0] + half[0],
                    "θ {theta}: corner under the beam"
                );
            }
        }
    }
}
