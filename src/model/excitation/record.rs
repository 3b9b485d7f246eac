//! Recorded ground motion: reading acceleration records and sampling them.
//!
//! Contract:
//! - Units: a [`Series`] holds times in seconds (s) and accelerations as
//!   fractions of g (a/g, g = 9.81 m/s²). [`RecordExcitation`] works in the
//!   model's normalised time τ = p·t, where p = sqrt(3 g / (4 R)) [1/s] is the
//!   block's frequency parameter, and returns accelerations in g.
//! - Formats: PEER NGA `.AT2` files and two-column `time_s accel_g` text; see
//!   [`read_record`] for the exact grammar of each.
//! - Interpolation: linear between samples, exact at sample times. The input
//!   is therefore piecewise linear with a kink at every sample;
//!   [`Series::next_sample_after`] and [`RecordExcitation::next_breakpoint`]
//!   tell the integrator where those kinks are so that it can stop on them.
//! - Outside the record: the ground is at rest, so the acceleration is 0
//!   before the first sample time and after the last one (a jump there if the
//!   record does not start or end at 0 g).
//! - Errors: malformed input is never repaired silently. Every problem is a
//!   one-line [`RecordError`] naming the file and, where one applies, the
//!   1-based line. Reading never panics, whatever the file holds.

use std::path::Path;

/// Largest |acceleration| accepted from a record, in g.
///
/// The largest peak ground acceleration ever recorded is about 4 g, so a value
/// above 100 g is a units mix-up (cm/s² or m/s² read as g) or a corrupt file,
/// not ground motion; it is rejected rather than simulated.
pub const MAX_ABS_ACCEL_G: f64 = 100.0;

/// Samples of ground acceleration: accelerations in g at strictly increasing
/// times in seconds, the first at or after t = 0.
///
/// Always holds at least 2 samples, all finite, with |a| <= [`MAX_ABS_ACCEL_G`].
/// Built by [`read_record`] or [`Series::new`], which enforce these invariants.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Sample times, s; strictly increasing, first >= 0.
    times_s: Vec<f64>,
    /// Accelerations at those times, in g.
    accel_g: Vec<f64>,
}

/// Why [`Series::new`] rejected its samples. Indices are 0-based.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// The two vectors have different lengths.
    #[error("{times} times but {values} acceleration values")]
    LengthMismatch {
        /// Number of times given.
        times: usize,
        /// Number of acceleration values given.
        values: usize,
    },
    /// Fewer than 2 samples: no interval to interpolate over.
    #[error("need at least 2 samples, found {found}")]
    TooFewSamples {
        /// Number of samples given.
        found: usize,
    },
    /// A time or an acceleration is NaN or infinite.
    #[error("sample {index}: non-finite time or acceleration")]
    NonFinite {
        /// Index of the offending sample.
        index: usize,
    },
    /// The first time is negative.
    #[error("first time {time} s is negative")]
    NegativeStart {
        /// The first sample time, s.
        time: f64,
    },
    /// A time does not exceed the one before it.
    #[error("sample {index}: time {time} does not increase (previous {previous})")]
    NotIncreasing {
        /// Index of the offending sample.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The previous sample's time, s.
        previous: f64,
    },
    /// |acceleration| exceeds [`MAX_ABS_ACCEL_G`].
    #[error("sample {index}: |acceleration| of {value} g exceeds the {max} g sanity limit", max = MAX_ABS_ACCEL_G)]
    TooLarge {
        /// Index of the offending sample.
        index: usize,
        /// The acceleration, g.
        value: f64,
    },
}

impl Series {
    /// Builds a series from sample times (s) and accelerations (g).
    ///
    /// # Errors
    /// [`SeriesError`] unless the lengths match, there are at least 2
    /// samples, every value is finite, the first time is >= 0, times strictly
    /// increase and every |acceleration| <= [`MAX_ABS_ACCEL_G`].
    pub fn new(times_s: Vec<f64>, accel_g: Vec<f64>) -> Result<Self, SeriesError> {
        if times_s.len() != accel_g.len() {
            return Err(SeriesError::LengthMismatch {
                times: times_s.len(),
                values: accel_g.len(),
            });
        }
        if times_s.len() < 2 {
            return Err(SeriesError::TooFewSamples { found: times_s.len() });
        }
        let mut previous: Option<f64> = None;
        for (index, (&time, &value)) in times_s.iter().zip(&accel_g).enumerate() {
            if !time.is_finite() || !value.is_finite() {
                return Err(SeriesError::NonFinite { index });
            }
            match previous {
                None if time < 0.0 => return Err(SeriesError::NegativeStart { time }),
                Some(previous) if time <= previous => {
                    return Err(SeriesError::NotIncreasing { index, time, previous });
                }
                _ => {}
            }
            if value.abs() > MAX_ABS_ACCEL_G {
                return Err(SeriesError::TooLarge { index, value });
            }
            previous = Some(time);
        }
        Ok(Self { times_s, accel_g })
    }

    /// Sample times, s (strictly increasing, first >= 0).
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }

    /// Sample accelerations, g, one per entry of [`Series::times_s`].
    pub fn accel_g(&self) -> &[f64] {
        &self.accel_g
    }

    /// Number of samples (always >= 2).
    pub fn len(&self) -> usize {
        self.times_s.len()
    }

    /// Always `false`: a series holds at least 2 samples. Provided because
    /// [`Series::len`] is public.
    pub fn is_empty(&self) -> bool {
        self.times_s.is_empty()
    }

    /// Time of the first sample, s. Before it the ground is at rest.
    pub fn start_s(&self) -> f64 {
        self.times_s.first().copied().unwrap_or(0.0)
    }

    /// Duration of the record in s, measured from t = 0 (not from the first
    /// sample): the time of the last sample, after which the ground is at
    /// rest. Measured from 0 because the record sits on the simulation's
    /// absolute time axis, which starts at 0.
    pub fn duration_s(&self) -> f64 {
        self.times_s.last().copied().unwrap_or(0.0)
    }

    /// Largest |acceleration| over the samples, g (the record's PGA). Since the
    /// interpolation is linear it is also the peak of [`Series::accel_at`].
    pub fn peak_abs_g(&self) -> f64 {
        self.accel_g.iter().fold(0.0, |peak, a| peak.max(a.abs()))
    }

    /// Acceleration at time `t_s` (s), in g, by linear interpolation between
    /// the neighbouring samples; exactly the sample value at a sample time.
    ///
    /// Returns 0 for `t_s` before the first sample time or after the last one
    /// (ground at rest), and NaN for a NaN `t_s` so that a bad time is caught
    /// by the integrator's non-finite check rather than hidden. O(log n):
    /// binary search.
    pub fn accel_at(&self, t_s: f64) -> f64 {
        if t_s.is_nan() {
            return f64::NAN;
        }
        // Number of samples at or before t_s.
        let i = self.times_s.partition_point(|&t| t <= t_s);
        let Some(before) = i.checked_sub(1) else {
            return 0.0; // before the first sample
        };
        let (Some(&t0), Some(&a0)) = (self.times_s.get(before), self.accel_g.get(before)) else {
            return 0.0;
        };
        if t0 == t_s {
            return a0;
        }
        match (self.times_s.get(i), self.accel_g.get(i)) {
            (Some(&t1), Some(&a1)) => a0 + (a1 - a0) * ((t_s - t0) / (t1 - t0)),
            _ => 0.0, // after the last sample
        }
    }

    /// The first sample time strictly greater than `t_s`, in s, or `None`
    /// past the last sample (or for a NaN `t_s`). These are the kinks of the
    /// piecewise-linear input, where the integrator should stop. O(log n).
    pub fn next_sample_after(&self, t_s: f64) -> Option<f64> {
        if t_s.is_nan() {
            return None;
        }
        let i = self.times_s.partition_point(|&t| t <= t_s);
        self.times_s.get(i).copied()
    }
}

/// A recorded base excitation in the model's normalised time.
///
/// Conversion: the model's time is τ = p·t with p in 1/s and t in s, so the
/// record is sampled at t = τ / p, and a sample at time t_k (s) lies at
/// τ_k = p·t_k. Each component is multiplied by its scale factor (for
/// amplitude scaling studies); results are in g, the vertical one positive
/// upward.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordExcitation {
    /// Horizontal component.
    horizontal: Series,
    /// Vertical component (positive upward), if any.
    vertical: Option<Series>,
    /// Frequency parameter p, 1/s.
    p: f64,
    /// Scale factor on the horizontal component (dimensionless).
    scale_h: f64,
    /// Scale factor on the vertical component (dimensionless).
    scale_v: f64,
}

impl RecordExcitation {
    /// Combines a horizontal record with an optional vertical one (positive
    /// upward), for a block of frequency parameter `p_per_s` (1/s), scaling
    /// the components by `scale_h` and `scale_v` (dimensionless; 1 replays the
    /// record as recorded).
    ///
    /// `p_per_s` must be finite and > 0; it comes from the block geometry,
    /// which the model validates. Any other value gives meaningless (but not
    /// panicking) results.
    pub fn new(horizontal: Series, vertical: Option<Series>, p_per_s: f64, scale_h: f64, scale_v: f64) -> Self {
        Self {
            horizontal,
            vertical,
            p: p_per_s,
            scale_h,
            scale_v,
        }
    }

    /// The horizontal component.
    pub fn horizontal(&self) -> &Series {
        &self.horizontal
    }

    /// The vertical component (positive upward), if any.
    pub fn vertical(&self) -> Option<&Series> {
        self.vertical.as_ref()
    }

    /// Frequency parameter p, 1/s.
    pub fn p_per_s(&self) -> f64 {
        self.p
    }

    /// Scale factor on the horizontal component.
    pub fn scale_h(&self) -> f64 {
        self.scale_h
    }

    /// Scale factor on the vertical component.
    pub fn scale_v(&self) -> f64 {
        self.scale_v
    }

    /// Ground acceleration `(a_h, a_v)` at normalised time `tau`, in g:
    /// `(scale_h · a_h(τ/p), scale_v · a_v(τ/p))`, with `a_v` positive upward
    /// and 0 when there is no vertical record. Each component is 0 outside
    /// its record (see [`Series::accel_at`]).
    pub fn accel(&self, tau: f64) -> (f64, f64) {
        let t_s = tau / self.p;
        let a_h = self.scale_h * self.horizontal.accel_at(t_s);
        let a_v = match &self.vertical {
            Some(vertical) => self.scale_v * vertical.accel_at(t_s),
            None => 0.0,
        };
        (a_h, a_v)
    }

    /// The smallest τ' > `tau` at which either component has a sample (a
    /// kink of the input), with sample times converted as τ' = p·t_k; `None`
    /// past the last sample of both.
    ///
    /// The comparison is made on p·t_k itself, so the result is strictly
    /// greater than `tau` even when `tau` is a previous breakpoint and `tau/p`
    /// rounds below its sample time.
    pub fn next_breakpoint(&self, tau: f64) -> Option<f64> {
        let h = next_tau(&self.horizontal, tau, self.p);
        let v = self
            .vertical
            .as_ref()
            .and_then(|vertical| next_tau(vertical, tau, self.p));
        match (h, v) {
            (Some(h), Some(v)) => Some(h.min(v)),
            (h, v) => h.or(v),
        }
    }

    /// End of the excitation in τ: p times the larger of the two components'
    /// [`Series::duration_s`]. After it the ground is at rest.
    pub fn end_tau(&self) -> f64 {
        let end_s = match &self.vertical {
            Some(vertical) => self.horizontal.duration_s().max(vertical.duration_s()),
            None => self.horizontal.duration_s(),
        };
        end_s * self.p
    }
}

/// First p·t_k strictly greater than `tau`, searched on p·t_k directly (which
/// is non-decreasing in t_k for p > 0, so the binary search is valid).
fn next_tau(series: &Series, tau: f64, p: f64) -> Option<f64> {
    if tau.is_nan() {
        return None;
    }
    let i = series.times_s.partition_point(|&t| t * p <= tau);
    series.times_s.get(i).map(|&t| t * p)
}

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
/// I/O failure, a directory, an empty file, a bad AT2 header (unparseable
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

/// 1-based number of the AT2 header line holding NPTS and DT.
const AT2_COUNT_LINE: usize = 4;

/// Parses an AT2 file split into lines (see [`read_record`]).
fn parse_at2(file: &str, lines: &[&str]) -> Result<Series, RecordError> {
    let (Some(description), Some(count_line)) = (lines.get(2), lines.get(AT2_COUNT_LINE - 1)) else {
        return Err(RecordError::TruncatedHeader {
            file: file.to_owned(),
            found: lines.len(),
        });
    };
    if !describes_acceleration_in_g(description) {
        return Err(RecordError::Units {
            file: file.to_owned(),
            line: 3,
            text: excerpt(description),
        });
    }
    let Some((npts, dt)) = parse_npts_dt(count_line) else {
        return Err(RecordError::Header {
            file: file.to_owned(),
            line: AT2_COUNT_LINE,
            text: excerpt(count_line),
        });
    };
    if npts == 0 {
        return Err(RecordError::NoSamples {
            file: file.to_owned(),
            line: AT2_COUNT_LINE,
        });
    }
    let bad_step = || RecordError::BadStep {
        file: file.to_owned(),
        line: AT2_COUNT_LINE,
        dt,
    };
    if !(dt.is_finite() && dt > 0.0) {
        return Err(bad_step());
    }
    // Capacity capped: NPTS comes from an untrusted header.
    let mut accel_g = Vec::with_capacity(npts.min(1 << 20));
    let mut found = 0_usize;
    for (index, line) in lines.iter().enumerate().skip(AT2_COUNT_LINE) {
        let line_no = index + 1;
        for field in fields(line) {
            let value = parse_number(file, line_no, field)?;
            check_accel(file, line_no, value)?;
            found += 1;
            if found <= npts {
                accel_g.push(value);
            }
        }
    }
    if found != npts {
        return Err(RecordError::CountMismatch {
            file: file.to_owned(),
            expected: npts,
            found,
        });
    }
    if npts < 2 {
        return Err(RecordError::TooFewSamples {
            file: file.to_owned(),
            found: npts,
        });
    }
    // k·DT rather than a running sum: no accumulated round-off.
    let times_s: Vec<f64> = (0..npts).map(|k| k as f64 * dt).collect();
    if !times_s.last().is_some_and(|t| t.is_finite()) {
        return Err(bad_step());
    }
    Ok(Series { times_s, accel_g })
}

/// Whether an AT2 description line (line 3) allows an acceleration in g:
/// it must not describe a velocity or displacement, and if it names
/// `UNITS OF x`, x must be `G`. Lenient otherwise, since the wording varies
/// between database releases.
fn describes_acceleration_in_g(line: &str) -> bool {
    let upper = line.to_ascii_uppercase();
    if upper.contains("VELOCITY") || upper.contains("DISPLACEMENT") {
        return false;
    }
    const UNITS_OF: &str = "UNITS OF";
    match upper.find(UNITS_OF) {
        Some(position) => upper
            .get(position + UNITS_OF.len()..)
            .and_then(|rest| {
                rest.split(|c: char| !c.is_ascii_alphanumeric() && c != '/')
                    .find(|word| !word.is_empty())
            })
            .is_some_and(|unit| unit == "G"),
        None => true,
    }
}

/// Reads `(NPTS, DT)` from an AT2 count line in any accepted form; `None` if
/// it cannot. DT is returned unchecked.
fn parse_npts_dt(line: &str) -> Option<(usize, f64)> {
    let cleaned: String = line
        .to_ascii_uppercase()
        .chars()
        .map(|c| if c == ',' || c == '=' { ' ' } else { c })
        .collect();
    let tokens: Vec<&str> = cleaned.split_whitespace().collect();
    let after = |key: &str| {
        let position = tokens.iter().position(|token| *token == key)?;
        tokens.get(position + 1).copied()
    };
    // Labelled forms: `NPTS= 5590, DT= .0050 SEC` and `NPTS=5590 DT=0.005`.
    if let (Some(npts), Some(dt)) = (after("NPTS"), after("DT"))
        && let (Some(npts), Some(dt)) = (parse_count(npts), parse_dt(dt))
    {
        return Some((npts, dt));
    }
    // Oldest form: `  5590   0.00500   NPTS, DT`.
    if let [npts, dt, rest @ ..] = tokens.as_slice()
        && rest.contains(&"NPTS")
        && rest.contains(&"DT")
        && let (Some(npts), Some(dt)) = (parse_count(npts), parse_dt(dt))
    {
        return Some((npts, dt));
    }
    None
}

/// Parses a non-negative integer count, also written as `5590.` or `5590.0`.
fn parse_count(token: &str) -> Option<usize> {
    if let Ok(count) = token.parse::<usize>() {
        return Some(count);
    }
    let value = token.parse::<f64>().ok()?;
    // 2^53: every integer below is exact in f64.
    let exact_limit = 9_007_199_254_740_992.0;
    if value >= 0.0 && value < exact_limit && value.fract() == 0.0 {
        usize::try_from(value as u64).ok()
    } else {
        None
    }
}

/// Parses a time step token, allowing a glued unit (`.0050SEC`).
fn parse_dt(token: &str) -> Option<f64> {
    let token = token.strip_suffix("SEC").unwrap_or(token);
    parse_float(token)
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

/// Parses a two-column file split into lines (see [`read_record`]).
fn parse_columns(file: &str, lines: &[&str]) -> Result<Series, RecordError> {
    let mut times_s: Vec<f64> = Vec::new();
    let mut accel_g: Vec<f64> = Vec::new();
    let mut first_content_line = true;
    for (index, raw) in lines.iter().enumerate() {
        let line_no = index + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let is_first = std::mem::replace(&mut first_content_line, false);
        let mut parts = fields(line);
        let (first, second, rest) = (parts.next(), parts.next(), parts.count());
        if is_first && first.is_some_and(|field| parse_float(field).is_none()) {
            continue; // the optional header line
        }
        let (Some(time_field), Some(accel_field), 0) = (first, second, rest) else {
            let found = usize::from(first.is_some()) + usize::from(second.is_some()) + rest;
            return Err(RecordError::Columns {
                file: file.to_owned(),
                line: line_no,
                found,
            });
        };
        let time = parse_number(file, line_no, time_field)?;
        let value = parse_number(file, line_no, accel_field)?;
        match times_s.last() {
            None if time < 0.0 => {
                return Err(RecordError::NegativeTime {
                    file: file.to_owned(),
                    line: line_no,
                    time,
                });
            }
            Some(&previous) if time <= previous => {
                return Err(RecordError::NotIncreasing {
                    file: file.to_owned(),
                    line: line_no,
                    time,
                    previous,
                });
            }
            _ => {}
        }
        check_accel(file, line_no, value)?;
        times_s.push(time);
        accel_g.push(value);
    }
    if times_s.len() < 2 {
        return Err(RecordError::TooFewSamples {
            file: file.to_owned(),
            found: times_s.len(),
        });
    }
    Ok(Series { times_s, accel_g })
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::path::PathBuf;
    use std::sync::atomic::{AtomicU64, Ordering};

    const SAMPLE_AT2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sample.AT2");
    const SAMPLE_V: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sample_v.txt");
    const BAD_LINE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bad_line.txt");

    /// A uniquely named temporary file, removed on drop.
    struct TempFile(PathBuf);

    impl TempFile {
        fn new(name: &str, content: &[u8]) -> Self {
            static COUNTER: AtomicU64 = AtomicU64::new(0);
            let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
            let path = std::env::temp_dir().join(format!("rocking-record-{}-{unique}-{name}", std::process::id()));
            std::fs::write(&path, content).unwrap();
            Self(path)
        }

        fn read(&self) -> Result<Series, RecordError> {
            read_record(&self.0)
        }
    }

    impl Drop for TempFile {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    fn read_str(name: &str, content: &str) -> Result<Series, RecordError> {
        TempFile::new(name, content.as_bytes()).read()
    }

    fn err_str(name: &str, content: &str) -> String {
        let error = read_str(name, content).unwrap_err();
        let message = error.to_string();
        assert!(!message.contains('\n'), "multi-line message: {message}");
        message
    }

    fn series(times: &[f64], accel: &[f64]) -> Series {
        Series::new(times.to_vec(), accel.to_vec()).unwrap()
    }

    // ---- Series ----

    #[test]
    fn interpolates_linearly_and_exactly_at_samples() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.accel_at(0.5), 0.2);
        assert_eq!(s.accel_at(1.0), -0.4);
        assert_eq!(s.accel_at(2.0), 0.6);
        assert!((s.accel_at(0.75) - (-0.1)).abs() < 1e-15);
        assert!((s.accel_at(1.5) - 0.1).abs() < 1e-15);
        assert!((s.accel_at(1.25) - (-0.15)).abs() < 1e-15);
    }

    #[test]
    fn zero_outside_the_record_nan_for_nan() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.accel_at(0.0), 0.0);
        assert_eq!(s.accel_at(0.499_999), 0.0);
        assert_eq!(s.accel_at(-3.0), 0.0);
        assert_eq!(s.accel_at(2.000_001), 0.0);
        assert_eq!(s.accel_at(f64::INFINITY), 0.0);
        assert_eq!(s.accel_at(f64::NEG_INFINITY), 0.0);
        assert!(s.accel_at(f64::NAN).is_nan());
    }

    #[test]
    fn series_accessors() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.len(), 3);
        assert!(!s.is_empty());
        assert_eq!(s.start_s(), 0.5);
        assert_eq!(s.duration_s(), 2.0);
        assert_eq!(s.peak_abs_g(), 0.6);
        assert_eq!(s.times_s(), &[0.5, 1.0, 2.0]);
        assert_eq!(s.accel_g(), &[0.2, -0.4, 0.6]);
    }

    #[test]
    fn next_sample_after_is_strict() {
        let s = series(&[0.5, 1.0, 2.0], &[0.2, -0.4, 0.6]);
        assert_eq!(s.next_sample_after(-1.0), Some(0.5));
        assert_eq!(s.next_sample_after(0.5), Some(1.0));
        assert_eq!(s.next_sample_after(0.7), Some(1.0));
        assert_eq!(s.next_sample_after(1.0), Some(2.0));
        assert_eq!(s.next_sample_after(2.0), None);
        assert_eq!(s.next_sample_after(5.0), None);
        assert_eq!(s.next_sample_after(f64::NAN), None);
    }

    #[test]
    fn series_new_validates() {
        use SeriesError as E;
        let new = |t: &[f64], a: &[f64]| Series::new(t.to_vec(), a.to_vec()).unwrap_err();
        assert_eq!(new(&[0.0, 1.0], &[0.0]), E::LengthMismatch { times: 2, values: 1 });
        assert_eq!(new(&[0.0], &[0.0]), E::TooFewSamples { found: 1 });
        assert_eq!(new(&[], &[]), E::TooFewSamples { found: 0 });
        assert_eq!(new(&[0.0, f64::NAN], &[0.0, 0.0]), E::NonFinite { index: 1 });
        assert_eq!(new(&[0.0, 1.0], &[0.0, f64::INFINITY]), E::NonFinite { index: 1 });
        assert_eq!(new(&[-0.1, 1.0], &[0.0, 0.0]), E::NegativeStart { time: -0.1 });
        assert_eq!(
            new(&[0.0, 1.0, 1.0], &[0.0, 0.0, 0.0]),
            E::NotIncreasing {
                index: 2,
                time: 1.0,
                previous: 1.0
            }
        );
        assert_eq!(
            new(&[0.0, 1.0], &[0.0, -100.5]),
            E::TooLarge {
                index: 1,
                value: -100.5
            }
        );
        assert!(Series::new(vec![0.0, 1.0], vec![100.0, -100.0]).is_ok());
    }

    // ---- RecordExcitation ----

    #[test]
    fn excitation_converts_time_and_scales() {
        let h = series(&[0.0, 1.0, 2.0], &[0.0, 0.4, 0.0]);
        let v = series(&[0.0, 0.5, 1.5], &[0.1, 0.3, -0.1]);
        let p = 4.0;
        let ex = RecordExcitation::new(h.clone(), Some(v.clone()), p, 2.0, -0.5);
        for &tau in &[-1.0, 0.0, 0.3, 1.0, 2.0, 3.7, 4.0, 6.0, 7.9, 8.0, 9.0] {
            let (a_h, a_v) = ex.accel(tau);
            assert_eq!(a_h, 2.0 * h.accel_at(tau / p));
            assert_eq!(a_v, -0.5 * v.accel_at(tau / p));
        }
        assert!((ex.accel(2.0).0 - 0.4).abs() < 1e-15); // t = 0.5 s, a_h = 0.2 g
        assert_eq!(ex.end_tau(), 8.0);
        let h_only = RecordExcitation::new(h, None, p, 1.0, 3.0);
        assert_eq!(h_only.accel(2.0).1, 0.0);
        assert_eq!(h_only.end_tau(), 8.0);
        assert!(h_only.vertical().is_none());
        assert_eq!(h_only.p_per_s(), 4.0);
        assert_eq!((h_only.scale_h(), h_only.scale_v()), (1.0, 3.0));
    }

    #[test]
    fn end_tau_takes_the_longer_component() {
        let h = series(&[0.0, 1.0], &[0.0, 0.1]);
        let v = series(&[0.0, 3.0], &[0.0, 0.1]);
        let ex = RecordExcitation::new(h, Some(v), 2.0, 1.0, 1.0);
        assert_eq!(ex.end_tau(), 6.0);
    }

    #[test]
    fn next_breakpoint_merges_both_components() {
        let h = series(&[0.0, 1.0, 2.0], &[0.0, 0.4, 0.0]);
        let v = series(&[0.25, 0.5, 1.5, 3.0], &[0.1, 0.3, -0.1, 0.0]);
        let ex = RecordExcitation::new(h, Some(v), 2.0, 1.0, 1.0);
        let mut tau = -1.0;
        let mut seen = Vec::new();
        while let Some(next) = ex.next_breakpoint(tau) {
            assert!(next > tau);
            seen.push(next);
            tau = next;
        }
        assert_eq!(seen, vec![0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 6.0]);
        assert_eq!(ex.next_breakpoint(f64::NAN), None);
    }

    #[test]
    fn next_breakpoint_strict_despite_rounding() {
        // p and times chosen so that (t·p)/p often differs from t.
        let times: Vec<f64> = (0..2000).map(|k| k as f64 * 0.01).collect();
        let accel = vec![0.0; times.len()];
        let h = Series::new(times.clone(), accel).unwrap();
        let p = 3.0_f64.sqrt() * 1.234_567;
        let ex = RecordExcitation::new(h, None, p, 1.0, 1.0);
        let mut tau = 0.0;
        let mut count = 1;
        while let Some(next) = ex.next_breakpoint(tau) {
            assert!(next > tau);
            tau = next;
            count += 1;
        }
        assert_eq!(count, times.len());
        assert_eq!(tau, ex.end_tau());
    }

    // ---- Reading: test data files ----

    #[test]
    fn reads_sample_at2() {
        let s = read_record(Path::new(SAMPLE_AT2)).unwrap();
        assert_eq!(s.len(), 40);
        for (k, &t) in s.times_s().iter().enumerate() {
            assert_eq!(t, k as f64 * 0.01);
        }
        assert_eq!(s.accel_g()[0], 0.0);
        assert!((s.accel_g()[1] - 0.7497104e-01).abs() < 1e-12);
        assert!((s.duration_s() - 0.39).abs() < 1e-15);
        assert!(s.peak_abs_g() > 0.1 && s.peak_abs_g() < 0.3);
    }

    #[test]
    fn reads_sample_two_column() {
        let s = read_record(Path::new(SAMPLE_V)).unwrap();
        assert_eq!(s.len(), 21);
        assert_eq!(s.times_s()[0], 0.0);
        assert_eq!(s.times_s()[1], 0.01);
        assert_eq!(s.accel_g()[2], 0.0231);
        assert_eq!(s.duration_s(), 0.2);
    }

    #[test]
    fn bad_line_names_line_4() {
        let error = read_record(Path::new(BAD_LINE)).unwrap_err();
        assert!(matches!(error, RecordError::Columns { line: 4, found: 3, .. }));
        let message = error.to_string();
        assert!(
            message.ends_with("bad_line.txt:4: expected 2 columns, found 3"),
            "{message}"
        );
    }

    // ---- Reading: AT2 header forms ----

    const AT2_HEAD: &str = "PEER NGA STRONG MOTION DATABASE RECORD\n\
        Test Event, 01/01/2000, Test Station, 090\n\
        ACCELERATION TIME SERIES IN UNITS OF G\n";

    fn at2(count_line: &str, data: &str) -> String {
        format!("{AT2_HEAD}{count_line}\n{data}")
    }

    #[test]
    fn accepts_all_count_line_forms() {
        let data = "  .1000000E-01  -.2000000E-01   .3000000E+00\n";
        for count_line in [
            "NPTS=     3, DT=   .0050 SEC",
            "NPTS=3, DT=.005 SEC,",
            "NPTS=3 DT=0.005",
            "NPTS=3, DT=0.005",
            "NPTS= 3 DT= 0.005 SEC",
            "NPTS=3 DT=0.005 SEC,",
            "npts=3, dt=.005sec",
            "    3   0.00500   NPTS, DT",
            "3 .005 NPTS DT",
        ] {
            let s = read_str("form.at2", &at2(count_line, data)).unwrap_or_else(|e| panic!("{count_line:?}: {e}"));
            assert_eq!(s.times_s(), &[0.0, 0.005, 0.01], "{count_line:?}");
            assert_eq!(s.accel_g(), &[0.01, -0.02, 0.3], "{count_line:?}");
        }
    }

    #[test]
    fn at2_detected_by_content_and_crlf_and_d_exponent() {
        let content = at2("NPTS=4, DT=0.02 SEC", "1.0D-02, 2.0d-2\n-3E-2 4.0e-02\n\n").replace('\n', "\r\n");
        let s = read_str("record.dat", &content).unwrap();
        assert_eq!(s.accel_g(), &[0.01, 0.02, -0.03, 0.04]);
        assert_eq!(s.times_s(), &[0.0, 0.02, 0.04, 0.06]);
    }

    #[test]
    fn at2_extension_any_case() {
        let content = at2("NPTS=2, DT=0.02 SEC", "0.1 0.2\n");
        for name in ["a.at2", "b.AT2", "c.At2"] {
            assert_eq!(read_str(name, &content).unwrap().len(), 2);
        }
    }

    #[test]
    fn at2_header_errors() {
        let m = err_str("ground.at2", &at2("NPTS: many, DT: small", "0.1 0.2\n"));
        assert!(
            m.ends_with("ground.at2:4: cannot read NPTS/DT from header \"NPTS: many, DT: small\""),
            "{m}"
        );
        let m = err_str("ground.at2", &at2("NPTS=2.5, DT=0.01", "0.1 0.2\n"));
        assert!(m.contains(":4: cannot read NPTS/DT"), "{m}");
        let m = err_str("ground.at2", &at2("NPTS=-2, DT=0.01", "0.1 0.2\n"));
        assert!(m.contains(":4: cannot read NPTS/DT"), "{m}");
        let m = err_str("ground.at2", &at2("NPTS=0, DT=0.01", ""));
        assert!(m.ends_with("ground.at2:4: NPTS = 0, the record has no samples"), "{m}");
        for dt in ["0", "-0.01", "nan", "inf"] {
            let m = err_str("ground.at2", &at2(&format!("NPTS=2, DT={dt}"), "0.1 0.2\n"));
            assert!(m.contains("ground.at2:4: invalid time step DT"), "{m}");
        }
        let m = err_str("ground.at2", &at2("NPTS=3, DT=1e308", "0.1 0.2 0.3\n"));
        assert!(m.contains(":4: invalid time step DT = 100000"), "{m}");
        let m = err_str("short.at2", "PEER NGA STRONG MOTION DATABASE RECORD\nx\n");
        assert!(m.ends_with("short.at2: AT2 header has 3 lines, expected 4"), "{m}");
    }

    #[test]
    fn at2_rejects_other_units_and_quantities() {
        for line3 in [
            "VELOCITY TIME SERIES IN UNITS OF CM/SEC",
            "DISPLACEMENT TIME SERIES IN UNITS OF CM",
            "ACCELERATION TIME SERIES IN UNITS OF CM/S/S",
        ] {
            let content = format!("TITLE\nEVENT\n{line3}\nNPTS=2, DT=0.01 SEC\n0.1 0.2\n");
            let m = err_str("units.at2", &content);
            assert!(m.contains("units.at2:3: not an acceleration record"), "{m}");
        }
        let content = "TITLE\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G.\nNPTS=2, DT=0.01\n0.1 0.2\n";
        assert_eq!(read_str("ok.at2", content).unwrap().len(), 2);
    }

    #[test]
    fn at2_value_count_must_match() {
        let m = err_str("x.at2", &at2("NPTS=  5590, DT=   .0050 SEC", "0.1 0.2\n"));
        assert!(m.ends_with("x.at2: expected 5590 values, found 2"), "{m}");
        let m = err_str("x.at2", &at2("NPTS=2, DT=.005", "0.1 0.2\n0.3\n"));
        assert!(m.ends_with("x.at2: expected 2 values, found 3"), "{m}");
        let m = err_str("x.at2", &at2("NPTS=1, DT=.005", "0.1\n"));
        assert!(m.ends_with("x.at2: need at least 2 samples, found 1"), "{m}");
    }

    #[test]
    fn at2_bad_values_name_their_line() {
        let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 nan\n"));
        assert!(m.ends_with("v.at2:6: non-finite value \"nan\""), "{m}");
        let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 1e999\n"));
        assert!(m.ends_with("v.at2:6: non-finite value \"1e999\""), "{m}");
        let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 0.4x\n"));
        assert!(m.ends_with("v.at2:6: cannot parse \"0.4x\" as a number"), "{m}");
        let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 -981.0\n"));
        assert!(
            m.ends_with("v.at2:6: |acceleration| of -981 g exceeds the 100 g sanity limit"),
            "{m}"
        );
    }

    // ---- Reading: two-column ----

    #[test]
    fn two_column_separators_comments_and_header() {
        let content =
            "# comment\n\n   # indented comment\ntime_s, accel_g\n0.0, 0.1\n0.1 ,0.2\n0.2\t-0.3\n0.3,-0.4\r\n\n# end\n";
        let s = read_str("rec.txt", content).unwrap();
        assert_eq!(s.times_s(), &[0.0, 0.1, 0.2, 0.3]);
        assert_eq!(s.accel_g(), &[0.1, 0.2, -0.3, -0.4]);
        // Without a header, and starting after t = 0.
        let s = read_str("rec.txt", "0.5 0\n1.5 0.25\n").unwrap();
        assert_eq!(s.accel_at(1.0), 0.125);
        assert_eq!(s.accel_at(0.25), 0.0);
    }

    #[test]
    fn two_column_errors_name_their_line() {
        let cases: &[(&str, &str)] = &[
            ("t a\n0 0\n0.1 0.2 0.3\n", "rec.txt:3: expected 2 columns, found 3"),
            ("0 0\n0.1\n", "rec.txt:2: expected 2 columns, found 1"),
            ("0 0\n , ,\n", "rec.txt:2: expected 2 columns, found 0"),
            (
                "0 0\n0.2 0\n0.2 0.1\n",
                "rec.txt:3: time 0.2 does not increase (previous 0.2)",
            ),
            (
                "0 0\n0.2 0\n0.1 0.1\n",
                "rec.txt:3: time 0.1 does not increase (previous 0.2)",
            ),
            ("0 0\n0.2 nan\n", "rec.txt:2: non-finite value \"nan\""),
            ("0 0\ninf 0.1\n", "rec.txt:2: non-finite value \"inf\""),
            ("-0.1 0\n0.2 0\n", "rec.txt:1: negative time -0.1 s"),
            (
                "0 0\n0.1 150\n",
                "rec.txt:2: |acceleration| of 150 g exceeds the 100 g sanity limit",
            ),
            (
                "time accel\n0 0\nagain header\n",
                "rec.txt:3: cannot parse \"again\" as a number",
            ),
            ("h1\nh2 x\n", "rec.txt:2: cannot parse \"h2\" as a number"),
            ("# only\ntime accel\n", "rec.txt: need at least 2 samples, found 0"),
            ("0 0\n", "rec.txt: need at least 2 samples, found 1"),
            ("", "rec.txt: empty file"),
            (" \n\t\r\n\n", "rec.txt: empty file"),
        ];
        for (content, expected) in cases {
            let m = err_str("rec.txt", content);
            assert!(m.ends_with(expected), "{content:?}: got {m}, want {expected}");
        }
    }

    #[test]
    fn io_errors_name_the_path() {
        let missing = std::env::temp_dir().join("rocking-record-does-not-exist.txt");
        let error = read_record(&missing).unwrap_err();
        assert!(matches!(error, RecordError::Io { .. }));
        assert!(
            error.to_string().starts_with(&format!("{}: ", missing.display())),
            "{error}"
        );
        let dir = std::env::temp_dir();
        let error = read_record(&dir).unwrap_err();
        assert_eq!(error.to_string(), format!("{}: is a directory", dir.display()));
    }

    #[test]
    fn invalid_utf8_is_an_error_not_a_panic() {
        let f = TempFile::new("latin1.txt", b"# Station M\xfcller\n0 0\n0.1 0.\xff\n");
        let m = f.read().unwrap_err().to_string();
        assert!(m.contains(":3: cannot parse"), "{m}");
        let f = TempFile::new("latin1ok.txt", b"# Station M\xfcller\n0 0\n0.1 0.5\n");
        assert_eq!(f.read().unwrap().len(), 2);
    }

    // ---- Never panics ----

    fn token() -> impl Strategy<Value = String> {
        prop_oneof![
            Just("NPTS=".to_owned()),
            Just("DT=".to_owned()),
            Just("SEC".to_owned()),
            Just(",".to_owned()),
            Just(" ".to_owned()),
            Just("\n".to_owned()),
            Just("\r\n".to_owned()),
            Just("#".to_owned()),
            Just("nan".to_owned()),
            Just("-inf".to_owned()),
            Just("1e999".to_owned()),
            Just("UNITS OF G".to_owned()),
            Just(".1234567E-02".to_owned()),
            any::<f64>().prop_map(|x| x.to_string()),
            any::<u32>().prop_map(|x| x.to_string()),
            (0_u32..5).prop_map(|x| x.to_string()),
            "[a-zA-Z0-9.,=+ -]{0,8}",
        ]
    }

    fn tokens_file() -> impl Strategy<Value = Vec<u8>> {
        (any::<bool>(), prop::collection::vec(token(), 0..60)).prop_map(|(head, tokens)| {
            let body: String = tokens.concat();
            let text = if head { format!("{AT2_HEAD}{body}") } else { body };
            text.into_bytes()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn arbitrary_bytes_never_panic(
            content in prop::collection::vec(any::<u8>(), 0..600),
            ext in prop::sample::select(vec!["at2", "AT2", "txt", "csv", ""]),
        ) {
            let file = TempFile::new(&format!("fuzz.{ext}"), &content);
            let _ = file.read();
        }

        #[test]
        fn arbitrary_token_soup_never_panics(
            content in tokens_file(),
            ext in prop::sample::select(vec!["at2", "txt"]),
        ) {
            let file = TempFile::new(&format!("soup.{ext}"), &content);
            if let Ok(s) = file.read() {
                // Whatever is accepted satisfies the Series invariants.
                prop_assert!(Series::new(s.times_s().to_vec(), s.accel_g().to_vec()).is_ok());
            }
        }
    }
}
