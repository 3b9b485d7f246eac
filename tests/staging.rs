//! Output folders on another file system: `--out` a symlink to another
//! disk, a mount point or a Docker volume. The staging folder goes on the
//! destination's file system, so the final renames never cross devices,
//! and a rename that does (EXDEV) falls back to copy + rename: a computed
//! result is never lost. Here `/dev/shm` (tmpfs) stands for the other disk;
//! where it is missing or on the temp folder's device the tests say so and
//! skip.

#![cfg(unix)]

use std::os::unix::fs::MetadataExt as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use rocking::io::staging::{Staging, move_file, staging_home};

fn tmpdir(root: &Path, name: &str) -> PathBuf {
    let d = root.join(format!("rocking-staging-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d.canonicalize().unwrap()
}

/// `/dev/shm` when it is a folder on another device than the temp folder.
fn other_disk() -> Option<PathBuf> {
    let shm = Path::new("/dev/shm");
    let dev = |p: &Path| std::fs::metadata(p).ok().map(|m| m.dev());
    match (dev(shm), dev(&std::env::temp_dir())) {
        (Some(a), Some(b)) if a != b && shm.is_dir() => Some(shm.to_path_buf()),
        _ => {
            println!("skipped: /dev/shm is missing or on the temp folder's file system");
            None
        }
    }
}

/// Every entry of `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A `--out` that is a symlink to a folder on another file system: every
/// staged command writes its files there and leaves no staging folder on
/// either side (before, each computed everything and then failed with
/// "Invalid cross-device link (os error 18)", writing nothing).
#[test]
fn out_through_a_symlink_to_another_file_system_is_written() {
    let Some(shm) = other_disk() else { return };
    let here = tmpdir(&std::env::temp_dir(), "symlink");
    let elcentro = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");
    let commands: [(&str, Vec<&str>, &str); 5] = [
        (
            "batch",
            vec!["--batch", "--preset", "free-rocking", "--set", "run.tau_end=5"],
            "summary.json",
        ),
        (
            "sweep",
            vec![
                "sweep",
                "--preset",
                "fig4",
                "--param",
                "excitation.a_v",
                "--from",
                "1.9",
                "--to",
                "2.1",
                "--step",
                "0.2",
                "--transient",
                "100",
                "--tau-end",
                "160",
                "-q",
            ],
            "sweep.json",
        ),
        (
            "map",
            vec![
                "map",
                "--preset",
                "fig4",
                "--x",
                "excitation.a_v",
                "1.0",
                "2.0",
                "2",
                "--y",
                "excitation.a_h",
                "0.5",
                "3.0",
                "2",
                "--transient",
                "100",
                "--tau-end",
                "160",
                "-q",
            ],
            "map.json",
        ),
        (
            "spectrum",
            vec![
                "spectrum", "--record", elcentro, "--unit", "g", "--from", "0.5", "--to", "1", "--count", "2", "-q",
            ],
            "spectrum.json",
        ),
        (
            "pulse-map",
            vec![
                "pulse-map",
                "--pulse",
                "one-sine",
                "--omega",
                "2",
                "--amp-step",
                "0.5",
                "--amp-max",
                "6",
                "-q",
            ],
            "pulse_map.json",
        ),
    ];
    for (name, args, file) in commands {
        let target = tmpdir(&shm, name);
        let link = here.join(format!("{name}-link"));
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args(&args)
            .arg("--out")
            .arg(&link)
            .output()
            .unwrap();
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(target.join(file).is_file(), "{name}: {:?}", names(&target));
        assert!(
            names(&target).iter().all(|n| !n.starts_with('.')),
            "{name}: {:?}",
            names(&target)
        );
        let _ = std::fs::remove_dir_all(&target);
    }
    assert!(names(&here).iter().all(|n| n.ends_with("-link")), "{:?}", names(&here));
    let _ = std::fs::remove_dir_all(&here);
}

/// Where the staging folder goes: inside an existing output folder (with
/// its symlinks resolved: the folder may be a mount point, whose parent is
/// on another file system), else in the real parent of a new one.
#[test]
fn the_staging_folder_is_on_the_destinations_file_system() {
    let Some(shm) = other_disk() else { return };
    let here = tmpdir(&std::env::temp_dir(), "home");
    let target = tmpdir(&shm, "home");
    let link = here.join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    assert_eq!(staging_home(&link).unwrap(), target);
    assert_eq!(staging_home(&link.join("new")).unwrap(), target);
    assert_eq!(staging_home(&here.join("new")).unwrap(), here);

    let mut s = Staging::new(&link).unwrap();
    assert_eq!(s.folder().parent().unwrap(), target);
    s.text("a.csv", "x\n1\n").unwrap();
    s.commit().unwrap();
    assert_eq!(names(&target), ["a.csv"]);
    let _ = std::fs::remove_dir_all(&here);
    let _ = std::fs::remove_dir_all(&target);
}

/// A rename across file systems fails with EXDEV; `move_file` then copies
/// beside the destination and renames, and removes the source.
#[test]
fn a_rename_across_file_systems_falls_back_to_copy_and_rename() {
    let Some(shm) = other_disk() else { return };
    let from_dir = tmpdir(&shm, "exdev");
    let to_dir = tmpdir(&std::env::temp_dir(), "exdev");
    let from = from_dir.join("a.bin");
    let to = to_dir.join("a.bin");
    std::fs::write(&from, [1u8, 2, 3]).unwrap();
    let e = std::fs::rename(&from, &to).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::CrossesDevices, "{e}");
    move_file(&from, &to).unwrap();
    assert_eq!(std::fs::read(&to).unwrap(), [1u8, 2, 3]);
    assert!(!from.exists());
    assert_eq!(names(&to_dir), ["a.bin"]);
    let _ = std::fs::remove_dir_all(&from_dir);
    let _ = std::fs::remove_dir_all(&to_dir);
}
