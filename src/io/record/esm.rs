//! The ASCII format of the Engineering Strong-Motion database (ESM, ORFEUS;
//! the "DYNA 1.2" header of its `.ASC` files). Grammar:
//! [`read_record_as`](super::read_record_as).
//!
//! A header of `KEY: value` lines (`EVENT_NAME: ...`, ..., `USER5:`), then
//! the samples, one per line. Read from the header: `NDATA` (the number of
//! samples), `SAMPLING_INTERVAL_S` (the time step, s), `UNITS` (`cm/s^2`)
//! and `DATA_TYPE` (`ACCELERATION`; the database also serves velocity,
//! displacement and spectra in the same layout, which are refused).

use super::counted::read_block;
use super::{RecordError, agreed_unit, check_accel, excerpt, parse_float};
use crate::model::excitation::record::{Series, step_in_range};
use crate::model::units::AccelUnit;

/// How many lines from the top an ESM header is looked for in: the DYNA
/// 1.2 header has 64; twice that leaves room for added keys.
const HEADER_SEARCH_LINES: usize = 128;

/// Whether the lines look like an ESM file: a first line `KEY: value` with
/// an upper-case key, and a `SAMPLING_INTERVAL_S:` key among the first
/// lines.
pub(super) fn is_esm(lines: &[&str]) -> bool {
    lines.first().and_then(|l| header_field(l)).is_some()
        && lines
            .iter()
            .take(HEADER_SEARCH_LINES)
            .any(|l| l.trim_start().starts_with("SAMPLING_INTERVAL_S:"))
}

/// A header line's key and value: `NDATA: 13876` gives `("NDATA", "13876")`.
/// Keys are upper-case letters, digits and `_/^.-` (`VS30_M/S`,
/// `PGA_CM/S^2`); anything else is not a header line.
fn header_field(line: &str) -> Option<(&str, &str)> {
    let (key, value) = line.split_once(':')?;
    let key = key.trim();
    let is_key = !key.is_empty()
        && key.starts_with(|c: char| c.is_ascii_uppercase())
        && key
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || "_/^.-".contains(c));
    is_key.then_some((key, value.trim()))
}

/// Parses an ESM file split into lines, in the header's unit or, when its
/// `UNITS` is empty, the `stated` one (a stated unit must agree with the
/// header's); returns the samples in g and the unit they were in.
pub(super) fn parse_esm(
    file: &str,
    lines: &[&str],
    stated: Option<AccelUnit>,
) -> Result<(Series, AccelUnit), RecordError> {
    let header_end = lines
        .iter()
        .position(|l| header_field(l).is_none())
        .unwrap_or(lines.len());
    let header = &lines[..header_end];
    let find = |key: &str| {
        header.iter().enumerate().find_map(|(i, l)| match header_field(l) {
            Some((k, v)) if k == key => Some((v, i + 1)),
            _ => None,
        })
    };
    let require = |key: &'static str| {
        find(key).ok_or_else(|| RecordError::MissingKey {
            file: file.to_owned(),
            line: header_end.max(1),
            key,
        })
    };
    if let Some((kind, line)) = find("DATA_TYPE")
        && !kind.eq_ignore_ascii_case("ACCELERATION")
    {
        return Err(RecordError::Units {
            file: file.to_owned(),
            line,
            text: excerpt(lines[line - 1]),
        });
    }
    let (units, units_line) = require("UNITS")?;
    let named = if units.is_empty() {
        None
    } else {
        Some(AccelUnit::parse_upper_case(units).ok_or_else(|| RecordError::Units {
            file: file.to_owned(),
            line: units_line,
            text: excerpt(lines[units_line - 1]),
        })?)
    };
    let unit = agreed_unit(file, units_line, named, stated, |file, line| {
        RecordError::NoHeaderUnit { file, line }
    })?;
    let (dt_text, dt_line) = require("SAMPLING_INTERVAL_S")?;
    let dt = parse_float(dt_text).unwrap_or(f64::NAN);
    if !step_in_range(dt) {
        return Err(RecordError::BadStep {
            file: file.to_owned(),
            line: dt_line,
            dt,
        });
    }
    let (count_text, count_line) = require("NDATA")?;
    let Ok(npts) = count_text.parse::<usize>() else {
        return Err(RecordError::BadValue {
            file: file.to_owned(),
            line: count_line,
            text: excerpt(lines[count_line - 1]),
        });
    };
    if npts == 0 {
        return Err(RecordError::NoSamples {
            file: file.to_owned(),
            line: count_line,
        });
    }
    // Capacity capped: NDATA comes from an untrusted header.
    let mut accel_g = Vec::with_capacity(npts.min(1 << 20));
    let end = read_block(file, lines, header_end, npts, count_line, None, |line, value| {
        let g = unit.to_g(value);
        check_accel(file, line, g)?;
        accel_g.push(g);
        Ok(())
    })?;
    // Only blank lines may follow the samples.
    if let Some(index) = (end..lines.len()).find(|&i| !lines[i].trim().is_empty()) {
        return Err(RecordError::NotANumber {
            file: file.to_owned(),
            line: index + 1,
            text: excerpt(lines[index]),
        });
    }
    if npts < 2 {
        return Err(RecordError::TooFewSamples {
            file: file.to_owned(),
            found: npts,
        });
    }
    // k·dt rather than a running sum: no accumulated round-off.
    let times_s: Vec<f64> = (0..npts).map(|k| k as f64 * dt).collect();
    Ok((Series::from_checked(times_s, accel_g), unit))
}
