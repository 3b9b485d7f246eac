//! The records of a fragility study: `--records FILE|DIR` and the suite
//! list `--suite LIST`, each record with how to read it and where it was
//! named. Errors name the flag, or the list's file and line; bad input is
//! refused before any record is read.
//!
//! A suite list has one record per line: `PATH [UNIT] [channel=N]`, or a
//! horizontal and its vertical component `PATH [UNIT] [channel=N] + VPATH
//! [UNIT] [channel=N]` (the `+` a word of its own; `channel=N` picks one
//! channel, from 1, of a COSMOS file that holds several, so that a station's
//! one file gives both components). PATH is relative to the list's folder; a path with spaces
//! is written in double quotes (`"my records/a b.dat" g`) or followed by a
//! tab (`my records/a b.dat<TAB>g`). UNIT (g, m/s2, cm/s2) applies to that
//! text record. Blank lines and lines starting with `#` are skipped, and
//! `#` after a space or tab starts a comment. A UTF-8 byte-order mark at
//! the start is ignored.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow};

use super::eng_args::input;
use super::error::BatchError;
use crate::io::record::RecordSpec;
use crate::model::units::AccelUnit;

/// One record of a suite: its file, how to read it, its vertical
/// component if the suite names one, and where it was named.
#[derive(Clone, Debug, PartialEq)]
pub struct SuiteEntry {
    /// The horizontal component's file.
    pub path: PathBuf,
    /// How to read it.
    pub spec: RecordSpec,
    /// The vertical component's file and how to read it (`+ VPATH [UNIT]`
    /// on a suite line; never from `--records`).
    pub vertical: Option<(PathBuf, RecordSpec)>,
    /// `LIST:LINE` for a suite list, `None` for `--records`.
    pub origin: Option<String>,
}

impl SuiteEntry {
    /// An entry of `--records`: a horizontal record alone.
    fn file(path: PathBuf, spec: RecordSpec) -> Self {
        Self {
            path,
            spec,
            vertical: None,
            origin: None,
        }
    }
}

/// Largest suite list read, bytes: a list holds one short line per record,
/// so 1 MiB is some 10 000 records, more than a fragility study runs in a
/// day; beyond it the file is not a suite (`/dev/zero` would be read
/// without end).
pub(crate) const MAX_SUITE_BYTES: u64 = 1 << 20;

/// Bytes of a file in a `--records` folder read to tell a record from
/// another file (a README, a suite list, a figure).
const SNIFF_BYTES: u64 = 64 << 10;

/// The record files named by `files` (each a file, or a folder whose
/// records are taken in name order, other files skipped with a warning)
/// and by the suite list `suite`, each with its reading spec. A record
/// named twice (by any route) is refused, naming both places: it would
/// count its runs twice and narrow every fit's band.
pub fn suite(files: &[PathBuf], suite: Option<&Path>, spec: RecordSpec) -> Result<Vec<SuiteEntry>, BatchError> {
    let mut out = Vec::new();
    for f in files {
        if f.is_dir() {
            folder(f, spec, &mut out)?;
        } else {
            out.push(SuiteEntry::file(f.clone(), spec));
        }
    }
    if let Some(list) = suite {
        let before = out.len();
        read_list(list, spec, &mut out)?;
        if out.len() == before {
            return Err(input(anyhow!(
                "--suite {}: the suite {} lists no records",
                list.display(),
                list.display()
            )));
        }
    }
    if out.is_empty() {
        return Err(input(anyhow!(
            "--records: give the records with --records FILE|DIR (repeatable) or --suite LIST"
        )));
    }
    refuse_twice(&out)?;
    Ok(out)
}

/// Where an entry was named, for messages.
fn origin(entry: &SuiteEntry) -> String {
    entry
        .origin
        .clone()
        .unwrap_or_else(|| format!("--records {}", entry.path.display()))
}

/// Refuses a record named twice (the same file and channel, however its
/// path is written, as a horizontal or a vertical component). A file read
/// without a stated channel holds one, so it is channel 1.
fn refuse_twice(entries: &[SuiteEntry]) -> Result<(), BatchError> {
    let id = |p: &PathBuf, s: &RecordSpec| (p.canonicalize().unwrap_or_else(|_| p.clone()), s.channel.unwrap_or(1));
    // ((file, channel), entry) for every component named, in order.
    let files: Vec<((PathBuf, usize), usize)> = entries
        .iter()
        .enumerate()
        .flat_map(|(k, e)| {
            std::iter::once((id(&e.path, &e.spec), k)).chain(e.vertical.as_ref().map(|(v, s)| (id(v, s), k)))
        })
        .collect();
    for (j, ((file, _), k)) in files.iter().enumerate() {
        if let Some((_, i)) = files[..j].iter().find(|(other, _)| *other == files[j].0) {
            let what = if i == k { "as its own vertical" } else { "twice" };
            return Err(input(anyhow!(
                "{}{}: the record {} is listed {what}; list each record once",
                origin(&entries[*i]),
                if i == k {
                    String::new()
                } else {
                    format!(" and {}", origin(&entries[*k]))
                },
                file.display()
            )));
        }
    }
    Ok(())
}

/// The records of the folder `dir` in name order; its other files (not
/// records by their first lines) are skipped, named in one warning line.
fn folder(dir: &Path, spec: RecordSpec, out: &mut Vec<SuiteEntry>) -> Result<(), BatchError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("--records {}", dir.display()))
        .map_err(input)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && !p.file_name().is_some_and(|n| n.to_string_lossy().starts_with('.')))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(input(anyhow!("--records {}: the folder holds no files", dir.display())));
    }
    let (records, skipped): (Vec<PathBuf>, Vec<PathBuf>) = files.into_iter().partition(|p| looks_like_record(p));
    let names = |ps: &[PathBuf]| {
        ps.iter()
            .map(|p| {
                p.file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    if records.is_empty() {
        return Err(input(anyhow!(
            "--records {}: no file in the folder is a record ({})",
            dir.display(),
            names(&skipped)
        )));
    }
    if !skipped.is_empty() {
        eprintln!(
            "warning: --records {}: skipped {} file(s) that are not records: {}",
            dir.display(),
            skipped.len(),
            names(&skipped)
        );
    }
    out.extend(records.into_iter().map(|p| SuiteEntry::file(p, spec)));
    Ok(())
}

/// Whether the file at `path` is a ground-motion record by the reader's
/// grammar (`io::record::read_record_as`): a `.at2` file, a 4th line with
/// `NPTS` (an AT2 header), or text whose first line that is not blank or a
/// comment starts with a number, or whose second does (after a header
/// line). A README or a suite list has words there; a broken record still
/// looks like one and is refused by the reader, naming its line.
fn looks_like_record(path: &Path) -> bool {
    if path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("at2"))
    {
        return true;
    }
    let mut bytes = Vec::new();
    let Ok(file) = std::fs::File::open(path) else {
        // Unreadable: taken as a record so that the reader says why.
        return true;
    };
    if file.take(SNIFF_BYTES).read_to_end(&mut bytes).is_err() {
        return true;
    }
    let text = String::from_utf8_lossy(&bytes);
    if crate::io::record::has_record_header(path, &text) {
        return true;
    }
    let lines: Vec<&str> = text.lines().collect();
    if lines.get(3).is_some_and(|l| l.to_ascii_uppercase().contains("NPTS")) {
        return true;
    }
    let comment = |l: &str| l.starts_with('#') || l.starts_with('%') || l.starts_with('!') || l.starts_with("//");
    let numeric = |l: &str| {
        l.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .find(|f| !f.is_empty())
            .is_some_and(|f| f.replace(['D', 'd'], "e").parse::<f64>().is_ok())
    };
    let mut content = lines
        .iter()
        .map(|l| l.trim().trim_start_matches('\u{feff}'))
        .filter(|l| !l.is_empty() && !comment(l));
    let first = content.next();
    let second = content.next();
    first.is_some_and(numeric) || second.is_some_and(numeric)
}

/// Reads the suite list `list` (a regular file of at most
/// [`MAX_SUITE_BYTES`]) into `out`.
fn read_list(list: &Path, spec: RecordSpec, out: &mut Vec<SuiteEntry>) -> Result<(), BatchError> {
    let name = list.display();
    let bad = |what: String| input(anyhow!("--suite {name}: {what}"));
    let meta = std::fs::metadata(list).map_err(|e| bad(e.to_string()))?;
    if meta.is_dir() {
        return Err(bad(format!(
            "is a folder; a suite is a file listing records (for a folder of records use --records {name})"
        )));
    }
    // Only a regular file of bounded size: a device would be read without
    // end and a FIFO would block forever.
    if !meta.is_file() {
        return Err(bad("not a regular file (a suite is read from a file)".into()));
    }
    let too_big = |bytes: u64| {
        bad(format!(
            "{bytes} bytes; a suite list is at most {MAX_SUITE_BYTES} bytes (1 MiB)"
        ))
    };
    if meta.len() > MAX_SUITE_BYTES {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(list)
        .and_then(|f| f.take(MAX_SUITE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| bad(e.to_string()))?;
    if bytes.len() as u64 > MAX_SUITE_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    let text = String::from_utf8(bytes).map_err(|_| bad("not UTF-8 text".into()))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let dir = list.parent().unwrap_or(Path::new("."));
    for (i, line) in text.lines().enumerate() {
        let at = format!("{name}:{}", i + 1);
        let Some(line) = suite_line(line).map_err(|e| input(anyhow!("{at}: {e}")))? else {
            continue;
        };
        let component = |c: Component<'_>| -> Result<(PathBuf, RecordSpec), BatchError> {
            let (path, unit) = (c.path, c.unit);
            let mut s = spec;
            if c.channel.is_some() {
                s.channel = c.channel;
            }
            if let Some(u) = unit {
                s.unit = Some(AccelUnit::parse(u).ok_or_else(|| {
                    input(anyhow!(
                        "{at}: unknown unit {u:?} (known: g, m/s2, cm/s2; a path with spaces goes in double quotes)"
                    ))
                })?);
            }
            let p = PathBuf::from(path);
            Ok((if p.is_absolute() { p } else { dir.join(p) }, s))
        };
        let (path, s) = component(line.horizontal)?;
        let vertical = line.vertical.map(component).transpose()?;
        out.push(SuiteEntry {
            path,
            spec: s,
            vertical,
            origin: Some(at),
        });
    }
    Ok(())
}

/// One suite line's components: `(PATH, UNIT)` of the horizontal and of
/// the vertical, if named.
#[derive(Debug, PartialEq)]
struct SuiteLine<'a> {
    horizontal: Component<'a>,
    vertical: Option<Component<'a>>,
}

/// One component of a suite line: PATH, UNIT and channel.
#[derive(Debug, PartialEq)]
struct Component<'a> {
    path: &'a str,
    unit: Option<&'a str>,
    channel: Option<usize>,
}

/// The components of one suite line, `None` for a blank or comment line.
fn suite_line(line: &str) -> Result<Option<SuiteLine<'_>>, String> {
    let Some((horizontal, rest)) = component(line)? else {
        return Ok(None);
    };
    let vertical = match rest {
        None => None,
        Some(v) => match component(v)? {
            Some((c, None)) => Some(c),
            Some((_, Some(_))) => {
                return Err(format!("a line pairs one horizontal with one vertical: {line:?}"));
            }
            None => return Err(format!("`+` names no vertical record after it in {line:?}")),
        },
    };
    Ok(Some(SuiteLine { horizontal, vertical }))
}

/// A component, and the text after a `+` word that follows it.
type Fields<'a> = (Component<'a>, Option<&'a str>);

/// The PATH and UNIT at the start of `line`, and the text after a `+`
/// word that follows them (a vertical component); `None` for a blank or
/// comment line (grammar in the module docs).
fn component(line: &str) -> Result<Option<Fields<'_>>, String> {
    let line = line.trim();
    if line.is_empty() || line.starts_with('#') {
        return Ok(None);
    }
    let (path, rest) = if let Some(quoted) = line.strip_prefix('"') {
        let Some(end) = quoted.find('"') else {
            return Err(format!("unclosed quote in {line:?}"));
        };
        let rest = &quoted[end + 1..];
        if !rest.is_empty() && !rest.starts_with(char::is_whitespace) {
            return Err(format!("expected a space or tab after the closing quote in {line:?}"));
        }
        (&quoted[..end], rest)
    } else if let Some((path, rest)) = line
        .split_once('\t')
        // A tab after a `+` word belongs to the vertical's path.
        .filter(|(path, _)| !path.split_whitespace().any(|w| w == "+"))
    {
        (path.trim_end(), rest)
    } else {
        line.split_once(char::is_whitespace).unwrap_or((line, ""))
    };
    if path.is_empty() {
        return Err(format!("empty path in {line:?}"));
    }
    // The words after the path up to a comment or a `+` word: at most one
    // UNIT and one `channel=N`; what follows the `+` is the vertical
    // component's own.
    let mut c = Component {
        path,
        unit: None,
        channel: None,
    };
    let mut rest = rest;
    let too_many = || {
        format!(
            "expected `PATH [UNIT] [channel=N] [+ VPATH [UNIT] [channel=N]]`, found {line:?} (a path with spaces goes in double quotes or before a tab)"
        )
    };
    loop {
        let word_start = rest.len() - rest.trim_start().len();
        let tail = &rest[word_start..];
        let word = tail.split(char::is_whitespace).next().unwrap_or("");
        if word.is_empty() || word.starts_with('#') {
            return Ok(Some((c, None)));
        }
        if word == "+" {
            return Ok(Some((c, Some(tail[1..].trim()))));
        }
        if let Some(n) = word.strip_prefix("channel=") {
            if c.channel.is_some() {
                return Err(too_many());
            }
            c.channel = Some(
                n.parse::<usize>()
                    .ok()
                    .filter(|&n| n >= 1)
                    .ok_or_else(|| format!("{word}: a channel is a whole number from 1"))?,
            );
        } else if c.unit.is_some() {
            return Err(too_many());
        } else {
            c.unit = Some(word);
        }
        rest = &tail[word.len()..];
    }
}

#[cfg(test)]
mod tests {
    use super::{Component, SuiteLine, suite_line};

    fn c<'a>(path: &'a str, unit: Option<&'a str>) -> Component<'a> {
        Component {
            path,
            unit,
            channel: None,
        }
    }

    /// A line of one horizontal record.
    fn one<'a>(path: &'a str, unit: Option<&'a str>) -> Option<SuiteLine<'a>> {
        Some(SuiteLine {
            horizontal: c(path, unit),
            vertical: None,
        })
    }

    #[test]
    fn suite_lines_take_quotes_tabs_and_trailing_comments() {
        let fields = suite_line;
        assert_eq!(fields("a.dat g").unwrap(), one("a.dat", Some("g")));
        assert_eq!(fields("  a.dat  ").unwrap(), one("a.dat", None));
        assert_eq!(fields("\"a b.dat\" m/s2 # Kobe").unwrap(), one("a b.dat", Some("m/s2")));
        assert_eq!(fields("a b.dat\tg").unwrap(), one("a b.dat", Some("g")));
        assert_eq!(fields("a b.dat\t# no unit").unwrap(), one("a b.dat", None));
        assert_eq!(fields("a.dat # note").unwrap(), one("a.dat", None));
        assert_eq!(fields("a.dat # note + b.dat g").unwrap(), one("a.dat", None));
        assert_eq!(fields("a#1.dat g").unwrap(), one("a#1.dat", Some("g")));
        assert_eq!(fields("# all comment").unwrap(), None);
        assert_eq!(fields("   ").unwrap(), None);
        assert!(fields("\"a b.dat g").unwrap_err().contains("unclosed quote"));
        assert!(fields("a b.dat g").unwrap_err().contains("double quotes"));
        assert!(fields("\"a\"g").is_err());
    }

    #[test]
    fn a_suite_line_pairs_a_horizontal_with_its_vertical_after_a_plus_word() {
        let pair = |h: (&'static str, Option<&'static str>), v: (&'static str, Option<&'static str>)| {
            Some(SuiteLine {
                horizontal: c(h.0, h.1),
                vertical: Some(c(v.0, v.1)),
            })
        };
        assert_eq!(
            suite_line("h.dat g + v.dat g").unwrap(),
            pair(("h.dat", Some("g")), ("v.dat", Some("g")))
        );
        assert_eq!(
            suite_line("h.dat + v.dat cm/s2 # Kobe").unwrap(),
            pair(("h.dat", None), ("v.dat", Some("cm/s2")))
        );
        assert_eq!(
            suite_line("\"a h.dat\" m/s2 + \"a v.dat\" m/s2").unwrap(),
            pair(("a h.dat", Some("m/s2")), ("a v.dat", Some("m/s2")))
        );
        assert_eq!(
            suite_line("h.dat\tg\t+\tv w.dat\tg").unwrap(),
            pair(("h.dat", Some("g")), ("v w.dat", Some("g")))
        );
        // A `+` inside a file name is part of it.
        assert_eq!(suite_line("a+b.dat g").unwrap(), one("a+b.dat", Some("g")));
        for bad in [
            "h.dat g +",
            "h.dat g + # none",
            "h.dat + v.dat g + w.dat g",
            "h.dat g x + v.dat",
        ] {
            assert!(suite_line(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_channel_word_picks_each_component_of_one_multichannel_file() {
        let line = suite_line("st.v2 channel=1 + st.v2 channel=2").unwrap().unwrap();
        assert_eq!(
            line.horizontal,
            Component {
                path: "st.v2",
                unit: None,
                channel: Some(1)
            }
        );
        assert_eq!(line.vertical.map(|v| (v.path, v.channel)), Some(("st.v2", Some(2))));
        let line = suite_line("st.v2 g channel=3").unwrap().unwrap();
        assert_eq!((line.horizontal.unit, line.horizontal.channel), (Some("g"), Some(3)));
        for bad in [
            "st.v2 channel=0",
            "st.v2 channel=x",
            "st.v2 channel=1 channel=2",
            "st.v2 g cm/s2",
        ] {
            assert!(suite_line(bad).is_err(), "{bad}");
        }
    }
}

#[cfg(test)]
mod channel_tests {
    use super::*;
    use crate::io::record::cosmos_text::{Channel, cosmos_file, damped_sine};
    use crate::io::record::read_record_as;

    #[test]
    fn one_station_file_gives_a_suite_line_its_horizontal_and_its_vertical_by_channel() {
        let dir = std::env::temp_dir().join(format!("rocking-suite-channels-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let h = damped_sine(1500, 0.005, 0.105, 1.3, 0.8);
        let v = damped_sine(1200, 0.005, 0.0488, 4.1, 1.5);
        let file = cosmos_file(
            &[
                Channel::v1("360 deg", 5.0, h.clone()),
                Channel::v1("Up", 5.0, v.clone()),
            ],
            true,
        );
        std::fs::write(dir.join("st.v1"), file.text).unwrap();
        let list = dir.join("suite.txt");
        std::fs::write(&list, "st.v1 channel=1 + st.v1 channel=2\n").unwrap();
        let entries = suite(&[], Some(&list), RecordSpec::default()).unwrap();
        assert_eq!(entries.len(), 1);
        let (vp, vs) = entries[0].vertical.clone().unwrap();
        let horizontal = read_record_as(&entries[0].path, &entries[0].spec).unwrap();
        let vertical = read_record_as(&vp, &vs).unwrap();
        // Each channel's peak as written (the writer rounds to 6 decimals).
        let peak = |x: &[f64]| x.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        assert!((horizontal.series.peak_abs_g() - peak(&h)).abs() < 1e-6);
        assert!((vertical.series.peak_abs_g() - peak(&v)).abs() < 1e-6);
        // The same channel on both sides is one record listed twice.
        std::fs::write(&list, "st.v1 channel=1 + st.v1 channel=1\n").unwrap();
        let e = match suite(&[], Some(&list), RecordSpec::default()) {
            Err(BatchError::Input(e)) => e.to_string(),
            other => panic!("{other:?}"),
        };
        assert!(e.contains("suite.txt:1") && e.contains("its own vertical"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
