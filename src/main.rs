//! The `rocking` binary: `rocking --batch …` runs headless.

use rocking::cli::{self, Cli, EXIT_BAD_INPUT, EXIT_RUN_FAILED, error::BatchError};

fn main() {
    let cli = Cli::parse_deferred();
    if let Some(command) = &cli.command {
        cli::interrupt::install();
        match command.run() {
            Ok(()) => return,
            Err(e) => std::process::exit(cli::report(&e)),
        }
    }
    if cli.list_presets {
        for (name, text) in rocking::io::presets::PRESETS {
            rocking::say!("{name:16} {}", rocking::io::presets::title(text));
        }
        return;
    }
    if !cli.batch {
        open_window(&cli);
    }
    cli::interrupt::install();
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

/// `rocking` without `--batch`: the desktop app on the chosen scene
/// (the `default` preset unless `--preset`/`--config`/`--set` say otherwise).
#[cfg(feature = "gui")]
fn open_window(cli: &Cli) -> ! {
    let scene = rocking::gui::Settings::from_cli(
        cli.scene.preset.as_deref(),
        cli.scene.config.as_deref(),
        &cli.scene.sets,
    );
    let (settings, config) = match scene {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(EXIT_BAD_INPUT);
        }
    };
    // Without a display the window cannot open: say so in one line, with
    // the headless command (X11 needs DISPLAY, Wayland WAYLAND_DISPLAY or
    // WAYLAND_SOCKET). After the scene is read, so that a bad scene or
    // record is reported first, as it is before a window opens.
    let has = |var: &str| std::env::var_os(var).is_some_and(|v| !v.is_empty());
    if !has("DISPLAY") && !has("WAYLAND_DISPLAY") && !has("WAYLAND_SOCKET") {
        eprintln!(
            "error: no display found (DISPLAY and WAYLAND_DISPLAY are unset), so the app cannot open; run headless with `rocking --batch --preset NAME --out DIR` (see `rocking --help`)"
        );
        std::process::exit(EXIT_BAD_INPUT);
    }
    match rocking::gui::run(settings, config, cli.paused) {
        Ok(()) => std::process::exit(0),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(EXIT_RUN_FAILED);
        }
    }
}

/// `rocking` without `--batch` in a build without the `gui` feature.
#[cfg(not(feature = "gui"))]
fn open_window(_cli: &Cli) -> ! {
    eprintln!(
        "error: this build has no window yet; run headless with `rocking --batch [--preset NAME | --config FILE] [--set KEY=VALUE]... [--out DIR]` (see --help)"
    );
    std::process::exit(EXIT_BAD_INPUT);
}
