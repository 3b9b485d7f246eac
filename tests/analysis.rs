//! The analyses against systems with known answers, through the public API:
//! the logistic map's period doublings through the sweep machinery, the
//! stroboscopic fixed point of a linear forced oscillator, the paper's
//! Fig. 4 period doubling on the block, determinism over thread counts, and
//! the figures.

use rocking::analysis::classify::{ClassifyOptions, Response, classify_points};
use rocking::analysis::orbit_diagram::{BlockSweep, Continuation, Grid, Plan, block_sweep, sweep};
use rocking::analysis::section::{Strobe, map_orbit};
use rocking::analysis::spectrum::{SpectrumOptions, SpectrumWindow, theta_spectrum};
use rocking::analysis::steady::{Window, steady_response};
use rocking::integrate::hybrid::{Driver, DriverError, HybridSystem, Jump, Limits, MAX_GUARDS, Outputs};
use rocking::integrate::{Dop853, Tolerances};
use rocking::io::config::load;
use rocking::plot::bifurcation::BifurcationFigure;
use rocking::plot::outcome_map::{MapColouring, OutcomeMapFigure};
use rocking::plot::poincare::PoincareFigure;
use rocking::plot::spectrum::SpectrumFigure;
use rocking::plot::time_history::TimeHistoryFigure;
use rocking::sim::Param;
use rocking::sim::simulate;

/// The logistic map's steady response at `r`, as a sweep closure: 2000
/// iterations of transient, 256 kept, seeded from `seed` or x = 0.3.
fn logistic(r: f64, seed: Option<&f64>) -> Result<(Response, Option<f64>), String> {
    let orbit = map_orbit(
        |x: &[f64; 1]| [r * x[0] * (1.0 - x[0])],
        [*seed.unwrap_or(&0.3)],
        2000,
        256,
    );
    let response = classify_points(&orbit, None, &ClassifyOptions::default()).map_err(|e| e.to_string())?;
    Ok((response, orbit.last().map(|x| x[0])))
}

#[test]
fn logistic_period_doublings_through_the_sweep_machinery() {
    let grid = Grid::new(2.5, 3.9, 0.01).unwrap();
    let bar = rocking::analysis::silent;
    let periods = |c: Continuation| -> Vec<(f64, Response)> {
        sweep(&Plan::new(grid, c, None).unwrap(), &bar, logistic)
            .unwrap()
            .into_iter()
            .map(|c| (c.value, c.result))
            .collect()
    };
    let parallel = periods(Continuation::None);
    assert_eq!(parallel.len(), 141);
    let first = |pred: &dyn Fn(Response) -> bool| parallel.iter().find(|(_, r)| pred(*r)).map(|(v, _)| *v);
    // Period doublings at r = 3, 1 + √6 = 3.4495 and 3.5441; chaos from 3.5699.
    let not_one = first(&|r| r != Response::Periodic { period: 1 }).unwrap();
    assert!((2.995..3.015).contains(&not_one), "period 1 ends at {not_one}");
    let four = first(&|r| r == Response::Periodic { period: 4 }).unwrap();
    assert!((3.445..3.465).contains(&four), "period 4 starts at {four}");
    let eight = first(&|r| r == Response::Periodic { period: 8 }).unwrap();
    assert!((3.54..3.56).contains(&eight), "period 8 starts at {eight}");
    let chaos = first(&|r| r == Response::Chaotic).unwrap();
    assert!((3.565..3.6).contains(&chaos), "chaos starts at {chaos}");
    let at = |r: f64| parallel.iter().find(|(v, _)| (v - r).abs() < 1e-9).map(|p| p.1);
    assert_eq!(at(2.9), Some(Response::Periodic { period: 1 }));
    assert_eq!(at(3.2), Some(Response::Periodic { period: 2 }));
    assert_eq!(at(3.5), Some(Response::Periodic { period: 4 }));
    assert_eq!(at(3.83), Some(Response::Periodic { period: 3 }));
    assert_eq!(at(3.9), Some(Response::Chaotic));
    // The logistic map has one attractor: continuation finds the same.
    let up = periods(Continuation::Up);
    let same = parallel.iter().zip(&up).filter(|(a, b)| a.1 == b.1).count();
    assert!(same >= 139, "continuation agrees on {same} of 141 values");
}

/// x'' + 2ζω₀x' + ω₀²x = F cos Ωt, a hybrid system with no guards.
struct Oscillator {
    omega0: f64,
    zeta: f64,
    force: f64,
    omega: f64,
}

impl HybridSystem<2> for Oscillator {
    type Mode = ();
    type Record = ();
    type Error = DriverError;

    fn rhs(&self, _mode: (), t: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        dydt[0] = y[1];
        dydt[1] = self.force * (self.omega * t).cos()
            - 2.0 * self.zeta * self.omega0 * y[1]
            - self.omega0 * self.omega0 * y[0];
    }
    fn guards(&self, _mode: (), _t: f64, _y: &[f64; 2], _g: &mut [f64; MAX_GUARDS]) -> usize {
        0
    }
    fn is_observer(&self, _mode: (), _index: usize) -> bool {
        false
    }
    fn observe(&mut self, _mode: (), _index: usize, _t: f64, _y: &[f64; 2]) {}
    fn jump(&mut self, _mode: (), _index: usize, t: f64, _y: &[f64; 2]) -> Result<Jump<(), (), 2>, DriverError> {
        // No guards, so the driver never calls this.
        Err(DriverError::TimeReversal { t })
    }
    fn is_terminal(&self, _mode: ()) -> bool {
        false
    }
    fn next_breakpoint(&self, _t: f64) -> Option<f64> {
        None
    }
}

#[test]
fn stroboscopic_fixed_point_of_a_linear_forced_oscillator() {
    let sys = Oscillator {
        omega0: 1.0,
        zeta: 0.1,
        force: 1.0,
        omega: 1.7,
    };
    let w2 = sys.omega0 * sys.omega0 - sys.omega * sys.omega;
    let c = 2.0 * sys.zeta * sys.omega0 * sys.omega;
    let amplitude = sys.force / (w2 * w2 + c * c).sqrt();
    let phase = c.atan2(w2);
    let fixed = [amplitude * phase.cos(), amplitude * sys.omega * phase.sin()];
    let period = std::f64::consts::TAU / sys.omega;
    let tol = Tolerances {
        rtol: 1e-12,
        atol: 1e-14,
        ..Tolerances::default()
    };
    let outputs = Outputs {
        sample_dt: None,
        section_period: Some(period),
    };
    // The transient decays like e^{−ζω₀t}: e^{−30} ≈ 1e-13 by t = 300.
    let mut driver = Driver::new(Dop853::new(tol), sys, (), 0.0, [0.5, 0.0], Limits::default(), outputs);
    let mut strobe = Strobe::<2>::new(300.0);
    driver.advance(600.0, &mut strobe).unwrap();
    let points: Vec<[f64; 2]> = strobe.points().iter().map(|p| p.y).collect();
    assert!(points.len() >= 64, "{} points", points.len());
    for p in strobe.points() {
        assert!((p.t - p.k as f64 * period).abs() < 1e-12 * p.t);
        assert!((p.y[0] - fixed[0]).abs() < 1e-9, "{:?} vs {fixed:?}", p.y);
        assert!((p.y[1] - fixed[1]).abs() < 1e-9, "{:?} vs {fixed:?}", p.y);
    }
    assert_eq!(
        classify_points(&points, None, &ClassifyOptions::default()).unwrap(),
        Response::Periodic { period: 1 }
    );
}

#[test]
fn issue_3_fig4_period_one_below_a_v_1_7_and_period_two_above() {
    // Fig. 4: Ω = 8, A_h = 3, no sliding, ratio law r = 0.925, from rest,
    // Poincaré points of τ 600..800. The paper: (1,1) up to A_v ≈ 1.7,
    // (1,2) from 1.7 to 2.25.
    let base = load(Some("fig4"), None, &[]).unwrap();
    let opts = ClassifyOptions::default();
    for (a_v, period) in [(1.0, 1), (1.5, 1), (1.9, 2), (2.1, 2)] {
        let cfg = Param::apply(&base, &[(Param::Av, a_v)]).unwrap();
        let s = steady_response(&cfg, &Window::default(), &opts, None).unwrap();
        assert_eq!(s.response, Response::Periodic { period }, "A_v = {a_v}");
        assert_eq!(s.points.len(), 255);
        assert!(s.points.iter().all(|p| p.tau >= 600.0));
        assert!(s.max_abs_theta < 1.0);
    }
}

fn short_fig4_sweep(threads: usize) -> Vec<rocking::analysis::orbit_diagram::BifurcationValue> {
    let base = load(Some("fig4"), None, &[]).unwrap();
    let spec = BlockSweep {
        base: &base,
        param: Param::Av,
        window: Window {
            transient: 100.0,
            tau_end: 160.0,
        },
        classify: ClassifyOptions::default(),
        lyapunov: None,
    };
    let plan = Plan::new(Grid::new(1.9, 3.3, 0.2).unwrap(), Continuation::None, None).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| block_sweep(&spec, &plan, &rocking::analysis::silent))
        .unwrap()
}

#[test]
fn block_sweep_is_bit_identical_with_one_and_two_threads() {
    let one = short_fig4_sweep(1);
    let two = short_fig4_sweep(2);
    assert_eq!(one.len(), 8);
    assert_eq!(one, two);
    for (a, b) in one.iter().zip(&two) {
        assert_eq!(a.max_abs_theta.to_bits(), b.max_abs_theta.to_bits());
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(
                (p.theta.to_bits(), p.theta_dot.to_bits()),
                (q.theta.to_bits(), q.theta_dot.to_bits())
            );
        }
        // Tumbled values are blank, as in the paper.
        if a.response == Response::Tumbled {
            assert!(a.points.is_empty());
        }
    }
    assert!(one.iter().any(|v| v.response == Response::Tumbled), "{one:?}");
}

fn figure_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rocking-figures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn check_png_and_svg(fig: &impl rocking::plot::Figure, dir: &std::path::Path, name: &str) {
    let png = dir.join(format!("{name}.png"));
    fig.write_png(&png).unwrap();
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name}.png");
    let svg = fig.to_svg().unwrap();
    assert!(svg.starts_with("<svg"), "{name}.svg");
    assert!(
        svg.contains("Θ") || svg.contains("Outcome map over A"),
        "{name}.svg has its labels"
    );
    std::fs::write(dir.join(format!("{name}.svg")), svg).unwrap();
}

#[test]
fn figures_are_written_as_png_and_svg() {
    let dir = figure_dir();
    // A chaotic response of Fig. 4 (A_v = 2.5) with a history on the
    // paper's grid, for the time history, spectrum and Poincaré map.
    let base = load(Some("fig4"), None, &[]).unwrap();
    let cfg = Param::apply(&base, &[(Param::Av, 2.5), (Param::OutputDt, 0.004)]).unwrap();
    let res = simulate(cfg.model().unwrap(), &cfg.initial, &cfg.run_options()).unwrap();
    let tau: Vec<f64> = res.history.iter().map(|r| r.tau).collect();
    let theta: Vec<f64> = res.history.iter().map(|r| r.theta).collect();
    let history = TimeHistoryFigure {
        title: "Time history, Fig. 4 conditions at A_v = 2.5".into(),
        subtitle: "Ω_h = Ω_v = 8, A_h = 3, no sliding, r = 0.925".into(),
        tau: &tau,
        theta: &theta,
        tumble_theta: Some(1.0),
    };
    check_png_and_svg(&history, &dir, "time_history");

    let spectrum = theta_spectrum(&res.history, SpectrumWindow::Paper, &SpectrumOptions::default()).unwrap();
    let harmonic: Vec<f64> = spectrum.omega().iter().map(|w| w / 8.0).collect();
    let peaks = spectrum.peaks(5, 1e-8, 8.0);
    assert!(!peaks.is_empty());
    let fig = SpectrumFigure {
        title: "Power spectrum of Θ, A_v = 2.5".into(),
        subtitle: "the paper's window: samples 3000–7095 at Δτ = 0.004, Hann".into(),
        harmonic: &harmonic,
        psd: &spectrum.psd,
        peaks: &peaks,
        max_harmonic: 4.0,
    };
    check_png_and_svg(&fig, &dir, "spectrum");

    let section: Vec<(f64, f64)> = res
        .section
        .iter()
        .filter(|p| p.tau >= 600.0)
        .map(|p| (p.theta, p.theta_dot))
        .collect();
    let fig = PoincareFigure {
        title: "Poincaré map, A_v = 2.5".into(),
        subtitle: "τ_k = 2πk/Ω_h, 600 ≤ τ_k ≤ 800".into(),
        points: &section,
    };
    check_png_and_svg(&fig, &dir, "poincare");

    let values = short_fig4_sweep(2);
    let classes: Vec<(f64, Response)> = values.iter().map(|v| (v.value, v.response)).collect();
    let points: Vec<(f64, f64)> = values
        .iter()
        .flat_map(|v| v.points.iter().map(move |p| (v.value, p.theta)))
        .collect();
    let fig = BifurcationFigure {
        title: "Bifurcation diagram over A_v".into(),
        subtitle: "short window".into(),
        x_label: "A_v".into(),
        y_label: "Θ = θ/ψ at τ_k = 2πk/Ω_h",
        values: &classes,
        points: &points,
        step: 0.1,
    };
    check_png_and_svg(&fig, &dir, "bifurcation");

    let xs = [1.0, 2.0, 3.0];
    let ys = [0.5, 1.0];
    let cells = [
        (Response::Rest, None),
        (Response::Periodic { period: 1 }, Some(-0.4)),
        (Response::Periodic { period: 2 }, Some(-0.1)),
        (Response::Chaotic, Some(0.7)),
        (Response::Quasiperiodic, Some(0.0)),
        (Response::Tumbled, None),
    ];
    for (colouring, name) in [(MapColouring::Outcome, "map"), (MapColouring::Lyapunov, "map_lyapunov")] {
        let fig = OutcomeMapFigure {
            title: "Outcome map over A_h × A_v".into(),
            subtitle: "test cells".into(),
            x_label: "A_h".into(),
            y_label: "A_v".into(),
            x: &xs,
            y: &ys,
            cells: &cells,
            colouring,
            basins: None,
        };
        check_png_and_svg(&fig, &dir, name);
    }
    eprintln!("figures in {}", dir.display());
}
