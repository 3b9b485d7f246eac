//! Reading ground-acceleration records from files: PEER NGA `.AT2`, COSMOS
//! V1/V2 (CESMD, USGS), ESM ASCII, two-column `time accel` text and
//! one-column text with a stated time step, parsed into the model's
//! [`Series`] (accelerations in g).
//!
//! Contract:
//! - Units: times in seconds (s). Accelerations are converted to g here,
//!   once, from the unit a header states (AT2, COSMOS, ESM) or the caller
//!   states ([`RecordSpec::unit`]); a text record whose unit nobody states is
//!   refused ([`RecordError::NoUnit`]), and a stated unit that contradicts
//!   a header is an error ([`RecordError::UnitConflict`]): guessing
//!   units is how objects get mis-designed.
//! - Formats: see [`read_record_as`] for the exact grammar of each (`at2`,
//!   `cosmos`, `esm` and `columns` parse them; `counted` reads the blocks
//!   whose length a header announces; the helpers here are shared).
//! - Channels: a COSMOS file may hold a station's components one after the
//!   other; one of several is read only when the caller names it
//!   ([`RecordSpec::channel`]), never taken silently.
//! - Errors: malformed input is never repaired silently. Every problem is a
//!   one-line [`RecordError`] naming the file and, where one applies, the
//!   1-based line. Reading never panics, whatever the file holds.
//!
//! The series itself (its invariants, interpolation and breakpoints) is the
//! model's, in `model::excitation::record`: the model evaluates a record but
//! never reads a file.

mod at2;
mod columns;
mod cosmos;
#[cfg(test)]
pub(crate) mod cosmos_text;
mod counted;
mod esm;
#[cfg(test)]
mod real_files;
#[cfg(test)]
mod test_helpers;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod written_files;

use std::path::Path;

use crate::model::excitation::record::{MAX_ABS_ACCEL_G, MAX_STEP_S, MIN_STEP_S, Series, step_in_range};
use crate::model::units::AccelUnit;
use at2::parse_at2;
use columns::parse_columns;
use cosmos::parse_cosmos;
use esm::parse_esm;

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
    /// An AT2 header says the series is not an acceleration, or names a
    /// unit that is not one of g, m/s², cm/s².
    #[error("{file}:{line}: not an acceleration record in g, m/s2 or cm/s2: {text:?}")]
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
    /// The AT2 time step is outside [[`MIN_STEP_S`], [`MAX_STEP_S`]] (or
    /// NPTS·DT overflows).
    #[error("{file}:{line}: invalid time step DT = {dt:?} s (need {min:e} s <= DT <= {max} s)", min = MIN_STEP_S, max = MAX_STEP_S)]
    BadStep {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time step read, s.
        dt: f64,
    },
    /// A data line has another number of fields than the format's.
    #[error("{file}:{line}: expected {expected} {}, found {found}", if *expected == 1 { "column (a time step is set)" } else { "columns" })]
    Columns {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// Number of fields the format has (1 or 2).
        expected: usize,
        /// Number of fields found.
        found: usize,
    },
    /// A text record, whose unit nobody stated.
    #[error("{file}: a text record does not say its unit; state it (g, m/s2 or cm/s2)")]
    NoUnit {
        /// The path as given.
        file: String,
    },
    /// An AT2 file whose header names no unit, with none stated.
    #[error("{file}:{line}: the AT2 header names no unit (\"UNITS OF ...\"); state it (g, m/s2 or cm/s2)")]
    HeaderNoUnit {
        /// The path as given.
        file: String,
        /// 1-based line of the description.
        line: usize,
    },
    /// A stated unit contradicts the AT2 header's.
    #[error("{file}:{line}: the header says the unit is {header}, but {stated} was stated")]
    UnitConflict {
        /// The path as given.
        file: String,
        /// 1-based line of the header's unit.
        line: usize,
        /// The header's unit.
        header: AccelUnit,
        /// The stated unit.
        stated: AccelUnit,
    },
    /// One value per line and no time step stated.
    #[error("{file}:{line}: one value per line: a one-column record needs its time step (s) stated")]
    NoStep {
        /// The path as given.
        file: String,
        /// 1-based line of the first value.
        line: usize,
    },
    /// A stated time step outside [[`MIN_STEP_S`], [`MAX_STEP_S`]].
    #[error("{file}: invalid time step {dt:?} s (need {min:e} s <= dt <= {max} s)", min = MIN_STEP_S, max = MAX_STEP_S)]
    StatedStep {
        /// The path as given.
        file: String,
        /// The step stated, s.
        dt: f64,
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
    /// Two times of a two-column file are closer than [`MIN_STEP_S`] or
    /// farther apart than [`MAX_STEP_S`].
    #[error("{file}:{line}: time step {step:?} s from the previous sample (at {previous:?} s) is outside [{min:e} s, {max} s]", min = MIN_STEP_S, max = MAX_STEP_S)]
    StepOutOfRange {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The step, s.
        step: f64,
        /// The previous sample's time, s.
        previous: f64,
    },
    /// |acceleration| exceeds [`MAX_ABS_ACCEL_G`] (after conversion to g).
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
    /// A COSMOS header that does not follow the format (a count line that
    /// cannot be read, a block that ends early, an unknown time step).
    #[error("{file}:{line}: COSMOS header: {what}")]
    Cosmos {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// An ESM header without a key the record needs.
    #[error("{file}:{line}: the header (ending here) has no {key} line")]
    MissingKey {
        /// The path as given.
        file: String,
        /// 1-based line where the header ends.
        line: usize,
        /// The key, as the format writes it (`NDATA`).
        key: &'static str,
    },
    /// A header value that is not what its key needs (a count that is not
    /// a whole number).
    #[error("{file}:{line}: cannot read the header value {text:?}")]
    BadValue {
        /// The path as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The header line (shortened).
        text: String,
    },
    /// A COSMOS or ESM header whose unit is empty, with none stated.
    #[error("{file}:{line}: the header states no unit; state it (g, m/s2 or cm/s2)")]
    NoHeaderUnit {
        /// The path as given.
        file: String,
        /// 1-based line where the unit belongs.
        line: usize,
    },
    /// A file of several channels (a station's three components), and no
    /// channel stated: taking one silently could take the wrong one.
    #[error("{file}: holds {count} channels ({names}); state which one to read (1 to {count})")]
    Channels {
        /// The path as given.
        file: String,
        /// How many channels the file holds.
        count: usize,
        /// `1: 360 deg; 2: Up; 3: 90 deg`.
        names: String,
    },
    /// A stated channel the file does not hold.
    #[error("{file}: no channel {channel}: the file holds {count} ({names})")]
    NoSuchChannel {
        /// The path as given.
        file: String,
        /// The channel stated, 1-based.
        channel: usize,
        /// How many channels the file holds.
        count: usize,
        /// `1: 360 deg; 2: Up; 3: 90 deg`.
        names: String,
    },
    /// A channel other than 1 stated for a format that holds one series.
    #[error("{file}: channel {channel} stated, but a {format} file holds one channel")]
    OneChannel {
        /// The path as given.
        file: String,
        /// The channel stated, 1-based.
        channel: usize,
        /// The format's name.
        format: &'static str,
    },
    /// A block of values longer or shorter than its header announces (a
    /// truncated file, a count mismatch).
    #[error("{file}:{line}: {found} values where line {announced_at} announces {expected}")]
    DataCount {
        /// The path as given.
        file: String,
        /// 1-based line where the block ended.
        line: usize,
        /// The count announced.
        expected: usize,
        /// The values found.
        found: usize,
        /// 1-based line of the announcement.
        announced_at: usize,
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

thread_local! {
    /// Records parsed on this thread ([`reads_on_this_thread`]).
    static READS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// How many records (files, or shipped records' bytes) this thread has
/// parsed so far: [`read_record_as`] and [`read_record_bytes`] count one
/// each. It exists for tests, which check with it that an edit which must
/// not read its scene's record again (a slider drag) reads none. Counted
/// per thread so that tests running side by side do not see each other's
/// reads; the app's edits resolve on its own thread.
pub fn reads_on_this_thread() -> usize {
    READS.with(std::cell::Cell::get)
}

/// Largest record file read, bytes: a day of 200 Hz samples in text is
/// about 50 MB; beyond 200 MB a file is not a ground-motion record.
pub(crate) const MAX_RECORD_BYTES: u64 = 200 << 20;

/// What the caller states about a record file: its unit and, for a
/// one-column file, its time step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RecordSpec {
    /// The unit of the accelerations. Required for text records; for an
    /// AT2 file it must agree with the header (or supply the unit a header
    /// leaves out).
    pub unit: Option<AccelUnit>,
    /// Time step, s, of a one-column file (sample k at k·dt). When set the
    /// file must have one value per line; when not, two (time, accel).
    pub dt: Option<f64>,
    /// The channel to read, 1-based, from a COSMOS file that holds several
    /// (a station's components one after the other). `None` reads a file
    /// of one channel and refuses one of several
    /// ([`RecordError::Channels`]); the other formats hold one channel, so
    /// only 1 may be stated for them.
    pub channel: Option<usize>,
}

impl RecordSpec {
    /// A record in `unit`, of one channel.
    pub fn stated(unit: AccelUnit) -> Self {
        Self {
            unit: Some(unit),
            dt: None,
            channel: None,
        }
    }
}

/// The format a record was read in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordFormat {
    /// PEER NGA `.AT2`.
    At2,
    /// COSMOS V1: uncorrected acceleration.
    CosmosV1,
    /// COSMOS V2: corrected acceleration.
    CosmosV2,
    /// ESM ASCII (`.ASC`).
    Esm,
    /// Two columns: time (s) and acceleration.
    TwoColumn,
    /// One column of accelerations at a stated time step.
    OneColumn,
}

impl RecordFormat {
    /// The format's name in outputs: `at2`, `cosmos-v1`, `cosmos-v2`,
    /// `esm`, `two-column`, `one-column`.
    pub fn name(self) -> &'static str {
        match self {
            RecordFormat::At2 => "at2",
            RecordFormat::CosmosV1 => "cosmos-v1",
            RecordFormat::CosmosV2 => "cosmos-v2",
            RecordFormat::Esm => "esm",
            RecordFormat::TwoColumn => "two-column",
            RecordFormat::OneColumn => "one-column",
        }
    }
}

/// A record as read: its samples in g, and how they were read.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedRecord {
    /// Times in s, accelerations converted to g.
    pub series: Series,
    /// The unit the file's accelerations were in.
    pub unit: AccelUnit,
    /// The format.
    pub format: RecordFormat,
    /// CRC-32 (IEEE) of the file's bytes, to notice a changed file.
    pub crc32: u32,
}

/// Reads a ground-acceleration record from `path`, converting its
/// accelerations from their unit to g.
///
/// Five formats are recognised, chosen by extension, else by header:
/// - **PEER NGA `.AT2`**, chosen when the extension is `.at2` (any case) or
///   the 4th line is not a comment and contains `NPTS`. Four header lines: a
///   title, the event/station, the series description (it must be an
///   acceleration; its `UNITS OF x` gives the unit: `G`, `CM/S/S`,
///   `CM/SEC/SEC`, `M/S/S`, ...), then NPTS and DT in any of the forms
///   `NPTS=  5590, DT=   .0050 SEC`, `NPTS=5590 DT=0.005` (commas and a
///   trailing `SEC` optional) or `  5590   0.00500   NPTS, DT`. Then
///   exactly NPTS values in free format (whitespace, commas or semicolons;
///   E or Fortran D exponents, e.g. `-.1234567E-02`). Sample k is at k·DT s.
/// - **COSMOS V1/V2** (v1.20), chosen when the extension is `.v1`, `.v2`,
///   `.v1c` or `.v2c` (any case) or the first line says `(Format v`. Per
///   channel: the text header (its first line `Uncorrected acceleration` or
///   `Corrected acceleration`, with the count of text lines), the integer
///   and real headers (each after a line `N ...-header values follow on M
///   lines, Format= (...)`), the comment lines, then a data line `NPTS
///   acceleration pts, ..., units=UNIT (CODE), Format=(...)` and NPTS
///   values (separated by spaces, or in the stated fixed-width fields).
///   The unit is the data line's (code 02 = g, 04 or 10 = cm/s²); the time
///   step is real-header value 62 (ms). Velocity or displacement blocks
///   after the acceleration are not read; a first block or a header
///   parameter (integer-header value 2) other than acceleration is refused.
///   A file of several channels needs `spec.channel`.
/// - **ESM ASCII** (`.ASC`), chosen when the first line is `KEY: value` and
///   a `SAMPLING_INTERVAL_S:` line follows: `NDATA` values at
///   `SAMPLING_INTERVAL_S` s in `UNITS`; a `DATA_TYPE` other than
///   `ACCELERATION` is refused.
/// - **Two-column text** (no `spec.dt`): `time_s accel` per line.
/// - **One-column text** (`spec.dt` set): one acceleration per line, sample
///   k at k·dt s.
///
/// In text files fields are separated by whitespace, commas and/or
/// semicolons; blank lines and comment lines (starting with `#`, `%`, `!`
/// or `//` after trimming) are ignored; the first other line may be a
/// header, recognised by a first field that is not a number. Times are in
/// s, the first >= 0, strictly increasing.
///
/// # Errors
/// A [`RecordError`] naming the file (as given) and the 1-based line for: an
/// I/O failure, a directory, a device or FIFO, a file over
/// [`MAX_RECORD_BYTES`], an empty file, a bad AT2 header (unparseable
/// NPTS/DT, NPTS = 0, not an acceleration), a time step (stated, DT or
/// between two times) outside [[`MIN_STEP_S`], [`MAX_STEP_S`]] s, a unit
/// nobody states or
/// that contradicts the header, a file that is not an acceleration, a
/// COSMOS file of several channels with none stated (or a channel it does
/// not hold), a one-column file without a time step, a
/// count of values other than the header's, a wrong number of columns, a field that
/// is not a finite number, a negative or non-increasing time,
/// |a| > [`MAX_ABS_ACCEL_G`] g, or fewer than 2 samples. Never panics.
pub fn read_record_as(path: &Path, spec: &RecordSpec) -> Result<LoadedRecord, RecordError> {
    let file = path.display().to_string();
    if let Some(dt) = spec.dt
        && !step_in_range(dt)
    {
        return Err(RecordError::StatedStep { file, dt });
    }
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
    read_record_bytes(&file, &bytes, spec)
}

/// Reads a record from its bytes, as [`read_record_as`] reads a file's:
/// `name` is the name errors give and whose extension (`.at2`, `.v2`, ...) chooses the
/// format, as a file's path does. For the records shipped in the binary
/// (`io::shipped`).
///
/// # Errors
/// As [`read_record_as`], less the file system's.
pub(crate) fn read_record_bytes(name: &str, bytes: &[u8], spec: &RecordSpec) -> Result<LoadedRecord, RecordError> {
    READS.with(|n| n.set(n.get() + 1));
    let file = name.to_string();
    if let Some(dt) = spec.dt
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(RecordError::StatedStep { file, dt });
    }
    let path = Path::new(name);
    let crc32 = crc32fast::hash(bytes);
    // Lossy: station names in old headers or comments may be Latin-1; a
    // replacement character in a data field fails as "not a number".
    let text = String::from_utf8_lossy(bytes);
    let lines: Vec<&str> = text
        .split('\n')
        .map(|line| line.strip_suffix('\r').unwrap_or(line))
        .collect();
    if lines.iter().all(|line| line.trim().is_empty()) {
        return Err(RecordError::Empty { file });
    }
    let (series, unit, format) = match detect(path, &lines) {
        Detected::At2 => {
            let (series, unit) = parse_at2(&file, &lines, spec.unit)?;
            (series, unit, RecordFormat::At2)
        }
        Detected::Cosmos => parse_cosmos(&file, &lines, spec.unit, spec.channel)?,
        Detected::Esm => {
            let (series, unit) = parse_esm(&file, &lines, spec.unit)?;
            (series, unit, RecordFormat::Esm)
        }
        Detected::Text => {
            let Some(unit) = spec.unit else {
                return Err(RecordError::NoUnit { file });
            };
            let (series, format) = parse_columns(&file, &lines, unit, spec.dt)?;
            (series, unit, format)
        }
    };
    // COSMOS chose its channel; the other formats hold one, channel 1.
    let one_channel = !matches!(format, RecordFormat::CosmosV1 | RecordFormat::CosmosV2);
    if let Some(channel) = spec.channel
        && channel != 1
        && one_channel
    {
        return Err(RecordError::OneChannel {
            file,
            channel,
            format: format.name(),
        });
    }
    Ok(LoadedRecord {
        series,
        unit,
        format,
        crc32,
    })
}

/// The grammar a file is read with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Detected {
    /// PEER NGA `.AT2`.
    At2,
    /// COSMOS V1 or V2.
    Cosmos,
    /// ESM ASCII.
    Esm,
    /// One or two columns of text.
    Text,
}

/// The extensions COSMOS files carry (any case): `.v1`, `.v2` and CESMD's
/// `.v1c`, `.v2c`. A CSMIP (DMG) file may carry `.v1`/`.v2` too; the COSMOS
/// reader refuses it, naming line 1, rather than reading it as text.
const COSMOS_EXTENSIONS: [&str; 4] = ["v1", "v2", "v1c", "v2c"];

/// Chooses the grammar: by extension (`.at2`; `.v1`, `.v2`, `.v1c`,
/// `.v2c`), else by the header: an AT2 count line (4th line with `NPTS`), a
/// COSMOS first line (`(Format v...`), an ESM header (`KEY: value` lines
/// with `SAMPLING_INTERVAL_S:`); text otherwise.
fn detect(path: &Path, lines: &[&str]) -> Detected {
    let extension = path.extension().and_then(|ext| ext.to_str()).unwrap_or_default();
    if extension.eq_ignore_ascii_case("at2") {
        return Detected::At2;
    }
    if COSMOS_EXTENSIONS.iter().any(|e| extension.eq_ignore_ascii_case(e)) {
        return Detected::Cosmos;
    }
    let first = lines.iter().find(|l| !l.trim().is_empty()).copied().unwrap_or_default();
    if cosmos::is_cosmos_start(first) {
        return Detected::Cosmos;
    }
    if esm::is_esm(lines) {
        return Detected::Esm;
    }
    let at2_header = lines
        .get(3)
        .is_some_and(|line| !is_comment(line.trim()) && line.to_ascii_uppercase().contains("NPTS"));
    if at2_header { Detected::At2 } else { Detected::Text }
}

/// Whether a file named `path` whose first bytes are `head` is a record in
/// a format with a header (AT2, COSMOS, ESM), by its extension or its
/// header lines, as [`read_record_as`] chooses the format. For tools that
/// sort records from other files in a folder.
pub(crate) fn has_record_header(path: &Path, head: &str) -> bool {
    let lines: Vec<&str> = head
        .split('\n')
        .map(|line| line.strip_suffix('\r').unwrap_or(line))
        .collect();
    detect(path, &lines) != Detected::Text
}

/// Whether a trimmed text line is a comment.
fn is_comment(line: &str) -> bool {
    line.starts_with('#') || line.starts_with('%') || line.starts_with('!') || line.starts_with("//")
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

/// The fields of a data line: separated by whitespace, commas and/or
/// semicolons.
/// The record's unit: the header's or the one the caller stated, which
/// must agree where both are given (`line`: where the header's unit
/// stands). Neither is the error `neither` makes of the file and line:
/// a unit is never guessed.
fn agreed_unit(
    file: &str,
    line: usize,
    header: Option<AccelUnit>,
    stated: Option<AccelUnit>,
    neither: fn(String, usize) -> RecordError,
) -> Result<AccelUnit, RecordError> {
    match (header, stated) {
        (Some(header), Some(stated)) if header != stated => Err(RecordError::UnitConflict {
            file: file.to_owned(),
            line,
            header,
            stated,
        }),
        (Some(unit), _) | (None, Some(unit)) => Ok(unit),
        (None, None) => Err(neither(file.to_owned(), line)),
    }
}

fn fields(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
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
