//! A stack of blocks (config `[[stack]]`) in the engineering analyses:
//! the size it is stepped by, the stack scaled to a size, and one run's
//! answer.
//!
//! A spectrum or a fragility study scales every body of the stack by one
//! factor, so its shape (each block's proportions, the offsets, the ratios
//! between the blocks) stays the config's and only its size changes, as a
//! block's B/H stays fixed while its R is stepped. The stack's size is
//! that of its **bounding block**: the bottom block's width B₀ and the
//! stack's total height H. A glued stack of blocks of one width is
//! exactly that block, so its spectrum is the block's.

use super::response::{BlockResponse, BlockSize, ResponseError};
use crate::model::stack::StackBlock;
use crate::sim::stack_run::simulate_stack;
use crate::sim::{EndState, Scenario, ScenarioError};

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

/// The answer of the stack of the checked scenario `s`: it ends as the
/// first body to overturn or fly ends it; its peak rotation is that of
/// the block that turned most over its own slenderness
/// ([`StackRun::most_turned`](crate::sim::stack_run::StackRun::most_turned)).
pub(crate) fn respond_stack(s: &Scenario) -> Result<BlockResponse, ResponseError> {
    let geo = s
        .stack_geometry()
        .ok_or_else(|| ScenarioError::new("stack", "its blocks do not stand on each other"))?;
    let run = simulate_stack(geo, s.excitation()?, s.run.zeno_eps, &s.run_options())?;
    let p = s.geometry().p;
    let end = EndState::of(run.outcome);
    let event = run.end.map(|(end, tau)| (end.body(), tau / p));
    Ok(BlockResponse {
        end,
        peak_theta_over_alpha: run.most_turned().2,
        t_end_event_s: event.map(|(_, t)| t),
        body: event.map(|(j, _)| j),
    })
}

#[cfg(test)]
mod tests {
    use super::super::response::{Drive, respond};
    use super::*;
    use crate::sim::scenario::ShapeKind;

    fn block(width: f64, height: f64, offset: f64, glued: bool) -> StackBlock {
        StackBlock {
            width,
            height,
            offset,
            mu_s: f64::INFINITY,
            mu_k: None,
            glued,
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

    #[test]
    fn a_glued_stack_of_one_width_answers_as_the_block_of_its_height() {
        // Three glued 0.4 × 0.5 m blocks but the bottom face free: the
        // 0.4 × 1.5 m block, under a one-sine pulse that rocks it and one
        // that overturns it. The block's answer is its own code's
        // (`respond` without a stack); τ units differ (the stack's are its
        // bottom block's), so times agree to the integrator's tolerance.
        let stack = stack_scene(vec![
            block(0.4, 0.5, 0.0, false),
            block(0.4, 0.5, 0.0, true),
            block(0.4, 0.5, 0.0, true),
        ]);
        let size = BlockSize {
            width_m: 0.4,
            height_m: 1.5,
        };
        for (a_p_g, want) in [(0.45, EndState::Rest), (3.0, EndState::Overturned)] {
            let drive = Drive::PhysicalPulse {
                shape: ShapeKind::OneSine,
                cycles: 1,
                a_p_g,
                omega_p: std::f64::consts::TAU / 0.5,
            };
            let one = respond(&Scenario::default(), size, &drive, 1.0).unwrap();
            let three = respond(&stack, size, &drive, 1.0).unwrap();
            assert_eq!((one.end, three.end), (want, want), "{one:?} {three:?}");
            // The glued blocks' own slenderness is atan(0.4/0.5), the
            // whole block's atan(0.4/1.5): the peak rotations agree once
            // each is brought back to radians.
            let (alpha_one, alpha_part) = ((0.4f64 / 1.5).atan(), 0.8f64.atan());
            let (rad_one, rad_three) = (
                one.peak_theta_over_alpha * alpha_one,
                three.peak_theta_over_alpha * alpha_part,
            );
            if want == EndState::Rest {
                assert!(rad_one > 0.01, "it rocks: {rad_one}");
                assert!((rad_one - rad_three).abs() < 1e-7, "{rad_one} vs {rad_three}");
            } else {
                let (t1, t3) = (one.t_end_event_s.unwrap(), three.t_end_event_s.unwrap());
                assert!((t1 - t3).abs() < 1e-7, "{t1} vs {t3}");
                assert_eq!(three.body, Some(0));
            }
            assert_eq!(one.body, None);
        }
    }
}
