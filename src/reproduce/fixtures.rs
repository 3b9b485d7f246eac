//! Made-up response grids shared by the tests of the diagram comparison
//! ([`super::diagrams`]) and of the report's verdicts ([`super::report`]).

use crate::analysis::classify::Response;

/// Period 1.
pub(crate) const P1: Response = Response::Periodic { period: 1 };
/// Period 2.
pub(crate) const P2: Response = Response::Periodic { period: 2 };
/// Period 4.
pub(crate) const P4: Response = Response::Periodic { period: 4 };
/// Chaotic.
pub(crate) const C: Response = Response::Chaotic;
/// Tumbled.
pub(crate) const T: Response = Response::Tumbled;

/// Values 0, 0.1, 0.2, … with these responses.
pub(crate) fn grid(rs: &[Response]) -> Vec<(f64, Response)> {
    rs.iter().enumerate().map(|(i, r)| (i as f64 * 0.1, *r)).collect()
}
