//! An output directory that appears whole or not at all: the one writer
//! every command's output goes through.
//!
//! The files go into a hidden staging directory beside the target — text
//! through [`Staging::text`], figures (which plotters writes straight to a
//! path) through the paths [`Staging::path`] hands out — and
//! [`Staging::commit`] moves them into place at the end. Dropping an
//! uncommitted staging removes it, so an error midway leaves nothing
//! behind. CSV text is refused if it holds a non-finite number.
//! [`write_all`](super::output::write_all) stages a set of text files in one
//! call.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use super::csv;
use super::output_error::{OutputError, io_err};

/// The folder `dir` is made in (`.` for a bare name), as written.
pub(crate) fn parent_of(dir: &Path) -> PathBuf {
    match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The folder the staging directory of output folder `dir` goes in, so
/// that moving the files into place is a rename on one file system: `dir`
/// itself, with its symlinks resolved, when it exists (it may be a mount
/// point, a Docker volume or a symlink to another disk, whose parent is on
/// another file system); else `dir`'s parent with its symlinks resolved,
/// where `dir` will be made. The parent is created if missing.
pub fn staging_home(dir: &Path) -> Result<PathBuf, OutputError> {
    if dir.is_dir() {
        return dir.canonicalize().map_err(io_err(dir));
    }
    let parent = parent_of(dir);
    std::fs::create_dir_all(&parent).map_err(io_err(&parent))?;
    parent.canonicalize().map_err(io_err(&parent))
}

/// Removes the staging folders `.{base}.partial-PID` in `parent` left by
/// processes that no longer run (killed while writing): they are never
/// output, and would otherwise stay forever. A process is alive while
/// `/proc/PID` exists; where there is no `/proc`, nothing is removed.
fn remove_stale(parent: &Path, base: &str) {
    let prefix = format!(".{base}.partial-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    if !Path::new("/proc/self").exists() {
        return;
    }
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(|n| n.strip_prefix(&prefix)) else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists() {
            // Best effort: a folder that cannot be removed is still not output.
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// The staging folders of this process not yet committed or dropped: what
/// [`remove_live_then`] removes when the process is interrupted. A commit
/// holds the lock while it moves files, so an interrupt never lands
/// between two of its renames.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// [`LIVE`], also after a panic in another thread (the list stays valid:
/// every change to it is one push or one retain).
fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Removes every staging folder of this process, then calls `then` with
/// no commit able to start: for a signal handler that removes the partial
/// output of an interrupted command before the process ends (a `then`
/// that ends the process). A commit under way finishes first, so the
/// output is whole or absent.
pub(crate) fn remove_live_then<R>(then: impl FnOnce() -> R) -> R {
    let live = live();
    for dir in live.iter() {
        // Threads may still be writing into it: a file made between the
        // listing and the removal makes one pass fail, the next one sees it.
        for _ in 0..20 {
            if std::fs::remove_dir_all(dir).is_ok() || !dir.exists() {
                break;
            }
        }
    }
    then()
}

/// Moves file `from` to `to`: a rename, or where the two are on different
/// file systems (EXDEV, which a rename cannot cross), a copy to a hidden
/// file beside `to` and a rename of that, so that `to` is never seen half
/// written; `from` is removed after.
pub fn move_file(from: &Path, to: &Path) -> std::io::Result<()> {
    match std::fs::rename(from, to) {
        Err(e) if e.kind() == std::io::ErrorKind::CrossesDevices => {
            let name = to
                .file_name()
                .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
            let tmp = parent_of(to).join(format!(".{name}.copy-{}", std::process::id()));
            let copied = std::fs::copy(from, &tmp).and_then(|_| std::fs::rename(&tmp, to));
            if copied.is_err() {
                let _ = std::fs::remove_file(&tmp);
            }
            copied?;
            std::fs::remove_file(from)
        }
        other => other,
    }
}

/// A staging directory for the files of one output directory.
#[derive(Debug)]
pub struct Staging {
    dir: PathBuf,
    staging: PathBuf,
    names: Vec<String>,
    committed: bool,
}

impl Staging {
    /// Starts staging the files of `dir` (which may exist; files of the same
    /// name are replaced at commit, others are left alone). The staging
    /// folder goes where [`staging_home`] says.
    pub fn new(dir: &Path) -> Result<Self, OutputError> {
        if dir.exists() && !dir.is_dir() {
            return Err(OutputError::NotADirectory(dir.display().to_string()));
        }
        let existed = dir.is_dir();
        let home = staging_home(dir)?;
        let base = dir
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        remove_stale(&home, &base);
        // A run killed before `dir` existed left its folder in the parent,
        // which is `home` itself when `dir` does not exist yet: listed once
        // (a folder of a sweep's thousand outputs costs a millisecond a
        // listing).
        if existed {
            remove_stale(&parent_of(dir), &base);
        }
        let staging = home.join(format!(".{base}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging).map_err(io_err(&staging))?;
        }
        std::fs::create_dir_all(&staging).map_err(io_err(&staging))?;
        live().push(staging.clone());
        Ok(Self {
            dir: dir.to_path_buf(),
            staging,
            names: Vec::new(),
            committed: false,
        })
    }

    /// The staging folder (for tests and messages).
    pub fn folder(&self) -> &Path {
        &self.staging
    }

    /// The staging path of file `name`, registered for the commit.
    pub fn path(&mut self, name: &str) -> PathBuf {
        if !self.names.iter().any(|n| n == name) {
            self.names.push(name.to_string());
        }
        self.staging.join(name)
    }

    /// Writes a text file. A `.csv` holding a non-finite number is refused
    /// ([`csv::has_non_finite`]: numbers, not names that spell `inf`).
    pub fn text(&mut self, name: &str, text: &str) -> Result<(), OutputError> {
        if name.ends_with(".csv") && csv::has_non_finite(text) {
            return Err(OutputError::NonFinite(name.to_string()));
        }
        let p = self.path(name);
        std::fs::write(&p, text).map_err(io_err(&p))
    }

    /// Moves every registered file into the target directory.
    pub fn commit(mut self) -> Result<(), OutputError> {
        for name in &self.names {
            let p = self.staging.join(name);
            if !p.is_file() {
                return Err(OutputError::Io {
                    path: p.display().to_string(),
                    error: std::io::Error::new(std::io::ErrorKind::NotFound, "was never written"),
                });
            }
        }
        // Held until the files are in place: an interrupt waits for them.
        let mut live = live();
        let whole = !self.dir.exists() && std::fs::rename(&self.staging, &self.dir).is_ok();
        if !whole {
            std::fs::create_dir_all(&self.dir).map_err(io_err(&self.dir))?;
            for name in &self.names {
                let (from, to) = (self.staging.join(name), self.dir.join(name));
                move_file(&from, &to).map_err(io_err(&to))?;
            }
            std::fs::remove_dir(&self.staging).map_err(io_err(&self.staging))?;
        }
        live.retain(|d| *d != self.staging);
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: an error here leaves only a hidden staging
            // directory, never a half-written output.
            let _ = std::fs::remove_dir_all(&self.staging);
            live().retain(|d| *d != self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rocking-staging-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn commit_creates_the_directory_whole() {
        let root = tmp("commit");
        let out = root.join("out");
        let mut s = Staging::new(&out).unwrap();
        s.text("a.csv", "x\n1\n").unwrap();
        std::fs::write(s.path("b.bin"), [0u8, 159, 255]).unwrap();
        assert!(!out.exists());
        s.commit().unwrap();
        assert_eq!(std::fs::read(out.join("b.bin")).unwrap(), vec![0u8, 159, 255]);
        assert_eq!(std::fs::read_to_string(out.join("a.csv")).unwrap(), "x\n1\n");
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 1);
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn dropping_or_a_nan_leaves_nothing() {
        let root = tmp("drop");
        let out = root.join("out");
        {
            let mut s = Staging::new(&out).unwrap();
            // What a CSV writer makes of a non-finite number.
            let nan = format!("x\n{}\n", csv::NON_FINITE_CELL);
            assert!(matches!(s.text("a.csv", &nan), Err(OutputError::NonFinite(_))));
        }
        assert!(!out.exists());
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 0);
        let mut s = Staging::new(&out).unwrap();
        let _ = s.path("never.png");
        assert!(s.commit().is_err());
        assert!(!out.exists());
        let _ = std::fs::remove_dir_all(&root);
    }
}
