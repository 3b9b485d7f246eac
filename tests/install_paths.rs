//! Files and paths as an installed program meets them: the presets' records
//! are shipped inside the binary (`shipped:NAME`), so a preset runs from
//! any folder and after `cargo install`, and `summary.json` repeats it from
//! any folder; a record path typed with `--set` is relative to the current
//! folder, one written in a config file relative to that file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const KOBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/kobe-1995.dat");

fn rocking(cwd: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rocking"));
    c.current_dir(cwd);
    c
}

/// A fresh empty folder outside the source tree, canonical (the binary
/// reports canonical paths).
fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-paths-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d.canonicalize().unwrap()
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn summary(out: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

fn file_h(out: &Path) -> String {
    summary(out)["config"]["excitation"]["file_h"]
        .as_str()
        .unwrap()
        .to_string()
}

/// Exit 2 and one `error:` line holding every needle.
fn refused(o: &Output, needles: &[&str]) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    assert!(err.starts_with("error: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "{err:?} does not name {n:?}");
    }
    err
}

/// The README's headline run from a folder outside the checkout: the record
/// is the shipped one, named so in `summary.json` (not a path into the
/// source tree the binary was built from), with the shipped bytes' CRC;
/// the answer names the file as before; and the summary repeats the run
/// byte for byte from yet another folder.
#[test]
fn kobe_rack_runs_the_shipped_record_from_any_folder() {
    let here = tmpdir("kobe-here");
    let stdout = ok(&rocking(&here)
        .args(["--batch", "--preset", "kobe-rack", "--out", "o"])
        .output()
        .unwrap());
    assert!(
        stdout.starts_with("overturned at t = 6.89 s (kobe-1995.dat, PGA 0.69 g)"),
        "{stdout}"
    );
    let out = here.join("o");
    assert_eq!(file_h(&out), "shipped:kobe-1995.dat");
    let crc = format!("{:08x}", crc32fast_hash(&std::fs::read(KOBE).unwrap()));
    let s = summary(&out);
    assert_eq!(s["config"]["excitation"]["crc32_h"].as_str().unwrap(), crc);
    assert_eq!(
        s["physical"]["record_h"]["file"].as_str().unwrap(),
        "shipped:kobe-1995.dat"
    );

    let there = tmpdir("kobe-there");
    let again = ok(&rocking(&there)
        .arg("--batch")
        .arg("--config")
        .arg(out.join("summary.json"))
        .args(["--out", "again"])
        .output()
        .unwrap());
    assert_eq!(again.lines().next(), stdout.lines().next());
    // The CRC names the shipped bytes: other bytes under the name are refused.
    let o = rocking(&there)
        .arg("--batch")
        .arg("--config")
        .arg(out.join("summary.json"))
        .args(["--set", "excitation.crc32_h=00000000", "--out", "changed"])
        .output()
        .unwrap();
    refused(
        &o,
        &[
            "excitation.crc32_h: shipped:kobe-1995.dat is not the record this config was written with",
            &crc,
        ],
    );
    for f in ["events.csv", "history.csv", "poincare.csv"] {
        assert_eq!(
            std::fs::read(out.join(f)).unwrap(),
            std::fs::read(there.join("again").join(f)).unwrap(),
            "{f}"
        );
    }
    let _ = std::fs::remove_dir_all(&here);
    let _ = std::fs::remove_dir_all(&there);
}

/// CRC-32 (IEEE), bitwise: the test's own, not the crate's.
fn crc32fast_hash(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Every preset that runs a record names a shipped one, and resolves
/// without any file on disk: none depends on the folder it was built in.
#[test]
fn every_preset_names_its_records_as_shipped() {
    use rocking::io::{config, presets, shipped};
    let mut records = 0;
    for (name, text) in presets::PRESETS {
        let table = config::parse_toml(text, name).unwrap();
        let Some(x) = table.get("excitation").and_then(|x| x.as_table()) else {
            continue;
        };
        for key in ["file_h", "file_v"] {
            if let Some(v) = x.get(key) {
                let v = v.as_str().unwrap();
                let file = shipped::name_of(v).unwrap_or_else(|| panic!("preset {name}: {key} = {v:?}"));
                assert!(shipped::get(file).is_some(), "preset {name}: {v}");
                records += 1;
            }
        }
        let s = config::from_table(&table, &config::Source::preset()).unwrap();
        if let Some(r) = &s.excitation.record_h {
            assert!(
                r.path.display().to_string().starts_with("shipped:"),
                "{name}: {}",
                r.path.display()
            );
        }
    }
    assert_eq!(
        records, 6,
        "kobe-rack, kobe-rack-5th-floor, elcentro-statue, rocking-frame, tombstone and statue-on-pedestal"
    );
}

/// A shipped name that is not shipped is refused naming the key and the
/// names there are; a user's file of the same name is not taken for it.
#[test]
fn an_unknown_shipped_record_is_refused_with_the_list() {
    let here = tmpdir("unknown-shipped");
    std::fs::write(here.join("nope.dat"), "0 0\n0.02 0.1\n").unwrap();
    let o = rocking(&here)
        .args([
            "--batch",
            "--preset",
            "kobe-rack",
            "--set",
            "excitation.file_h=shipped:nope.dat",
        ])
        .args(["--out", "o"])
        .output()
        .unwrap();
    refused(
        &o,
        &[
            "excitation.file_h",
            "shipped:nope.dat: no such shipped record",
            "shipped:kobe-1995.dat",
        ],
    );
    assert!(!here.join("o").exists());
    let _ = std::fs::remove_dir_all(&here);
}

/// `--set excitation.file_h=rel.dat` with a preset (or neither a preset
/// nor a config) is `./rel.dat`, the file in the folder the user is in;
/// `summary.json` names it absolute.
#[test]
fn a_set_record_path_is_relative_to_the_current_folder() {
    let here = tmpdir("set-rel");
    std::fs::copy(KOBE, here.join("rel.dat")).unwrap();
    ok(&rocking(&here)
        .args([
            "--batch",
            "--preset",
            "kobe-rack",
            "--set",
            "excitation.file_h=rel.dat",
            "--out",
            "o",
        ])
        .output()
        .unwrap());
    assert_eq!(file_h(&here.join("o")), here.join("rel.dat").display().to_string());
    ok(&rocking(&here)
        .args([
            "--batch",
            "--set",
            "excitation.kind=record",
            "--set",
            "excitation.file_h=rel.dat",
        ])
        .args(["--set", "excitation.unit_h=m/s2", "--set", "run.t_end=2s", "--out", "p"])
        .output()
        .unwrap());
    assert_eq!(file_h(&here.join("p")), here.join("rel.dat").display().to_string());
    let _ = std::fs::remove_dir_all(&here);
}

/// With `--config cfg/c.toml`, a path written in the file is relative to
/// the file's folder, and one typed with `--set` to the current folder,
/// even when both folders hold a file of that name.
#[test]
fn a_config_path_is_relative_to_the_config_and_a_set_path_to_the_current_folder() {
    let here = tmpdir("config-rel");
    std::fs::create_dir(here.join("cfg")).unwrap();
    std::fs::copy(KOBE, here.join("rel.dat")).unwrap();
    std::fs::write(here.join("cfg/rel.dat"), "0 0\n0.02 0.5\n0.04 -0.5\n0.06 0\n").unwrap();
    std::fs::write(
        here.join("cfg/c.toml"),
        "[block]\nwidth = \"0.6 m\"\nheight = \"2.0 m\"\n[excitation]\nkind = \"record\"\nfile_h = \"rel.dat\"\nunit_h = \"m/s2\"\n[run]\nt_end = \"2 s\"\n",
    )
    .unwrap();
    ok(&rocking(&here)
        .args(["--batch", "--config", "cfg/c.toml", "--out", "in-file"])
        .output()
        .unwrap());
    assert_eq!(
        file_h(&here.join("in-file")),
        here.join("cfg/rel.dat").display().to_string()
    );
    ok(&rocking(&here)
        .args([
            "--batch",
            "--config",
            "cfg/c.toml",
            "--set",
            "excitation.file_h=rel.dat",
        ])
        .args(["--out", "typed"])
        .output()
        .unwrap());
    assert_eq!(file_h(&here.join("typed")), here.join("rel.dat").display().to_string());
    let _ = std::fs::remove_dir_all(&here);
}

/// A typed path that does not exist is reported resolved: the error names
/// the file in the current folder, where the user looked for it.
#[test]
fn a_missing_set_record_is_reported_where_it_was_looked_for() {
    let here = tmpdir("set-missing");
    let o = rocking(&here)
        .args([
            "--batch",
            "--preset",
            "kobe-rack",
            "--set",
            "excitation.file_h=missing.dat",
        ])
        .args(["--out", "o"])
        .output()
        .unwrap();
    refused(
        &o,
        &["excitation.file_h", &here.join("missing.dat").display().to_string()],
    );
    assert!(!here.join("o").exists());
    let _ = std::fs::remove_dir_all(&here);
}

/// The rule in the library, as Python's keywords use it: a relative path
/// set through `set_dotted_from` joins the folder given; an absolute one
/// and a shipped name are kept; other keys are untouched.
#[test]
fn set_paths_resolve_against_the_folder_given() {
    use rocking::io::config::set_dotted_from;
    let mut t = toml::Table::new();
    let base = || Ok(PathBuf::from("/data/here"));
    set_dotted_from(&mut t, "excitation.file_h=rec/a.dat", base).unwrap();
    set_dotted_from(&mut t, "excitation.file_v=/abs/b.dat", base).unwrap();
    set_dotted_from(&mut t, "excitation.unit_h=g", base).unwrap();
    let x = t["excitation"].as_table().unwrap();
    assert_eq!(x["file_h"].as_str(), Some("/data/here/rec/a.dat"));
    assert_eq!(x["file_v"].as_str(), Some("/abs/b.dat"));
    assert_eq!(x["unit_h"].as_str(), Some("g"));
    set_dotted_from(&mut t, "excitation.file_h=shipped:kobe-1995.dat", || {
        panic!("not asked")
    })
    .unwrap();
    assert_eq!(t["excitation"]["file_h"].as_str(), Some("shipped:kobe-1995.dat"));
}
