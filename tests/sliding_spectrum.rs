//! The sliding spectrum (`rocking sliding-spectrum`): the block that cannot
//! rock against the rigid-plastic sliding block computed independently
//! here, in closed form under a half-sine pulse and by an exact
//! piecewise-closed-form Newmark integration on the El Centro record; the
//! command on El Centro; byte-identical output for any thread count; bad
//! input refused in one line, exit 2.
//!
//! Physical units throughout (m, s, g = 9.81 m/s², the crate's g): the
//! block's relative displacement x (+x to the right) obeys
//! ẍ = −a(t) − s μ_k g while it slips in direction s, and sticks when ẋ
//! returns to 0 unless |a| > μ_s g (Newmark 1965). Nothing here calls the
//! crate's dynamics, events or integrator.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rocking::analysis::engineering::sliding_spectrum::{SlidingSpec, sliding_spectrum};
use rocking::analysis::engineering::{BlockSize, Drive, EndState};
use rocking::io::record::{RecordSpec, read_record_as};
use rocking::model::units::AccelUnit;
use rocking::sim::Scenario;
use rocking::sim::scenario::{Record, ShapeKind};

const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");

/// The crate's g, m/s² (MODEL-DECISIONS: one constant, 9.81).
const G: f64 = 9.81;

fn el_centro() -> Drive {
    let path = PathBuf::from(ELCENTRO);
    let loaded = read_record_as(
        &path,
        &RecordSpec {
            unit: Some(AccelUnit::G),
            dt: None,
            channel: None,
        },
    )
    .unwrap();
    Drive::Record(Record {
        path,
        series: loaded.series,
        unit: loaded.unit,
        dt: None,
        crc32: loaded.crc32,
        channel: None,
    })
}

/// The two columns of a text record (s, g), read here.
fn columns(path: &str) -> (Vec<f64>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut it = l.split_whitespace().map(|v| v.parse::<f64>().unwrap());
            (it.next().unwrap(), it.next().unwrap())
        })
        .unzip()
}

/// The smallest root u > 0 of c2 u² + c1 u + c0 (with `from_rest`, c0 = 0
/// and the root u = 0 itself is the start, not a stop).
fn first_positive_root(c2: f64, c1: f64, c0: f64, from_rest: bool) -> Option<f64> {
    let roots: Vec<f64> = if from_rest {
        if c2 != 0.0 { vec![-c1 / c2] } else { vec![] }
    } else if c2 == 0.0 {
        if c1 != 0.0 { vec![-c0 / c1] } else { vec![] }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            vec![]
        } else {
            // The cancellation-free pair of roots.
            let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
            let mut r = vec![q / c2];
            if q != 0.0 {
                r.push(c0 / q);
            }
            r
        }
    };
    roots.into_iter().filter(|&u| u > 0.0).min_by(f64::total_cmp)
}

/// Newmark's rigid-plastic sliding block on the piecewise-linear record
/// (`times_s`, `accel_g`·`scale`), ground at rest (a = 0) after the last
/// sample, integrated exactly: on each interval a(t) = a₀ + k τ is linear,
/// so while the block slips in direction s its relative velocity
/// v = v₀ − a₀τ − ½kτ² − sμ_k g τ is a quadratic and x a cubic in τ, and
/// the stick time is a root of the quadratic; while it sticks, slip starts
/// where the linear |a| reaches μ_s g, in direction −sign a. Returns
/// (peak |x|, final x), m. x is monotone while the block slips, so its
/// extremes are at stick times and at the end.
fn newmark(times_s: &[f64], accel_g: &[f64], scale: f64, mu_s: f64, mu_k: f64) -> (f64, f64) {
    let (mut x, mut v, mut s, mut peak) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    let n = times_s.len();
    for i in 0..n {
        // The interval [t_i, t_{i+1}], or after the record for ever.
        let (a0, k, h) = if i + 1 < n {
            let h = times_s[i + 1] - times_s[i];
            let (a0, a1) = (G * scale * accel_g[i], G * scale * accel_g[i + 1]);
            (a0, (a1 - a0) / h, h)
        } else {
            (0.0, 0.0, f64::INFINITY)
        };
        if i == 0 && accel_g[0].abs() * scale * G > mu_s * G {
            s = -(accel_g[0]).signum();
        }
        let mut tau = 0.0;
        while tau < h {
            let a_here = a0 + k * tau;
            let rem = h - tau;
            if s != 0.0 {
                let (c2, c1, c0) = (-0.5 * k, -(a_here + s * mu_k * G), v);
                let advance = |u: f64| (v * u + 0.5 * c1 * u * u + c2 * u * u * u / 3.0, v + c1 * u + c2 * u * u);
                match first_positive_root(c2, c1, c0, v == 0.0).filter(|&u| u <= rem) {
                    Some(u) => {
                        x += advance(u).0;
                        v = 0.0;
                        s = 0.0;
                        tau += u;
                        peak = peak.max(x.abs());
                        let a_now = a0 + k * tau;
                        if a_now.abs() > mu_s * G {
                            s = -a_now.signum();
                        }
                    }
                    None => {
                        let (dx, v_end) = advance(rem);
                        x += dx;
                        v = v_end;
                        tau = h;
                    }
                }
            } else {
                // Stuck: the first u in (0, rem] where a reaches ±μ_s g.
                let crossing = if k == 0.0 {
                    None
                } else {
                    [mu_s * G, -mu_s * G]
                        .into_iter()
                        .map(|target| (target - a_here) / k)
                        .filter(|&u| u > 0.0 && u <= rem)
                        .min_by(f64::total_cmp)
                };
                match crossing {
                    Some(u) => {
                        tau += u;
                        s = -(a0 + k * tau).signum();
                    }
                    None => tau = h,
                }
            }
        }
    }
    peak = peak.max(x.abs());
    (peak, x)
}

/// The slide-only answers of `mu` under `drive` (scale 1), through the
/// library, with the given block `block`.
fn slide_only(drive: &Drive, block: BlockSize, mu: Vec<f64>, kinetic_ratio: f64) -> Vec<(f64, f64, f64, EndState)> {
    let base = Scenario::default();
    let spec = SlidingSpec {
        base: &base,
        drive,
        scale: 1.0,
        block,
        mu,
        kinetic_ratio,
    };
    spec.check().unwrap();
    sliding_spectrum(&spec, &rocking::analysis::silent)
        .unwrap()
        .iter()
        .map(|p| {
            let r = p.slide_only;
            assert_eq!(
                r.peak_theta_over_alpha, 0.0,
                "the slide-only block rocked at μ = {}",
                p.mu_s
            );
            (p.mu_s, r.peak_sliding_m, r.residual_sliding_m.unwrap(), r.end)
        })
        .collect()
}

/// The rigid-plastic block under a half-sine pulse a(t) = A g sin(ωt),
/// 0 ≤ t ≤ π/ω (then 0), in closed form (as `engineering_physics.rs` has it
/// in τ, here in seconds): slip to −x starts at t₀, A sin ωt₀ = μ_s; then
///
///   v(t) = μ_k g (t − t₀) + (A g/ω)(cos ωt − cos ωt₀),
///   x(t) = ½ μ_k g (t − t₀)² + (A g/ω²)(sin ωt − sin ωt₀) − (A g/ω) cos ωt₀ (t − t₀)
///
/// to the pulse's end T = π/ω (the cases keep v(T) < 0, checked), after
/// which v rises at μ_k g to 0, adding −v(T)²/(2 μ_k g). One slip, so the
/// peak is |x_final|. Checked to 1e-9 relative, as that test: rtol 1e-10 on
/// an O(1) state over a handful of steps, switches located to round-off.
#[test]
fn the_block_that_cannot_rock_slides_as_the_closed_form_rigid_plastic_block_under_a_half_sine_pulse() {
    // (A in g, pulse duration T = π/ω in s, μ_s, μ_k/μ_s), on a slender
    // block (0.3 × 1.5 m) that would rock: the slide-only block must not.
    for (amp, duration, mu_s, ratio) in [
        (0.9, 0.4, 0.3, 1.0),
        (1.2, 1.0, 0.35, 0.3 / 0.35),
        (1.5, 0.25, 0.5, 0.8),
    ] {
        let omega = PI / duration;
        let drive = Drive::PhysicalPulse {
            shape: ShapeKind::HalfSine,
            cycles: 1,
            a_p_g: amp,
            // The crate's pulse frequency: a half-sine of frequency ω lasts π/ω.
            omega_p: omega,
        };
        let mu_k = ratio * mu_s;
        let t0 = (mu_s / amp).asin() / omega;
        let v_end = mu_k * G * (duration - t0) + (amp * G / omega) * (-1.0 - (omega * t0).cos());
        assert!(v_end < 0.0, "still sliding when the pulse ends");
        let x_end = 0.5 * mu_k * G * (duration - t0).powi(2) + (amp * G / (omega * omega)) * (0.0 - (omega * t0).sin())
            - (amp * G / omega) * (omega * t0).cos() * (duration - t0);
        let expected = x_end - v_end * v_end / (2.0 * mu_k * G);
        let block = BlockSize {
            width_m: 0.3,
            height_m: 1.5,
        };
        let got = slide_only(&drive, block, vec![mu_s], ratio);
        let (_, peak, residual, end) = got[0];
        println!(
            "half-sine A = {amp} g, T = {duration} s, μ_s = {mu_s}, μ_k = {mu_k}: residual {residual:.12} m \
             (closed form {expected:.12}, rel {:.1e}), peak {peak:.12} m",
            residual / expected - 1.0
        );
        assert_eq!(end, EndState::Rest);
        assert!((residual / expected - 1.0).abs() < 1e-9, "{residual} vs {expected}");
        assert!((peak / expected.abs() - 1.0).abs() < 1e-9, "{peak} vs {expected}");
    }
}

/// The block that cannot rock on El Centro 1940 (PGA 0.349 g) against
/// [`newmark`], at friction coefficients from many stick-slip cycles (μ =
/// 0.05) to none (μ = 0.36 > PGA), μ_k = μ_s and μ_k = 0.8 μ_s. Both
/// integrate the same piecewise-linear record exactly up to the crate's
/// rtol of 1e-10 (its steps land on every sample and it locates every
/// stick and slip to round-off), so the tolerance is 1e-10 of the peak,
/// plus 1e-14 m (a hundredth of a picometre) for a peak of zero. Measured:
/// at most 7e-15 m, below 1e-13 relative.
#[test]
fn the_block_that_cannot_rock_matches_an_independent_newmark_integration_on_el_centro() {
    let (times, accel) = columns(ELCENTRO);
    let drive = el_centro();
    let block = BlockSize {
        width_m: 0.4,
        height_m: 1.8,
    };
    let mu = vec![0.05, 0.1, 0.15, 0.2, 0.3, 0.36];
    for ratio in [1.0, 0.8] {
        let got = slide_only(&drive, block, mu.clone(), ratio);
        for (mu_s, peak, residual, end) in got {
            let (want_peak, want_residual) = newmark(&times, &accel, 1.0, mu_s, ratio * mu_s);
            println!(
                "El Centro μ_s = {mu_s}, μ_k = {}: peak {peak:.9} m (Newmark {want_peak:.9}, diff {:.1e}), \
                 residual {residual:.9} m ({want_residual:.9}, diff {:.1e})",
                ratio * mu_s,
                peak - want_peak,
                residual - want_residual
            );
            assert_eq!(end, EndState::Rest);
            let tol = 1e-10 * want_peak + 1e-14;
            assert!((peak - want_peak).abs() < tol, "μ = {mu_s}: peak {peak} vs {want_peak}");
            assert!(
                (residual - want_residual).abs() < tol,
                "μ = {mu_s}: residual {residual} vs {want_residual}"
            );
        }
    }
    // The independent integration is not trivially zero: El Centro slides a
    // block at μ = 0.05 by decimetres, and not at all above its PGA.
    let (low, _) = newmark(&times, &accel, 1.0, 0.05, 0.05);
    let (high, _) = newmark(&times, &accel, 1.0, 0.36, 0.36);
    assert!(low > 0.05 && high == 0.0, "{low} {high}");
}

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-slide-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// `rocking sliding-spectrum` on El Centro for the statue preset's block
/// (0.4 × 1.8 m, corner-momentum impacts) at `mu`, with `extra` flags.
fn sliding(out: &Path, mu: &str, extra: &[&str]) -> Output {
    rocking()
        .args([
            "sliding-spectrum",
            "--record",
            ELCENTRO,
            "--unit",
            "g",
            "--preset",
            "elcentro-statue",
            "--mu",
            mu,
            "-q",
            "--out",
        ])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

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

#[test]
fn sliding_spectrum_of_el_centro_writes_the_csv_json_and_figure() {
    let dir = tmpdir("elcentro");
    let out = dir.join("out");
    ok(&sliding(&out, "0.05:0.6:12", &[]));
    for f in [
        "sliding_spectrum.csv",
        "sliding_spectrum.json",
        "sliding_spectrum.png",
        "sliding_spectrum.svg",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let rows = cells(&std::fs::read_to_string(out.join("sliding_spectrum.csv")).unwrap());
    assert_eq!(
        rows[0].join(","),
        "block,width_m,height_m,mu,mu_k,end,peak_sliding_m,residual_sliding_m,peak_theta_over_alpha,t_overturn_s,t_flight_s"
    );
    assert_eq!(rows.len(), 1 + 24);
    let kinds = column(&rows, "block");
    assert!(kinds[..12].iter().all(|k| k == "slide-only") && kinds[12..].iter().all(|k| k == "block"));
    let num = |name: &str| -> Vec<f64> { column(&rows, name).iter().map(|v| v.parse().unwrap()).collect() };
    let (mu, peak) = (num("mu"), num("peak_sliding_m"));
    // μ = 0.05, 0.10, …, 0.60 as the range says.
    for (i, m) in mu[..12].iter().enumerate() {
        assert!((m - 0.05 * (i + 1) as f64).abs() < 1e-12, "{m}");
    }
    // The slide-only rows are Newmark's block (computed here), exactly 0
    // once μ exceeds the PGA (0.349 g); tolerance as in the test above.
    let (times, accel) = columns(ELCENTRO);
    let residual_cells = column(&rows, "residual_sliding_m");
    for i in 0..12 {
        let (want_peak, want_residual) = newmark(&times, &accel, 1.0, mu[i], mu[i]);
        let tol = 1e-10 * want_peak + 1e-14;
        let residual: f64 = residual_cells[i].parse().unwrap();
        assert!(
            (peak[i] - want_peak).abs() < tol,
            "μ = {}: {} vs {want_peak}",
            mu[i],
            peak[i]
        );
        assert!(
            (residual - want_residual).abs() < tol,
            "μ = {}: {residual} vs {want_residual}",
            mu[i]
        );
        assert_eq!(peak[i] == 0.0, mu[i] > 0.349, "μ = {}", mu[i]);
    }
    // The statue (tan α = 0.222) cannot slide flat once μ > tan α: it
    // rocks first; below it, it slides. Every run of it ends in one of the
    // named states, and only overturned or flight runs lack a residual.
    let ends = column(&rows, "end");
    let residual = column(&rows, "residual_sliding_m");
    for i in 12..24 {
        assert!(["rest", "moving", "overturned", "flight"].contains(&ends[i].as_str()));
        assert_eq!(
            residual[i].is_empty(),
            !["rest", "moving"].contains(&ends[i].as_str()),
            "row {i}"
        );
    }
    assert!(peak[12] > 0.0, "the statue does not slide at μ = 0.05");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sliding_spectrum.json")).unwrap()).unwrap();
    assert_eq!(json["block"]["width_m"], 0.4);
    assert_eq!(json["slide_only"]["b_over_h"], 1000.0);
    assert_eq!(json["summary"][0]["no_sliding_from_mu"], serde_json::json!(mu[6]));
    let svg = std::fs::read_to_string(out.join("sliding_spectrum.svg")).unwrap();
    assert!(svg.contains("cannot rock") && svg.contains("0.4 × 1.8 m"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The command on an analytic pulse (Makris type A, a = 0.5 g sin(2πt/T)
/// for one period T = 0.8 s) against [`newmark`] on that pulse sampled
/// every 0.1 ms. The sampled pulse differs from the sine by at most
/// A(ω dt)²/8 = 4e-8 g between samples, which moves a slip's start and end
/// by about 2e-8 s and its displacement by under 1e-6 relative; the
/// tolerance is 1e-5 of the peak + 1e-9 m. Measured: 8e-8 to 5e-7 relative.
#[test]
fn sliding_spectrum_of_a_one_sine_pulse_matches_newmark_on_the_sampled_pulse() {
    let dir = tmpdir("pulse");
    let out = dir.join("out");
    ok(&rocking()
        .args([
            "sliding-spectrum",
            "--pulse",
            "one-sine",
            "--pulse-accel",
            "0.5",
            "--pulse-period",
            "0.8",
            "--mu",
            "0.1,0.2,0.4",
            "--block",
            "0.4x1.8",
            "-q",
            "--out",
        ])
        .arg(&out)
        .output()
        .expect("runs"));
    let rows = cells(&std::fs::read_to_string(out.join("sliding_spectrum.csv")).unwrap());
    let (period, dt) = (0.8, 1e-4);
    let n = (period / dt) as usize;
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * dt).collect();
    let accel: Vec<f64> = times.iter().map(|t| 0.5 * (2.0 * PI * t / period).sin()).collect();
    // The slide-only rows come first (the statue's may lack a residual).
    assert!(column(&rows, "block")[..3].iter().all(|b| b == "slide-only"));
    let num = |name: &str| -> Vec<f64> { column(&rows, name)[..3].iter().map(|v| v.parse().unwrap()).collect() };
    let (mu, peak, residual) = (num("mu"), num("peak_sliding_m"), num("residual_sliding_m"));
    for i in 0..3 {
        let (want_peak, want_residual) = newmark(&times, &accel, 1.0, mu[i], mu[i]);
        println!(
            "one-sine μ = {}: peak {} m (sampled Newmark {want_peak}, rel {:.1e}), residual {} m ({want_residual})",
            mu[i],
            peak[i],
            peak[i] / want_peak - 1.0,
            residual[i]
        );
        let tol = 1e-5 * want_peak + 1e-9;
        assert!(want_peak > 1e-3, "μ = {}: the pulse barely slides the block", mu[i]);
        assert!(
            (peak[i] - want_peak).abs() < tol,
            "μ = {}: {} vs {want_peak}",
            mu[i],
            peak[i]
        );
        assert!(
            (residual[i] - want_residual).abs() < tol,
            "μ = {}: {} vs {want_residual}",
            mu[i],
            residual[i]
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sliding_spectrum_is_byte_identical_for_one_and_three_threads() {
    let dir = tmpdir("threads");
    let (a, b) = (dir.join("a"), dir.join("b"));
    ok(&sliding(
        &a,
        "0.05:0.6:12",
        &["--threads", "1", "--kinetic-ratio", "0.9"],
    ));
    ok(&sliding(
        &b,
        "0.05:0.6:12",
        &["--threads", "3", "--kinetic-ratio", "0.9"],
    ));
    for f in [
        "sliding_spectrum.csv",
        "sliding_spectrum.json",
        "sliding_spectrum.svg",
        "sliding_spectrum.png",
    ] {
        assert!(
            std::fs::read(a.join(f)).unwrap() == std::fs::read(b.join(f)).unwrap(),
            "{f} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sliding_spectrum_refuses_bad_coefficients_and_friction_keys_in_one_line() {
    let dir = tmpdir("bad");
    let out = dir.join("out");
    for (mu, extra, needle) in [
        ("0.3,0.1", &[][..], "--mu"),
        ("0:0.5:6", &[][..], "--mu"),
        ("0.1,0.2", &["--kinetic-ratio", "1.5"][..], "--kinetic-ratio 1.5"),
        (
            "0.1,0.2",
            &["--set", "friction.static=0.3"][..],
            "--set friction.static",
        ),
        ("0.1,0.2", &["--block", "0.4"][..], "--block 0.4"),
        ("0.1,0.2", &["--cycles", "2"][..], "--cycles"),
    ] {
        let o = sliding(&out, mu, extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
        assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
        assert!(!out.exists(), "{} was written", out.display());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
