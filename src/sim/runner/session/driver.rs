//! The driver and the system of a live run behind pointers: whatever the method and the body, the session and its ghosts hold one pointer each.

use crate::integrate::Stepper;
use crate::integrate::hybrid::{Advance, Driver, Limits, Observer, Outputs};
use crate::model::rocker::RockerCore;
use crate::model::system::{EventRecord, ModelError, N};
use crate::model::{Mode, Model, Rocker, RockerVisitor, with_rocker};
use crate::sim::Scenario;
use crate::sim::method::{StepperVisitor, with_stepper};

/// The driver of a live run, whatever its method: a trait object, so the
/// session and a hundred ghosts hold one pointer each. Dispatch is per
/// chunk and per output, not per step: the stepping inside
/// [`Driver::advance_past`] stays monomorphised.
pub(super) trait LiveDriver: Send {
    fn t(&self) -> f64;
    fn y(&self) -> [f64; N];
    fn mode(&self) -> Mode;
    /// To `t_end` or past it, by whole steps that end on `horizon` at the
    /// latest ([`Driver::advance_past`]).
    fn advance(
        &mut self,
        t_end: f64,
        horizon: f64,
        obs: &mut dyn Observer<Mode, EventRecord, N>,
    ) -> Result<Advance, ModelError>;
    /// Exactly onto `t_end` ([`Driver::advance`]).
    fn advance_onto(&mut self, t_end: f64, obs: &mut dyn Observer<Mode, EventRecord, N>)
    -> Result<Advance, ModelError>;
    /// Largest |Θ| the model found at its rocking peaks (between samples).
    fn peak_theta(&self) -> f64;
}

/// An observer behind a `dyn` pointer, for the generic driver.
struct Forward<'a>(&'a mut dyn Observer<Mode, EventRecord, N>);

impl Observer<Mode, EventRecord, N> for Forward<'_> {
    fn sample(&mut self, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.sample(t, mode, y);
    }
    fn section(&mut self, k: u64, t: f64, mode: Mode, y: &[f64; N]) {
        self.0.section(k, t, mode, y);
    }
    fn event(&mut self, t: f64, before: Mode, y_before: &[f64; N], record: EventRecord) {
        self.0.event(t, before, y_before, record);
    }
}

impl<S: Stepper<N> + Send, R: Rocker> LiveDriver for Driver<S, R, N> {
    fn t(&self) -> f64 {
        Driver::t(self)
    }
    fn y(&self) -> [f64; N] {
        *Driver::y(self)
    }
    fn mode(&self) -> Mode {
        Driver::mode(self)
    }
    fn advance(
        &mut self,
        t_end: f64,
        horizon: f64,
        obs: &mut dyn Observer<Mode, EventRecord, N>,
    ) -> Result<Advance, ModelError> {
        self.advance_past(t_end, horizon, &mut Forward(obs))
    }
    fn advance_onto(
        &mut self,
        t_end: f64,
        obs: &mut dyn Observer<Mode, EventRecord, N>,
    ) -> Result<Advance, ModelError> {
        Driver::advance(self, t_end, &mut Forward(obs))
    }
    fn peak_theta(&self) -> f64 {
        self.system().tallied().max_abs_theta
    }
}

pub(super) type AnyDriver = Box<dyn LiveDriver>;

/// The model's system behind a pointer (the block's or a frame's): what
/// the session asks of it between chunks ([`RockerCore`]), a copy, and the
/// driver it starts. The stepping itself stays monomorphised inside the
/// driver.
pub(super) trait LiveSystem: RockerCore {
    /// A copy.
    fn boxed_clone(&self) -> Box<dyn LiveSystem>;
    /// A driver of `scenario`'s method for this system from `from`.
    fn into_driver(self: Box<Self>, scenario: &Scenario, from: DriverStart, outputs: Outputs) -> AnyDriver;
}

/// Where a driver starts: the mode, τ and the state there.
#[derive(Clone, Copy, Debug)]
pub(super) struct DriverStart {
    pub(super) mode: Mode,
    pub(super) t0: f64,
    pub(super) y0: [f64; N],
}

impl<R: Rocker> LiveSystem for R {
    fn boxed_clone(&self) -> Box<dyn LiveSystem> {
        Box::new(self.clone())
    }
    fn into_driver(self: Box<Self>, scenario: &Scenario, from: DriverStart, outputs: Outputs) -> AnyDriver {
        live_driver(scenario, *self, from, outputs)
    }
}

/// The system `model` describes, behind a pointer.
pub(super) fn live_system(model: Model) -> Box<dyn LiveSystem> {
    struct Boxed;
    impl RockerVisitor for Boxed {
        type Output = Box<dyn LiveSystem>;
        fn visit<R: Rocker>(self, system: R) -> Self::Output {
            Box::new(system)
        }
    }
    with_rocker(model, Boxed)
}

/// A live driver of `scenario`'s method.
fn live_driver<R: Rocker>(scenario: &Scenario, system: R, from: DriverStart, outputs: Outputs) -> AnyDriver {
    /// The driver, waiting for its stepper.
    struct Make<R> {
        system: R,
        from: DriverStart,
        limits: Limits,
        outputs: Outputs,
    }
    impl<R: Rocker> StepperVisitor for Make<R> {
        type Output = AnyDriver;
        fn visit<S: Stepper<N> + Send + 'static>(self, stepper: S) -> AnyDriver {
            Box::new(Driver::new(
                stepper,
                self.system,
                self.from.mode,
                self.from.t0,
                self.from.y0,
                self.limits,
                self.outputs,
            ))
        }
    }
    let opts = scenario.run_options();
    let make = Make {
        system,
        from,
        limits: opts.limits,
        outputs,
    };
    with_stepper(opts.method, opts.tol, make)
}
