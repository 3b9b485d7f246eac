//! How a run ended, typed once for every surface: the mechanics' word
//! ([`Outcome`], `summary.json`'s `outcome`, Python's `Run.outcome`) and the
//! engineer's ([`EndState`], `physical.end_state`, spectra, fragility, the
//! GUI's banner), with the one mapping between them and the one spelling of
//! each name.

use serde::Serialize;

/// How a run ended, in the mechanics' words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Still moving at `tau_end`.
    Running,
    /// At rest at `tau_end`.
    Rest,
    /// Tumbled.
    Tumbled,
    /// Flight.
    Flight,
}

impl Outcome {
    /// Every outcome, in the order above.
    pub const ALL: [Outcome; 4] = [Outcome::Running, Outcome::Rest, Outcome::Tumbled, Outcome::Flight];

    /// The name in outputs (`summary.json`'s `outcome`, Python's
    /// `Run.outcome`).
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Running => "running",
            Outcome::Rest => "rest",
            Outcome::Tumbled => "tumbled",
            Outcome::Flight => "flight",
        }
    }

    /// Reads an output name back.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|o| o.name() == name)
    }
}

// Written through `name()` so that the JSON and every other output spell an
// outcome the same way.
impl Serialize for Outcome {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// How a run ended, in the words an engineer uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndState {
    /// Flat and stuck at the end of the run.
    Rest,
    /// Still rocking or sliding at the end: the run ended before the block
    /// settled, so it is not known to have survived.
    Moving,
    /// Overturned: |Θ| reached `run.tumble_theta` (default 1: the centre of
    /// mass passed over the pivot).
    Overturned,
    /// Left the ground (the normal force vanished); what follows is not
    /// computed.
    Flight,
}

impl EndState {
    /// Every end state, in the order above.
    pub const ALL: [EndState; 4] = [EndState::Rest, EndState::Moving, EndState::Overturned, EndState::Flight];

    /// The engineer's word for a run's `outcome`.
    pub fn of(outcome: Outcome) -> Self {
        match outcome {
            Outcome::Running => EndState::Moving,
            Outcome::Rest => EndState::Rest,
            Outcome::Tumbled => EndState::Overturned,
            Outcome::Flight => EndState::Flight,
        }
    }

    /// The name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            EndState::Rest => "rest",
            EndState::Moving => "moving",
            EndState::Overturned => "overturned",
            EndState::Flight => "flight",
        }
    }

    /// Reads an output name back.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether the block is known to have survived (rest or still moving).
    pub fn survived(self) -> bool {
        matches!(self, EndState::Rest | EndState::Moving)
    }

    /// Whether the run ended on an event (overturning or flight) whose
    /// time is part of the answer.
    pub fn is_event(self) -> bool {
        !self.survived()
    }
}

impl Serialize for EndState {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for EndState {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        EndState::from_name(&name)
            .ok_or_else(|| serde::de::Error::unknown_variant(&name, &["rest", "moving", "overturned", "flight"]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names as the outputs have always spelled them, written out here
    /// rather than read from the code under test.
    #[test]
    fn outcomes_and_end_states_keep_their_output_spellings() {
        let outcomes: Vec<_> = Outcome::ALL.iter().map(|o| o.name()).collect();
        assert_eq!(outcomes, ["running", "rest", "tumbled", "flight"]);
        let ends: Vec<_> = EndState::ALL.iter().map(|e| e.name()).collect();
        assert_eq!(ends, ["rest", "moving", "overturned", "flight"]);
    }

    #[test]
    fn json_spells_each_name_as_the_name_does() {
        for o in Outcome::ALL {
            assert_eq!(serde_json::to_string(&o).unwrap(), format!("\"{}\"", o.name()));
            assert_eq!(Outcome::from_name(o.name()), Some(o));
        }
        for e in EndState::ALL {
            let json = serde_json::to_string(&e).unwrap();
            assert_eq!(json, format!("\"{}\"", e.name()));
            assert_eq!(serde_json::from_str::<EndState>(&json).unwrap(), e);
        }
        assert!(serde_json::from_str::<EndState>("\"fallen\"").is_err());
    }

    #[test]
    fn each_outcome_has_the_engineers_word_for_it() {
        let pairs = [
            (Outcome::Running, EndState::Moving),
            (Outcome::Rest, EndState::Rest),
            (Outcome::Tumbled, EndState::Overturned),
            (Outcome::Flight, EndState::Flight),
        ];
        for (o, e) in pairs {
            assert_eq!(EndState::of(o), e);
        }
        assert!(EndState::Moving.survived() && EndState::Rest.survived());
        assert!(EndState::Overturned.is_event() && EndState::Flight.is_event());
    }
}
