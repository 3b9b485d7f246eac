//! The largest exponent from two trajectories (Benettin et al. 1976),
//! renormalised only on the stroboscopic grid `t_k = k · period`.
//!
//! A perturbed copy of the system follows the fiducial trajectory. At each
//! grid time their distance `d_k` in tangent coordinates is measured,
//! `ln(d_k / d_start)` is added, and the perturbed state is pulled back to
//! distance `d0` along the current separation. The grid times are where
//! both copies are smooth: renormalising at arbitrary times near an impact
//! could put the copies on opposite sides of the jump and measure the jump
//! instead of the divergence.
//!
//! Rules, each for a reason:
//! - The perturbation is seeded half-way through the transient, so its
//!   direction has aligned with the most unstable one when accumulation
//!   starts; it is re-seeded whenever it is lost (below).
//! - At a grid time where the two copies are in different modes (one has
//!   just switched), nothing is renormalised; the growth is measured, over
//!   the longer interval, at the next grid time where the modes agree.
//! - If the perturbed copy ends (e.g. tumbles) but the fiducial does not,
//!   the growth since the last renormalisation is dropped (time and log
//!   alike) and the perturbation re-seeded.
//! - If the two copies become identical after the transient, every
//!   perturbation has died out in finite time (the caller reports it).

use super::tangent::{Perturbable, Quiet, TangentError};
use crate::integrate::hybrid::{Advance, Driver, Limits, Outputs};
use crate::integrate::{Dop853, Tolerances};

/// Euclidean distance.
pub(super) fn distance<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

/// What one grid time gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Step {
    /// Growth `ln(d_k/d_start)` measured over time `dt` (0 and 0 when
    /// nothing was measured at this grid time).
    Growth {
        /// Time the growth was measured over.
        dt: f64,
        /// Its natural log.
        log: f64,
    },
    /// The copies coincide: every perturbation died out.
    Collapsed,
}

/// The perturbed copy and its bookkeeping.
pub(super) struct Perturbed<S, const N: usize>
where
    S: crate::integrate::hybrid::HybridSystem<N>,
{
    driver: Driver<Dop853<N>, S, N>,
    d0: f64,
    d_start: f64,
    last_renorm: f64,
    active: bool,
}

impl<S, const N: usize> Perturbed<S, N>
where
    S: crate::integrate::hybrid::HybridSystem<N>,
{
    /// An inactive copy of `sys` with separation `d0`.
    pub(super) fn new(sys: S, mode0: S::Mode, y0: [f64; N], d0: f64, tol: Tolerances, limits: Limits) -> Self {
        let outputs = Outputs {
            sample_dt: None,
            section_period: None,
        };
        Self {
            driver: Driver::new(Dop853::<N>::new(tol), sys, mode0, 0.0, y0, limits, outputs),
            d0,
            d_start: d0,
            last_renorm: 0.0,
            active: false,
        }
    }

    /// Handles grid time `t_k`, where the fiducial is in `mode` at `y`.
    /// `sys` is the fiducial's system (for coordinates and displacements);
    /// growth is measured only over intervals that start at or after
    /// `t_start`; `seed` allows (re-)seeding at this grid time.
    pub(super) fn section<const D: usize>(
        &mut self,
        sys: &S,
        t_k: f64,
        mode: S::Mode,
        y: &[f64; N],
        t_start: f64,
        seed: bool,
    ) -> Result<Step, TangentError<S::Error>>
    where
        S: Perturbable<N, D>,
    {
        let z = sys.coords(y);
        let mut step = Step::Growth { dt: 0.0, log: 0.0 };
        if self.active {
            let ended = self.driver.advance(t_k, &mut Quiet).map_err(TangentError::System)? == Advance::Terminal;
            if ended {
                self.active = false;
            } else if self.driver.mode() == mode {
                let zp = sys.coords(self.driver.y());
                let d = distance(&z, &zp);
                if d == 0.0 {
                    self.active = false;
                    if t_k > t_start {
                        return Ok(Step::Collapsed);
                    }
                } else {
                    if self.last_renorm >= t_start {
                        step = Step::Growth {
                            dt: t_k - self.last_renorm,
                            log: (d / self.d_start).ln(),
                        };
                    }
                    let scale = self.d0 / d;
                    let dz: [f64; D] = std::array::from_fn(|i| (zp[i] - z[i]) * scale);
                    self.place(sys, t_k, mode, y, &dz);
                }
            }
        }
        if !self.active && seed {
            let dz = [self.d0 / (D as f64).sqrt(); D];
            self.place(sys, t_k, mode, y, &dz);
        }
        Ok(step)
    }

    /// Puts the copy at `dz` from `y` (or at `−dz` if `dz` leaves the
    /// mode's domain); inactive if neither is admissible.
    fn place<const D: usize>(&mut self, sys: &S, t: f64, mode: S::Mode, y: &[f64; N], dz: &[f64; D])
    where
        S: Perturbable<N, D>,
    {
        let z = sys.coords(y);
        let neg = dz.map(|v| -v);
        let placed = [*dz, neg].into_iter().find_map(|d| {
            let yp = sys.displaced(mode, t, y, &d)?;
            let dist = distance(&z, &sys.coords(&yp));
            (dist > 0.0).then_some((yp, dist))
        });
        match placed {
            Some((yp, dist)) => {
                self.driver.reinit(mode, t, yp);
                self.d_start = dist;
                self.last_renorm = t;
                self.active = true;
            }
            None => self.active = false,
        }
    }
}
