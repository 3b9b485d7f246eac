//! The bifurcation view's background sweep: one named thread per sweep,
//! which runs the analysis layer's generic [`sweep`] (rayon, all cores) and
//! sends each value's result back as soon as it is computed.
//!
//! Contract:
//! - No physics here: every value is [`steady_response`] of the base
//!   configuration with the swept key set, exactly as `rocking sweep`
//!   computes it (from the configuration's initial state, no continuation).
//! - Results arrive value by value, in completion order (rayon spreads the
//!   values over the cores, so the diagram fills in across its whole range).
//! - The sweep is a [`Job`] named `bifurcation`. Its reply channel holds
//!   [`CAPACITY`] messages, one per value plus `Done` for the largest
//!   sweep, so a sweep never waits on a slow view; one larger than the
//!   view allows would wait for room (backpressure), and cancelling ends
//!   the wait.
//! - Cancellation: a flag checked before and after each value. A cancelled
//!   sweep finishes the values already running (at most one per core) and
//!   sends nothing more; the view stops reading it at once, so nothing
//!   stale is ever drawn.
//! - The thread is joined when its [`Sweeper`] is dropped (after cancelling
//!   it), so no sweep outlives the view.

use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::orbit_diagram::{BlockSweep, Continuation, Grid, Plan, sweep};
use crate::analysis::steady::{Window, steady_response};
use crate::sim::job::{Job, Link, Waker};
use crate::sim::{Param, Scenario};

/// Most values one interactive sweep may have: 2001 values of 255 points
/// each is about 4 MB, and more columns than a screen has pixels add nothing.
pub(crate) const MAX_VALUES: usize = 2001;

/// Replies the channel holds: every value of the largest sweep plus `Done`.
pub(crate) const CAPACITY: usize = MAX_VALUES + 1;

/// What to compute.
#[derive(Clone, Debug)]
pub struct Request {
    /// The scene with the swept key free.
    pub base: Scenario,
    /// The swept parameter.
    pub param: Param,
    /// The values.
    pub grid: Grid,
    /// Transient and end of each run, τ.
    pub window: Window,
}

/// One computed value: its class and the Θ of its section points after the
/// transient (none for tumbled or flight).
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// The parameter value.
    pub value: f64,
    /// The steady response.
    pub response: Response,
    /// Θ(τ_k) for the section points after the transient, units of ψ.
    pub thetas: Vec<f64>,
}

/// What the sweep thread sends.
#[derive(Clone, Debug, PartialEq)]
pub enum Reply {
    /// One value done.
    Value(Column),
    /// One value failed (the others go on).
    Failed {
        /// The parameter value.
        value: f64,
        /// Why, one line.
        error: String,
    },
    /// The sweep was refused before anything ran (a value out of range, a
    /// window too short, non-harmonic excitation), one line naming the key.
    Invalid(String),
    /// Every value has been sent.
    Done,
}

/// A running (or finished) sweep: [`Job::drain`] its replies,
/// [`Job::cancel`] it, ask whether it [`Job::finished`]; dropping it
/// cancels and joins.
pub(crate) type Sweeper = Job<Reply>;

/// The closure's error when the sweep was cancelled.
struct Cancelled;

impl std::fmt::Display for Cancelled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("cancelled")
    }
}

/// Starts `req` on a thread named `bifurcation`.
pub fn start(req: Request, waker: Waker) -> Result<Sweeper, String> {
    Job::spawn("bifurcation", CAPACITY, waker, move |link| run(&req, &link))
        .map_err(|e| format!("cannot start the bifurcation thread: {e}"))
}

fn run(req: &Request, link: &Link<Reply>) {
    let send = |r: Reply| {
        // Refused only when cancelled (a newer sweep, a hidden view): the
        // checks around each value then stop the sweep.
        let _ = link.send(r);
    };
    let plan = match Plan::new(req.grid, Continuation::None, None) {
        Ok(p) => p,
        Err(e) => return send(Reply::Invalid(e.to_string())),
    };
    let classify = ClassifyOptions::default();
    let spec = BlockSweep {
        base: &req.base,
        param: req.param,
        window: req.window,
        classify,
        lyapunov: None,
    };
    // Every value's configuration is checked before anything runs.
    if let Err(e) = spec.scenarios(&plan) {
        return send(Reply::Invalid(e.to_string()));
    }
    let result = sweep(&plan, &crate::analysis::silent, |value, _: Option<&()>| {
        if link.cancelled() {
            return Err(Cancelled);
        }
        let out = spec
            .scenario(value)
            .map_err(|e| e.to_string())
            .and_then(|cfg| steady_response(&cfg, &req.window, &classify, None).map_err(|e| e.to_string()));
        if link.cancelled() {
            return Err(Cancelled);
        }
        send(match out {
            Ok(s) => Reply::Value(Column {
                value,
                response: s.response,
                thetas: s.points.iter().map(|p| p.theta).collect(),
            }),
            Err(error) => Reply::Failed { value, error },
        });
        Ok(((), None))
    });
    if result.is_ok() {
        send(Reply::Done);
    }
}
