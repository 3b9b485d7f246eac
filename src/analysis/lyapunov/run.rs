//! The renormalisation loop shared by both methods.
//!
//! One fiducial trajectory is integrated to each grid time `t_k = k ·
//! period`. With tangent dynamics the fiducial carries its tangent vectors
//! (the augmented system of `tangent.rs`), which are re-orthonormalised
//! there; with the two-trajectory method a perturbed copy is measured and
//! pulled back there (`benettin.rs`). Asked for both, the two estimates
//! come from the **same** fiducial trajectory: their difference then
//! measures the methods, not the luck of which part of the attractor (or
//! which of coexisting attractors) each run visited.

use super::batch::{Accumulator, Estimate};
use super::benettin::{Perturbed, Step};
use super::qr;
use super::tangent::{Augmented, Perturbable, Quiet, TangentError, TangentSystem};
use crate::integrate::hybrid::{Advance, Driver, Limits, Observer, Outputs};
use crate::integrate::{Dop853, Tolerances};
use nalgebra::{Const, DimMin};

/// When to renormalise and what to keep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Renormalisation interval (the forcing period for a forced system),
    /// in the system's time unit; renormalisation times are `k · period`.
    pub period: f64,
    /// Intervals skipped before accumulating (transient; the tangent
    /// vectors and the perturbation align with the Oseledets directions
    /// meanwhile).
    pub transient: u64,
    /// Last interval: the run ends at `total · period`.
    pub total: u64,
    /// Batches for the error estimate.
    pub batches: usize,
}

impl Schedule {
    /// Intervals accumulated.
    pub fn intervals(&self) -> u64 {
        self.total.saturating_sub(self.transient)
    }
}

/// Which estimates to compute.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Request {
    /// Tangent dynamics (the whole spectrum).
    pub tangent: bool,
    /// Two trajectories with this separation (the largest exponent).
    pub separation: Option<f64>,
}

/// How a Lyapunov computation ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome<M, const D: usize> {
    /// The accumulation window was completed.
    Estimate {
        /// Tangent dynamics: all `D` exponents (only the first `min_dim`
        /// are finite exponents).
        tangent: Option<Estimate<D>>,
        /// Two trajectories: the largest exponent.
        benettin: Option<Estimate<1>>,
        /// Fewest tangent directions alive in the window: exponents beyond
        /// this index are −∞.
        min_dim: usize,
        /// Mode at the end of the window.
        final_mode: M,
    },
    /// The system entered a terminal mode at `t`.
    Terminal {
        /// The terminal mode.
        mode: M,
        /// When.
        t: f64,
    },
    /// The two trajectories became identical (every perturbation died out
    /// in finite time) at `t`.
    Collapsed {
        /// When.
        t: f64,
    },
}

/// Watches the modes left at events after a time, for the fewest tangent
/// directions a plain (untangented) trajectory had.
struct ModeWatch<F> {
    from: f64,
    min_dim: usize,
    dim: F,
}

impl<M, R, F: Fn(M) -> usize, const N: usize> Observer<M, R, N> for ModeWatch<F> {
    fn sample(&mut self, _t: f64, _mode: M, _y: &[f64; N]) {}
    fn section(&mut self, _k: u64, _t: f64, _mode: M, _y: &[f64; N]) {}
    fn event(&mut self, t: f64, before: M, _y_before: &[f64; N], _record: R) {
        if t >= self.from {
            self.min_dim = self.min_dim.min((self.dim)(before));
        }
    }
}

/// Measures the perturbed copy at grid time `t_k` (the fiducial `sys` in
/// `mode` at `y`) and adds the growth to `acc` when accumulating; `true`
/// when the copies have become identical.
#[allow(clippy::too_many_arguments)]
fn measure<S, const N: usize, const D: usize>(
    p: &mut Perturbed<S, N>,
    sys: &S,
    t_k: f64,
    mode: S::Mode,
    y: &[f64; N],
    t_start: f64,
    seed: bool,
    acc: Option<&mut Accumulator<1>>,
) -> Result<bool, TangentError<S::Error>>
where
    S: Perturbable<N, D>,
{
    match p.section::<D>(sys, t_k, mode, y, t_start, seed)? {
        Step::Collapsed => Ok(true),
        Step::Growth { dt, log } => {
            if let Some(acc) = acc {
                acc.push(t_k, dt, &[log]);
            }
            Ok(false)
        }
    }
}

/// The largest Lyapunov exponent of `sys` from `(0, y0)` in `mode0`, per
/// unit time, by two trajectories `separation` apart (`benettin.rs`),
/// renormalised and accumulated as `schedule` says. It needs no Jacobian:
/// this is the estimate of a model whose tangent equations are not
/// written. The outcome's `tangent` is `None`.
pub fn two_trajectories<S, const N: usize, const D: usize>(
    sys: S,
    mode0: S::Mode,
    y0: [f64; N],
    schedule: &Schedule,
    tol: Tolerances,
    limits: Limits,
    separation: f64,
) -> Result<Outcome<S::Mode, D>, TangentError<S::Error>>
where
    S: Perturbable<N, D> + Clone,
{
    let period = schedule.period;
    let outputs = Outputs {
        sample_dt: None,
        section_period: None,
    };
    let dims = sys.clone();
    let mut watch = ModeWatch {
        from: f64::INFINITY,
        min_dim: D,
        dim: |m| dims.tangent_dim(m),
    };
    let mut perturbed = Perturbed::new(sys.clone(), mode0, y0, separation, tol, limits);
    let mut fiducial = Driver::new(Dop853::<N>::new(tol), sys, mode0, 0.0, y0, limits, outputs);
    let t_start = schedule.transient as f64 * period;
    let mut acc = Accumulator::<1>::new(schedule.intervals(), schedule.batches, t_start);
    let seed_at = schedule.transient / 2;
    for k in 0..=schedule.total {
        let t_k = k as f64 * period;
        let advance = fiducial.advance(t_k, &mut watch).map_err(TangentError::System)?;
        let (mode, y, t) = (fiducial.mode(), *fiducial.y(), fiducial.t());
        if advance == Advance::Terminal {
            return Ok(Outcome::Terminal { mode, t });
        }
        let accumulating = k > schedule.transient;
        if k == schedule.transient {
            watch.from = t_k;
            watch.min_dim = dims.tangent_dim(mode).min(D);
        }
        if k >= schedule.transient {
            watch.min_dim = watch.min_dim.min(dims.tangent_dim(mode));
        }
        let acc_now = accumulating.then_some(&mut acc);
        if measure::<S, N, D>(
            &mut perturbed,
            fiducial.system(),
            t_k,
            mode,
            &y,
            t_start,
            k >= seed_at,
            acc_now,
        )? {
            return Ok(Outcome::Collapsed { t: t_k });
        }
    }
    Ok(Outcome::Estimate {
        tangent: None,
        benettin: Some(acc.estimate()),
        min_dim: watch.min_dim,
        final_mode: fiducial.mode(),
    })
}

/// Lyapunov exponents of `sys` from `(0, y0)` in `mode0`, per unit time:
/// by tangent dynamics and/or two trajectories as `request` says, with
/// renormalisation and accumulation as `schedule` says. `NA` must be
/// `N + D·D` (checked at compile time). The bound on `D` is the QR's
/// (it holds for every `D` up to 127).
pub fn exponents<S, const N: usize, const D: usize, const NA: usize>(
    sys: S,
    mode0: S::Mode,
    y0: [f64; N],
    schedule: &Schedule,
    tol: Tolerances,
    limits: Limits,
    request: Request,
) -> Result<Outcome<S::Mode, D>, TangentError<S::Error>>
where
    S: TangentSystem<N, D> + Clone,
    Const<D>: DimMin<Const<D>, Output = Const<D>>,
{
    if !request.tangent {
        return match request.separation {
            Some(d0) => two_trajectories::<S, N, D>(sys, mode0, y0, schedule, tol, limits, d0),
            None => Ok(Outcome::Estimate {
                tangent: None,
                benettin: None,
                min_dim: D,
                final_mode: mode0,
            }),
        };
    }
    let period = schedule.period;
    let outputs = Outputs {
        sample_dt: None,
        section_period: None,
    };
    let dims = sys.clone();
    let mut min_dim = D;
    let mut perturbed = request
        .separation
        .map(|d0| Perturbed::new(sys.clone(), mode0, y0, d0, tol, limits));
    let aug = Augmented::<S, N, D, NA>::new(sys);
    let ya0 = Augmented::<S, N, D, NA>::pack(&y0, &qr::Matrix::identity());
    let mut fiducial = Driver::new(Dop853::<NA>::new(tol), aug, mode0, 0.0, ya0, limits, outputs);
    let t_start = schedule.transient as f64 * period;
    let mut acc_tangent = Accumulator::<D>::new(schedule.intervals(), schedule.batches, t_start);
    let mut acc_benettin = request
        .separation
        .map(|_| Accumulator::<1>::new(schedule.intervals(), schedule.batches, t_start));
    let seed_at = schedule.transient / 2;

    for k in 0..=schedule.total {
        let t_k = k as f64 * period;
        let advance = fiducial.advance(t_k, &mut Quiet)?;
        let (mode, y, t) = (
            fiducial.mode(),
            Augmented::<S, N, D, NA>::unpack(fiducial.y()).0,
            fiducial.t(),
        );
        if advance == Advance::Terminal {
            return Ok(Outcome::Terminal { mode, t });
        }
        let accumulating = k > schedule.transient;
        if k == schedule.transient {
            min_dim = dims.tangent_dim(mode).min(D);
            fiducial.system_mut().track_from(t_k, mode);
        }
        if k >= schedule.transient {
            min_dim = min_dim.min(dims.tangent_dim(mode));
        }
        if k > 0 {
            let (_, phi) = Augmented::<S, N, D, NA>::unpack(fiducial.y());
            let (q, r) = qr::qr_matrix(&phi);
            if q.iter().chain(r.iter()).any(|v| !v.is_finite()) {
                return Err(TangentError::NonFinite { t: t_k });
            }
            if accumulating {
                // An annihilated direction gives R_ii = 0 exactly; it lies
                // beyond `min_dim` and is not reported, but its sum must
                // stay finite.
                let logs: [f64; D] = std::array::from_fn(|i| r[i].max(f64::MIN_POSITIVE).ln());
                acc_tangent.push(t_k, period, &logs);
            }
            fiducial.reinit(mode, t_k, Augmented::<S, N, D, NA>::pack(&y, &q));
        }
        if let Some(p) = perturbed.as_mut() {
            let acc_now = acc_benettin.as_mut().filter(|_| accumulating);
            let fid_sys = &fiducial.system().inner;
            if measure::<S, N, D>(p, fid_sys, t_k, mode, &y, t_start, k >= seed_at, acc_now)? {
                return Ok(Outcome::Collapsed { t: t_k });
            }
        }
    }
    Ok(Outcome::Estimate {
        tangent: Some(acc_tangent.estimate()),
        benettin: acc_benettin.map(|a| a.estimate()),
        min_dim: fiducial.system().min_dim().min(min_dim),
        final_mode: fiducial.mode(),
    })
}
