//! The COSMOS strong-motion format (COSMOS Strong Motion Data Format, v1.20,
//! 2001), as CESMD and the USGS distribute records: V1 (uncorrected
//! acceleration) and V2 (corrected acceleration). Grammar:
//! [`read_record`](super::read_record_as).
//!
//! Each channel is a block: a text header (its first line names the data
//! type and says `(Format v01.20 with 13 text lines)`), an integer header
//! and a real header (each announced by a line `100 Integer-header values
//! follow on 10 lines, Format= (10I8)`), a count of comment lines and the
//! comments, then a data line `13400 acceleration pts, approx 67 secs,
//! units=g (02), Format=(8f9.6)` and the values. A V2 channel may go on with
//! velocity and displacement blocks: they are not read. A file may hold
//! several channels one after the other (a station's three components).
//!
//! What is read where: the number of values and the unit from the data
//! line (the unit code in parentheses, COSMOS table 2: 02 = g, 04 = cm/s²,
//! 10 = gal; or the unit's name where a writer gives no code), the time step
//! from real-header value 62 (the sampling interval in ms; value 34 is the
//! V0 file's, which resampling may have changed), and the physical
//! parameter from integer-header value 2 (1 = acceleration).

use super::counted::{FixedWidth, is_data_line, line_values, read_block};
use super::{RecordError, RecordFormat, agreed_unit, check_accel, excerpt};
use crate::model::excitation::record::{Series, step_in_range};
use crate::model::units::AccelUnit;

/// 1-based integer-header value holding the physical parameter (COSMOS
/// table 1: 1 = acceleration, 2 = velocity, 3 = displacement).
const INT_PARAMETER: usize = 2;

/// 1-based integer-header value holding the unit code (COSMOS table 2).
const INT_UNIT: usize = 3;

/// 1-based real-header value holding the sampling interval, ms.
const REAL_STEP_MS: usize = 62;

/// The value COSMOS writes where a header value is unknown.
const UNKNOWN: f64 = -999.0;

/// Whether `line` is the first line of a COSMOS channel: it says
/// `(Format v...` (any case).
pub(super) fn is_cosmos_start(line: &str) -> bool {
    line.to_ascii_lowercase().contains("(format v")
}

/// Parses a COSMOS file split into lines: the one channel it holds, or the
/// `channel` (1-based) of several; the unit from the data line, or the
/// `stated` one where the data line names none (a stated unit must agree
/// with a named one). Returns the samples in g, the unit they were in and
/// the format (V1 or V2).
pub(super) fn parse_cosmos(
    file: &str,
    lines: &[&str],
    stated: Option<AccelUnit>,
    channel: Option<usize>,
) -> Result<(Series, AccelUnit, RecordFormat), RecordError> {
    let starts: Vec<usize> = (0..lines.len()).filter(|&i| is_cosmos_start(lines[i])).collect();
    let Some(&first) = starts.first() else {
        return Err(cosmos(
            file,
            1,
            "no line says \"(Format v...)\": not a COSMOS file (a CSMIP/DMG .V1 or .V2 file is another format)",
        ));
    };
    if let Some(index) = lines[..first].iter().position(|l| !l.trim().is_empty()) {
        return Err(cosmos(file, index + 1, "text before the first channel's header"));
    }
    let names = || {
        starts
            .iter()
            .enumerate()
            .map(|(k, &s)| format!("{}: {}", k + 1, channel_name(lines, s)))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let chosen = match (starts.len(), channel) {
        (1, None) => 0,
        (n, None) => {
            return Err(RecordError::Channels {
                file: file.to_owned(),
                count: n,
                names: names(),
            });
        }
        (n, Some(k)) if (1..=n).contains(&k) => k - 1,
        (n, Some(k)) => {
            return Err(RecordError::NoSuchChannel {
                file: file.to_owned(),
                channel: k,
                count: n,
                names: names(),
            });
        }
    };
    let start = starts[chosen];
    let end = starts.get(chosen + 1).copied().unwrap_or(lines.len());
    parse_channel(file, &lines[..end], start, stated)
}

/// A channel's name for a choice: `Sta Chan 1: 360 deg` of its 9th text
/// line, as `360 deg`; `?` when the line says nothing readable.
fn channel_name(lines: &[&str], start: usize) -> String {
    const STATION_CHANNEL_LINE: usize = 8;
    let Some(line) = lines.get(start + STATION_CHANNEL_LINE) else {
        return "?".into();
    };
    let Some(rest) = line.find(':').map(|i| &line[i + 1..]) else {
        return "?".into();
    };
    let end = [rest.find("(Rcrdr"), rest.find("Location")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(rest.len());
    let name = rest[..end].split_whitespace().collect::<Vec<_>>().join(" ");
    if name.is_empty() { "?".into() } else { name }
}

/// A COSMOS header error at a 1-based line.
fn cosmos(file: &str, line: usize, what: &str) -> RecordError {
    RecordError::Cosmos {
        file: file.to_owned(),
        line,
        what: what.to_owned(),
    }
}

/// Parses the channel whose first line is `lines[start]` (`lines` ends
/// where the channel does).
fn parse_channel(
    file: &str,
    lines: &[&str],
    start: usize,
    stated: Option<AccelUnit>,
) -> Result<(Series, AccelUnit, RecordFormat), RecordError> {
    let first = lines[start];
    let format = data_type(first).ok_or_else(|| RecordError::Units {
        file: file.to_owned(),
        line: start + 1,
        text: excerpt(first),
    })?;
    let text_lines = text_line_count(first)
        .ok_or_else(|| cosmos(file, start + 1, "cannot read \"with N text lines\" from the first line"))?;
    // Saturating: the counts come from an untrusted header.
    let integers = header_block(file, lines, start.saturating_add(text_lines), "INTEGER-HEADER")?;
    let reals = header_block(file, lines, integers.next, "REAL-HEADER")?;
    let data_at = skip_comments(file, lines, reals.next)?;
    let data_line = lines[data_at];
    let data_no = data_at + 1;
    let tokens: Vec<&str> = data_line.split_whitespace().collect();
    let (Some(npts), Some(quantity)) = (
        tokens.first().and_then(|t| t.parse::<usize>().ok()),
        tokens.get(1).map(|t| t.to_ascii_lowercase()),
    ) else {
        return Err(cosmos(
            file,
            data_no,
            &format!("expected \"N acceleration pts, ...\", found {:?}", excerpt(data_line)),
        ));
    };
    // A file whose first block is a velocity or a displacement is refused,
    // as is a channel whose header says it measured something else.
    let parameter = integers.value(INT_PARAMETER);
    if quantity != "acceleration" || parameter.is_some_and(|(p, _)| p != 1.0 && p != UNKNOWN) {
        let line = match parameter {
            Some((p, line)) if p != 1.0 && p != UNKNOWN => line,
            _ => data_no,
        };
        return Err(RecordError::Units {
            file: file.to_owned(),
            line,
            text: excerpt(lines[line - 1]),
        });
    }
    let named = data_unit(data_line).map_err(|_| RecordError::Units {
        file: file.to_owned(),
        line: data_no,
        text: excerpt(data_line),
    })?;
    if let (Some(unit), Some((code, line))) = (named, integers.value(INT_UNIT))
        && let Some(header) = unit_of_code(code)
        && header != unit
    {
        return Err(cosmos(
            file,
            line,
            &format!("integer-header value {INT_UNIT} says the unit is {header}, the data line {data_no} says {unit}"),
        ));
    }
    let unit = agreed_unit(file, data_no, named, stated, |file, line| RecordError::NoHeaderUnit {
        file,
        line,
    })?;
    let (step_ms, step_line) = match reals.value(REAL_STEP_MS) {
        Some((ms, line)) if ms != UNKNOWN => (ms, line),
        Some((_, line)) => {
            return Err(cosmos(
                file,
                line,
                &format!("real-header value {REAL_STEP_MS} (the sampling interval, ms) is unknown (-999)"),
            ));
        }
        None => {
            return Err(cosmos(
                file,
                reals.count_line,
                &format!("the real header has no value {REAL_STEP_MS} (the sampling interval, ms)"),
            ));
        }
    };
    let dt = step_ms / 1000.0;
    if !step_in_range(dt) {
        return Err(RecordError::BadStep {
            file: file.to_owned(),
            line: step_line,
            dt,
        });
    }
    if npts == 0 {
        return Err(RecordError::NoSamples {
            file: file.to_owned(),
            line: data_no,
        });
    }
    let layout = FixedWidth::after_format(data_line);
    // Capacity capped: the count comes from an untrusted header.
    let mut accel_g = Vec::with_capacity(npts.min(1 << 20));
    read_block(file, lines, data_at + 1, npts, data_no, layout, |line, value| {
        let g = unit.to_g(value);
        check_accel(file, line, g)?;
        accel_g.push(g);
        Ok(())
    })?;
    if npts < 2 {
        return Err(RecordError::TooFewSamples {
            file: file.to_owned(),
            found: npts,
        });
    }
    // k·dt rather than a running sum: no accumulated round-off.
    let times_s: Vec<f64> = (0..npts).map(|k| k as f64 * dt).collect();
    Ok((Series::from_checked(times_s, accel_g), unit, format))
}

/// The format a channel's first line names: V1 for `Uncorrected
/// acceleration`, V2 for `Corrected acceleration`; `None` for anything
/// else (raw counts of a V0 file, velocity, spectra), which is not an
/// acceleration in a physical unit.
fn data_type(first: &str) -> Option<RecordFormat> {
    let upper = first.to_ascii_uppercase();
    let kind = upper.split("(FORMAT").next().unwrap_or_default();
    let words: Vec<&str> = kind.split_whitespace().collect();
    match words.as_slice() {
        ["UNCORRECTED", "ACCELERATION", ..] => Some(RecordFormat::CosmosV1),
        ["CORRECTED", "ACCELERATION", ..] => Some(RecordFormat::CosmosV2),
        _ => None,
    }
}

/// The N of `(Format v01.20 with N text lines)`.
fn text_line_count(first: &str) -> Option<usize> {
    let upper = first.to_ascii_uppercase();
    let rest = &upper[upper.find("WITH")? + "WITH".len()..];
    let count: usize = rest.split_whitespace().next()?.parse().ok()?;
    rest.contains("TEXT LINE").then_some(count).filter(|&n| n > 0)
}

/// A header block's values, each with its 1-based line.
struct HeaderBlock {
    /// The values in order, with the line each is on.
    values: Vec<(f64, usize)>,
    /// 1-based line announcing the block.
    count_line: usize,
    /// 0-based index of the line after the block.
    next: usize,
}

impl HeaderBlock {
    /// The 1-based `number`th value and its line.
    fn value(&self, number: usize) -> Option<(f64, usize)> {
        number.checked_sub(1).and_then(|i| self.values.get(i)).copied()
    }
}

/// Reads the header block announced on line `index` (0-based) by
/// `N <label> values follow on M lines, Format= (...)`.
fn header_block(file: &str, lines: &[&str], index: usize, label: &str) -> Result<HeaderBlock, RecordError> {
    let what = label.to_ascii_lowercase();
    let Some(line) = lines.get(index) else {
        return Err(cosmos(
            file,
            lines.len(),
            &format!("the file ends before the {what} line"),
        ));
    };
    let count_line = index + 1;
    let upper = line.to_ascii_uppercase();
    let tokens: Vec<&str> = upper.split_whitespace().collect();
    let count = tokens.first().and_then(|t| t.parse::<usize>().ok());
    let on = tokens
        .iter()
        .position(|t| *t == "ON")
        .and_then(|i| tokens.get(i + 1))
        .and_then(|t| t.parse::<usize>().ok());
    let (Some(count), Some(on), true) = (count, on, upper.contains(label)) else {
        return Err(cosmos(
            file,
            count_line,
            &format!(
                "expected \"N {what} values follow on M lines\", found {:?}",
                excerpt(line)
            ),
        ));
    };
    if index.checked_add(on).is_none_or(|last| last >= lines.len()) {
        return Err(cosmos(
            file,
            lines.len(),
            &format!("the file ends inside the {what} announced on line {count_line}"),
        ));
    }
    let layout = FixedWidth::after_format(line);
    let block = &lines[index + 1..=index + on];
    // Capacity capped: the count comes from an untrusted header.
    let mut values = Vec::with_capacity(count.min(1 << 10));
    for (k, text) in block.iter().enumerate() {
        let line_no = count_line + 1 + k;
        values.extend(
            line_values(file, line_no, text, layout)?
                .into_iter()
                .map(|v| (v, line_no)),
        );
    }
    if values.len() != count {
        return Err(cosmos(
            file,
            count_line,
            &format!("{count} {what} values announced on {on} lines, {} found", values.len()),
        ));
    }
    Ok(HeaderBlock {
        values,
        count_line,
        next: index + on + 1,
    })
}

/// Skips the comment block announced on line `index` (0-based) by `N
/// Comment line(s) follow, ...`; returns the index of the data line.
fn skip_comments(file: &str, lines: &[&str], index: usize) -> Result<usize, RecordError> {
    let Some(line) = lines.get(index) else {
        return Err(cosmos(file, lines.len(), "the file ends before the comment line"));
    };
    let count = line.split_whitespace().next().and_then(|t| t.parse::<usize>().ok());
    let Some(count) = count.filter(|_| line.to_ascii_uppercase().contains("COMMENT LINE")) else {
        return Err(cosmos(
            file,
            index + 1,
            &format!("expected \"N Comment line(s) follow\", found {:?}", excerpt(line)),
        ));
    };
    let data_at = index.saturating_add(1).saturating_add(count);
    match lines.get(data_at) {
        Some(data) if !is_data_line(data) => Ok(data_at),
        Some(_) => Err(cosmos(
            file,
            data_at + 1,
            &format!(
                "expected the data line after the {count} comment line(s) of line {}",
                index + 1
            ),
        )),
        None => Err(cosmos(file, lines.len(), "the file ends before the data line")),
    }
}

/// The unit COSMOS table 2 gives a code: 02 = g, 04 = cm/s², 10 = gal
/// (= cm/s²); `None` for the others (in/s², mg, counts, ...), which are not
/// read.
fn unit_of_code(code: f64) -> Option<AccelUnit> {
    if code == 2.0 {
        Some(AccelUnit::G)
    } else if code == 4.0 || code == 10.0 {
        Some(AccelUnit::CentimetresPerSecond2)
    } else {
        None
    }
}

/// The unit a data line names after `units=`: by the code in parentheses
/// (`units=cm/sec2(04)`, `units=g. (02)`, `units=cm/s^2 (4)`), or by its
/// name where there is no code (`units=cm/s^2,Format=...`). `Ok(None)` when
/// the line names no unit; `Err(())` for a unit that is not g or cm/s², or
/// a name that contradicts the code.
fn data_unit(line: &str) -> Result<Option<AccelUnit>, ()> {
    let lower = line.to_ascii_lowercase();
    let Some(at) = lower.find("units") else {
        return Ok(None);
    };
    let rest = lower[at + "units".len()..].trim_start();
    let Some(rest) = rest.strip_prefix('=') else {
        return Ok(None);
    };
    let rest = rest.split("format").next().unwrap_or_default();
    let name = rest
        .split([',', '('])
        .next()
        .unwrap_or_default()
        .trim()
        .trim_end_matches('.');
    let by_name = (!name.is_empty())
        .then(|| AccelUnit::parse_upper_case(name))
        .map(|unit| unit.ok_or(()))
        .transpose()?;
    let code = rest
        .find('(')
        .map(|i| &rest[i + 1..])
        .and_then(|r| r.split(')').next())
        .and_then(|c| c.trim().parse::<f64>().ok());
    match (code.map(unit_of_code), by_name) {
        (Some(None), _) => Err(()),
        (Some(Some(by_code)), Some(by_name)) if by_code != by_name => Err(()),
        (Some(Some(unit)), _) | (None, Some(unit)) => Ok(Some(unit)),
        (None, None) if name.is_empty() => Ok(None),
        (None, None) => Err(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_lines_name_their_unit_by_code_or_by_name() {
        let cases = [
            (
                "13400 acceleration pts, approx  67 secs, units=g.     (02)Format=(8f9.6)",
                Ok(Some(AccelUnit::G)),
            ),
            (
                "42000 acceleration pts, approx  210 secs, units=cm/sec2(04),Format=(1E15.6)",
                Ok(Some(AccelUnit::CentimetresPerSecond2)),
            ),
            (
                "12091 acceleration pts, approx  120 secs, units=cm/s^2 (4),Format=(10F8.5)",
                Ok(Some(AccelUnit::CentimetresPerSecond2)),
            ),
            (
                "12725 acceleration pts, approx 63 secs, units=cm/s^2,Format=(8F10.5)",
                Ok(Some(AccelUnit::CentimetresPerSecond2)),
            ),
            (
                "100 acceleration pts, approx 1 secs, units=in/s/s (07), Format=(8F10.5)",
                Err(()),
            ),
            (
                "100 acceleration pts, approx 1 secs, units=g (04), Format=(8F10.5)",
                Err(()),
            ),
            (
                "100 acceleration pts, approx 1 secs, units=counts (50),Format=(10I8)",
                Err(()),
            ),
            ("100 acceleration pts, approx 1 secs, Format=(10I8)", Ok(None)),
        ];
        for (line, unit) in cases {
            assert_eq!(data_unit(line), unit, "{line}");
        }
    }

    #[test]
    fn fortran_formats_give_the_fields_per_line_and_their_width() {
        let cases = [
            ("Format=(8f9.6)", Some((8, 9))),
            ("Format= (10I8)", Some((10, 8))),
            ("Format=(1E15.6)", Some((1, 15))),
            ("Format=(1F15.6E)", Some((1, 15))),
            ("Format= ( 6F13.6)", Some((6, 13))),
            ("Format=(E15.6)", Some((1, 15))),
            ("Format=(8A10)", None),
            ("no format", None),
        ];
        for (line, expected) in cases {
            let got = FixedWidth::after_format(line).map(|f| (f.per_line, f.width));
            assert_eq!(got, expected, "{line}");
        }
    }

    #[test]
    fn first_lines_name_v1_v2_and_refuse_counts() {
        assert_eq!(
            data_type("Uncorrected acceleration  (Format v01.20 with 13 text lines) Src:  ce23837j"),
            Some(RecordFormat::CosmosV1)
        );
        assert_eq!(
            data_type("Corrected acceleration    (Format v01.20 with 13 text lines)"),
            Some(RecordFormat::CosmosV2)
        );
        assert_eq!(
            data_type("Raw acceleration counts   (Format v01.20 with 13 text lines)"),
            None
        );
        assert_eq!(
            data_type("Corrected velocity        (Format v01.20 with 13 text lines)"),
            None
        );
        assert_eq!(
            text_line_count("Corrected acceleration    (Format v01.20 with 13 text lines)"),
            Some(13)
        );
        assert_eq!(text_line_count("Corrected acceleration (Format v01.20)"), None);
    }
}
