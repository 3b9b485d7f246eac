//! A writer of COSMOS V1/V2 text (COSMOS Strong Motion Data Format v1.20)
//! for the reader's tests: the layout `cosmos.rs` documents and
//! docs/model.md §1.8 states, so that every format and refusal test runs on
//! a file written here rather than on a recording the project may not ship.
//!
//! Per channel: 13 text lines (the first names the data type and the count
//! of text lines, the 9th the channel, `Sta Chan  1: 360 deg`), the integer
//! header (100 values, `(10I8)`: value 1 the processing stage, 2 the
//! physical parameter, 1 = acceleration, 3 the unit code), the real header
//! (100 values in the channel's format: value 62 the sampling interval in
//! ms, 63 the length in s, 64 the peak and 65 its time), the comment
//! lines, the data line (`N acceleration pts, approx S secs,
//! units=g.(02),Format=(8F9.6)`) and the values in that fixed-width
//! format; a V2 channel may go on with velocity and displacement blocks;
//! `End-of-data for Chan  k acceleration` closes the channel. The writer
//! also returns where each part landed, so that a test can name the line
//! an error must name without counting by hand.

use crate::model::units::AccelUnit;

/// The value COSMOS writes where a header value is unknown.
pub(crate) const UNKNOWN: f64 = -999.0;

/// A Fortran edit descriptor for the values of a block: `per_line` fields
/// of `width` characters, `F` (fixed) or `E` (exponent) with `decimals`
/// digits after the point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fortran {
    per_line: usize,
    exponent: bool,
    width: usize,
    decimals: usize,
    /// `-0.105433` rather than `-.105433` (CSMIP's writer drops the zero).
    leading_zero: bool,
}

impl Fortran {
    /// `(nFw.d)`, written with the zero before the point.
    pub const fn f(per_line: usize, width: usize, decimals: usize) -> Self {
        Self {
            per_line,
            exponent: false,
            width,
            decimals,
            leading_zero: true,
        }
    }

    /// `(nEw.d)`: `3.437285e-04`, as the USGS writes V2 values.
    pub const fn e(per_line: usize, width: usize, decimals: usize) -> Self {
        Self {
            per_line,
            exponent: true,
            width,
            decimals,
            leading_zero: true,
        }
    }

    /// The same, with no zero before the point (`-.105433`), as CSMIP writes.
    pub(crate) const fn without_leading_zero(self) -> Self {
        Self {
            leading_zero: false,
            ..self
        }
    }

    /// The largest rounding error of `value` written in this format: half a
    /// unit of its last decimal, which for an `E` field scales with the
    /// value's decade.
    pub fn rounding(self, value: f64) -> f64 {
        let half_unit = 0.5 * 10f64.powi(-(self.decimals as i32));
        if self.exponent && value != 0.0 {
            half_unit * 10f64.powf(value.abs().log10().floor())
        } else {
            half_unit
        }
    }

    fn descriptor(self) -> String {
        let letter = if self.exponent { 'E' } else { 'F' };
        format!("({}{letter}{}.{})", self.per_line, self.width, self.decimals)
    }

    /// One value in its field, right-aligned; panics (a broken test) when
    /// it does not fit, as Fortran would write stars.
    pub fn field(self, value: f64) -> String {
        let d = self.decimals;
        let mut text = if self.exponent {
            let s = format!("{value:.d$e}");
            let (mantissa, exp) = s.split_once('e').unwrap();
            let exp: i32 = exp.parse().unwrap();
            let sign = if exp < 0 { '-' } else { '+' };
            format!("{mantissa}e{sign}{:02}", exp.abs())
        } else {
            format!("{value:.d$}")
        };
        if !self.leading_zero && !self.exponent {
            if let Some(rest) = text.strip_prefix("0.") {
                text = format!(".{rest}");
            } else if let Some(rest) = text.strip_prefix("-0.") {
                text = format!("-.{rest}");
            }
        }
        assert!(text.len() <= self.width, "{text} does not fit {}", self.descriptor());
        format!("{text:>w$}", w = self.width)
    }

    /// The values in lines of `per_line` fields, with no separator but the
    /// fields' own padding (values that fill their field touch).
    fn lines(self, values: &[f64]) -> Vec<String> {
        values
            .chunks(self.per_line)
            .map(|chunk| chunk.iter().map(|&v| self.field(v)).collect())
            .collect()
    }
}

/// One channel of a COSMOS file.
#[derive(Clone, Debug)]
pub(crate) struct Channel {
    /// V2 (`Corrected acceleration`) or V1 (`Uncorrected acceleration`).
    pub corrected: bool,
    /// The channel's name on its 9th text line (`360 deg`, `Up`).
    pub name: &'static str,
    /// The unit of `values`: g (code 02) or cm/s² (code 04).
    pub unit: AccelUnit,
    /// The sampling interval, ms (real-header value 62).
    pub step_ms: f64,
    /// The accelerations, in `unit`.
    pub values: Vec<f64>,
    /// How the values are written.
    pub format: Fortran,
    /// How the real header is written: `(6F13.6)` (CSMIP) or `(5F15.6)`.
    pub real_format: Fortran,
    /// Comment lines (each written after a `|`).
    pub comments: Vec<String>,
    /// Whether velocity and displacement blocks follow the acceleration
    /// (a V2 file's), integrated here by the trapezoidal rule.
    pub velocity: bool,
}

impl Channel {
    /// A V1 channel in g, written as CSMIP writes it: `(8F9.6)`, no zero
    /// before the point, the real header in `(6F13.6)`.
    pub fn v1(name: &'static str, step_ms: f64, values: Vec<f64>) -> Self {
        Self {
            corrected: false,
            name,
            unit: AccelUnit::G,
            step_ms,
            values,
            format: Fortran::f(8, 9, 6).without_leading_zero(),
            real_format: Fortran::f(6, 13, 6).without_leading_zero(),
            comments: vec!["<SCNL>00000.HNN.XX.--  written by the test".to_owned()],
            velocity: false,
        }
    }

    /// A V2 channel in cm/s², written as the USGS writes it: `(1E15.6)`, the
    /// real header in `(5F15.6)`, velocity and displacement after it.
    pub fn v2(name: &'static str, step_ms: f64, values: Vec<f64>) -> Self {
        Self {
            corrected: true,
            name,
            unit: AccelUnit::CentimetresPerSecond2,
            step_ms,
            values,
            format: Fortran::e(1, 15, 6),
            real_format: Fortran::f(5, 15, 6),
            comments: vec![
                "Recorder: written by the test".to_owned(),
                "<PROCESS> MANUAL".to_owned(),
            ],
            velocity: true,
        }
    }
}

/// Where one channel's parts landed: 1-based line numbers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChannelLines {
    /// The first text line (`... (Format v01.20 with 13 text lines)`).
    pub first: usize,
    /// `100 Integer-header values follow on 10 lines`.
    pub integer_count: usize,
    /// The first line of integer values (values 1 to 10).
    pub integer_first: usize,
    /// The line holding real-header value 62 (the sampling interval).
    pub step: usize,
    /// The data line (`N acceleration pts, ...`).
    pub data: usize,
    /// The first line of values.
    pub first_value: usize,
    /// The first line after the acceleration values (a velocity block's
    /// data line, or `End-of-data`).
    pub after_values: usize,
}

/// A COSMOS file as written, and where its channels' parts are.
pub(crate) struct CosmosText {
    pub text: String,
    pub channels: Vec<ChannelLines>,
}

/// COSMOS table 2's unit code and the name a data line gives it.
fn unit_code(unit: AccelUnit) -> (u32, &'static str) {
    match unit {
        AccelUnit::G => (2, "g.     "),
        AccelUnit::CentimetresPerSecond2 => (4, "cm/sec2"),
        AccelUnit::MetresPerSecond2 => panic!("COSMOS has no code for m/s2"),
    }
}

/// Writes `channels` one after the other, lines ended by CRLF (as CESMD's
/// files are) when `crlf`.
pub(crate) fn cosmos_file(channels: &[Channel], crlf: bool) -> CosmosText {
    let mut lines: Vec<String> = Vec::new();
    let mut at = Vec::new();
    for (k, c) in channels.iter().enumerate() {
        at.push(write_channel(&mut lines, k + 1, c));
    }
    let end = if crlf { "\r\n" } else { "\n" };
    let mut text = lines.join(end);
    text.push_str(end);
    CosmosText { text, channels: at }
}

/// Appends channel `k` (1-based) to `lines`.
fn write_channel(lines: &mut Vec<String>, k: usize, c: &Channel) -> ChannelLines {
    let n = c.values.len();
    let dt = c.step_ms / 1000.0;
    let (code, unit_name) = unit_code(c.unit);
    let (peak_at, peak) = c
        .values
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap_or((0, UNKNOWN));
    let kind = if c.corrected { "Corrected" } else { "Uncorrected" };
    let first = lines.len() + 1;
    lines.push(format!(
        "{kind} acceleration    (Format v01.20 with 13 text lines) Src: test"
    ));
    lines.push("Record of a damped sine written by the reader's tests".to_owned());
    lines.push("Hypocenter: To be determined    H=   km       ML=     Mw=".to_owned());
    lines.push("Origin: To be determined".to_owned());
    lines.push("Statn No: 00-00000 Code:XX-TEST  TEST  Nowhere, written by a test".to_owned());
    lines.push("Coords: 0.000    0.000   Site geology:".to_owned());
    lines.push("Recorder: Test   s/n 0000 ( 3 Chns of   3 at Sta) Sensor: FBA".to_owned());
    lines.push("Rcrd start time: 1/01/2000, 00:00:  .0 UTC (Q=5) RcrdId: test".to_owned());
    lines.push(format!("Sta Chan {k:>2}: {} (Rcrdr Chan {k:>2})", c.name));
    lines.push(format!("Raw record length = {:7.3} sec", n as f64 * dt));
    lines.push("Processed: by the test".to_owned());
    lines.push("Record not filtered.".to_owned());
    lines.push("Values used when parameter or data value is unknown/unspecified:   -999, -999.0".to_owned());

    let mut integers = [UNKNOWN as i64; 100];
    integers[0] = if c.corrected { 2 } else { 1 };
    integers[1] = 1;
    integers[2] = i64::from(code);
    integers[3] = 120;
    let integer_count = lines.len() + 1;
    lines.push(" 100 Integer-header values follow on  10 lines, Format= (10I8)".to_owned());
    let integer_first = lines.len() + 1;
    for chunk in integers.chunks(10) {
        lines.push(chunk.iter().map(|v| format!("{v:>8}")).collect());
    }

    let mut reals = [UNKNOWN; 100];
    reals[61] = c.step_ms;
    reals[62] = n as f64 * dt;
    reals[63] = peak;
    reals[64] = peak_at as f64 * dt;
    let real_lines = c.real_format.lines(&reals);
    lines.push(format!(
        " 100 Real-header values follow on {:>3} lines, Format= {}",
        real_lines.len(),
        c.real_format.descriptor()
    ));
    let step = lines.len() + 1 + 61 / c.real_format.per_line;
    lines.extend(real_lines);

    lines.push(format!(
        "{:>4} Comment line(s) follow, each starting with a \"|\":",
        c.comments.len()
    ));
    lines.extend(c.comments.iter().map(|l| format!("| {l}")));

    let secs = (n as f64 * dt).round() as i64;
    let data = lines.len() + 1;
    lines.push(format!(
        "{n:>8} acceleration pts, approx {secs:>3} secs, units={unit_name}({code:02}),Format={}",
        c.format.descriptor()
    ));
    let first_value = lines.len() + 1;
    lines.extend(c.format.lines(&c.values));
    let after_values = lines.len() + 1;
    if c.velocity {
        // cm/s from cm/s² (or g·s: the unit is not read), then cm.
        let velocity = trapezoid(&c.values, dt);
        let displacement = trapezoid(&velocity, dt);
        for (quantity, units, values) in [
            ("velocity    ", "cm/sec (05)", &velocity),
            ("displacement", "cm (06)", &displacement),
        ] {
            lines.push(format!(
                "{n:>8} {quantity} pts, approx {secs:>3} secs, units={units},Format={}",
                c.format.descriptor()
            ));
            lines.extend(c.format.lines(values));
        }
    }
    lines.push(format!("End-of-data for Chan {k:>2} acceleration"));
    ChannelLines {
        first,
        integer_count,
        integer_first,
        step,
        data,
        first_value,
        after_values,
    }
}

/// The running trapezoidal integral of `values` at step `dt`, from 0.
fn trapezoid(values: &[f64], dt: f64) -> Vec<f64> {
    let mut sum = 0.0;
    let mut out = Vec::with_capacity(values.len());
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            sum += 0.5 * (values[i - 1] + v) * dt;
        }
        out.push(sum);
    }
    out
}

/// A damped sine sampled at `k·dt` s: `amplitude·exp(−decay·t)·sin(2π·hz·t)`,
/// the analytic record of the tests. Its first lobe is its largest.
pub(crate) fn damped_sine(n: usize, dt: f64, amplitude: f64, hz: f64, decay: f64) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let t = k as f64 * dt;
            amplitude * (-decay * t).exp() * (std::f64::consts::TAU * hz * t).sin()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_fields_are_written_as_fortran_writes_them() {
        assert_eq!(Fortran::f(8, 9, 6).field(-0.105433), "-0.105433");
        assert_eq!(Fortran::f(8, 9, 6).without_leading_zero().field(-0.105433), " -.105433");
        assert_eq!(Fortran::f(8, 9, 6).without_leading_zero().field(0.048757), "  .048757");
        assert_eq!(Fortran::f(10, 8, 5).field(-0.00003), "-0.00003");
        assert_eq!(Fortran::e(1, 15, 6).field(3.437285e-4), "   3.437285e-04");
        assert_eq!(Fortran::e(1, 15, 6).field(-685.1512), "  -6.851512e+02");
        assert_eq!(Fortran::f(5, 15, 6).field(UNKNOWN), "    -999.000000");
    }
}
