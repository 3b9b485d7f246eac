//! Each block's outline at a state: what a picture of the stack draws,
//! from the same placement the equations use ([`Pose`]), so the drawing
//! and the mechanics cannot disagree.

use super::pose::{Pose, V2};
use super::{Contact, MAX_BLOCKS, NS, StackGeometry};

/// Block `j`'s four corners at rest, m: lower left, lower right, upper
/// right, upper left (counter-clockwise, as a polygon is drawn).
pub fn rest_corners(geo: &StackGeometry, j: usize) -> [V2; 4] {
    let [cx, cy] = geo.centre[j];
    let [w, h] = geo.size[j];
    let (hw, hh) = (0.5 * w, 0.5 * h);
    [
        [cx - hw, cy - hh],
        [cx + hw, cy - hh],
        [cx + hw, cy + hh],
        [cx - hw, cy + hh],
    ]
}

/// Block `j`'s four corners in `pose`, m, in the base's frame (x to the
/// right from under the bottom block's centre at rest, y up from the
/// base), in the order of [`rest_corners`].
pub fn corners(geo: &StackGeometry, pose: &Pose, j: usize) -> [V2; 4] {
    rest_corners(geo, j).map(|c| pose.place(j, c))
}

/// Every block's corners at state `y` with contacts `contacts`, bottom
/// to top (the first `geo.k` entries; the rest are zero).
pub fn outlines(geo: &StackGeometry, contacts: &[Contact; MAX_BLOCKS], y: &[f64; NS]) -> [[V2; 4]; MAX_BLOCKS] {
    let pose = Pose::new(geo, contacts, y);
    let mut out = [[[0.0; 2]; 4]; MAX_BLOCKS];
    for (j, o) in out.iter_mut().enumerate().take(geo.k) {
        *o = corners(geo, &pose, j);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::stack::StackBlock;

    fn block(width: f64, height: f64, offset: f64) -> StackBlock {
        StackBlock::new(width, height, offset)
    }

    /// Turns `p` clockwise by `a` about `c`.
    fn turn_about(p: V2, c: V2, a: f64) -> V2 {
        let (s, co) = a.sin_cos();
        let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
        [c[0] + dx * co + dy * s, c[1] - dx * s + dy * co]
    }

    /// Two blocks, the bottom rocking on its right corner by q₁ and the
    /// top on its left corner by q₂: built here by turning the rest
    /// corners about the pivots in turn (the top about its pivot, which
    /// rides on the bottom block, then both about the base's pivot).
    #[test]
    fn a_rocking_two_block_stacks_corners_are_its_rest_corners_turned_about_each_pivot() {
        let geo = StackGeometry::new(&[block(1.0, 2.0, 0.0), block(0.6, 1.0, 0.1)]).expect("stands");
        let (q1, q2) = (0.07, -0.12);
        let mut contacts = [Contact::Closed; MAX_BLOCKS];
        contacts[0] = Contact::Right;
        contacts[1] = Contact::Left;
        let mut y = [0.0; NS];
        y[0] = q1;
        y[1] = q2;
        let drawn = outlines(&geo, &contacts, &y);
        // Pivots at rest: the base's under the bottom block's right edge,
        // the top's at the left end of the overlap (top's left edge, as
        // 0.1 − 0.3 > −0.5), on the bottom block's top face.
        let p1 = [0.5, 0.0];
        let p2 = [0.1 - 0.3, 2.0];
        let bottom = [[-0.5, 0.0], [0.5, 0.0], [0.5, 2.0], [-0.5, 2.0]].map(|c| turn_about(c, p1, q1));
        let top = [[-0.2, 2.0], [0.4, 2.0], [0.4, 3.0], [-0.2, 3.0]].map(|c| turn_about(turn_about(c, p2, q2), p1, q1));
        for (want, got) in [bottom, top].iter().zip(&drawn[..2]) {
            for (w, g) in want.iter().zip(got) {
                assert!(
                    (w[0] - g[0]).abs() < 1e-14 && (w[1] - g[1]).abs() < 1e-14,
                    "{w:?} vs {g:?}"
                );
            }
        }
    }
}
