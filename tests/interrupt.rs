//! An interrupted command leaves no partial output: Ctrl-C (SIGINT) or
//! `kill` (SIGTERM) during a long `--batch` removes its hidden staging
//! folder `.NAME.partial-PID`, and the process ends by that signal (a
//! shell shows 130 or 143).

#![cfg(unix)]

use std::os::unix::process::ExitStatusExt as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-interrupt-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn entries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Starts a `--batch` run long enough to be interrupted, waits until its
/// staging folder holds data, sends `signal` (a `kill` name) and returns
/// how it ended, with the folder's entries after.
fn interrupt(name: &str, signal: &str) -> (std::process::ExitStatus, Vec<String>) {
    let dir = tmpdir(name);
    let mut child = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args([
            "--batch",
            "--preset",
            "default",
            "--set",
            "run.tau_end=1e6",
            "-q",
            "--out",
        ])
        .arg(dir.join("out"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let partial = dir.join(format!(".out.partial-{}", child.id()));
    let start = Instant::now();
    // Until the staging folder holds data.
    while !partial.is_dir() || entries(&partial).is_empty() {
        assert!(start.elapsed() < Duration::from_secs(60), "no {}", partial.display());
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it was interrupted"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // Let it write for a moment, as a user would.
    std::thread::sleep(Duration::from_millis(300));
    let killed = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("SIG{signal} did not end the run");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let left = entries(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    (status, left)
}

#[test]
fn sigint_removes_the_partial_output_and_ends_by_sigint() {
    let (status, left) = interrupt("int", "INT");
    assert!(left.is_empty(), "left behind: {left:?}");
    assert_eq!(status.signal(), Some(2), "{status:?}");
}

#[test]
fn sigterm_removes_the_partial_output_and_ends_by_sigterm() {
    let (status, left) = interrupt("term", "TERM");
    assert!(left.is_empty(), "left behind: {left:?}");
    assert_eq!(status.signal(), Some(15), "{status:?}");
}
