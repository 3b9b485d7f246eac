//! The records in `assets/records/` against their provenance table in
//! `assets/records/README.md`: every record file has a row, each row's
//! points, step and PGA are its file's (computed here from the text, and
//! read again by the crate's reader), and every suite list of the folder
//! names files of the table in the table's unit. A library suite
//! (`far-field.txt`, `near-fault.txt`) pairs each horizontal with its
//! vertical (`H UNIT + V UNIT`) and the table holds the station's other
//! horizontal too: the three components of each event-station.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rocking::io::record::{RecordSpec, read_record_as};
use rocking::model::units::AccelUnit;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records");

/// The model's g, m/s² (`model::units`): the table's PGA is in this g.
const G: f64 = 9.81;

/// Suite lists whose lines must be three-component records.
const LIBRARY_SUITES: [&str; 2] = ["far-field.txt", "near-fault.txt"];

/// One row of the provenance table: its cells by column name.
type Row = BTreeMap<String, String>;

/// The provenance table's rows, keyed by file name (the backticks removed).
fn table() -> BTreeMap<String, Row> {
    let text = std::fs::read_to_string(Path::new(DIR).join("README.md")).expect("README.md");
    let cells = |line: &str| -> Vec<String> {
        let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
        inner.split('|').map(|c| c.trim().to_string()).collect()
    };
    let mut lines = text.lines().skip_while(|l| !l.starts_with("| file |"));
    let header = cells(lines.next().expect("README.md has a table starting `| file |`"));
    let mut rows = BTreeMap::new();
    for line in lines.skip(1).take_while(|l| l.starts_with('|')) {
        let c = cells(line);
        assert_eq!(c.len(), header.len(), "README.md row has {} cells: {line}", c.len());
        let row: Row = header.iter().cloned().zip(c).collect();
        let file = row["file"].trim_matches('`').to_string();
        assert!(rows.insert(file.clone(), row).is_none(), "{file} has two rows");
    }
    assert!(!rows.is_empty(), "the provenance table has no rows");
    rows
}

/// The unit named in the table or a suite line, as the model converts it
/// to g (written here, not the crate's conversion).
fn to_g_factor(unit: &str) -> f64 {
    match unit {
        "g" => 1.0,
        "m/s2" => 1.0 / G,
        "cm/s2" => 0.01 / G,
        other => panic!("unit {other:?} is none of g, m/s2, cm/s2"),
    }
}

/// Times and accelerations of a two-column text record, read here: blank
/// and `#` lines skipped, whitespace-separated fields.
fn two_columns(path: &Path) -> (Vec<f64>, Vec<f64>) {
    let text = std::fs::read_to_string(path).expect("record text");
    let (mut t, mut a) = (Vec::new(), Vec::new());
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let f: Vec<f64> = line
            .split_whitespace()
            .map(|x| {
                x.parse()
                    .unwrap_or_else(|_| panic!("{}:{}: {x:?}", path.display(), n + 1))
            })
            .collect();
        assert_eq!(f.len(), 2, "{}:{}: two columns", path.display(), n + 1);
        t.push(f[0]);
        a.push(f[1]);
    }
    (t, a)
}

/// Every record file of the folder and its subfolders (by extension).
fn record_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("records folder") {
        let p = e.expect("entry").path();
        let ext = p.extension().map(|x| x.to_string_lossy().to_ascii_lowercase());
        if p.is_dir() {
            record_files(&p, out);
        } else if matches!(ext.as_deref(), Some("dat" | "at2" | "v2" | "asc")) {
            out.push(p);
        }
    }
}

#[test]
fn every_record_file_has_a_row_whose_points_step_and_pga_are_the_files() {
    let rows = table();
    let mut files = Vec::new();
    record_files(Path::new(DIR), &mut files);
    for f in &files {
        let name = f
            .strip_prefix(DIR)
            .expect("under DIR")
            .to_string_lossy()
            .trim_start_matches('/')
            .to_string();
        assert!(
            rows.contains_key(&name),
            "{name} has no row in assets/records/README.md"
        );
    }
    for (name, row) in &rows {
        let path = Path::new(DIR).join(name);
        assert!(path.is_file(), "{name}: the table names a file that is not there");
        assert!(!row["licence"].is_empty(), "{name}: no licence stated");
        let (t, a) = two_columns(&path);
        let points: usize = row["points"].parse().expect("points");
        assert_eq!(t.len(), points, "{name}: points");
        // A constant step: each difference of the printed times equals the
        // table's step to the printing's rounding (times are given to 1e-9 s
        // or better).
        let step: f64 = row["step (s)"].parse().expect("step");
        for w in t.windows(2) {
            assert!(
                (w[1] - w[0] - step).abs() < 1e-9,
                "{name}: step {} at t = {}",
                w[1] - w[0],
                w[0]
            );
        }
        assert_eq!(t[0], 0.0, "{name}: starts at 0 s");
        // The PGA the table prints, to its 3 decimals.
        let factor = to_g_factor(&row["unit"]);
        let pga_g = a.iter().fold(0.0_f64, |m, v| m.max(v.abs())) * factor;
        let stated: f64 = row["PGA (g)"].parse().expect("PGA");
        assert!(
            (pga_g - stated).abs() <= 0.0005 + 1e-12,
            "{name}: PGA {pga_g} g, table {stated}"
        );
        // The crate's reader, told the table's unit, gives the same samples.
        let unit = AccelUnit::parse(&row["unit"]).expect("unit");
        let read = read_record_as(&path, &RecordSpec::stated(unit)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(read.series.times_s(), &t[..], "{name}: times");
        let read_pga = read.series.accel_g().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(
            (read_pga - pga_g).abs() <= 1e-12 * pga_g,
            "{name}: {read_pga} g read, {pga_g} g here"
        );
    }
}

/// A suite line: its 1-based line number and its components, each a path
/// and the unit written after it.
type SuiteLine = (usize, Vec<(String, Option<String>)>);

/// A suite line's components: `PATH [UNIT] [+ VPATH [UNIT]]`, comments
/// and blank lines dropped (the grammar of `cli::suite`, paths without
/// spaces, which is all this folder holds).
fn suite_lines(list: &Path) -> Vec<SuiteLine> {
    let text = std::fs::read_to_string(list).expect("suite list");
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split(" #").next().unwrap_or("").trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut parts = Vec::new();
        for side in line.split(" + ") {
            let mut w = side.split_whitespace();
            let path = w.next().expect("a path").to_string();
            parts.push((path, w.next().map(str::to_string)));
            assert!(w.next().is_none(), "{}:{}: more than PATH UNIT", list.display(), n + 1);
        }
        out.push((n + 1, parts));
    }
    out
}

#[test]
fn every_suite_list_names_files_of_the_table_in_the_tables_unit() {
    let rows = table();
    let lists: Vec<PathBuf> = std::fs::read_dir(DIR)
        .expect("records folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "txt"))
        .collect();
    assert!(!lists.is_empty(), "no suite list in assets/records");
    for list in &lists {
        let lines = suite_lines(list);
        assert!(!lines.is_empty(), "{}: lists no records", list.display());
        for (n, parts) in &lines {
            for (path, unit) in parts {
                let row = rows
                    .get(path)
                    .unwrap_or_else(|| panic!("{}:{n}: {path} has no row in README.md", list.display()));
                assert_eq!(
                    unit.as_deref(),
                    Some(row["unit"].as_str()),
                    "{}:{n}: unit of {path}",
                    list.display()
                );
            }
        }
    }
}

#[test]
fn a_library_suite_lists_three_component_records() {
    let rows = table();
    let station = |r: &Row| (r["event"].clone(), r["date (UTC)"].clone(), r["station"].clone());
    for name in LIBRARY_SUITES {
        let list = Path::new(DIR).join(name);
        if !list.exists() {
            continue;
        }
        for (n, parts) in suite_lines(&list) {
            assert_eq!(parts.len(), 2, "{name}:{n}: a horizontal + its vertical");
            let (h, v) = (&rows[&parts[0].0], &rows[&parts[1].0]);
            assert_eq!(station(h), station(v), "{name}:{n}: H and V of one event-station");
            assert!(
                v["component"].contains("vertical"),
                "{name}:{n}: {} is not vertical",
                parts[1].0
            );
            let same: Vec<&Row> = rows.values().filter(|r| station(r) == station(h)).collect();
            let horizontals = same.iter().filter(|r| !r["component"].contains("vertical")).count();
            assert_eq!(
                (same.len(), horizontals),
                (3, 2),
                "{name}:{n}: the table's components of that station"
            );
        }
    }
}
