//! What the app remembers between sessions: the presentation scale and
//! whether the lecture presentation is on. Kept
//! in a small TOML file of its own (`$XDG_CONFIG_HOME/rocking/app.toml`,
//! else `~/.config/rocking/app.toml`) rather than eframe's persistence,
//! which would also restore panel sizes and plot zooms a lecturer does not
//! expect to come back.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// Smallest and largest presentation scale (egui's zoom factor): below
/// 0.75 text is unreadable even on a laptop; above 3 a 1280 × 800
/// projector has no room left for the block.
pub(crate) const SCALE_RANGE: (f32, f32) = (0.75, 3.0);

/// The scales the View menu offers where the window holds them
/// ([`max_scale`]; the keyboard steps between any up to that).
pub const SCALES: [f32; 6] = [1.0, 1.25, 1.5, 1.75, 2.0, 2.5];

/// The smallest window, in points, that holds every panel beside the
/// block scene with readable plots: at a larger scale the points left
/// (window pixels / scale) are too few, and panels would cover each other
/// or squeeze the plots to a few ticks. 800 × 500 is 1280 × 800 at 160 %
/// and 1920 × 1080 at 216 %.
pub(crate) const MIN_LAYOUT_POINTS: [f32; 2] = [800.0, 500.0];

/// The same in the lecture presentation, whose text is a third larger:
/// 1000 × 625 is 1280 × 800 at 128 % and 1920 × 1080 at 173 %.
pub(crate) const LECTURE_LAYOUT_POINTS: [f32; 2] = [1000.0, 625.0];

/// The largest presentation scale a window of `window` logical pixels (its
/// size in points at scale 1) holds, in the lecture presentation if
/// `lecture`: [`MIN_LAYOUT_POINTS`] (or [`LECTURE_LAYOUT_POINTS`]) still
/// fit, and within [`SCALE_RANGE`].
pub fn max_scale(window: [f32; 2], lecture: bool) -> f32 {
    let min = if lecture {
        LECTURE_LAYOUT_POINTS
    } else {
        MIN_LAYOUT_POINTS
    };
    let fit = (window[0] / min[0]).min(window[1] / min[1]);
    if fit.is_finite() {
        fit.clamp(SCALE_RANGE.0, SCALE_RANGE.1)
    } else {
        SCALE_RANGE.1
    }
}

/// The [`SCALES`] a window of `window` logical pixels holds (in the
/// lecture presentation if `lecture`): what the View menu offers.
pub fn offered(window: [f32; 2], lecture: bool) -> Vec<f32> {
    let top = max_scale(window, lecture);
    SCALES.iter().copied().filter(|&s| s <= top + 1e-4).collect()
}

/// The remembered settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Prefs {
    /// Presentation scale: how much all text and lines are enlarged. 1 is
    /// egui's default size.
    pub scale: f32,
    /// The lecture presentation: larger text and plot numbers (20 px), the
    /// plots as tabs so each keeps its size. Off by default (a file from
    /// before it existed reads as off).
    #[serde(default)]
    pub lecture: bool,
}

impl Default for Prefs {
    fn default() -> Self {
        Self {
            scale: 1.0,
            lecture: false,
        }
    }
}

impl Prefs {
    /// `scale` clamped to [`SCALE_RANGE`] (NaN: 1).
    pub(crate) fn clamp_scale(scale: f32) -> f32 {
        if scale.is_finite() {
            scale.clamp(SCALE_RANGE.0, SCALE_RANGE.1)
        } else {
            1.0
        }
    }

    /// The prefs in `path`: defaults if the file does not exist; an error
    /// naming the file if it cannot be read or parsed.
    pub fn load(path: &Path) -> Result<Self, String> {
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Self::default()),
            Err(e) => return Err(format!("{}: {e}", path.display())),
        };
        let p: Self = toml::from_str(&text).map_err(|e| format!("{}: {}", path.display(), e.message()))?;
        Ok(Self {
            scale: Self::clamp_scale(p.scale),
            lecture: p.lecture,
        })
    }

    /// Writes the prefs to `path` (creating its folder), atomically.
    pub fn save(&self, path: &Path) -> Result<(), String> {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let text = toml::to_string(self).map_err(|e| e.to_string())?;
        crate::gui::export::write_atomic(path, text.as_bytes())
    }
}

/// Where the prefs live: `$XDG_CONFIG_HOME/rocking/app.toml`, else
/// `$HOME/.config/rocking/app.toml`; `None` without either variable.
pub(crate) fn default_path() -> Option<PathBuf> {
    let base = std::env::var_os("XDG_CONFIG_HOME")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
    Some(base.join("rocking").join("app.toml"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefs_round_trip_and_a_missing_file_is_the_default() {
        let dir = std::env::temp_dir().join(format!("rocking-prefs-{}", std::process::id()));
        let path = dir.join("sub").join("app.toml");
        assert_eq!(Prefs::load(&path).unwrap(), Prefs::default());
        Prefs {
            scale: 1.75,
            lecture: true,
        }
        .save(&path)
        .unwrap();
        assert_eq!(
            Prefs::load(&path).unwrap(),
            Prefs {
                scale: 1.75,
                lecture: true
            }
        );
        std::fs::write(&path, "scale = 40.0\n").unwrap();
        assert_eq!(Prefs::load(&path).unwrap().scale, SCALE_RANGE.1);
        assert!(!Prefs::load(&path).unwrap().lecture, "a file without it: off");
        std::fs::write(&path, "scale = \"big\"\n").unwrap();
        let e = Prefs::load(&path).unwrap_err();
        assert!(e.contains("app.toml"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// 1280 × 800 holds up to 160 %, 1920 × 1080 up to 216 %: the menu
    /// offers 100–150 % and 100–200 %.
    #[test]
    fn the_menu_offers_the_scales_the_window_holds() {
        assert!((max_scale([1280.0, 800.0], false) - 1.6).abs() < 1e-6);
        assert_eq!(offered([1280.0, 800.0], false), [1.0, 1.25, 1.5]);
        assert_eq!(offered([1920.0, 1080.0], false), [1.0, 1.25, 1.5, 1.75, 2.0]);
        assert_eq!(offered([3840.0, 2160.0], false), SCALES);
        assert_eq!(max_scale([100.0, 100.0], false), SCALE_RANGE.0);
        assert_eq!(offered([1280.0, 800.0], true), [1.0, 1.25]);
        assert_eq!(offered([1920.0, 1080.0], true), [1.0, 1.25, 1.5]);
    }
}
