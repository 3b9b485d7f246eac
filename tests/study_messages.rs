//! A study's errors name its inputs by meaning, never by a CLI flag: the
//! app shows them as they are and the Python package words them with its
//! keywords, so neither says `--tau-end` where its user wrote no flag.
//! Each expected message is written out here; the keyword forms are the
//! ones the Python package has always given (the CLI's message with
//! `--flag VALUE` as `keyword=VALUE`).

use std::borrow::Cow;

use rocking::analysis::classify::ClassifyOptions;
use rocking::analysis::field::{FieldNames, StudyField};
use rocking::analysis::orbit_diagram::{Continuation, Grid, Plan, PlanError, Shard};
use rocking::analysis::outcome_map::Axis;
use rocking::analysis::steady::{SteadyError, Window, check_scenario};
use rocking::sim::Scenario;

/// The Python package's keywords (`rocking.sweep(scene, param, start,
/// stop, step, *, transient, tau_end, continuation)`, `shard=(K, N)` of
/// its private `_sweep`), written out independently of the package.
struct Keywords;

impl FieldNames for Keywords {
    fn name(&self, field: StudyField) -> Cow<'static, str> {
        Cow::Borrowed(match field {
            StudyField::From => "start",
            StudyField::To => "stop",
            StudyField::Step => "step",
            StudyField::Shard => "shard",
            StudyField::Continuation => "continuation",
            StudyField::Transient => "transient",
            StudyField::TauEnd => "tau_end",
        })
    }

    fn valued(&self, field: StudyField, value: &str) -> String {
        format!("{}={value}", self.name(field))
    }
}

/// One refused study input of each kind the analysis layer checks.
enum Refused {
    Plan(PlanError),
    Steady(SteadyError),
}

impl Refused {
    fn render(&self, names: &impl FieldNames) -> String {
        match self {
            Refused::Plan(e) => e.render(names),
            Refused::Steady(e) => e.render(names),
        }
    }

    fn display(&self) -> String {
        match self {
            Refused::Plan(e) => e.to_string(),
            Refused::Steady(e) => e.to_string(),
        }
    }
}

fn plan<T: std::fmt::Debug>(r: Result<T, PlanError>) -> Refused {
    Refused::Plan(r.unwrap_err())
}

fn every_kind() -> Vec<Refused> {
    let grid = Grid::new(0.0, 1.0, 0.5).unwrap();
    let window = |transient, tau_end| Window { transient, tau_end };
    let harmonic = Scenario::default();
    let steady = |w: Window| Refused::Steady(check_scenario(&harmonic, &w, &ClassifyOptions::default()).unwrap_err());
    vec![
        plan(Grid::new(f64::NAN, 1.0, 0.1)),
        plan(Grid::new(0.0, f64::INFINITY, 0.1)),
        plan(Grid::new(0.0, 1.0, 0.0)),
        plan(Grid::new(1.0, 0.0, 0.1)),
        plan(Grid::new(0.0, 1e20, 1.0)),
        plan(Grid::new(1.0, 1.0 + 1e-14, 1.5e-16)),
        plan(Shard::parse("3")),
        plan(Shard::parse("a/b")),
        plan(Shard::parse("0/0")),
        plan(Shard::parse("3/3")),
        plan(Plan::new(grid, Continuation::Down, Some(Shard { index: 0, count: 2 }))),
        plan(Axis::new("x", "excitation.a_h", 2.0, 1.0, 3)),
        steady(window(-1.0, 800.0)),
        steady(window(600.0, f64::NAN)),
        steady(window(900.0, 800.0)),
        steady(window(0.0, 10.0)),
    ]
}

#[test]
fn no_study_error_names_a_cli_flag_as_shown_or_as_python_words_it() {
    for e in every_kind() {
        for message in [e.display(), e.render(&Keywords)] {
            assert!(!message.contains("--"), "{message}");
            assert!(!message.is_empty());
        }
    }
}

#[test]
fn python_words_each_input_as_the_keyword_that_gave_it() {
    let rendered: Vec<String> = every_kind().iter().map(|e| e.render(&Keywords)).collect();
    let period = std::f64::consts::TAU / Scenario::default().excitation.omega_h;
    // τ_k = k·period in [0, 10]: k = 0 … ⌊10/period⌋.
    let points = (10.0 / period).floor() as u64 + 1;
    let need = 2 * ClassifyOptions::default().k_max;
    let expected = [
        "start=NaN: must be finite".to_string(),
        "stop=inf: must be finite".to_string(),
        "step=0.0: must be finite and > 0".to_string(),
        "stop=0.0: must be >= start=1".to_string(),
        "step=1.0: gives more than 10000000 values".to_string(),
        "step=1.5e-16: is below the resolution of the values near 1.0000000000000002: values 1 and 2 are both 1.0000000000000002".to_string(),
        "shard=3: expected K/N, e.g. 0/4 (K counts from 0)".to_string(),
        "shard=a/b: expected K/N with non-negative integers, e.g. 0/4".to_string(),
        "shard=0/0: N must be >= 1".to_string(),
        "shard=3/3: K must be < N (K counts from 0: 0..=2)".to_string(),
        "shard cannot be combined with continuation=down: each value is seeded from the previous one, so the values cannot be split".to_string(),
        "x excitation.a_h 2 1 3: A must be < B when N > 1".to_string(),
        "transient=-1: must be finite and >= 0".to_string(),
        "tau_end=NaN: must be finite and <= 1e9".to_string(),
        "tau_end=800: must be larger than transient=900".to_string(),
        format!(
            "transient=0 / tau_end=10: the window holds {points} section points (period {period:.6}); at least {need} are needed to classify"
        ),
    ];
    assert_eq!(rendered.len(), expected.len());
    for (got, want) in rendered.iter().zip(&expected) {
        assert_eq!(got, want);
    }
}

#[test]
fn the_app_sees_the_cores_own_field_names() {
    let e = Window {
        transient: 900.0,
        tau_end: 800.0,
    }
    .validate()
    .unwrap_err();
    assert_eq!(e.to_string(), "tau_end = 800: must be larger than transient = 900");
    let e = Grid::new(1.0, 0.0, 0.1).unwrap_err();
    assert_eq!(e.to_string(), "to = 0.0: must be >= from = 1");
}
