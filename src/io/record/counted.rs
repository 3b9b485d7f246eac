//! Reading a counted block of values: the data of the formats whose header
//! announces how many samples follow (COSMOS, ESM), and the headers of
//! COSMOS, whose lines may be written in fixed-width Fortran fields with no
//! space between two values (`-0.00003-0.00004` under `(10F8.5)`).

use super::{RecordError, fields, parse_float, parse_number};

/// A Fortran edit descriptor as COSMOS writes it after `Format=`:
/// `(8F10.5)`, `(1E15.6)`, `(10I8)`: so many fields of a fixed width per
/// line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct FixedWidth {
    /// Fields per line.
    pub per_line: usize,
    /// Characters per field.
    pub width: usize,
}

impl FixedWidth {
    /// Reads the descriptor after `Format=` in `line` (any case, spaces
    /// allowed: `Format= (6F13.6)`, `Format=(8f9.6)`); `None` when there is
    /// none or it is not `(nXw...)` with X one of F, E, G, D, I.
    pub(crate) fn after_format(line: &str) -> Option<FixedWidth> {
        let upper = line.to_ascii_uppercase();
        let rest = &upper[upper.find("FORMAT")? + "FORMAT".len()..];
        let rest = rest.trim_start().strip_prefix('=')?.trim_start().strip_prefix('(')?;
        let inner: String = rest
            .chars()
            .take_while(|c| *c != ')')
            .filter(|c| !c.is_whitespace())
            .collect();
        let digits = |s: &str| s.chars().take_while(char::is_ascii_digit).count();
        let n = digits(&inner);
        let per_line = if n == 0 { 1 } else { inner[..n].parse().ok()? };
        let after = &inner[n..];
        let letter = after.chars().next()?;
        if !matches!(letter, 'F' | 'E' | 'G' | 'D' | 'I') {
            return None;
        }
        let after = &after[1..];
        let w = digits(after);
        let width: usize = after[..w].parse().ok()?;
        (per_line > 0 && width > 0).then_some(FixedWidth { per_line, width })
    }

    /// The fields of `line` cut at the fixed widths, trimmed; blank fields at
    /// the end of the line are dropped (a last line is often short).
    fn cut(self, line: &str) -> Vec<String> {
        let chars: Vec<char> = line.chars().collect();
        let mut out: Vec<String> = chars
            .chunks(self.width)
            .take(self.per_line)
            .map(|c| c.iter().collect::<String>().trim().to_owned())
            .collect();
        while out.last().is_some_and(String::is_empty) {
            out.pop();
        }
        out
    }
}

/// Whether a line can hold data values: only digits, signs, points,
/// exponent letters (E, D) and separators. A line with other letters ends
/// a data block (`End-of-data for Chan 1`, `13400 velocity pts, ...`).
pub(super) fn is_data_line(line: &str) -> bool {
    !line.trim().is_empty()
        && !line
            .chars()
            .any(|c| c.is_ascii_alphabetic() && !matches!(c, 'e' | 'E' | 'd' | 'D'))
}

/// The numbers on one line: split at whitespace, commas and semicolons, or,
/// when a field is not a number and a fixed width is known, cut at that
/// width. Whitespace first, because a file whose values are separated by
/// spaces reads the same whatever its stated format; the widths only part
/// values written with no space between them.
pub(super) fn line_values(
    file: &str,
    line_no: usize,
    line: &str,
    layout: Option<FixedWidth>,
) -> Result<Vec<f64>, RecordError> {
    let split: Vec<&str> = fields(line).collect();
    if split.iter().all(|f| parse_float(f).is_some()) {
        return split.iter().map(|f| parse_number(file, line_no, f)).collect();
    }
    match layout {
        Some(layout) => layout
            .cut(line)
            .iter()
            .map(|f| parse_number(file, line_no, f))
            .collect(),
        None => split.iter().map(|f| parse_number(file, line_no, f)).collect(),
    }
}

/// A block of `expected` values starting at the 0-based line `start`, as
/// announced on the 1-based line `announced_at`; each value is passed to
/// `take` with its 1-based line (to convert and check it). The block ends
/// at the first line that is not data, or at the end of `lines`.
///
/// # Errors
/// [`RecordError::DataCount`] naming the line where the block ended when it
/// holds fewer or more values than announced, or the errors of
/// [`line_values`] and `take`.
pub(super) fn read_block(
    file: &str,
    lines: &[&str],
    start: usize,
    expected: usize,
    announced_at: usize,
    layout: Option<FixedWidth>,
    mut take: impl FnMut(usize, f64) -> Result<(), RecordError>,
) -> Result<usize, RecordError> {
    let mut found = 0_usize;
    let mut index = start;
    while let Some(line) = lines.get(index) {
        if line.trim().is_empty() {
            index += 1;
            continue;
        }
        if !is_data_line(line) {
            break;
        }
        for value in line_values(file, index + 1, line, layout)? {
            found += 1;
            if found <= expected {
                take(index + 1, value)?;
            }
        }
        index += 1;
    }
    if found != expected {
        // The line the block ended on: the first that is not data, or the
        // last of the file that is not blank.
        let line = if index < lines.len() {
            index + 1
        } else {
            lines
                .iter()
                .rposition(|l| !l.trim().is_empty())
                .map_or(lines.len(), |i| i + 1)
        };
        return Err(RecordError::DataCount {
            file: file.to_owned(),
            line,
            expected,
            found,
            announced_at,
        });
    }
    Ok(index)
}
