//! The Lyapunov exponents of the bodies beyond the single block: a
//! `[[stack]]`'s largest by two trajectories (its tangent equations are not
//! written), a `[frame]`'s whole spectrum by the tangent dynamics its
//! equations generate and its largest by two trajectories, against
//! independent answers computed here:
//!
//! - the single block each is equivalent to (a glued stack of one width is
//!   the block of their height; a frame is Makris & Vassiliou's block),
//!   whose exponents come from the block's tangent dynamics, a different
//!   method on different equations;
//! - the exact value on a stable orbit with two impacts per cycle whose
//!   Floquet multipliers are a complex pair. Between impacts the rocking
//!   flow is conservative, so it keeps phase-space area; an impact with
//!   angular-velocity ratio r at Θ = 0 has the saltation matrix
//!   `[[r, 0], [·, r]]`, of determinant r². Over a cycle the two exponents
//!   then sum to 2 · ln r² = 4 ln r, and a complex pair shares it: each
//!   is 2 ln r per cycle.
//! - on any orbit of a frame that rocks throughout, the sum of its two
//!   exponents: the flow keeps area and each impact multiplies it by r²,
//!   so λ₁ + λ₂ = Σ_impacts ln r² over the window's length.

mod common;
use std::process::Command;

use common::{refusal, scene};
use rocking::analysis::lyapunov::{
    Lyapunov, LyapunovOptions, LyapunovResult, Method, NoExponent, method_for, of_scenario,
};
use rocking::sim::Scenario;

/// The exponents of `cfg` by `method` over its own run.
fn exponents(cfg: &Scenario, method: Method) -> LyapunovResult {
    match of_scenario(cfg, &LyapunovOptions::for_scenario(cfg, method)).expect("lyapunov") {
        Lyapunov::Exponents(r) => *r,
        other => panic!("no exponent: {other:?}"),
    }
}

/// Whether `a` and `b`, each with its standard error, agree within three
/// combined standard errors.
fn agree(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() <= 3.0 * (a.1 * a.1 + b.1 * b.1).sqrt()
}

/// The shaking of both tests: 0.5 g at 1.5 Hz for 800 s (in physical
/// units, so each body and its block feel the same motion whatever their
/// time unit). Every body here settles onto its period-1 orbit.
const SHAKING: &str = "[excitation]\nkind = \"harmonic\"\na_h = \"0.5 g\"\nomega_h = \"1.5 Hz\"\n[run]\nt_end = \"800 s\"\noutput_dt = 0\n";

/// Impacts per forcing cycle of `cfg`'s run after its transient (the
/// stack's and the frame's runs are their own `simulate`s).
fn impacts_per_cycle(events_tau: &[f64], period: f64, from: f64, to: f64) -> f64 {
    events_tau.iter().filter(|&&t| t > from && t <= to).count() as f64 / ((to - from) / period)
}

#[test]
fn a_glued_stacks_largest_exponent_is_its_single_blocks_and_housners() {
    let stack = scene(&format!(
        "[[stack]]\nwidth = 1.0\nheight = 2.5\n[[stack]]\nwidth = 1.0\nheight = 1.5\nglued = true\n{SHAKING}"
    ));
    let block = scene(&format!(
        "[block]\nwidth = 1.0\nheight = 4.0\n[impact]\nlaw = \"housner\"\n{SHAKING}"
    ));
    assert_eq!(method_for(&stack), Method::Benettin);
    assert_eq!(method_for(&block), Method::Tangent);
    let s = exponents(&stack, Method::Benettin);
    let b = exponents(&block, Method::Tangent);
    // The precondition of the exact value: the block's two exponents are
    // one complex pair.
    assert_eq!(b.spectrum.len(), 2);
    assert!(
        agree(
            (b.spectrum[0], b.spectrum_stderr[0]),
            (b.spectrum[1], b.spectrum_stderr[1])
        ),
        "{:?}",
        b.spectrum
    );
    // Two impacts a cycle, each of Housner's ratio for the whole stack's
    // α = atan(1/4) (docs/model.md §18.5: one body, the new pivot stuck).
    let run = rocking::sim::stack_run::simulate_stack(
        stack.stack_geometry().expect("geometry"),
        stack.excitation().expect("excitation"),
        stack.run.zeno_eps,
        &stack.run_options(),
    )
    .expect("run");
    let impacts: Vec<f64> = run
        .events
        .iter()
        .filter(|e| e.kind.name() == "impact")
        .map(|e| e.tau)
        .collect();
    let n = impacts_per_cycle(&impacts, s.period, s.tau_start, s.tau_end);
    assert!((n - 2.0).abs() < 0.01, "{n} impacts a cycle");
    let alpha = (1.0f64 / 4.0).atan();
    let exact = 2.0 * (1.0 - 1.5 * alpha.sin().powi(2)).ln();
    eprintln!(
        "stack {:.5} ± {:.5}, block {:.5} ± {:.5}, exact {exact:.5} per cycle",
        s.per_cycle, s.stderr_per_cycle, b.per_cycle, b.stderr_per_cycle
    );
    assert!(agree(
        (s.per_cycle, s.stderr_per_cycle),
        (b.per_cycle, b.stderr_per_cycle)
    ));
    assert!(agree((s.per_cycle, s.stderr_per_cycle), (exact, 0.0)));
    assert!(s.stderr_per_cycle < 0.01, "a usable error bar: {}", s.stderr_per_cycle);
    assert_eq!(s.neutral, "u");
    assert!(s.spectrum.is_empty() && s.check.is_none());
}

#[test]
fn a_frames_exponents_are_its_equivalent_blocks_and_its_restitutions() {
    let gamma: f64 = 0.5;
    let frame = scene(&format!(
        "[frame]\nwidth = 1.0\nheight = 4.0\nbeam_mass_ratio = {gamma:?}\n{SHAKING}"
    ));
    // Makris & Vassiliou (2013): the block of the same α and half-diagonal
    // R/κ, with the frame's impact ratio.
    let kappa = (1.0 + 2.0 * gamma) / (1.0 + 3.0 * gamma);
    let alpha = (1.0f64 / 4.0).atan();
    let r = (1.0 - 1.5 * alpha.sin().powi(2) + 3.0 * gamma * (2.0 * alpha).cos()) / (1.0 + 3.0 * gamma);
    let block = scene(&format!(
        "[block]\nwidth = {:?}\nheight = {:?}\n[impact]\nlaw = \"ratio\"\nr = {r:?}\n{SHAKING}",
        1.0 / kappa,
        4.0 / kappa
    ));
    assert_eq!(method_for(&frame), Method::Tangent);
    let f = exponents(&frame, Method::Benettin);
    let ft = exponents(&frame, Method::Tangent);
    let b = exponents(&block, Method::Tangent);
    assert!(agree(
        (b.spectrum[0], b.spectrum_stderr[0]),
        (b.spectrum[1], b.spectrum_stderr[1])
    ));
    let res = rocking::sim::simulate(frame.model().expect("model"), &frame.initial, &frame.run_options()).expect("run");
    let impacts: Vec<f64> = res
        .events
        .iter()
        .filter(|e| e.kind.name() == "impact")
        .map(|e| e.tau)
        .collect();
    let n = impacts_per_cycle(&impacts, f.period, f.tau_start, f.tau_end);
    assert!((n - 2.0).abs() < 0.01, "{n} impacts a cycle");
    let exact = 2.0 * r.ln();
    eprintln!(
        "frame {:.5} ± {:.5}, block {:.5} ± {:.5}, exact {exact:.5} per cycle",
        f.per_cycle, f.stderr_per_cycle, b.per_cycle, b.stderr_per_cycle
    );
    assert!(agree(
        (f.per_cycle, f.stderr_per_cycle),
        (b.per_cycle, b.stderr_per_cycle)
    ));
    assert!(agree((f.per_cycle, f.stderr_per_cycle), (exact, 0.0)));
    assert_eq!(f.neutral, "X");
    // The whole spectrum by the frame's generated tangent dynamics: each
    // exponent per cycle is the equivalent block's and 2 ln r.
    let per_cycle = |r: &LyapunovResult, i: usize| {
        let k = r.per_cycle / r.largest_per_tau;
        (r.spectrum[i] * k, r.spectrum_stderr[i] * k)
    };
    assert_eq!(ft.spectrum.len(), 2, "{:?}", ft.spectrum);
    for i in 0..2 {
        eprintln!(
            "frame λ{} {:.5} ± {:.5}, block {:.5} ± {:.5} per cycle",
            i + 1,
            per_cycle(&ft, i).0,
            per_cycle(&ft, i).1,
            per_cycle(&b, i).0,
            per_cycle(&b, i).1
        );
        assert!(agree(per_cycle(&ft, i), per_cycle(&b, i)), "λ{}", i + 1);
        assert!(agree(per_cycle(&ft, i), (exact, 0.0)), "λ{}", i + 1);
    }
}

/// On an orbit that rocks throughout, a frame's two exponents sum to the
/// log of the area its impacts keep: the rocking flow's Jacobian has trace
/// 0 (Θ'' reads Θ alone), and an impact's saltation matrix has determinant
/// r² whatever the state, so λ₁ + λ₂ = n ln r² / (τ_end − τ_start) with n
/// the impacts in the window. The scene (1 g at 2 Hz) is not a period-1
/// orbit with two impacts a cycle: its exponents are not 2 ln r per cycle
/// each, and only their sum is known.
#[test]
fn a_frames_two_exponents_sum_to_the_log_of_its_impacts_area() {
    let gamma: f64 = 0.5;
    let frame = scene(&format!(
        "[frame]\nwidth = 1.0\nheight = 4.0\nbeam_mass_ratio = {gamma:?}\n[excitation]\nkind = \"harmonic\"\na_h = \"1 g\"\nomega_h = \"2 Hz\"\n[run]\nt_end = \"400 s\"\noutput_dt = 0\n"
    ));
    let f = exponents(&frame, Method::Tangent);
    let alpha = (1.0f64 / 4.0).atan();
    let r = (1.0 - 1.5 * alpha.sin().powi(2) + 3.0 * gamma * (2.0 * alpha).cos()) / (1.0 + 3.0 * gamma);
    let res = rocking::sim::simulate(frame.model().expect("model"), &frame.initial, &frame.run_options()).expect("run");
    assert!(
        res.events.iter().all(|e| e.kind.name() != "rest"),
        "it rocks throughout"
    );
    let n = res
        .events
        .iter()
        .filter(|e| e.kind.name() == "impact" && e.tau >= f.tau_start && e.tau < f.tau_end)
        .count();
    let sum = n as f64 * 2.0 * r.ln() / (f.tau_end - f.tau_start);
    let (l1, l2) = (f.spectrum[0], f.spectrum[1]);
    eprintln!(
        "λ₁ {l1:.6}, λ₂ {l2:.6}, sum {:.12} against {sum:.12} from {n} impacts",
        l1 + l2
    );
    assert!(((l1 + l2) - sum).abs() <= 1e-9 * sum.abs(), "{} against {sum}", l1 + l2);
    assert!(l1 >= l2, "ordered: {l1} {l2}");
    assert!(
        (f.per_cycle - 2.0 * r.ln()).abs() > 0.1,
        "another orbit: {}",
        f.per_cycle
    );
}

#[test]
fn a_stack_that_never_lifts_has_no_exponent_and_says_it_rests() {
    let stack = scene(
        "[[stack]]\nwidth = 1.0\nheight = 2.0\n[[stack]]\nwidth = 0.6\nheight = 1.0\n[excitation]\nkind = \"harmonic\"\na_h = \"0.05 g\"\nomega_h = \"2 Hz\"\n[run]\nt_end = \"100 s\"\n",
    );
    let opts = LyapunovOptions::for_scenario(&stack, Method::Benettin);
    match of_scenario(&stack, &opts).expect("lyapunov") {
        Lyapunov::None {
            no_exponent, method, ..
        } => {
            assert_eq!(no_exponent, NoExponent::Rest);
            assert_eq!(method, Method::Benettin);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_stack_asked_for_tangent_exponents_is_told_the_method_it_has() {
    {
        let body = "[[stack]]\nwidth = 1.0\nheight = 2.0\n[[stack]]\nwidth = 0.6\nheight = 1.0\n";
        for method in ["tangent", "both"] {
            let e = refusal(&format!(
                "{body}{SHAKING}[analysis]\nlyapunov = true\nlyapunov_method = \"{method}\"\n"
            ));
            assert!(
                e.starts_with(&format!(
                    "analysis.lyapunov_method: \"{method}\" needs tangent equations"
                )),
                "{e}"
            );
            assert!(e.contains("\"benettin\""), "{e}");
            assert!(!e.contains('\n'), "one line: {e}");
        }
        // The library refuses it too, for a scene built without the check.
        let cfg = scene(&format!("{body}{SHAKING}"));
        let err = of_scenario(&cfg, &LyapunovOptions::for_scenario(&cfg, Method::Tangent)).expect_err("refused");
        assert!(err.is_input() && err.to_string().contains("\"benettin\""), "{err}");
    }
}

#[test]
fn batch_adds_a_stacks_exponent_to_its_summary_and_its_report() {
    let out = std::env::temp_dir().join(format!("rocking-lyapunov-stack-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["--batch", "--preset", "stack-patterns"])
        // No method named: a stack's default is the one it has.
        .args(["--set", "analysis.lyapunov=true"])
        .args(["--set", "run.tau_end=400", "--out"])
        .arg(&out)
        .output()
        .expect("rocking");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(stdout.contains("lyapunov (benettin): largest -"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    let l = &summary["lyapunov"];
    assert_eq!(l["method"], "benettin");
    assert_eq!(summary["config"]["analysis"]["lyapunov_method"], "benettin");
    assert_eq!(l["neutral"], "u (exponent 0, not listed)");
    let per_tau = l["largest_per_tau"].as_f64().expect("a number");
    let per_cycle = l["per_cycle"].as_f64().expect("a number");
    // per cycle = per τ × 2π/Ω_h, Ω_h the stack's (its bottom block's τ).
    let omega = summary["config"]["excitation"]["omega_h"].as_f64().expect("Ω_h");
    assert!((per_cycle - per_tau * std::f64::consts::TAU / omega).abs() < 1e-12);
    assert!(per_tau < 0.0, "stack-patterns settles onto a stable orbit: {per_tau}");
    std::fs::remove_dir_all(&out).ok();
}

/// `--batch` on a harmonic frame with no method named writes both of its
/// exponents by tangent dynamics, the same as the library's.
#[test]
fn batch_writes_a_frames_spectrum_by_tangent_dynamics() {
    let out = std::env::temp_dir().join(format!("rocking-lyapunov-frame-batch-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["--batch", "--preset", "rocking-frame"])
        .args(["--set", "excitation.kind=harmonic", "--set", "excitation.a_h=\"0.5 g\""])
        .args(["--set", "excitation.omega_h=\"1.5 Hz\"", "--set", "run.t_end=\"300 s\""])
        .args(["--set", "analysis.lyapunov=true", "--out"])
        .arg(&out)
        .output()
        .expect("rocking");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(stdout.contains("lyapunov (tangent): largest -"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    let l = &summary["lyapunov"];
    assert_eq!(l["method"], "tangent");
    let spectrum: Vec<f64> = l["spectrum"]
        .as_array()
        .expect("a spectrum")
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect();
    assert_eq!(spectrum.len(), 2, "{spectrum:?}");
    let sets = [
        "excitation.kind=harmonic",
        "excitation.a_h=\"0.5 g\"",
        "excitation.omega_h=\"1.5 Hz\"",
        "run.t_end=\"300 s\"",
    ]
    .map(String::from);
    let cfg = rocking::io::config::load(Some("rocking-frame"), None, &sets).expect("scene");
    let own = exponents(&cfg, Method::Tangent);
    assert_eq!(own.spectrum, spectrum);
    std::fs::remove_dir_all(&out).ok();
}

/// A frame's sweep with `--lyapunov` used to leave the column empty without
/// a word (the block's tangent method refused it and the hook read that as
/// "no exponent"); it now holds the frame's exponent by the method a frame
/// has (`method_for`).
#[test]
fn a_frame_sweep_writes_each_values_exponent() {
    let dir = std::env::temp_dir().join(format!("rocking-lyapunov-frame-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let config = dir.join("frame.toml");
    std::fs::write(
        &config,
        "[frame]\nwidth = 1.0\nheight = 4.0\nbeam_mass_ratio = 0.5\n[excitation]\nkind = \"harmonic\"\na_h = \"0.5 g\"\nomega_h = \"1.5 Hz\"\n",
    )
    .expect("config");
    let out = dir.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(["sweep", "--config"])
        .arg(&config)
        .args(["--param", "excitation.a_h"])
        .args(["--from", "1.5", "--to", "2.0", "--step", "0.5"])
        .args(["--tau-end", "700", "--lyapunov", "--out"])
        .arg(&out)
        .output()
        .expect("rocking");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let text = std::fs::read_to_string(out.join("classes.csv")).expect("classes.csv");
    let rows: Vec<Vec<&str>> = text.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2);
    for row in rows {
        let value = row[0];
        let written: f64 = row[4]
            .parse()
            .unwrap_or_else(|_| panic!("A_h {value}: no exponent written"));
        let sets = [format!("excitation.a_h={value}"), "run.tau_end=700".to_string()];
        let cfg = rocking::io::config::load(None, Some(&config), &sets).expect("scene");
        let own = of_scenario(&cfg, &LyapunovOptions::for_scenario(&cfg, method_for(&cfg)))
            .expect("lyapunov")
            .largest_per_tau()
            .expect("an exponent");
        assert_eq!(own.to_bits(), written.to_bits(), "A_h {value}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
