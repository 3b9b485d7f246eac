//! Reading ground-acceleration records from files: PEER NGA `.AT2` and
//! two-column `time_s accel_g` text, parsed into the model's [`Series`].
//!
//! Contract:
//! - Units: times in seconds (s), accelerations as fractions of g (a/g,
//!   g = 9.81 m/s²), as the files hold them; no conversion.
//! - Formats: see [`read_record`] for the exact grammar of each (`at2` and
//!   `columns` parse them; the helpers here are shared by both).
//! - Errors: malformed input is never repaired silently. Every problem is a
//!   one-line [`RecordError`] naming the file and, where one applies, the
//!   1-based line. Reading never panics, whatever the file holds.
//!
//! The series itself (its invariants, interpolation and breakpoints) is the
//! model's, in `model::excitation::record`: the model evaluates a record but
//! never reads a file.

mod at2;
mod columns;
#[cfg(test)]
mod tests;

use std::path::Path;

use crate::model::excitation::record::{MAX_ABS_ACCEL_G, Series};
use at2::parse_at2;
use columns::parse_columns;

/// Why a record could not be read. Every message is one line and names the
/// file as given to [`read_record`] and, where one applies, the 1-based line.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The file could not be opened or read (missing, no permission, ...).
    #[error("{file}: {error}")]
    Io {
        /// The path as given.
        file: String,
        /// The underlying error.
        error: std::io::Error,
    },
    /// The path is a directory.
    #[error("{file}: is a directory")]
    IsDirectory {
        /// The path as given.
        file: String,
    },
    /// The path is not a regular file (a device, a FIFO).
    #[error("{file}: not a regular file (a record is read from a file)")]
    NotAFile {
        /// The path as given.
        file: String,
    },
    /// The file is larger than [`MAX_RECORD_BYTES`].
    #[error("{file}: {bytes} bytes; a record file is at most 200 MB")]
    FileTooLarge {
        /// The path as given.
        file: String,
        /// Its size.
        bytes: u64,
    },
    /// The file is empty or holds only whitespace.
    #[error("{file}: empty file")]
    Empty {
        /// The path as given.
        file: String,
    },
    /// An AT2 file ends before its 4 header lines.
    #[error("{file}: AT2 header has {found} lines, expected 4")]
    TruncatedHeader {
        /// The path as given.
        file: String,
        /// Number of lines present.
        found: usize,
    },
    /// An AT2 header says the series is not an acceleration in g (a
    /// velocity or displacement file, or other units).
    #[error("{file}:{line}: not an acceleration record in units of g: {text:?}")]
    Units {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The header line (shortened).
        text: String,
    },
    /// The AT2 header line holding NPTS and DT could not be parsed.
    #[error("{file}:{line}: cannot read NPTS/DT from header {text:?}")]
    Header {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The header line (shortened).
        text: String,
    },
    /// The AT2 header announces NPTS = 0.
    #[error("{file}:{line}: NPTS = 0, the record has no samples")]
    NoSamples {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// The AT2 time step is not a finite positive number (or NPTS·DT
    /// overflows).
    #[error("{file}:{line}: invalid time step DT = {dt} s (need 0 < DT and a finite NPTS*DT)")]
    BadStep {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time step read, s.
        dt: f64,
    },
    /// A two-column line has another number of fields.
    #[error("{file}:{line}: expected 2 columns, found {found}")]
    Columns {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// Number of fields found.
        found: usize,
    },
    /// A field is not a number.
    #[error("{file}:{line}: cannot parse {text:?} as a number")]
    NotANumber {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The field (shortened).
        text: String,
    },
    /// A field is NaN or infinite (or overflows to infinity).
    #[error("{file}:{line}: non-finite value {text:?}")]
    NonFinite {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The field (shortened).
        text: String,
    },
    /// The first time of a two-column file is negative.
    #[error("{file}:{line}: negative time {time} s")]
    NegativeTime {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time read, s.
        time: f64,
    },
    /// A time of a two-column file does not exceed the previous one.
    #[error("{file}:{line}: time {time} does not increase (previous {previous})")]
    NotIncreasing {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time read, s.
        time: f64,
        /// The previous time, s.
        previous: f64,
    },
    /// |acceleration| exceeds [`MAX_ABS_ACCEL_G`].
    #[error("{file}:{line}: |acceleration| of {value} g exceeds the {max} g sanity limit", max = MAX_ABS_ACCEL_G)]
    TooLarge {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The acceleration read, g.
        value: f64,
    },
    /// An AT2 file holds another number of values than its header's NPTS.
    #[error("{file}: expected {expected} values, found {found}")]
    CountMismatch {
        /// The path as given.
        file: String,
        /// NPTS from the header.
        expected: usize,
        /// Number of values in the file.
        found: usize,
    },
    /// Fewer than 2 samples: no interval to interpolate over.
    #[error("{file}: need at least 2 samples, found {found}")]
    TooFewSamples {
        /// The path as given.
        file: String,
        /// Number of samples found.
        found: usize,
    },
}

/// Largest record file read, bytes: a day of 200 Hz samples in text is
/// about 50 MB; beyond 200 MB a file is not a ground-motion record.
pub const MAX_RECORD_BYTES: u64 = 200 << 20;

/// Reads a ground-acceleration record from `path`.
///
/// Two formats are recognised:
/// - **PEER NGA `.AT2`**, chosen when the extension is `.at2` (any case) or
///   the 4th line is not a `#` comment and contains `NPTS`. Four header
///   lines: a title, the event/station, the series description (it must be
///   an acceleration; if it names `UNITS OF x`, x must be `G`), then NPTS and
///   DT in any of the forms `NPTS=  5590, DT=   .0050 SEC`,
///   `NPTS=5590 DT=0.005` (commas and a trailing `SEC` optional) or
///   `  5590   0.00500   NPTS, DT`. Then exactly NPTS values in free format
///   (whitespace or commas; E or Fortran D exponents, e.g. `-.1234567E-02`).
///   Sample k is at time k·DT s, k = 0..NPTS-1.
/// - **Two-column text** otherwise: `time_s accel_g` per line, separated by
///   whitespace and/or a comma. Blank lines and lines starting with `#`
///   (after trimming) are ignored; the first other line may be a header,
///   recognised by a first field that is not a number.
///
/// Accelerations are in g; times in s, the first >= 0, strictly increasing.
///
/// # Errors
/// A [`RecordError`] naming the file (as given) and the 1-based line for: an
/// I/O failure, a directory, a device or FIFO, a file over
/// [`MAX_RECORD_BYTES`], an empty file, a bad AT2 header (unparseable
/// NPTS/DT, NPTS = 0, DT <= 0, not in g), a count of values other than NPTS,
/// a wrong number of columns, a field that is not a finite number, a negative
/// or non-increasing time, |a| > [`MAX_ABS_ACCEL_G`], or fewer than 2
/// samples. Never panics.
pub fn read_record(path: &Path) -> Result<Series, RecordError> {
    let file = path.display().to_string();
    let io_error = |error| RecordError::Io {
        file: file.clone(),
        error,
    };
    let metadata = std::fs::metadata(path).map_err(io_error)?;
    if metadata.is_dir() {
        return Err(RecordError::IsDirectory { file });
    }
    if !metadata.is_file() {
        return Err(RecordError::NotAFile { file });
    }
    if metadata.len() > MAX_RECORD_BYTES {
        return Err(RecordError::FileTooLarge {
            file,
            bytes: metadata.len(),
        });
    }
    let bytes = std::fs::read(path).map_err(io_error)?;
    // Lossy: station names in old headers or comments may be Latin-1; a
    // replacement character in a data field fails as "not a number".
    let text = String::from_utf8_lossy(&bytes);
    let lines: Vec<&str> = text
        .split('\n')
        .map(|line| line.strip_suffix('\r').unwrap_or(line))
        .collect();
    if lines.iter().all(|line| line.trim().is_empty()) {
        return Err(RecordError::Empty { file });
    }
    let at2_extension = path
        .extension()
        .and_then(|ext| ext.to_str())
        .is_some_and(|ext| ext.eq_ignore_ascii_case("at2"));
    let at2_header = lines
        .get(3)
        .is_some_and(|line| !line.trim_start().starts_with('#') && line.to_ascii_uppercase().contains("NPTS"));
    if at2_extension || at2_header {
        parse_at2(&file, &lines)
    } else {
        parse_columns(&file, &lines)
    }
}

/// Parses a float, also with a Fortran `D` exponent (`1.0D-02`).
fn parse_float(token: &str) -> Option<f64> {
    match token.parse::<f64>() {
        Ok(value) => Some(value),
        Err(_) if token.contains(['D', 'd']) => token.replace(['D', 'd'], "E").parse().ok(),
        Err(_) => None,
    }
}

/// Parses a data field as a finite number.
fn parse_number(file: &str, line: usize, field: &str) -> Result<f64, RecordError> {
    match parse_float(field) {
        Some(value) if value.is_finite() => Ok(value),
        Some(_) => Err(RecordError::NonFinite {
            file: file.to_owned(),
            line,
            text: excerpt(field),
        }),
        None => Err(RecordError::NotANumber {
            file: file.to_owned(),
            line,
            text: excerpt(field),
        }),
    }
}

/// Rejects |acceleration| above [`MAX_ABS_ACCEL_G`].
fn check_accel(file: &str, line: usize, value: f64) -> Result<(), RecordError> {
    if value.abs() > MAX_ABS_ACCEL_G {
        Err(RecordError::TooLarge {
            file: file.to_owned(),
            line,
            value,
        })
    } else {
        Ok(())
    }
}

/// The fields of a data line: separated by whitespace and/or commas.
fn fields(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|field| !field.is_empty())
}
/// A trimmed, shortened copy of `text` for an error message, so that the
/// message stays on one readable line.
fn excerpt(text: &str) -> String {
    const MAX_CHARS: usize = 60;
    let text = text.trim();
    if text.chars().count() > MAX_CHARS {
        let mut short: String = text.chars().take(MAX_CHARS).collect();
        short.push('…');
        short
    } else {
        text.to_owned()
    }
}
