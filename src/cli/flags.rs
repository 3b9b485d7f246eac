//! The CLI's words for a study's inputs: the analysis layer's errors name
//! a field by meaning ([`StudyField`]); here each becomes the flag that
//! gives it (`--tau-end 700: must be larger than --transient 800`).

use std::borrow::Cow;

use crate::analysis::field::{FieldNames, StudyField};

/// Study inputs named as `rocking sweep`, `map` and `merge` name them.
#[derive(Clone, Copy, Debug, Default)]
pub struct Flags;

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
