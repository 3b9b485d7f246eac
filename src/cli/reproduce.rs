//! `rocking reproduce`: recomputes every figure of the paper (Figs. 3–19)
//! and writes them, with `report.md` setting each beside the paper's
//! statements, into `--out` (see [`crate::reproduce`]).
//!
//! `--quick` is the CI-sized variant (A_v step 0.25, short runs), and
//! `--only fig4,fig12` limits the work to some figures. Bad input exits 2
//! with a one-line error naming the flag, before anything runs; the output
//! directory appears whole (all figures, CSVs, `reproduce.json` and
//! `report.md`) or not at all.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, anyhow};

use super::error::BatchError;
use super::sweep::{progress_bar, progress_fn, thread_pool};
use crate::io::output;
use crate::io::output_error::OutputError;
use crate::io::staging::Staging;
use crate::reproduce::paper::parse_figure;
use crate::reproduce::write::{Sink, write_all};
use crate::reproduce::{Options, reproduce};

/// Arguments of `rocking reproduce`.
#[derive(Debug, Clone, clap::Args)]
pub struct ReproduceArgs {
    /// Output directory: figures (PNG and SVG), CSV tables,
    /// reproduce.json and report.md.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// CI-sized run: A_v step 0.25 and short runs (minutes become seconds;
    /// not the paper's resolution, and the report says so).
    #[arg(long)]
    pub quick: bool,
    /// Only these figures, e.g. --only fig4,fig12 (the paper's Figs. 3–19).
    #[arg(long, value_name = "FIGS", value_delimiter = ',')]
    pub only: Vec<String>,
    /// Worker threads (default: one per core; at most 4 per core). The
    /// figures and CSV files do not depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// A staging directory as the reproduction's file sink.
struct StagingSink<'a>(&'a mut Staging);

impl Sink for StagingSink<'_> {
    fn text(&mut self, name: &str, text: &str) -> Result<(), OutputError> {
        self.0.text(name, text)
    }

    fn path(&mut self, name: &str) -> PathBuf {
        self.0.path(name)
    }
}

/// Parses `--only`: figure names (`fig4`, `4`), at least one, no repeats.
fn parse_only(only: &[String]) -> Result<Option<Vec<u32>>, BatchError> {
    if only.is_empty() {
        return Ok(None);
    }
    let mut figs = Vec::new();
    for name in only {
        let Some(n) = parse_figure(name) else {
            return Err(BatchError::Input(anyhow!(
                "--only {name}: not one of the paper's figures (fig3 … fig19)"
            )));
        };
        if !figs.contains(&n) {
            figs.push(n);
        }
    }
    figs.sort_unstable();
    Ok(Some(figs))
}

/// Runs `rocking reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<(), BatchError> {
    let start = Instant::now();
    let options = Options {
        quick: args.quick,
        only: parse_only(&args.only)?,
    };
    let pool = thread_pool(args.threads)?;
    output::check_writable(&args.out)
        .with_context(|| "--out: cannot write the output directory".to_string())
        .map_err(BatchError::Input)?;
    let bar = progress_bar(1, "figures", args.quiet);
    let rep = pool
        .install(|| reproduce(&options, &progress_fn(&bar)))
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    bar.finish_and_clear();

    let mut staging = Staging::new(&args.out).context("--out").map_err(BatchError::Run)?;
    let names = write_all(&rep, &mut StagingSink(&mut staging), pool.current_num_threads())
        .map_err(|e| BatchError::Run(anyhow!(e)))?;
    staging
        .commit()
        .with_context(|| format!("writing {}", args.out.display()))
        .map_err(BatchError::Run)?;
    if !args.quiet {
        crate::say!(
            "reproduced {} diagram(s) and {} response example(s){} in {:.1} s ({:.1} s computing); wrote {} files to {} (see report.md)",
            rep.diagrams.len(),
            rep.responses.len(),
            if args.quick { " (quick)" } else { "" },
            start.elapsed().as_secs_f64(),
            rep.wall_s,
            names.len(),
            args.out.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_parses_names_and_rejects_unknown_figures() {
        let v = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(parse_only(&[]).unwrap(), None);
        assert_eq!(parse_only(&v(&["fig12", "4", "fig4"])).unwrap(), Some(vec![4, 12]));
        let e = parse_only(&v(&["fig2"])).unwrap_err();
        match e {
            BatchError::Input(e) => assert!(e.to_string().starts_with("--only fig2:"), "{e}"),
            BatchError::Run(e) => panic!("{e}"),
        }
    }
}
