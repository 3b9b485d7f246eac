//! A stack of blocks (config `[[stack]]`) in the engineering analyses:
//! the size it is stepped by and the stack scaled to a size (its run's
//! answer is `response::respond`'s).
//!
//! A spectrum or a fragility study scales every body of the stack by one
//! factor, so its shape (each block's proportions, the offsets, the ratios
//! between the blocks) stays the config's and only its size changes, as a
//! block's B/H stays fixed while its R is stepped. The stack's size is
//! that of its **bounding block**: the bottom block's width B₀ and the
//! stack's total height H. A glued stack of blocks of one width is
//! exactly that block, so its spectrum is the block's.

use super::block_size::BlockSize;
use crate::model::stack::StackBlock;
use crate::sim::{Scenario, ScenarioError};

/// How far apart (relative) a size's B/H and the stack's own may be and
/// still be the stack's: sizes are rebuilt from R and B/H through a sine
/// and a cosine, which moves B/H by a few ulps, never by 1e-9.
const SAME_SHAPE: f64 = 1e-9;

/// The stack's bounding block: its bottom block's width and its total
/// height, m.
pub fn stack_size(blocks: &[StackBlock]) -> BlockSize {
    BlockSize {
        width_m: blocks.first().map_or(0.0, |b| b.width),
        height_m: blocks.iter().map(|b| b.height).sum(),
    }
}

/// Scales every block of `s`'s stack (widths, heights and offsets) by the
/// one factor that makes its bounding block `size`, and sets `s.block` to
/// the scaled bottom block (whose p and ψ are the run's units). Refused
/// when `size`'s B/H is not the stack's own: that would change its shape,
/// not its size.
pub(crate) fn scale_stack(s: &mut Scenario, size: BlockSize) -> Result<(), ScenarioError> {
    let Some(blocks) = s.stack.as_mut() else {
        return Ok(());
    };
    let own = stack_size(blocks);
    let (ratio, asked) = (own.width_m / own.height_m, size.width_m / size.height_m);
    if (asked - ratio).abs() > SAME_SHAPE * ratio || asked.is_nan() {
        return Err(ScenarioError::new(
            "stack",
            format!(
                "is scaled as a whole, keeping its own B/H = {ratio:.4} (its bottom width over its total height); a size of B/H = {asked:.4} would change its shape"
            ),
        ));
    }
    let k = size.half_diagonal_m() / own.half_diagonal_m();
    for b in blocks.iter_mut() {
        b.width *= k;
        b.height *= k;
        b.offset *= k;
    }
    s.block.width = blocks[0].width;
    s.block.height = blocks[0].height;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(width: f64, height: f64, offset: f64, glued: bool) -> StackBlock {
        StackBlock {
            glued,
            ..StackBlock::new(width, height, offset)
        }
    }

    /// A scenario of `blocks` (bottom to top) on the default scene.
    fn stack_scene(blocks: Vec<StackBlock>) -> Scenario {
        let mut s = Scenario::default();
        s.block.width = blocks[0].width;
        s.block.height = blocks[0].height;
        s.stack = Some(blocks);
        s
    }

    #[test]
    fn a_stack_is_scaled_as_a_whole_to_the_size_of_its_bounding_block() {
        let mut s = stack_scene(vec![block(0.6, 0.4, 0.0, false), block(0.3, 0.8, 0.05, false)]);
        assert_eq!(
            stack_size(s.stack.as_ref().unwrap()),
            BlockSize {
                width_m: 0.6,
                height_m: 1.2000000000000002
            }
        );
        // Twice the bounding block: 1.2 m wide and 2.4 m tall.
        let size = BlockSize::from_half_diagonal(0.5 * 1.2f64.hypot(2.4), 0.5);
        scale_stack(&mut s, size).unwrap();
        let b = s.stack.as_ref().unwrap();
        for (got, want) in [
            (b[0].width, 1.2),
            (b[0].height, 0.8),
            (b[1].width, 0.6),
            (b[1].height, 1.6),
            (b[1].offset, 0.1),
            (s.block.width, 1.2),
            (s.block.height, 0.8),
        ] {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
        // Another B/H would change the shape: refused, naming the stack.
        let e = scale_stack(&mut s, BlockSize::from_height(2.0, 0.3)).unwrap_err();
        assert_eq!(e.key, "stack");
        assert!(e.to_string().contains("B/H = 0.5000"), "{e}");
    }
}
