//! The outcome map's background computation: one named thread per map,
//! which drives the analysis layer's map engine ([`MapRun`], the one
//! `rocking map` and Python drive) with the fast plan: each cell stops as
//! soon as its class is certain, and the map is computed coarse first and
//! then refined where labels meet. Each batch's cells run on all cores
//! (rayon) and each cell's class is sent back as soon as it is known.
//!
//! Contract:
//! - No physics here: every cell is [`MapRun::compute`] of the
//!   [`BlockMap`]'s scenario for that cell, exactly as `rocking map`
//!   computes it (from the configuration's initial state), and which cells
//!   are computed is the engine's schedule.
//! - Every cell of the full grid is checked before anything runs (as the
//!   CLI does); a refusal is one [`Reply::Invalid`] naming both keys.
//! - Replies, in order: per batch, [`Reply::Level`] (its stride and the
//!   number of cells to compute), then one [`Reply::Cell`] per cell in
//!   completion order, then (once the engine has recorded the batch)
//!   [`Reply::Labels`] with each of the batch's cells' [`Label`] and, in a
//!   basin map, [`Reply::Attractors`]; after the last batch
//!   [`Reply::Done`]. The view mirrors the schedule with its own
//!   [`Refiner`](crate::analysis::map_refine::Refiner) fed the same labels
//!   (the schedule depends only on them), so it never needs the thread's
//!   copy. Attractor numbers are known only once a batch is recorded
//!   (the engine numbers them in index order), hence the labels after the
//!   cells.
//! - Refinement tells cells apart by their [`Label`]: the exact class and,
//!   in a basin map, the attractor, as in `rocking map`. A failed cell is
//!   a class of its own: its neighbours are refined, and the view paints
//!   it as failed.
//! - Cancellation: a flag checked before and after each cell. A cancelled
//!   map finishes the cells already running (at most one per core) and
//!   sends nothing more.
//! - The reply channel holds [`CAPACITY`] messages; when it is full the
//!   thread waits for the view to drain it (backpressure), and cancelling
//!   ends the wait. The thread is joined when its [`Mapper`] is dropped.

use rayon::prelude::*;

use crate::analysis::attractor::Attractor;
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::outcome_map::{Axis, BlockMap, Label, MapPlan, MapRun};
use crate::analysis::settle::CellResponse;
use crate::analysis::steady::Window;
use crate::sim::job::{Job, Link, Waker};
use crate::sim::{Param, Scenario};

/// Replies the channel holds: a whole 64 × 64 map, so a small map never
/// waits on the view; larger ones wait for it to drain (it drains every
/// frame).
pub(crate) const CAPACITY: usize = 4096;

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

impl Request {
    /// The engine's description of this map.
    pub fn spec(&self) -> BlockMap<'_> {
        BlockMap {
            base: &self.base,
            x_param: self.x_param,
            x: &self.x,
            y_param: self.y_param,
            y: &self.y,
            window: self.window,
            classify: ClassifyOptions::default(),
            lyapunov: None,
        }
    }

    /// The plan the panel computes with: early stopping, refinement from
    /// `coarse`.
    pub fn plan(&self) -> MapPlan {
        MapPlan {
            early_stop: true,
            coarse: Some(self.coarse),
        }
    }

    /// Whether attractors are told apart (both keys are initial-state
    /// keys), as the engine decides.
    pub fn is_basin(&self) -> bool {
        self.x_param.is_initial_state() && self.y_param.is_initial_state()
    }
}

/// The class of a computed cell; `None` when its run failed.
pub(crate) type Class = Option<Response>;

/// What the map thread sends.
#[derive(Clone, Debug, PartialEq)]
pub enum Reply {
    /// A batch begins: its stride and the number of cells it computes.
    Level {
        /// Lattice stride, cells (the coarse one first, then halving to 1).
        stride: usize,
        /// Cells computed in this batch.
        cells: usize,
    },
    /// One cell done.
    Cell {
        /// Row-major index, `j·nx + i`.
        index: usize,
        /// Its class (`None`: the run failed, see `error`).
        class: Class,
        /// Whether its run stopped before the end of its window (its class
        /// was certain).
        stopped_early: bool,
        /// Why the run failed, one line.
        error: Option<String>,
    },
    /// The batch's cells as the engine recorded them (index, label), for
    /// the view's mirror of the schedule. A label's attractor is its
    /// discovery number: [`Reply::Attractors`] numbers it.
    Labels(Vec<(usize, Label)>),
    /// A basin map's attractors so far, numbered by their first cell in
    /// row order as `rocking map` numbers them, and the number of each
    /// discovery number.
    Attractors {
        /// The attractors, ids 1, 2, ….
        attractors: Vec<Attractor>,
        /// `ids[d]`: the id of discovery number `d`.
        ids: Vec<u32>,
    },
    /// The map was refused before anything ran, one line naming the keys.
    Invalid(String),
    /// Every batch has been sent.
    Done,
}

/// A running (or finished) map: drain its replies, cancel it, ask whether
/// it finished; dropping it cancels and joins.
pub(crate) type Mapper = Job<Reply>;

/// Starts `req` on a thread named `outcome map`.
pub fn start(req: Request, waker: Waker) -> Result<Mapper, String> {
    Job::spawn("outcome map", CAPACITY, waker, move |link| run(&req, &link))
        .map_err(|e| format!("cannot start the outcome-map thread: {e}"))
}

fn run(req: &Request, link: &Link<Reply>) {
    let send = |r: Reply| link.send(r).is_ok();
    let spec = req.spec();
    if let Err(e) = spec.check() {
        send(Reply::Invalid(format!(
            "{} = {}, {} = {}: {}",
            req.x.key, e.x, req.y.key, e.y, e.error
        )));
        return;
    }
    let mut run = MapRun::new(spec, req.plan());
    while let Some((cells, _inherited)) = run.next_batch() {
        if !send(Reply::Level {
            stride: run.stride(),
            cells: cells.len(),
        }) {
            return;
        }
        let engine = &run;
        let results: Vec<Option<(usize, Option<CellResponse>)>> = cells
            .par_iter()
            .map(|&index| {
                if link.cancelled() {
                    return None;
                }
                let out = engine.compute(index);
                if link.cancelled() {
                    return None;
                }
                let reply = match &out {
                    Ok(c) => Reply::Cell {
                        index,
                        class: Some(c.response),
                        stopped_early: c.stopped_at.is_some(),
                        error: None,
                    },
                    Err(e) => Reply::Cell {
                        index,
                        class: None,
                        stopped_early: false,
                        error: Some(e.to_string()),
                    },
                };
                send(reply).then_some((index, out.ok()))
            })
            .collect();
        if link.cancelled() {
            return;
        }
        let mut computed = Vec::with_capacity(results.len());
        for (index, cell) in results.into_iter().flatten() {
            match cell {
                Some(c) => computed.push((index, c)),
                None => run.record_failed(index),
            }
        }
        run.record(computed);
        let failed = Label {
            response: None,
            attractor: None,
        };
        let labels = cells
            .iter()
            .map(|&index| (index, run.label(index).unwrap_or(failed)))
            .collect();
        if !send(Reply::Labels(labels)) {
            return;
        }
        if run.is_basin() {
            let (attractors, ids) = run.attractors();
            if !send(Reply::Attractors { attractors, ids }) {
                return;
            }
        }
    }
    send(Reply::Done);
}
