//! Inputs of the engineering commands that used to change results without
//! a word (issue 24, items 2, 3, 4, 6, 8 and 15): a vertical record, keys
//! and flags a command ignores, two `--set` of exclusive keys, duplicated
//! records, levels and blocks, suite lists as users write them, and suite
//! files that are not files. Each is refused with one line naming what the
//! user typed, exit 2, nothing written; or, where the input is sound
//! (quoted paths, tabs, a byte-order mark, comments), accepted.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");
const KOBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/kobe-1995.dat");

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-inputs-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Runs `cmd`, killing it after `limit` (a FIFO or a device must not
/// hang the suite).
fn output_within(mut cmd: Command, limit: Duration) -> Output {
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let start = Instant::now();
    while child.try_wait().expect("waits").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

/// Exit 2, a one-line `error: …` containing every needle, nothing at `out`.
fn refused(o: &Output, needles: &[&str], out: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err:?}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
    }
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    assert!(!out.exists(), "{} was written", out.display());
}

fn spectrum(out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "0.5", "--to", "1", "--count", "2",
        ])
        .args(["-q", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

fn pulse_spectrum(out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args([
            "spectrum",
            "--pulse",
            "one-sine",
            "--pulse-accel",
            "0.5",
            "--pulse-period",
            "0.5",
        ])
        .args(["--from", "0.5", "--to", "1", "--count", "2", "-q", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

fn fragility(out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args(["fragility", "--records", ELCENTRO, "--unit", "g"])
        .args(["--levels", "0.2", "--block", "0.6x2.0", "-q", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

fn fragility_suite(list: &Path, out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args(["fragility", "--suite"])
        .arg(list)
        .args(["--levels", "0.2", "--block", "0.6x2.0", "-q", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

fn pulse_map(out: &Path, extra: &[&str]) -> Output {
    rocking()
        .args([
            "pulse-map",
            "--pulse",
            "one-sine",
            "--omega",
            "2",
            "--amp-max",
            "1",
            "-q",
            "--out",
        ])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

#[test]
fn spectrum_and_fragility_take_a_vertical_record_from_their_own_flags_not_from_keys() {
    let dir = tmpdir("vertical");
    let out = dir.join("out");
    let file_v = format!("excitation.file_v={KOBE}");
    let o = spectrum(&out, &["--set", &file_v, "--set", "excitation.unit_v=m/s2"]);
    refused(
        &o,
        &["--set excitation.file_v", "--record-v", "scales it with the horizontal"],
        &out,
    );
    let o = fragility(&out, &["--set", &file_v, "--set", "excitation.unit_v=m/s2"]);
    refused(
        &o,
        &["--set excitation.file_v", "+ VPATH", "scales it with the horizontal"],
        &out,
    );
    for key in [
        "excitation.scale_v=2",
        "excitation.pga_v=0.3 g",
        "excitation.a_v=0.5",
        "excitation.dt_v=0.02",
    ] {
        let o = fragility(&out, &["--set", key]);
        let shown = key.split('=').next().unwrap_or_default();
        refused(&o, &[&format!("--set {shown}"), "+ VPATH"], &out);
    }
    // From a config: the vertical record would be applied unscaled.
    let cfg = dir.join("hv.toml");
    std::fs::write(
        &cfg,
        format!("[excitation]\nkind = \"record\"\nfile_h = \"{ELCENTRO}\"\nunit_h = \"g\"\nfile_v = \"{KOBE}\"\nunit_v = \"m/s2\"\n"),
    )
    .expect("write");
    let o = spectrum(&out, &["--config", cfg.to_str().expect("utf-8")]);
    refused(&o, &["--config", "excitation.file_v", "--record-v"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn engineering_commands_refuse_keys_and_flags_they_ignore() {
    let dir = tmpdir("ignored");
    let out = dir.join("out");
    let cases: Vec<(Output, Vec<&str>)> = vec![
        (
            spectrum(&out, &["--set", "run.tau_end=100"]),
            vec!["--set run.tau_end", "run.tail_s"],
        ),
        (spectrum(&out, &["--set", "run.t_end=10 s"]), vec!["--set run.t_end"]),
        (
            spectrum(&out, &["--set", "block.width=0.5"]),
            vec!["--set block.width: spectrum sets every block's size itself (--from/--to/--count"],
        ),
        (
            spectrum(&out, &["--set", "initial.theta=0.1"]),
            vec!["--set initial.theta", "at rest"],
        ),
        (
            spectrum(&out, &["--set", "run.output_dt=0.01 s"]),
            vec!["--set run.output_dt"],
        ),
        (
            spectrum(&out, &["--set", "analysis.lyapunov=true"]),
            vec!["--set analysis.lyapunov"],
        ),
        (
            spectrum(&out, &["--pulse-accel", "0.5"]),
            vec!["--pulse-accel", "--record"],
        ),
        (spectrum(&out, &["--cycles", "2"]), vec!["--cycles"]),
        (
            spectrum(&out, &["--search-max", "3"]),
            vec!["--search-max", "--overturn-scale"],
        ),
        (
            spectrum(&out, &["--rel-tol", "0.01"]),
            vec!["--rel-tol", "--overturn-scale"],
        ),
        (pulse_spectrum(&out, &["--unit", "g"]), vec!["--unit", "--pulse"]),
        (pulse_spectrum(&out, &["--cycles", "3"]), vec!["--cycles 3", "type-c"]),
        (
            pulse_spectrum(&out, &["--set", "run.tail_s=5 s"]),
            vec!["--set run.tail_s", "50 τ"],
        ),
        (
            fragility(&out, &["--set", "excitation.kind=harmonic"]),
            vec!["--set excitation.kind: fragility sets the motion itself (--records/--suite"],
        ),
        (
            fragility(&out, &["--set", &format!("excitation.file_h={KOBE}")]),
            vec!["--set excitation.file_h"],
        ),
        (
            fragility(&out, &["--set", "excitation.scale_h=2"]),
            vec!["--set excitation.scale_h"],
        ),
        (
            fragility(&out, &["--set", "block.height=2"]),
            vec!["--set block.height", "--block"],
        ),
        (
            fragility(&out, &["--friction", "0.5", "--set", "friction.static=0.6"]),
            vec!["--friction 0.5", "--set friction.static"],
        ),
        (pulse_map(&out, &["--cycles", "2"]), vec!["--cycles 2", "type-c"]),
        (pulse_map(&out, &["--set", "run.tail_s=5 s"]), vec!["--set run.tail_s"]),
        (
            pulse_map(&out, &["--set", "excitation.a_h=0.5"]),
            vec!["--set excitation.a_h", "--amp-max"],
        ),
    ];
    for (o, needles) in &cases {
        refused(o, needles, &out);
    }
    // What the commands do use still works: the record tail, the impact
    // law, the friction from --set alone.
    let o = fragility(
        &out,
        &[
            "--set",
            "run.tail_s=5 s",
            "--set",
            "impact.law=housner",
            "--set",
            "friction.static=0.6",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn two_sets_of_exclusive_keys_are_refused_and_one_set_overrides_the_presets_twin() {
    let dir = tmpdir("exclusive");
    let out = dir.join("out");
    let batch = |args: &[&str]| {
        rocking()
            .args(["--batch", "-q"])
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .expect("runs")
    };
    let o = batch(&[
        "--preset",
        "default",
        "--set",
        "run.t_end=2 s",
        "--set",
        "run.tau_end=3",
    ]);
    refused(&o, &["--set run.t_end=2 s", "--set run.tau_end=3", "give one"], &out);
    let o = batch(&[
        "--preset",
        "default",
        "--set",
        "run.tau_end=3",
        "--set",
        "run.t_end=2 s",
    ]);
    refused(&o, &["--set run.tau_end=3", "--set run.t_end=2 s"], &out);
    let o = batch(&[
        "--preset",
        "kobe-rack",
        "--set",
        "excitation.scale_h=2",
        "--set",
        "excitation.pga_h=0.4 g",
    ]);
    refused(
        &o,
        &["--set excitation.scale_h=2", "--set excitation.pga_h=0.4 g"],
        &out,
    );
    let o = batch(&[
        "--preset",
        "kobe-rack",
        "--set",
        "run.tail_s=5 s",
        "--set",
        "run.t_end=2 s",
    ]);
    refused(&o, &["--set run.tail_s=5 s", "--set run.t_end=2 s"], &out);
    // Keys alone (no preset) and the other subcommands that take --set.
    let o = batch(&["--set", "run.t_end=2 s", "--set", "run.tau_end=3"]);
    refused(&o, &["--set run.t_end=2 s", "--set run.tau_end=3"], &out);
    let o = rocking()
        .args([
            "sweep",
            "--param",
            "excitation.a_h",
            "--from",
            "1",
            "--to",
            "2",
            "--step",
            "1",
        ])
        .args(["--set", "run.t_end=2 s", "--set", "run.tau_end=3", "-q", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    refused(&o, &["--set run.t_end=2 s", "--set run.tau_end=3"], &out);
    // A file with both stays refused, even when --set names one of them.
    let both = dir.join("both.toml");
    std::fs::write(&both, "[run]\ntau_end = 3\nt_end = \"3 s\"\n").expect("write");
    let o = batch(&["--config", both.to_str().expect("utf-8"), "--set", "run.t_end=2 s"]);
    refused(&o, &["run.t_end: give either run.tau_end or run.t_end, not both"], &out);
    // One --set of a pair replaces the preset's twin: an override.
    let o = batch(&["--preset", "default", "--set", "run.t_end=2 s"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn duplicated_records_levels_blocks_and_sizes_are_refused_naming_both() {
    let dir = tmpdir("duplicates");
    let out = dir.join("out");
    let list = dir.join("suite.txt");
    std::fs::write(&list, format!("{ELCENTRO} g\n# again\n{ELCENTRO} g\n")).expect("write");
    let o = fragility_suite(&list, &out, &[]);
    refused(&o, &["suite.txt:1", "suite.txt:3", "listed twice"], &out);
    // The same file under another spelling of its path.
    let copy = dir.join("elcentro.dat");
    std::fs::copy(ELCENTRO, &copy).expect("copy");
    std::fs::write(&list, "elcentro.dat g\n./elcentro.dat g\n").expect("write");
    let o = fragility_suite(&list, &out, &[]);
    refused(&o, &["suite.txt:1", "suite.txt:2"], &out);
    let o = fragility(&out, &["--records", ELCENTRO]);
    refused(&o, &["--records", "listed twice"], &out);
    for (levels, needle) in [
        ("0.1:0.1:3", "gives the same value 3 times"),
        ("0.1,0.2,0.1", "0.1 is given twice (values 1 and 3)"),
    ] {
        let o = rocking()
            .args(["fragility", "--records", ELCENTRO, "--unit", "g", "--levels", levels])
            .args(["--block", "0.6x2.0", "-q", "--out"])
            .arg(&out)
            .output()
            .expect("runs");
        refused(&o, &["--levels", needle], &out);
    }
    let o = fragility(&out, &["--block", "0.6x2"]);
    refused(&o, &["--block 0.6x2.0", "--block 0.6x2", "twice"], &out);
    let o = rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "1", "--to", "1",
        ])
        .args(["--count", "5", "-q", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    refused(&o, &["--count 5", "5 identical blocks"], &out);
    let o = spectrum(&out, &["--b-over-h", "0.2,0.3,0.2"]);
    refused(&o, &["--b-over-h", "0.2 is given twice"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn suites_take_quoted_paths_tabs_a_bom_and_comments() {
    let dir = tmpdir("suite-syntax");
    let out = dir.join("out");
    let sub = dir.join("my records");
    std::fs::create_dir_all(&sub).expect("dir");
    std::fs::copy(ELCENTRO, sub.join("el centro.dat")).expect("copy");
    std::fs::copy(KOBE, sub.join("kobe 1995.dat")).expect("copy");
    let list = dir.join("suite.txt");
    std::fs::write(
        &list,
        "\u{feff}# two records with spaces in their paths\n\"my records/el centro.dat\" g # El Centro 1940\nmy records/kobe 1995.dat\tm/s2\t# Kobe\n",
    )
    .expect("write");
    let o = fragility_suite(&list, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = std::fs::read_to_string(out.join("runs.csv")).expect("runs.csv");
    assert!(runs.contains("el centro") && runs.contains("kobe 1995"), "{runs}");
    // An empty suite says so.
    let empty = dir.join("empty.txt");
    std::fs::write(&empty, "\u{feff}# nothing yet\n\n").expect("write");
    let none = dir.join("none");
    let o = fragility_suite(&empty, &none, &[]);
    refused(&o, &["the suite", "empty.txt lists no records"], &none);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_records_folder_skips_files_that_are_not_records_and_says_which() {
    let dir = tmpdir("folder");
    let out = dir.join("out");
    let recs = dir.join("records");
    std::fs::create_dir_all(&recs).expect("dir");
    std::fs::copy(ELCENTRO, recs.join("elcentro.dat")).expect("copy");
    std::fs::write(recs.join("README.md"), "# Records\n\nEl Centro 1940, in g.\n").expect("write");
    std::fs::write(recs.join("suite.txt"), "elcentro.dat g\n").expect("write");
    let o = rocking()
        .args(["fragility", "--records"])
        .arg(&recs)
        .args(["--unit", "g", "--levels", "0.2", "--block", "0.6x2.0", "-q", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("warning: ") && err.contains("README.md, suite.txt") && err.contains("not records"),
        "{err}"
    );
    // A folder with no record is refused.
    let docs = dir.join("docs");
    std::fs::create_dir_all(&docs).expect("dir");
    std::fs::write(docs.join("README.md"), "# Nothing here\n\nSee the paper.\n").expect("write");
    let none = dir.join("none");
    let o = rocking()
        .args(["fragility", "--records"])
        .arg(&docs)
        .args(["--unit", "g", "--levels", "0.2", "--block", "0.6x2.0", "-q", "--out"])
        .arg(&none)
        .output()
        .expect("runs");
    refused(
        &o,
        &["--records", "no file in the folder is a record", "README.md"],
        &none,
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn messages_name_the_flag_typed_and_print_numbers_readably() {
    let dir = tmpdir("messages");
    let out = dir.join("out");
    let o = rocking()
        .args([
            "spectrum",
            "--pulse",
            "type-c",
            "--pulse-accel",
            "0.5",
            "--pulse-period",
            "0.5",
        ])
        .args([
            "--cycles", "0", "--from", "0.5", "--to", "1", "--count", "2", "-q", "--out",
        ])
        .arg(&out)
        .output()
        .expect("runs");
    refused(&o, &["--cycles 0"], &out);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("excitation.a_h"));
    for flag in ["--pga", "--scale"] {
        let o = spectrum(&out, &[&format!("{flag}=-1e-300")]);
        refused(&o, &[&format!("{flag} -1e-300")], &out);
        assert!(o.stderr.len() < 200, "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = rocking()
        .args([
            "spectrum", "--record", ELCENTRO, "--unit", "g", "--from", "1e-300", "--to", "1e-301",
        ])
        .args(["-q", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    refused(&o, &["--to 1e-301", "--from 1e-300"], &out);
    assert!(o.stderr.len() < 200, "{}", String::from_utf8_lossy(&o.stderr));
    let o = pulse_map(&out, &["--amp-step", "1e-300"]);
    refused(
        &o,
        &["--amp-step 1e-300", "--amp-max 1", "more than 100000 steps"],
        &out,
    );
    assert!(o.stderr.len() < 200, "{}", String::from_utf8_lossy(&o.stderr));
    // A pulse far shorter than any block's time scale: refused at once,
    // not an hour's silent run.
    let mut cmd = rocking();
    cmd.args(["pulse-map", "--omega", "1e6", "-q", "--out"]).arg(&out);
    let o = output_within(cmd, Duration::from_secs(20));
    refused(&o, &["--omega 1e6", "above 1000"], &out);
    let o = rocking()
        .args([
            "spectrum",
            "--pulse",
            "one-sine",
            "--pulse-accel",
            "0.5",
            "--pulse-period",
            "1e-6",
        ])
        .args(["--from", "0.5", "--to", "1", "--count", "2", "-q", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    refused(&o, &["--pulse-period 1e-6", "above 1000"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_suite_reader_refuses_devices_fifos_folders_and_huge_files() {
    let dir = tmpdir("suite-files");
    let out = dir.join("out");
    let run = |list: &Path| {
        let mut cmd = rocking();
        cmd.args(["fragility", "--suite"])
            .arg(list)
            .args(["--levels", "0.2", "--block", "0.6x2.0", "-q", "--out"])
            .arg(&out);
        output_within(cmd, Duration::from_secs(20))
    };
    let o = run(Path::new("/dev/zero"));
    refused(&o, &["--suite /dev/zero", "not a regular file"], &out);
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let o = run(&fifo);
    refused(&o, &["not a regular file"], &out);
    let big = dir.join("big.txt");
    std::fs::File::create(&big)
        .and_then(|f| f.set_len(2 << 20))
        .expect("sparse file");
    let o = run(&big);
    refused(&o, &["big.txt", "at most 1048576 bytes"], &out);
    let o = run(&dir);
    refused(&o, &["is a folder", "--records"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}
