//! The cheap screening of a step: which guards can be cleared on the cubic
//! Hermite interpolant, so that most steps never build the high-order dense
//! output. It must change no result, bit for bit (`tests/screening.rs`).

use super::{HybridSystem, MAX_GUARDS, SUBINTERVALS};
use crate::integrate::stepper::Stepper;

/// Margin of the cheap screening of a step: a guard is cleared without
/// dense output if its values at the ends and at the Hermite midpoint are
/// all above `SCREEN_MARGIN` times its variation between them. For a
/// resolved smooth guard (steps below the time scale, error control on the
/// state) the value between samples departs from them by a fraction of that
/// variation: at most 1/8 of it for a sinusoid sampled at its extremum.
pub const SCREEN_MARGIN: f64 = 1.0;

/// Whether the samples `values` of a guard over a step (start, interior,
/// end, in time order) clear it for the step: all of one sign, `sign`
/// (+1 for an armed guard that must not fall to zero, −1 for an unarmed
/// one that must not rise above it), and farther from zero than
/// [`SCREEN_MARGIN`] times the largest change between neighbours plus
/// `slack`, the possible error of the samples.
#[inline]
fn clears(values: &[f64], sign: f64, slack: f64) -> bool {
    let mut nearest = f64::INFINITY;
    let mut largest_change = 0.0f64;
    for (j, &g) in values.iter().enumerate() {
        nearest = nearest.min(sign * g);
        if j > 0 {
            largest_change = largest_change.max((g - values[j - 1]).abs());
        }
    }
    nearest > 0.0 && nearest > SCREEN_MARGIN * largest_change + slack
}

/// How a guard is screened, by its state at the start of the step.
#[derive(Clone, Copy)]
enum Screening {
    /// Armed and positive: must stay positive.
    Positive,
    /// Unarmed and negative (an observer that fired, or a guard behind its
    /// surface): must stay negative, so it can neither arm nor fire.
    Negative,
    /// Just reset onto its surface (exactly 0): must leave it at once and
    /// stay positive. [`bracket`] arms such a guard at the first sample
    /// above zero and looks for a bump only if that sample is not above
    /// zero, so the screening asks the same of the first sample and the
    /// margin of the rest.
    FromSurface,
}

/// The [`Screening`] of a guard, or `None` when there is no cheap verdict
/// (the dense output decides).
#[inline]
fn screening_case(armed: bool, g_start: f64) -> Option<Screening> {
    if armed && g_start > 0.0 {
        Some(Screening::Positive)
    } else if !armed && g_start < 0.0 {
        Some(Screening::Negative)
    } else if !armed && g_start == 0.0 {
        Some(Screening::FromSurface)
    } else {
        None
    }
}

/// Whether the samples `values` (start, interior, end, in time order) clear
/// a guard screened as `case`.
#[inline]
fn cleared(values: &[f64], case: Screening, slack: f64) -> bool {
    match case {
        Screening::Positive => clears(values, 1.0, slack),
        Screening::Negative => clears(values, -1.0, slack),
        Screening::FromSurface => {
            // The first sample after the surface must be clearly above it
            // (a quarter of the largest change between the later samples),
            // and the later ones clear with the usual margin.
            let rest = &values[2..];
            let largest_change = rest.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
            values[1] > 0.25 * largest_change + slack && values[1] > 0.0 && clears(rest, 1.0, slack)
        }
    }
}

/// Which guards of the step just taken need the high-order dense output:
/// those that are not cleared on the cheap cubic Hermite interpolant.
///
/// First all guards are evaluated at the Hermite midpoint and tested on
/// (start, midpoint, end) with [`clears`]. The guards left are sampled alone
/// at the [`SUBINTERVALS`]` - 1` interior Hermite points (for guards on the
/// state alone that is a few flops each) and tested again on those samples.
/// The Hermite interpolant is accurate to O(h⁴), orders of magnitude below
/// the margin for a step that resolves the state (and steps are capped at
/// the system's time scale for guards that depend on time alone).
pub(super) fn screen<Sys, S, const N: usize>(
    sys: &Sys,
    mode: Sys::Mode,
    n: usize,
    stepper: &S,
    armed: &[bool; MAX_GUARDS],
    g_start: &[f64; MAX_GUARDS],
    g_end: &[f64; MAX_GUARDS],
) -> [bool; MAX_GUARDS]
where
    Sys: HybridSystem<N>,
    S: Stepper<N>,
{
    let mut need = [true; MAX_GUARDS];
    let (t0, t1) = (stepper.t_prev(), stepper.t());
    let mut ym = [0.0; N];
    let tm = 0.5 * (t0 + t1);
    // Only a step that resolves the explicit time dependence is screened
    // (loose tolerances can take steps of several radians of forcing).
    // Guards read no quadrature: the interpolants skip them.
    let reads = N - Sys::QUADRATURES.min(N);
    if n == 0 || t1 - t0 > sys.time_scale() || !stepper.hermite_leading(tm, &mut ym, reads) {
        return need;
    }
    let mut gm = [0.0; MAX_GUARDS];
    sys.guards(mode, tm, &ym, &mut gm);
    // How far the Hermite values may be off, in each guard's own units: the
    // guards at the midpoint of the quadratic through y0, f0, y1 differ from
    // those of the cubic by about the cubic's third-order term, an
    // overestimate of its error. A guard whose values are not clear of zero
    // by more than that is left to the dense output (this is what catches a
    // guard of size 1e-8 on a step whose Hermite error is 1e-5).
    let mut spread = [0.0; N];
    if !stepper.hermite_spread(&mut spread) {
        return need;
    }
    let yq: [f64; N] = std::array::from_fn(|k| ym[k] - spread[k]);
    let mut gq = [0.0; MAX_GUARDS];
    sys.guards(mode, tm, &yq, &mut gq);
    let mut slack = [0.0; MAX_GUARDS];
    for i in 0..n {
        slack[i] = (gm[i] - gq[i]).abs();
        if !slack[i].is_finite() {
            return need;
        }
    }
    let mut rest = false;
    for i in 0..n {
        let Some(case) = screening_case(armed[i], g_start[i]) else {
            continue;
        };
        // A guard just reset onto its surface needs the finer look: three
        // samples say nothing about how it leaves the surface.
        if !matches!(case, Screening::FromSurface) && cleared(&[g_start[i], gm[i], g_end[i]], case, slack[i]) {
            need[i] = false;
        } else {
            rest = true;
        }
    }
    if !rest {
        return need;
    }
    // The finer look, on the Hermite interpolant.
    let mut ys = [[0.0; N]; SUBINTERVALS + 1];
    let mut ts = [0.0; SUBINTERVALS + 1];
    for j in 1..SUBINTERVALS {
        ts[j] = t0 + (t1 - t0) * (j as f64 / SUBINTERVALS as f64);
        stepper.hermite_leading(ts[j], &mut ys[j], reads);
    }
    // Guards still in question, and all of them per sample if that is
    // cheaper (see `several_costly`).
    let mut open = [false; MAX_GUARDS];
    for i in 0..n {
        open[i] = need[i] && screening_case(armed[i], g_start[i]).is_some();
    }
    let mut all = [[0.0; MAX_GUARDS]; SUBINTERVALS + 1];
    let all_at_once = several_costly(sys, mode, n, &open);
    if all_at_once {
        for j in 1..SUBINTERVALS {
            sys.guards(mode, ts[j], &ys[j], &mut all[j]);
        }
    }
    for i in 0..n {
        let Some(case) = screening_case(armed[i], g_start[i]) else {
            continue;
        };
        if !need[i] {
            continue;
        }
        let mut values = [0.0; SUBINTERVALS + 1];
        values[0] = g_start[i];
        values[SUBINTERVALS] = g_end[i];
        for j in 1..SUBINTERVALS {
            values[j] = if all_at_once {
                all[j][i]
            } else {
                sys.guard(mode, i, ts[j], &ys[j])
            };
        }
        if cleared(&values, case, slack[i]) {
            need[i] = false;
        }
    }
    need
}

/// Whether the guards marked in `need` are cheaper evaluated all at once by
/// [`HybridSystem::guards`] than one by one by [`HybridSystem::guard`]: when
/// at least two are wanted and one of them is not cheap (each costly
/// `guard` call costs about a `guards` call). Same values either way (the
/// contract of `guard`).
pub(super) fn several_costly<Sys: HybridSystem<N>, const N: usize>(
    sys: &Sys,
    mode: Sys::Mode,
    n: usize,
    need: &[bool; MAX_GUARDS],
) -> bool {
    let wanted = (0..n).filter(|&i| need[i]).count();
    wanted >= 2 && (0..n).any(|i| need[i] && !sys.guard_is_cheap(mode, i))
}
