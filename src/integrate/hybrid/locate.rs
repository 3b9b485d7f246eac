//! Event location on the dense output: guard samples over a step, the
//! bracket of each guard's first crossing (dips and departures from a
//! surface included), Brent's root, and the observers before the event.

use super::screen::several_costly;
use super::{Driver, Field, HybridSystem, MAX_GUARDS, Observer, SUBINTERVALS};
use crate::integrate::root::{brent_min, brent_root};
use crate::integrate::stepper::Stepper;

/// Most offsets [`landing_near_surface_time`] looks at (halvings of half a
/// sample interval: 40 reach 1e-12 of it).
const SURFACE_PROBES: usize = 40;

/// Evenly spaced points at which [`landing_near_surface_time`] looks over
/// the first sample interval when its probes near the reset find nothing:
/// the hop it was added for (stress tier) landed 0.6 of the way through
/// the interval and was back above the surface by its end, 0.35 of it later.
const SURFACE_SCAN: usize = 16;

/// How deep behind its surface, relative to the guard's value two samples
/// after a reset, a probe must find it to count as a landing (1e-6: the
/// missed landing this catches dipped to 5.6e-3 of that value; round-off
/// noise right after a reset is far below it).
const LANDING_DEPTH: f64 = 1e-6;

/// How far behind its surface, in the guard's own units, a guard reset onto
/// it must be at the end of a step that took it straight there (every
/// sample behind, no bump above) for that to count as leaving at once
/// (see [`straight_behind_surface`]): far above the round-off of a reset
/// (1e-16 of state components of order 1), far below any motion that
/// matters (the case that needed it ended its step 2.8e-6 behind).
const BEHIND_FLOOR: f64 = 1e-12;

impl<S, Sys, const N: usize> Driver<S, Sys, N>
where
    S: Stepper<N>,
    Sys: HybridSystem<N>,
{
    /// Samples the guards in `need` on the dense output of the step just
    /// taken, locates the earliest crossing and the observers before it, and
    /// applies the event (or accepts the step if there is none).
    pub(super) fn locate<O>(
        &mut self,
        need: &[bool; MAX_GUARDS],
        g_end: [f64; MAX_GUARDS],
        obs: &mut O,
    ) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let n = self.n_guards;
        // Guards read no quadrature: samples interpolate the rest only.
        let reads = N - Sys::QUADRATURES.min(N);
        let mut armed = self.armed;
        // Observer roots before the event; their states are interpolated
        // after this block (no array of states to zero on every call).
        let mut observed = [None; MAX_GUARDS];
        let screening = self.limits.screening;
        let best = {
            let sys = &self.system;
            let stepper = &mut self.stepper;
            let f = Field { sys, mode };
            let t0 = stepper.t_prev();
            let t1 = stepper.t();
            // Guard samples on the dense output, for the guards that need it.
            let mut ts = [0.0; SUBINTERVALS + 1];
            let mut gs = [[0.0; MAX_GUARDS]; SUBINTERVALS + 1];
            ts[0] = t0;
            gs[0] = self.g_start;
            ts[SUBINTERVALS] = t1;
            gs[SUBINTERVALS] = g_end;
            // The sampled states (leading components), kept for the
            // observers' `observer_may_record`.
            let mut ys = [[0.0; N]; SUBINTERVALS + 1];
            // (The dense output returns the step's end states exactly.)
            stepper.dense(&f, t0, &mut ys[0]);
            ys[SUBINTERVALS] = *stepper.y();
            let all_at_once = several_costly(sys, mode, n, need);
            // The samples interpolate what the guards sampled read: Θ
            // alone for the block's impact and tumble guards, a quarter of
            // the dense output's work; all guards' reads when they are
            // evaluated together (Θ and Θ' for the block's rocking).
            let sample_reads = (0..n)
                .filter(|&i| all_at_once || need[i])
                .map(|i| sys.guard_reads(mode, i).min(reads))
                .max()
                .unwrap_or(reads);
            for j in 1..SUBINTERVALS {
                ts[j] = t0 + (t1 - t0) * (j as f64 / SUBINTERVALS as f64);
                let yj = &mut ys[j];
                stepper.dense_leading(&f, ts[j], yj, sample_reads);
                if all_at_once {
                    sys.guards(mode, ts[j], yj, &mut gs[j]);
                } else {
                    for i in (0..n).filter(|&i| need[i]) {
                        gs[j][i] = sys.guard(mode, i, ts[j], yj);
                    }
                }
            }

            // Earliest bracket per guard, then its root.
            let mut best: Option<(f64, usize)> = None;
            let mut roots = [None; MAX_GUARDS];
            for i in (0..n).filter(|&i| need[i]) {
                let reads_i = sys.guard_reads(mode, i).min(reads);
                let mut value = |tt: f64| {
                    let mut yy = [0.0; N];
                    stepper.dense_leading(&f, tt, &mut yy, reads_i);
                    sys.guard(mode, i, tt, &yy)
                };
                let Some((a, b)) = bracket(i, &ts, &gs, &mut armed[i], &mut value) else {
                    continue;
                };
                // An observer whose root cannot change its record is not
                // located (a bracket between two samples only). Part of the
                // screening: `tests/screening.rs` checks that it changes
                // no result.
                if screening
                    && sys.is_observer(mode, i)
                    && let (Some(ka), Some(kb)) = (ts.iter().position(|&x| x == a), ts.iter().position(|&x| x == b))
                    && !sys.observer_may_record(mode, i, a, &ys[ka], b, &ys[kb])
                {
                    continue;
                }
                // Bracket ends at samples have their values already (the
                // same bits: `guard` equals `guards`, and the dense output
                // returns the step's end states exactly); a dip's minimum
                // does not.
                let mut at = |x: f64| match ts.iter().position(|&tk| tk == x) {
                    Some(k) => gs[k][i],
                    None => value(x),
                };
                let ga = at(a);
                let gb = at(b);
                let root = if ga > 0.0 && gb <= 0.0 {
                    let xtol = (4.0 * f64::EPSILON * a.abs().max(b.abs())).max(1e-15);
                    match brent_root(&mut value, a, b, ga, gb, xtol, 200) {
                        Ok((r, _)) => r,
                        Err(_) => b,
                    }
                } else {
                    b
                };
                roots[i] = Some(root);
                if !sys.is_observer(mode, i) && best.is_none_or(|(tb, _)| root < tb) {
                    best = Some((root, i));
                }
            }
            // Observers located before the event (or anywhere, without one).
            let t_cut = best.map_or(t1, |(tb, _)| tb);
            for i in 0..n {
                if let Some(to) = roots[i]
                    && sys.is_observer(mode, i)
                    && to <= t_cut
                {
                    observed[i] = Some(to);
                }
            }
            best
        };
        for (i, to) in observed.iter().enumerate().take(n) {
            if let Some(to) = *to {
                let mut yo = [0.0; N];
                {
                    let f = Field {
                        sys: &self.system,
                        mode,
                    };
                    self.stepper.dense(&f, to, &mut yo);
                }
                self.system.observe(mode, i, to, &yo);
            }
        }

        match best {
            None => {
                self.accept(armed, g_end, obs);
                Ok(())
            }
            Some((t_ev, i)) => {
                let mut y_ev = [0.0; N];
                {
                    let sys = &self.system;
                    let f = Field { sys, mode };
                    self.stepper.dense(&f, t_ev, &mut y_ev);
                }
                self.emit_samples_dense(t_ev, obs);
                // A section time at the event itself reports the post-jump
                // state (`apply_jump`).
                self.emit_sections_dense(t_ev, false, obs);
                self.apply_jump(i, t_ev, y_ev, obs)
            }
        }
    }
}

/// The bracket `[a, b]` of the first crossing of guard `i` in one step, if
/// any, including dips between samples. `value` evaluates guard `i` on the
/// step's dense output.
fn bracket<V: FnMut(f64) -> f64>(
    i: usize,
    ts: &[f64; SUBINTERVALS + 1],
    gs: &[[f64; MAX_GUARDS]; SUBINTERVALS + 1],
    armed: &mut bool,
    value: &mut V,
) -> Option<(f64, f64)> {
    for j in 0..SUBINTERVALS {
        let (ga, gb) = (gs[j][i], gs[j + 1][i]);
        if !*armed {
            if ga > 0.0 {
                *armed = true;
            } else {
                if gb > 0.0 {
                    *armed = true;
                    // Reset onto the surface and above it at the next
                    // sample: usually a departure. But a hop shorter than a
                    // sample interval (the last one before an impact
                    // accumulation: Θ' = 1.4e-5 after the impact, back on
                    // the surface 1e-4 τ later, in an interval of 1.9e-3)
                    // lands and dips behind the surface in between, and the
                    // samples then start far from linearly. Only then, look
                    // closer (see `landing_near_surface_time`).
                    if ga == 0.0
                        && j + 2 <= SUBINTERVALS
                        && gs[j + 2][i] > 3.0 * gb
                        && let Some(b) = landing_near_surface_time(ts[j], ts[j + 1], gs[j + 2][i], value)
                    {
                        return Some(b);
                    }
                    continue;
                }
                // Starts on the surface and is behind it at the next sample:
                // a bump above zero in between is a real departure and return
                // (grazing right after a reset). No bump is no event.
                if ga == 0.0 {
                    let (tm, gm) = brent_min(|tt| -value(tt), ts[j], ts[j + 1], 0.0, 100);
                    if -gm > 0.0 && tm < ts[j + 1] {
                        return Some((tm, ts[j + 1]));
                    }
                    // No bump, and behind the surface all through the step:
                    // the state left the new mode's side at once, so the
                    // mode was never right and its guard fires now (see
                    // `straight_behind_surface`).
                    if gs[j + 1..].iter().all(|g| g[i] < 0.0) && gs[SUBINTERVALS][i] < -BEHIND_FLOOR {
                        return Some(straight_behind_surface(ts[j], ts[j + 1], gb, value));
                    }
                }
                continue;
            }
        }
        if ga > 0.0 && gb <= 0.0 {
            return Some((ts[j], ts[j + 1]));
        }
        // Dip check on the parabola through samples j, j+1, j+2.
        if j + 2 <= SUBINTERVALS {
            let gc = gs[j + 2][i];
            if ga > 0.0 && gb > 0.0 && gc > 0.0 {
                let curv = ga - 2.0 * gb + gc;
                if curv > 0.0 {
                    // Vertex offset from sample j+1, in sample spacings.
                    let u = 0.5 * (ga - gc) / curv;
                    let gmin = gb - 0.125 * (ga - gc) * (ga - gc) / curv;
                    let lowest = ga.min(gb).min(gc);
                    if u.abs() < 1.0 && gmin < 0.1 * lowest {
                        let (tm, gm) = brent_min(&mut *value, ts[j], ts[j + 2], 0.0, 100);
                        if gm <= 0.0 {
                            return Some((ts[j], tm));
                        }
                    }
                }
            }
        }
    }
    None
}

/// The first landing of a guard that was reset onto its surface at `t0`,
/// is above it at `t1` and at `g_later` a sample later: offsets from `t0`
/// halving from `(t1 - t0)/2` down to the spacing of floats
/// ([`SURFACE_PROBES`] at most), then [`SURFACE_SCAN`] evenly spaced points
/// over `(t0, t1)`, give a bracket `(a, b)` with the guard above the
/// surface at `a` and clearly behind it at `b`, or `None`. Clearly
/// means below `-LANDING_DEPTH * g_later`: right after a reset the guard is
/// at round-off level, and a dip of that size is noise, not a landing (a
/// stick–slip reset would otherwise fire again and again at one instant).
/// Called only when `g_later > 3 g(t1)`, which a departure at a finite rate
/// (ratio about 2) does not give, but a short hop does, and a departure
/// from rest (ratio 4 to 8: uplifts, rare, and then nothing is found).
fn landing_near_surface_time<V: FnMut(f64) -> f64>(
    t0: f64,
    t1: f64,
    g_later: f64,
    value: &mut V,
) -> Option<(f64, f64)> {
    let depth = LANDING_DEPTH * g_later;
    let mut probes = [(0.0, 0.0); SURFACE_PROBES];
    let mut n = 0;
    let mut offset = 0.5 * (t1 - t0);
    while n < SURFACE_PROBES {
        let t = t0 + offset;
        if t <= t0 {
            break;
        }
        probes[n] = (t, value(t));
        n += 1;
        offset *= 0.5;
    }
    // The probes run backwards in time; the earliest landing wins.
    let near = probes[..n]
        .iter()
        .rev()
        .zip(probes[..n].iter().rev().skip(1))
        .find(|((_, ga), (_, gb))| *ga > 0.0 && *gb < -depth)
        .map(|((ta, _), (tb, _))| (*ta, *tb));
    if near.is_some() {
        return near;
    }
    // A hop that lands in the later half of the interval and leaves again
    // before its end is between the probes: look at evenly spaced points.
    let mut prev = (t0, 0.0);
    for k in 1..SURFACE_SCAN {
        let t = t0 + (t1 - t0) * (k as f64 / SURFACE_SCAN as f64);
        let g = value(t);
        if prev.1 > 0.0 && g < -depth {
            return Some((prev.0, t));
        }
        prev = (t, g);
    }
    None
}

/// The bracket of a guard that is exactly on its surface at `t0` (just
/// reset onto it) and behind it from then on, with no bump above it in
/// between (`g1` at `t1`, the first sample): `(t0, b)` with `b` the
/// earliest of the offsets halving from `t1 - t0` at which the guard is
/// still clearly behind the surface (deeper than [`LANDING_DEPTH`] of `g1`).
/// So the event falls soon after the reset, with the state hardly moved
/// behind the surface (for g ∝ −(τ − τ0)⁴, at 3 % of the sample interval
/// and 1e-6 of `g1`), yet late enough that what moved it there is no longer
/// at round-off level: at the reset itself the model resolves the new mode
/// from forces that are zero to round-off, and an event there would send
/// it back into the same mode, again and again.
///
/// Found by the extensive stress tier: a block at rest whose uplift moment
/// only touches zero (two-frequency forcing) is lifted at the tangency, and
/// then Θ ∝ −(τ − τ0)⁴: it never leaves its base. Without this the impact
/// guard, which starts on its surface, was never armed, and Θ went on
/// behind the pivot (−2.8e-6 at the end of the step). With it the block
/// lands at once (an impact at Θ' ≈ 0, so it is back at rest).
fn straight_behind_surface<V: FnMut(f64) -> f64>(t0: f64, t1: f64, g1: f64, value: &mut V) -> (f64, f64) {
    let depth = LANDING_DEPTH * g1.abs();
    let mut b = t1;
    let mut offset = 0.5 * (t1 - t0);
    for _ in 0..SURFACE_PROBES {
        let t = t0 + offset;
        if t <= t0 || value(t) >= -depth {
            break;
        }
        b = t;
        offset *= 0.5;
    }
    (t0, b)
}
