//! A stack of blocks (`[[stack]]`) in the engineering commands, run as a
//! user runs them: `rocking spectrum` scales the whole stack and agrees
//! with `--batch` on the stack's own size; a glued stack of one width
//! gives the single block's spectrum and fragility; the commands and
//! flags that cannot take a stack refuse it with one line, exit 2,
//! nothing written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const KOBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/kobe-1995.dat");
const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-stack-studies-{}-{name}", std::process::id()));
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

/// Column `name` of the CSV file `path`, as text.
fn column(path: &Path, name: &str) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("csv");
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let i = rows[0]
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows[1..].iter().map(|r| r[i].to_string()).collect()
}

/// Column `name` as numbers, an empty cell (no such time) as NaN.
fn numbers(path: &Path, name: &str) -> Vec<f64> {
    column(path, name)
        .iter()
        .map(|c| {
            if c.is_empty() {
                f64::NAN
            } else {
                c.parse().expect("number")
            }
        })
        .collect()
}

#[test]
fn the_tombstone_spectrum_at_its_own_size_is_its_batch_run() {
    // The preset's stones: 0.75 × 0.30, 0.50 × 0.25 and 0.27 × 0.80 m, so
    // the bounding block is 0.75 × 1.35 m, R = ½√(0.75² + 1.35²).
    let r = 0.5 * 0.75f64.hypot(1.35);
    let d = tmpdir("own");
    let batch = d.join("batch");
    ok(&rocking()
        .args(["--batch", "--preset", "tombstone", "-q", "--out"])
        .arg(&batch)
        .output()
        .unwrap());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(batch.join("summary.json")).unwrap()).unwrap();
    let t_batch = summary["physical"]["t_overturn_s"]
        .as_f64()
        .expect("the top stone overturns");
    let out = d.join("spectrum");
    let said = ok(&rocking()
        .args([
            "spectrum",
            "--preset",
            "tombstone",
            "--record",
            KOBE,
            "--unit",
            "m/s2",
            "--count",
            "1",
        ])
        .args(["--from", &r.to_string(), "--to", &r.to_string(), "--out"])
        .arg(&out)
        .output()
        .unwrap());
    let csv = out.join("spectrum.csv");
    assert_eq!(column(&csv, "end"), ["overturned"]);
    // The same stones at the same size: the scale factor is 1 to a few
    // ulps, so the times agree far below the solver's tolerance.
    let t = numbers(&csv, "t_overturn_s")[0];
    assert!((t - t_batch).abs() < 1e-9, "{t} s vs --batch {t_batch} s");
    assert!((numbers(&csv, "width_m")[0] - 0.75).abs() < 1e-12);
    assert!((numbers(&csv, "height_m")[0] - 1.35).abs() < 1e-12);
    let b_over_h = numbers(&csv, "b_over_h")[0];
    assert!((b_over_h - 0.75 / 1.35).abs() < 1e-15, "{b_over_h}");
    // The answer names the body that went over.
    assert!(
        said.contains("3-block stack, B/H = 0.556: 1 of 1 overturned (top block 1)"),
        "{said}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("spectrum.json")).unwrap()).unwrap();
    assert_eq!(json["stack"]["blocks"], 3);
}

/// A glued stack of three 0.4 m wide blocks on a free bottom face, and
/// the 0.4 × 1.5 m block it is.
const GLUED: &str = "[[stack]]\nwidth = 0.4\nheight = 0.5\n[[stack]]\nwidth = 0.4\nheight = 0.5\nglued = true\n[[stack]]\nwidth = 0.4\nheight = 0.5\nglued = true\n";
const BLOCK: &str = "[block]\nwidth = 0.4\nheight = 1.5\n";

#[test]
fn a_glued_stack_of_one_width_has_the_single_blocks_spectrum() {
    let d = tmpdir("glued-spectrum");
    let (stack_toml, block_toml) = (d.join("stack.toml"), d.join("block.toml"));
    std::fs::write(&stack_toml, GLUED).unwrap();
    std::fs::write(&block_toml, BLOCK).unwrap();
    let run = |config: &Path, extra: &[&str], out: &Path| {
        ok(&rocking()
            .args([
                "spectrum", "--record", KOBE, "--unit", "m/s2", "--from", "0.2", "--to", "3", "--count", "8",
            ])
            .args(extra)
            .arg("--config")
            .arg(config)
            .args(["-q", "--out"])
            .arg(out)
            .output()
            .unwrap())
    };
    let (s, b) = (d.join("s"), d.join("b"));
    run(&stack_toml, &[], &s);
    run(&block_toml, &["--b-over-h", &(0.4f64 / 1.5).to_string()], &b);
    let (cs, cb) = (s.join("spectrum.csv"), b.join("spectrum.csv"));
    assert_eq!(column(&cs, "end"), column(&cb, "end"));
    for name in ["r_m", "p_per_s"] {
        for (x, y) in numbers(&cs, name).iter().zip(numbers(&cb, name)) {
            assert!((x - y).abs() < 1e-12 * y, "{name}: {x} vs {y}");
        }
    }
    // Peak rotation: the stack's is over a glued block's own α =
    // atan(0.4/0.5), the block's over atan(0.4/1.5); in radians they are
    // the one body's rotation; the two runs step in other units (the
    // stack's τ is its bottom block's, the block's its own), so they agree
    // to the solver's tolerance
    // (rtol 1e-10; 3.7e-14 rad measured over 200 sizes under Kobe).
    let (a_part, a_whole) = (0.8f64.atan(), (0.4f64 / 1.5).atan());
    let ends = column(&cs, "end");
    for (i, (x, y)) in numbers(&cs, "peak_theta_over_alpha")
        .iter()
        .zip(numbers(&cb, "peak_theta_over_alpha"))
        .enumerate()
    {
        if ends[i] != "overturned" {
            assert!((x * a_part - y * a_whole).abs() < 1e-10, "row {i}: {x} vs {y}");
        }
    }
    assert!(
        ends.iter().any(|e| e == "overturned") && ends.iter().any(|e| e == "rest"),
        "{ends:?}"
    );
}

#[test]
fn a_glued_stack_of_one_width_has_the_single_blocks_fragility() {
    let d = tmpdir("glued-fragility");
    let (stack_toml, block_toml) = (d.join("stack.toml"), d.join("block.toml"));
    std::fs::write(&stack_toml, GLUED).unwrap();
    std::fs::write(&block_toml, BLOCK).unwrap();
    let run = |config: &Path, extra: &[&str], out: &Path| {
        ok(&rocking()
            .args([
                "fragility",
                "--records",
                ELCENTRO,
                "--unit",
                "g",
                "--levels",
                "0.1:1.2:12",
            ])
            .args(extra)
            .arg("--config")
            .arg(config)
            .args(["-q", "--out"])
            .arg(out)
            .output()
            .unwrap())
    };
    let (s, b) = (d.join("s"), d.join("b"));
    // The stack at its own size (no --block), the block named; the
    // figure names the stack.
    run(&stack_toml, &[], &s);
    let svg = std::fs::read_to_string(s.join("fragility.svg")).unwrap();
    assert!(svg.contains("3-block stack 0.4 × 1.5 m"), "the figure names the stack");
    run(&block_toml, &["--block", "0.4x1.5"], &b);
    let (rs, rb) = (s.join("runs.csv"), b.join("runs.csv"));
    let ends = column(&rs, "end");
    assert_eq!(ends, column(&rb, "end"));
    assert!(
        ends.iter().any(|e| e == "overturned") && ends.iter().any(|e| e == "rest"),
        "{ends:?}"
    );
    for (x, y) in numbers(&rs, "t_overturn_s")
        .iter()
        .zip(numbers(&rb, "t_overturn_s"))
        .filter(|(x, _)| !x.is_nan())
    {
        assert!((x - y).abs() < 1e-10, "{x} vs {y}");
    }
}

#[test]
fn the_commands_and_flags_that_cannot_take_a_stack_refuse_it_in_one_line() {
    let d = tmpdir("refusals");
    let out = d.join("out");
    let tomb = ["--preset", "tombstone"];
    let kobe = ["--record", KOBE, "--unit", "m/s2"];
    let suite = ["fragility", "--records", KOBE, "--unit", "m/s2", "--levels", "0.5"];
    let patterns = ["--preset", "stack-patterns"];
    let cases: [(Vec<&str>, &[&str]); 7] = [
        // What a sweep or a map of a stack cannot vary or compute.
        (
            [
                &[
                    "sweep",
                    "--param",
                    "block.width",
                    "--from",
                    "0.1",
                    "--to",
                    "0.3",
                    "--step",
                    "0.1",
                    "--tau-end",
                    "700",
                ][..],
                &patterns,
            ]
            .concat(),
            &["block.width: is not read by a [[stack]]", "vary an excitation key"],
        ),
        (
            [
                &["spectrum", "--from", "0.5", "--to", "2", "--b-over-h", "0.2"][..],
                &tomb,
                &kobe,
            ]
            .concat(),
            &["--b-over-h", "keeps its own shape", "B/H = 0.5556"],
        ),
        (
            [&suite[..], &tomb, &["--block", "1x2"]].concat(),
            &["--block 1x2", "B/H = 0.5556"],
        ),
        (
            [&suite[..], &tomb, &["--im", "pga-tan-alpha"]].concat(),
            &["--im: a [[stack]] has no one slenderness", "use pga, pgv or sa"],
        ),
        // A block scene without --block.
        (suite.to_vec(), &["--block: give at least one block"]),
        (
            [&["sliding-spectrum", "--mu", "0.1,0.2"][..], &kobe, &tomb].concat(),
            &["stack: sliding-spectrum", "varies a single block's friction"],
        ),
        (
            [&["pulse-map"][..], &tomb].concat(),
            &["stack: pulse-map", "rocking spectrum --pulse"],
        ),
    ];
    for (args, needles) in cases {
        let o = rocking().args(&args).arg("--out").arg(&out).output().unwrap();
        refused(&o, needles, &out);
    }
}

#[test]
fn a_stack_sweep_takes_each_values_largest_exponent_from_two_trajectories() {
    use rocking::analysis::lyapunov::{LyapunovOptions, Method, of_scenario};
    let d = tmpdir("lyapunov");
    let out = d.join("out");
    ok(&rocking()
        .args(["sweep", "--preset", "stack-patterns", "--param", "excitation.a_h"])
        .args(["--from", "0.8", "--to", "1.0", "--step", "0.1"])
        .args(["--tau-end", "700", "--lyapunov", "--out"])
        .arg(&out)
        .output()
        .expect("rocking"));
    let classes = out.join("classes.csv");
    let values = numbers(&classes, "value");
    let exponents = numbers(&classes, "lyapunov");
    assert_eq!(values.len(), 3);
    for (v, l) in values.iter().zip(&exponents) {
        // The value's own scene over the sweep's window, by the stack's
        // method: the same number, bit for bit.
        let sets = [format!("excitation.a_h={v}"), "run.tau_end=700".to_string()];
        let cfg = rocking::io::config::load(Some("stack-patterns"), None, &sets).expect("scene");
        let own = of_scenario(&cfg, &LyapunovOptions::for_scenario(&cfg, Method::Benettin))
            .expect("lyapunov")
            .largest_per_tau()
            .expect("an exponent");
        assert_eq!(own.to_bits(), l.to_bits(), "A_h {v}: {own} vs {l}");
        // stack-patterns rocks on stable orbits here.
        assert!(*l < 0.0, "A_h {v}: {l}");
    }
    let _ = std::fs::remove_dir_all(&d);
}
