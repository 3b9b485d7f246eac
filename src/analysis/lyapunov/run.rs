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
use super::tangent::{Augmented, Quiet, TangentError, TangentSystem};
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

/// The fiducial trajectory, with or without tangent vectors.
enum Fiducial<S, const N: usize, const D: usize, const NA: usize>
where
    S: TangentSystem<N, D>,
{
    Plain(Driver<Dop853<N>, S, N>),
    Tangent(Driver<Dop853<NA>, Augmented<S, N, D, NA>, NA>),
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
    let mut perturbed = request
        .separation
        .map(|d0| Perturbed::new(sys.clone(), mode0, y0, d0, tol, limits));
    let mut fiducial = if request.tangent {
        let aug = Augmented::<S, N, D, NA>::new(sys);
        let ya0 = Augmented::<S, N, D, NA>::pack(&y0, &qr::Matrix::identity());
        Fiducial::Tangent(Driver::new(
            Dop853::<NA>::new(tol),
            aug,
            mode0,
            0.0,
            ya0,
            limits,
            outputs,
        ))
    } else {
        Fiducial::Plain(Driver::new(Dop853::<N>::new(tol), sys, mode0, 0.0, y0, limits, outputs))
    };
    let t_start = schedule.transient as f64 * period;
    let mut acc_tangent = request
        .tangent
        .then(|| Accumulator::<D>::new(schedule.intervals(), schedule.batches, t_start));
    let mut acc_benettin = request
        .separation
        .map(|_| Accumulator::<1>::new(schedule.intervals(), schedule.batches, t_start));
    let seed_at = schedule.transient / 2;

    for k in 0..=schedule.total {
        let t_k = k as f64 * period;
        let advance = match &mut fiducial {
            Fiducial::Plain(d) => d.advance(t_k, &mut watch).map_err(TangentError::System)?,
            Fiducial::Tangent(d) => d.advance(t_k, &mut Quiet)?,
        };
        let (mode, y, t) = match &fiducial {
            Fiducial::Plain(d) => (d.mode(), *d.y(), d.t()),
            Fiducial::Tangent(d) => (d.mode(), Augmented::<S, N, D, NA>::unpack(d.y()).0, d.t()),
        };
        if advance == Advance::Terminal {
            return Ok(Outcome::Terminal { mode, t });
        }
        let accumulating = k > schedule.transient;
        if k == schedule.transient {
            watch.from = t_k;
            watch.min_dim = dims.tangent_dim(mode).min(D);
            if let Fiducial::Tangent(d) = &mut fiducial {
                d.system_mut().track_from(t_k, mode);
            }
        }
        if k >= schedule.transient {
            watch.min_dim = watch.min_dim.min(dims.tangent_dim(mode));
        }
        if let Fiducial::Tangent(d) = &mut fiducial
            && k > 0
        {
            let (_, phi) = Augmented::<S, N, D, NA>::unpack(d.y());
            let (q, r) = qr::qr_matrix(&phi);
            if q.iter().chain(r.iter()).any(|v| !v.is_finite()) {
                return Err(TangentError::NonFinite { t: t_k });
            }
            if accumulating && let Some(acc) = acc_tangent.as_mut() {
                // An annihilated direction gives R_ii = 0 exactly; it lies
                // beyond `min_dim` and is not reported, but its sum must
                // stay finite.
                let logs: [f64; D] = std::array::from_fn(|i| r[i].max(f64::MIN_POSITIVE).ln());
                acc.push(t_k, period, &logs);
            }
            d.reinit(mode, t_k, Augmented::<S, N, D, NA>::pack(&y, &q));
        }
        if let Some(p) = perturbed.as_mut() {
            let fid_sys: &S = match &fiducial {
                Fiducial::Plain(d) => d.system(),
                Fiducial::Tangent(d) => &d.system().inner,
            };
            match p.section::<D>(fid_sys, t_k, mode, &y, t_start, k >= seed_at)? {
                Step::Collapsed => return Ok(Outcome::Collapsed { t: t_k }),
                Step::Growth { dt, log } => {
                    if accumulating && let Some(acc) = acc_benettin.as_mut() {
                        acc.push(t_k, dt, &[log]);
                    }
                }
            }
        }
    }
    let (min_dim, final_mode) = match &fiducial {
        Fiducial::Plain(d) => (watch.min_dim, d.mode()),
        Fiducial::Tangent(d) => (d.system().min_dim().min(watch.min_dim), d.mode()),
    };
    Ok(Outcome::Estimate {
        tangent: acc_tangent.map(|a| a.estimate()),
        benettin: acc_benettin.map(|a| a.estimate()),
        min_dim,
        final_mode,
    })
}
