//! The presets shipped in `assets/presets/`, compiled into the binary so
//! `--preset NAME` works from any directory.

/// `(name, TOML text)` of every preset.
pub const PRESETS: &[(&str, &str)] = &[
    ("default", include_str!("../../assets/presets/default.toml")),
    ("free-rocking", include_str!("../../assets/presets/free-rocking.toml")),
    ("period-one", include_str!("../../assets/presets/period-one.toml")),
    (
        "period-doubling",
        include_str!("../../assets/presets/period-doubling.toml"),
    ),
    ("sliding", include_str!("../../assets/presets/sliding.toml")),
    ("fig3", include_str!("../../assets/presets/fig3.toml")),
    ("fig4", include_str!("../../assets/presets/fig4.toml")),
    ("fig5", include_str!("../../assets/presets/fig5.toml")),
    ("fig6", include_str!("../../assets/presets/fig6.toml")),
    ("fig7", include_str!("../../assets/presets/fig7.toml")),
    ("fig8", include_str!("../../assets/presets/fig8.toml")),
    ("fig9", include_str!("../../assets/presets/fig9.toml")),
    ("fig10", include_str!("../../assets/presets/fig10.toml")),
    ("fig11", include_str!("../../assets/presets/fig11.toml")),
    ("fig12", include_str!("../../assets/presets/fig12.toml")),
    ("fig13", include_str!("../../assets/presets/fig13.toml")),
    ("fig14", include_str!("../../assets/presets/fig14.toml")),
    ("fig15", include_str!("../../assets/presets/fig15.toml")),
    ("fig16", include_str!("../../assets/presets/fig16.toml")),
    ("fig17", include_str!("../../assets/presets/fig17.toml")),
    ("fig18", include_str!("../../assets/presets/fig18.toml")),
    ("fig19", include_str!("../../assets/presets/fig19.toml")),
    ("kobe-rack", include_str!("../../assets/presets/kobe-rack.toml")),
    (
        "kobe-rack-5th-floor",
        include_str!("../../assets/presets/kobe-rack-5th-floor.toml"),
    ),
    (
        "elcentro-statue",
        include_str!("../../assets/presets/elcentro-statue.toml"),
    ),
    ("rocking-frame", include_str!("../../assets/presets/rocking-frame.toml")),
    ("tombstone", include_str!("../../assets/presets/tombstone.toml")),
    (
        "statue-on-pedestal",
        include_str!("../../assets/presets/statue-on-pedestal.toml"),
    ),
    (
        "stack-patterns",
        include_str!("../../assets/presets/stack-patterns.toml"),
    ),
];

/// The TOML text of preset `name`.
pub fn get(name: &str) -> Option<&'static str> {
    PRESETS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// What preset `text` is, in words: its header's first line without the
/// leading `# name: ` (`Chaotic rocking without sliding, Ω_h = …`).
pub fn title(text: &str) -> &str {
    let first = text.lines().next().unwrap_or("").trim_start_matches('#').trim();
    first.split_once(": ").map_or(first, |(_, t)| t)
}

/// All preset names.
pub fn names() -> Vec<&'static str> {
    PRESETS.iter().map(|(n, _)| *n).collect()
}
