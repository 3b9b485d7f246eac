//! Outputs: regular samples and section points, from the dense output of
//! the step that contains them, from a constant state across a closed-form
//! skip, or at the current time.

use super::{Driver, Field, HybridSystem, Observer};
use crate::integrate::stepper::{Rhs, Stepper};

impl<S, Sys, const N: usize> Driver<S, Sys, N>
where
    S: Stepper<N>,
    Sys: HybridSystem<N>,
{
    /// Regular samples up to and including `t_to`, from the last step's
    /// dense output.
    pub(super) fn emit_samples_dense<O>(&mut self, t_to: f64, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(dt) = self.outputs.sample_dt else {
            return;
        };
        let mode = self.mode;
        let f = Field {
            sys: &self.system,
            mode,
        };
        let due = |ts: f64| ts <= t_to;
        dense_outputs(&mut self.stepper, &f, dt, &mut self.next_sample, due, |_, ts, y| {
            obs.sample(ts, mode, y)
        });
    }

    /// Section points in the last step up to `t_to` (included if
    /// `inclusive`), from its dense output; the step's end state bit for bit
    /// at its end. The dense output of DOP853 is of the method's accuracy
    /// (Hairer–Nørsett–Wanner II.6), so the points agree with stepping onto
    /// the section times to the tolerance (tested in `section_points_from_
    /// dense_output_match_stepping_onto_them`).
    pub(super) fn emit_sections_dense<O>(&mut self, t_to: f64, inclusive: bool, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(p) = self.outputs.section_period else {
            return;
        };
        let mode = self.mode;
        let f = Field {
            sys: &self.system,
            mode,
        };
        let due = |ts: f64| ts < t_to || (ts == t_to && inclusive);
        dense_outputs(&mut self.stepper, &f, p, &mut self.next_section, due, |k, ts, y| {
            obs.section(k, ts, mode, y)
        });
    }

    /// Outputs due exactly at the current time (the start of a run).
    pub(super) fn emit_current<O>(&mut self, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let t = self.stepper.t();
        let y = *self.stepper.y();
        if let Some(dt) = self.outputs.sample_dt
            && self.next_sample as f64 * dt == t
        {
            obs.sample(t, self.mode, &y);
            self.next_sample += 1;
        }
        self.emit_section_if_hit(t, obs);
    }

    /// Samples and section points in `(t_from, t_to)` of a constant state.
    pub(super) fn emit_constant<O>(&mut self, _t_from: f64, t_to: f64, y: &[f64; N], obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        if let Some(dt) = self.outputs.sample_dt {
            while (self.next_sample as f64 * dt) < t_to {
                obs.sample(self.next_sample as f64 * dt, self.mode, y);
                self.next_sample += 1;
            }
        }
        if let Some(p) = self.outputs.section_period {
            while (self.next_section as f64 * p) < t_to {
                obs.section(self.next_section, self.next_section as f64 * p, self.mode, y);
                self.next_section += 1;
            }
        }
    }

    /// Reports the section point if the current time is the next section time.
    pub(super) fn emit_section_if_hit<O>(&mut self, t: f64, obs: &mut O)
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let Some(p) = self.outputs.section_period else {
            return;
        };
        let ts = self.next_section as f64 * p;
        if ts == t {
            let y = *self.stepper.y();
            obs.section(self.next_section, t, self.mode, &y);
            self.next_section += 1;
        } else if ts < t {
            // Only reachable if a jump moved time past a section time; those
            // points were emitted by `emit_constant`.
            while (self.next_section as f64 * p) < t {
                self.next_section += 1;
            }
        }
    }
}

/// Hands `emit` each output time `k·dt` that is `due`, `k` counting on
/// from `*next`, in the step the stepper just took, with the state there:
/// the step's end state bit for bit at its end, its dense output inside.
#[inline(always)]
fn dense_outputs<S: Stepper<N>, F: Rhs<N>, const N: usize>(
    stepper: &mut S,
    f: &F,
    dt: f64,
    next: &mut u64,
    due: impl Fn(f64) -> bool,
    mut emit: impl FnMut(u64, f64, &[f64; N]),
) {
    let t_end = stepper.t();
    let mut y = [0.0; N];
    loop {
        let ts = *next as f64 * dt;
        if !due(ts) {
            break;
        }
        if ts == t_end {
            y = *stepper.y();
        } else {
            stepper.dense(f, ts, &mut y);
        }
        emit(*next, ts, &y);
        *next += 1;
    }
}
