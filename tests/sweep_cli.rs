//! `rocking sweep`, `rocking merge` and `rocking map` as a user runs them:
//! the files and their columns, bit-identical output for any thread count
//! and with sharding + merge, and bad input (exit 2, the flag named,
//! nothing written).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-sweep-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// A short Fig. 4 sweep through periods 2 and 4, chaos and tumbling: 8
/// values A_v = 1.9, 2.1, …, 3.3, window τ 100..160 (77 section points
/// each). From 2.7 on the block tumbles well inside the window; the chaotic
/// values in between end in a tumble or not depending on round-off, so the
/// grid keeps clear of them for that check.
const SWEEP: [&str; 16] = [
    "sweep",
    "--preset",
    "fig4",
    "--param",
    "excitation.a_v",
    "--from",
    "1.9",
    "--to",
    "3.3",
    "--step",
    "0.2",
    "--transient",
    "100",
    "--tau-end",
    "160",
    "-q",
];

fn run(args: &[&str], out: &Path) -> Output {
    rocking().args(args).arg("--out").arg(out).output().expect("runs")
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "status {:?}, stderr: {}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn sweep_writes_its_files_with_their_columns() {
    let dir = tmpdir("files");
    let out = dir.join("out");
    ok(&run(&SWEEP, &out));
    let names: Vec<String> = files(&out).into_iter().map(|f| f.0).collect();
    assert_eq!(
        names,
        [
            "bifurcation.png",
            "bifurcation.svg",
            "classes.csv",
            "points.csv",
            "sweep.json"
        ]
    );
    let classes = std::fs::read_to_string(out.join("classes.csv")).unwrap();
    let mut lines = classes.lines();
    assert_eq!(lines.next(), Some("value,outcome,period,max_abs_theta,lyapunov"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 8);
    let names = ["periodic", "quasiperiodic", "chaotic", "tumbled", "rest", "flight"];
    for r in &rows {
        assert_eq!(r.len(), 5);
        assert!(names.contains(&r[1]), "{r:?}");
        assert_eq!(r[2].is_empty(), r[1] != "periodic");
        assert!(r[4].is_empty(), "no Lyapunov exponent without the hook");
    }
    assert_eq!(rows[0][..3], ["1.9", "periodic", "2"]);
    let points = std::fs::read_to_string(out.join("points.csv")).unwrap();
    let mut lines = points.lines();
    assert_eq!(lines.next(), Some("value,k,tau,theta,theta_dot"));
    let tumbled: Vec<&str> = rows.iter().filter(|r| r[1] == "tumbled").map(|r| r[0]).collect();
    assert!(!tumbled.is_empty());
    for l in lines {
        let f: Vec<&str> = l.split(',').collect();
        assert_eq!(f.len(), 5);
        assert!(!tumbled.contains(&f[0]), "tumbled values are blank");
        assert!(f[2].parse::<f64>().unwrap() >= 100.0);
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["param"], "excitation.a_v");
    assert_eq!(json["grid"]["count"], 8);
    assert_eq!(json["window"]["transient"], 100.0);
    assert_eq!(json["config"]["run"]["tau_end"], 160.0);
    assert!(json["shard"].is_null());
    assert_eq!(json["version"], env!("CARGO_PKG_VERSION"));
}

#[test]
fn sweep_output_is_the_same_bytes_for_any_thread_count_and_with_shards_merged() {
    let dir = tmpdir("identical");
    let one = dir.join("one");
    let two = dir.join("two");
    let mut a = SWEEP.to_vec();
    a.extend(["--threads", "1"]);
    ok(&run(&a, &one));
    let mut b = SWEEP.to_vec();
    b.extend(["--threads", "2"]);
    ok(&run(&b, &two));
    assert_eq!(files(&one), files(&two));

    let mut shard_dirs = Vec::new();
    for k in ["1/3", "0/3", "2/3"] {
        let d = dir.join(format!("shard{}", &k[..1]));
        let mut s = SWEEP.to_vec();
        s.extend(["--shard", k]);
        ok(&run(&s, &d));
        let names: Vec<String> = files(&d).into_iter().map(|f| f.0).collect();
        assert_eq!(names, ["classes.csv", "points.csv", "sweep.json"]);
        shard_dirs.push(d);
    }
    let merged = dir.join("merged");
    let o = rocking()
        .args(["merge", "-q", "--out"])
        .arg(&merged)
        .args(&shard_dirs)
        .output()
        .unwrap();
    ok(&o);
    assert_eq!(files(&merged), files(&one));
}

fn bad(args: &[&str], flag: &str) {
    let dir = tmpdir(&format!("bad-{}", flag.trim_start_matches('-')));
    let out = dir.join("out");
    let o = run(args, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(flag), "{args:?}: stderr names {flag}: {stderr}");
    assert!(!out.exists(), "{args:?}: nothing written");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "{args:?}: nothing staged");
}

fn with(extra: &[&'static str], drop: &[&str]) -> Vec<&'static str> {
    let mut v: Vec<&'static str> = Vec::new();
    let mut skip = 0;
    for a in SWEEP {
        if skip > 0 {
            skip -= 1;
            continue;
        }
        if drop.contains(&a) {
            skip = 1;
            continue;
        }
        v.push(a);
    }
    v.extend(extra);
    v
}

#[test]
fn sweep_rejects_bad_input_naming_the_flag_and_writing_nothing() {
    bad(&with(&["--step", "0"], &["--step"]), "--step");
    bad(&with(&["--step", "-0.1"], &["--step"]), "--step");
    bad(&with(&["--to", "1"], &["--to"]), "--to");
    bad(&with(&["--from", "nan"], &["--from"]), "--from");
    bad(&with(&["--shard", "3/3"], &[]), "--shard");
    bad(&with(&["--shard", "x"], &[]), "--shard");
    bad(&with(&["--shard", "0/2", "--continuation", "up"], &[]), "--shard");
    bad(&with(&["--param", "excitation.nope"], &["--param"]), "excitation.nope");
    bad(&with(&["--param", "impact.law"], &["--param"]), "impact.law");
    bad(&with(&["--param", "run.tau_end"], &["--param"]), "--param run.tau_end");
    bad(&with(&["--transient", "200"], &["--transient"]), "--tau-end");
    bad(&with(&["--transient", "150"], &["--transient"]), "--transient");
    bad(&with(&["--threads", "0"], &[]), "--threads");
    bad(&with(&["--set", "excitation.kind=pulse"], &[]), "excitation.kind");
    bad(&with(&["--preset", "nope"], &["--preset"]), "--preset nope");
    // A value out of the key's range, named with the value.
    bad(
        &with(
            &["--param", "excitation.omega_h", "--from", "-1"],
            &["--param", "--from"],
        ),
        "excitation.omega_h",
    );
}

#[test]
fn merge_rejects_shards_of_different_sweeps_or_missing_shards() {
    let dir = tmpdir("merge-bad");
    let shard = |k: &str, extra: &[&'static str]| {
        let d = dir.join(format!("s{}-{}", &k[..1], extra.len()));
        let mut s = SWEEP.to_vec();
        s.extend(["--shard", k]);
        s.extend(extra);
        ok(&run(&s, &d));
        d
    };
    let s0 = shard("0/2", &[]);
    let s1 = shard("1/2", &[]);
    let other = shard("1/2", &["--set", "excitation.a_h=2.9"]);
    let out = dir.join("out");
    let merge = |dirs: &[&PathBuf]| {
        rocking()
            .args(["merge", "--out"])
            .arg(&out)
            .args(dirs)
            .output()
            .unwrap()
    };
    let o = merge(&[&s0, &other]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("not the same sweep") && err.contains("\"config\""),
        "{err}"
    );
    let o = merge(&[&s0]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("shard 1/2 is missing"));
    let o = merge(&[&s0, &s0, &s1]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("given twice"));
    std::fs::write(
        s1.join("classes.csv"),
        "value,outcome,period,max_abs_theta,lyapunov\n9.9,chaotic,,0.5,\n",
    )
    .unwrap();
    let o = merge(&[&s0, &s1]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("classes.csv:2"), "{err}");
    assert!(!out.exists());
}

#[test]
fn map_writes_its_files_and_rejects_bad_axes() {
    let dir = tmpdir("map");
    let out = dir.join("out");
    let args = [
        "map",
        "--preset",
        "fig4",
        "--x",
        "excitation.a_v",
        "1.0",
        "2.0",
        "2",
        "--y",
        "excitation.a_h",
        "0.5",
        "3.0",
        "2",
        "--transient",
        "100",
        "--tau-end",
        "160",
        "-q",
    ];
    ok(&run(&args, &out));
    let names: Vec<String> = files(&out).into_iter().map(|f| f.0).collect();
    assert_eq!(names, ["map.csv", "map.json", "map.png", "map.svg"]);
    let csv = std::fs::read_to_string(out.join("map.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "x,y,outcome,period,max_abs_theta,lyapunov,attractor,computed");
    assert_eq!(rows.len(), 5);
    // A_h = 0.5 cannot lift the block: rest; A_h = 3, A_v = 1: period 1.
    assert!(rows[1].starts_with("1.0,0.5,rest,,"), "{}", rows[1]);
    assert!(rows[3].starts_with("1.0,3.0,periodic,1,"), "{}", rows[3]);

    let bad_map = |x: [&'static str; 4], flag: &str| {
        let mut a: Vec<&str> = vec!["map", "--preset", "fig4", "--x"];
        a.extend(x);
        a.extend([
            "--y",
            "excitation.a_h",
            "0.5",
            "3.0",
            "2",
            "--tau-end",
            "160",
            "--transient",
            "100",
        ]);
        let out = dir.join("bad");
        let o = run(&a, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(flag), "{a:?}: {err}");
        assert!(!out.exists());
    };
    bad_map(["excitation.a_v", "1.0", "2.0", "0"], "--x excitation.a_v");
    bad_map(["excitation.a_v", "1.0", "x", "2"], "--x excitation.a_v: B");
    bad_map(["excitation.a_v", "2.0", "1.0", "3"], "--x excitation.a_v");
    bad_map(["excitation.nope", "1.0", "2.0", "2"], "--x excitation.nope");
    bad_map(["excitation.a_h", "1.0", "2.0", "2"], "--y excitation.a_h");
}

#[test]
fn batch_still_works_beside_the_subcommands() {
    let dir = tmpdir("batch");
    let out = dir.join("out");
    let o = rocking()
        .args(["--batch", "--preset", "fig4", "--set", "run.tau_end=20", "-q", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    ok(&o);
    assert!(out.join("summary.json").is_file());
    // Top-level flags do not mix with a subcommand.
    let o = rocking().args(["--batch", "sweep"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
}

/// Rows of a CSV file after its header, split into cells.
fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn a_sweep_value_is_the_batch_run_at_the_value_typed() {
    // In binary 2.2 + 1·0.1 is 2.3000000000000003, which in a chaotic window
    // can be another run than 2.3: the sweep must run 2.3 itself.
    let dir = tmpdir("decimal");
    let sweep = dir.join("sweep");
    let args = [
        "sweep",
        "--preset",
        "fig4",
        "--param",
        "excitation.a_v",
        "--from",
        "2.2",
        "--to",
        "2.4",
        "--step",
        "0.1",
        "--transient",
        "100",
        "--tau-end",
        "160",
        "-q",
    ];
    ok(&run(&args, &sweep));
    let classes = csv_rows(&sweep.join("classes.csv"));
    let values: Vec<&str> = classes.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(values, ["2.2", "2.3", "2.4"], "the values as typed");
    let batch = dir.join("batch");
    let o = rocking()
        .args([
            "--batch",
            "--preset",
            "fig4",
            "--set",
            "excitation.a_v=2.3",
            "--set",
            "run.tau_end=160",
            "-q",
        ])
        .arg("--out")
        .arg(&batch)
        .output()
        .expect("runs");
    ok(&o);
    // The sweep's points at 2.3 are the batch run's section points from τ 100.
    let from_sweep: Vec<(String, String, String)> = csv_rows(&sweep.join("points.csv"))
        .into_iter()
        .filter(|r| r[0] == "2.3")
        .map(|r| (r[2].clone(), r[3].clone(), r[4].clone()))
        .collect();
    let from_batch: Vec<(String, String, String)> = csv_rows(&batch.join("poincare.csv"))
        .into_iter()
        .filter(|r| r[1].parse::<f64>().expect("tau") >= 100.0)
        .map(|r| (r[1].clone(), r[2].clone(), r[3].clone()))
        .collect();
    assert!(
        !from_sweep.is_empty(),
        "A_v = 2.3 rocks (periods 2–4), so it has points"
    );
    assert_eq!(from_sweep, from_batch);
    let _ = std::fs::remove_dir_all(&dir);
}
