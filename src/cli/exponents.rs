//! `analysis.lyapunov` in a `--batch` run of any body: the exponents for
//! summary.json and the line they add to the report.

use crate::analysis::lyapunov::{self, Lyapunov, LyapunovOptions, Method};
use crate::sim::Scenario;
use crate::sim::scenario::LyapunovChoice;

use super::error::BatchError;

/// The line the exponents of `analysis.lyapunov` add to a run's report.
pub(crate) fn say_lyapunov(exponents: Option<&Lyapunov>) {
    match exponents {
        Some(Lyapunov::Exponents(r)) => crate::say!(
            "lyapunov ({}): largest {:.4} ± {:.4} per tau, {:.4} per cycle; spectrum {:?}",
            r.method.name(),
            r.largest_per_tau,
            r.stderr,
            r.per_cycle,
            r.spectrum
        ),
        Some(Lyapunov::None {
            method, no_exponent, ..
        }) => crate::say!("lyapunov ({}): no exponent ({})", method.name(), no_exponent.name()),
        None => {}
    }
}

/// The Lyapunov exponents of `cfg`'s run (`analysis.lyapunov`), over the
/// run's own `tau_end` ([`LyapunovOptions::for_scenario`]). A run too
/// short for them is bad input.
pub(crate) fn lyapunov_summary(cfg: &Scenario) -> Result<Lyapunov, BatchError> {
    for warning in cfg.warnings() {
        eprintln!("{warning}");
    }
    let method = match cfg.analyses.lyapunov_method {
        LyapunovChoice::Tangent => Method::Tangent,
        LyapunovChoice::Benettin => Method::Benettin,
        LyapunovChoice::Both => Method::Both,
    };
    let opts = LyapunovOptions::for_scenario(cfg, method);
    lyapunov::of_scenario(cfg, &opts).map_err(|e| {
        if e.is_input() {
            BatchError::Input(anyhow::anyhow!("analysis.lyapunov: {e}"))
        } else {
            BatchError::Run(anyhow::Error::new(e).context("lyapunov exponents failed"))
        }
    })
}
