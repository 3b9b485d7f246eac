//! Progress of long commands on stderr: an indicatif bar on a terminal,
//! and where stderr is not a terminal (a log file, a cluster job's output)
//! one plain line every [`LOG_INTERVAL_S`] seconds, so a log shows how far
//! a run got without being flooded. Nothing with `--quiet`.

use std::io::IsTerminal as _;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle, TermLike};

/// Seconds between two progress lines in a log.
pub(crate) const LOG_INTERVAL_S: u64 = 5;

/// A progress bar counting `len` units named `what` (e.g. "blocks").
pub fn bar(len: usize, what: &str, quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let (target, template) = if std::io::stderr().is_terminal() {
        (
            ProgressDrawTarget::stderr(),
            format!("{{bar:40}} {{pos}}/{{len}} {what} {{elapsed_precise}} (eta {{eta}})"),
        )
    } else {
        (
            ProgressDrawTarget::term_like(Box::new(LogLines::new(Duration::from_secs(LOG_INTERVAL_S)))),
            format!("progress: {{pos}}/{{len}} {what}, {{elapsed_precise}} elapsed (eta {{eta}})"),
        )
    };
    let bar = ProgressBar::with_draw_target(Some(len as u64), target);
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    bar
}

/// An indicatif draw target that writes the bar's text as one line to
/// stderr at most once per interval (the first draw waits one interval,
/// so short runs print nothing).
#[derive(Debug)]
struct LogLines {
    interval: Duration,
    last: Mutex<Instant>,
}

impl LogLines {
    fn new(interval: Duration) -> Self {
        Self {
            interval,
            last: Mutex::new(Instant::now()),
        }
    }

    /// Whether a line is due (an interval has passed since the last one,
    /// or since the start); if so, the clock restarts.
    fn due(&self) -> bool {
        let Ok(mut last) = self.last.lock() else {
            return false;
        };
        let due = last.elapsed() >= self.interval;
        if due {
            *last = Instant::now();
        }
        due
    }

    /// Prints `text` if a line is due.
    fn offer(&self, text: &str) {
        let text = text.trim();
        if !text.is_empty() && self.due() {
            eprintln!("{text}");
        }
    }
}

impl TermLike for LogLines {
    fn width(&self) -> u16 {
        200
    }

    fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }

    fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }

    fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }

    fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }

    fn write_line(&self, s: &str) -> std::io::Result<()> {
        self.offer(s);
        Ok(())
    }

    fn write_str(&self, s: &str) -> std::io::Result<()> {
        self.offer(s);
        Ok(())
    }

    fn clear_line(&self) -> std::io::Result<()> {
        Ok(())
    }

    fn flush(&self) -> std::io::Result<()> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_line_is_due_once_per_interval() {
        let hourly = LogLines::new(Duration::from_secs(3600));
        assert!(!hourly.due(), "the first line waits one interval");
        let always = LogLines::new(Duration::ZERO);
        assert!(always.due() && always.due());
        assert!(bar(10, "runs", true).is_hidden());
    }
}
