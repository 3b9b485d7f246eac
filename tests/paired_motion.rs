//! Paired horizontal and vertical motion in the engineering commands:
//! a suite line `H [UNIT] + V [UNIT]` and `spectrum --record-v`, both
//! components scaled by one factor set by the horizontal's intensity, and
//! `--vertical none|record` choosing. Checked against the uplift condition
//! of a block on a base accelerating both ways, written here:
//! |a_h| > tan α (g + a_v), a_v positive upward (docs/model.md).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-hv-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exit 2, one line naming every needle, nothing at `out`.
fn refused(o: &Output, needles: &[&str], out: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
    }
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    assert!(!out.exists(), "{} was written", out.display());
}

/// A step record: 0 at t = 0, `level` g from 1 ms on, for 2 s.
fn step(dir: &Path, name: &str, level: f64) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, format!("0 0\n0.001 {level}\n2.0 {level}\n")).expect("write");
    p
}

/// Column `name` of the CSV `text`.
fn column(text: &str, name: &str) -> Vec<String> {
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let i = rows[0]
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows[1..].iter().map(|r| r[i].to_string()).collect()
}

/// tan α of the 0.5 × 2.0 m block of these tests.
const TAN_ALPHA: f64 = 0.25;
/// Horizontal step, g (its PGA, so the scale of a run is its level).
const A_H: f64 = 1.0;
/// Vertical step, g: downward, lowering the uplift threshold.
const A_V: f64 = -0.4;

/// Whether the block lifts off at scale `s` by the closed form: the
/// horizontal overcomes tan α times the apparent gravity g + a_v.
fn uplifts(s: f64, with_vertical: bool) -> bool {
    let a_v = if with_vertical { s * A_V } else { 0.0 };
    s * A_H > TAN_ALPHA * (1.0 + a_v)
}

fn fragility(dir: &Path, out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args([
            "fragility",
            "--levels",
            "0.20,0.24,0.26",
            "--block",
            "0.5x2.0",
            "-q",
            "--suite",
        ])
        .arg(dir.join("suite.txt"))
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

#[test]
fn a_suite_with_and_without_its_vertical_differs_only_where_the_vertical_moves_the_uplift_threshold() {
    let dir = tmpdir("threshold");
    step(&dir, "h.dat", A_H);
    step(&dir, "v.dat", A_V);
    std::fs::write(dir.join("suite.txt"), "# a step pair\nh.dat g + v.dat g\n").expect("write");
    let levels = [0.20, 0.24, 0.26];
    // The closed form puts the thresholds at 0.25 g (horizontal only) and
    // 0.25 / (1 + 0.25·0.4) = 0.2273 g (with the vertical): the middle level
    // lies between them.
    assert_eq!(levels.map(|s| uplifts(s, false)), [false, false, true]);
    assert_eq!(levels.map(|s| uplifts(s, true)), [false, true, true]);

    let with = dir.join("with");
    let text = ok(&fragility(&dir, &with, &[]));
    assert!(text.is_empty(), "-q prints nothing: {text}");
    let runs = std::fs::read_to_string(with.join("runs.csv")).expect("runs.csv");
    let peaks: Vec<f64> = column(&runs, "peak_theta_over_alpha")
        .iter()
        .map(|v| v.parse().expect("number"))
        .collect();
    assert_eq!(
        peaks.iter().map(|&p| p > 0.0).collect::<Vec<_>>(),
        levels.map(|s| uplifts(s, true))
    );
    // Both components scaled by one factor: level / the horizontal's PGA.
    for (k, &level) in levels.iter().enumerate() {
        let h: f64 = column(&runs, "pga_h_g")[k].parse().expect("number");
        let v: f64 = column(&runs, "pga_v_g")[k].parse().expect("number");
        assert!((h - level).abs() < 1e-15, "{h} vs {level}");
        assert!((v - level * A_V.abs() / A_H).abs() < 1e-15, "{v}");
    }
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(with.join("fragility.json")).expect("json")).expect("json");
    assert_eq!(meta["vertical"], "record");
    assert_eq!(meta["records"][0]["vertical"]["pga_g"], 0.4);
    assert!(meta["scaling"].as_str().unwrap_or_default().contains("one factor"));
    // The figures say the verticals ran.
    for svg in ["fragility.svg", "incremental.svg"] {
        let text = std::fs::read_to_string(with.join(svg)).expect("svg");
        assert!(text.contains("with each record") && text.contains("vertical"), "{svg}");
    }

    let without = dir.join("without");
    ok(&fragility(&dir, &without, &["--vertical", "none"]));
    let runs = std::fs::read_to_string(without.join("runs.csv")).expect("runs.csv");
    let peaks_h: Vec<f64> = column(&runs, "peak_theta_over_alpha")
        .iter()
        .map(|v| v.parse().expect("number"))
        .collect();
    assert_eq!(
        peaks_h.iter().map(|&p| p > 0.0).collect::<Vec<_>>(),
        levels.map(|s| uplifts(s, false))
    );
    assert_eq!(column(&runs, "pga_v_g"), ["", "", ""]);
    // Where neither lifts off, the vertical changes nothing.
    assert_eq!((peaks[0], peaks_h[0]), (0.0, 0.0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_suite_that_names_verticals_for_some_records_only_must_say_which_study_it_means() {
    let dir = tmpdir("mixed");
    step(&dir, "h1.dat", A_H);
    step(&dir, "h2.dat", 0.5);
    step(&dir, "v1.dat", A_V);
    std::fs::write(dir.join("suite.txt"), "h1.dat g + v1.dat g\nh2.dat g\n").expect("write");
    let out = dir.join("out");
    let o = fragility(&dir, &out, &[]);
    refused(&o, &["suite.txt:1", "suite.txt:2", "--vertical none"], &out);
    let o = fragility(&dir, &out, &["--vertical", "record"]);
    refused(&o, &["--vertical record", "suite.txt:2", "names no vertical"], &out);
    // Horizontals only is a study of its own.
    ok(&fragility(&dir, &out, &["--vertical", "none"]));
    // A record cannot be its own vertical, nor be listed twice.
    std::fs::write(dir.join("suite.txt"), "h1.dat g + h1.dat g\n").expect("write");
    let out2 = dir.join("out2");
    let o = fragility(&dir, &out2, &[]);
    refused(&o, &["suite.txt:1", "its own vertical"], &out2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_spectrum_with_a_vertical_record_scales_it_with_the_horizontal_and_reports_both_pgas() {
    let dir = tmpdir("spectrum");
    let h = step(&dir, "h.dat", A_H);
    let v = step(&dir, "v.dat", A_V);
    let run = |out: &Path, extra: &[&str]| {
        rocking()
            .args([
                "spectrum", "--unit", "g", "--size", "h", "--from", "2", "--to", "2", "--count", "1",
            ])
            .args(["--b-over-h", "0.25", "--pga", "0.24", "-q", "--record"])
            .arg(&h)
            .arg("--out")
            .arg(out)
            .args(extra)
            .output()
            .expect("runs")
    };
    let peak = |out: &Path| -> f64 {
        let csv = std::fs::read_to_string(out.join("spectrum.csv")).expect("csv");
        column(&csv, "peak_theta_over_alpha")[0].parse().expect("number")
    };
    let with = dir.join("with");
    ok(&run(&with, &["--record-v", v.to_str().expect("utf-8")]));
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(with.join("spectrum.json")).expect("json")).expect("json");
    assert_eq!(meta["vertical"], "record");
    assert!((meta["pga_g"].as_f64().expect("pga") - 0.24).abs() < 1e-15);
    assert!((meta["pga_v_g"].as_f64().expect("pga_v") - 0.24 * 0.4).abs() < 1e-15);
    assert_eq!(meta["motion"]["vertical"]["pga_g"], 0.4);
    // 0.24 g lies between the two thresholds (see the fragility test).
    assert!(uplifts(0.24, true) && !uplifts(0.24, false));
    assert!(peak(&with) > 0.0);
    let without = dir.join("without");
    ok(&run(
        &without,
        &["--record-v", v.to_str().expect("utf-8"), "--vertical", "none"],
    ));
    assert_eq!(peak(&without), 0.0);
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(without.join("spectrum.json")).expect("json")).expect("json");
    assert_eq!(meta["vertical"], "none");
    assert!(meta["pga_v_g"].is_null());
    let out = dir.join("bad");
    let o = run(&out, &["--vertical", "record"]);
    refused(&o, &["--vertical record", "--record-v"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_rocking_intensity_measures_scale_each_block_by_its_own_uplift_acceleration_and_velocity() {
    let dir = tmpdir("im");
    step(&dir, "h.dat", 0.5);
    // A triangle 0 → 0.5 g at 0.5 s → 0 at 1 s: PGV = 0.5 g · 1 s / 2.
    std::fs::write(dir.join("tri.dat"), "0 0\n0.5 0.5\n1.0 0\n").expect("write");
    std::fs::write(dir.join("suite.txt"), "h.dat g\n").expect("write");
    let blocks = [(0.5, 2.0), (0.3, 1.5)];
    let run = |im: &str, levels: &str, suite: &str, out: &Path| {
        std::fs::write(dir.join("suite.txt"), suite).expect("write");
        rocking()
            .args(["fragility", "--im", im, "--levels", levels, "-q", "--suite"])
            .arg(dir.join("suite.txt"))
            .args(["--block", "0.5x2.0", "--block", "0.3x1.5", "--out"])
            .arg(out)
            .output()
            .expect("runs")
    };
    // PGA/(g tan α) = 1 is each block's static uplift threshold, whatever
    // its size and slenderness: a step just below stays at rest, just
    // above rocks.
    let out = dir.join("pga");
    ok(&run("pga-tan-alpha", "0.99,1.01", "h.dat g\n", &out));
    let runs = std::fs::read_to_string(out.join("runs.csv")).expect("runs");
    let peaks: Vec<bool> = column(&runs, "peak_theta_over_alpha")
        .iter()
        .map(|v| v.parse::<f64>().expect("number") > 0.0)
        .collect();
    assert_eq!(peaks, [false, true, false, true]);
    let scales: Vec<f64> = column(&runs, "scale")
        .iter()
        .map(|v| v.parse().expect("number"))
        .collect();
    for (k, (level, (b, h))) in [
        (0.99, blocks[0]),
        (1.01, blocks[0]),
        (0.99, blocks[1]),
        (1.01, blocks[1]),
    ]
    .into_iter()
    .enumerate()
    {
        let expected = level * (b / h) / 0.5;
        assert!(
            (scales[k] - expected).abs() < 1e-15 * expected,
            "{} vs {expected}",
            scales[k]
        );
    }
    assert_eq!(column(&runs, "im")[0], "pga_over_g_tan_alpha");
    // PGV·p/(g tan α): scale = level · g tan α / (PGV · p), p = √(3g/(4R)).
    let out = dir.join("pgv");
    ok(&run("pgv-p-tan-alpha", "2", "tri.dat g\n", &out));
    let runs = std::fs::read_to_string(out.join("runs.csv")).expect("runs");
    let scales: Vec<f64> = column(&runs, "scale")
        .iter()
        .map(|v| v.parse().expect("number"))
        .collect();
    let g = 9.81;
    let pgv = 0.5 * g * 1.0 / 2.0;
    for (k, (b, h)) in blocks.into_iter().enumerate() {
        let p = (3.0 * g / (4.0 * 0.5 * b.hypot(h))).sqrt();
        let expected = 2.0 * g * (b / h) / (pgv * p);
        assert!(
            (scales[k] - expected).abs() < 1e-12 * expected,
            "{} vs {expected}",
            scales[k]
        );
    }
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fragility.json")).expect("json")).expect("json");
    assert_eq!(meta["im"], "pgv-p-tan-alpha");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sa_scales_each_record_by_its_pseudo_spectral_acceleration_at_the_stated_period() {
    let dir = tmpdir("sa");
    // A step of 0.3 g from t = 0 held for 2 s: an oscillator from rest
    // overshoots to u = (a/ω²)(1 + e^{−ζπ/√(1−ζ²)}) at t = π/ω_d (0.25 s
    // at T = 0.5 s, well inside the record), so Sa = a (1 + e^{−ζπ/√(1−ζ²)}).
    std::fs::write(dir.join("step.dat"), "0 0.3\n2.0 0.3\n").expect("write");
    std::fs::write(dir.join("suite.txt"), "step.dat g\n").expect("write");
    let zeta: f64 = 0.05;
    let sa = 0.3 * (1.0 + (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp());
    let out = dir.join("out");
    let run = |out: &Path, extra: &[&str]| {
        rocking()
            .args([
                "fragility",
                "--levels",
                "0.2,0.5",
                "--block",
                "0.5x2.0",
                "-q",
                "--suite",
            ])
            .arg(dir.join("suite.txt"))
            .arg("--out")
            .arg(out)
            .args(extra)
            .output()
            .expect("runs")
    };
    ok(&run(&out, &["--im", "sa", "--sa-period", "0.5"]));
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fragility.json")).expect("json")).expect("json");
    let got = meta["records"][0]["sa_g"].as_f64().expect("sa_g");
    assert!((got - sa).abs() < 1e-12, "{got} vs {sa}");
    assert_eq!(meta["im"], "sa");
    assert_eq!(meta["sa_period_s"], 0.5);
    let runs = std::fs::read_to_string(out.join("runs.csv")).expect("runs");
    let scales: Vec<f64> = column(&runs, "scale")
        .iter()
        .map(|v| v.parse().expect("number"))
        .collect();
    assert!((scales[1] - 0.5 / sa).abs() < 1e-12, "{}", scales[1]);
    assert_eq!(column(&runs, "im")[0], "sa_g");
    let bad = dir.join("bad");
    refused(&run(&bad, &["--im", "sa"]), &["--im sa", "--sa-period"], &bad);
    refused(
        &run(&bad, &["--sa-period", "1"]),
        &["--sa-period 1", "only with --im sa"],
        &bad,
    );
    refused(
        &run(&bad, &["--im", "sa", "--sa-period", "-1"]),
        &["--sa-period -1"],
        &bad,
    );
    let _ = std::fs::remove_dir_all(&dir);
}
