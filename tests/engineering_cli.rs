//! The engineering commands (issue 14, "Engineering analyses") run as a
//! user runs them: `rocking spectrum`, `rocking pulse-map`,
//! `rocking fragility` and `rocking merge` of fragility shards. Outputs,
//! byte-identical results for any thread count and for shards + merge,
//! and bad input refused with one line naming the flag, file or line, exit
//! 2, nothing written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");
const KOBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/kobe-1995.dat");

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-eng-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exit 2, a one-line error containing every needle, and nothing at `out`.
fn refused(o: &Output, needles: &[&str], out: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
    }
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    assert!(!out.exists(), "{} was written", out.display());
}

/// The CSV `text` as rows of cells, header first.
fn cells(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

fn column(rows: &[Vec<String>], name: &str) -> Vec<String> {
    let i = rows[0]
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows[1..].iter().map(|r| r[i].clone()).collect()
}

fn spectrum(out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "0.1", "--to", "5", "--count", "12",
        ])
        .args(["--b-over-h", "0.2", "-q", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

#[test]
fn spectrum_of_el_centro_small_blocks_overturn_large_ones_survive() {
    let dir = tmpdir("spectrum");
    let out = dir.join("out");
    ok(&spectrum(
        &out,
        &["--overturn-scale", "--search-step", "0.25", "--search-max", "2"],
    ));
    for f in [
        "spectrum.csv",
        "safe_windows.csv",
        "spectrum.json",
        "spectrum.png",
        "spectrum.svg",
        "overturn_scale.png",
        "overturn_scale.svg",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let text = std::fs::read_to_string(out.join("spectrum.csv")).unwrap();
    assert!(!text.contains("NaN") && !text.contains("inf"));
    let rows = cells(&text);
    assert_eq!(rows.len(), 13);
    let end = column(&rows, "end");
    let t = column(&rows, "t_overturn_s");
    let peak: Vec<f64> = column(&rows, "peak_theta_over_alpha")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    // R = 0.1 m (p = 8.6/s) overturns under El Centro at B/H = 0.2; R = 5 m
    // barely rocks (Housner's size effect).
    assert_eq!(end[0], "overturned");
    assert!(end[11] == "rest" || end[11] == "moving", "{}", end[11]);
    assert!(peak[11] < 0.5 && peak[11] > 0.0, "{}", peak[11]);
    for (e, t) in end.iter().zip(&t) {
        assert_eq!(e == "overturned", !t.is_empty(), "{e} {t}");
    }
    // p falls as R grows, and the PGA column is the record's 0.349 g.
    let p: Vec<f64> = column(&rows, "p_per_s").iter().map(|v| v.parse().unwrap()).collect();
    assert!(p.windows(2).all(|w| w[1] < w[0]));
    assert!(
        column(&rows, "pga_g")
            .iter()
            .all(|v| (v.parse::<f64>().unwrap() - 0.349).abs() < 1e-3)
    );
    // The overturning scale of the smallest block is at most 1 (it
    // overturned at scale 1) and above the uplift scale tan α/PGA.
    let s0: f64 = column(&rows, "overturn_scale")[0].parse().unwrap();
    assert!(s0 <= 1.0 && s0 > 0.2 / 0.349, "{s0}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("spectrum.json")).unwrap()).unwrap();
    assert_eq!(json["motion"]["unit"], "g");
    assert_eq!(json["summary"][0]["blocks"], 12);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spectrum_is_byte_identical_for_one_and_two_threads() {
    let dir = tmpdir("spectrum-threads");
    let (a, b) = (dir.join("a"), dir.join("b"));
    ok(&spectrum(
        &a,
        &[
            "--threads",
            "1",
            "--overturn-scale",
            "--search-step",
            "0.5",
            "--search-max",
            "2",
        ],
    ));
    ok(&spectrum(
        &b,
        &[
            "--threads",
            "2",
            "--overturn-scale",
            "--search-step",
            "0.5",
            "--search-max",
            "2",
        ],
    ));
    for f in [
        "spectrum.csv",
        "safe_windows.csv",
        "spectrum.json",
        "spectrum.svg",
        "overturn_scale.svg",
    ] {
        assert!(
            std::fs::read(a.join(f)).unwrap() == std::fs::read(b.join(f)).unwrap(),
            "{f} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spectrum_refuses_a_size_range_from_above_to_and_a_record_without_unit() {
    let dir = tmpdir("spectrum-bad");
    let out = dir.join("out");
    let o = rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "2", "--to", "1", "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    refused(&o, &["--to 1", "--from 2"], &out);
    let o = rocking()
        .args(["spectrum", "--record", ELCENTRO, "--from", "0.1", "--to", "1", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    refused(&o, &["--unit", "elcentro-1940-ns.dat"], &out);
    let o = rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "0.1", "--to", "1",
        ])
        .args(["--b-over-h", "0.2,-0.1", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    refused(&o, &["--b-over-h"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pulse_map_minimum_overturning_amplitude_rises_with_frequency() {
    let dir = tmpdir("pulse-map");
    let out = dir.join("out");
    let stdout = ok(&rocking()
        .args([
            "pulse-map",
            "--pulse",
            "one-sine,type-c",
            "--omega",
            "2,6",
            "--amp-step",
            "0.25",
            "--amp-max",
            "12",
        ])
        .args(["-q", "--out"])
        .arg(&out)
        .output()
        .unwrap());
    assert!(stdout.is_empty());
    let rows = cells(&std::fs::read_to_string(out.join("pulse_map.csv")).unwrap());
    assert_eq!(rows.len(), 5);
    assert_eq!(column(&rows, "pulse"), ["one-sine", "one-sine", "type-c1", "type-c1"]);
    let amp: Vec<f64> = column(&rows, "min_overturn_amplitude")[..2]
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    // Above the uplift amplitude 1 and rising with ω_p/p (Makris & Roussos 2000).
    assert!(amp[0] > 1.0 && amp[1] > amp[0], "{amp:?}");
    // a_p/g = a_p/(g tan α)·tan α with tan α = B/H = 0.2.
    let ap: f64 = column(&rows, "min_overturn_ap_g")[0].parse().unwrap();
    assert!((ap - 0.2 * amp[0]).abs() < 1e-12);
    assert!(out.join("pulse_map.png").is_file() && out.join("safe_windows.csv").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

fn suite_list(dir: &Path) -> PathBuf {
    let list = dir.join("suite.txt");
    std::fs::write(
        &list,
        format!("# El Centro in g, Kobe in m/s2\n{ELCENTRO} g\n{KOBE} m/s2\n"),
    )
    .unwrap();
    list
}

fn fragility(list: &Path, out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args(["fragility", "--suite"])
        .arg(list)
        .args([
            "--levels",
            "0.1:1.5:8",
            "--block",
            "0.6x2.0",
            "--block",
            "0.3x1.2",
            "-q",
            "--out",
        ])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

#[test]
fn fragility_counts_and_fits_both_curves() {
    let dir = tmpdir("fragility");
    let out = dir.join("out");
    ok(&fragility(&suite_list(&dir), &out, &[]));
    let runs = cells(&std::fs::read_to_string(out.join("runs.csv")).unwrap());
    assert_eq!(runs.len(), 1 + 2 * 8 * 2);
    assert_eq!(column(&runs, "record")[..2], ["elcentro-1940-ns", "kobe-1995"]);
    // Kobe's PGA 6.80 m/s2 = 0.693 g: scaled to 0.1 g by 0.1/0.693.
    let scale: f64 = column(&runs, "scale")[1].parse().unwrap();
    assert!((scale - 0.1 * 9.81 / 6.8).abs() < 1e-3, "{scale}");
    let fr = cells(&std::fs::read_to_string(out.join("fractions.csv")).unwrap());
    assert_eq!(fr.len(), 1 + 2 * 8);
    // 0.1 g is below the uplift acceleration g tan α = 0.3 g: nothing moves.
    assert_eq!(column(&fr, "fraction_overturned")[0], "0.0");
    assert_eq!(column(&fr, "fraction_exceeded")[0], "0.0");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fragility.json")).unwrap()).unwrap();
    assert_eq!(json["im"], "pga");
    assert_eq!(json["records"][1]["unit"], "m/s2");
    for fit in json["fits"].as_array().unwrap() {
        // Either a fit with its interval around the median, or why not.
        let o = &fit["overturning"];
        if let Some(m) = o["median"].as_f64() {
            let ci = o["median_ci95"].as_array().unwrap();
            assert!(ci[0].as_f64().unwrap() < m && m < ci[1].as_f64().unwrap());
            assert!(o["beta"].as_f64().unwrap() > 0.0);
            assert_eq!(o["band"].as_array().unwrap().len(), 60);
        } else {
            assert!(o["error"].as_str().unwrap().len() > 10, "{o}");
        }
    }
    assert!(out.join("fragility.png").is_file() && out.join("fragility.svg").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fragility_is_byte_identical_across_threads_and_shards_merged() {
    let dir = tmpdir("fragility-shards");
    let list = suite_list(&dir);
    let (one, two) = (dir.join("one"), dir.join("two"));
    ok(&fragility(&list, &one, &["--threads", "1"]));
    ok(&fragility(&list, &two, &["--threads", "2"]));
    let shard_dirs: Vec<PathBuf> = (0..3)
        .map(|k| {
            let d = dir.join(format!("shard{k}"));
            ok(&fragility(&list, &d, &["--shard", &format!("{k}/3")]));
            assert!(!d.join("fractions.csv").exists(), "a shard writes no fits");
            d
        })
        .collect();
    let merged = dir.join("merged");
    // Any order of the shards.
    ok(&rocking()
        .args(["merge", "-q", "--out"])
        .arg(&merged)
        .args([&shard_dirs[2], &shard_dirs[0], &shard_dirs[1]])
        .output()
        .unwrap());
    for f in [
        "runs.csv",
        "fractions.csv",
        "fragility.json",
        "fragility.svg",
        "fragility.png",
        "incremental.csv",
        "incremental.svg",
        "incremental.png",
    ] {
        let a = std::fs::read(one.join(f)).unwrap();
        assert!(
            a == std::fs::read(two.join(f)).unwrap(),
            "{f}: differs between 1 and 2 threads"
        );
        assert!(
            a == std::fs::read(merged.join(f)).unwrap(),
            "{f}: the merge differs from one run"
        );
    }
    // A missing shard is refused, naming it, and nothing is written.
    let partial = dir.join("partial");
    let o = rocking()
        .args(["merge", "--out"])
        .arg(&partial)
        .args([&shard_dirs[0], &shard_dirs[2]])
        .output()
        .unwrap();
    refused(&o, &["shard 1/3 is missing"], &partial);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fragility_refuses_zero_or_negative_levels() {
    let dir = tmpdir("fragility-levels");
    let list = suite_list(&dir);
    let out = dir.join("out");
    for levels in ["0,0.5", "-0.1,0.5", "0.5:0.1:4"] {
        let o = rocking()
            .args(["fragility", "--suite"])
            .arg(&list)
            .args(["--levels", levels, "--block", "0.6x2.0", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        refused(&o, &["--levels"], &out);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fragility_names_the_file_and_line_of_an_unreadable_suite_entry() {
    let dir = tmpdir("fragility-suite");
    let out = dir.join("out");
    // A suite whose third line names a file that does not exist.
    let list = dir.join("suite.txt");
    std::fs::write(&list, format!("{ELCENTRO} g\n\nmissing.dat g\n")).unwrap();
    let o = fragility(&list, &out, &[]);
    refused(&o, &["suite.txt:3", "missing.dat"], &out);
    // A record with a bad sample on its line 4.
    let bad = dir.join("bad.dat");
    std::fs::write(&bad, "0.0 0.01\n0.02 0.02\n0.04 0.03\n0.06 abc\n").unwrap();
    std::fs::write(&list, "bad.dat g\n").unwrap();
    let o = fragility(&list, &out, &[]);
    refused(&o, &["bad.dat:4"], &out);
    // A suite line with an unknown unit.
    std::fs::write(&list, format!("{ELCENTRO} furlongs\n")).unwrap();
    let o = fragility(&list, &out, &[]);
    refused(&o, &["suite.txt:1", "furlongs"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}
