//! The PEER NGA `.AT2` format: four header lines, then NPTS values at a
//! fixed time step (grammar: [`read_record`](super::read_record)).

use super::{RecordError, agreed_unit, check_accel, excerpt, fields, parse_float, parse_number};
use crate::model::excitation::record::{Series, step_in_range};
use crate::model::units::AccelUnit;

/// 1-based number of the AT2 header line holding NPTS and DT.
const AT2_COUNT_LINE: usize = 4;

/// 1-based number of the AT2 header line describing the series.
const AT2_DESCRIPTION_LINE: usize = 3;

/// Parses an AT2 file split into lines (see [`read_record_as`]), in the
/// header's unit or, when the header names none, the `stated` one; returns
/// the samples in g and the unit they were in.
///
/// [`read_record_as`]: super::read_record_as
pub(super) fn parse_at2(
    file: &str,
    lines: &[&str],
    stated: Option<AccelUnit>,
) -> Result<(Series, AccelUnit), RecordError> {
    let (Some(description), Some(count_line)) = (lines.get(AT2_DESCRIPTION_LINE - 1), lines.get(AT2_COUNT_LINE - 1))
    else {
        return Err(RecordError::TruncatedHeader {
            file: file.to_owned(),
            found: lines.len(),
        });
    };
    let Ok(header_unit) = header_unit(description) else {
        return Err(RecordError::Units {
            file: file.to_owned(),
            line: AT2_DESCRIPTION_LINE,
            text: excerpt(description),
        });
    };
    let unit = agreed_unit(file, AT2_DESCRIPTION_LINE, header_unit, stated, |file, line| {
        RecordError::HeaderNoUnit { file, line }
    })?;
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
    if !step_in_range(dt) {
        return Err(bad_step());
    }
    // Capacity capped: NPTS comes from an untrusted header.
    let mut accel_g = Vec::with_capacity(npts.min(1 << 20));
    let mut found = 0_usize;
    for (index, line) in lines.iter().enumerate().skip(AT2_COUNT_LINE) {
        let line_no = index + 1;
        for field in fields(line) {
            let value = unit.to_g(parse_number(file, line_no, field)?);
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
    Ok((Series::from_checked(times_s, accel_g), unit))
}

/// The unit an AT2 description line (line 3) names: `Ok(Some(unit))` for
/// `UNITS OF x` with x one of g, m/s², cm/s² (any spelling
/// [`AccelUnit::parse`] reads, in any case: the format writes `G`), `Ok(None)` when it names no unit, and
/// `Err(())` when it describes a velocity or displacement or names another
/// unit. Lenient about the rest of the wording, which varies between
/// database releases.
fn header_unit(line: &str) -> Result<Option<AccelUnit>, ()> {
    let upper = line.to_ascii_uppercase();
    if upper.contains("VELOCITY") || upper.contains("DISPLACEMENT") {
        return Err(());
    }
    const UNITS_OF: &str = "UNITS OF";
    let Some(position) = upper.find(UNITS_OF) else {
        return Ok(None);
    };
    upper
        .get(position + UNITS_OF.len()..)
        .and_then(|rest| {
            rest.split(|c: char| !c.is_ascii_alphanumeric() && c != '/' && c != '^')
                .find(|word| !word.is_empty())
        })
        .and_then(AccelUnit::parse_upper_case)
        .map(Some)
        .ok_or(())
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
