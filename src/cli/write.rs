//! Writing a command's output folder: every command stages its files and
//! moves them into place only when all are written (`io::staging`).

use std::path::Path;

use anyhow::Context as _;

use super::error::BatchError;
use crate::io::staging::Staging;
use crate::plot::Figure;

/// Writes the output folder `out` with `write`, which puts the files into
/// the staging directory; nothing appears at `out` unless all succeed.
pub fn staged(out: &Path, write: impl FnOnce(&mut Staging) -> anyhow::Result<()>) -> Result<(), BatchError> {
    let mut staging = Staging::new(out).context("--out").map_err(output_error)?;
    write(&mut staging)
        .and_then(|()| Ok(staging.commit()?))
        .with_context(|| format!("writing {}", out.display()))
        .map_err(output_error)
}

/// A failure while writing outputs: a problem of the output location (a
/// full disk, a name too long, no permission: any I/O error, exit 2), or
/// else of the computation that renders them (exit 1).
pub(crate) fn output_error(e: anyhow::Error) -> BatchError {
    use crate::io::output_error::OutputError;
    let io = e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>().is_some()
            || matches!(
                c.downcast_ref::<OutputError>(),
                Some(OutputError::Io { .. } | OutputError::NotADirectory(_))
            )
    });
    if io { BatchError::Input(e) } else { BatchError::Run(e) }
}

/// `fig` as `STEM.png` and `STEM.svg`.
pub fn figure(staging: &mut Staging, stem: &str, fig: &impl Figure) -> anyhow::Result<()> {
    fig.write_png(&staging.path(&format!("{stem}.png")))?;
    staging.text(&format!("{stem}.svg"), &fig.to_svg()?)?;
    Ok(())
}
