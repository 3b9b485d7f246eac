//! The paper's event location for its fixed-step method: a step that
//! crosses a guard is undone and retried with a step ten times smaller
//! until the guard is within [`PAPER_GUARD_TOL`] of zero.

use super::{Driver, DriverError, Field, HybridSystem, MAX_GUARDS, Observer};
use crate::integrate::stepper::Stepper;

/// Guard tolerance of the paper's step-cutting event location (`|Θ| < 1e-6`).
pub const PAPER_GUARD_TOL: f64 = 1e-6;

/// Smallest step the paper's step cutting may reach before it accepts the
/// crossing anyway.
const PAPER_MIN_STEP: f64 = 1e-13;

impl<S, Sys, const N: usize> Driver<S, Sys, N>
where
    S: Stepper<N>,
    Sys: HybridSystem<N>,
{
    /// One step of the paper's fixed-step method, with events located by
    /// undoing the step and retrying with a step ten times smaller.
    pub(super) fn cutting_step<O>(&mut self, t_stop: f64, obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        let mode = self.mode;
        let n = self.n_guards;
        let mut g1 = [0.0; MAX_GUARDS];
        loop {
            let sys = &self.system;
            let f = Field { sys, mode };
            self.stepper.step(&f, t_stop).map_err(DriverError::from)?;
            self.steps += 1;
            let t1 = self.stepper.t();
            let y1 = *self.stepper.y();
            sys.guards(mode, t1, &y1, &mut g1);
            // A guard that started on its surface (g = 0, just reset) and
            // ends the step behind it went out and back within the step: a
            // crossing too (after an impact with a tiny Θ', the block can
            // lift and fall back inside one fixed step).
            let crossing = (0..n).find(|&i| {
                !sys.is_observer(mode, i)
                    && ((self.armed[i] && g1[i] <= 0.0) || (self.g_start[i] == 0.0 && g1[i] < 0.0))
            });
            match crossing {
                Some(i) if g1[i].abs() >= PAPER_GUARD_TOL && self.stepper.step_size() > PAPER_MIN_STEP => {
                    if !self.stepper.undo_and_shrink(10.0) {
                        // A stepper that cannot undo: accept the crossing here.
                        return self.finish_cutting(i, t1, y1, obs);
                    }
                }
                Some(i) => return self.finish_cutting(i, t1, y1, obs),
                None => {
                    for (i, &gi) in g1.iter().enumerate().take(n) {
                        if self.system.is_observer(mode, i) && self.armed[i] && gi <= 0.0 {
                            self.system.observe(mode, i, t1, &y1);
                        }
                        if gi > 0.0 {
                            self.armed[i] = true;
                        } else if self.system.is_observer(mode, i) {
                            self.armed[i] = false;
                        }
                    }
                    self.g_start = g1;
                    self.emit_samples_dense(t1, obs);
                    self.emit_section_if_hit(t1, obs);
                    return Ok(());
                }
            }
        }
    }

    fn finish_cutting<O>(&mut self, i: usize, t1: f64, y1: [f64; N], obs: &mut O) -> Result<(), Sys::Error>
    where
        O: Observer<Sys::Mode, Sys::Record, N>,
    {
        self.emit_samples_dense(t1, obs);
        self.stepper.reset_step_size();
        self.apply_jump(i, t1, y1, obs)
    }
}
