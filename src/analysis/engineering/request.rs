//! What an engineering study is asked, checked before anything runs: the
//! motion's scale (a factor or a PGA), an analytic pulse in physical units,
//! a rocking spectrum's sizes, slendernesses and overturning-scale search,
//! and the ladder of a search.
//!
//! Contract: every surface (the CLI, the Python package) builds these from
//! its own arguments and calls the same checks, so the rules and their
//! wording live here once. An error names each input by meaning
//! ([`RequestField`]); [`RequestError::render`] words it as the surface
//! names its arguments (`--to 0.2: below --from 3`, `sizes[1]=0.2: below
//! sizes[0]=3`). Numbers print as [`show`](crate::analysis::field::show) writes them.

use std::f64::consts::TAU;

use super::fragility::{Intensity, SA_DAMPING};
use super::overturn_scale::ladder;
use super::response::{BlockSize, Drive};
use super::stack_response::stack_size;
use crate::analysis::field::RequestField;
use crate::model::excitation::pulse::MAX_TYPE_C_CYCLES;
use crate::model::excitation::record::Series;
use crate::model::oscillator::Oscillator;
use crate::model::units::AccelUnit;
use crate::sim::Scenario;
use crate::sim::scenario::ShapeKind;

mod error;
mod spectrum;

pub use error::RequestError;
pub use spectrum::{OverturnRequest, SPECTRUM_B_OVER_H, SpectrumBlocks, SpectrumRequest, spectrum_ratios};

/// The period of Sa(T), s, given exactly when the intensity measure is
/// Sa (a period the 5 %-damped oscillator cannot have is refused).
pub fn sa_period(im: Intensity, sa_period_s: Option<f64>) -> Result<Option<f64>, RequestError> {
    match (im, sa_period_s) {
        (Intensity::Sa, None) => Err(RequestError::SaPeriodMissing),
        (Intensity::Sa, Some(t)) if !(t > 0.0 && t.is_finite()) || Oscillator::new(t, SA_DAMPING).is_none() => {
            Err(RequestError::SaPeriod(t))
        }
        (Intensity::Sa, Some(t)) => Ok(Some(t)),
        (_, Some(t)) => Err(RequestError::SaPeriodWithoutSa(t)),
        (_, None) => Ok(None),
    }
}

/// A fragility study's levels (each finite and > 0) and blocks: at least
/// one of each.
pub fn levels_and_blocks(levels: &[f64], blocks: usize) -> Result<(), RequestError> {
    if let Some(&v) = levels.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(RequestError::Level(v));
    }
    if levels.is_empty() || blocks == 0 {
        return Err(RequestError::NoLevelsOrBlocks);
    }
    Ok(())
}

/// The blocks of a fragility study of `base` under `im`: those `given`;
/// for a stack, its own bounding block when none is given. A stack has no
/// one slenderness, so the rocking intensity measures are refused for it.
pub fn fragility_blocks(base: &Scenario, given: Vec<BlockSize>, im: Intensity) -> Result<Vec<BlockSize>, RequestError> {
    match &base.stack {
        None if given.is_empty() => Err(RequestError::NoBlock),
        None => Ok(given),
        Some(_) if im.per_block() => Err(RequestError::StackIntensity),
        Some(blocks) if given.is_empty() => Ok(vec![stack_size(blocks)]),
        Some(_) => Ok(given),
    }
}

/// The θ/α whose exceedance is counted, finite and > 0.
pub fn threshold(theta_over_alpha: f64) -> Result<f64, RequestError> {
    if theta_over_alpha > 0.0 && theta_over_alpha.is_finite() {
        Ok(theta_over_alpha)
    } else {
        Err(RequestError::Threshold(theta_over_alpha))
    }
}

/// The intensity measure `im` of the record at `path` at scale 1, which
/// must be > 0 for any factor to scale the record to a level.
pub fn record_intensity(
    path: &std::path::Path,
    series: &Series,
    im: Intensity,
    sa_period_s: Option<f64>,
) -> Result<f64, RequestError> {
    let value = im.record_value(series, sa_period_s).unwrap_or(0.0);
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(RequestError::ZeroIntensity {
            file: path.display().to_string(),
            column: im.column(),
        })
    }
}

/// The unit named `text` (g, m/s2, cm/s2), given as `field`.
pub fn unit(field: RequestField, text: &str) -> Result<AccelUnit, RequestError> {
    AccelUnit::parse(text).ok_or_else(|| RequestError::Unit {
        field,
        text: text.to_string(),
    })
}

/// How the motion is scaled: by a factor or to a PGA (g), or neither
/// (played as read).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scaling {
    /// Factor on the motion.
    pub scale: Option<f64>,
    /// The PGA to scale the motion to, g.
    pub pga_g: Option<f64>,
}

impl Scaling {
    /// The factor on a motion whose PGA at scale 1 is `motion_pga_g`
    /// (1 when neither is given, as the motion was recorded).
    pub fn factor(&self, motion_pga_g: f64) -> Result<f64, RequestError> {
        if motion_pga_g <= 0.0 {
            return Err(RequestError::ZeroRecord);
        }
        match (self.scale, self.pga_g) {
            (Some(_), Some(_)) => Err(RequestError::ScaleAndPga),
            (Some(s), None) if !(s > 0.0 && s.is_finite()) => Err(RequestError::Scale(s)),
            (Some(s), None) => Ok(s),
            (None, Some(p)) if !(p > 0.0 && p.is_finite()) => Err(RequestError::Pga(p)),
            (None, Some(p)) => Ok(p / motion_pga_g),
            (None, None) => Ok(1.0),
        }
    }
}

/// An analytic pulse in physical units, as asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PulseRequest {
    /// Shape.
    pub shape: ShapeKind,
    /// Main cycles n of a type-C pulse (default 1: the simplest pulse).
    pub cycles: Option<u32>,
    /// Peak acceleration a_p, g.
    pub accel_g: Option<f64>,
    /// Period T_p = 2π/ω_p, s.
    pub period_s: Option<f64>,
}

/// A checked pulse: its drive and the numbers it was built from.
#[derive(Clone, Debug)]
pub struct Pulse {
    /// The motion.
    pub drive: Drive,
    /// Peak acceleration, g.
    pub a_p_g: f64,
    /// Period, s.
    pub period_s: f64,
    /// Main cycles.
    pub cycles: u32,
}

impl PulseRequest {
    /// The pulse, or the first input at fault (accel, period, cycles).
    pub fn checked(&self) -> Result<Pulse, RequestError> {
        let positive = |field: RequestField, v: Option<f64>| match v {
            Some(v) if v > 0.0 && v.is_finite() => Ok(v),
            Some(v) => Err(RequestError::PulseValue(field, v)),
            None => Err(RequestError::PulseMissing(field)),
        };
        let a_p_g = positive(RequestField::PulseAccel, self.accel_g)?;
        let period_s = positive(RequestField::PulsePeriod, self.period_s)?;
        let cycles = self.cycles.unwrap_or(1);
        if !(1..=MAX_TYPE_C_CYCLES).contains(&cycles) {
            return Err(RequestError::Cycles(cycles));
        }
        Ok(Pulse {
            drive: Drive::PhysicalPulse {
                shape: self.shape,
                cycles,
                a_p_g,
                omega_p: TAU / period_s,
            },
            a_p_g,
            period_s,
            cycles,
        })
    }
}

/// The values a search tries, `step, 2·step, …` up to `max`
/// ([`ladder`]), with errors naming `step_field` and `max_field`.
pub(crate) fn search_ladder(
    step_field: RequestField,
    step: f64,
    max_field: RequestField,
    max: f64,
) -> Result<Vec<f64>, RequestError> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(RequestError::SearchStep { step_field, step });
    }
    if !(max >= step && max.is_finite()) {
        return Err(RequestError::SearchMax {
            step_field,
            step,
            max_field,
            max,
        });
    }
    ladder(step, max).map_err(|_| RequestError::SearchSteps {
        step_field,
        step,
        max_field,
        max,
    })
}

#[cfg(test)]
mod tests {
    use super::super::rocking_spectrum::SizeAxis;
    use super::*;
    use crate::analysis::field::FieldNames;

    /// A surface that names every input `<name>` and a value `<name>:v`,
    /// so a test sees which input each message names and where.
    struct Angled;

    impl FieldNames<RequestField> for Angled {
        fn name(&self, field: RequestField) -> std::borrow::Cow<'static, str> {
            format!("<{}>", field.name()).into()
        }
        fn valued(&self, field: RequestField, value: &str) -> String {
            format!("<{}>:{value}", field.name())
        }
    }

    fn request(from_m: f64, to_m: f64, count: usize, b_over_h: Vec<f64>) -> SpectrumRequest {
        SpectrumRequest {
            axis: SizeAxis::HalfDiagonal,
            from_m,
            to_m,
            count,
            b_over_h,
            overturn: None,
        }
    }

    #[test]
    fn a_scale_and_a_pga_resolve_to_the_factor_a_hand_division_gives() {
        // A record of PGA 0.25 g scaled to 0.5 g is played twice as strong.
        let to_pga = Scaling {
            scale: None,
            pga_g: Some(0.5),
        };
        assert_eq!(to_pga.factor(0.25), Ok(0.5 / 0.25));
        let by_factor = Scaling {
            scale: Some(3.0),
            pga_g: None,
        };
        assert_eq!(by_factor.factor(0.25), Ok(3.0));
        assert_eq!(Scaling::default().factor(0.25), Ok(1.0));
        assert_eq!(Scaling::default().factor(0.0), Err(RequestError::ZeroRecord));
        let both = Scaling {
            scale: Some(1.0),
            pga_g: Some(1.0),
        };
        assert_eq!(
            both.factor(0.25).unwrap_err().render(&Angled),
            "<scale> and <pga>: give one"
        );
    }

    #[test]
    fn each_message_names_the_input_at_fault_through_the_surfaces_names() {
        let e = |r: SpectrumRequest| r.checked().unwrap_err().render(&Angled);
        assert_eq!(
            e(request(3.0, 0.2, 50, vec![0.25])),
            "<to_m>:0.2: below <from_m>:3; give from <= to"
        );
        assert_eq!(
            e(request(2.0, 2.0, 3, vec![0.25])),
            "<count>:3: <from_m> = <to_m> = 2 m gives 3 identical blocks; give <count>:1 or a <to_m> above <from_m>"
        );
        assert_eq!(
            e(request(1.0, 2.0, 5, vec![0.3, 0.2])),
            "<b_over_h>: values must increase (0.3 then 0.2)"
        );
        assert_eq!(
            e(request(1.0, 2.0, 5, vec![-1.0])),
            "<b_over_h>:-1: every ratio must be finite and > 0"
        );
        let mut search = request(1.0, 2.0, 5, vec![0.25]);
        search.overturn = Some(OverturnRequest {
            search_step: 0.5,
            search_max: 0.25,
            rel_tol: 1e-3,
        });
        assert_eq!(e(search), "<search_max>:0.25: must be finite and >= <search_step>:0.5");
        let pulse = PulseRequest {
            shape: ShapeKind::OneSine,
            cycles: None,
            accel_g: Some(0.3),
            period_s: None,
        };
        assert_eq!(
            pulse.checked().unwrap_err().render(&Angled),
            "<pulse_period>: required with <pulse>"
        );
    }

    #[test]
    fn a_checked_spectrum_holds_the_sizes_and_the_ladder_it_was_asked_for() {
        let mut r = request(0.5, 8.0, 5, vec![0.2, 0.25]);
        r.overturn = Some(OverturnRequest {
            search_step: 0.5,
            search_max: 2.0,
            rel_tol: 1e-3,
        });
        let b = r.checked().unwrap();
        // 0.5 · 16^(i/4): 0.5, 1, 2, 4, 8 m.
        let sizes = b.sizes.values();
        for (got, want) in sizes.iter().zip([0.5, 1.0, 2.0, 4.0, 8.0]) {
            assert!((got - want).abs() <= 1e-12 * want, "{sizes:?}");
        }
        assert_eq!(b.overturn.unwrap().ladder, vec![0.5, 1.0, 1.5, 2.0]);
        // A pulse of period 2 s is ω_p = π rad/s.
        let p = PulseRequest {
            shape: ShapeKind::OneSine,
            cycles: None,
            accel_g: Some(0.3),
            period_s: Some(2.0),
        }
        .checked()
        .unwrap();
        match p.drive {
            Drive::PhysicalPulse { omega_p, cycles, .. } => {
                assert!((omega_p - std::f64::consts::PI).abs() < 1e-15);
                assert_eq!(cycles, 1);
            }
            other => panic!("{other:?}"),
        }
    }
}
