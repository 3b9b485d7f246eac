//! A stack of blocks on the shake table: every block at the pose the core
//! gives its state ([`crate::model::stack::Pose`]), bottom to top, each in
//! the colour of its lower face's contact (closed, rocking left, rocking
//! right: the block's mode colours; a glued face is closed), the pivot of
//! every open face marked, and a flash at the face that last hit.
//!
//! This module does no mechanics: it places rectangles where the core's
//! placement puts each block and picks colours, sizes on screen and the
//! camera.

use egui::{Color32, Rect};

use super::scene::{Camera, fit, mode_color, stage};
use crate::gui::block_view::Shape;
use crate::model::Mode;
use crate::model::stack::{Contact, Pose, StackEnd, StackGeometry};
use crate::sim::protocol::{StackFrame, face_mode, face_slip};

/// What the stack's scene needs from the app.
pub struct StackSceneInput<'a> {
    /// The stack's shape.
    pub geo: &'a StackGeometry,
    /// The state shown.
    pub frame: &'a StackFrame,
    /// The base's displacement, m.
    pub base_x: f64,
    /// Impact flash strength in [0, 1].
    pub flash: f32,
    /// The interface the flash is at (0: the base under the bottom block).
    pub flash_face: Option<usize>,
    /// How the run ended, if it did (the last sample is drawn, from
    /// before the end: the overturned blocks are drawn red from it).
    pub ended: Option<StackEnd>,
}

/// One block as drawn: its centre (m), half width and height (m) and its
/// clockwise rotation (rad), in the base's rest frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Centre, m.
    pub centre: [f64; 2],
    /// Half width and half height, m.
    pub half: [f64; 2],
    /// Rotation φ_j, rad, clockwise.
    pub angle: f64,
}

impl Body {
    /// Its four corners, m: lower left, lower right, upper right, upper
    /// left, as the renderer turns them (clockwise by the angle).
    pub fn corners(&self) -> [[f64; 2]; 4] {
        let (s, c) = self.angle.sin_cos();
        [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]].map(|[a, b]| {
            let (x, y) = (a * self.half[0], b * self.half[1]);
            [self.centre[0] + x * c + y * s, self.centre[1] - x * s + y * c]
        })
    }
}

/// Every block of `geo` in state `frame`, bottom to top, moved with the
/// base by `base_x`, m.
pub fn bodies(geo: &StackGeometry, frame: &StackFrame, base_x: f64) -> Vec<Body> {
    let pose = Pose::new(geo, &frame.mode.contacts, &frame.y);
    (0..geo.k)
        .map(|j| Body {
            centre: [pose.centre[j][0] + base_x, pose.centre[j][1]],
            half: [0.5 * geo.size[j][0], 0.5 * geo.size[j][1]],
            angle: pose.phi[j],
        })
        .collect()
}

/// The colour block `j` is drawn in: its lower face's contact, or red
/// once it (or a block under it) overturned, violet once it flew.
fn body_color(frame: &StackFrame, ended: Option<StackEnd>, j: usize) -> Color32 {
    let mode = match ended.or(frame.mode.end) {
        Some(StackEnd::Overturned(i)) if j >= i => Mode::Tumbled,
        Some(StackEnd::Flight(i)) if j >= i => Mode::Flight,
        Some(StackEnd::Overturned(_) | StackEnd::Flight(_)) | None => {
            face_mode(frame.mode.contacts[j], face_slip(&frame.mode, j))
        }
    };
    mode_color(mode)
}

/// The half-diagonal of the stack's bounding box at rest, m: the camera
/// frames a body this size as it frames one block (2.5 of it high), so
/// the whole stack is in view, tilted or not.
pub(crate) fn framing_radius(geo: &StackGeometry) -> f64 {
    let height: f64 = (0..geo.k).map(|j| geo.size[j][1]).sum();
    let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
    for j in 0..geo.k {
        left = left.min(geo.centre[j][0] - 0.5 * geo.size[j][0]);
        right = right.max(geo.centre[j][0] + 0.5 * geo.size[j][0]);
    }
    0.5 * (right - left).hypot(height)
}

/// Builds the shapes of one frame, back to front, and moves the camera;
/// also returns the blocks as drawn. Returns (shapes, points per metre,
/// world height at the rect's centre, bodies).
pub fn build(input: &StackSceneInput<'_>, rect: Rect, camera: &mut Camera) -> (Vec<Shape>, f64, f64, Vec<Body>) {
    let geo = input.geo;
    let r = framing_radius(geo);
    let (scale, y_mid) = fit(rect, r, 0.0);
    let half_w = rect.width() as f64 / scale * 0.5;
    let drawn = bodies(geo, input.frame, input.base_x);
    // Follow the stack's middle (the bottom block, with the base), with a
    // dead zone as for one block.
    let x = drawn.first().map_or(0.0, |b| b.centre[0]);
    let dead = 0.3 * half_w;
    if (x - camera.x).abs() > dead {
        camera.x = x - dead * (x - camera.x).signum();
    }
    let px = 1.0 / scale;
    let mut shapes = Vec::with_capacity(40 + 4 * geo.k);
    stage(&mut shapes, camera.x, half_w, r, input.base_x, px);
    for (j, b) in drawn.iter().enumerate() {
        shapes.push(Shape::rect(
            b.centre,
            b.half,
            b.angle,
            body_color(input.frame, input.ended, j),
        ));
        // A thin dark outline, so blocks of one colour stay apart.
        shapes.push(Shape::outline(
            b.centre,
            b.half,
            b.angle,
            px,
            Color32::from_rgb(30, 30, 36),
        ));
    }
    if input.flash > 0.0
        && let Some(b) = input.flash_face.and_then(|i| drawn.get(i))
    {
        // A bright band along the lower face of the block that hit.
        let [l, r, ..] = b.corners();
        let grow = 4.0 * px;
        shapes.push(Shape::rect(
            [0.5 * (l[0] + r[0]), 0.5 * (l[1] + r[1])],
            [b.half[0] + grow, grow],
            b.angle,
            Color32::from_rgb(255, 245, 200).gamma_multiply(0.9 * input.flash),
        ));
    }
    // The centres of mass, then the pivots of the open faces on top.
    for b in &drawn {
        shapes.push(Shape::circle(b.centre, 3.0 * px, Color32::from_rgb(30, 30, 36)));
    }
    if input.frame.mode.end.is_none() {
        let pose = Pose::new(geo, &input.frame.mode.contacts, &input.frame.y);
        for j in 0..geo.k {
            if input.frame.mode.contacts[j] != Contact::Closed {
                let at = [pose.pivot[j][0] + input.base_x, pose.pivot[j][1]];
                shapes.push(Shape::circle(at, 6.0 * px, Color32::from_rgb(255, 230, 60)));
                shapes.push(Shape::circle(at, 3.0 * px, Color32::from_rgb(40, 30, 10)));
            }
        }
    }
    (shapes, scale, y_mid, drawn)
}
