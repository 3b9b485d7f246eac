//! A scene built from `--set` keys alone (no `--preset`, no `--config`)
//! starts from the literature's base (Housner's impact law, no sliding, no
//! vertical motion, a record run as long as its record plus the tail), not
//! from the app's demo scene; and every answer names the impact law and the
//! friction it used.

use std::path::{Path, PathBuf};
use std::process::Command;

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-keys-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn kobe() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/records/kobe-1995.dat")
        .display()
        .to_string()
}

fn summary(out: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json");
    serde_json::from_str(&text).expect("json")
}

/// The cabinet of the issue: 0.5 × 1.8 m under Kobe 1995 scaled to
/// 0.55 g, from keys alone. With the demo's ratio law r = 0.82 and friction
/// 0.4/0.35 it "survived"; under Housner's law without sliding it
/// overturns. The independent check: Housner's r for this block,
/// 1 − 1.5 sin²α with tan α = 0.5/1.8, computed here.
#[test]
fn a_cabinet_from_keys_alone_uses_housner_without_sliding_and_says_so() {
    let dir = tmpdir("cabinet");
    let out = dir.join("out");
    let file = format!("excitation.file_h={}", kobe());
    let o = rocking()
        .args([
            "--batch",
            "--set",
            "block.width=0.5",
            "--set",
            "block.height=1.8",
            "--set",
            "excitation.kind=record",
            "--set",
            &file,
            "--set",
            "excitation.unit_h=m/s2",
            "--set",
            "excitation.pga_h=0.55g",
            "--out",
        ])
        .arg(&out)
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let line = stdout.lines().next().expect("the answer");
    assert!(line.starts_with("overturned at t = "), "{line}");
    let alpha = (0.5f64 / 1.8).atan();
    let r = 1.0 - 1.5 * alpha.sin().powi(2);
    assert!(line.contains(&format!("Housner impact r = {r:.3}")), "{line}");
    assert!(line.ends_with("no friction limit (cannot slide)"), "{line}");

    let s = summary(&out);
    let config = &s["config"];
    assert_eq!(config["impact"]["law"], "housner");
    assert_eq!(config["friction"]["static"], "inf");
    assert_eq!(config["excitation"]["a_v"], 0.0);
    // The record decides the length: no τ_end, the tail instead.
    assert!(config["run"]["tau_end"].is_null(), "{}", config["run"]);
    assert_eq!(config["run"]["tail_s"], 30.0);
    let physical = &s["physical"];
    assert_eq!(physical["impact_law"], "housner");
    assert!((physical["impact_r"].as_f64().unwrap() - r).abs() < 1e-15);
    assert!(physical["friction_static"].is_null(), "{physical}");
    assert!(physical["friction_kinetic"].is_null(), "{physical}");
}

/// A friction given with the keys is used, and named.
#[test]
fn friction_given_with_the_keys_is_used_and_named() {
    let dir = tmpdir("friction");
    let out = dir.join("out");
    let o = rocking()
        .args([
            "--batch",
            "--set",
            "excitation.a_h=0.5",
            "--set",
            "friction.static=0.3",
            "--set",
            "friction.kinetic=0.25",
            "--set",
            "run.tau_end=20",
            "--out",
        ])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line = stdout.lines().next().expect("the answer");
    assert!(line.ends_with("friction μ_s = 0.3, μ_k = 0.25"), "{line}");
    let physical = &summary(&out)["physical"];
    assert_eq!(physical["friction_static"], 0.3);
    assert_eq!(physical["friction_kinetic"], 0.25);
    // No vertical motion unless asked for: the demo's A_v = 2.5 is not here.
    assert_eq!(summary(&out)["config"]["excitation"]["a_v"], 0.0);
}

/// Without any key, `--batch` is the app's scene: the `default` preset,
/// whose answer names its own law.
#[test]
fn batch_without_keys_is_the_default_preset() {
    let dir = tmpdir("none");
    let out = dir.join("out");
    let o = rocking()
        .args(["--batch", "--out"])
        .arg(&out)
        .args(["--quiet"])
        .output()
        .expect("runs");
    assert!(o.status.success(), "stderr: {}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&out);
    assert_eq!(s["config"]["impact"]["law"], "ratio");
    assert_eq!(s["config"]["excitation"]["a_v"], 2.5);
}

/// The scene from keys is the scenario's own defaults: the same base the
/// engineering commands take without `--preset`/`--config`.
#[test]
fn keys_alone_and_the_engineering_base_are_one_definition() {
    let sets = vec!["block.width=0.5".to_string()];
    let from_keys = rocking::io::config::load(None, None, &sets).expect("scene");
    let base = rocking::sim::Scenario::default();
    assert_eq!(from_keys.impact, base.impact);
    assert_eq!(from_keys.excitation, base.excitation);
    assert_eq!(from_keys.run, base.run);
    assert_eq!(from_keys.block.mu_s, base.block.mu_s);
    assert_eq!(from_keys.block.width, 0.5);
}
