//! Outputs: regular samples and section points, from the dense output of
//! the step that contains them, from a constant state across a closed-form
//! skip, or at the current time.

use super::{Driver, Field, HybridSystem, Observer};
use crate::integrate::stepper::Stepper;

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
        let mut y = [0.0; N];
        loop {
            let ts = self.next_sample as f64 * dt;
            if ts > t_to {
                break;
            }
            self.dense_state(ts, &mut y);
            obs.sample(ts, self.mode, &y);
            self.next_sample += 1;
        }
    }

    /// The state at `ts` in the last step into `y`: the step's end state bit
    /// for bit at its end, else its dense output.
    #[inline]
    fn dense_state(&mut self, ts: f64, y: &mut [f64; N]) {
        if ts == self.stepper.t() {
            *y = *self.stepper.y();
        } else {
            let f = Field {
                sys: &self.system,
                mode: self.mode,
            };
            self.stepper.dense(&f, ts, y);
        }
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
        let mut y = [0.0; N];
        loop {
            let ts = self.next_section as f64 * p;
            if ts > t_to || (ts == t_to && !inclusive) {
                break;
            }
            self.dense_state(ts, &mut y);
            obs.section(self.next_section, ts, self.mode, &y);
            self.next_section += 1;
        }
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
