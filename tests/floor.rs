//! Floor motion and the exact linear oscillator, each against an
//! independent computation written here: the closed-form transfer function
//! of a damped oscillator, and the piecewise-exact recurrence of Nigam &
//! Jennings (1969) in the coefficient form of Chopra, *Dynamics of
//! Structures*, Table 5.2.1 (the code under test uses a particular solution
//! plus a free vibration instead).

use std::path::{Path, PathBuf};
use std::process::Command;

use rocking::model::Excitation;
use rocking::model::excitation::record::Series;
use rocking::model::excitation::{FloorExcitation, FloorMode, Harmonic, RecordExcitation};
use rocking::model::oscillator::{Oscillator, pseudo_acceleration};
use serde_json::Value;

const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");

/// El Centro 1940 NS as the file has it: seconds and g, parsed here.
fn elcentro() -> Series {
    let text = std::fs::read_to_string(ELCENTRO).expect("record");
    let (mut t, mut a) = (Vec::new(), Vec::new());
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let mut cols = line.split_whitespace().map(|c| c.parse::<f64>().expect("number"));
        t.push(cols.next().expect("time"));
        a.push(cols.next().expect("accel"));
    }
    Series::new(t, a).expect("series")
}

/// One step of Chopra's Table 5.2.1 (unit mass, force p = −a_g): the state
/// after `dt` from (u, v) with the ground acceleration going linearly from
/// `a0` to `a1`.
fn chopra_step(period: f64, zeta: f64, (u, v): (f64, f64), a0: f64, a1: f64, dt: f64) -> (f64, f64) {
    let w = std::f64::consts::TAU / period;
    let k = w * w;
    let sq = (1.0 - zeta * zeta).sqrt();
    let wd = w * sq;
    let e = (-zeta * w * dt).exp();
    let (s, c) = ((wd * dt).sin(), (wd * dt).cos());
    let a = e * (zeta / sq * s + c);
    let b = e * (s / wd);
    let cc = (2.0 * zeta / (w * dt)
        + e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - zeta / sq) * s - (1.0 + 2.0 * zeta / (w * dt)) * c))
        / k;
    let d =
        (1.0 - 2.0 * zeta / (w * dt) + e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * s + 2.0 * zeta / (w * dt) * c)) / k;
    let a_ = -e * (w / sq * s);
    let b_ = e * (c - zeta / sq * s);
    let c_ = (-1.0 / dt + e * ((w / sq + zeta / (dt * sq)) * s + c / dt)) / k;
    let d_ = (1.0 - e * (zeta / sq * s + c)) / (k * dt);
    let (p0, p1) = (-a0, -a1);
    (a * u + b * v + cc * p0 + d * p1, a_ * u + b_ * v + c_ * p0 + d_ * p1)
}

/// The states at every sample of `series`, from rest, by [`chopra_step`].
fn chopra_states(period: f64, zeta: f64, series: &Series) -> Vec<(f64, f64)> {
    let (t, a) = (series.times_s(), series.accel_g());
    let mut out = vec![(0.0, 0.0)];
    for i in 1..t.len() {
        let prev = out[i - 1];
        out.push(chopra_step(period, zeta, prev, a[i - 1], a[i], t[i] - t[i - 1]));
    }
    out
}

/// The absolute acceleration −2ζωu̇ − ω²u of a one-mode floor with Γφ = 1.
fn absolute(period: f64, zeta: f64, (u, v): (f64, f64)) -> f64 {
    let w = std::f64::consts::TAU / period;
    -2.0 * zeta * w * v - w * w * u
}

fn floor_of(series: &Series, p: f64, period: f64, zeta: f64) -> FloorExcitation {
    let record = RecordExcitation::new(series.clone(), None, p, 1.0, 1.0);
    FloorExcitation::record(
        record,
        vec![FloorMode {
            oscillator: Oscillator::new(period, zeta).expect("oscillator"),
            participation: 1.0,
        }],
    )
}

#[test]
fn steady_state_floor_amplification_is_the_damped_oscillators_transfer_function() {
    // In τ units: the building's ω_τ = 2π/(T p). After the transient has
    // decayed (e^{−ζω_τ τ} < 1e-20), a_f is a sinusoid of amplitude
    // A ψ |H(Ω)|, read from two samples a quarter period apart.
    let (p, zeta, psi) = (2.5, 0.05, 0.3);
    let period_s = 1.0;
    let w = std::f64::consts::TAU / (period_s * p);
    for ratio in [0.2, 0.7, 0.95, 1.0, 1.05, 1.5, 3.0] {
        let big = ratio * w;
        let h = Harmonic {
            a_h: 1.3,
            a_v: 0.0,
            omega_h: big,
            omega_v: big,
            phase_h: 0.4,
            phase_v: 0.4,
            psi,
        };
        let floor = FloorExcitation::harmonic(
            h,
            vec![FloorMode {
                oscillator: Oscillator::new(period_s, zeta).unwrap(),
                participation: 1.0,
            }],
            p,
        );
        let tau = 50.0 / (zeta * w);
        let x0 = floor.accel(tau).0;
        let x1 = floor.accel(tau + std::f64::consts::FRAC_PI_2 / big).0;
        let measured = x0.hypot(x1) / (1.3 * psi);
        let c = 2.0 * zeta * w * big;
        let expected = ((w.powi(4) + c * c) / ((w * w - big * big).powi(2) + c * c)).sqrt();
        assert!(
            (measured - expected).abs() <= 1e-9 * expected,
            "Ω/ω = {ratio}: {measured} against |H| = {expected}"
        );
        // The bound on |a_f| used for contact forces holds it.
        let (peak, _) = Excitation::Floor(Box::new(floor)).peak_accel().unwrap();
        assert!(peak >= measured * 1.3 * psi);
    }
}

#[test]
fn a_floor_under_el_centro_is_the_independent_piecewise_exact_integration() {
    let series = elcentro();
    let p = 3.7;
    for (period, zeta) in [(0.15, 0.02), (0.5, 0.05), (1.2, 0.05), (3.0, 0.1)] {
        let floor = floor_of(&series, p, period, zeta);
        let states = chopra_states(period, zeta, &series);
        let (t, a) = (series.times_s(), series.accel_g());
        let mut worst = 0.0_f64;
        for i in 0..t.len() {
            let expected = absolute(period, zeta, states[i]);
            let got = floor.accel(p * t[i]).0;
            worst = worst.max((got - expected).abs());
            // Inside the interval: one shorter step from the sample.
            if i + 1 < t.len() {
                for frac in [0.25, 0.5, 0.9] {
                    let s = frac * (t[i + 1] - t[i]);
                    let a_s = a[i] + frac * (a[i + 1] - a[i]);
                    let inside = chopra_step(period, zeta, states[i], a[i], a_s, s);
                    let got = floor.accel(p * (t[i] + s)).0;
                    worst = worst.max((got - absolute(period, zeta, inside)).abs());
                }
            }
        }
        // 1e-10 g against a PGA of 0.35 g: the two agree to rounding over
        // 2688 steps.
        assert!(worst < 1e-10, "T = {period} s, ζ = {zeta}: worst |Δa_f| {worst:e} g");
    }
}

#[test]
fn a_rigid_floor_gives_the_ground_motion() {
    // As T → 0 the relative acceleration ü = a_f − a_g answers only to the
    // kinks of the piecewise-linear ground: a slope change Δk excites
    // −Δk e^{−σs} sin(ω_d s)/ω_d, so |a_f − a_g| ≤ max|Δk| / ω_d once the
    // start's jump has decayed (e^{−σ·0.02 s} underflows for these T).
    let series = elcentro();
    let (t, a) = (series.times_s(), series.accel_g());
    let slopes: Vec<f64> = (1..t.len()).map(|i| (a[i] - a[i - 1]) / (t[i] - t[i - 1])).collect();
    let max_dk = slopes.windows(2).fold(0.0_f64, |m, w| m.max((w[1] - w[0]).abs()));
    let p = 3.7;
    let zeta = 0.05;
    let mut previous = f64::INFINITY;
    for period in [1e-3, 1e-4, 1e-5] {
        let floor = floor_of(&series, p, period, zeta);
        let wd = std::f64::consts::TAU / period * (1.0 - zeta * zeta).sqrt();
        let bound = max_dk / wd * 1.001;
        let mut worst = 0.0_f64;
        for i in 1..t.len() - 1 {
            for frac in [0.0, 0.5] {
                let ti = t[i] + frac * (t[i + 1] - t[i]);
                let ground = series.accel_at(ti);
                worst = worst.max((floor.accel(p * ti).0 - ground).abs());
            }
        }
        assert!(worst <= bound, "T = {period}: {worst:e} > {bound:e}");
        // It shrinks with T until rounding (1e-14 g) is all that is left.
        assert!(
            worst < previous / 5.0 || worst < 1e-13,
            "T = {period}: {worst:e} does not shrink"
        );
        previous = worst;
    }
    assert!(previous < 1e-4, "{previous:e} g");
}

/// Sa(T, ζ) by the independent recurrence: ω² times the largest |u| at the
/// samples and at the zeros of u̇ inside each interval, found by sampling u̇
/// at 32 points per interval and bisecting every sign change with shorter
/// steps from the interval's start.
fn independent_sa(series: &Series, period: f64, zeta: f64) -> f64 {
    let (t, a) = (series.times_s(), series.accel_g());
    let states = chopra_states(period, zeta, series);
    let mut peak = states.iter().fold(0.0_f64, |m, s| m.max(s.0.abs()));
    for i in 0..t.len() - 1 {
        let h = t[i + 1] - t[i];
        let at = |s: f64| {
            if s <= 0.0 {
                return states[i];
            }
            chopra_step(period, zeta, states[i], a[i], a[i] + s / h * (a[i + 1] - a[i]), s)
        };
        let n = 32;
        for j in 0..n {
            let (mut lo, mut hi) = (h * j as f64 / n as f64, h * (j + 1) as f64 / n as f64);
            let (vlo, vhi) = (at(lo).1, at(hi).1);
            if (vlo < 0.0) == (vhi < 0.0) {
                continue;
            }
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if (at(mid).1 < 0.0) == (vlo < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            peak = peak.max(at(lo).0.abs()).max(at(hi).0.abs());
        }
    }
    let w = std::f64::consts::TAU / period;
    w * w * peak
}

#[test]
fn sa_of_el_centro_is_the_independent_integrations_at_several_periods() {
    let series = elcentro();
    for period in [0.1, 0.2, 0.5, 1.0, 2.0, 4.0] {
        let got = pseudo_acceleration(&series, 1.0, period, 0.05).expect("Sa");
        let expected = independent_sa(&series, period, 0.05);
        assert!(
            (got - expected).abs() <= 1e-10 * expected,
            "T = {period} s: Sa {got} g against {expected} g"
        );
        // And scaling the record scales Sa.
        let scaled = pseudo_acceleration(&series, -2.0, period, 0.05).unwrap();
        assert!((scaled - 2.0 * got).abs() <= 1e-12 * got);
    }
}

#[test]
fn sa_over_continuous_time_is_at_least_the_peak_over_samples() {
    // With a 0.02 s step a 0.06 s oscillator peaks between samples: the
    // continuous maximum must exceed the samples' (the reason to search
    // inside intervals at all).
    let series = elcentro();
    let period = 0.06;
    let got = pseudo_acceleration(&series, 1.0, period, 0.05).unwrap();
    let states = chopra_states(period, 0.05, &series);
    let w = std::f64::consts::TAU / period;
    let over_samples = w * w * states.iter().fold(0.0_f64, |m, s| m.max(s.0.abs()));
    assert!(got > over_samples * (1.0 + 1e-6), "{got} vs {over_samples}");
    assert!((got - independent_sa(&series, period, 0.05)).abs() <= 1e-10 * got);
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-floor-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn batch(out: &Path, args: &[&str]) -> (std::process::Output, Option<Value>) {
    let mut all = vec!["--batch", "--quiet", "--out", out.to_str().expect("utf-8")];
    all.extend_from_slice(args);
    let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(&all)
        .output()
        .expect("runs");
    let summary = std::fs::read_to_string(out.join("summary.json"))
        .ok()
        .map(|t| serde_json::from_str(&t).expect("json"));
    (o, summary)
}

#[test]
fn a_config_with_a_floor_runs_batch_and_reports_the_floor_peaks() {
    let dir = tmpdir("batch");
    let config = dir.join("floor.toml");
    std::fs::write(
        &config,
        format!(
            "[block]\nwidth = \"0.6 m\"\nheight = \"2.0 m\"\n\n[excitation]\nkind = \"record\"\nfile_h = \"{ELCENTRO}\"\nunit_h = \"g\"\n\n[floor]\nperiod = \"0.5 s\"\ndamping = 0.05\n\n[run]\ntail_s = \"2 s\"\noutput_dt = 0\n"
        ),
    )
    .unwrap();
    let (o, summary) = batch(&dir.join("out"), &["--config", config.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary.expect("summary.json");
    let floor = &s["physical"]["floor"];
    let pga = floor["pga_g"].as_f64().expect("physical.floor.pga_g");
    let pgv = floor["pgv_m_s"].as_f64().expect("physical.floor.pgv_m_s");
    // The independent recurrence's peak over samples is a lower bound of the
    // continuous peak, and a fine subdivision comes within 1e-6 of it.
    let series = elcentro();
    let states = chopra_states(0.5, 0.05, &series);
    let over_samples = states.iter().fold(0.0_f64, |m, s| m.max(absolute(0.5, 0.05, *s).abs()));
    assert!(
        pga >= over_samples - 1e-12 && pga <= over_samples * 1.05,
        "{pga} vs {over_samples}"
    );
    // Continuous time: 64 points inside every interval by the recurrence
    // bound the peak from below, and from above within the interpolation
    // error M₂ w²/8 (M₂ ≤ ω² |a_f| ≤ ω² · 2 PGA, w = 0.02 s / 64).
    let (t, a) = (series.times_s(), series.accel_g());
    let mut dense = over_samples;
    for i in 0..t.len() - 1 {
        let h = t[i + 1] - t[i];
        for j in 1..64 {
            let s = h * j as f64 / 64.0;
            let a_s = a[i] + s / h * (a[i + 1] - a[i]);
            let inside = chopra_step(0.5, 0.05, states[i], a[i], a_s, s);
            dense = dense.max(absolute(0.5, 0.05, inside).abs());
        }
    }
    let w = std::f64::consts::TAU / 0.5;
    let slack = w * w * 2.0 * pga * (0.02_f64 / 64.0).powi(2) / 8.0;
    assert!(
        pga >= dense - 1e-12 && pga <= dense + slack,
        "{pga} vs {dense} (+{slack:e})"
    );
    assert!(pgv > 0.0 && pgv.is_finite());
    // The config written back repeats the floor.
    assert_eq!(s["config"]["floor"]["period"].as_f64(), Some(0.5));
    // The ground's own peak is still reported beside it.
    assert!(s["physical"]["record_h"]["pga_g"].as_f64().unwrap() > 0.34);
}

#[test]
fn a_floor_under_a_pulse_or_with_a_bad_period_is_refused_naming_the_key() {
    let dir = tmpdir("refused");
    for (sets, key) in [
        (
            vec![
                "--set",
                "excitation.kind=pulse",
                "--set",
                "excitation.a_h=2",
                "--set",
                "floor.period=0.5",
            ],
            "floor:",
        ),
        (vec!["--set", "floor.period=0"], "floor.period"),
        (
            vec!["--set", "floor.period=0.5", "--set", "floor.damping=1.2"],
            "floor.damping",
        ),
        (vec!["--set", "floor.damping=0.05"], "floor.period"),
    ] {
        let out = dir.join("out");
        let (o, _) = batch(&out, &sets);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{sets:?}: {err}");
        assert!(err.contains(key), "{sets:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

#[test]
fn two_modes_given_as_tables_add_their_participations_as_derived() {
    // a_f = a_g + Σ Γ_kφ_k ü_k, with ü_k = −a_g − 2ζω u̇_k − ω² u_k from the
    // independent recurrence, for the config's [[floor.mode]] tables.
    use rocking::io::config;
    let text = format!(
        "[block]\nwidth = 0.6\nheight = 2.0\n\n[excitation]\nkind = \"record\"\nfile_h = \"{ELCENTRO}\"\nunit_h = \"g\"\nscale_h = 1.5\n\n[[floor.mode]]\nperiod = \"0.9 s\"\ndamping = 0.05\nparticipation = 1.27\n\n[[floor.mode]]\nperiod = \"0.3 s\"\ndamping = 0.03\nparticipation = -0.42\n"
    );
    let table = config::parse_toml(&text, "two-modes.toml").expect("toml");
    let scenario = config::from_table(&table, &config::Source::default()).expect("scenario");
    let model = scenario.model().expect("model");
    let p = scenario.geometry().p;
    let series = elcentro();
    let scaled = Series::new(
        series.times_s().to_vec(),
        series.accel_g().iter().map(|a| 1.5 * a).collect(),
    )
    .unwrap();
    let modes = [(0.9, 0.05, 1.27), (0.3, 0.03, -0.42)];
    let states: Vec<Vec<(f64, f64)>> = modes.iter().map(|&(t, z, _)| chopra_states(t, z, &scaled)).collect();
    let (t, a) = (scaled.times_s(), scaled.accel_g());
    let mut worst = 0.0_f64;
    for i in 0..t.len() {
        let mut expected = a[i];
        for (k, &(period, zeta, gamma)) in modes.iter().enumerate() {
            let w = std::f64::consts::TAU / period;
            let (u, v) = states[k][i];
            expected += gamma * (-a[i] - 2.0 * zeta * w * v - w * w * u);
        }
        worst = worst.max((model.excitation.forcing(p * t[i]).a - expected).abs());
    }
    assert!(worst < 1e-10, "{worst:e}");
    // A missing participation with several modes is refused, naming it.
    let bad = text.replace("participation = -0.42\n", "");
    let err = config::from_table(
        &config::parse_toml(&bad, "bad.toml").unwrap(),
        &config::Source::default(),
    )
    .expect_err("refused")
    .to_string();
    assert!(err.contains("floor.mode[1].participation"), "{err}");
}

#[test]
fn a_harmonic_floors_rate_and_peaks_agree_with_its_acceleration() {
    // The closed-form rate (used by the tangent Lyapunov method) against
    // central differences of the acceleration, and the continuous-time
    // peaks between the densely sampled maximum and the contact-force bound.
    let (p, psi) = (2.2, 0.25);
    let h = Harmonic {
        a_h: 2.0,
        a_v: 0.5,
        omega_h: 3.0,
        omega_v: 3.0,
        phase_h: 0.3,
        phase_v: 0.3,
        psi,
    };
    let modes = vec![
        FloorMode {
            oscillator: Oscillator::new(0.8, 0.05).unwrap(),
            participation: 1.1,
        },
        FloorMode {
            oscillator: Oscillator::new(0.25, 0.04).unwrap(),
            participation: -0.3,
        },
    ];
    let floor = FloorExcitation::harmonic(h, modes, p);
    for tau in [0.1, 1.7, 12.3, 40.0] {
        let e = 1e-5;
        let fd = (floor.accel(tau + e).0 - floor.accel(tau - e).0) / (2.0 * e);
        let (rate, rate_v) = floor.accel_rate(tau).unwrap();
        assert!(
            (fd - rate).abs() < 1e-6 * (1.0 + rate.abs()),
            "τ = {tau}: {fd} vs {rate}"
        );
        let fdv = (floor.accel(tau + e).1 - floor.accel(tau - e).1) / (2.0 * e);
        assert!((fdv - rate_v).abs() < 1e-6, "{fdv} vs {rate_v}");
    }
    let tau_end = 60.0;
    let peaks = floor.peaks(tau_end);
    let dense = (0..=600_000).fold(0.0_f64, |m, j| {
        m.max(floor.accel(tau_end * j as f64 / 600_000.0).0.abs())
    });
    assert!(
        peaks.pga_g >= dense - 1e-12 && peaks.pga_g <= dense * (1.0 + 1e-6),
        "{} vs {dense}",
        peaks.pga_g
    );
    let bound = Excitation::Floor(Box::new(floor)).peak_accel().unwrap().0;
    assert!(peaks.pga_g <= bound, "{} > bound {bound}", peaks.pga_g);
}
