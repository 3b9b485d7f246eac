//! The Python package's words for a study's inputs: the analysis layer's
//! errors name a field by meaning ([`StudyField`]); here each becomes the
//! keyword that gives it (`tau_end=700: must be larger than
//! transient=800`), never the CLI's flag.

use std::borrow::Cow;

use rocking::analysis::field::{FieldNames, StudyField};

/// Study inputs named as `rocking.sweep` and `rocking.outcome_map` name
/// their parameters (`start`/`stop`/`step` for a grid, `shard=(K, N)` as
/// the private `_sweep` takes it).
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
