//! `rocking map`: the outcome map over two config keys.
//!
//! Writes into `--out`:
//! - `map.csv`: `x,y,outcome,period,max_abs_theta,lyapunov,attractor,computed`,
//!   rows with y outer and x inner, both increasing (`period` only for
//!   `periodic`, `lyapunov` empty unless computed, `attractor` the periodic
//!   attractor's number in a basin map, `computed` false for a cell that
//!   inherited its class while the map was refined, whose
//!   `max_abs_theta` is then empty);
//! - `map.png`, `map.svg`: cells coloured by outcome, with a legend;
//! - `map_lyapunov.png`, `map_lyapunov.svg` as well when exponents were
//!   computed: cells coloured by the largest exponent;
//! - `map.json`: the base configuration, the axes, window, classifier
//!   thresholds, how the map was computed (`plan`, cells run and stopped
//!   early), a basin map's attractors and the crate version.
//!
//! By default each cell stops as soon as its class is certain and the map
//! is refined where classes meet (docs/analysis.md); `--full` runs every
//! cell over its whole window.
//!
//! Bad input exits 2 with a one-line error naming the flag or key, before
//! anything runs or is written.

use std::time::Instant;

use anyhow::{Context as _, anyhow};
use serde_json::json;

use super::args::{SceneArgs, StudyArgs, StudyOutput};
use super::error::BatchError;
use super::flags::Flags;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::analysis::classify::{ClassifyOptions, Response};
use crate::analysis::outcome_map::{Axis, BlockMap, COARSE_CELLS, Cell, MapPlan, compute_map};
use crate::analysis::steady::LyapunovFn;
use crate::io::config;
use crate::io::csv::{self, Num, Row};
use crate::io::output;
use crate::plot::labels::{fixed_parameters, num, param_label, param_symbol, section_units};
use crate::plot::outcome_map::{Basins, MapColouring, OutcomeMapFigure, attractor_label};
use crate::sim::Param;

/// Arguments of `rocking map`.
#[derive(Debug, Clone, clap::Args)]
pub struct MapArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Horizontal axis: config key, first and last value, number of values.
    #[arg(long = "x", num_args = 4, value_names = ["KEY", "A", "B", "N"], allow_negative_numbers = true, required = true)]
    pub x: Vec<String>,
    /// Vertical axis: config key, first and last value, number of values.
    #[arg(long = "y", num_args = 4, value_names = ["KEY", "A", "B", "N"], allow_negative_numbers = true, required = true)]
    pub y: Vec<String>,
    /// Window and threads.
    #[command(flatten)]
    pub study: StudyArgs,
    /// Run every cell over its whole window, no early stop and no
    /// refinement (the reference the fast map is checked against).
    #[arg(long)]
    pub full: bool,
    /// Cells along the longer axis of the coarse grid that refinement
    /// starts from; an island smaller than the map's extent over this may
    /// be missed.
    #[arg(long, value_name = "N", default_value_t = COARSE_CELLS, conflicts_with = "full")]
    pub coarse: usize,
    /// Output folder, Lyapunov exponents, quiet.
    #[command(flatten)]
    pub output: StudyOutput,
}

/// Parses `KEY A B N` of `--x`/`--y` into the axis and its parameter.
fn axis(flag: &str, parts: &[String]) -> anyhow::Result<(Axis, Param)> {
    let [key, a, b, n] = parts else {
        return Err(anyhow!("{flag}: expected KEY A B N"));
    };
    let param = config::param(key).map_err(|e| anyhow!("{flag} {e}"))?;
    let number = |name: &str, s: &str| {
        s.parse::<f64>()
            .map_err(|_| anyhow!("{flag} {key}: {name} = '{s}' is not a number"))
    };
    let (a, b) = (number("A", a)?, number("B", b)?);
    let n: usize = n
        .parse()
        .map_err(|_| anyhow!("{flag} {key}: N = '{n}' is not a positive integer"))?;
    Ok((Axis::new(flag, key, a, b, n)?, param))
}

/// A row of `map.csv`: one cell and its steady response.
#[derive(serde::Serialize)]
struct MapRow {
    x: Num,
    y: Num,
    outcome: &'static str,
    period: Option<u32>,
    max_abs_theta: Option<Num>,
    lyapunov: Option<Num>,
    attractor: Option<u32>,
    computed: bool,
}

impl Row for MapRow {
    const HEADER: &'static [&'static str] = &[
        "x",
        "y",
        "outcome",
        "period",
        "max_abs_theta",
        "lyapunov",
        "attractor",
        "computed",
    ];
}

/// `map.csv` of `cells` (in row order).
pub(crate) fn map_csv(cells: &[Cell]) -> String {
    csv::to_string(cells.iter().map(|c| MapRow {
        x: Num(c.x),
        y: Num(c.y),
        outcome: c.response.name(),
        period: c.response.period(),
        max_abs_theta: c.max_abs_theta.map(Num),
        lyapunov: c.lyapunov.map(Num),
        attractor: c.attractor,
        computed: c.computed,
    }))
}

/// Runs `rocking map` without Lyapunov exponents.
pub fn run(args: &MapArgs) -> Result<(), BatchError> {
    run_with(args, None)
}

/// Runs `rocking map`; `lyapunov`, if given, fills the `lyapunov` column,
/// decides between quasiperiodic and chaotic, and adds the λ-coloured map.
pub(crate) fn run_with(args: &MapArgs, lyapunov: Option<&LyapunovFn<'_>>) -> Result<(), BatchError> {
    let input = BatchError::Input;
    let base = args.scene.load().map_err(|e| input(e.into()))?;
    let (x, x_param) = axis("--x", &args.x).map_err(input)?;
    let (y, y_param) = axis("--y", &args.y).map_err(input)?;
    if x_param == y_param {
        return Err(input(anyhow!("--y {}: the two axes must be different keys", y.key)));
    }
    for (flag, p) in [("--x", x_param), ("--y", y_param)] {
        if p == Param::TauEnd {
            return Err(input(anyhow!(
                "{flag} run.tau_end: the run length is set by --tau-end, it cannot be an axis"
            )));
        }
    }
    if !args.full && args.coarse < 2 {
        return Err(input(anyhow!("--coarse {}: must be >= 2", args.coarse)));
    }
    let plan = if args.full {
        MapPlan::FULL
    } else {
        MapPlan {
            early_stop: true,
            coarse: Some(args.coarse),
        }
    };
    let mut config = base.clone();
    let window = args.study.window(&base).map_err(|e| input(anyhow!(e)))?;
    config.run.tau_end = window.tau_end;
    let spec = BlockMap {
        base: &base,
        x_param,
        x: &x,
        y_param,
        y: &y,
        window,
        classify: ClassifyOptions::default(),
        lyapunov,
    };
    spec.check().map_err(|e| {
        input(anyhow!(
            "--x {} = {}, --y {} = {}: {}",
            x.key,
            e.x,
            y.key,
            e.y,
            e.error.render(&Flags)
        ))
    })?;
    let pool = thread_pool(args.study.threads)?;
    output::check_writable(&args.output.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(input)?;

    let start = Instant::now();
    let bar = progress_bar(x.n * y.n, "cells", args.output.quiet);
    let map = pool
        .install(|| compute_map(&spec, plan, &progress_fn(&bar)))
        .map_err(|e| {
            let message = anyhow!("{} = {}, {} = {}: {}", x.key, e.x, y.key, e.y, e.error.render(&Flags));
            BatchError::of(message, e.error.is_input())
        })?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    let cells = &map.cells;
    let attractors: Vec<serde_json::Value> = map
        .attractors
        .iter()
        .map(|a| {
            json!({
                "id": a.id,
                "period": a.period,
                "point": {"theta": a.point[0], "theta_dot": a.point[1], "x_dot": a.point[2]},
                "cells": a.cells,
            })
        })
        .collect();

    let meta = json!({
        "command": "rocking map",
        "version": env!("CARGO_PKG_VERSION"),
        "x": x,
        "y": y,
        "window": window,
        "classify": spec.classify,
        "plan": plan,
        "cells_run": map.computed,
        "cells_stopped_early": map.stopped_early,
        "cells_on_known_attractor": map.reached_known,
        "attractors": attractors,
        "config": config::to_json(&config),
        "units": format!("{}; lyapunov per unit τ; config: the base configuration, the two axis keys take each cell's values", section_units(&config)),
    });
    let (sx, sy) = (param_symbol(x_param), param_symbol(y_param));
    let what = if map.attractors.is_empty() {
        "Outcome map"
    } else {
        "Basins of attraction"
    };
    let title = format!(
        "{what} over {sx} × {sy}: {}",
        fixed_parameters(&config, &[x_param, y_param])
    );
    let how = if args.full {
        "every cell run to the end".to_string()
    } else {
        format!("{} run, the rest inherited", map.computed)
    };
    let subtitle = format!(
        "{} × {} cells ({how}); response from the Poincaré points at {} ≤ τ_k ≤ {}, from the initial state",
        x.n,
        y.n,
        num(window.transient),
        num(window.tau_end)
    );
    let (xs, ys) = (x.values(), y.values());
    let data: Vec<(Response, Option<f64>)> = cells.iter().map(|c| (c.response, c.lyapunov)).collect();
    let ids: Vec<Option<u32>> = cells.iter().map(|c| c.attractor).collect();
    let basins = (!map.attractors.is_empty()).then_some(Basins {
        ids: &ids,
        attractors: &map.attractors,
    });
    let figure = |colouring| OutcomeMapFigure {
        title: title.clone(),
        subtitle: subtitle.clone(),
        x_label: param_label(x_param),
        y_label: param_label(y_param),
        x: &xs,
        y: &ys,
        cells: &data,
        colouring,
        basins,
    };
    let with_lyapunov = cells.iter().any(|c| c.lyapunov.is_some());
    super::write::staged(&args.output.out, |staging| {
        staging.text("map.csv", &map_csv(cells))?;
        staging.text("map.json", &(serde_json::to_string_pretty(&meta)? + "\n"))?;
        let outcome = figure(MapColouring::Outcome);
        super::write::figure(staging, "map", &outcome)?;
        if with_lyapunov {
            let lyap = figure(MapColouring::Lyapunov);
            super::write::figure(staging, "map_lyapunov", &lyap)?;
        }
        Ok(())
    })?;

    if !args.output.quiet {
        let mut counts: Vec<(String, usize)> = Vec::new();
        for c in cells {
            let name = match c.attractor {
                Some(id) => format!("{} A{id}", c.response),
                None => c.response.to_string(),
            };
            match counts.iter_mut().find(|(n, _)| *n == name) {
                Some(entry) => entry.1 += 1,
                None => counts.push((name, 1)),
            }
        }
        counts.sort();
        let summary: Vec<String> = counts.iter().map(|(n, c)| format!("{n}: {c}")).collect();
        let total = x.n * y.n;
        let reached = match map.reached_known {
            0 => String::new(),
            n => format!(", {n} on reaching a known attractor"),
        };
        let how = if args.full {
            "every cell run over its whole window".to_string()
        } else if map.computed == total {
            format!("every cell run, {} stopped early{reached}", map.stopped_early)
        } else {
            format!(
                "{} cells run, {} of them stopped early{reached}; {} inherited from uniform neighbourhoods",
                map.computed,
                map.stopped_early,
                total - map.computed
            )
        };
        crate::say!(
            "mapped {} × {} cells in {wall:.1} s ({how}); {}",
            x.n,
            y.n,
            summary.join(", ")
        );
        for a in &map.attractors {
            crate::say!("attractor {} ({} cells)", attractor_label(a), a.cells);
        }
        crate::say!("wrote {}", args.output.out.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_csv_header_is_the_row_fields() {
        let r = MapRow {
            x: Num(0.5),
            y: Num(8.0),
            outcome: "chaotic",
            period: None,
            max_abs_theta: Some(Num(0.25)),
            lyapunov: Some(Num(0.1)),
            attractor: None,
            computed: true,
        };
        assert_eq!(csv::header_of(&r), csv::header::<MapRow>());
        let cell = Cell {
            x: 0.5,
            y: 8.0,
            response: crate::analysis::classify::Response::Periodic { period: 2 },
            max_abs_theta: Some(0.25),
            lyapunov: None,
            attractor: Some(2),
            computed: true,
        };
        assert_eq!(
            map_csv(&[cell]),
            "x,y,outcome,period,max_abs_theta,lyapunov,attractor,computed\n0.5,8.0,periodic,2,0.25,,2,true\n"
        );
    }
}
