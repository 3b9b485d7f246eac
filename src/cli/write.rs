//! Writing a command's output folder: every command stages its files and
//! moves them into place only when all are written (`io::staging`).

use std::path::Path;

use anyhow::Context as _;

use super::batch::BatchError;
use crate::io::staging::Staging;
use crate::plot::Figure;

/// Writes the output folder `out` with `write`, which puts the files into
/// the staging directory; nothing appears at `out` unless all succeed.
pub fn staged(out: &Path, write: impl FnOnce(&mut Staging) -> anyhow::Result<()>) -> Result<(), BatchError> {
    let mut staging = Staging::new(out).context("--out").map_err(BatchError::Run)?;
    write(&mut staging)
        .and_then(|()| Ok(staging.commit()?))
        .with_context(|| format!("writing {}", out.display()))
        .map_err(BatchError::Run)
}

/// `fig` as `STEM.png` and `STEM.svg`.
pub fn figure(staging: &mut Staging, stem: &str, fig: &impl Figure) -> anyhow::Result<()> {
    fig.write_png(&staging.path(&format!("{stem}.png")))?;
    staging.text(&format!("{stem}.svg"), &fig.to_svg()?)?;
    Ok(())
}
