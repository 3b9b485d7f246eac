//! The CSV files of a bifurcation sweep, `classes.csv` and `points.csv`:
//! written by `rocking sweep`, read back and joined by `rocking merge`.

use serde::{Deserialize, Serialize};

use super::csv::{self, Num, Row};
use crate::analysis::orbit_diagram::BifurcationValue;

/// A row of `classes.csv`: one swept value and its steady response.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClassRow {
    /// The parameter value.
    pub value: Num,
    /// The response class (`periodic`, `chaotic`, `tumbled`, …).
    pub outcome: String,
    /// k of a period-k response (the paper's (1,k) mode), else empty.
    pub period: Option<u32>,
    /// Largest |Θ| over the run, transient included.
    pub max_abs_theta: Num,
    /// Largest Lyapunov exponent per unit τ, when computed.
    pub lyapunov: Option<Num>,
}

impl Row for ClassRow {
    const HEADER: &'static [&'static str] = &["value", "outcome", "period", "max_abs_theta", "lyapunov"];
}

impl ClassRow {
    /// The row of `v`.
    pub fn of(v: &BifurcationValue) -> Self {
        Self {
            value: Num(v.value),
            outcome: v.response.name().to_string(),
            period: v.response.period(),
            max_abs_theta: Num(v.max_abs_theta),
            lyapunov: v.lyapunov.map(Num),
        }
    }
}

/// A row of `points.csv`: one Poincaré point of one value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointRow {
    /// The parameter value.
    pub value: Num,
    /// k of τ_k = 2πk/Ω_h.
    pub k: u64,
    /// τ_k.
    pub tau: Num,
    /// Θ(τ_k).
    pub theta: Num,
    /// Θ'(τ_k).
    pub theta_dot: Num,
}

impl Row for PointRow {
    const HEADER: &'static [&'static str] = &["value", "k", "tau", "theta", "theta_dot"];
}

/// `classes.csv` of `values`.
pub(crate) fn classes_csv(values: &[BifurcationValue]) -> String {
    csv::to_string(values.iter().map(ClassRow::of))
}

/// The point rows of `values`, in value order.
pub(crate) fn point_rows(values: &[BifurcationValue]) -> impl Iterator<Item = PointRow> + '_ {
    values.iter().flat_map(|v| {
        v.points.iter().map(move |p| PointRow {
            value: Num(v.value),
            k: p.k,
            tau: Num(p.tau),
            theta: Num(p.theta),
            theta_dot: Num(p.theta_dot),
        })
    })
}

/// `points.csv` of `values`.
pub(crate) fn points_csv(values: &[BifurcationValue]) -> String {
    csv::to_string(point_rows(values))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::classify::Response;
    use crate::model::{Mode, Sign};
    use crate::sim::SectionRow;

    #[test]
    fn headers_are_the_row_fields() {
        let c = ClassRow {
            value: Num(1.0),
            outcome: "rest".into(),
            period: None,
            max_abs_theta: Num(0.0),
            lyapunov: None,
        };
        assert_eq!(csv::header_of(&c), csv::header::<ClassRow>());
        let p = PointRow {
            value: Num(1.0),
            k: 0,
            tau: Num(0.0),
            theta: Num(0.0),
            theta_dot: Num(0.0),
        };
        assert_eq!(csv::header_of(&p), csv::header::<PointRow>());
    }

    #[test]
    fn csv_rows_use_round_trip_numbers_and_empty_cells() {
        let v = BifurcationValue {
            value: 0.1 + 0.2,
            response: Response::Periodic { period: 2 },
            max_abs_theta: 0.25,
            lyapunov: None,
            points: vec![SectionRow {
                k: 3,
                tau: 2.5,
                theta: -0.125,
                theta_dot: 1.0,
                x: 0.0,
                x_dot: 0.0,
                mode: Mode::Rock { pivot: Sign::Neg },
            }],
        };
        assert_eq!(
            classes_csv(std::slice::from_ref(&v)),
            "value,outcome,period,max_abs_theta,lyapunov\n0.30000000000000004,periodic,2,0.25,\n"
        );
        assert_eq!(
            points_csv(&[v]),
            "value,k,tau,theta,theta_dot\n0.30000000000000004,3,2.5,-0.125,1.0\n"
        );
    }
}
