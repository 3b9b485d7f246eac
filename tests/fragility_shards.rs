//! `rocking fragility` shards as `rocking merge` reads them: a shard whose
//! `runs.csv` was edited, cut or written without its checks is refused
//! (exit 2, one line naming the file, nothing written), like a sweep
//! shard; and a record whose name spells `inf` or `nan` is a name, not a
//! non-finite number.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const ELCENTRO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records/elcentro-1940-ns.dat");

fn rocking() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rocking"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rocking-shards-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exit 2, a one-line error containing every needle, and nothing at `out`.
fn refused(o: &Output, needles: &[&str], out: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} does not name {needle:?}");
    }
    assert_eq!(err.trim().lines().count(), 1, "one line: {err:?}");
    assert!(!out.exists(), "{} was written", out.display());
}

/// The first `lines` samples of El Centro (in g, 0.02 s apart) as
/// `dir/name`: short runs through the strong motion.
fn short_record(dir: &Path, name: &str, lines: usize) -> PathBuf {
    let text = std::fs::read_to_string(ELCENTRO).unwrap();
    let head: Vec<&str> = text.lines().take(lines).collect();
    let path = dir.join(name);
    std::fs::write(&path, head.join("\n") + "\n").unwrap();
    path
}

/// A fragility study of `records` (in g), 2 levels, one block.
fn fragility(records: &[PathBuf], out: &Path, extra: &[&str]) -> Output {
    let mut c = rocking();
    c.arg("fragility");
    for r in records {
        c.arg("--records").arg(r);
    }
    c.args([
        "--unit", "g", "--levels", "0.2,0.6", "--block", "0.3x1.2", "-q", "--out",
    ])
    .arg(out)
    .args(extra)
    .output()
    .expect("runs")
}

fn merge(out: &Path, shards: &[PathBuf]) -> Output {
    rocking()
        .args(["merge", "-q", "--out"])
        .arg(out)
        .args(shards)
        .output()
        .expect("runs")
}

/// Two shards of one small study in `dir`.
fn two_shards(dir: &Path) -> Vec<PathBuf> {
    let record = short_record(dir, "elcentro-8s.dat", 400);
    (0..2)
        .map(|k| {
            let d = dir.join(format!("shard{k}"));
            ok(&fragility(
                std::slice::from_ref(&record),
                &d,
                &["--shard", &format!("{k}/2")],
            ));
            d
        })
        .collect()
}

#[test]
fn merge_refuses_a_fragility_shard_whose_runs_csv_was_edited() {
    let dir = tmpdir("edited");
    let shards = two_shards(&dir);
    // Unchanged shards merge.
    ok(&merge(&dir.join("merged"), &shards));
    // One run's end changed by hand: the counts and fits would change.
    let runs = shards[0].join("runs.csv");
    let text = std::fs::read_to_string(&runs).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let end = lines[0].split(',').position(|h| h == "end").expect("an end column");
    let mut cells: Vec<String> = lines[1].split(',').map(str::to_string).collect();
    cells[end] = if cells[end] == "overturned" {
        "rest"
    } else {
        "overturned"
    }
    .to_string();
    lines[1] = cells.join(",");
    std::fs::write(&runs, lines.join("\n") + "\n").unwrap();
    let out = dir.join("merged-edited");
    refused(&merge(&out, &shards), &["runs.csv", "CRC-32"], &out);
    // A row removed: the row count the shard wrote disagrees.
    lines.truncate(lines.len() - 1);
    std::fs::write(&runs, lines.join("\n") + "\n").unwrap();
    refused(&merge(&out, &shards), &["runs.csv"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn merge_refuses_a_fragility_shard_without_checks_asking_to_recompute_it() {
    let dir = tmpdir("old");
    let shards = two_shards(&dir);
    // A shard as an older version wrote it: no "files" entry.
    let json_path = shards[1].join("fragility.json");
    let mut json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    assert!(json.get("files").is_some(), "a shard records its files' checks");
    json.as_object_mut().unwrap().remove("files");
    std::fs::write(&json_path, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    let out = dir.join("merged");
    refused(&merge(&out, &shards), &["fragility.json", "recompute"], &out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_record_named_infill_or_nan_is_a_name_not_a_non_finite_number() {
    let dir = tmpdir("names");
    let records = [
        short_record(&dir, "elcentro-infill.dat", 400),
        short_record(&dir, "nan.dat", 300),
    ];
    let out = dir.join("out");
    ok(&fragility(&records, &out, &[]));
    let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    assert!(runs.contains(",elcentro-infill,") && runs.contains(",nan,"), "{runs}");
    let _ = std::fs::remove_dir_all(&dir);
}
