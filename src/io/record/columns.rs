//! Two-column `time_s accel_g` text (grammar:
//! [`read_record`](super::read_record)).

use super::{RecordError, check_accel, fields, parse_float, parse_number};
use crate::model::excitation::record::Series;

/// Parses a two-column file split into lines (see [`read_record`]).
pub(super) fn parse_columns(file: &str, lines: &[&str]) -> Result<Series, RecordError> {
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
    Ok(Series::from_checked(times_s, accel_g))
}
