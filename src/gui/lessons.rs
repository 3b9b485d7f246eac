//! What each preset teaches: the Presets menu's groups ("Phenomena", "The
//! paper's figures", "Engineering") and the sentence shown on screen above
//! the block when one is loaded, saying what to look at.
//!
//! The phenomena are the ones a lecture on chaos in impacting systems
//! walks through, each on a scene chosen (and measured, see each preset's
//! header in `assets/presets/`) to show it within a minute of play. A
//! figure's sentence says what the paper claims and what this model
//! shows on the same scene, where they differ too: a teacher should not
//! discover during the lecture that fig7 tumbles.

/// One phenomenon: a preset plus how the app should show it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lesson {
    /// The Presets ▸ Phenomena entry and the strip's title.
    pub title: &'static str,
    /// The preset it loads.
    pub preset: &'static str,
    /// What to look at, one or two sentences, shown on screen.
    pub look: &'static str,
    /// Ghost copies to start (0: none), and their spread in Θ (units of ψ).
    pub ghosts: (usize, f64),
    /// Playback speed, multiple of real time.
    pub speed: f64,
    /// Whether to draw the contact force and friction cone.
    pub forces: bool,
}

const fn lesson(title: &'static str, preset: &'static str, look: &'static str) -> Lesson {
    Lesson {
        title,
        preset,
        look,
        ghosts: (0, 1e-3),
        speed: 1.0,
        forces: false,
    }
}

/// Presets ▸ Phenomena, in lecture order.
pub const PHENOMENA: &[Lesson] = &[
    lesson(
        "Free rocking and impact accumulation",
        "free-rocking",
        "Released at half its tipping angle on a still base, the block keeps 91 % of its angular velocity at each impact, so every rock is shorter than the last: the impacts come faster and faster and the phase portrait spirals into the origin. 124 impacts, then rest after 11 s: infinitely many impacts in finite time.",
    ),
    lesson(
        "A period-1 orbit",
        "period-one",
        "After a short transient the block repeats exactly the same rocking in every forcing period: the Poincaré points (one per period) pile up on a single dot, and the phase portrait retraces one closed loop.",
    ),
    lesson(
        "Period doubling",
        "period-doubling",
        "Press on the A_v slider (under Excitation), hold Shift and drag slowly right in one go, 0.005 a point: the Poincaré dot splits into 2 at A_v ≈ 1.71, into 4 at ≈ 2.27 and into 8 at 2.32 (stop there; Shift+arrow keys step 0.005); from 2.33, chaos or a tumble: the road to chaos of the paper's Fig. 4.",
    ),
    Lesson {
        speed: 20.0,
        ..lesson(
            "Chaos",
            "default",
            "The motion never repeats: the Poincaré points, one per forcing period, never settle on a few dots but fill out a strange attractor (largest Lyapunov exponent +0.46 per τ). At 20× speed the picture fills in within a minute.",
        )
    },
    Lesson {
        ghosts: (20, 1e-6),
        ..lesson(
            "Sensitive dependence",
            "default",
            "20 ghost copies, each outlined in its own colour, start within a millionth of the block's tilt (ε = 1e-6) as the base first lifts it. For a while they hide behind it; then chaos amplifies the difference (by about e^0.46 per τ) and about a dozen τ later they rock out of step, in the scene and as coloured dots in the phase portrait: the butterfly effect, live.",
        )
    },
    Lesson {
        forces: true,
        ..lesson(
            "Sliding and slide-rock",
            "sliding",
            "On a slippery base (μ_k = 0.1) the block rocks (green), slides flat (cyan) and rocks while sliding (orange). Each slip goes the same way, so it walks across the table; the red arrow is the contact force, the yellow lines the friction cone it may not leave.",
        )
    },
    lesson(
        "Overturning in Kobe 1995",
        "kobe-rack",
        "A 0.6 × 2.0 m server rack on the 1995 Kobe record (JMA station, PGA 0.69 g): it rocks ever harder in the strong shaking and overturns at t = 6.9 s, the same answer as rocking --batch --preset kobe-rack.",
    ),
];

/// What the paper claims and what this model shows, per figure preset.
pub(crate) const FIGURES: &[(&str, &str)] = &[
    (
        "fig3",
        "The paper: a bifurcation diagram over A_v (the View menu's Bifurcation diagram draws it). This model, at this run's A_v = 1.0: the (1,2) orbit the paper reports for 0.7 < A_v < 1.25, two Poincaré dots.",
    ),
    (
        "fig4",
        "The paper: period doubling as A_v grows (View menu: Bifurcation diagram). This model: period 1 to A_v = 1.70, 2 to 2.26, 4 at 2.28–2.30, 8 at 2.32, chaos at 2.50; this run, A_v = 2.0, is on the period-2 orbit.",
    ),
    (
        "fig5",
        "The paper: a bifurcation diagram over A_v at Ω = 10 (View menu: Bifurcation diagram). This model, at this run's A_v = 1.0: a period-2 orbit, two Poincaré dots.",
    ),
    (
        "fig6",
        "The paper: a bifurcation diagram over A_v at Ω = 10, A_h = 3 (View menu: Bifurcation diagram). This model, at this run's A_v = 2.0: a period-2 orbit, two Poincaré dots.",
    ),
    (
        "fig7",
        "The paper: chaos that goes on (λ = 0.74). This model: a chaotic transient that ends in a tumble, at τ = 514 in a batch run (4.5 minutes at 1×; exactly when depends on round-off). Try 100× speed.",
    ),
    (
        "fig8",
        "The paper: chaos with λ = 1.02. This model: chaos that lasts (to τ = 4,000 at least, |Θ| up to 0.81). Try 20× speed to fill in the attractor.",
    ),
    (
        "fig9",
        "The paper: the bifurcation diagram with sliding (μ_s = 0.4; View menu: Bifurcation diagram). This model, at this run's A_v = 1.0: the block never slips and settles on fig3's (1,2) orbit.",
    ),
    (
        "fig10",
        "The paper: the bifurcation diagram with sliding (μ_s = 0.35; View menu: Bifurcation diagram). This model, at this run's A_v = 1.0: the block never slips and settles on fig3's (1,2) orbit.",
    ),
    (
        "fig11",
        "The paper: chaotic rocking with sliding. This model: the run from rest tumbles at τ = 188 (1.7 minutes at 1×). Try 20× speed.",
    ),
    (
        "fig12",
        "The paper: chaos with sliding, λ = 0.71, |Θ| up to about 0.75. This model: a chaotic transient with slide-rock (|Θ| up to 0.90) that settles on a period-4 orbit with slip and stick, four Poincaré dots.",
    ),
    (
        "fig13",
        "The paper: chaos with sliding, λ = 1.34, |Θ| up to about 0.4. This model: a chaotic transient that tumbles at τ = 555 (4.9 minutes at 1×). Try 100× speed.",
    ),
    (
        "fig14",
        "The paper: the bifurcation diagram with sliding at Ω = 10 (View menu: Bifurcation diagram). This model, at this run's A_v = 2.0: a period-2 orbit without slip.",
    ),
    (
        "fig15",
        "The paper: the bifurcation diagram with sliding at Ω = 10, μ_s = 0.35 (View menu: Bifurcation diagram). This model, at this run's A_v = 2.0: a period-2 orbit with slide-rock in every period.",
    ),
    (
        "fig16",
        "The paper: chaotic rocking with sliding. This model: a period-2 orbit without slip (two Poincaré dots).",
    ),
    (
        "fig17",
        "The paper: chaotic rocking with sliding (the caption's μ_s = 3.35 is a misprint for 0.35). This model: a period-2 orbit with slide-rock in every period.",
    ),
    (
        "fig18",
        "The paper: chaos with sliding, λ = 1.91. This model: a period-2 orbit with slide-rock after the transient.",
    ),
    (
        "fig19",
        "The paper: chaos with sliding, λ = 1.76. This model: a period-4 orbit with slide-rock after the transient (beside a chaotic one, docs/analysis.md).",
    ),
];

/// Presets ▸ Engineering: real records in physical units.
pub(crate) const ENGINEERING: &[&str] = &["kobe-rack", "elcentro-statue"];

/// Presets ▸ Stacks of blocks: the presets with a `[[stack]]`.
pub(crate) const STACKS: &[&str] = &["tombstone", "statue-on-pedestal", "stack-patterns"];

/// The text shown above the block for a loaded scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Note {
    /// Bold, first.
    pub title: String,
    /// What to look at.
    pub text: String,
}

impl Note {
    /// The note of `lesson`.
    pub(crate) fn of_lesson(lesson: &Lesson) -> Self {
        Self {
            title: lesson.title.to_string(),
            text: lesson.look.to_string(),
        }
    }

    /// The note for preset `name` loaded by name (command line or menu):
    /// its phenomenon's (the first that uses it) or its figure's; `None`
    /// for a preset with nothing to say.
    pub fn of_preset(name: &str) -> Option<Self> {
        if let Some(l) = lesson_of_preset(name) {
            return Some(Self::of_lesson(l));
        }
        FIGURES.iter().find(|(n, _)| *n == name).map(|(n, text)| Self {
            title: format!("{n}: {}", figure_title(n)),
            text: (*text).to_string(),
        })
    }
}

/// The phenomenon whose note preset `name` shows when loaded by name: the
/// first that uses it.
pub(crate) fn lesson_of_preset(name: &str) -> Option<&'static Lesson> {
    PHENOMENA.iter().find(|l| l.preset == name)
}

/// A preset's title: its header's first line without the name, cut before
/// the first comma-separated parameter list (`Chaotic rocking without
/// sliding`).
pub fn figure_title(name: &str) -> &'static str {
    let Some(text) = crate::io::presets::get(name) else {
        return "";
    };
    let title = crate::io::presets::title(text);
    title.split(',').next().unwrap_or(title).trim()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_lesson_and_figure_names_a_shipped_preset() {
        for l in PHENOMENA {
            assert!(crate::io::presets::get(l.preset).is_some(), "{}", l.preset);
            assert!(!l.look.is_empty());
        }
        for name in STACKS {
            let text = crate::io::presets::get(name).expect("a shipped preset");
            assert!(text.contains("[[stack]]"), "{name} is a stack");
        }
        for (name, text) in FIGURES {
            assert!(crate::io::presets::get(name).is_some(), "{name}");
            assert!(text.starts_with("The paper"), "{name}");
        }
        // Every figure preset has its note.
        for name in crate::io::presets::names().into_iter().filter(|n| n.starts_with("fig")) {
            assert!(FIGURES.iter().any(|(n, _)| *n == name), "{name} has no note");
        }
    }

    #[test]
    fn a_preset_loaded_by_name_gets_its_note() {
        let n = Note::of_preset("period-doubling").unwrap();
        assert_eq!(n.title, "Period doubling");
        assert!(n.text.contains("hold Shift and drag slowly right"));
        let f = Note::of_preset("fig7").unwrap();
        assert_eq!(f.title, "fig7: Chaotic rocking without sliding");
        assert!(f.text.contains("tumble"));
        assert!(Note::of_preset("elcentro-statue").is_none());
    }
}
