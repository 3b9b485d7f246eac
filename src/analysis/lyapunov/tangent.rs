//! Tangent dynamics of a hybrid system: the variational equations
//! integrated with the state, saltation matrices at every event, and QR
//! renormalisation on a fixed grid (Müller 1995; Leine & Nijmeijer 2004).
//!
//! Between events the tangent vectors (the columns of Φ) obey `Φ' = J Φ`.
//! At an event of guard `g` with reset `R`, crossed at `(t, y⁻)`:
//!
//! `S = J_R + (f⁺ − J_R f⁻) n_yᵀ / (n_y·f⁻ + ∂g/∂t)`,  `Φ⁺ = S Φ⁻`,
//!
//! where `J_R` is the Jacobian of the reset, `f⁻`, `f⁺` the vector fields
//! before and after (the latter at the post-reset state and time), and
//! `n_y` the guard's state gradient. The term in `∂g/∂t` makes the formula
//! hold for a non-autonomous guard (the denominator is `dg/dt` along the
//! flow). For a guard that depends on time alone (`n_y = 0`) the event time
//! does not move with the state and `S = J_R`.
//!
//! The generic machinery is written against [`TangentSystem`]; the block
//! implements it in `block.rs`, the tests on small systems with known
//! exponents. The renormalisation loop is in `run.rs`.
//!
//! The interface speaks arrays ([`Square`], `[f64; D]`: what
//! `model::variational` builds the block's matrices as); the machinery
//! converts them to nalgebra's fixed-size [`Matrix`] and [`Vector`] where
//! they enter, and computes with those.

use super::qr::{self, Matrix, Square, Vector};
use crate::integrate::hybrid::{DriverError, HybridSystem, Jump, MAX_GUARDS, Observer};

/// What the two-trajectory estimate needs beyond a [`HybridSystem`]:
/// tangent coordinates (`D` of them), how many of them a mode leaves free,
/// and a way to displace a state along them. No Jacobian: a model whose
/// tangent equations are not written (a stack, a frame) still has its
/// largest exponent this way.
pub trait Perturbable<const N: usize, const D: usize>: HybridSystem<N> {
    /// Tangent coordinates of a state, or of a rate of change of one (the
    /// map must be linear).
    fn coords(&self, y: &[f64; N]) -> [f64; D];

    /// Number of free tangent directions in `mode` (fewer than `D` where
    /// the mode constrains part of the state).
    fn tangent_dim(&self, mode: Self::Mode) -> usize;

    /// A state of `mode` displaced from `y` by about `dz` in tangent
    /// coordinates and consistent with the mode's constraints, or `None`
    /// if the displacement leaves the mode's domain (for the two-trajectory method).
    fn displaced(&self, mode: Self::Mode, t: f64, y: &[f64; N], dz: &[f64; D]) -> Option<[f64; N]>;
}

/// What the tangent dynamics need beyond [`Perturbable`]: the Jacobians,
/// guard gradients and reset Jacobians in tangent coordinates.
pub trait TangentSystem<const N: usize, const D: usize>: Perturbable<N, D> {
    /// Jacobian of `mode`'s vector field in tangent coordinates.
    fn jacobian(&self, mode: Self::Mode, t: f64, y: &[f64; N]) -> Square<D>;

    /// Gradient of guard `index` of `mode`: `(∂g/∂z, ∂g/∂t)`, `None` if the
    /// system has none for that guard.
    fn guard_gradient(&self, mode: Self::Mode, index: usize, t: f64, y: &[f64; N]) -> Option<([f64; D], f64)>;

    /// Jacobian of the reset of guard `index` of `before` at `y_before`,
    /// which ended in `after` at `y_after`, and the number of directions
    /// that survive the event (the rank of its saltation matrix).
    fn reset_jacobian(
        &self,
        before: Self::Mode,
        index: usize,
        y_before: &[f64; N],
        after: Self::Mode,
        y_after: &[f64; N],
    ) -> (Square<D>, usize);
}

/// Errors of the tangent and two-trajectory computations.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum TangentError<E> {
    /// The system (or its driver) failed.
    #[error("{0}")]
    System(E),
    /// The driver failed.
    #[error(transparent)]
    Driver(#[from] DriverError),
    /// The trajectory crossed a guard tangentially (`dg/dt = 0`), where the
    /// saltation matrix is unbounded.
    #[error("grazing event at t = {t}: the saltation matrix is unbounded")]
    Grazing {
        /// Time of the event.
        t: f64,
    },
    /// The system gave no gradient for a guard that fired.
    #[error("no guard gradient for guard {index} at t = {t}")]
    NoGradient {
        /// Guard index.
        index: usize,
        /// Time of the event.
        t: f64,
    },
    /// The tangent vectors became non-finite.
    #[error("non-finite tangent vectors at t = {t}")]
    NonFinite {
        /// Time.
        t: f64,
    },
}

/// The system with its tangent vectors appended to the state:
/// `[y (N), Φ (D×D, row-major)]`, `NA = N + D·D`. Row-major although
/// nalgebra stores column-major: the integrator's error norm sums the
/// components in state order, so this order keeps its step sizes (and the
/// results) those of the array-based code it replaced.
#[derive(Clone, Debug)]
pub struct Augmented<S, const N: usize, const D: usize, const NA: usize> {
    /// The system.
    pub inner: S,
    /// Events at `t >= track_from` lower [`min_dim`](Self::min_dim).
    track_from: f64,
    /// Fewest tangent directions alive since `track_from`.
    min_dim: usize,
}

impl<S, const N: usize, const D: usize, const NA: usize> Augmented<S, N, D, NA>
where
    S: TangentSystem<N, D>,
{
    /// Wraps `inner`.
    pub fn new(inner: S) -> Self {
        const { assert!(NA == N + D * D, "NA must be N + D·D") };
        Self {
            inner,
            track_from: f64::INFINITY,
            min_dim: D,
        }
    }

    /// Starts counting surviving directions at `t`, in `mode`.
    pub(crate) fn track_from(&mut self, t: f64, mode: S::Mode) {
        self.track_from = t;
        self.min_dim = self.inner.tangent_dim(mode).min(D);
    }

    /// Fewest tangent directions alive since tracking started: exponents
    /// beyond it are −∞ (annihilated in finite time).
    pub fn min_dim(&self) -> usize {
        self.min_dim
    }

    /// The augmented state of `y` with tangent vectors `phi`.
    pub fn pack(y: &[f64; N], phi: &Matrix<D>) -> [f64; NA] {
        let mut out = [0.0; NA];
        out[..N].copy_from_slice(y);
        Self::put_phi(phi, &mut out);
        out
    }

    /// The state and tangent vectors of an augmented state.
    pub fn unpack(ya: &[f64; NA]) -> ([f64; N], Matrix<D>) {
        (Self::state(ya), Self::phi(ya))
    }

    /// Φ, stored row-major after the state.
    fn phi(ya: &[f64; NA]) -> Matrix<D> {
        Matrix::from_row_slice(&ya[N..])
    }

    /// Stores `phi` row-major after the state.
    fn put_phi(phi: &Matrix<D>, ya: &mut [f64; NA]) {
        // The column-major storage of Φᵀ is Φ row-major.
        ya[N..].copy_from_slice(phi.transpose().as_slice());
    }

    fn state(ya: &[f64; NA]) -> [f64; N] {
        let mut y = [0.0; N];
        y.copy_from_slice(&ya[..N]);
        y
    }

    /// The saltation matrix of the event just handled by `jump`.
    fn saltation(
        &self,
        before: S::Mode,
        index: usize,
        t: f64,
        y: &[f64; N],
        jump: &Jump<S::Mode, S::Record, N>,
    ) -> Result<(Matrix<D>, usize), TangentError<S::Error>> {
        if self.inner.is_terminal(jump.mode) {
            // The run ends here; the tangent vectors are not used again.
            return Ok((Matrix::zeros(), 0));
        }
        let (jr, dim) = self.inner.reset_jacobian(before, index, y, jump.mode, &jump.y);
        let jr = qr::matrix(&jr);
        let (n, g_t) = self
            .inner
            .guard_gradient(before, index, t, y)
            .ok_or(TangentError::NoGradient { index, t })?;
        let n = Vector::from(n);
        if n.iter().all(|&v| v == 0.0) {
            return Ok((jr, dim));
        }
        let mut rate = [0.0; N];
        self.inner.rhs(before, t, y, &mut rate);
        let f_before = Vector::from(self.inner.coords(&rate));
        self.inner.rhs(jump.mode, jump.t, &jump.y, &mut rate);
        let f_after = Vector::from(self.inner.coords(&rate));
        let den = n.dot(&f_before) + g_t;
        if den == 0.0 || !den.is_finite() {
            return Err(TangentError::Grazing { t });
        }
        // Divided before the outer product, as `c nᵀ` with `c = (f⁺ − J_R f⁻)/den`:
        // the same roundings as the array code this replaced.
        let c = (f_after - jr * f_before) / den;
        let s = jr + c * n.transpose();
        if s.iter().any(|v| !v.is_finite()) {
            return Err(TangentError::Grazing { t });
        }
        Ok((s, dim))
    }
}

impl<S, const N: usize, const D: usize, const NA: usize> HybridSystem<NA> for Augmented<S, N, D, NA>
where
    S: TangentSystem<N, D>,
{
    type Mode = S::Mode;
    type Record = S::Record;
    type Error = TangentError<S::Error>;

    fn rhs(&self, mode: S::Mode, t: f64, ya: &[f64; NA], dya: &mut [f64; NA]) {
        let y = Self::state(ya);
        let mut dy = [0.0; N];
        self.inner.rhs(mode, t, &y, &mut dy);
        dya[..N].copy_from_slice(&dy);
        let j = qr::matrix(&self.inner.jacobian(mode, t, &y));
        Self::put_phi(&(j * Self::phi(ya)), dya);
    }

    fn guards(&self, mode: S::Mode, t: f64, ya: &[f64; NA], g: &mut [f64; MAX_GUARDS]) -> usize {
        self.inner.guards(mode, t, &Self::state(ya), g)
    }

    fn is_observer(&self, mode: S::Mode, index: usize) -> bool {
        self.inner.is_observer(mode, index)
    }

    fn observe(&mut self, mode: S::Mode, index: usize, t: f64, ya: &[f64; NA]) {
        self.inner.observe(mode, index, t, &Self::state(ya));
    }

    fn jump(
        &mut self,
        mode: S::Mode,
        index: usize,
        t: f64,
        ya: &[f64; NA],
    ) -> Result<Jump<S::Mode, S::Record, NA>, Self::Error> {
        let (y, phi) = Self::unpack(ya);
        let jump = self.inner.jump(mode, index, t, &y).map_err(TangentError::System)?;
        let (s, dim) = self.saltation(mode, index, t, &y, &jump)?;
        if t >= self.track_from {
            let dims = self.inner.tangent_dim(mode).min(self.inner.tangent_dim(jump.mode));
            self.min_dim = self.min_dim.min(dim).min(dims);
        }
        let phi_after = s * phi;
        Ok(Jump {
            mode: jump.mode,
            t: jump.t,
            y: Self::pack(&jump.y, &phi_after),
            records: jump.records,
        })
    }

    fn is_terminal(&self, mode: S::Mode) -> bool {
        self.inner.is_terminal(mode)
    }

    fn next_breakpoint(&self, t: f64) -> Option<f64> {
        self.inner.next_breakpoint(t)
    }

    fn time_scale(&self) -> f64 {
        self.inner.time_scale()
    }

    fn step_cap(&self, mode: S::Mode) -> f64 {
        self.inner.step_cap(mode)
    }
}

/// An observer that ignores everything (the loops read the driver's state).
pub(super) struct Quiet;

impl<M, R, const N: usize> Observer<M, R, N> for Quiet {
    fn sample(&mut self, _t: f64, _mode: M, _y: &[f64; N]) {}
    fn section(&mut self, _k: u64, _t: f64, _mode: M, _y: &[f64; N]) {}
    fn event(&mut self, _t: f64, _before: M, _y_before: &[f64; N], _record: R) {}
}
