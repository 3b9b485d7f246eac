//! Ctrl-C and `kill`: a headless command interrupted while writing removes
//! its hidden staging folder (`.NAME.partial-PID`, which can hold hundreds
//! of MB of a `--batch` run's history) before it ends, instead of leaving
//! it for the next run to find. The process then ends by the signal it
//! got, as if it had not caught it, so a shell sees 130 (SIGINT) or 143
//! (SIGTERM) and a script's loop stops on Ctrl-C. SIGKILL cannot be
//! caught: the next run into the same folder removes what it leaves
//! (`io::staging`).

/// Installs the handler for SIGINT and SIGTERM: a named thread that waits
/// for either, removes every live staging folder and re-raises the signal
/// with its default action. Best effort: if it cannot be installed the
/// command runs as before (a signal then ends it at once).
#[cfg(unix)]
pub fn install() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use signal_hook::iterator::Signals;

    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    let _ = std::thread::Builder::new().name("interrupt".into()).spawn(move || {
        if let Some(signal) = signals.forever().next() {
            crate::io::staging::remove_live_then::<()>(|| {
                // Resets the default action and raises the signal again:
                // the process ends here, reported as killed by it.
                let _ = signal_hook::low_level::emulate_default_handler(signal);
                // Only if the default action did not end it.
                std::process::exit(128 + signal);
            })
        }
    });
}

/// Without Unix signals there is nothing to install.
#[cfg(not(unix))]
pub fn install() {}
