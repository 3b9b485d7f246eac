//! Sweeps and maps of a stack of blocks (`[[stack]]`): a glued stack of one
//! width classified as the single block of its height, cell for cell and
//! point for point in physical units; `rocking sweep` and `rocking map` of
//! a stack against its own `--batch` run sampled at the section times.

mod common;
use common::{CsvRow, csv_rows, scene};
use rocking::analysis::classify::{ClassifyOptions, Response};
use rocking::analysis::outcome_map::{Axis, BlockMap};
use rocking::analysis::steady::{Steady, Window, steady_response};
use rocking::sim::{Param, Scenario};
use std::path::PathBuf;
use std::process::Command;

const FORCING_HZ: f64 = 1.5;

/// A block of 0.5 × 1.0 m under a glued 0.5 × 0.8 m one, and the single
/// 0.5 × 1.8 m block without sliding, under `a_h` g at 1.5 Hz and the phase
/// `phase` rad.
fn pair(a_h: f64, phase: f64) -> (Scenario, Scenario) {
    let excitation = format!(
        "[excitation]\nkind = \"harmonic\"\na_h = \"{a_h} g\"\nomega_h = \"{FORCING_HZ} Hz\"\nphase_h = {phase:?}\n"
    );
    let stack = scene(&format!(
        "[[stack]]\nwidth = 0.5\nheight = 1.0\n[[stack]]\nwidth = 0.5\nheight = 0.8\nglued = true\n{excitation}"
    ));
    let block = scene(&format!(
        "[block]\nwidth = 0.5\nheight = 1.8\n[friction]\nstatic = \"inf\"\n{excitation}"
    ));
    (stack, block)
}

/// The window from 60 s to 120 s of physical time in `s`'s τ, its ends half
/// a forcing period off the section times so that both systems keep the
/// same section points.
fn window(s: &Scenario) -> Window {
    let p = s.geometry().p;
    let half = 0.5 / FORCING_HZ;
    Window {
        transient: (60.0 + half) * p,
        tau_end: (120.0 + half) * p,
    }
}

/// The top block's α of the glued stack, and the block's ψ.
fn angles() -> (f64, f64) {
    ((0.5_f64 / 0.8).atan(), (0.5_f64 / 1.8).atan())
}

fn compare(stack: &Steady, block: &Steady, ps: f64, pb: f64) {
    let (alpha, psi) = angles();
    assert_eq!(stack.response, block.response);
    let (ms, mb) = (stack.max_abs_theta * alpha, block.max_abs_theta * psi);
    assert!((ms - mb).abs() < 1e-9, "peak rotation {ms} rad against {mb} rad");
    assert_eq!(stack.points.len(), block.points.len());
    for (s, b) in stack.points.iter().zip(&block.points) {
        assert_eq!(s.k, b.k);
        assert!((s.tau / ps - b.tau / pb).abs() < 1e-9, "section times differ");
        let (ts, tb) = (s.theta * alpha, b.theta * psi);
        assert!((ts - tb).abs() < 1e-9, "k = {}: θ {ts} rad against {tb} rad", s.k);
        let (ws, wb) = (s.theta_dot * alpha * ps, b.theta_dot * psi * pb);
        assert!((ws - wb).abs() < 1e-8, "k = {}: θ' {ws} rad/s against {wb} rad/s", s.k);
    }
}

#[test]
fn a_glued_stack_of_one_width_sweeps_as_the_single_block_of_its_height() {
    let opts = ClassifyOptions::default();
    let mut seen = Vec::new();
    for (a_h, phase) in [(0.2, 0.0), (0.3, 0.0), (0.5, 0.0), (0.5, 1.0)] {
        let (stack, block) = pair(a_h, phase);
        let s = steady_response(&stack, &window(&stack), &opts, None).expect("stack");
        let b = steady_response(&block, &window(&block), &opts, None).expect("block");
        compare(&s, &b, stack.geometry().p, block.geometry().p);
        assert!(s.seed.is_none(), "a stack starts at rest: no seed");
        seen.push(s.response);
    }
    // Rest below the block's uplift (tan ψ = 0.278 g), a periodic rocking
    // cycle, tumbling and, at another phase, a cycle again.
    assert_eq!(
        seen,
        [
            Response::Rest,
            Response::Periodic { period: 1 },
            Response::Tumbled,
            Response::Periodic { period: 1 }
        ]
    );
}

#[test]
fn a_glued_stack_of_one_width_maps_as_the_single_block_of_its_height() {
    // The phase of each motion along both axes: radians in both systems.
    let (stack, block) = pair(0.5, 0.0);
    let axis = Axis::new("x", "excitation.phase_h", 0.0, 1.0, 3).expect("axis");
    let opts = ClassifyOptions::default();
    fn map<'a>(s: &'a Scenario, axis: &'a Axis, opts: ClassifyOptions) -> BlockMap<'a> {
        BlockMap {
            base: s,
            x_param: Param::PhaseH,
            x: axis,
            y_param: Param::PhaseV,
            y: axis,
            window: window(s),
            classify: opts,
            lyapunov: None,
        }
    }
    let (ms, mb) = (map(&stack, &axis, opts), map(&block, &axis, opts));
    ms.check().expect("a stack's map is accepted");
    let (alpha, psi) = angles();
    let mut classes = Vec::new();
    for x in axis.values() {
        let (cs, cb) = (
            ms.cell(x, 0.0, false, &[], None).expect("stack"),
            mb.cell(x, 0.0, false, &[], None).expect("block"),
        );
        assert_eq!(cs.response, cb.response, "phase {x}");
        assert!((cs.max_abs_theta * alpha - cb.max_abs_theta * psi).abs() < 1e-9);
        assert_eq!(cs.cycle.len(), cb.cycle.len());
        for (a, b) in cs.cycle.iter().zip(&cb.cycle) {
            assert!((a[0] * alpha - b[0] * psi).abs() < 1e-9, "cycle {a:?} against {b:?}");
        }
        assert_eq!(cs.stopped_at, None, "asked for the whole window");
        // Stopped as soon as it is certain: the same class, and a periodic
        // cycle converged to a hundredth of the classifier's tolerance.
        let early = ms.cell(x, 0.0, true, &[], None).expect("stack");
        assert_eq!(early.response, cs.response, "phase {x}");
        assert_eq!(early.stopped_at.is_some(), cs.response.period().is_some(), "phase {x}");
        assert_eq!(early.cycle.len(), cs.cycle.len());
        for (a, b) in early.cycle.iter().zip(&cs.cycle) {
            assert!(
                (a[0] - b[0]).abs() < 1e-6 * b[0].abs().max(1.0),
                "cycle {a:?} against {b:?}"
            );
        }
        classes.push(cs.response);
    }
    assert!(
        classes.contains(&Response::Tumbled) && classes.iter().any(|r| r.period().is_some()),
        "{classes:?}"
    );
}

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-stack-sweeps-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn run_ok(args: &[&str]) {
    let o = rocking().args(args).output().expect("run");
    assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
}

fn num(row: &CsvRow, key: &str) -> f64 {
    row[key].parse().unwrap_or_else(|_| panic!("{key} = {:?}", row[key]))
}

#[test]
fn a_stack_sweep_and_map_agree_with_its_batch_run_at_the_section_times() {
    let d = tmpdir("cli");
    let (sweep, map) = (d.join("sweep"), d.join("map"));
    let s = sweep.to_str().unwrap();
    let window = ["--transient", "400", "--tau-end", "600"];
    let preset = ["--preset", "stack-patterns"];
    let args = [
        "sweep",
        "--param",
        "excitation.a_h",
        "--from",
        "1.0",
        "--to",
        "1.2",
        "--step",
        "0.2",
        "-q",
        "--out",
        s,
    ];
    run_ok(&[&args[..], &window, &preset].concat());
    let classes = csv_rows(&sweep.join("classes.csv"));
    let periods: Vec<&str> = classes.iter().map(|r| r["period"].as_str()).collect();
    // A period-4 cycle at A_h = 1.0 and a period-1 one at 1.2.
    assert_eq!(periods, ["4", "1"]);
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(sweep.join("sweep.json")).unwrap()).unwrap();
    let omega = meta["config"]["excitation"]["omega_h"].as_f64().expect("omega_h");
    assert!(
        meta["units"].as_str().unwrap().contains("top block"),
        "{}",
        meta["units"]
    );
    let period = std::f64::consts::TAU / omega;
    let points = csv_rows(&sweep.join("points.csv"));
    // The top block (0.4 × 1.2 m) of the preset.
    let alpha = (0.4_f64 / 1.2).atan();
    for value in ["1.0", "1.2"] {
        let out = d.join(format!("batch-{value}"));
        let set_a = format!("excitation.a_h={value}");
        let set_dt = format!("run.output_dt={period:?}");
        let batch = [
            "--batch",
            "-q",
            "--set",
            &set_a,
            "--set",
            "run.tau_end=600",
            "--set",
            &set_dt,
            "--out",
            out.to_str().unwrap(),
        ];
        run_ok(&[&batch[..], &preset].concat());
        let history = csv_rows(&out.join("history.csv"));
        let mine: Vec<_> = points
            .iter()
            .filter(|p| num(p, "value") == value.parse::<f64>().unwrap())
            .collect();
        assert!(mine.len() >= 40, "{} points", mine.len());
        for p in mine {
            let k: usize = p["k"].parse().unwrap();
            let h = &history[k];
            assert!((num(h, "tau") - num(p, "tau")).abs() < 1e-9, "k = {k}");
            let top = num(h, "theta_1_rad");
            assert!(
                (num(p, "theta") * alpha - top).abs() < 1e-8,
                "k = {k}: {} against {top}",
                num(p, "theta") * alpha
            );
            let rate = num(h, "theta_dot_1_rad_s");
            let p_scale = num(h, "tau") / num(h, "t_s");
            assert!((num(p, "theta_dot") * alpha * p_scale - rate).abs() < 1e-7, "k = {k}");
        }
    }
    // The map's cells at the same values are the sweep's.
    let m = map.to_str().unwrap();
    let omega_s = format!("{omega:?}");
    let omega_2 = format!("{:?}", omega + 1.0);
    let args = [
        "map",
        "--x",
        "excitation.a_h",
        "1.0",
        "1.2",
        "2",
        "--y",
        "excitation.omega_h",
        &omega_s,
        &omega_2,
        "2",
        "-q",
        "--out",
        m,
    ];
    run_ok(&[&args[..], &window, &preset].concat());
    let cells = csv_rows(&map.join("map.csv"));
    for (cell, class) in cells.iter().take(2).zip(&classes) {
        assert_eq!(num(cell, "y"), omega);
        assert_eq!(cell["x"], class["value"]);
        assert_eq!(
            (&cell["outcome"], &cell["period"]),
            (&class["outcome"], &class["period"])
        );
        assert_eq!(cell["max_abs_theta"], class["max_abs_theta"]);
    }
    // Without --tau-end the study would end at the preset's own 20 s
    // (τ = 55.7), before the default transient: the message says so.
    let o = rocking()
        .args([
            "sweep",
            "--param",
            "excitation.a_h",
            "--from",
            "1.0",
            "--to",
            "1.2",
            "--step",
            "0.2",
            "--out",
        ])
        .arg(d.join("none"))
        .args(preset)
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(
        err.trim(),
        "error: --tau-end: not given, and the scene's run.tau_end = 55.70 ends before --transient 600: give --tau-end above the transient (the paper's window is 600 to 800)"
    );
    assert!(!d.join("none").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_stack_whose_friction_cannot_hold_stops_a_sweep_as_bad_input() {
    // A squat top block (B/H = 2) on friction 0.3: at A_h = 1 it would
    // slide long before it tips, and a stack's inner sliding is not
    // followed.
    let d = tmpdir("slip");
    let config = d.join("slip.toml");
    std::fs::write(
        &config,
        "[[stack]]\nwidth = 0.5\nheight = 2.0\n[[stack]]\nwidth = 0.6\nheight = 0.3\nstatic = 0.3\n\
         [excitation]\nkind = \"harmonic\"\na_h = \"0.5 g\"\nomega_h = \"1 Hz\"\n",
    )
    .unwrap();
    let out = d.join("out");
    let o = rocking()
        .args([
            "sweep",
            "--param",
            "excitation.a_h",
            "--from",
            "0.5",
            "--to",
            "1",
            "--step",
            "0.5",
        ])
        .args(["--tau-end", "900", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: excitation.a_h = 1: stack block 2's lower face would slip at t = "),
        "{err}"
    );
    assert!(
        err.contains("raise stack[1].static or set it to inf") && err.trim().lines().count() == 1,
        "{err}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// A stack's map stopped cell by cell as soon as each is certain gives
/// every cell the class `--full` gives it, over a corner of stack-patterns'
/// map that holds rest, periods 1, 5 and 6, chaos and overturning, and
/// cells that rest at every section time while lifting and chattering in
/// between (about 100 impacts a period) until they overturn at τ ≈ 330:
/// those must run their whole window, as `--full` does.
#[test]
fn a_stacks_map_stopped_early_classifies_every_cell_as_the_full_map() {
    let d = tmpdir("early");
    let map = |out: &str, full: bool| {
        let out = d.join(out);
        let mut args = vec!["map", "--preset", "stack-patterns", "--tau-end", "800"];
        args.extend(["--x", "excitation.a_h", "0.6", "1.5", "10"]);
        args.extend(["--y", "excitation.omega_h", "3.5", "4.0", "6"]);
        if full {
            args.push("--full");
        }
        let out_s = out.to_str().expect("utf-8 path");
        args.extend(["--out", out_s]);
        run_ok(&args);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("map.json")).expect("map.json")).expect("json");
        (
            csv_rows(&out.join("map.csv")),
            summary["cells_stopped_early"].as_u64().expect("count"),
        )
    };
    let (early, stopped) = map("early", false);
    let (full, none) = map("full", true);
    assert_eq!(none, 0);
    assert!(stopped >= 20, "{stopped} of 60 cells stopped early");
    assert_eq!(early.len(), 60);
    let class = |r: &CsvRow| format!("{} {}", r["outcome"], r["period"]);
    let mut seen: Vec<String> = Vec::new();
    for (a, b) in early.iter().zip(&full) {
        assert_eq!((&a["x"], &a["y"]), (&b["x"], &b["y"]));
        assert_eq!(class(a), class(b), "A_h {}, Ω_h {}", a["x"], a["y"]);
        if !seen.contains(&class(b)) {
            seen.push(class(b));
        }
    }
    for c in ["rest ", "periodic 1", "periodic 5", "chaotic ", "tumbled "] {
        assert!(seen.iter().any(|s| s == c), "{c:?} among {seen:?}");
    }
    // The chattering cells that rest at their section times ran out.
    let chatter = full
        .iter()
        .position(|r| r["x"] == "0.7" && r["y"] == "3.9")
        .expect("cell");
    assert_eq!(class(&full[chatter]), "tumbled ");
    let _ = std::fs::remove_dir_all(&d);
}
