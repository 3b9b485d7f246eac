//! Argument groups that several commands share (`#[command(flatten)]`), so
//! each flag is declared, documented and read in one place.

use std::path::PathBuf;

use super::flags::Flags;
use crate::analysis::steady::Window;
use crate::io::ConfigError;
use crate::io::config;
use crate::sim::Scenario;

/// Which scene: a preset or a config file, and `--set` overrides
/// (`--batch`, `sweep`, `map` and the app).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct SceneArgs {
    /// A preset (default, phenomena such as period-doubling, fig3 … fig19; `--list-presets` shows them).
    /// Without this or --config, --set keys build on the literature's base (Housner impact, no sliding,
    /// no vertical motion); with no key at all the scene is the default preset.
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// A config file: TOML, or a summary.json / sweep.json to repeat its
    /// run with its configuration.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Override one key, e.g. --set excitation.a_v=2.5 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

impl SceneArgs {
    /// The scenario these arguments name, validated. The config layer
    /// names a preset and a file by what they are; giving both is worded
    /// here, as the flags.
    pub fn load(&self) -> Result<Scenario, ConfigError> {
        if self.preset.is_some() && self.config.is_some() {
            return Err(ConfigError::Usage("give either --preset or --config, not both".into()));
        }
        config::load(self.preset.as_deref(), self.config.as_deref(), &self.sets)
    }
}

/// The sampling window of a steady-response study and its worker threads
/// (`sweep` and `map`).
#[derive(Debug, Clone, clap::Args)]
pub struct StudyArgs {
    /// Section points before this τ are discarded (the paper's 600).
    #[arg(long, value_name = "T", default_value_t = 600.0, allow_negative_numbers = true)]
    pub transient: f64,
    /// End of each run, τ (default: the config's run.tau_end, 800 in the
    /// paper presets).
    #[arg(long = "tau-end", value_name = "T", allow_negative_numbers = true)]
    pub tau_end: Option<f64>,
    /// Worker threads (default: one per core; at most 4 per core). The output
    /// does not depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

impl StudyArgs {
    /// The window for `base`, whose `run.tau_end` is the default end;
    /// checked, errors naming the flags.
    pub fn window(&self, base: &Scenario) -> Result<Window, String> {
        Window::of_study(base, self.transient, self.tau_end).map_err(|e| e.render(&Flags))
    }
}

/// What a steady-response study writes (`sweep` and `map`).
#[derive(Debug, Clone, clap::Args)]
pub struct StudyOutput {
    /// Also compute the largest Lyapunov exponent of each value or cell
    /// (tangent dynamics with saltation matrices, τ 600–2600 by default;
    /// about half a second each in release) into the `lyapunov` column.
    #[arg(long)]
    pub lyapunov: bool,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}
