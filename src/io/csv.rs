//! CSV files through the `csv` crate: every file's rows are a serde struct
//! ([`Row`]) whose field names are its header, so header and rows cannot
//! drift apart; reading a file checks its header, its column count and
//! every cell's type, naming the file and line of a bad row.
//!
//! Numbers are written with Rust's shortest round-trip form (`{:?}`: `1.0`,
//! `0.30000000000000004`, `1e-5`), so a value read back is bit-identical
//! and the files are the same bytes as before the `csv` crate wrote them.

use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A number cell: written in shortest round-trip form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

/// What a [`Num`] that is NaN or infinite writes: a cell no text cell can
/// hold, so that [`has_non_finite`] finds non-finite numbers and nothing
/// else. A NUL byte cannot occur in a path (record names are file stems)
/// nor in the fixed words (end states, intensity measures) these files
/// hold, whereas `inf` and `nan` occur in names (`elcentro-infill`).
pub(crate) const NON_FINITE_CELL: &str = "\0non-finite";

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.collect_str(&format_args!("{:?}", self.0))
        } else {
            s.serialize_str(NON_FINITE_CELL)
        }
    }
}

/// Whether CSV text made by [`to_string`] holds a non-finite number (a
/// [`Num`] that was NaN or infinite). Text cells never count, whatever
/// they spell.
pub(crate) fn has_non_finite(text: &str) -> bool {
    text.contains(NON_FINITE_CELL)
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = <std::borrow::Cow<'de, str>>::deserialize(d)?;
        match text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Num(x)),
            Ok(_) => Err(serde::de::Error::custom(format!("non-finite number {text:?}"))),
            Err(_) => Err(serde::de::Error::custom(format!("not a number: {text:?}"))),
        }
    }
}

/// The row of one kind of CSV file.
pub trait Row {
    /// The header: the field names in order (checked against the serde
    /// field names by each row type's test, [`header_of`]).
    const HEADER: &'static [&'static str];
}

/// Declares a row struct and its [`Row`] impl at once: the header is the
/// field names in order, written once here instead of again in a `HEADER`
/// list that could drift from them (serde writes the same names, which
/// each file's `header_of` test checks).
macro_rules! csv_row {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $($(#[$field_meta:meta])* $field_vis:vis $field:ident : $ty:ty),* $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis struct $name {
            $($(#[$field_meta])* $field_vis $field: $ty),*
        }

        impl $crate::io::csv::Row for $name {
            const HEADER: &'static [&'static str] = &[$(stringify!($field)),*];
        }
    };
}
pub(crate) use csv_row;

/// The header line `Row::HEADER` joined with commas (no newline).
pub fn header<R: Row>() -> String {
    R::HEADER.join(",")
}

/// The header serde writes for `row` (for tests that `Row::HEADER` is the
/// struct's fields).
pub fn header_of<R: Row + Serialize>(row: &R) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    let _ = w.serialize(row);
    let bytes = w.into_inner().unwrap_or_default();
    String::from_utf8_lossy(&bytes)
        .lines()
        .next()
        .unwrap_or_default()
        .to_string()
}

/// `rows` as a CSV file: the header line, then one line per row.
pub fn to_string<R: Row + Serialize>(rows: impl IntoIterator<Item = R>) -> String {
    let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(Vec::new());
    // Writing to a Vec cannot fail, and every cell is a number or a plain
    // name, so serialisation cannot either; an error would be a bug here.
    w.write_record(R::HEADER).expect("CSV header into memory");
    for row in rows {
        w.serialize(row).expect("CSV row into memory");
    }
    String::from_utf8(w.into_inner().expect("CSV into memory")).expect("CSV is UTF-8")
}

/// A CSV file that cannot be read as rows of its kind.
#[derive(Debug, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct CsvError {
    /// The file.
    pub file: String,
    /// 1-based line.
    pub line: u64,
    /// What is wrong.
    pub message: String,
}

/// Reads the rows of the CSV file `path`, each with its 1-based line: the
/// header must be `R::HEADER`, every row must have its columns with cells
/// of the right types.
pub fn read<R: Row + DeserializeOwned>(path: &Path) -> Result<Vec<(u64, R)>, CsvError> {
    let file = path.display().to_string();
    let err = |line: u64, message: String| CsvError {
        file: file.clone(),
        line,
        message,
    };
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_path(path)
        .map_err(|e| err(1, e.to_string()))?;
    let found = reader.headers().map_err(|e| err(1, e.to_string()))?.clone();
    if found.iter().ne(R::HEADER.iter().copied()) {
        return Err(err(1, format!("expected the header `{}`", header::<R>())));
    }
    let mut out = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, csv::Position::line);
            err(line, format!("expected `{}`: {e}", header::<R>()))
        })?;
        let line = record.position().map_or(0, csv::Position::line);
        let row: R = record
            .deserialize(Some(&found))
            .map_err(|e| err(line, format!("expected `{}`: {e}", header::<R>())))?;
        out.push((line, row));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Pair {
        name: String,
        value: Num,
        extra: Option<Num>,
    }

    impl Row for Pair {
        const HEADER: &'static [&'static str] = &["name", "value", "extra"];
    }

    fn pair(name: &str, value: f64, extra: Option<f64>) -> Pair {
        Pair {
            name: name.into(),
            value: Num(value),
            extra: extra.map(Num),
        }
    }

    fn file(name: &str, text: &str) -> std::path::PathBuf {
        let p = std::env::temp_dir().join(format!("rocking-csv-{}-{name}.csv", std::process::id()));
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn rows_round_trip_bit_for_bit() {
        let rows = vec![pair("a", 0.1 + 0.2, None), pair("b", -1e-300, Some(2.0))];
        let text = to_string(rows.iter().map(|r| pair(&r.name, r.value.0, r.extra.map(|x| x.0))));
        assert_eq!(text, "name,value,extra\na,0.30000000000000004,\nb,-1e-300,2.0\n");
        assert_eq!(header_of(&rows[0]), header::<Pair>());
        let p = file("round", &text);
        let back: Vec<(u64, Pair)> = read(&p).unwrap();
        assert_eq!(back.iter().map(|(l, _)| *l).collect::<Vec<_>>(), vec![2, 3]);
        assert_eq!(back.into_iter().map(|(_, r)| r).collect::<Vec<_>>(), rows);
        let _ = std::fs::remove_file(p);
    }

    #[test]
    fn only_a_non_finite_number_counts_as_non_finite_not_a_name_that_spells_one() {
        let names = ["elcentro-infill", "inf", "NaN", "-inf", "nan", "Infinity"];
        let text = to_string(names.iter().map(|n| pair(n, 1.5, Some(-2.0))));
        assert!(!has_non_finite(&text), "{text}");
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(has_non_finite(&to_string([pair("a", bad, None)])), "{bad}");
            assert!(has_non_finite(&to_string([pair("a", 1.0, Some(bad))])), "{bad}");
        }
    }

    #[test]
    fn a_bad_file_is_named_with_its_line() {
        let cases = [
            ("header", "name,value\na,1\n", ":1: expected the header"),
            ("short", "name,value,extra\na,1,\nb,2\n", ":3:"),
            ("long", "name,value,extra\na,1,,9\n", ":2:"),
            ("nan", "name,value,extra\na,NaN,\n", ":2:"),
            ("text", "name,value,extra\na,1,x\n", ":2:"),
        ];
        for (name, text, needle) in cases {
            let p = file(name, text);
            let e = read::<Pair>(&p).unwrap_err().to_string();
            assert!(e.contains(needle), "{name}: {e}");
            assert!(e.starts_with(&p.display().to_string()), "{name}: {e}");
            let _ = std::fs::remove_file(p);
        }
    }
}
