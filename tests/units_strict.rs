//! Units and records as users type them: unit symbols are case-sensitive
//! SI (`10 Ms` is not 10 ms), a scale of 0 and record time steps outside
//! [1e-5 s, 10 s] are refused, and a record whose peak suggests a wrong
//! unit (PGA below 0.01 g or above 5 g) or a large scale factor is named
//! in a warning. Refusals: exit 2, one line naming the key, flag or file,
//! nothing written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const RECORDS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records");

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
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

/// Exit 2, one line holding every needle, nothing at `out`.
fn refused(o: &Output, needles: &[&str], out: &Path) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
    }
    assert!(!out.exists(), "{} was written", out.display());
}

/// A batch run of the kobe-rack preset with `sets`, its record's tail cut
/// to 1 s unless `sets` give the run's end (the two exclude each other).
fn batch(out: &Path, sets: &[&str]) -> Output {
    let mut c = rocking();
    c.args(["--batch", "--preset", "kobe-rack"]);
    if !sets.iter().any(|s| s.starts_with("run.t_end")) {
        c.args(["--set", "run.tail_s=1 s"]);
    }
    for s in sets {
        c.args(["--set", s]);
    }
    c.arg("--out").arg(out).output().expect("runs")
}

#[test]
fn unit_symbols_in_the_wrong_case_are_refused_naming_the_key_and_the_unit_meant() {
    let dir = tmpdir("case");
    let out = dir.join("out");
    for (set, key, meant) in [
        ("run.t_end=10 Ms", "run.t_end", "ms"),
        ("block.width=600 Mm", "block.width", "mm"),
        ("excitation.unit_h=G", "excitation.unit_h", "g"),
    ] {
        let o = batch(&out, &[set]);
        refused(&o, &[key, "case-sensitive", &format!("did you mean \"{meant}\"")], &out);
        assert!(stderr(&o).contains("known: g, m/s2"), "{set}: no list of units");
    }
    // The same in a config file.
    let config = dir.join("rack.toml");
    std::fs::write(
        &config,
        format!(
            "[block]\nwidth = \"0.6 m\"\nheight = \"2 m\"\n[excitation]\nkind = \"record\"\nfile_h = \"{RECORDS}/kobe-1995.dat\"\nunit_h = \"m/s2\"\n[run]\nt_end = \"10 Ms\"\n"
        ),
    )
    .unwrap();
    let o = rocking()
        .args(["--batch", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    refused(&o, &["t_end", "did you mean \"ms\""], &out);
    // The engineering commands' --unit follows the same rule.
    let o = rocking()
        .args([
            "spectrum",
            "--record",
            &format!("{RECORDS}/elcentro-1940-ns.dat"),
            "--unit",
            "G",
        ])
        .args([
            "--from",
            "0.5",
            "--to",
            "1",
            "--count",
            "2",
            "--b-over-h",
            "0.2",
            "-q",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    refused(&o, &["--unit G", "g, m/s2, cm/s2"], &out);
    // The right case runs.
    let o = batch(&out, &["run.t_end=100 ms"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_zero_scale_is_refused_and_a_negative_one_flips_the_record() {
    let dir = tmpdir("scale");
    let out = dir.join("out");
    refused(
        &batch(&out, &["excitation.scale_h=0"]),
        &["excitation.scale_h", "no excitation"],
        &out,
    );
    let o = batch(&out, &["excitation.scale_h=-1", "run.t_end=2 s"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn record_time_steps_outside_1e_5_to_10_s_are_refused_naming_the_key_or_line() {
    let dir = tmpdir("steps");
    let out = dir.join("out");
    let text = std::fs::read_to_string(format!("{RECORDS}/elcentro-1940-ns.dat")).unwrap();
    let one = dir.join("one.txt");
    let values: Vec<&str> = text.lines().filter_map(|l| l.split_whitespace().nth(1)).collect();
    std::fs::write(&one, values.join("\n")).unwrap();
    let one_column = |dt: &str| {
        batch(
            &out,
            &[
                &format!("excitation.file_h={}", one.display()),
                "excitation.unit_h=g",
                &format!("excitation.dt_h={dt}"),
            ],
        )
    };
    // 1e-300 s gave pgd_m: null in summary.json.
    refused(
        &one_column("1e-300"),
        &["excitation.dt_h", "invalid time step 1e-300 s"],
        &out,
    );
    refused(&one_column("20 s"), &["excitation.dt_h", "<= 10 s"], &out);
    let two = dir.join("two.txt");
    std::fs::write(&two, "0 0.1\n0.01 0.2\n0.010000001 0.3\n0.02 0.1\n").unwrap();
    let o = batch(
        &out,
        &[&format!("excitation.file_h={}", two.display()), "excitation.unit_h=g"],
    );
    refused(&o, &["two.txt:3: time step"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_record_far_too_weak_for_its_unit_warns_as_one_far_too_strong_does() {
    let dir = tmpdir("weak");
    let out = dir.join("out");
    // El Centro (in g) declared cm/s²: PGA 0.00036 g.
    let o = rocking()
        .args(["--batch", "--preset", "elcentro-statue", "--set", "run.tail_s=1 s"])
        .args(["--set", "excitation.unit_h=cm/s2", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let warnings: Vec<&str> = err.lines().filter(|l| l.starts_with("warning:")).collect();
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(
        warnings[0].contains("elcentro-1940-ns.dat: PGA 3.55e-4 g (read in cm/s2")
            && warnings[0].contains("below 0.01 g")
            && warnings[0].contains("excitation.unit_h"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fragility_warns_for_implausible_record_peaks_and_large_scale_factors_naming_the_record() {
    let dir = tmpdir("fragility");
    let out = dir.join("out");
    // Kobe (m/s²) read as g: PGA 6.8 g; El Centro (0.35 g) scaled to 4 g:
    // a factor of 11.5.
    let list = dir.join("suite.txt");
    std::fs::write(
        &list,
        format!("{RECORDS}/kobe-1995.dat g\n{RECORDS}/elcentro-1940-ns.dat g\n"),
    )
    .unwrap();
    let o = rocking()
        .args(["fragility", "--suite"])
        .arg(&list)
        .args(["--levels", "0.5,4", "--block", "2x6", "-q", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let warnings: Vec<&str> = err.lines().filter(|l| l.starts_with("warning:")).collect();
    assert_eq!(warnings.len(), 2, "one line each: {err}");
    assert!(
        warnings[0].contains("record kobe-1995")
            && warnings[0].contains("PGA 6.803 g")
            && warnings[0].contains("above 5 g"),
        "{err}"
    );
    assert!(
        warnings[1].contains("record elcentro-1940-ns") && warnings[1].contains("scaled by up to 11.5"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spectrum_and_sliding_spectrum_warn_for_a_record_whose_peak_suggests_a_wrong_unit() {
    let dir = tmpdir("spectra");
    let kobe = format!("{RECORDS}/kobe-1995.dat");
    // Kobe is in m/s²: read as g its PGA is 6.8 g, and every block would
    // be shaken 9.81 times too hard.
    for (args, unit, warned) in [
        (
            &["spectrum", "--from", "0.5", "--to", "1", "--count", "2"][..],
            "g",
            true,
        ),
        (
            &["spectrum", "--from", "0.5", "--to", "1", "--count", "2"][..],
            "m/s2",
            false,
        ),
        (&["sliding-spectrum", "--mu", "0.2,0.4"][..], "g", true),
    ] {
        let o = rocking()
            .args(args)
            .args(["--record", &kobe, "--unit", unit, "-q", "--out"])
            .arg(dir.join(format!("{}-{unit}", args[0]).replace('/', "")))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        let warnings: Vec<&str> = err.lines().filter(|l| l.starts_with("warning:")).collect();
        if warned {
            assert_eq!(warnings.len(), 1, "{args:?}: {err}");
            assert!(
                warnings[0].contains("--record") && warnings[0].contains("kobe-1995.dat: PGA 6.803 g as read in g"),
                "{err}"
            );
        } else {
            assert!(warnings.is_empty(), "{args:?}: {err}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
