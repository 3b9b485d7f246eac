//! What the paper says about each of its Figs. 3–19: the caption, the
//! statements of its section 4 about the figure, and the numbers it quotes
//! (mode ranges, Lyapunov exponents, maximum amplitudes).
//!
//! These are the paper's claims, transcribed once here so that the report
//! can set each of our figures beside them. Nothing is computed here. Where
//! the paper is ambiguous, the field says so (e.g. Fig. 10's example, whose
//! A_v the paper does not give).

/// The two kinds of figure in the paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureKind {
    /// A bifurcation diagram: a sweep of A_v from 0 to 3 in steps of 0.02,
    /// Poincaré points of Θ after τ = 600 (the paper's steps 150,000 to
    /// 200,000 of 0.004), blank where the block tumbles.
    Bifurcation,
    /// A response example: (a) time history, (b) power spectrum, (c)
    /// Poincaré map, and sometimes a quoted Lyapunov exponent.
    Response,
}

/// The response the paper reports over a range of A_v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expect {
    /// A periodic response of period k, the paper's (1,k) mode.
    Period(u32),
    /// "Higher order rocking periodic and chaotic responses coexist": a
    /// period above 2, quasiperiodic or chaotic (not tumbled, not period 1
    /// or 2).
    HigherOrChaotic,
    /// A chaotic response.
    Chaotic,
}

impl Expect {
    /// How the paper's wording reads in the report.
    pub fn label(self) -> String {
        match self {
            Expect::Period(k) => format!("periodic (1,{k})"),
            Expect::HigherOrChaotic => "higher-order periodic and chaotic, coexisting".to_string(),
            Expect::Chaotic => "chaotic".to_string(),
        }
    }
}

/// A range of A_v over which the paper reports one response.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperRange {
    /// First A_v ("from about …").
    pub from: f64,
    /// Last A_v ("to about …").
    pub to: f64,
    /// The response the paper reports.
    pub expect: Expect,
}

/// One figure of the paper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperFigure {
    /// Figure number, 3 … 19.
    pub number: u32,
    /// The preset holding its parameters (`assets/presets/figN.toml`).
    pub preset: &'static str,
    /// Bifurcation diagram or response example.
    pub kind: FigureKind,
    /// The paper's caption.
    pub caption: &'static str,
    /// The paper's statements about this figure (section 4), quoted.
    pub statements: &'static [&'static str],
    /// Mode ranges the paper gives (bifurcation diagrams only).
    pub ranges: &'static [PaperRange],
    /// The Lyapunov exponent the paper quotes (its units are not stated).
    pub lyapunov: Option<f64>,
    /// The maximum |Θ| the paper quotes ("about").
    pub max_amplitude: Option<f64>,
    /// Whether the paper calls the response chaotic (`None`: not said).
    pub chaotic: Option<bool>,
}

const NO_RANGES: &[PaperRange] = &[];

/// The fields a figure's entry leaves out when the paper quotes no number
/// for it: no ranges, no exponent, no amplitude, no word on chaos. Each
/// entry sets its number, preset, kind, caption and statements.
const NOT_QUOTED: PaperFigure = PaperFigure {
    number: 0,
    preset: "",
    kind: FigureKind::Bifurcation,
    caption: "",
    statements: &[],
    ranges: NO_RANGES,
    lyapunov: None,
    max_amplitude: None,
    chaotic: None,
};

/// What the paper says of Figs. 14 and 15 together: the two friction
/// levels of one comparison.
const LOWER_FRICTION: &[&str] = &[
    "\"The chaotic response region is expanded in these bifurcation diagrams by lowering its frictional coefficient.\"",
    "\"the chaotic response region is widely extended at higher excitation frequencies and becomes wider in the case with sliding than in the case without sliding.\"",
];

/// Every figure of the paper's section 4, in order.
pub(crate) const FIGURES: [PaperFigure; 17] = [
    PaperFigure {
        number: 3,
        preset: "fig3",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 0 ~ 3)",
        statements: &[
            "\"Fig. 3 shows the periodic response of the (1,1) mode from 0 to about 0.7, of vertical amplitude. Periodic responses of the (1,2) mode from about 0.7 to 1.25 and the higher order rocking periodic and chaotic responses coexist in the region over the normalized vertical amplitude of 1.25.\"",
            "\"the two diagrams of Figs. 3 and 5 show intermittency bifurcation.\"",
        ],
        ranges: &[
            PaperRange {
                from: 0.0,
                to: 0.7,
                expect: Expect::Period(1),
            },
            PaperRange {
                from: 0.7,
                to: 1.25,
                expect: Expect::Period(2),
            },
            PaperRange {
                from: 1.25,
                to: 3.0,
                expect: Expect::HigherOrChaotic,
            },
        ],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 4,
        preset: "fig4",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 8, A_h = 3.0, A_v = 0 ~ 3)",
        statements: &[
            "\"Fig. 4 shows the periodic response of the (1,1) mode, in the rocking response region, from 0 to about a vertical amplitude 1.7, and the periodic response of the (1,2) mode from about 1.7 to 2.25, and the periodic response of the (1,4) mode from about 2.25 to 2.3 and a chaotic response after 2.3.\"",
            "\"In the case of Fig. 4 and Fig. 6, the diagrams apparently show a periodic-double bifurcation for a change of vertical amplitude\"",
        ],
        ranges: &[
            PaperRange {
                from: 0.0,
                to: 1.7,
                expect: Expect::Period(1),
            },
            PaperRange {
                from: 1.7,
                to: 2.25,
                expect: Expect::Period(2),
            },
            PaperRange {
                from: 2.25,
                to: 2.3,
                expect: Expect::Period(4),
            },
            PaperRange {
                from: 2.3,
                to: 3.0,
                expect: Expect::Chaotic,
            },
        ],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 5,
        preset: "fig5",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 10, A_h = 2.0, A_v = 0 ~ 3)",
        statements: &[
            "\"Figs. 5~6 show the same tendency as Figs. 3~4, but the region of the periodic response is wider and the region of tumbling narrower.\"",
            "\"the two diagrams of Figs. 3 and 5 show intermittency bifurcation.\"",
        ],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 6,
        preset: "fig6",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 0 ~ 3)",
        statements: &[
            "\"Figs. 5~6 show the same tendency as Figs. 3~4, but the region of the periodic response is wider and the region of tumbling narrower.\"",
            "\"In the case of Fig. 4 and Fig. 6, the diagrams apparently show a periodic-double bifurcation\"",
        ],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 7,
        preset: "fig7",
        kind: FigureKind::Response,
        caption: "Rocking response without sliding (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 2.5)",
        statements: &[
            "\"Examples of chaotic responses in the bifurcation diagram of Figs. 3 and 6 are shown in Figs. 7~8\"",
            "\"The maximum amplitude of the rocking response when Ω_h = Ω_v = 8 is larger than for Ω_h = Ω_v = 10 although the excitation amplitude in the horizontal direction A_h is smaller.\"",
            "\"the chaotic attractor is composed of multiple limit cycles, which are characterized by a unique shape, which is 'asymmetrical' to zero angular displacement and 'whirled' in the counter clockwise direction.\"",
            "\"The Lyapunov exponents for these chaotic responses were 0.74 and 1.02, respectively.\"",
        ],
        lyapunov: Some(0.74),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 8,
        preset: "fig8",
        kind: FigureKind::Response,
        caption: "Rocking response without sliding (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 2.5)",
        statements: &[
            "\"Examples of chaotic responses in the bifurcation diagram of Figs. 3 and 6 are shown in Figs. 7~8\"",
            "\"The maximum amplitude of the rocking response when Ω_h = Ω_v = 8 is larger than for Ω_h = Ω_v = 10\"",
            "\"The Lyapunov exponents for these chaotic responses were 0.74 and 1.02, respectively.\"",
        ],
        lyapunov: Some(1.02),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 9,
        preset: "fig9",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 0 ~ 3, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: &[
            "\"The rocking behavior is affected by the sliding motion in the horizontal direction, and the distribution of the rocking response is dependent on the frictional coefficient.\"",
            "Conclusion (2): \"There is a case in which it becomes a chaotic response by sliding, even in the region showing a periodic response in the case of no sliding. That is, the chaotic response region gets wider when sliding occurs.\"",
        ],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 10,
        preset: "fig10",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 0 ~ 3, μ_s = μ̄_s = 0.35, μ_k = μ̄_k = 0.3)",
        statements: &[
            "\"An example is shown in Fig. 10, in this case, the Lyapunov exponent was 0.51.\" (the paper does not say for which A_v)",
            "Conclusion (3): \"The periodic response region narrows with the lowering of the frictional force and the chaotic response region is expanded.\"",
        ],
        lyapunov: Some(0.51),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 11,
        preset: "fig11",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 2.0, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: &[
            "\"We next examined the two rocking responses to investigate the effect of sliding on rocking response, which shows chaotic behavior even without sliding. Figure 11 shows an example for Ω_h = Ω_v = 8, A_h = 2, and A_v = 2.0\"",
        ],
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 12,
        preset: "fig12",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 2.5, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: &[
            "\"Figures. 7, 12~13 show responses for the identical excitation condition, but with a different frictional coefficient, the attractor shape becomes smaller on lowering the frictional coefficient, and it is shown that the maximum amplitude of the rocking response is lowered.\"",
            "\"Though it had reached a tumbling level in the case of Fig. 6, the maximum amplitude was about 0.75 in Fig. 12, and this became about 0.4 in Fig. 13.\" (\"Fig. 6\" presumably means Fig. 7, the same excitation without sliding)",
            "\"The Lyapunov exponents for the rocking response of Figs. 12~13 were 0.71 and 1.34, respectively.\"",
        ],
        lyapunov: Some(0.71),
        max_amplitude: Some(0.75),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 13,
        preset: "fig13",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 8, A_h = 2.0, A_v = 2.5, μ_s = μ̄_s = 0.35, μ_k = μ̄_k = 0.3)",
        statements: &[
            "\"the maximum amplitude was about 0.75 in Fig. 12, and this became about 0.4 in Fig. 13.\"",
            "\"Lowering of the frictional force between the block and the base, and this increasing energy dissipation by sliding, produced a smaller rocking response attractor shape and a smaller rocking response maximum amplitude\"",
            "\"The Lyapunov exponents for the rocking response of Figs. 12~13 were 0.71 and 1.34, respectively.\"",
        ],
        lyapunov: Some(1.34),
        max_amplitude: Some(0.4),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 14,
        preset: "fig14",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 0 ~ 3, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: LOWER_FRICTION,
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 15,
        preset: "fig15",
        kind: FigureKind::Bifurcation,
        caption: "Bifurcation diagram for rocking responses (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 0 ~ 3, μ_s = μ̄_s = 0.35, μ_k = μ̄_k = 0.3)",
        statements: LOWER_FRICTION,
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 16,
        preset: "fig16",
        kind: FigureKind::Response,
        caption: "Rocking response (with sliding) (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 2.0, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: &["\"The examples of rocking response in Fig. 14 are shown in Figs. 16~17.\""],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 17,
        preset: "fig17",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 2.0, μ_s = μ̄_s = 3.35 [sic: 0.35], μ_k = μ̄_k = 0.3)",
        statements: &["\"The examples of rocking response in Fig. 14 are shown in Figs. 16~17.\""],
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 18,
        preset: "fig18",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 10, A_h = 2.5, A_v = 2.0, μ_s = μ̄_s = 0.4, μ_k = μ̄_k = 0.35)",
        statements: &[
            "\"when the excitation amplitude is comparatively large at A_h = 3, the shape of the attractor is comparable to the case without sliding, as shown in Figs. 18~19.\"",
            "\"when the horizontal displacement produced by sliding is large, and it takes a form which inclines toward the negative direction for the rotational velocity axis. The Lyapunov exponents for these responses were 1.91 and 1.76. Lyapunov exponent increases more so in the presence of sliding.\"",
        ],
        lyapunov: Some(1.91),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
    PaperFigure {
        number: 19,
        preset: "fig19",
        kind: FigureKind::Response,
        caption: "Rocking response with sliding (Ω_h = Ω_v = 10, A_h = 3.0, A_v = 2.5, μ_s = μ̄_s = 0.35, μ_k = μ̄_k = 0.3)",
        statements: &[
            "\"The Lyapunov exponents for these responses were 1.91 and 1.76. Lyapunov exponent increases more so in the presence of sliding. It follows that the sliding motion intensifies the chaoticity of the rocking response.\"",
        ],
        lyapunov: Some(1.76),
        chaotic: Some(true),
        ..NOT_QUOTED
    },
];

/// The figure numbered `number`, if the paper has it.
pub fn figure(number: u32) -> Option<&'static PaperFigure> {
    FIGURES.iter().find(|f| f.number == number)
}

/// Parses a figure name as written on the command line: `fig4`, `fig04`,
/// `4` (case-insensitive); `None` if it is not one of Figs. 3–19.
pub(crate) fn parse_figure(name: &str) -> Option<u32> {
    let t = name.trim().to_ascii_lowercase();
    let digits = t.strip_prefix("fig").unwrap_or(&t);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let n: u32 = digits.parse().ok()?;
    figure(n).map(|f| f.number)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_figure_has_its_preset_and_ranges_are_ordered() {
        for f in &FIGURES {
            assert_eq!(f.preset, format!("fig{}", f.number));
            assert!(crate::io::presets::get(f.preset).is_some(), "{}", f.preset);
            assert!(f.ranges.windows(2).all(|w| w[0].to <= w[1].from + 1e-12));
            assert!(!f.statements.is_empty());
        }
        assert_eq!(
            FIGURES.iter().map(|f| f.number).collect::<Vec<_>>(),
            (3..=19).collect::<Vec<_>>()
        );
    }

    #[test]
    fn figure_names_parse() {
        assert_eq!(parse_figure("fig4"), Some(4));
        assert_eq!(parse_figure("FIG04"), Some(4));
        assert_eq!(parse_figure("19"), Some(19));
        assert_eq!(parse_figure("fig2"), None);
        assert_eq!(parse_figure("fig"), None);
        assert_eq!(parse_figure("fig-4"), None);
    }
}
