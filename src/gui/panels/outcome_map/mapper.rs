//! The outcome map's background computation: one named thread per map,
//! which walks the analysis layer's refinement schedule
//! ([`Refiner`]) level by level, computes each level's cells on all cores
//! (rayon) and sends each cell's class back as soon as it is known.
//!
//! Contract:
//! - No physics here: every cell is [`steady_response`] of the
//!   [`BlockMap`]'s scenario for that cell, exactly as `rocking map`
//!   computes it (from the configuration's initial state).
//! - Every cell of the full grid is checked before anything runs (as the
//!   CLI does); a refusal is one [`Reply::Invalid`] naming both keys.
//! - Replies, in order: per level, [`Reply::Level`] (its stride and the
//!   number of cells to compute), then one [`Reply::Cell`] per cell in
//!   completion order; after the last level [`Reply::Done`]. The view
//!   mirrors the schedule with its own [`Refiner`] (the schedule depends
//!   only on the classes, which it receives), so it never needs the
//!   thread's copy.
//! - Refinement tells cells apart by their legend class ([`Slot`]): the
//!   picture shows period 3 and period 6 in one colour, so a boundary
//!   between them is not refined. A failed cell is a class of its own:
//!   its neighbours are refined, and the view paints it as failed. Each
//!   computed cell's exact class is still sent.
//! - Cancellation: a flag checked before and after each cell. A cancelled
//!   map finishes the cells already running (at most one per core) and
//!   sends nothing more.
//! - The reply channel holds [`CAPACITY`] messages; when it is full the
//!   thread waits for the view to drain it (backpressure), and cancelling
//!   ends the wait. The thread is joined when its [`Mapper`] is dropped.

use rayon::prelude::*;

use super::Slot;
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::map_refine::Refiner;
use crate::analysis::outcome_map::{Axis, BlockMap};
use crate::analysis::steady::{Window, steady_response};
use crate::sim::job::{Job, Link, Waker};
use crate::sim::{Param, Scenario};

/// Replies the channel holds: a whole 64 × 64 map, so a small map never
/// waits on the view; larger ones wait for it to drain (it drains every
/// frame).
pub const CAPACITY: usize = 4096;

/// Lattice lines around a cell that must agree before it inherits their
/// class (the [`Refiner`]'s halo): 1 catches boundaries that bulge between
/// two lattice lines, at about twice the cells of 0 along each boundary.
pub const HALO: usize = 1;

/// What to compute.
#[derive(Clone, Debug)]
pub struct Request {
    /// The scene with the two keys free.
    pub base: Scenario,
    /// Parameter along the horizontal axis.
    pub x_param: Param,
    /// Horizontal axis.
    pub x: Axis,
    /// Parameter along the vertical axis.
    pub y_param: Param,
    /// Vertical axis.
    pub y: Axis,
    /// Transient and end of each run, τ.
    pub window: Window,
    /// Cells of the coarse level along the longer axis (at least).
    pub coarse: usize,
}

/// The class of a computed cell; `None` when its run failed.
pub type Class = Option<Response>;

/// What the map thread sends.
#[derive(Clone, Debug, PartialEq)]
pub enum Reply {
    /// A level begins: its stride and the number of cells it computes.
    Level {
        /// Lattice stride, cells (the coarse one first, then halving to 1).
        stride: usize,
        /// Cells computed at this level.
        cells: usize,
    },
    /// One cell done.
    Cell {
        /// Row-major index, `j·nx + i`.
        index: usize,
        /// Its class (`None`: the run failed, see `error`).
        class: Class,
        /// Why the run failed, one line.
        error: Option<String>,
    },
    /// The map was refused before anything ran, one line naming the keys.
    Invalid(String),
    /// Every level has been sent.
    Done,
}

/// A running (or finished) map: drain its replies, cancel it, ask whether
/// it finished; dropping it cancels and joins.
pub type Mapper = Job<Reply>;

/// Starts `req` on a thread named `outcome map`.
pub fn start(req: Request, waker: Waker) -> Result<Mapper, String> {
    Job::spawn("outcome map", CAPACITY, waker, move |link| run(&req, &link))
        .map_err(|e| format!("cannot start the outcome-map thread: {e}"))
}

fn run(req: &Request, link: &Link<Reply>) {
    let send = |r: Reply| link.send(r).is_ok();
    let classify = ClassifyOptions::default();
    let spec = BlockMap {
        base: &req.base,
        x_param: req.x_param,
        x: &req.x,
        y_param: req.y_param,
        y: &req.y,
        window: req.window,
        classify,
        lyapunov: None,
    };
    if let Err(e) = spec.check() {
        send(Reply::Invalid(format!(
            "{} = {}, {} = {}: {}",
            req.x.key, e.x, req.y.key, e.y, e.error
        )));
        return;
    }
    let nx = req.x.n;
    let mut refiner: Refiner<Slot> = Refiner::new(nx, req.y.n, req.coarse, HALO);
    while let Some(cells) = refiner.next_level() {
        let stride = refiner.stride().unwrap_or(1);
        if !send(Reply::Level {
            stride,
            cells: cells.len(),
        }) {
            return;
        }
        let results: Vec<Option<(usize, Class)>> = cells
            .par_iter()
            .map(|&index| {
                if link.cancelled() {
                    return None;
                }
                let (x, y) = (req.x.value(index % nx), req.y.value(index / nx));
                let out = spec
                    .scenario(x, y)
                    .and_then(|cfg| steady_response(&cfg, &req.window, &classify, None));
                if link.cancelled() {
                    return None;
                }
                let (class, error) = match out {
                    Ok(s) => (Some(s.response), None),
                    Err(e) => (None, Some(e.to_string())),
                };
                send(Reply::Cell { index, class, error }).then_some((index, class))
            })
            .collect();
        if link.cancelled() {
            return;
        }
        for (index, class) in results.into_iter().flatten() {
            refiner.record(index, Slot::of(class));
        }
    }
    send(Reply::Done);
}
