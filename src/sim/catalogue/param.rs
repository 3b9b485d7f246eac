//! The numeric parameters of a [`Scenario`] that sweeps, maps and the app
//! vary, as a typed enum: `Param::Av.set(&mut scenario, 2.3)`.
//!
//! The config layer resolves the user's key (`excitation.a_v`) to a
//! [`Param`] once; below it nothing looks a parameter up by name.
//! [`Param::key`] is the name it is shown by, in messages, tables and axis
//! titles.
//!
//! Setting a parameter whose default follows another (Ω_v, μ_k, r, the
//! impact friction) fixes it; setting the one it follows moves it while it
//! is unset, exactly as writing the key in a config file would.

use crate::sim::scenario::Scenario;

/// A numeric parameter of a scenario. Units are those of its config key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Param {
    /// `block.width`, B, m.
    Width,
    /// `block.height`, H, m.
    Height,
    /// `friction.static`, μ_s.
    MuS,
    /// `friction.kinetic`, μ_k.
    MuK,
    /// `impact.r`, the ratio law's r.
    ImpactR,
    /// `impact.e`, the impulse law's vertical restitution.
    ImpactE,
    /// `impact.static`, μ̄_s during impact.
    ImpactMuS,
    /// `impact.kinetic`, μ̄_k during impact.
    ImpactMuK,
    /// `excitation.a_h`, A_h, units of ψ g.
    Ah,
    /// `excitation.a_v`, A_v, units of ψ g.
    Av,
    /// `excitation.omega_h`, Ω_h, units of p.
    OmegaH,
    /// `excitation.omega_v`, Ω_v, units of p.
    OmegaV,
    /// `excitation.phase_h`, Φ_h, rad.
    PhaseH,
    /// `excitation.phase_v`, Φ_v, rad.
    PhaseV,
    /// `excitation.scale_h`, factor on the horizontal record.
    ScaleH,
    /// `excitation.scale_v`, factor on the vertical record.
    ScaleV,
    /// `initial.theta`, Θ(0).
    Theta0,
    /// `initial.theta_dot`, Θ'(0).
    ThetaDot0,
    /// `initial.x_dot`, X'(0).
    XDot0,
    /// `run.tau_end`, τ.
    TauEnd,
    /// `run.rtol`.
    Rtol,
    /// `run.atol`.
    Atol,
    /// `run.step`, Ralston's fixed step, τ.
    Step,
    /// `run.output_dt`, τ.
    OutputDt,
    /// `run.tumble_theta`, |Θ| of a tumble.
    TumbleTheta,
    /// `run.zeno_eps`, the impact accumulation threshold on |Θ'|.
    ZenoEps,
}

impl Param {
    /// Every parameter, in the order of the config file's keys.
    pub const ALL: [Param; 26] = [
        Param::Width,
        Param::Height,
        Param::MuS,
        Param::MuK,
        Param::ImpactR,
        Param::ImpactE,
        Param::ImpactMuS,
        Param::ImpactMuK,
        Param::Ah,
        Param::Av,
        Param::OmegaH,
        Param::OmegaV,
        Param::PhaseH,
        Param::PhaseV,
        Param::ScaleH,
        Param::ScaleV,
        Param::Theta0,
        Param::ThetaDot0,
        Param::XDot0,
        Param::TauEnd,
        Param::Rtol,
        Param::Atol,
        Param::Step,
        Param::OutputDt,
        Param::TumbleTheta,
        Param::ZenoEps,
    ];

    /// Whether the parameter is part of the initial state (a map over
    /// two of them is a basin map: the same system in every cell).
    pub(crate) fn is_initial_state(self) -> bool {
        matches!(self, Param::Theta0 | Param::ThetaDot0 | Param::XDot0)
    }

    /// Whether a `[[stack]]` reads it: the excitation's keys and the run's
    /// tolerances, end and outputs. The block's size, friction, impact law
    /// and initial state, Ralston's step and the tumble angle are the
    /// single block's (a stack has its own tables, impulse law and
    /// overturning, and starts at rest).
    pub(crate) fn applies_to_stack(self) -> bool {
        matches!(
            self,
            Param::Ah
                | Param::Av
                | Param::OmegaH
                | Param::OmegaV
                | Param::PhaseH
                | Param::PhaseV
                | Param::ScaleH
                | Param::ScaleV
                | Param::TauEnd
                | Param::Rtol
                | Param::Atol
                | Param::OutputDt
                | Param::ZenoEps
        )
    }

    /// The config key it is written and shown as, e.g. `excitation.a_v`:
    /// its entry's in the catalogue, where the key is declared.
    pub fn key(self) -> &'static str {
        super::spec_of(self).key
    }

    /// Sets the parameter (no validation: call [`Scenario::validate`]).
    pub fn set(self, s: &mut Scenario, v: f64) {
        match self {
            Param::Width => s.block.width = v,
            Param::Height => s.block.height = v,
            Param::MuS => s.block.mu_s = v,
            Param::MuK => s.block.mu_k = Some(v),
            Param::ImpactR => s.impact.r = Some(v),
            Param::ImpactE => s.impact.e = v,
            Param::ImpactMuS => s.impact.mu_s = Some(v),
            Param::ImpactMuK => s.impact.mu_k = Some(v),
            Param::Ah => s.excitation.a_h = v,
            Param::Av => s.excitation.a_v = v,
            Param::OmegaH => s.excitation.omega_h = v,
            Param::OmegaV => s.excitation.omega_v = Some(v),
            Param::PhaseH => s.excitation.phase_h = v,
            Param::PhaseV => s.excitation.phase_v = v,
            Param::ScaleH => s.excitation.scale_h = v,
            Param::ScaleV => s.excitation.scale_v = v,
            Param::Theta0 => s.initial.theta = v,
            Param::ThetaDot0 => s.initial.theta_dot = v,
            Param::XDot0 => s.initial.x_dot = Some(v),
            Param::TauEnd => s.run.tau_end = v,
            Param::Rtol => s.run.rtol = v,
            Param::Atol => s.run.atol = v,
            Param::Step => s.run.step = v,
            Param::OutputDt => s.run.output_dt = v,
            Param::TumbleTheta => s.run.tumble_theta = v,
            Param::ZenoEps => s.run.zeno_eps = v,
        }
    }

    /// Its value in `s`, resolved (a defaulted value as it is run).
    pub fn get(self, s: &Scenario) -> f64 {
        match self {
            Param::Width => s.block.width,
            Param::Height => s.block.height,
            Param::MuS => s.block.mu_s,
            Param::MuK => s.block.kinetic(),
            Param::ImpactR => s.impact_r(),
            Param::ImpactE => s.impact.e,
            Param::ImpactMuS => s.impact_mu_s(),
            Param::ImpactMuK => s.impact_mu_k(),
            Param::Ah => s.excitation.a_h,
            Param::Av => s.excitation.a_v,
            Param::OmegaH => s.excitation.omega_h,
            Param::OmegaV => s.excitation.omega_v(),
            Param::PhaseH => s.excitation.phase_h,
            Param::PhaseV => s.excitation.phase_v,
            Param::ScaleH => s.excitation.scale_h,
            Param::ScaleV => s.excitation.scale_v,
            Param::Theta0 => s.initial.theta,
            Param::ThetaDot0 => s.initial.theta_dot,
            Param::XDot0 => s.initial.x_dot.unwrap_or(0.0),
            Param::TauEnd => s.run.tau_end,
            Param::Rtol => s.run.rtol,
            Param::Atol => s.run.atol,
            Param::Step => s.run.step,
            Param::OutputDt => s.run.output_dt,
            Param::TumbleTheta => s.run.tumble_theta,
            Param::ZenoEps => s.run.zeno_eps,
        }
    }

    /// The scenario `base` with each `(param, value)` set, validated.
    pub fn apply(base: &Scenario, assignments: &[(Param, f64)]) -> Result<Scenario, crate::sim::ScenarioError> {
        let mut s = base.clone();
        for &(p, v) in assignments {
            p.set(&mut s, v);
        }
        s.validate()?;
        Ok(s)
    }
}

impl serde::Serialize for Param {
    /// As its config key.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.key())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_distinct_and_set_then_get_round_trips() {
        let mut keys: Vec<&str> = Param::ALL.iter().map(|p| p.key()).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), Param::ALL.len());
        for p in Param::ALL {
            let mut s = Scenario::default();
            p.set(&mut s, 0.125);
            assert_eq!(p.get(&s), 0.125, "{}", p.key());
        }
    }

    #[test]
    fn setting_the_followed_value_moves_an_unset_default() {
        let mut s = Scenario::default();
        Param::OmegaH.set(&mut s, 3.0);
        assert_eq!(Param::OmegaV.get(&s), 3.0);
        Param::OmegaV.set(&mut s, 4.0);
        Param::OmegaH.set(&mut s, 5.0);
        assert_eq!(Param::OmegaV.get(&s), 4.0);
    }

    #[test]
    fn apply_validates() {
        let e = Param::apply(&Scenario::default(), &[(Param::OmegaH, -1.0)]).unwrap_err();
        assert!(e.to_string().starts_with("excitation.omega_h"), "{e}");
    }
}
