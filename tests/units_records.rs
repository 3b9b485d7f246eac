//! Will it overturn? Units in every input, records in their own units, the
//! record-end rule and the engineer's answer, as a user meets them through
//! the `rocking` binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const G: f64 = 9.81;
const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");
const KOBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/kobe-1995.dat");

fn rocking(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(args)
        .output()
        .expect("runs")
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-units-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs `--batch` with `args` into `out` and returns summary.json.
fn batch(out: &Path, args: &[&str]) -> Value {
    let mut all = vec!["--batch", "--quiet", "--out", out.to_str().expect("utf-8")];
    all.extend_from_slice(args);
    let o = rocking(&all);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json");
    serde_json::from_str(&text).expect("json")
}

/// A refused run: exit 2, one line naming `key`, nothing at `--out`.
fn refused(dir: &Path, args: &[&str], expected: &str) {
    let out = dir.join("refused");
    let mut all = vec!["--batch", "--out", out.to_str().expect("utf-8")];
    all.extend_from_slice(args);
    let o = rocking(&all);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: not one line: {err}");
    assert!(err.contains(expected), "{args:?}: expected {expected:?} in {err}");
    assert!(!out.exists(), "{args:?}: wrote {}", out.display());
}

fn f(v: &Value, path: &[&str]) -> f64 {
    let mut v = v;
    for k in path {
        v = &v[*k];
    }
    v.as_f64().unwrap_or_else(|| panic!("{path:?} is not a number: {v}"))
}

/// Kobe 1995 in three units: m/s² (as shipped), g and cm/s², written by
/// this test from the shipped file.
fn kobe_in(dir: &Path) -> [(PathBuf, &'static str); 3] {
    let text = std::fs::read_to_string(KOBE).expect("kobe");
    let convert = |factor: f64| -> String {
        text.lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| {
                let mut it = l.split_whitespace();
                let t: f64 = it.next().and_then(|x| x.parse().ok()).expect("time");
                let a: f64 = it.next().and_then(|x| x.parse().ok()).expect("accel");
                format!("{t:?} {:?}\n", a * factor)
            })
            .collect()
    };
    let g = dir.join("kobe-g.txt");
    let cm = dir.join("kobe-cm.txt");
    std::fs::write(&g, convert(1.0 / G)).expect("write");
    std::fs::write(&cm, convert(100.0)).expect("write");
    [(PathBuf::from(KOBE), "m/s2"), (g, "g"), (cm, "cm/s2")]
}

#[test]
fn the_same_motion_in_g_m_s2_and_cm_s2_gives_the_same_outputs_to_1e_12() {
    let dir = tmpdir("same-motion");
    let mut answers = Vec::new();
    for (k, (file, unit)) in kobe_in(&dir).iter().enumerate() {
        let file_set = format!("excitation.file_h={}", file.display());
        let unit_set = format!("excitation.unit_h={unit}");
        let s = batch(
            &dir.join(format!("out{k}")),
            &["--preset", "kobe-rack", "--set", &file_set, "--set", &unit_set],
        );
        answers.push(s);
    }
    let keys: [&[&str]; 6] = [
        &["physical", "t_overturn_s"],
        &["physical", "max_rotation_rad"],
        &["physical", "record_h", "pga_g"],
        &["physical", "record_h", "pgv_m_s"],
        &["physical", "record_h", "pgd_m"],
        &["tau_end"],
    ];
    for key in keys {
        let a = f(&answers[0], key);
        for s in &answers[1..] {
            let b = f(s, key);
            assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0), "{key:?}: {a} vs {b}");
        }
    }
    assert_eq!(answers[0]["physical"]["end_state"], "overturned");
    assert_eq!(answers[2]["config"]["excitation"]["unit_h"], "cm/s2");
}

#[test]
fn both_shipped_records_read_with_their_published_pga() {
    let dir = tmpdir("pga");
    // El Centro 1940 NS: 0.349 g (two columns, s and g), the largest
    // |value| of the file's second column.
    let s = batch(&dir.join("e"), &["--preset", "elcentro-statue"]);
    let pga = f(&s, &["physical", "record_h", "pga_g"]);
    assert!((pga - 0.349).abs() < 5e-4, "El Centro PGA {pga} g");
    let peak = std::fs::read_to_string(ELCENTRO)
        .expect("El Centro")
        .lines()
        .filter_map(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .fold(0.0_f64, |m, a| m.max(a.abs()));
    assert_eq!(pga, peak);
    assert_eq!(s["physical"]["record_h"]["unit"], "g");
    assert!((f(&s, &["physical", "record_h", "duration_s"]) - 53.74).abs() < 1e-9);
    // Kobe 1995: 6.80 m/s² = 0.693 g (two columns, s and m/s²).
    let s = batch(&dir.join("k"), &["--preset", "kobe-rack"]);
    let pga = f(&s, &["physical", "record_h", "pga_g"]);
    assert!((pga * G - 6.80).abs() < 5e-3, "Kobe PGA {} m/s2", pga * G);
    assert_eq!(s["physical"]["record_h"]["unit"], "m/s2");
}

#[test]
fn pga_h_scales_the_record_to_the_target() {
    let dir = tmpdir("pga-h");
    let s = batch(
        &dir.join("o"),
        &["--preset", "elcentro-statue", "--set", "excitation.pga_h=0.2 g"],
    );
    assert!((f(&s, &["physical", "record_h", "pga_g"]) - 0.2).abs() < 1e-12);
    let scale = f(&s, &["config", "excitation", "scale_h"]);
    assert!((scale - 0.2 / 0.34873739).abs() < 1e-9, "{scale}");
    let s2 = batch(
        &dir.join("o2"),
        &["--preset", "elcentro-statue", "--set", "excitation.pga_h=196.2 gal"],
    );
    assert!((f(&s2, &["physical", "record_h", "pga_g"]) - 0.2).abs() < 1e-12);
}

#[test]
fn the_record_end_rule() {
    let dir = tmpdir("end-rule");
    // Default: the whole record, then on until rest (El Centro's statue
    // settles long before the 30 s tail is spent).
    let s = batch(&dir.join("full"), &["--preset", "elcentro-statue"]);
    let p = &s["physical"];
    assert_eq!(p["record_complete"], true);
    assert_eq!(p["end_state"], "rest");
    let t_end = f(p, &["t_end_s"]);
    assert!((53.74 - 1e-9..=53.74 + 30.0 + 1e-9).contains(&t_end), "{t_end}");
    assert!(f(p, &["max_rotation_over_alpha"]) > 0.1, "the statue rocks");
    // Cut short while rocking: the answer is "moving", never "rest".
    let s = batch(&dir.join("cut"), &["--preset", "kobe-rack", "--set", "run.t_end=5 s"]);
    let p = &s["physical"];
    assert_eq!(p["record_complete"], false);
    assert_eq!(p["end_state"], "moving");
    assert!((f(p, &["t_end_s"]) - 5.0).abs() < 1e-12);
    // An explicit end past the record runs to it exactly, without stopping
    // at rest.
    let s = batch(
        &dir.join("long"),
        &["--preset", "elcentro-statue", "--set", "run.t_end=90"],
    );
    assert_eq!(s["physical"]["record_complete"], true);
    assert!((f(&s, &["physical", "t_end_s"]) - 90.0).abs() < 1e-9);
    // The tail is bounded: no tail ends at the record's end.
    let s = batch(
        &dir.join("notail"),
        &[
            "--preset",
            "kobe-rack",
            "--set",
            "block.width=3",
            "--set",
            "block.height=2",
            "--set",
            "run.tail_s=0",
        ],
    );
    assert!(f(&s, &["physical", "t_end_s"]) <= 24.98 + 1e-9);
}

#[test]
fn the_answer_reads_like_an_engineers() {
    let dir = tmpdir("answer");
    let o = rocking(&[
        "--batch",
        "--preset",
        "kobe-rack",
        "--out",
        dir.join("k").to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let first = stdout(&o).lines().next().unwrap_or_default().to_string();
    assert!(
        first.starts_with("overturned at t = ")
            && first.ends_with(" s (kobe-1995.dat, PGA 0.69 g); corner-momentum impact r = 0.876, friction μ = 0.5"),
        "{first}"
    );
    let o = rocking(&[
        "--batch",
        "--preset",
        "elcentro-statue",
        "--out",
        dir.join("e").to_str().expect("utf-8"),
    ]);
    let first = stdout(&o).lines().next().unwrap_or_default().to_string();
    assert!(first.starts_with("survived: peak rotation "), "{first}");
    assert!(
        first.contains("; at rest from t = ")
            && first
                .ends_with("(elcentro-1940-ns.dat, PGA 0.35 g); corner-momentum impact r = 0.929, friction μ = 0.6"),
        "{first}"
    );
}

#[test]
fn physical_columns_are_the_normalised_ones_converted() {
    let dir = tmpdir("columns");
    let out = dir.join("o");
    let s = batch(&out, &["--preset", "kobe-rack"]);
    let p = f(&s, &["block", "p_per_s"]);
    let psi = f(&s, &["block", "psi_rad"]);
    let history = std::fs::read_to_string(out.join("history.csv")).expect("history");
    let mut lines = history.lines();
    assert_eq!(
        lines.next(),
        Some("tau,theta,theta_dot,x,x_dot,mode,t_s,theta_rad,sliding_m")
    );
    for line in lines.take(2000) {
        let c: Vec<&str> = line.split(',').collect();
        let num = |i: usize| c[i].parse::<f64>().expect("number");
        assert!((num(6) - num(0) / p).abs() <= 1e-12 * num(6).abs().max(1.0));
        assert!((num(7) - num(1) * psi).abs() <= 1e-15);
    }
    let events = std::fs::read_to_string(out.join("events.csv")).expect("events");
    assert!(events.starts_with(
        "tau,kind,mode_before,mode_after,theta,theta_dot_before,theta_dot_after,x_dot,t_s,theta_rad,sliding_m\n"
    ));
    // Seconds for the answer, τ/p for the run.
    let t = f(&s, &["physical", "t_overturn_s"]);
    assert!((t - f(&s, &["tumble_tau"]) / p).abs() < 1e-12);
    let deg = f(&s, &["physical", "max_rotation_deg"]);
    assert!((deg - f(&s, &["max_abs_theta"]) * psi.to_degrees()).abs() < 1e-9);
}

#[test]
fn harmonic_shaking_in_g_and_hz_is_the_normalised_run() {
    let dir = tmpdir("harmonic");
    // The paper's block (B = 1, H = 4): ψ = atan(1/4), p = √(3g/(4R)).
    let psi = (0.25_f64).atan();
    let r = 0.5 * 17.0_f64.sqrt();
    let p = (3.0 * G / (4.0 * r)).sqrt();
    let a_g = 2.0 * psi; // A_h = 2
    let f_hz = 8.0 * p / std::f64::consts::TAU; // Ω = 8
    let bare = batch(&dir.join("bare"), &["--preset", "default", "--set", "run.tau_end=40"]);
    let a_set = format!("excitation.a_h={a_g:?} g");
    let f_set = format!("excitation.omega_h={f_hz:?} Hz");
    let v_set = format!("excitation.a_v={:?} m/s2", 2.5 * psi * G);
    let t_set = format!("run.t_end={:?} s", 40.0 / p);
    let phys = batch(
        &dir.join("phys"),
        &[
            "--preset", "default", "--set", &a_set, "--set", &f_set, "--set", &v_set, "--set", &t_set,
        ],
    );
    for key in [
        ["config", "excitation", "a_h"],
        ["config", "excitation", "omega_h"],
        ["config", "excitation", "a_v"],
        ["config", "run", "tau_end"],
    ] {
        let (a, b) = (f(&bare, &key), f(&phys, &key));
        assert!((a - b).abs() <= 1e-12 * a.abs(), "{key:?}: {a} vs {b}");
    }
    let (a, b) = (f(&bare, &["max_abs_theta"]), f(&phys, &["max_abs_theta"]));
    assert!((a - b).abs() <= 1e-8, "{a} vs {b}");
    let s = batch(
        &dir.join("uplift"),
        &[
            "--preset",
            "default",
            "--set",
            "run.tau_end=1",
            "--set",
            "excitation.a_h=1.2 g*tan(alpha)",
        ],
    );
    assert!((f(&s, &["config", "excitation", "a_h"]) - 1.2 * 0.25 / psi).abs() < 1e-12);
    assert!((f(&s, &["resolved", "excitation", "a_h", "over_g_tan_alpha"]) - 1.2).abs() < 1e-12);
}

#[test]
fn every_unit_is_accepted_where_it_fits_and_refused_where_it_does_not() {
    let dir = tmpdir("fits");
    let fits: [(&str, &[&str]); 10] = [
        ("block.width", &["0.8 m", "80 cm", "800 mm"]),
        (
            "excitation.a_h",
            &["0.3 g", "2.9 m/s2", "290 cm/s2", "290 gal", "1.1 g*tan(alpha)", "1.5"],
        ),
        ("excitation.omega_h", &["2.5 Hz", "15.7 rad/s", "8"]),
        ("excitation.phase_h", &["30 deg", "0.5 rad", "0.5"]),
        ("initial.theta", &["2 deg", "0.03 rad", "0.1"]),
        ("initial.theta_dot", &["1 deg/s", "0.01 rad/s"]),
        ("run.tau_end", &["3 s", "500 ms", "2"]),
        ("run.t_end", &["3 s", "3"]),
        ("run.output_dt", &["0.01 s", "10 ms", "0.05"]),
        ("run.tumble_theta", &["30 deg", "0.5 rad", "1"]),
    ];
    for (key, values) in fits {
        for v in values {
            let set = format!("{key}={v}");
            let mut args = vec!["--preset", "default", "--set", "run.tau_end=2", "--set", &set];
            if key == "run.t_end" {
                args = vec!["--preset", "default", "--set", &set];
            }
            batch(&dir.join("ok"), &args);
        }
    }
    let misfits = [
        (
            "excitation.omega_h=2 m",
            "excitation.omega_h: unit \"m\" does not fit: a frequency",
        ),
        (
            "excitation.a_h=2 Hz",
            "excitation.a_h: unit \"Hz\" does not fit: an acceleration",
        ),
        ("block.height=1 g", "block.height: unit \"g\" does not fit: a length"),
        ("initial.theta=2 s", "initial.theta: unit \"s\" does not fit: an angle"),
        ("run.tau_end=3 deg", "run.tau_end: unit \"deg\" does not fit: a time"),
        (
            "excitation.a_h=0.3 furlongs",
            "excitation.a_h: unknown unit \"furlongs\"",
        ),
        (
            "friction.static=0.5 g",
            "friction.static: expected a number or \"inf\", found string \"0.5 g\"",
        ),
        (
            "run.rtol=1e-8 s",
            "run.rtol: expected a number, found string \"1e-8 s\"",
        ),
        (
            "excitation.scale_h=2 g",
            "excitation.scale_h: expected a number, found string \"2 g\"",
        ),
    ];
    for (set, expected) in misfits {
        refused(&dir, &["--preset", "default", "--set", set], expected);
    }
    // A file that gives both ends is refused; a later --set replaces the
    // other (a preset's run.tau_end is overridden by --set run.t_end).
    let both = dir.join("both.toml");
    std::fs::write(&both, "[run]\ntau_end = 3\nt_end = \"3 s\"\n").expect("write");
    refused(
        &dir,
        &["--config", both.to_str().expect("utf-8")],
        "run.t_end: give either run.tau_end or run.t_end, not both",
    );
    let s = batch(&dir.join("later"), &["--preset", "default", "--set", "run.t_end=2 s"]);
    assert!((f(&s, &["physical", "t_end_s"]) - 2.0).abs() < 1e-12);
}

#[test]
fn bad_records_are_refused_naming_the_key_file_and_line() {
    let dir = tmpdir("bad-records");
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        p.display().to_string()
    };
    let two = write("two.txt", "0 0.1\n0.02 -0.2\n0.04 0.05\n");
    let one = write("one.txt", "# one column, dt 0.02 s\n0.1\n-0.2\n0.05\n");
    let empty = write("empty.txt", "\n\n");
    let single = write("single.txt", "0 0.1\n");
    let at2 = write(
        "r.at2",
        "TITLE\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=3, DT=0.02 SEC\n0.1 -0.2 0.05\n",
    );
    let rec = |file: &str| {
        vec![
            "--preset".to_string(),
            "kobe-rack".into(),
            "--set".into(),
            format!("excitation.file_h={file}"),
        ]
    };
    let run = |mut args: Vec<String>, extra: &[&str], expected: &str| {
        for e in extra {
            args.push("--set".into());
            args.push((*e).into());
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&dir, &args, expected);
    };
    // kobe-rack states m/s2; each case overrides what it needs.
    let no_unit = format!("excitation.unit_h: {two}: a text record does not say its unit");
    let table = format!("[excitation]\nkind = \"record\"\nfile_h = \"{two}\"\n");
    let cfg = write("nounit.toml", &table);
    refused(&dir, &["--config", &cfg], &no_unit);
    run(
        rec(&two),
        &["excitation.unit_h=furlongs"],
        "excitation.unit_h: unknown unit \"furlongs\" (known: g, m/s2, cm/s2)",
    );
    run(
        rec(&one),
        &[],
        &format!("excitation.dt_h: {one}:2: one value per line: a one-column record needs its time step (s) stated"),
    );
    run(rec(&one), &["excitation.dt_h=0"], "excitation.dt_h: ");
    run(rec(&one), &["excitation.dt_h=-0.02 s"], "invalid time step -0.02 s");
    run(
        rec(&two),
        &["excitation.dt_h=0.02"],
        &format!("excitation.dt_h: {two}:1: expected 1 column (a time step is set), found 2"),
    );
    run(rec(&empty), &[], &format!("excitation.file_h: {empty}: empty file"));
    run(
        rec(&single),
        &[],
        &format!("excitation.file_h: {single}: need at least 2 samples, found 1"),
    );
    run(
        rec(&at2),
        &[],
        &format!("excitation.unit_h: {at2}:3: the header says the unit is g, but m/s2 was stated"),
    );
    run(rec(&two), &["excitation.pga_h=0.4"], "excitation.pga_h: needs a unit");
    let both = write(
        "both.toml",
        &format!(
            "[excitation]\nkind = \"record\"\nfile_h = \"{two}\"\nunit_h = \"g\"\nscale_h = 2\npga_h = \"0.4 g\"\n"
        ),
    );
    refused(
        &dir,
        &["--config", &both],
        "excitation.pga_h: give either excitation.scale_h or excitation.pga_h, not both",
    );
    run(rec(&two), &["excitation.pga_h=-0.4 g"], "excitation.pga_h: must be > 0");
    // A one-column record with its step runs.
    let out = dir.join("one-ok");
    let s = batch(
        &out,
        &[
            "--preset",
            "kobe-rack",
            "--set",
            &format!("excitation.file_h={one}"),
            "--set",
            "excitation.dt_h=0.02 s",
            "--set",
            "excitation.unit_h=g",
        ],
    );
    assert!((f(&s, &["physical", "record_h", "duration_s"]) - 0.04).abs() < 1e-15);
    assert_eq!(s["config"]["excitation"]["dt_h"], 0.02);
    // An implausible PGA runs but warns, naming the file and its PGA.
    let o = rocking(&[
        "--batch",
        "--quiet",
        "--preset",
        "kobe-rack",
        "--set",
        "excitation.unit_h=g",
        "--out",
        dir.join("warn").to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("kobe-1995.dat: PGA 6.803 g (read in g, scaled by 1) is implausible"),
        "{err}"
    );
}

#[test]
fn a_record_summary_repeats_its_run_from_another_folder() {
    let dir = tmpdir("repeat");
    let s1 = batch(&dir.join("a"), &["--preset", "kobe-rack"]);
    let summary = dir.join("a").join("summary.json");
    let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .current_dir(std::env::temp_dir())
        .args(["--batch", "--quiet", "--config"])
        .arg(&summary)
        .arg("--out")
        .arg(dir.join("b"))
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let s2: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("b").join("summary.json")).expect("b")).expect("json");
    assert_eq!(s1["physical"]["t_overturn_s"], s2["physical"]["t_overturn_s"]);
    assert_eq!(s1["config"], s2["config"]);
    assert!(Path::new(s1["config"]["excitation"]["file_h"].as_str().expect("path")).is_absolute());
}
