//! The hybrid driver catches a shallow double crossing inside one step
//! (grazing) on a constructed system whose guard dips below zero between
//! two samples and comes back.

use rocking::integrate::hybrid::{Driver, DriverError, HybridSystem, Jump, Limits, MAX_GUARDS, Observer, Outputs};
use rocking::integrate::{Dop853, Dopri5, Stepper, Tolerances};

/// y' = 2(t − 1), y(0) = 1 − ε: y = (t − 1)² − ε, which is below zero only
/// on (1 − √ε, 1 + √ε). The solution is a polynomial, so the adaptive
/// methods take huge steps and the dip falls between guard samples.
struct Dip {
    hits: Vec<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Before,
    After,
}

impl HybridSystem<1> for Dip {
    type Mode = Phase;
    type Record = f64;
    type Error = DriverError;
    fn rhs(&self, _m: Phase, t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) {
        dy[0] = 2.0 * (t - 1.0);
    }
    fn guards(&self, m: Phase, _t: f64, y: &[f64; 1], g: &mut [f64; MAX_GUARDS]) -> usize {
        g[0] = y[0];
        usize::from(m == Phase::Before)
    }
    fn is_observer(&self, _m: Phase, _i: usize) -> bool {
        false
    }
    fn observe(&mut self, _m: Phase, _i: usize, _t: f64, _y: &[f64; 1]) {}
    fn jump(&mut self, _m: Phase, _i: usize, t: f64, y: &[f64; 1]) -> Result<Jump<Phase, f64, 1>, DriverError> {
        self.hits.push(t);
        Ok(Jump {
            mode: Phase::After,
            t,
            y: *y,
            records: [Some(t), None],
        })
    }
    fn is_terminal(&self, _m: Phase) -> bool {
        false
    }
    fn next_breakpoint(&self, _t: f64) -> Option<f64> {
        None
    }
}

struct Nothing;
impl Observer<Phase, f64, 1> for Nothing {
    fn sample(&mut self, _t: f64, _m: Phase, _y: &[f64; 1]) {}
    fn section(&mut self, _k: u64, _t: f64, _m: Phase, _y: &[f64; 1]) {}
    fn event(&mut self, _t: f64, _m: Phase, _y: &[f64; 1], _r: f64) {}
}

fn first_hit<S: Stepper<1>>(stepper: S, eps: f64) -> (Option<f64>, u64) {
    let sys = Dip { hits: Vec::new() };
    let mut d = Driver::new(
        stepper,
        sys,
        Phase::Before,
        0.0,
        [1.0 - eps],
        Limits::default(),
        Outputs {
            sample_dt: None,
            section_period: None,
        },
    );
    d.advance(10.0, &mut Nothing).expect("runs");
    (d.system().hits.first().copied(), d.steps())
}

#[test]
fn shallow_double_crossing_inside_one_step_is_caught() {
    for eps in [1e-4, 1e-6, 1e-8] {
        let tol = Tolerances {
            rtol: 1e-10,
            atol: 1e-12,
            ..Tolerances::default()
        };
        for (name, (hit, steps)) in [
            ("dop853", first_hit(Dop853::new(tol), eps)),
            ("dopri5", first_hit(Dopri5::new(tol), eps)),
        ] {
            let expected = 1.0 - eps.sqrt();
            let hit = hit.unwrap_or_else(|| panic!("{name}: dip of depth {eps} missed"));
            assert!(
                (hit - expected).abs() < 1e-10,
                "{name}: hit at {hit}, expected {expected}"
            );
            // The dip is far narrower than a step: the sign-change test
            // alone could not have seen it.
            assert!(
                steps < 20,
                "{name}: {steps} steps; the test needs steps wider than the dip"
            );
        }
    }
}
