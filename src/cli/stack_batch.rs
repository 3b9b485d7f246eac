//! `rocking --batch` on a `[[stack]]`: one headless run of stacked blocks.

use anyhow::Context as _;

use super::Cli;
use super::error::BatchError;
use crate::io::output;
use crate::io::stack_files::{stack_summary, write_stack};
use crate::sim::Scenario;
use crate::sim::stack_run::simulate_stack;

/// Runs the stack of `cfg` as `cli` says. Nothing is written unless the
/// run succeeds; an upper face that would slip is bad input (exit 2): its
/// `static` is below what the motion needs, and sliding between blocks is
/// not simulated (the base face's is).
pub fn run(cli: &Cli, cfg: &Scenario) -> Result<(), BatchError> {
    let input = |e: anyhow::Error| BatchError::Input(e);
    let geo = cfg
        .stack_geometry()
        .ok_or_else(|| input(anyhow::anyhow!("stack: its blocks do not stand on each other")))?;
    let excitation = cfg.excitation().map_err(|e| input(e.into()))?;
    for warning in cfg.warnings() {
        eprintln!("{warning}");
    }
    output::check_writable(&cli.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(input)?;
    let run = simulate_stack(geo, excitation, cfg.run.zeno_eps, &cfg.run_options()).map_err(|e| {
        if e.is_input() {
            input(anyhow::Error::new(e))
        } else {
            BatchError::Run(anyhow::Error::new(e).context("simulation failed"))
        }
    })?;
    let mut summary = stack_summary(cfg, &run);
    let exponents = if cfg.analyses.lyapunov {
        Some(super::exponents::lyapunov_summary(cfg)?)
    } else {
        None
    };
    if let (Some(l), Some(obj)) = (&exponents, summary.as_object_mut()) {
        obj.insert("lyapunov".to_string(), l.summary());
    }
    let text = serde_json::to_string_pretty(&summary)
        .context("serialising summary.json")
        .map_err(BatchError::Run)?
        + "\n";
    super::write::staged(&cli.out, |staging| Ok(write_stack(staging, cfg, &run, &text)?))?;
    if !cli.quiet {
        crate::say!("{}", crate::sim::Physical::of_stack(cfg, &run).line());
        crate::say!(
            "outcome {} at tau {:.6} | impacts {} | energy residual {:.2e} (relative {:.1e}) | {} steps, {} rhs evals, solver {:.3} s",
            serde_json::to_value(run.outcome)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default(),
            run.tau_end,
            run.tally.impacts,
            run.energy.residual,
            run.energy.relative_residual,
            run.stats.accepted,
            run.stats.rhs_evals,
            run.wall_s,
        );
        crate::say!(
            "wrote {}/{{summary.json, events.csv ({} events), history.csv ({} rows)}}",
            cli.out.display(),
            run.events.len(),
            run.history.len()
        );
        super::exponents::say_lyapunov(exponents.as_ref());
    }
    Ok(())
}
