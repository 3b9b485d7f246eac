//! `rocking reproduce` as a user runs it, CI-sized (`--quick`): the files,
//! a report section per figure with the paper beside ours, the Fig. 4
//! sweep's period 1 at low A_v and period 2 near 2.0, output independent of
//! the thread count, and bad input (exit 2, one line naming the flag,
//! nothing written).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-reproduce-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn reproduce(args: &[&str], out: &Path) -> Output {
    rocking()
        .arg("reproduce")
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .expect("runs")
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "status {:?}, stderr: {}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `classes.csv` rows as (value, outcome, period).
fn classes(path: &Path) -> Vec<(f64, String, String)> {
    let text = std::fs::read_to_string(path).expect("classes.csv");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("value,outcome,period,max_abs_theta"));
    lines
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (c[0].parse().expect("value"), c[1].to_string(), c[2].to_string())
        })
        .collect()
}

#[test]
fn quick_fig4_and_fig12_write_figures_and_a_report_beside_the_paper() {
    let root = tmpdir("quick");
    let out = root.join("out");
    let o = reproduce(&["--quick", "--only", "fig4,fig12", "-q"], &out);
    ok(&o);
    assert!(o.stdout.is_empty(), "-q prints nothing");

    for name in [
        "fig04_bifurcation.png",
        "fig04_bifurcation.svg",
        "fig04_classes.csv",
        "fig04_points.csv",
        "fig04_variant_ralston_bifurcation.png",
        "fig04_variant_continuation-up_bifurcation.png",
        "fig04_variant_printed-eq20_classes.csv",
        "fig04_impact_ratio_map.png",
        "fig12_time_history.png",
        "fig12_time_history.svg",
        "fig12_spectrum_paper_window.png",
        "fig12_spectrum_long_window.svg",
        "fig12_poincare.png",
        "fig12_poincare.csv",
        "reproduce.json",
        "report.md",
    ] {
        let p = out.join(name);
        assert!(p.is_file(), "{name} missing");
        let bytes = std::fs::read(&p).expect("read");
        if name.ends_with(".png") {
            assert!(bytes.starts_with(b"\x89PNG"), "{name} is not a PNG");
        }
        if name.ends_with(".svg") {
            assert!(String::from_utf8_lossy(&bytes).contains("<svg"), "{name} is not an SVG");
        }
    }
    // Nothing of the figures not asked for, and no staging left behind.
    assert!(!out.join("fig03_bifurcation.png").exists());
    assert!(!out.join("fig07_time_history.png").exists());
    assert_eq!(std::fs::read_dir(&root).expect("root").count(), 1);

    // The Fig. 4 sweep (Ω = 8, A_h = 3, no sliding, r = 0.925, from rest):
    // period 1 at low A_v, period 2 near 2.0 (the paper: (1,1) up to 1.7,
    // (1,2) from 1.7 to 2.25).
    let rows = classes(&out.join("fig04_classes.csv"));
    assert_eq!(rows.len(), 13, "A_v 0 … 3 in steps of 0.25");
    for (v, outcome, period) in &rows {
        if *v <= 1.5 {
            assert_eq!((outcome.as_str(), period.as_str()), ("periodic", "1"), "A_v = {v}");
        }
        if (*v - 2.0).abs() < 1e-9 {
            assert_eq!((outcome.as_str(), period.as_str()), ("periodic", "2"), "A_v = {v}");
        }
    }

    // The report: a section per figure, the paper's words beside ours, the
    // investigation and the verdicts.
    let report = std::fs::read_to_string(out.join("report.md")).expect("report");
    assert!(report.contains("## Fig. 4: Bifurcation diagram"), "{report}");
    assert!(report.contains("## Fig. 12: Rocking response with sliding"));
    assert!(!report.contains("## Fig. 3:"));
    assert!(report.contains("Quick mode"));
    assert!(report.contains("a chaotic response after 2.3"), "the paper is quoted");
    assert!(report.contains("| 4 | A_v 0–1.7 | periodic (1,1) | run 0.00–1.50; 7/7 values | agrees |"));
    assert!(report.contains("| 4 | A_v 1.7–2.25 | periodic (1,2) |"));
    assert!(report.contains("## Investigation: where Fig. 4 differs, and why"));
    assert!(report.contains("VARIANT: the paper's Ralston RK2, step 0.004"));
    assert!(report.contains("| 12 | largest Lyapunov exponent | 0.71 |"));
    assert!(report.contains("![Fig. 12 (c) Poincaré map](fig12_poincare.png)"));
    assert!(report.contains("Computation wall time"));
    assert!(!report.contains("NaN"));

    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("reproduce.json")).expect("json")).expect("valid");
    assert_eq!(json["quick"], true);
    assert_eq!(json["responses"][0]["figure"], 12);
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn the_files_do_not_depend_on_the_thread_count() {
    let root = tmpdir("threads");
    let (one, two) = (root.join("one"), root.join("two"));
    ok(&reproduce(&["--quick", "--only", "fig5", "--threads", "1", "-q"], &one));
    ok(&reproduce(&["--quick", "--only", "fig5", "--threads", "2", "-q"], &two));
    let mut names: Vec<String> = std::fs::read_dir(&one)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(names.contains(&"fig05_bifurcation.png".to_string()));
    for name in names.iter().filter(|n| *n != "report.md") {
        assert_eq!(
            std::fs::read(one.join(name)).expect("one"),
            std::fs::read(two.join(name)).expect("two"),
            "{name} differs between 1 and 2 threads"
        );
    }
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn bad_input_exits_2_with_one_line_and_writes_nothing() {
    let root = tmpdir("bad");
    let out = root.join("out");
    let o = reproduce(&["--quick", "--only", "fig2"], &out);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: --only fig2"), "{err}");
    assert!(!out.exists());

    let file = root.join("a-file");
    std::fs::write(&file, "x").expect("file");
    let o = reproduce(&["--quick", "--only", "fig4"], &file);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.starts_with("error: --out"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).expect("file"), "x");

    let o = reproduce(&["--threads", "0", "--only", "fig4"], &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).starts_with("error: --threads 0"));
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&root);
}
