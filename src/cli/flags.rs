//! The CLI's words for a study's inputs: the analysis layer's errors name
//! a field by meaning ([`StudyField`]); here each becomes the flag that
//! gives it (`--tau-end 700: must be larger than --transient 800`).

use std::borrow::Cow;

use crate::analysis::field::{FieldNames, RequestField, StudyField};

/// Study inputs named as `rocking sweep`, `map`, `merge` and the
/// engineering commands (`spectrum`, `sliding-spectrum`, `pulse-map`) name them.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Flags;

impl FieldNames for Flags {
    fn name(&self, field: StudyField) -> Cow<'static, str> {
        Cow::Borrowed(match field {
            StudyField::From => "--from",
            StudyField::To => "--to",
            StudyField::Step => "--step",
            StudyField::Shard => "--shard",
            StudyField::Continuation => "--continuation",
            StudyField::Transient => "--transient",
            StudyField::TauEnd => "--tau-end",
        })
    }

    fn valued(&self, field: StudyField, value: &str) -> String {
        format!("{} {value}", self.name(field))
    }
}

impl FieldNames<RequestField> for Flags {
    fn name(&self, field: RequestField) -> Cow<'static, str> {
        Cow::Borrowed(match field {
            RequestField::Record => "--record",
            RequestField::Unit => "--unit",
            RequestField::UnitV => "--unit-v",
            RequestField::Scale => "--scale",
            RequestField::Pga => "--pga",
            RequestField::Pulse => "--pulse",
            RequestField::PulseAccel => "--pulse-accel",
            RequestField::PulsePeriod => "--pulse-period",
            RequestField::Cycles => "--cycles",
            RequestField::SizeFrom => "--from",
            RequestField::SizeTo => "--to",
            RequestField::SizeCount => "--count",
            RequestField::BOverH => "--b-over-h",
            RequestField::SearchStep => "--search-step",
            RequestField::SearchMax => "--search-max",
            RequestField::AmpStep => "--amp-step",
            RequestField::AmpMax => "--amp-max",
            RequestField::RelTol => "--rel-tol",
            RequestField::Mu => "--mu",
            RequestField::KineticRatio => "--kinetic-ratio",
            RequestField::Im => "--im",
            RequestField::SaPeriod => "--sa-period",
            RequestField::Levels => "--levels",
            RequestField::Blocks => "--block",
            RequestField::Threshold => "--threshold",
        })
    }

    fn valued(&self, field: RequestField, value: &str) -> String {
        format!("{} {value}", self.name(field))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::orbit_diagram::{Continuation, Grid, Plan, PlanError, Shard};
    use crate::analysis::steady::{Window, WindowError};

    /// The messages `rocking sweep` and `map` have always printed, written
    /// out: the typed errors must render to them byte for byte.
    #[test]
    fn the_cli_words_each_input_as_its_flag_as_it_always_has() {
        let plan = |e: PlanError| e.render(&Flags);
        let window = |e: WindowError| e.render(&Flags);
        assert_eq!(
            plan(Grid::new(0.0, 1.0, 0.0).unwrap_err()),
            "--step 0.0: must be finite and > 0"
        );
        assert_eq!(
            plan(Grid::new(1.0, 0.0, 0.1).unwrap_err()),
            "--to 0.0: must be >= --from 1"
        );
        assert_eq!(
            plan(Grid::new(f64::NAN, 0.0, 0.1).unwrap_err()),
            "--from NaN: must be finite"
        );
        assert_eq!(
            plan(Shard::parse("x").unwrap_err()),
            "--shard x: expected K/N, e.g. 0/4 (K counts from 0)"
        );
        let grid = Grid::new(0.0, 1.0, 0.5).unwrap();
        assert_eq!(
            plan(Plan::new(grid, Continuation::Up, Some(Shard { index: 0, count: 2 })).unwrap_err()),
            "--shard cannot be combined with --continuation up: each value is seeded from the previous one, so the values cannot be split"
        );
        let w = |transient, tau_end| Window { transient, tau_end };
        assert_eq!(
            window(w(150.0, 100.0).validate().unwrap_err()),
            "--tau-end 100: must be larger than --transient 150"
        );
        assert_eq!(
            window(w(-1.0, 100.0).validate().unwrap_err()),
            "--transient -1: must be finite and >= 0"
        );
        assert_eq!(
            window(w(0.0, 2e9).validate().unwrap_err()),
            "--tau-end 2000000000: must be finite and <= 1e9"
        );
        let short = w(0.0, 10.0)
            .check_points(std::f64::consts::TAU / 8.0, &Default::default())
            .unwrap_err();
        assert_eq!(
            window(short),
            "--transient 0 / --tau-end 10: the window holds 13 section points (period 0.785398); at least 64 are needed to classify"
        );
    }
}
