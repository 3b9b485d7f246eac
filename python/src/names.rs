//! The Python package's words for a study's inputs: the analysis layer's
//! errors name a field by meaning ([`StudyField`]); here each becomes the
//! keyword that gives it (`tau_end=700: must be larger than
//! transient=800`), never the CLI's flag.

use std::borrow::Cow;

use rocking::analysis::field::{FieldNames, RequestField, StudyField};

/// Study inputs named as `rocking.sweep`, `rocking.outcome_map`,
/// `rocking.spectrum` and `rocking.sliding_spectrum` name their parameters
/// (`start`/`stop`/`step` for a grid, `shard=(K, N)` as the private
/// `_sweep` takes it, `sizes=(from, to, count)` for a spectrum's sizes).
#[derive(Clone, Copy, Debug, Default)]
pub struct Keywords;

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

    /// `name=value`, as the argument is written in the call.
    fn valued(&self, field: StudyField, value: &str) -> String {
        format!("{}={value}", self.name(field))
    }
}

impl FieldNames<RequestField> for Keywords {
    fn name(&self, field: RequestField) -> Cow<'static, str> {
        Cow::Borrowed(match field {
            RequestField::Record => "record",
            RequestField::Unit => "unit",
            RequestField::UnitV => "unit_v",
            RequestField::Scale => "scale",
            RequestField::Pga => "pga",
            RequestField::Pulse => "pulse",
            RequestField::PulseAccel => "pulse_accel",
            RequestField::PulsePeriod => "pulse_period",
            RequestField::Cycles => "cycles",
            RequestField::SizeFrom => "sizes[0]",
            RequestField::SizeTo => "sizes[1]",
            RequestField::SizeCount => "sizes[2]",
            RequestField::BOverH => "b_over_h",
            RequestField::SearchStep => "search_step",
            RequestField::SearchMax => "search_max",
            RequestField::AmpStep => "amp_step",
            RequestField::AmpMax => "amp_max",
            RequestField::RelTol => "rel_tol",
            RequestField::Mu => "mu",
            RequestField::KineticRatio => "kinetic_ratio",
            RequestField::Im => "im",
            RequestField::SaPeriod => "sa_period",
            RequestField::Levels => "levels",
            RequestField::Blocks => "blocks",
            RequestField::Threshold => "threshold",
        })
    }

    fn valued(&self, field: RequestField, value: &str) -> String {
        format!("{}={value}", self.name(field))
    }
}
