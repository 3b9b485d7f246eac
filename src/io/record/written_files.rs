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

#[test]
fn each_channel_of_a_written_cosmos_v1_file_reads_as_written() {
    let (channels, file) = three_channels();
    for (k, c) in channels.iter().enumerate() {
        let r = read_text("three.V1C", &file.text, channel(k + 1)).unwrap();
        assert_eq!(r.format, RecordFormat::CosmosV1);
        assert_eq!(r.unit, AccelUnit::G, "the data line's units=g. (02)");
        assert_reads_as_written(c.name, &r, &c.values, c.step_ms / 1000.0, 1.0, |v| c.format.rounding(v));
    }
    // The second channel's negative values touch the value before them.
    let ChannelLines {
        first_value,
        after_values,
        ..
    } = file.channels[1];
    let glued = file
        .text
        .lines()
        .take(after_values - 1)
        .skip(first_value - 1)
        .filter(|l| l.split_whitespace().any(|f| f.len() > 8))
        .count();
    assert!(glued > 10, "{glued} lines with touching values");
    // A file named otherwise is known by its first line.
    let r = read_text("three.txt", &file.text, channel(3)).unwrap();
    assert_eq!(r.series.len(), 800);
}

#[test]
fn the_written_headers_read_by_the_real_files_own_parser_give_what_was_written() {
    // The independent parser of the real-file tests (by whitespace and the
    // header layout) finds in the written file the count, the step (value
    // 62) and the peak and its time (values 64, 65) where a real file has
    // them: the writer follows the layout of the real files.
    let (channels, file) = three_channels();
    let text = file.text.replace('\r', "");
    for (k, c) in channels.iter().enumerate() {
        let raw = raw_channel(&text, k + 1);
        assert_eq!(raw.count, c.values.len());
        assert_eq!(raw.step_ms, c.step_ms);
        let (i, _) = analytic_peak(&c.values);
        assert!(
            (raw.peak - c.values[i]).abs() <= 0.5e-6,
            "{} vs {}",
            raw.peak,
            c.values[i]
        );
        assert!((raw.peak_time_s - i as f64 * c.step_ms / 1000.0).abs() <= 0.5e-6);
        // Value by value where the values are parted by spaces (not the
        // glued channel 2, which whitespace cannot part): within the
        // rounding of (8F9.6), and of (5E14.6) for values under 0.1.
        let tol = [0.5e-6, 0.0, 0.5e-7][k];
        if k != 1 {
            for (a, v) in raw.values.iter().zip(&c.values) {
                assert!((a - v).abs() <= tol, "{a} vs {v}");
            }
        }
    }
}

/// A V2 channel in cm/s², with velocity and displacement after it.
fn v2_channel() -> Channel {
    Channel::v2("Up", 5.0, damped_sine(3000, 0.005, 685.0, 0.9, 0.3))
}

#[test]
fn a_written_cosmos_v2_file_reads_in_cm_s2_converted_to_g() {
    let c = v2_channel();
    let file = cosmos_file(std::slice::from_ref(&c), false);
    let r = read_text("bmr.V2c", &file.text, RecordSpec::default()).unwrap();
    assert_eq!(r.format, RecordFormat::CosmosV2);
    assert_eq!(r.unit, AccelUnit::CentimetresPerSecond2, "units=cm/sec2(04)");
    // 1 g = 981 cm/s² in this model (g = 9.81 m/s²).
    assert_reads_as_written("V2", &r, &c.values, 0.005, 1.0 / 981.0, |v| {
        c.format.rounding(v) / 981.0
    });
    assert!((r.series.duration_s() - 2999.0 * 0.005).abs() < 1e-12);
}

#[test]
fn a_cosmos_file_of_three_channels_is_refused_without_a_stated_channel() {
    let (_, file) = three_channels();
    let e = read_text("three.V1C", &file.text, RecordSpec::default()).unwrap_err();
    assert!(matches!(e, RecordError::Channels { count: 3, .. }));
    assert_eq!(
        e.to_string(),
        "three.V1C: holds 3 channels (1: 360 deg; 2: Up; 3: 90 deg); state which one to read (1 to 3)"
    );
    let m = read_text("three.V1C", &file.text, channel(4)).unwrap_err().to_string();
    assert_eq!(
        m,
        "three.V1C: no channel 4: the file holds 3 (1: 360 deg; 2: Up; 3: 90 deg)"
    );
    // A one-channel file reads as channel 1, and no other.
    let v2 = cosmos_file(&[v2_channel()], false).text;
    assert_eq!(read_text("one.V2c", &v2, channel(1)).unwrap().series.len(), 3000);
    assert!(matches!(
        read_text("one.V2c", &v2, channel(2)).unwrap_err(),
        RecordError::NoSuchChannel {
            channel: 2,
            count: 1,
            ..
        }
    ));
    let m = read_text(
        "one.txt",
        "0 0.1\n0.01 0.2\n",
        RecordSpec {
            unit: Some(AccelUnit::G),
            ..channel(2)
        },
    )
    .unwrap_err()
    .to_string();
    assert_eq!(m, "one.txt: channel 2 stated, but a two-column file holds one channel");
}

#[test]
fn a_stated_unit_must_agree_with_the_cosmos_data_line() {
    let file = cosmos_file(&[v2_channel()], false);
    let data = file.channels[0].data;
    let e = read_text("bmr.V2c", &file.text, RecordSpec::stated(AccelUnit::G)).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("bmr.V2c:{data}: the header says the unit is cm/s2, but g was stated")
    );
    let agreed = read_text(
        "bmr.V2c",
        &file.text,
        RecordSpec::stated(AccelUnit::CentimetresPerSecond2),
    )
    .unwrap();
    assert_eq!(agreed.series.len(), 3000);
}

#[test]
fn cosmos_velocity_counts_and_other_units_are_refused_naming_their_line() {
    let file = cosmos_file(&[v2_channel()], false);
    let ChannelLines {
        first,
        integer_first,
        data,
        ..
    } = file.channels[0];
    let cases = [
        // A velocity block where the acceleration belongs.
        (
            "acceleration pts",
            "velocity     pts",
            format!("bmr.V2c:{data}: not an acceleration record"),
        ),
        // The header's physical parameter (integer value 2): velocity.
        (
            "       2       1       4     120",
            "       2       2       4     120",
            format!("bmr.V2c:{integer_first}: not an acceleration record"),
        ),
        // Raw counts (a V0 file's first line).
        (
            "Corrected acceleration    (Format",
            "Raw acceleration counts   (Format",
            format!("bmr.V2c:{first}: not an acceleration record"),
        ),
        // A unit that is not g or cm/s² (in/s², code 07).
        (
            "units=cm/sec2(04)",
            "units=in/s/s(07)",
            format!("bmr.V2c:{data}: not an acceleration record"),
        ),
        // The data line and the integer header disagree on the unit.
        (
            "units=cm/sec2(04)",
            "units=g(02)",
            format!(
                "bmr.V2c:{integer_first}: COSMOS header: integer-header value 3 says the unit is cm/s2, the data line {data} says g"
            ),
        ),
    ];
    for (from, to, expected) in cases {
        assert_eq!(file.text.matches(from).count(), 1, "{from}");
        let e = read_text("bmr.V2c", &file.text.replacen(from, to, 1), RecordSpec::default()).unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with(&expected), "{m}\nexpected: {expected}");
    }
}

#[test]
fn a_v2_channel_reads_its_acceleration_and_leaves_the_velocity_after_it() {
    let with = v2_channel();
    let without = Channel {
        velocity: false,
        ..with.clone()
    };
    let a = cosmos_file(&[with], false);
    let b = cosmos_file(&[without], false);
    // Both blocks are there, as long as the acceleration, and differ from it.
    assert_eq!(a.text.matches("    3000 velocity     pts").count(), 1);
    assert_eq!(a.text.matches("    3000 displacement pts").count(), 1);
    assert!(!b.text.contains("velocity"));
    let a = read_text("with.V2c", &a.text, RecordSpec::default()).unwrap();
    let b = read_text("without.V2c", &b.text, RecordSpec::default()).unwrap();
    assert_eq!(a.series, b.series);
    // And in a file of two such channels, the second is read past the
    // first's velocity and displacement.
    let two = cosmos_file(
        &[
            v2_channel(),
            Channel::v2("90 deg", 5.0, damped_sine(500, 0.005, 120.0, 3.0, 2.0)),
        ],
        false,
    );
    let r = read_text("two.V2c", &two.text, channel(2)).unwrap();
    assert_eq!(r.series.len(), 500);
    let r = read_text("two.V2c", &two.text, channel(1)).unwrap();
    assert_eq!(r.series, b.series);
}

#[test]
fn a_truncated_cosmos_file_and_a_wrong_count_name_their_lines() {
    let file = cosmos_file(&[v2_channel()], false);
    let ChannelLines {
        integer_count,
        data,
        after_values,
        ..
    } = file.channels[0];
    let lines: Vec<&str> = file.text.lines().collect();
    // Cut after 1000 of the 3000 values, one a line: the block ends on the
    // 1000th value's line.
    let cut = lines[..data + 1000].join("\n");
    let m = read_text("bmr.V2c", &cut, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert_eq!(
        m,
        format!("bmr.V2c:{}: 1000 values where line {data} announces 3000", data + 1000)
    );
    // One value announced more or fewer than the file holds: the block
    // ends at the velocity block's data line.
    assert_eq!(after_values, data + 3001);
    for announced in [3001, 2999] {
        let changed = file
            .text
            .replacen("    3000 acceleration", &format!("{announced:>8} acceleration"), 1);
        let m = read_text("bmr.V2c", &changed, RecordSpec::default())
            .unwrap_err()
            .to_string();
        assert_eq!(
            m,
            format!("bmr.V2c:{after_values}: 3000 values where line {data} announces {announced}")
        );
    }
    // A header block that ends early: the file stops 5 lines into the
    // integer header's 10.
    let short_header = lines[..integer_count + 5].join("\n");
    let m = read_text("bmr.V2c", &short_header, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with(&format!(
            "bmr.V2c:{}: COSMOS header: the file ends inside the integer-header announced on line {integer_count}",
            integer_count + 5
        )),
        "{m}"
    );
}

#[test]
fn an_unknown_cosmos_step_and_a_non_cosmos_v2_are_refused_naming_their_line() {
    let unknown = Channel {
        step_ms: UNKNOWN,
        ..v2_channel()
    };
    let file = cosmos_file(&[unknown], false);
    let step = file.channels[0].step;
    // Value 62 is the 2nd of its line in (5F15.6).
    let line = file.text.lines().nth(step - 1).unwrap();
    assert_eq!(line.split_whitespace().nth(1), Some("-999.000000"), "{line}");
    let m = read_text("bmr.V2c", &file.text, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with(&format!(
            "bmr.V2c:{step}: COSMOS header: real-header value 62 (the sampling interval, ms) is unknown"
        )),
        "{m}"
    );
    // A step outside [1e-5 s, 10 s] names the same line.
    let file = cosmos_file(
        &[Channel {
            step_ms: 20_000.0,
            ..v2_channel()
        }],
        false,
    );
    let m = read_text("bmr.V2c", &file.text, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with(&format!("bmr.V2c:{step}: invalid time step DT = 20.0 s")),
        "{m}"
    );
    // A CSMIP (DMG) file carries .V2 too; it is not read as anything else.
    let dmg = "CORRECTED ACCELEROGRAM 18-0829-0233 CE23837\n  .0050 secs\n";
    let m = read_text("CE23837.V2", dmg, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with("CE23837.V2:1: COSMOS header: no line says \"(Format v...)\""),
        "{m}"
    );
}

#[test]
fn cosmos_values_written_without_spaces_are_cut_at_their_stated_width() {
    // (10F8.5) in g: every negative value fills its 8 characters and
    // touches the value before it.
    let c = Channel {
        format: Fortran::f(10, 8, 5),
        ..Channel::v1("360 deg", 5.0, damped_sine(400, 0.005, 0.9, 2.0, 1.0))
    };
    let file = cosmos_file(std::slice::from_ref(&c), false);
    let first = file.channels[0].first_value;
    let glued = file
        .text
        .lines()
        .skip(first - 1)
        .take(40)
        .filter(|l| l.split_whitespace().any(|f| f.len() > 8))
        .count();
    assert!(glued > 5, "{glued} lines with touching values");
    let r = read_text("glued.v1", &file.text, RecordSpec::default()).unwrap();
    assert_reads_as_written("glued", &r, &c.values, 0.005, 1.0, |v| c.format.rounding(v));
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

/// A file written to the temporary folder, removed on drop.
struct TempFile(std::path::PathBuf);

impl TempFile {
    fn new(name: &str, content: &str) -> Self {
        let path = std::env::temp_dir().join(format!("rocking-written-{}-{name}", std::process::id()));
        std::fs::write(&path, content).unwrap();
        Self(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

#[test]
fn a_config_chooses_a_cosmos_channel_and_its_summary_repeats_the_choice() {
    use crate::io::config;
    let (channels, file) = three_channels();
    let temp = TempFile::new("three.V1C", &file.text);
    let path = temp.0.display().to_string();
    let sets = |extra: &[&str]| {
        let mut sets = vec![
            "excitation.kind=\"record\"".to_owned(),
            format!("excitation.file_h={path:?}"),
        ];
        sets.extend(extra.iter().map(|s| s.to_string()));
        sets
    };
    let s = config::load(None, None, &sets(&["excitation.channel_h=2"])).unwrap();
    let record = s.excitation.record_h.as_ref().unwrap();
    assert_eq!(record.channel, Some(2));
    // Channel 2 is the vertical (Up): its peak, from the analytic sequence,
    // within the (10F8.5) rounding.
    let up = &channels[1].values;
    let (k, _) = analytic_peak(up);
    let (peak, time) = peak_and_time(&record.series);
    assert!((peak - up[k]).abs() <= 0.5e-5, "{peak} vs {}", up[k]);
    assert!((time - k as f64 * 0.005).abs() < 1e-12);
    let json = config::to_json(&s);
    assert_eq!(json["excitation"]["channel_h"], 2);
    assert!(json["excitation"]["channel_v"].is_null());
    let e = config::load(None, None, &sets(&[])).unwrap_err().to_string();
    assert!(
        e.starts_with("excitation.channel_h: ") && e.contains("holds 3 channels (1: 360 deg; 2: Up; 3: 90 deg)"),
        "{e}"
    );
    let e = config::load(None, None, &sets(&["excitation.channel_h=0"]))
        .unwrap_err()
        .to_string();
    assert_eq!(e, "excitation.channel_h: 0: channels are counted from 1");
    let e = config::load(None, None, &["excitation.channel_v=1".to_owned()])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("excitation.channel_v: needs excitation.file_v"), "{e}");
}

// ---- ESM ----

/// The header of an ESM file as the database writes it (DYNA 1.2: the
/// keys of a real file, in its order); `{ndata}`, `{units}` and
/// `{data_type}` are filled in by [`esm_file`].
const ESM_HEADER: [(&str, &str); 64] = [
    ("EVENT_NAME", "GREECE"),
    ("EVENT_ID", "EMSC-20190728_0000106"),
    ("EVENT_DATE_YYYYMMDD", "20190728"),
    ("EVENT_TIME_HHMMSS", "160908"),
    ("EVENT_LATITUDE_DEGREE", "38.1000"),
    ("EVENT_LONGITUDE_DEGREE", "23.5400"),
    ("EVENT_DEPTH_KM", "9.0"),
    ("HYPOCENTER_REFERENCE", "EMSC-CSEM"),
    ("MAGNITUDE_W", ""),
    ("MAGNITUDE_W_REFERENCE", ""),
    ("MAGNITUDE_L", "4.6"),
    ("MAGNITUDE_L_REFERENCE", "EMSC-CSEM"),
    ("FOCAL_MECHANISM", ""),
    ("NETWORK", "HL"),
    ("STATION_CODE", "DLFA"),
    ("STATION_NAME", "Delfoi, Greece"),
    ("STATION_LATITUDE_DEGREE", "38.478360"),
    ("STATION_LONGITUDE_DEGREE", "22.495830"),
    ("STATION_ELEVATION_M", "570"),
    ("LOCATION", ""),
    ("SENSOR_DEPTH_M", "0.0"),
    ("VS30_M/S", ""),
    ("SITE_CLASSIFICATION_EC8", ""),
    ("MORPHOLOGIC_CLASSIFICATION", ""),
    ("EPICENTRAL_DISTANCE_KM", "100.5"),
    ("EARTHQUAKE_BACKAZIMUTH_DEGREE", "114.4"),
    ("DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", "20190728_160905.700"),
    ("DATE_TIME_FIRST_SAMPLE_PRECISION", "milliseconds"),
    ("SAMPLING_INTERVAL_S", "0.005000"),
    ("NDATA", "{ndata}"),
    ("DURATION_S", "69.380"),
    ("STREAM", "HNE"),
    ("UNITS", "{units}"),
    ("INSTRUMENT", "sensor = CMG_5 [Unknown] | digitizer = Unknown [Unknown]"),
    ("INSTRUMENT_ANALOG/DIGITAL", "D"),
    ("INSTRUMENTAL_FREQUENCY_HZ", ""),
    ("INSTRUMENTAL_DAMPING", ""),
    ("FULL_SCALE_G", ""),
    ("N_BIT_DIGITAL_CONVERTER", ""),
    ("PGA_CM/S^2", "-0.227973"),
    ("TIME_PGA_S", "36.310000"),
    ("BASELINE_CORRECTION", "BASELINE REMOVED"),
    ("FILTER_TYPE", "BUTTERWORTH"),
    ("FILTER_ORDER", "2"),
    ("LOW_CUT_FREQUENCY_HZ", "0.200"),
    ("HIGH_CUT_FREQUENCY_HZ", "30.000"),
    ("LATE/NORMAL_TRIGGERED", "NT"),
    ("DATABASE_VERSION", "DYNA 1.0"),
    ("HEADER_FORMAT", "DYNA 1.2"),
    ("DATA_TYPE", "{data_type}"),
    ("PROCESSING", "manual (Paolucci et al., 2011)"),
    ("DATA_TIMESTAMP_YYYYMMDD_HHMMSS", "20190730_121037.500"),
    ("DATA_LICENSE", ""),
    ("DATA_CITATION", ""),
    ("DATA_CREATOR", ""),
    ("ORIGINAL_DATA_MEDIATOR_CITATION", ""),
    ("ORIGINAL_DATA_MEDIATOR", "http://eida.gein.noa.gr/"),
    ("ORIGINAL_DATA_CREATOR_CITATION", ""),
    ("ORIGINAL_DATA_CREATOR", ""),
    ("USER1", "/home/dyna/processing.py --tmp /tmp/fpacor/"),
    ("USER2", ""),
    ("USER3", ""),
    ("USER4", ""),
    ("USER5", ""),
];

/// An ESM file with the header above and the samples given.
fn esm_file(data_type: &str, units: &str, ndata: usize, values: &[f64]) -> String {
    let mut s = String::new();
    for (key, value) in ESM_HEADER {
        let value = value
            .replace("{ndata}", &ndata.to_string())
            .replace("{units}", units)
            .replace("{data_type}", data_type);
        s.push_str(&format!("{key}: {value}\n"));
    }
    for v in values {
        s.push_str(&format!("{v:.6}\n"));
    }
    s
}

/// Line numbers of the layout above.
const ESM_DT_LINE: usize = 29;
const ESM_NDATA_LINE: usize = 30;
const ESM_UNITS_LINE: usize = 33;
const ESM_DATA_TYPE_LINE: usize = 50;
const ESM_FIRST_VALUE_LINE: usize = 65;

#[test]
fn an_esm_file_reads_its_count_step_and_unit_from_the_header() {
    let values = [0.0, -0.227973, 0.1, 0.05];
    let text = esm_file("ACCELERATION", "cm/s^2", 4, &values);
    for name in ["HL.TEST..HNE.D.20190728.160908.C.ACC.ASC", "record.txt"] {
        let r = read_text(name, &text, RecordSpec::default()).unwrap();
        assert_eq!(r.format, RecordFormat::Esm);
        assert_eq!(r.unit, AccelUnit::CentimetresPerSecond2);
        assert_eq!(r.series.times_s(), &[0.0, 0.005, 0.01, 0.015]);
        for (a, v) in r.series.accel_g().iter().zip(values) {
            assert!((a - v / 981.0).abs() <= f64::EPSILON * (v / 981.0).abs());
        }
    }
    assert!(has_record_header(Path::new("x.ASC"), &text));
}

#[test]
fn esm_refusals_name_their_line() {
    let ok = [0.1, 0.2, 0.3];
    let cases = [
        (
            esm_file("VELOCITY", "cm/s", 3, &ok),
            format!("e.ASC:{ESM_DATA_TYPE_LINE}: not an acceleration record"),
        ),
        (
            esm_file("ACCELERATION", "cm/s", 3, &ok),
            format!("e.ASC:{ESM_UNITS_LINE}: not an acceleration record"),
        ),
        (
            esm_file("ACCELERATION", "", 3, &ok),
            format!("e.ASC:{ESM_UNITS_LINE}: the header states no unit"),
        ),
        (
            esm_file("ACCELERATION", "cm/s^2", 4, &ok),
            format!(
                "e.ASC:{}: 3 values where line {ESM_NDATA_LINE} announces 4",
                ESM_FIRST_VALUE_LINE + 2
            ),
        ),
        (
            esm_file("ACCELERATION", "cm/s^2", 2, &ok),
            format!(
                "e.ASC:{}: 3 values where line {ESM_NDATA_LINE} announces 2",
                ESM_FIRST_VALUE_LINE + 2
            ),
        ),
        (
            esm_file("ACCELERATION", "cm/s^2", 3, &ok)
                .replace("SAMPLING_INTERVAL_S: 0.005000", "SAMPLING_INTERVAL_S: 0"),
            format!("e.ASC:{ESM_DT_LINE}: invalid time step DT = 0.0 s"),
        ),
        (
            esm_file("ACCELERATION", "cm/s^2", 3, &ok).replace("NDATA: 3\n", ""),
            format!(
                "e.ASC:{}: the header (ending here) has no NDATA line",
                ESM_FIRST_VALUE_LINE - 2
            ),
        ),
    ];
    for (text, expected) in cases {
        let m = read_text("e.ASC", &text, RecordSpec::default())
            .unwrap_err()
            .to_string();
        assert!(m.starts_with(&expected), "{m}\nexpected: {expected}");
    }
    // A stated unit: must agree with the header's, and supplies an empty one.
    let text = esm_file("ACCELERATION", "cm/s^2", 3, &ok);
    let m = read_text("e.ASC", &text, RecordSpec::stated(AccelUnit::MetresPerSecond2))
        .unwrap_err()
        .to_string();
    assert_eq!(
        m,
        format!("e.ASC:{ESM_UNITS_LINE}: the header says the unit is cm/s2, but m/s2 was stated")
    );
    let empty = esm_file("ACCELERATION", "", 3, &ok);
    let r = read_text("e.ASC", &empty, RecordSpec::stated(AccelUnit::G)).unwrap();
    assert_eq!(r.series.accel_g(), &ok);
}

// ---- Never panics ----

/// Lines a broken COSMOS or ESM file might hold instead of its own: other
/// headers' lines, absurd counts, empty values, random text.
fn odd_line() -> impl proptest::strategy::Strategy<Value = String> {
    use proptest::prelude::*;
    prop_oneof![
        Just(" 100 Integer-header values follow on  10 lines, Format= (10I8)".to_owned()),
        Just(" 99999999999999999999 Real-header values follow on 18446744073709551615 lines".to_owned()),
        Just("   1 Comment line(s) follow, each starting with a \"|\":".to_owned()),
        Just("18446744073709551615 acceleration pts, approx 67 secs, units=g (02),Format=(8f9.6)".to_owned()),
        Just("   3 velocity pts, units=cm/sec (05),Format=(0F0.0)".to_owned()),
        Just("Corrected acceleration (Format v01.20 with 0 text lines)".to_owned()),
        Just("Uncorrected acceleration (Format v01.20 with 18446744073709551615 text lines)".to_owned()),
        Just("NDATA: 18446744073709551615".to_owned()),
        Just("SAMPLING_INTERVAL_S: -1".to_owned()),
        Just("UNITS: ".to_owned()),
        Just("-0.00003-0.00004-1e999 nan".to_owned()),
        Just(String::new()),
        "[ -~]{0,40}",
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(
        if std::env::var("ROCKING_STRESS").is_ok_and(|v| v == "1") { 20_000 } else { 200 }
    ))]

    #[test]
    fn cosmos_and_esm_files_with_lines_changed_never_panic(
        esm in proptest::prelude::any::<bool>(),
        edits in proptest::collection::vec((0..90_usize, odd_line()), 0..6),
        cut in 1..120_usize,
        channel in proptest::option::of(0..5_usize),
        ext in proptest::sample::select(vec!["V1C", "v2", "ASC", "txt"]),
    ) {
        let base = if esm {
            esm_file("ACCELERATION", "cm/s^2", 20, &[0.5; 20])
        } else {
            three_channels().1.text.lines().take(100).collect::<Vec<_>>().join("\n")
        };
        let mut lines: Vec<String> = base.lines().map(str::to_owned).collect();
        for (at, line) in edits {
            if at < lines.len() {
                lines[at] = line;
            }
        }
        lines.truncate(cut);
        let text = lines.join("\n");
        let spec = RecordSpec { channel, ..RecordSpec::default() };
        match read_text(&format!("edited.{ext}"), &text, spec) {
            Ok(r) => proptest::prop_assert!(Series::new(r.series.times_s().to_vec(), r.series.accel_g().to_vec()).is_ok()),
            Err(e) => proptest::prop_assert!(!e.to_string().contains('\n')),
        }
    }
}
