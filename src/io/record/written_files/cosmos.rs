//! The COSMOS reader on written V1 and V2 files: channels, units, counts, steps, values written without spaces, refusals naming their line, and the config's channel choice.

use super::*;

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
