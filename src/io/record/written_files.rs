//! Tests of the COSMOS and ESM readers on files written by the tests
//! (`cosmos_text` for COSMOS, [`esm_file`] for ESM), so that every format
//! and refusal property runs everywhere, with no recording in the tree.
//! Each file holds a damped sine; each expected count, step, unit
//! conversion, value, peak and peak time is computed here from that
//! sequence, and each line an error must name from where the writer put
//! the part it concerns.

use super::cosmos_text::{Channel, ChannelLines, CosmosText, Fortran, UNKNOWN, cosmos_file, damped_sine};
use super::test_helpers::{channel, peak_and_time, raw_channel};
use super::*;

mod cosmos;
mod esm;
mod never_panics;

use esm::esm_file;

/// Reads `content` as a file named `name` (its extension chooses the
/// format), as [`read_record_as`] reads a file.
pub(super) fn read_text(name: &str, content: &str, spec: RecordSpec) -> Result<LoadedRecord, RecordError> {
    read_record_bytes(name, content.as_bytes(), &spec)
}

/// The index of the largest |a| of an analytic sequence, and by how much
/// it exceeds the next largest |a|: a margin wider than twice the writing's
/// rounding means the file's peak is at the same sample.
fn analytic_peak(values: &[f64]) -> (usize, f64) {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&i, &j| values[j].abs().total_cmp(&values[i].abs()));
    (order[0], values[order[0]].abs() - values[order[1]].abs())
}

/// Checks a channel as read against the analytic sequence it was written
/// from: the count, each time k·dt, each value in g within `tolerance(v)`
/// (the writing's rounding, in g, of the value v in the file's unit), and
/// the peak and its time.
fn assert_reads_as_written(
    what: &str,
    r: &LoadedRecord,
    values: &[f64],
    dt: f64,
    to_g: f64,
    tolerance: impl Fn(f64) -> f64,
) {
    assert_eq!(r.series.len(), values.len(), "{what}: count");
    for (k, &t) in r.series.times_s().iter().enumerate() {
        // k·dt, as the reader computes it, to the last bit or two.
        assert!((t - k as f64 * dt).abs() <= 1e-15 * k as f64, "{what}: t[{k}] = {t}");
    }
    for (k, (&a, &v)) in r.series.accel_g().iter().zip(values).enumerate() {
        // The rounding of the text, plus the binary parse and division.
        let tol = tolerance(v) + 4.0 * f64::EPSILON * (v * to_g).abs();
        assert!(
            (a - v * to_g).abs() <= tol,
            "{what}: a[{k}] = {a}, expected {}",
            v * to_g
        );
    }
    let (k, margin) = analytic_peak(values);
    assert!(
        margin * to_g > 2.0 * tolerance(values[k]),
        "{what}: peak margin {margin}"
    );
    let (peak, time) = peak_and_time(&r.series);
    assert!(
        (peak - values[k] * to_g).abs() <= tolerance(values[k]) + 1e-15,
        "{what}: peak {peak}"
    );
    assert!(
        (time - k as f64 * dt).abs() < 1e-12,
        "{what}: peak at {time} s, expected {} s",
        k as f64 * dt
    );
}

/// Three channels of a V1 file in g, as a station's three components:
/// CSMIP's `(8F9.6)`, a `(10F8.5)` whose negative values touch their left
/// neighbour, and `(5E14.6)` at another step. Lines end with CRLF, as
/// CESMD's do.
fn three_channels() -> (Vec<Channel>, CosmosText) {
    let ch1 = Channel::v1("360 deg", 5.0, damped_sine(1500, 0.005, 0.105, 1.3, 0.8));
    let ch2 = Channel {
        format: Fortran::f(10, 8, 5),
        ..Channel::v1("Up", 5.0, damped_sine(1200, 0.005, 0.0488, 4.1, 1.5))
    };
    let ch3 = Channel {
        format: Fortran::e(5, 14, 6),
        ..Channel::v1("90 deg", 10.0, damped_sine(800, 0.010, 0.059, 2.2, 0.5))
    };
    let channels = vec![ch1, ch2, ch3];
    let text = cosmos_file(&channels, true);
    (channels, text)
}

/// A V2 channel in cm/s², with velocity and displacement after it.
fn v2_channel() -> Channel {
    Channel::v2("Up", 5.0, damped_sine(3000, 0.005, 685.0, 0.9, 0.3))
}

#[test]
fn the_suite_sniffer_knows_cosmos_and_esm_by_name_and_by_header() {
    let cosmos = cosmos_file(&[v2_channel()], false).text;
    let head: String = cosmos.chars().take(4096).collect();
    assert!(has_record_header(Path::new("any.name"), &head));
    for name in ["a.V2", "a.v1", "a.V1C", "a.v2c", "a.AT2"] {
        assert!(has_record_header(Path::new(name), ""), "{name}");
    }
    assert!(!has_record_header(
        Path::new("README.md"),
        "# Records\nThese are records.\n"
    ));
    assert!(!has_record_header(Path::new("list.txt"), "0 0.1\n0.01 0.2\n"));
    // A header of `KEY: value` lines without the ESM keys is not ESM.
    assert!(!has_record_header(Path::new("notes.asc"), "TITLE: notes\nAUTHOR: me\n"));
    let esm = esm_file("ACCELERATION", "cm/s^2", 3, &[0.1, 0.2, 0.3]);
    assert!(has_record_header(Path::new("any.name"), &esm));
}
