//! `rocking bench`: work–precision benchmarks (run time against error).

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;

use super::error::BatchError;
use crate::bench::{self, BenchOptions, Record};
use crate::io::staging::Staging;
use crate::plot::Figure as _;
use crate::plot::work_precision::WorkPrecisionFigure;

/// Arguments of `rocking bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// One scene (free, periodic, sliding, chaotic); all four if absent.
    #[arg(long, value_name = "NAME")]
    pub scene: Option<String>,
    /// Repeats per point, at least: short runs are repeated until they add
    /// up to 0.05 s. The median wall time is reported.
    #[arg(long, default_value_t = 5, value_name = "N")]
    pub repeats: usize,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// Runs the benchmark and writes work_precision.json, .csv, .png and .svg.
pub fn run(args: &BenchArgs) -> Result<(), BatchError> {
    let all = bench::scenes();
    let scenes: Vec<_> = match &args.scene {
        None => all,
        Some(name) => {
            let known: Vec<&str> = all.iter().map(|s| s.name).collect();
            let picked: Vec<_> = all.iter().filter(|s| s.name == name).cloned().collect();
            if picked.is_empty() {
                return Err(BatchError::Input(anyhow::anyhow!(
                    "--scene {name}: unknown scene (known: {})",
                    known.join(", ")
                )));
            }
            picked
        }
    };
    if args.repeats == 0 || args.repeats > 1000 {
        return Err(BatchError::Input(anyhow::anyhow!(
            "--repeats {}: must be in 1..=1000",
            args.repeats
        )));
    }
    let mut staging = Staging::new(&args.out)
        .context("--out: cannot write the output directory")
        .map_err(BatchError::Input)?;
    let opts = BenchOptions {
        repeats: args.repeats,
        ..BenchOptions::default()
    };
    let mut records = Vec::new();
    let mut references = Vec::new();
    let mut targets = Vec::new();
    for scene in &scenes {
        let (reference, recs) = bench::work_precision(scene, &opts)
            .with_context(|| format!("scene {}", scene.name))
            .map_err(BatchError::Run)?;
        let t = bench::targets(scene.name, &recs);
        crate::say!(
            "{:9} reference self-check {:.1e}; Ralston at 0.004: error {:.2e} in {:.4} s; DOP853 at that error {:.4} s (×{:.1}); at 1e-9: ×{:.0}",
            scene.name,
            reference.self_check,
            t.ralston_error_at_paper_step.unwrap_or(f64::NAN),
            t.ralston_time_at_paper_step.unwrap_or(f64::NAN),
            t.dop853_time_at_that_error.unwrap_or(f64::NAN),
            t.speedup_at_paper_error.unwrap_or(f64::NAN),
            t.speedup_at_1e9.unwrap_or(f64::NAN),
        );
        references.push(reference);
        targets.push(t);
        records.extend(recs);
    }
    let json = serde_json::json!({
        "records": records,
        "references": references,
        "targets": targets,
        "scenes": scenes.iter().map(|s| serde_json::json!({"name": s.name, "description": s.description, "tau_end": s.tau_end})).collect::<Vec<_>>(),
        "version": env!("CARGO_PKG_VERSION"),
    });
    let text = serde_json::to_string_pretty(&json)
        .context("serialising")
        .map_err(BatchError::Run)?;
    staging
        .text("work_precision.json", &(text + "\n"))
        .context("writing")
        .map_err(BatchError::Run)?;
    staging
        .text("work_precision.csv", &bench::to_csv(&records))
        .context("writing")
        .map_err(BatchError::Run)?;
    let points: Vec<_> = records.iter().map(Record::point).collect();
    let fig = WorkPrecisionFigure {
        points: &points,
        scenes: scenes.iter().map(|s| s.name.to_string()).collect(),
    };
    fig.write_png(&staging.path("work_precision.png"))
        .context("drawing")
        .map_err(BatchError::Run)?;
    let svg = fig.to_svg().context("drawing").map_err(BatchError::Run)?;
    staging
        .text("work_precision.svg", &svg)
        .context("writing")
        .map_err(BatchError::Run)?;
    staging
        .commit()
        .context("writing the output directory")
        .map_err(BatchError::Run)?;
    crate::say!("wrote {}", args.out.display());
    Ok(())
}
