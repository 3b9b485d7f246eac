//! The `rocking` binary as a user runs it.

use std::path::{Path, PathBuf};
use std::process::Command;

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(String::from).collect();
    let rows = lines.map(|l| l.split(',').map(String::from).collect()).collect();
    (header, rows)
}

const MODES: [&str; 6] = ["rest", "slide", "rock", "slide-rock", "tumbled", "flight"];

/// The default scene (Fig. 12's conditions with r = 0.82): chaotic rocking
/// with sliding that never tumbles (tests/default_scene.rs). Fig. 12's own r = 0.925 wanders
/// chaotically from rest and then tumbles or settles depending on round-off
/// (at τ 56 with this session's numerics), which would cut the files short.
#[test]
fn batch_default_scene_writes_every_file_with_its_columns() {
    let dir = tmpdir("default");
    let out = dir.join("out");
    let o = rocking()
        .args(["--batch", "--preset", "default", "--set", "run.tau_end=120", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));

    let (h, rows) = read_csv(&out.join("events.csv"));
    assert_eq!(
        h,
        [
            "tau",
            "kind",
            "mode_before",
            "mode_after",
            "theta",
            "theta_dot_before",
            "theta_dot_after",
            "x_dot",
            "t_s",
            "theta_rad",
            "sliding_m"
        ]
    );
    assert!(rows.len() > 20);
    let kinds = ["uplift", "slip", "stick", "impact", "rest", "tumble", "flight"];
    let mut last = f64::NEG_INFINITY;
    for r in &rows {
        assert_eq!(r.len(), 11);
        let tau: f64 = r[0].parse().expect("tau");
        assert!(tau > last, "event times increase");
        last = tau;
        assert!(kinds.contains(&r[1].as_str()), "kind {}", r[1]);
        assert!(MODES.contains(&r[2].as_str()) && MODES.contains(&r[3].as_str()));
        for c in &r[4..] {
            assert!(c.parse::<f64>().expect("number").is_finite());
        }
    }
    assert!(rows.iter().any(|r| r[1] == "impact") && rows.iter().any(|r| r[3] == "slide-rock"));

    let (h, rows) = read_csv(&out.join("poincare.csv"));
    assert_eq!(h, ["k", "tau", "theta", "theta_dot", "x", "x_dot", "mode"]);
    let period = std::f64::consts::TAU / 8.0;
    assert!(rows.len() >= 150);
    for (i, r) in rows.iter().enumerate() {
        let k: u64 = r[0].parse().expect("k");
        assert_eq!(k, i as u64);
        let tau: f64 = r[1].parse().expect("tau");
        assert_eq!(tau, k as f64 * period, "strobe time is 2πk/Ω exactly");
        assert!(MODES.contains(&r[6].as_str()));
    }

    let (h, rows) = read_csv(&out.join("history.csv"));
    assert_eq!(
        h,
        [
            "tau",
            "theta",
            "theta_dot",
            "x",
            "x_dot",
            "mode",
            "t_s",
            "theta_rad",
            "sliding_m"
        ]
    );
    assert_eq!(rows.len(), 6001, "τ 0..120 every 0.02");
    for r in &rows {
        for c in r[..5].iter().chain(&r[6..]) {
            assert!(c.parse::<f64>().expect("number").is_finite());
        }
    }

    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    for key in [
        "outcome",
        "tau_end",
        "tumble_tau",
        "max_abs_theta",
        "impacts",
        "mode_time",
        "energy",
        "solver",
        "config",
        "version",
    ] {
        assert!(s.get(key).is_some(), "summary.json lacks {key}");
    }
    assert_eq!(s["config"]["friction"]["static"], 0.4);
    assert_eq!(s["config"]["run"]["tau_end"], 120.0);
    assert_eq!(s["config"]["impact"]["law"], "ratio");
    for k in ["rest", "slide", "rock", "slide-rock"] {
        assert!(s["mode_time"][k].is_number());
    }
    for k in [
        "initial",
        "final",
        "work_base",
        "loss_friction",
        "loss_impact",
        "residual",
    ] {
        assert!(s["energy"][k].is_number(), "energy.{k}");
    }
    assert!(s["energy"]["relative_residual"].as_f64().expect("residual") < 1e-6);
    for k in ["steps", "rhs_evals", "wall_s"] {
        assert!(s["solver"][k].is_number());
    }

    // The summary repeats the run.
    let again = dir.join("again");
    let o = rocking()
        .args(["--batch", "--config"])
        .arg(out.join("summary.json"))
        .arg("--out")
        .arg(&again)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    for f in ["events.csv", "poincare.csv", "history.csv"] {
        assert_eq!(
            std::fs::read(out.join(f)).expect("first"),
            std::fs::read(again.join(f)).expect("second"),
            "{f} differs when repeated from summary.json"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `--batch` with `args`; it must fail with exit code 2, a one-line
/// error containing `needle`, and write nothing.
fn rejects(args: &[&str], needle: &str) {
    let dir = tmpdir(&needle.replace(['/', ' ', '.', '"'], "_"));
    let out = dir.join("out");
    let o = rocking()
        .arg("--batch")
        .args(args)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "args {args:?}: stderr {err}");
    assert!(
        err.contains(needle),
        "args {args:?}: error {err:?} does not name {needle:?}"
    );
    assert_eq!(err.trim().lines().count(), 1, "one-line error, got {err:?}");
    assert!(!out.exists(), "args {args:?}: output directory was created");
    let leftovers: Vec<_> = std::fs::read_dir(&dir).expect("dir").collect();
    assert!(leftovers.is_empty(), "args {args:?}: left {leftovers:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_is_refused_with_exit_2_and_nothing_written() {
    rejects(&["--set", "block.widht=2"], "block.widht");
    rejects(&["--set", "block.width=-1"], "block.width");
    rejects(&["--set", "block.height=abc"], "block.height");
    rejects(
        &["--set", "friction.static=0.3", "--set", "friction.kinetic=0.4"],
        "friction.kinetic",
    );
    rejects(&["--set", "impact.r=1.5"], "impact.r");
    rejects(&["--set", "impact.law=elastic"], "impact.law");
    rejects(&["--set", "run.rtol=0"], "run.rtol");
    rejects(&["--set", "run.atol=2"], "run.atol");
    rejects(&["--set", "excitation.a_h=nan"], "excitation.a_h");
    rejects(&["--set", "excitation.omega_h=inf"], "excitation.omega_h");
    rejects(&["--set", "run.method=euler"], "run.method");
    rejects(&["--set", "nosuch.key=1"], "nosuch");
    rejects(&["--set", "justakey"], "KEY=VALUE");
    rejects(&["--preset", "fig99"], "fig99");
    rejects(&["--config", "/nonexistent/rocking.toml"], "/nonexistent/rocking.toml");
    rejects(
        &[
            "--set",
            "excitation.kind=record",
            "--set",
            "excitation.file_h=/nonexistent.AT2",
        ],
        "/nonexistent.AT2",
    );
}

#[test]
fn malformed_files_are_named_with_their_line() {
    let dir = tmpdir("malformed");
    let cfg = dir.join("bad.toml");
    std::fs::write(&cfg, "[block]\nwidth = 1.0\nheight = = 4\n").expect("write");
    rejects(&["--config", cfg.to_str().expect("utf8")], "bad.toml:3");
    let cfg2 = dir.join("rec.toml");
    let bad = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bad_line.txt");
    std::fs::write(
        &cfg2,
        format!("[excitation]\nkind = \"record\"\nfile_h = \"{bad}\"\nunit_h = \"g\"\n"),
    )
    .expect("write");
    rejects(&["--config", cfg2.to_str().expect("utf8")], "bad_line.txt:4");
    rejects(&["--config", dir.to_str().expect("utf8")], "is a directory");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn record_run_from_an_at2_file() {
    let dir = tmpdir("record");
    let out = dir.join("out");
    let at2 = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sample.AT2");
    let o = rocking()
        .args(["--batch", "--set", "excitation.kind=record", "--set"])
        .arg(format!("excitation.file_h=\"{at2}\""))
        .args([
            "--set",
            "excitation.scale_h=3",
            "--set",
            "block.width=0.5",
            "--set",
            "block.height=1.0",
        ])
        .args(["--set", "run.tau_end=10", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    assert_eq!(s["config"]["excitation"]["kind"], "record");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unwritable_output_is_refused_before_running() {
    // A path below a regular file can never be created (even as root, which
    // ignores permission bits).
    let dir = tmpdir("unwritable");
    let file = dir.join("plain-file");
    std::fs::write(&file, b"not a directory").expect("write");
    for out in [file.join("out"), file.clone()] {
        let o = rocking()
            .args(["--batch", "--preset", "fig12", "--set", "run.tau_end=5", "--out"])
            .arg(&out)
            .output()
            .expect("runs");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("--out"), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
    assert_eq!(std::fs::read(&file).expect("read"), b"not a directory");
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn closed_stdout_is_not_a_panic() {
    use std::process::Stdio;
    let mut child = rocking()
        .arg("--list-presets")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("wait");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bench_writes_the_work_precision_files() {
    let dir = tmpdir("bench");
    let out = dir.join("out");
    let o = rocking()
        .args(["bench", "--scene", "free", "--repeats", "1", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let (h, rows) = read_csv(&out.join("work_precision.csv"));
    assert_eq!(
        h[..7],
        ["scene", "method", "setting", "wall_s", "rhs_evals", "steps", "error"]
    );
    for m in ["dop853", "dopri5", "ralston"] {
        assert!(rows.iter().any(|r| r[1] == m), "no {m} record");
    }
    // Tighter tolerances give smaller errors: DOP853 at rtol 1e-12 beats 1e-4.
    let err = |m: &str, s: &str| {
        rows.iter()
            .find(|r| r[1] == m && r[2] == s)
            .map(|r| r[6].parse::<f64>().expect("error"))
            .expect("record")
    };
    assert!(err("dop853", "1e-12") < 1e-3 * err("dop853", "0.0001"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("work_precision.json")).expect("json")).expect("parse");
    assert!(json["records"].as_array().is_some_and(|r| r.len() == rows.len()));
    assert!(json["references"][0]["self_check"].as_f64().expect("self check") < 1e-9);
    for f in ["work_precision.png", "work_precision.svg"] {
        assert!(std::fs::metadata(out.join(f)).expect(f).len() > 1000);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_rejects_an_unknown_scene() {
    let dir = tmpdir("bench-bad");
    let out = dir.join("out");
    let o = rocking()
        .args(["bench", "--scene", "nosuch", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--scene nosuch"));
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn batch_spectrum_of_a_period_one_response_peaks_at_the_forcing_harmonics() {
    let dir = tmpdir("spectrum");
    let out = dir.join("out");
    let o = rocking()
        .args([
            "--batch",
            "--preset",
            "fig4",
            "--set",
            "excitation.a_v=1.0",
            "--set",
            "analysis.spectrum=true",
        ])
        .args(["--set", "run.tau_end=400", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let (h, rows) = read_csv(&out.join("spectrum.csv"));
    assert_eq!(h, ["freq", "omega", "omega_over_omega_h", "psd"]);
    assert!(rows.len() > 1000);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    let peaks = s["spectrum"]["peaks"].as_array().expect("peaks");
    let top = peaks[0]["harmonic"].as_f64().expect("harmonic");
    assert!((top - 1.0).abs() < 0.01, "dominant peak at ω/Ω_h = {top}");
    for p in peaks.iter().take(3) {
        let k = p["harmonic"].as_f64().expect("harmonic");
        assert!(
            (k - k.round()).abs() < 0.01,
            "a period-1 response has only forcing harmonics, got {k}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Without a display the app says so in one line with the headless command
/// and exits 2 (issue "The app for a lecture hall": robustness); `--help`
/// says that no arguments opens the app.
#[test]
fn without_a_display_the_app_points_to_batch() {
    let o = rocking()
        .args(["--preset", "kobe-rack"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("rocking --batch"), "{err}");
    let help = rocking().arg("--help").output().expect("runs");
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(
        text.contains("With no --batch and no subcommand, rocking opens the desktop app"),
        "{text}"
    );
}

/// A bad record is reported before the app's window would open, like every
/// other config error (issue "Nothing lost", item 12): exit 2, one line
/// naming the key and file. (A build without the app reads no scene.)
#[cfg(feature = "gui")]
#[test]
fn the_app_reports_a_bad_record_before_its_window() {
    let o = rocking()
        .args([
            "--set",
            "excitation.kind=record",
            "--set",
            "excitation.file_h=/nonexistent/record.txt",
            "--set",
            "excitation.unit_h=g",
        ])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("excitation.file_h: /nonexistent/record.txt"), "{err}");
}

/// `--paused` is for the app; with `--batch` it is refused, not ignored.
#[test]
fn paused_is_refused_with_batch() {
    let o = rocking().args(["--batch", "--paused"]).output().expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("'--paused'") && err.contains("'--batch'"), "{err}");
}

/// Every phenomenon preset runs headless too, as its header says.
#[test]
fn the_phenomenon_presets_run_headless_as_their_headers_say() {
    let dir = std::env::temp_dir().join(format!("rocking-phenomena-{}", std::process::id()));
    let o = rocking()
        .args(["--batch", "--preset", "free-rocking", "--out"])
        .arg(&dir)
        .output()
        .expect("runs");
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{out}");
    // 124 impacts, at rest by t = 11.2 s, and no sliding: released
    // tilted about its corner, it has not slid at all.
    assert!(out.contains("no sliding; at rest from t = 11.2"), "{out}");
    assert!(out.contains("impacts 124 "), "{out}");
    std::fs::remove_dir_all(&dir).unwrap();
}
