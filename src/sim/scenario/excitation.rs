//! The base motion as a config gives it, and the excitation it makes: the ground's, filtered through the building of `[floor]` if there is one.

use super::{ExcitationKind, Record, Scenario, ScenarioError, ShapeKind};
use crate::model::excitation::{
    Excitation, FloorExcitation, FloorMode, Harmonic, Pulse, PulsePair, PulseShape, RecordExcitation,
};
use crate::model::oscillator::Oscillator;

/// The base motion.
#[derive(Clone, Debug, PartialEq)]
pub struct ExcitationSpec {
    /// Which kind. Default harmonic.
    pub kind: ExcitationKind,
    /// A_h, units of ψ g (harmonic and pulse). Default 0.
    pub a_h: f64,
    /// A_v, units of ψ g. Default 0.
    pub a_v: f64,
    /// Ω_h, units of p, > 0. Default 8 (the paper's).
    pub omega_h: f64,
    /// Ω_v, units of p, > 0; `None`: Ω_h.
    pub omega_v: Option<f64>,
    /// Φ_h, rad. Default 0.
    pub phase_h: f64,
    /// Φ_v, rad. Default 0.
    pub phase_v: f64,
    /// Pulse shape. Default one-sine.
    pub shape: ShapeKind,
    /// n of a type-C_n pulse, 1..=[`MAX_TYPE_C_CYCLES`](crate::model::excitation::pulse::MAX_TYPE_C_CYCLES). Default 1.
    pub cycles: u32,
    /// Horizontal record (required for `Record`).
    pub record_h: Option<Record>,
    /// Optional vertical record.
    pub record_v: Option<Record>,
    /// Factor on the horizontal record. Default 1.
    pub scale_h: f64,
    /// Factor on the vertical record. Default 1.
    pub scale_v: f64,
}

impl ExcitationSpec {
    /// Ω_v, resolved.
    pub fn omega_v(&self) -> f64 {
        self.omega_v.unwrap_or(self.omega_h)
    }

    /// The forcing period 2π/Ω_h of harmonic excitation, τ; `None` for the
    /// other kinds.
    pub fn forcing_period(&self) -> Option<f64> {
        (self.kind == ExcitationKind::Harmonic).then(|| std::f64::consts::TAU / self.omega_h)
    }
}

impl Scenario {
    /// The excitation the block feels: the ground's ([`Scenario::ground_excitation`])
    /// filtered through the building of `[floor]` if there is one. Fails
    /// for a pulse the model refuses (the error names the amplitude's key)
    /// and for a pulse under `[floor]`.
    pub fn excitation(&self) -> Result<Excitation, ScenarioError> {
        let ground = self.ground_excitation()?;
        let Some(floor) = &self.floor else {
            return Ok(ground);
        };
        let mut modes = Vec::with_capacity(floor.modes.len());
        for (k, m) in floor.modes.iter().enumerate() {
            let key = if floor.as_tables {
                format!("floor.mode[{k}].period")
            } else {
                "floor.period".to_string()
            };
            let oscillator = Oscillator::new(m.period_s, m.damping)
                .ok_or_else(|| ScenarioError::new(key, "needs a period > 0 s and a damping in [0, 1)"))?;
            modes.push(FloorMode {
                oscillator,
                participation: m.participation,
            });
        }
        Ok(match ground {
            Excitation::None => Excitation::None,
            Excitation::Harmonic(h) => {
                Excitation::Floor(Box::new(FloorExcitation::harmonic(h, modes, self.geometry().p)))
            }
            Excitation::Record(r) => Excitation::Floor(Box::new(FloorExcitation::record(*r, modes))),
            Excitation::Pulse(_) | Excitation::Floor(_) => {
                return Err(ScenarioError::new(
                    "floor",
                    "filters records and harmonic ground motion only; a pulse stands for near-fault ground motion, remove [floor] or use excitation.kind = \"record\"",
                ));
            }
        })
    }

    /// The ground's excitation, without the building of `[floor]`.
    pub(crate) fn ground_excitation(&self) -> Result<Excitation, ScenarioError> {
        let geo = self.geometry();
        let x = &self.excitation;
        Ok(match x.kind {
            ExcitationKind::None => Excitation::None,
            ExcitationKind::Harmonic => Excitation::Harmonic(Harmonic {
                a_h: x.a_h,
                a_v: x.a_v,
                omega_h: x.omega_h,
                omega_v: x.omega_v(),
                phase_h: x.phase_h,
                phase_v: x.phase_v,
                psi: geo.psi,
            }),
            ExcitationKind::Pulse => {
                let shape = match x.shape {
                    ShapeKind::OneCosine => PulseShape::OneCosine,
                    ShapeKind::TypeC => PulseShape::TypeC { n: x.cycles },
                    ShapeKind::OneSine => PulseShape::OneSine,
                    ShapeKind::Rectangular => PulseShape::Rectangular,
                    ShapeKind::HalfSine => PulseShape::HalfSine,
                };
                let make = |amp: f64, omega: f64, key: &str| {
                    Pulse::new(shape, amp * geo.psi, omega).map_err(|e| ScenarioError::new(key, e))
                };
                let horizontal = make(x.a_h, x.omega_h, "excitation.a_h")?;
                let vertical = if x.a_v != 0.0 {
                    Some(make(x.a_v, x.omega_v(), "excitation.a_v")?)
                } else {
                    None
                };
                Excitation::Pulse(PulsePair { horizontal, vertical })
            }
            ExcitationKind::Record => {
                let Some(h) = &x.record_h else {
                    return Err(ScenarioError::new(
                        "excitation.file_h",
                        "is required when excitation.kind = \"record\"",
                    ));
                };
                let v = x.record_v.as_ref().map(|r| r.series.clone());
                Excitation::Record(Box::new(RecordExcitation::new(
                    h.series.clone(),
                    v,
                    geo.p,
                    x.scale_h,
                    x.scale_v,
                )))
            }
        })
    }
}
