//! Text records: two columns `time_s accel`, or one column of accelerations
//! at a stated time step (grammar: [`read_record_as`](super::read_record_as)).

use super::{RecordError, RecordFormat, check_accel, fields, is_comment, parse_float, parse_number};
use crate::model::excitation::record::{Series, step_in_range};
use crate::model::units::AccelUnit;

/// Parses a text record split into lines: one column at step `dt` (s) when
/// it is given, two columns otherwise; accelerations in `unit`, returned in
/// g.
pub(super) fn parse_columns(
    file: &str,
    lines: &[&str],
    unit: AccelUnit,
    dt: Option<f64>,
) -> Result<(Series, RecordFormat), RecordError> {
    let expected = if dt.is_some() { 1 } else { 2 };
    let mut times_s: Vec<f64> = Vec::new();
    let mut accel_g: Vec<f64> = Vec::new();
    let mut first_content_line = true;
    for (index, raw) in lines.iter().enumerate() {
        let line_no = index + 1;
        let line = raw.trim();
        if line.is_empty() || is_comment(line) {
            continue;
        }
        let is_first = std::mem::replace(&mut first_content_line, false);
        let parts: Vec<&str> = fields(line).take(expected + 8).collect();
        if is_first && parts.first().is_some_and(|field| parse_float(field).is_none()) {
            continue; // the optional header line
        }
        let (time, accel_field) = match (dt, parts.as_slice()) {
            (Some(dt), [accel]) => (times_s.len() as f64 * dt, *accel),
            (None, [time, accel]) => (parse_number(file, line_no, time)?, *accel),
            (None, [_]) if times_s.is_empty() => {
                return Err(RecordError::NoStep {
                    file: file.to_owned(),
                    line: line_no,
                });
            }
            _ => {
                return Err(RecordError::Columns {
                    file: file.to_owned(),
                    line: line_no,
                    expected,
                    found: fields(line).count(),
                });
            }
        };
        let value = unit.to_g(parse_number(file, line_no, accel_field)?);
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
            // A stated dt was checked already; the times of a two-column
            // file are checked here, each step against the last.
            Some(&previous) if dt.is_none() && !step_in_range(time - previous) => {
                return Err(RecordError::StepOutOfRange {
                    file: file.to_owned(),
                    line: line_no,
                    step: time - previous,
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
    if !times_s.last().is_some_and(|t| t.is_finite()) {
        return Err(RecordError::StatedStep {
            file: file.to_owned(),
            dt: dt.unwrap_or(f64::NAN),
        });
    }
    let format = if dt.is_some() {
        RecordFormat::OneColumn
    } else {
        RecordFormat::TwoColumn
    };
    Ok((Series::from_checked(times_s, accel_g), format))
}
