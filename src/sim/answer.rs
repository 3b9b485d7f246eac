//! The engineer's answer to a run, in physical units: did it overturn, when,
//! how far did it rotate, slide and lift, how did the run end.
//!
//! Everything here is a conversion of a [`RunResult`] with the scenario's
//! geometry (t = τ/p, θ = ψΘ, x = R·X); nothing is recomputed.

use serde::Serialize;

pub use super::end_state::EndState;
use super::run::RunResult;
use super::scenario::{ExcitationKind, LawKind, Scenario};
use crate::model::excitation::record::GroundPeaks;
use crate::model::excitation::{Excitation, FloorPeaks};

/// Seconds spent in each grounded mode.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ModeSeconds {
    /// Flat and stuck.
    pub rest: f64,
    /// Flat and sliding.
    pub slide: f64,
    /// Rocking on a sticking corner.
    pub rock: f64,
    /// Rocking on a slipping corner.
    #[serde(rename = "slide-rock")]
    pub slide_rock: f64,
}

/// One record's name and peaks after its unit and scale.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RecordPeaks {
    /// The file.
    pub file: String,
    /// The unit it was read in.
    pub unit: &'static str,
    /// The scale factor applied.
    pub scale: f64,
    /// Its peaks, scaled.
    #[serde(flatten)]
    pub peaks: GroundPeaks,
    /// Duration, s (time of its last sample).
    pub duration_s: f64,
}

impl RecordPeaks {
    /// The peaks of record `r` of scenario `s` at `scale`; `None` unless `s`
    /// runs a record.
    pub(crate) fn of(s: &Scenario, r: &Option<super::scenario::Record>, scale: f64) -> Option<Self> {
        r.as_ref()
            .filter(|_| s.excitation.kind == ExcitationKind::Record)
            .map(|r| RecordPeaks {
                file: r.path.display().to_string(),
                unit: r.unit.name(),
                scale,
                peaks: r.series.peaks(scale),
                duration_s: r.series.duration_s(),
            })
    }
}

/// The peaks of the floor `s` stands on over the run's planned length;
/// `None` without `[floor]`.
pub(crate) fn floor_peaks(s: &Scenario) -> Option<FloorPeaks> {
    match s.excitation() {
        Ok(Excitation::Floor(f)) => Some(f.peaks(s.tau_end())),
        _ => None,
    }
}

/// The run in physical units (`summary.json`'s `physical`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Physical {
    /// Whether the block overturned.
    pub overturned: bool,
    /// When it overturned, s.
    pub t_overturn_s: Option<f64>,
    /// Largest |θ|, rad.
    pub max_rotation_rad: f64,
    /// Largest |θ|, degrees.
    pub max_rotation_deg: f64,
    /// Largest |θ| / α (α = ψ, the slenderness angle): 1 is the overturning
    /// angle of a block at rest.
    pub max_rotation_over_alpha: f64,
    /// Largest |sliding displacement| relative to the base, m
    /// (docs/model.md §1.7).
    pub max_sliding_m: f64,
    /// Sliding displacement at the end, m (signed, + to the right).
    pub residual_sliding_m: f64,
    /// Largest height of the lifted corner, m.
    pub max_uplift_m: f64,
    /// Impacts.
    pub impacts: u64,
    /// Time in each mode, s.
    pub mode_time_s: ModeSeconds,
    /// When the run ended, s.
    pub t_end_s: f64,
    /// For a block at rest at the end: when it last came to rest, s (0 if
    /// it never moved).
    pub t_rest_s: Option<f64>,
    /// How it ended.
    pub end_state: EndState,
    /// For a record: whether the run's end was at or after the record's
    /// end (`false`: the user cut it short, so "rest" or "moving" says
    /// nothing about the rest of the record). `None` for other kinds.
    pub record_complete: Option<bool>,
    /// The horizontal record, for record runs.
    pub record_h: Option<RecordPeaks>,
    /// The vertical record, if any.
    pub record_v: Option<RecordPeaks>,
    /// The floor the block stood on (`[floor]`): its peak horizontal
    /// acceleration and velocity over continuous time, for the scaled
    /// motion the block felt, from τ = 0 to the run's planned end (the
    /// whole record and its tail). `None` without `[floor]`.
    pub floor: Option<FloorPeaks>,
    /// The impact law used (`impact.law`'s name), so that an answer never
    /// hides which law produced it.
    pub impact_law: &'static str,
    /// Its angular-velocity ratio r for the laws that have one (`housner`,
    /// `corner-momentum` without slip, `ratio`); `None` for `impulse`.
    pub impact_r: Option<f64>,
    /// Static friction coefficient at the base; `None`: no sliding (μ = ∞).
    pub friction_static: Option<f64>,
    /// Kinetic friction coefficient at the base; `None`: no sliding.
    pub friction_kinetic: Option<f64>,
    /// Each body's answer, bottom to top (a frame's columns, then its
    /// beam); absent for the single block, whose answer is the above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bodies: Option<Vec<Body>>,
    /// What the one-line answer calls the structure when it has several
    /// bodies (`frame`); `None` for the single block.
    #[serde(skip)]
    pub subject: Option<&'static str>,
}

/// One body's answer (`physical.bodies`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Body {
    /// What it is: `column 1`, …, `beam`.
    pub name: String,
    /// Largest |rotation|, degrees.
    pub max_rotation_deg: f64,
    /// Whether it overturned.
    pub overturned: bool,
    /// Largest |sliding displacement| relative to what it stands on, m.
    pub max_sliding_m: f64,
    /// Largest rise, m: a column's lifted corner, the beam's whole body.
    pub max_uplift_m: f64,
}

/// A frame's bodies: its columns, all rocking alike, then its beam, which
/// translates on the columns' top corners and rises by
/// 2R(cos(ψ − |θ|) − cos ψ) (docs/model.md §16.1).
fn frame_bodies(s: &Scenario, res: &RunResult, overturned: bool) -> Option<Vec<Body>> {
    let frame = s.frame.as_ref()?;
    let geo = s.geometry();
    let theta = geo.psi * res.max_abs_theta;
    let mut bodies: Vec<Body> = (1..=frame.columns)
        .map(|k| Body {
            name: format!("column {k}"),
            max_rotation_deg: theta.to_degrees(),
            overturned,
            max_sliding_m: res.max_abs_sliding * geo.r,
            max_uplift_m: geo.uplift_m(res.max_abs_theta),
        })
        .collect();
    // Past |θ| = ψ the frame has collapsed; the rise is taken at ψ.
    let tilt = theta.min(geo.psi);
    bodies.push(Body {
        name: "beam".to_string(),
        max_rotation_deg: 0.0,
        overturned,
        max_sliding_m: res.max_abs_sliding * geo.r,
        max_uplift_m: 2.0 * geo.r * ((geo.psi - tilt).cos() - geo.cos_psi),
    });
    Some(bodies)
}

impl Physical {
    /// The answer of run `res` of scenario `s`.
    pub fn of(s: &Scenario, res: &RunResult) -> Self {
        let geo = s.geometry();
        let sec = |tau: f64| tau / geo.p;
        let end_state = res.end_state();
        let theta = geo.psi * res.max_abs_theta;
        let [rest, slide, rock, slide_rock] = res.mode_time.map(sec);
        Physical {
            overturned: end_state == EndState::Overturned,
            t_overturn_s: res.tumble_tau.map(sec),
            max_rotation_rad: theta,
            max_rotation_deg: theta.to_degrees(),
            max_rotation_over_alpha: res.max_abs_theta,
            max_sliding_m: res.max_abs_sliding * geo.r,
            residual_sliding_m: res.final_sliding * geo.r,
            max_uplift_m: geo.uplift_m(res.max_abs_theta),
            impacts: res.tally.impacts,
            mode_time_s: ModeSeconds {
                rest,
                slide,
                rock,
                slide_rock,
            },
            t_end_s: sec(res.tau_end),
            t_rest_s: (end_state == EndState::Rest).then(|| res.tallies.last_rest_tau.map_or(0.0, sec)),
            end_state,
            record_complete: s.record_complete(),
            record_h: RecordPeaks::of(s, &s.excitation.record_h, s.excitation.scale_h),
            record_v: RecordPeaks::of(s, &s.excitation.record_v, s.excitation.scale_v),
            floor: floor_peaks(s),
            impact_law: s.impact.law.name(),
            impact_r: (s.impact.law != LawKind::Impulse).then(|| s.impact_r()),
            friction_static: s.block.mu_s.is_finite().then_some(s.block.mu_s),
            friction_kinetic: s.block.mu_s.is_finite().then(|| s.block.kinetic()),
            bodies: frame_bodies(s, res, end_state == EndState::Overturned),
            subject: s.frame.is_some().then_some("frame"),
        }
    }

    /// The contact the answer holds for, in words:
    /// `Housner impact r = 0.899, friction μ = 0.5`.
    pub fn contact(&self) -> String {
        let law = match (self.impact_law, self.impact_r) {
            ("housner" | "corner-momentum", Some(r)) if self.subject == Some("frame") => {
                format!("frame impact r = {r:.3} (docs/model.md §16.3)")
            }
            ("housner", Some(r)) => format!("Housner impact r = {r:.3}"),
            ("stack", _) => "impacts with each new pivot stuck (docs/model.md §18.5)".to_string(),
            (law, Some(r)) => format!("{law} impact r = {r:.3}"),
            (law, None) => format!("{law} impact"),
        };
        let friction = match (self.friction_static, self.friction_kinetic) {
            (Some(s), Some(k)) if s == k => format!("friction μ = {s}"),
            (Some(s), Some(k)) => format!("friction μ_s = {s}, μ_k = {k}"),
            _ => "no friction limit (cannot slide)".to_string(),
        };
        format!("{law}, {friction}")
    }

    /// The answer in one line, as an engineer would say it, then the
    /// contact it holds for ([`Physical::contact`]):
    /// `overturned at t = 6.42 s (kobe-1995.dat, PGA 0.55 g); Housner impact r = 0.893, no friction limit (cannot slide)` or
    /// `survived: peak rotation 12.3° (0.71 α), sliding 17 mm, at rest at t = 31.2 s; …`.
    pub fn line(&self) -> String {
        format!("{}; {}", self.outcome_line(), self.contact())
    }

    /// The answer without the contact.
    fn outcome_line(&self) -> String {
        let input = match &self.record_h {
            Some(r) => {
                let name = super::scenario::record_file_name(&r.file);
                match &self.floor {
                    Some(f) => format!(" ({name}, PGA {:.2} g, floor PGA {:.2} g)", r.peaks.pga_g, f.pga_g),
                    None => format!(" ({name}, PGA {:.2} g)", r.peaks.pga_g),
                }
            }
            None => String::new(),
        };
        let cut = if self.record_complete == Some(false) {
            " (the run ended before the record did: run.t_end is shorter than the record)"
        } else {
            ""
        };
        let rocking = if self.max_rotation_rad > 0.0 {
            format!(
                "peak rotation {:.2}° ({:.2} α), uplift {}",
                self.max_rotation_deg,
                self.max_rotation_over_alpha,
                length(self.max_uplift_m)
            )
        } else {
            "no rocking".to_string()
        };
        // Below a nanometre a sliding displacement is round-off of a block
        // that never slipped.
        let sliding = if self.max_sliding_m > 1e-9 {
            format!(
                "sliding {} ({} at the end)",
                length(self.max_sliding_m),
                length(self.residual_sliding_m.abs())
            )
        } else {
            "no sliding".to_string()
        };
        let motion = format!("{rocking}, {sliding}");
        let subject = self.subject.map_or(String::new(), |s| format!("{s} "));
        match self.end_state {
            EndState::Overturned => format!(
                "{subject}overturned at t = {:.2} s{input}",
                self.t_overturn_s.unwrap_or(self.t_end_s)
            ),
            EndState::Flight => format!(
                "{}left the ground (flight) at t = {:.2} s{input}: {motion}; the model stops there",
                self.subject
                    .filter(|s| s.ends_with("block"))
                    .map_or(String::new(), |s| format!("{s} ")),
                self.t_end_s
            ),
            EndState::Rest => format!(
                "survived: {motion}; at rest from t = {:.2} s{input}{cut}",
                self.t_rest_s.unwrap_or(self.t_end_s)
            ),
            EndState::Moving => format!(
                "still moving at t = {:.2} s, the end of the run (not known to survive): {motion}{input}{cut}",
                self.t_end_s
            ),
        }
    }
}

/// A length for people: mm with two decimals below 1 mm, whole mm below
/// 1 m, else m with two decimals.
fn length(m: f64) -> String {
    if m.abs() < 1e-3 {
        format!("{:.2} mm", m * 1e3)
    } else if m.abs() < 1.0 {
        format!("{:.0} mm", m * 1e3)
    } else {
        format!("{m:.2} m")
    }
}
