//! Helpers shared by the integration tests.
#![allow(dead_code)]

use rocking::integrate::Tolerances;
use rocking::integrate::hybrid::Limits;
use rocking::model::excitation::Excitation;
use rocking::model::{FlightPolicy, Geometry, Harmonic, ImpactLaw, Model};
use rocking::sim::{InitialState, Method, RunOptions, RunResult, simulate};

/// A model of a `width` × `height` block with the given law, friction and excitation.
pub fn model(width: f64, height: f64, law: ImpactLaw, mu: (f64, f64), excitation: Excitation) -> Model {
    Model {
        geo: Geometry::new(width, height),
        mu_s: mu.0,
        mu_k: mu.1,
        law,
        excitation,
        tumble_theta: 1.0,
        flight: FlightPolicy::Stop,
        zeno_eps: 1e-5,
        frame: None,
    }
}

/// Harmonic excitation for `geo`.
pub fn harmonic(geo: &Geometry, a_h: f64, a_v: f64, omega: f64) -> Excitation {
    Excitation::Harmonic(Harmonic {
        a_h,
        a_v,
        omega_h: omega,
        omega_v: omega,
        phase_h: 0.0,
        phase_v: 0.0,
        psi: geo.psi,
    })
}

/// Run options with tolerance `rtol` (atol = rtol/100).
pub fn opts(tau_end: f64, rtol: f64, output_dt: Option<f64>) -> RunOptions {
    RunOptions {
        tau_end,
        method: Method::Dop853,
        tol: Tolerances {
            rtol,
            atol: rtol * 1e-2,
            ..Tolerances::default()
        },
        output_dt,
        section: true,
        rest_after: None,
        limits: Limits::default(),
    }
}

/// Runs from `(theta, theta_dot)` with no initial slip.
pub fn run(model: Model, theta: f64, theta_dot: f64, opts: &RunOptions) -> RunResult {
    simulate(
        model,
        &InitialState {
            theta,
            theta_dot,
            x_dot: None,
        },
        opts,
    )
    .expect("run succeeds")
}

/// Every history row in a rocking mode has Θ on its pivot's side (sΘ >= 0,
/// up to round-off): an impact was never missed.
pub fn assert_pivot_side(res: &RunResult) {
    for r in &res.history {
        if let rocking::model::Mode::Rock { pivot } | rocking::model::Mode::SlideRock { pivot, .. } = r.mode {
            assert!(
                pivot.value() * r.theta >= -1e-9,
                "Θ = {} on the wrong side of pivot {pivot:?} at τ = {}",
                r.theta,
                r.tau
            );
        }
    }
}

/// The scenario of config text `text` (a test's own config).
pub fn scene(text: &str) -> rocking::sim::Scenario {
    let table = rocking::io::config::parse_toml(text, "test.toml").expect("toml");
    rocking::io::config::from_table(&table, &rocking::io::config::Source::default()).expect("scenario")
}

/// The one-line error config text `text` is refused with.
pub fn refusal(text: &str) -> String {
    let table = rocking::io::config::parse_toml(text, "test.toml").expect("toml");
    match rocking::io::config::from_table(&table, &rocking::io::config::Source::default()) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// One row of a CSV file: header → cell.
pub type CsvRow = std::collections::HashMap<String, String>;

/// The rows of the CSV file at `path` (a test's own output).
pub fn csv_rows(path: &std::path::Path) -> Vec<CsvRow> {
    let text = std::fs::read_to_string(path).expect("csv");
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().expect("header").split(',').map(String::from).collect();
    lines
        .map(|l| head.iter().cloned().zip(l.split(',').map(String::from)).collect())
        .collect()
}
