//! The `rocking` binary: `rocking --batch …` runs headless.

use clap::Parser as _;
use rocking::cli::{self, Cli, EXIT_BAD_INPUT, EXIT_RUN_FAILED, batch::BatchError};

fn main() {
    let cli = Cli::parse();
    if cli.list_presets {
        for (name, text) in rocking::io::presets::PRESETS {
            let title = text.lines().next().unwrap_or("").trim_start_matches('#').trim();
            println!("{name:10} {}", title.split_once(": ").map_or(title, |(_, t)| t));
        }
        return;
    }
    if !cli.batch {
        eprintln!(
            "error: this build has no window yet; run headless with `rocking --batch [--preset NAME | --config FILE] [--set KEY=VALUE]... [--out DIR]` (see --help)"
        );
        std::process::exit(EXIT_BAD_INPUT);
    }
    match cli::batch::run(&cli) {
        Ok(()) => {}
        Err(BatchError::Input(e)) => {
            eprintln!("error: {e:#}");
            std::process::exit(EXIT_BAD_INPUT);
        }
        Err(BatchError::Run(e)) => {
            eprintln!("error: {e:#}");
            std::process::exit(EXIT_RUN_FAILED);
        }
    }
}
