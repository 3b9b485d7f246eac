//! What the app remembers between sessions: the presentation scale. Kept
//! in a small TOML file of its own (`$XDG_CONFIG_HOME/rocking/app.toml`,
//! else `~/.config/rocking/app.toml`) rather than eframe's persistence,
//! which would also restore panel sizes and plot zooms a lecturer does not
//! expect to come back.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// Smallest and largest presentation scale (egui's zoom factor): below
/// 0.75 text is unreadable even on a laptop; above 3 a 1280 × 800
/// projector has no room left for the block.
pub const SCALE_RANGE: (f32, f32) = (0.75, 3.0);

/// The scales the View menu offers (the keyboard steps between any).
pub const SCALES: [f32; 6] = [1.0, 1.25, 1.5, 1.75, 2.0, 2.5];

/// The remembered settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Prefs {
    /// Presentation scale: how much all text and lines are enlarged. 1 is
    /// egui's default size.
    pub scale: f32,
}

impl Default for Prefs {
    fn default() -> Self {
        Self { scale: 1.0 }
    }
}

impl Prefs {
    /// `scale` clamped to [`SCALE_RANGE`] (NaN: 1).
    pub fn clamp_scale(scale: f32) -> f32 {
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
pub fn default_path() -> Option<PathBuf> {
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
        Prefs { scale: 1.75 }.save(&path).unwrap();
        assert_eq!(Prefs::load(&path).unwrap().scale, 1.75);
        std::fs::write(&path, "scale = 40.0\n").unwrap();
        assert_eq!(Prefs::load(&path).unwrap().scale, SCALE_RANGE.1);
        std::fs::write(&path, "scale = \"big\"\n").unwrap();
        let e = Prefs::load(&path).unwrap_err();
        assert!(e.contains("app.toml"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
