//! The rules a [`Scenario`] must satisfy, checked in the order of the config
//! file's sections so that the first broken rule is the one reported. Every
//! message names the key as the user writes it and says what is allowed.

use super::catalogue::{self, KeySpec, Param};
use super::method::Method;
use super::scenario::{
    ExcitationKind, LawKind, LyapunovChoice, MAX_FLOOR_PARTICIPATION, MAX_FLOOR_PERIOD_S, MAX_HISTORY_ROWS,
    MIN_FLOOR_PERIOD_S, MIN_PSI, MIN_SPECTRUM_SAMPLES, MU_K_LIMIT, PAPER_SPECTRUM_END, Scenario, ScenarioError,
    SpectrumRange,
};
use crate::model::excitation::pulse;

/// `value` checked against the range the catalogue declares for `p`.
fn within(p: Param, value: f64) -> Result<(), ScenarioError> {
    within_spec(catalogue::spec_of(p), value)
}

/// `value` checked against the range the catalogue declares for `key`.
fn within_key(key: &str, value: f64) -> Result<(), ScenarioError> {
    match catalogue::spec(key) {
        Some(spec) => within_spec(spec, value),
        None => Ok(()),
    }
}

fn within_spec(spec: &KeySpec, value: f64) -> Result<(), ScenarioError> {
    match spec.range {
        Some(range) => check(spec.key, (range.ok)(value), range.allowed, value),
        None => Ok(()),
    }
}

/// `Ok` if `ok`, else "`key`: `value` is out of range: must be `allowed`".
pub(super) fn check(key: &str, ok: bool, allowed: &str, value: f64) -> Result<(), ScenarioError> {
    if ok {
        Ok(())
    } else {
        Err(ScenarioError::new(
            key,
            // Debug formatting: 1e-308 as "1e-308", not 309 digits.
            format!("{value:?} is out of range: must be {allowed}"),
        ))
    }
}

impl Scenario {
    /// Checks every rule; the first broken one is the error.
    pub fn validate(&self) -> Result<(), ScenarioError> {
        self.validate_stack()?;
        if self.frame.is_some() {
            self.validate_frame()?;
        } else {
            self.validate_block()?;
        }
        self.validate_impact()?;
        self.validate_excitation()?;
        self.validate_run()?;
        self.validate_initial()?;
        self.validate_analyses()?;
        self.validate_floor()?;
        self.validate_frame_analyses()
    }

    /// A rocking frame's columns, beam and contact (docs/model.md §16).
    fn validate_frame(&self) -> Result<(), ScenarioError> {
        let (Some(frame), b) = (&self.frame, &self.block) else {
            return Ok(());
        };
        within_key("frame.width", b.width)?;
        within_key("frame.height", b.height)?;
        check(
            "frame.width",
            self.geometry().psi >= MIN_PSI,
            "at least 1e-6 of frame.height (a slenderness ψ = atan(B/H) below 1e-6 rad makes every amplitude in ψg vanish)",
            b.width,
        )?;
        check(
            "frame.columns",
            (2..=1000).contains(&frame.columns),
            "an integer in 2..=1000 (a cap beam rests on at least two columns)",
            f64::from(frame.columns),
        )?;
        within_key("frame.beam_mass_ratio", frame.beam_mass_ratio)?;
        if b.mu_s.is_finite() {
            return Err(ScenarioError::new(
                "friction.static",
                "a [frame]'s columns rock on stuck corners; sliding of a frame is not modelled (docs/model.md §16)",
            ));
        }
        Ok(())
    }

    /// What a frame cannot do yet: the single block's impulse law and the
    /// Lyapunov exponents, whose tangent equations are the block's.
    fn validate_frame_analyses(&self) -> Result<(), ScenarioError> {
        if self.frame.is_none() {
            return Ok(());
        }
        if self.impact.law == LawKind::Impulse {
            return Err(ScenarioError::new(
                "impact.law",
                "\"impulse\" is the single block's law; a [frame] takes \"housner\" (its own coefficient, docs/model.md §16.3) or \"ratio\"",
            ));
        }
        Ok(())
    }

    /// A body without tangent equations (`body`: a stack) has its
    /// largest Lyapunov exponent by two trajectories alone.
    pub(super) fn two_trajectories_only(&self, body: &str) -> Result<(), ScenarioError> {
        let method = self.analyses.lyapunov_method;
        if method == LyapunovChoice::Benettin {
            return Ok(());
        }
        Err(ScenarioError::new(
            "analysis.lyapunov_method",
            format!(
                "\"{}\" needs tangent equations, which a {body} does not have (yet): \"benettin\" gives its largest exponent by two trajectories",
                method.name()
            ),
        ))
    }

    fn validate_floor(&self) -> Result<(), ScenarioError> {
        let Some(floor) = &self.floor else {
            return Ok(());
        };
        if floor.modes.is_empty() {
            return Err(ScenarioError::new("floor.mode", "needs at least one mode"));
        }
        for (k, m) in floor.modes.iter().enumerate() {
            let key = |name: &str| {
                if floor.as_tables {
                    format!("floor.mode[{k}].{name}")
                } else {
                    format!("floor.{name}")
                }
            };
            check(
                &key("period"),
                (MIN_FLOOR_PERIOD_S..=MAX_FLOOR_PERIOD_S).contains(&m.period_s),
                "in [0.01, 20] s (a stiffer floor is rigid: leave [floor] out)",
                m.period_s,
            )?;
            check(
                &key("damping"),
                m.damping > 0.0 && m.damping < 1.0,
                "in (0, 1), a fraction of critical (0.05 is 5 %)",
                m.damping,
            )?;
            check(
                &key("participation"),
                m.participation.abs() <= MAX_FLOOR_PARTICIPATION,
                "in [-10, 10] (Γφ of the mode at the floor)",
                m.participation,
            )?;
        }
        if self.excitation.kind == ExcitationKind::Pulse {
            return Err(ScenarioError::new(
                "floor",
                "filters records and harmonic ground motion only, not pulses: remove [floor] or change excitation.kind",
            ));
        }
        Ok(())
    }

    fn validate_block(&self) -> Result<(), ScenarioError> {
        let b = &self.block;
        within(Param::Width, b.width)?;
        within(Param::Height, b.height)?;
        let psi = self.geometry().psi;
        check(
            "block.width",
            psi >= MIN_PSI,
            "at least 1e-6 of block.height (a slenderness ψ = atan(B/H) below 1e-6 rad makes every amplitude in ψg vanish)",
            b.width,
        )?;
        within(Param::MuS, b.mu_s)?;
        let mu_k = b.kinetic();
        // An absent kinetic coefficient takes the static one; an error about
        // it must then say so, or the user is told about a key never written.
        let kinetic_key = if b.mu_k.is_some() {
            "friction.kinetic"
        } else {
            "friction.kinetic (absent, so equal to friction.static)"
        };
        check(kinetic_key, mu_k >= 0.0, ">= 0 or inf", mu_k)?;
        check(
            kinetic_key,
            mu_k <= b.mu_s,
            &format!("<= friction.static ({:?})", b.mu_s),
            mu_k,
        )?;
        check(
            kinetic_key,
            mu_k.is_finite() || b.mu_s.is_infinite(),
            "finite when friction.static is finite",
            mu_k,
        )?;
        check(
            kinetic_key,
            mu_k < MU_K_LIMIT || b.mu_s.is_infinite(),
            "< 4/3 (larger kinetic friction makes slide-rock ill-posed: the Painlevé paradox, docs/model.md §4)",
            mu_k,
        )
    }

    fn validate_impact(&self) -> Result<(), ScenarioError> {
        let r = self.impact_r();
        within(Param::ImpactR, r)?;
        let e = self.impact.e;
        within(Param::ImpactE, e)?;
        let (mu_s, mu_k) = (self.impact_mu_s(), self.impact_mu_k());
        within(Param::ImpactMuS, mu_s)?;
        within(Param::ImpactMuK, mu_k)?;
        check(
            "impact.kinetic",
            mu_k < MU_K_LIMIT || mu_s.is_infinite(),
            "< 4/3 (larger kinetic friction makes the slipping impact ill-posed, docs/model.md §7.2)",
            mu_k,
        )?;
        check(
            "impact.kinetic",
            mu_k <= mu_s,
            &format!("<= impact.static ({mu_s:?})"),
            mu_k,
        )
    }

    fn validate_excitation(&self) -> Result<(), ScenarioError> {
        let x = &self.excitation;
        within(Param::Ah, x.a_h)?;
        within(Param::Av, x.a_v)?;
        within(Param::OmegaH, x.omega_h)?;
        let omega_v = x.omega_v();
        within(Param::OmegaV, omega_v)?;
        within(Param::PhaseH, x.phase_h)?;
        within(Param::PhaseV, x.phase_v)?;
        if !(1..=pulse::MAX_TYPE_C_CYCLES).contains(&x.cycles) {
            return Err(ScenarioError::new(
                "excitation.cycles",
                format!(
                    "{} is out of range: must be in 1..={}",
                    x.cycles,
                    pulse::MAX_TYPE_C_CYCLES
                ),
            ));
        }
        within(Param::ScaleH, x.scale_h)?;
        within(Param::ScaleV, x.scale_v)?;
        // A zero factor makes the record no excitation at all, which no one
        // means to ask for (a block at rest needs no run); a negative one
        // flips the record's sign, the other polarity a rocking block
        // responds to differently, and is allowed.
        for (key, scale) in [("excitation.scale_h", x.scale_h), ("excitation.scale_v", x.scale_v)] {
            if scale == 0.0 {
                return Err(ScenarioError::new(
                    key,
                    "0 turns the record into no excitation at all; give a non-zero factor (a negative one flips the record's sign)",
                ));
            }
        }
        if x.kind == ExcitationKind::Record && x.record_h.is_none() {
            return Err(ScenarioError::new(
                "excitation.file_h",
                "is required when excitation.kind = \"record\"",
            ));
        }
        Ok(())
    }

    fn validate_run(&self) -> Result<(), ScenarioError> {
        let r = &self.run;
        within(Param::Rtol, r.rtol)?;
        within(Param::Atol, r.atol)?;
        within(Param::Step, r.step)?;
        if let Some(tail) = r.record_tail_s {
            within_key("run.tail_s", tail)?;
        }
        let tau_end = self.tau_end();
        let end_key = if self.record_end_tau().is_some() && r.record_tail_s.is_some() {
            "run.tail_s (the record's length plus the tail, in τ)"
        } else {
            "run.tau_end"
        };
        check(end_key, tau_end > 0.0 && tau_end <= 1e9, "in (0, 1e9]", tau_end)?;
        within(Param::OutputDt, r.output_dt)?;
        if r.output_dt > 0.0 && tau_end / r.output_dt > MAX_HISTORY_ROWS {
            return Err(ScenarioError::new(
                "run.output_dt",
                format!(
                    "{} gives more than 5e7 history rows over the run (run.tau_end or run.t_end: τ = {}); use a larger step or 0",
                    r.output_dt, tau_end
                ),
            ));
        }
        let side = self.geometry().side_theta();
        check(
            "run.tumble_theta",
            r.tumble_theta > 0.0 && r.tumble_theta <= side,
            &format!("in (0, π/(2ψ) = {side}]"),
            r.tumble_theta,
        )?;
        within(Param::ZenoEps, r.zeno_eps)?;
        if r.max_steps == 0 {
            return Err(ScenarioError::new("run.max_steps", "must be >= 1"));
        }
        if r.max_events == 0 {
            return Err(ScenarioError::new("run.max_events", "must be >= 1"));
        }
        // A fixed-step method's step count is known before it starts: a run
        // that would stop at max_steps is refused now, not hours later.
        if r.method() == Method::Ralston {
            let steps = tau_end / r.step;
            if steps > r.max_steps as f64 {
                return Err(ScenarioError::new(
                    "run.step",
                    format!(
                        "{:?} needs {steps:.3e} steps of run.method = \"ralston\" over τ = {tau_end:?}, more than run.max_steps = {}; use a larger step or another method",
                        r.step, r.max_steps
                    ),
                ));
            }
        }
        Ok(())
    }

    fn validate_initial(&self) -> Result<(), ScenarioError> {
        let i = &self.initial;
        let tumble = self.run.tumble_theta;
        check(
            "initial.theta",
            i.theta.abs() < tumble,
            &format!("|Θ| < run.tumble_theta ({tumble})"),
            i.theta,
        )?;
        check(
            "initial.theta_dot",
            i.theta_dot.abs() <= 1e6,
            "|Θ'| <= 1e6",
            i.theta_dot,
        )?;
        if let Some(x) = i.x_dot {
            check("initial.x_dot", x.abs() <= 1e6, "|X'| <= 1e6", x)?;
        }
        Ok(())
    }

    fn validate_analyses(&self) -> Result<(), ScenarioError> {
        let a = &self.analyses;
        if a.lyapunov && self.excitation.kind != ExcitationKind::Harmonic {
            return Err(ScenarioError::new(
                "analysis.lyapunov",
                "needs excitation.kind = \"harmonic\" (the exponents of the periodically forced block)",
            ));
        }
        if a.spectrum && self.run.output_dt <= 0.0 {
            return Err(ScenarioError::new(
                "analysis.spectrum",
                "needs run.output_dt > 0 (the spectrum is computed from the history)",
            ));
        }
        let samples = (self.tau_end() / self.run.output_dt).floor() + 1.0;
        if a.spectrum && a.spectrum_window == SpectrumRange::All && samples < MIN_SPECTRUM_SAMPLES as f64 {
            return Err(ScenarioError::new(
                "analysis.spectrum",
                format!(
                    "needs at least {MIN_SPECTRUM_SAMPLES} history samples; run.tau_end = {:?} with run.output_dt = {:?} gives {samples}",
                    self.tau_end(),
                    self.run.output_dt
                ),
            ));
        }
        if a.spectrum && a.spectrum_window == SpectrumRange::Paper && self.run.tau_end < PAPER_SPECTRUM_END {
            return Err(ScenarioError::new(
                "analysis.spectrum_window",
                "\"paper\" needs run.tau_end >= 28.384 (the paper's window is τ 12–28.384)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_scenario_is_valid() {
        assert_eq!(Scenario::default().validate(), Ok(()));
    }

    #[test]
    fn each_rule_names_its_key() {
        type Break = fn(&mut Scenario);
        let cases: Vec<(&str, Break)> = vec![
            ("block.width", |s| s.block.width = 0.0),
            ("friction.kinetic (absent", |s| s.block.mu_s = 2.0),
            ("friction.kinetic:", |s| {
                s.block.mu_s = 0.5;
                s.block.mu_k = Some(0.6);
            }),
            ("impact.r", |s| s.impact.r = Some(1.5)),
            ("excitation.omega_v", |s| s.excitation.omega_v = Some(-1.0)),
            ("excitation.cycles", |s| s.excitation.cycles = 0),
            ("run.output_dt", |s| {
                s.run.tau_end = 1e9;
                s.run.output_dt = 1.0;
            }),
            ("initial.theta", |s| s.initial.theta = 1.0),
            ("analysis.spectrum", |s| {
                s.analyses.spectrum = true;
                s.run.output_dt = 0.0;
            }),
        ];
        for (key, break_it) in cases {
            let mut s = Scenario::default();
            break_it(&mut s);
            let e = s.validate().unwrap_err().to_string();
            assert!(e.starts_with(key), "{key}: {e}");
        }
    }

    #[test]
    fn defaults_that_follow_another_value_move_with_it() {
        let mut s = Scenario::default();
        s.excitation.omega_h = 5.0;
        assert_eq!(s.excitation.omega_v(), 5.0);
        s.block.width = 2.0;
        assert_eq!(s.impact_r(), s.geometry().housner_r().max(0.0));
        s.run.rtol = 1e-3;
        assert_eq!(s.run.method(), super::super::Method::Dop853);
    }
}
