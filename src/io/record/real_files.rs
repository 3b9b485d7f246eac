//! Tests of the COSMOS and ESM readers on real files (COSMOS: in
//! `tests/data/records/`, their provenance in its README) and on files
//! changed from them to show each refusal, naming its line. Each expected
//! value is the file's own header value or is computed here from the raw
//! numbers by a reader written in the test.

use super::*;

const RECORDS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/records");

/// CGS station 23837 (Pomona), 2018-08-29: three channels of COSMOS V1, in g.
const CE23837_V1C: &str = "CE23837.V1C";

/// USGS/AK station BMR, 2018-11-30 Anchorage M7.0, vertical: COSMOS V2 in cm/s².
const AKBMR_V2C: &str = "us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c";

fn text_of(name: &str) -> String {
    std::fs::read_to_string(Path::new(RECORDS).join(name)).unwrap()
}

/// Reads `content` as a file named `name` (its extension chooses the
/// format), as [`read_record_as`] reads a file.
fn read_text(name: &str, content: &str, spec: RecordSpec) -> Result<LoadedRecord, RecordError> {
    read_record_bytes(name, content.as_bytes(), &spec)
}

fn channel(k: usize) -> RecordSpec {
    RecordSpec {
        channel: Some(k),
        ..RecordSpec::default()
    }
}

/// The test's own reading of a COSMOS channel, by the header layout the
/// format fixes and by whitespace: the data line's count, the real
/// header's sampling interval (value 62, ms), peak (64) and its time (65),
/// and the values.
struct Raw {
    count: usize,
    step_ms: f64,
    peak: f64,
    peak_time_s: f64,
    values: Vec<f64>,
}

fn raw_channel(text: &str, k: usize) -> Raw {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.contains("(Format v"))
        .nth(k - 1)
        .unwrap()
        .0;
    let real_at = start + lines[start..].iter().position(|l| l.contains("Real-header")).unwrap();
    let real_lines: usize = lines[real_at].split_whitespace().nth(5).unwrap().parse().unwrap();
    let reals: Vec<f64> = lines[real_at + 1..=real_at + real_lines]
        .iter()
        .flat_map(|l| l.split_whitespace().map(|v| v.parse::<f64>().unwrap()))
        .collect();
    let data_at = start
        + lines[start..]
            .iter()
            .position(|l| l.contains("acceleration pts"))
            .unwrap();
    let count: usize = lines[data_at].split_whitespace().next().unwrap().parse().unwrap();
    let values: Vec<f64> = lines[data_at + 1..]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .take(count)
        .map(|v| v.parse().unwrap())
        .collect();
    Raw {
        count,
        step_ms: reals[61],
        peak: reals[63],
        peak_time_s: reals[64],
        values,
    }
}

/// The largest |a| of a series and its time.
fn peak_and_time(series: &Series) -> (f64, f64) {
    let (k, a) = series
        .accel_g()
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap();
    (*a, series.times_s()[k])
}

#[test]
fn each_channel_of_a_cosmos_v1_file_reads_as_its_header_states() {
    let text = text_of(CE23837_V1C);
    let path = Path::new(RECORDS).join(CE23837_V1C);
    for k in 1..=3 {
        let raw = raw_channel(&text, k);
        let r = read_record_as(&path, &channel(k)).unwrap();
        assert_eq!(r.format, RecordFormat::CosmosV1);
        assert_eq!(r.unit, AccelUnit::G, "the data line's units=g (02)");
        assert_eq!(raw.count, 13400);
        assert_eq!(r.series.len(), raw.count);
        assert_eq!(raw.step_ms, 5.0);
        let dt = raw.step_ms / 1000.0;
        for (i, &t) in r.series.times_s().iter().enumerate() {
            assert_eq!(t, i as f64 * dt);
        }
        // Values in g are read as written: exactly the test's parse.
        assert_eq!(r.series.accel_g(), raw.values.as_slice(), "channel {k}");
        // The header's peak (6 decimals, as the data) and its time.
        let (peak, time) = peak_and_time(&r.series);
        assert_eq!(peak, raw.peak, "channel {k}");
        assert!((time - raw.peak_time_s).abs() < 1e-12, "channel {k}: {time} s");
    }
    // The peaks the header states, for the record: 360°, Up, 90°.
    let peaks: Vec<f64> = (1..=3).map(|k| raw_channel(&text, k).peak).collect();
    assert_eq!(peaks, [-0.105433, 0.048757, -0.059022]);
}

#[test]
fn a_cosmos_v2_file_reads_in_cm_s2_as_its_header_states() {
    let text = text_of(AKBMR_V2C);
    let raw = raw_channel(&text, 1);
    let r = read_record_as(&Path::new(RECORDS).join(AKBMR_V2C), &RecordSpec::default()).unwrap();
    assert_eq!(r.format, RecordFormat::CosmosV2);
    assert_eq!(r.unit, AccelUnit::CentimetresPerSecond2, "units=cm/sec2(04)");
    assert_eq!((raw.count, raw.step_ms), (42000, 5.0));
    assert_eq!(r.series.len(), 42000);
    assert_eq!(r.series.times_s()[1], 0.005);
    assert_eq!(r.series.duration_s(), 41999.0 * 0.005);
    // cm/s² to g: 1 g = 981 cm/s² in this model (g = 9.81 m/s²); one
    // rounding of the division.
    for (a, v) in r.series.accel_g().iter().zip(&raw.values) {
        assert!((a - v / 981.0).abs() <= 2.0 * f64::EPSILON * (v / 981.0).abs());
    }
    let (peak, time) = peak_and_time(&r.series);
    assert_eq!(raw.peak, -6.851512, "the header's Max = -6.852 cm/sec2 at 76.215 sec");
    assert!((peak - raw.peak / 981.0).abs() < 1e-15);
    assert!((time - raw.peak_time_s).abs() < 1e-12);
}

#[test]
fn a_cosmos_file_of_three_channels_is_refused_without_a_stated_channel() {
    let path = Path::new(RECORDS).join(CE23837_V1C);
    let e = read_record_as(&path, &RecordSpec::default()).unwrap_err();
    assert!(matches!(e, RecordError::Channels { count: 3, .. }));
    let m = e.to_string();
    assert!(
        m.ends_with("CE23837.V1C: holds 3 channels (1: 360 deg; 2: Up; 3: 90 deg); state which one to read (1 to 3)"),
        "{m}"
    );
    let m = read_record_as(&path, &channel(4)).unwrap_err().to_string();
    assert!(
        m.ends_with("CE23837.V1C: no channel 4: the file holds 3 (1: 360 deg; 2: Up; 3: 90 deg)"),
        "{m}"
    );
    // A one-channel file reads as channel 1, and no other.
    let v2 = Path::new(RECORDS).join(AKBMR_V2C);
    assert_eq!(read_record_as(&v2, &channel(1)).unwrap().series.len(), 42000);
    assert!(matches!(
        read_record_as(&v2, &channel(2)).unwrap_err(),
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
    let text = text_of(AKBMR_V2C);
    let e = read_text("bmr.V2c", &text, RecordSpec::stated(AccelUnit::G)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "bmr.V2c:53: the header says the unit is cm/s2, but g was stated"
    );
    let agreed = read_text("bmr.V2c", &text, RecordSpec::stated(AccelUnit::CentimetresPerSecond2)).unwrap();
    assert_eq!(agreed.series.len(), 42000);
}

#[test]
fn cosmos_velocity_counts_and_other_units_are_refused_naming_their_line() {
    let text = text_of(AKBMR_V2C);
    let cases = [
        // A velocity block where the acceleration belongs.
        (
            "acceleration pts",
            "velocity     pts",
            "bmr.V2c:53: not an acceleration record",
        ),
        // The header's physical parameter (integer value 2): velocity.
        (
            "       2       1       4     120",
            "       2       2       4     120",
            "bmr.V2c:15: not an acceleration record",
        ),
        // Raw counts (a V0 file's first line).
        (
            "Corrected acceleration    (Format",
            "Raw acceleration counts   (Format",
            "bmr.V2c:1: not an acceleration record",
        ),
        // A unit that is not g or cm/s² (in/s², code 07).
        (
            "units=cm/sec2(04)",
            "units=in/s/s(07)",
            "bmr.V2c:53: not an acceleration record",
        ),
        // The data line and the integer header disagree on the unit.
        (
            "units=cm/sec2(04)",
            "units=g(02)",
            "bmr.V2c:15: COSMOS header: integer-header value 3 says the unit is cm/s2, the data line 53 says g",
        ),
    ];
    for (from, to, expected) in cases {
        assert_eq!(text.matches(from).count(), 1, "{from}");
        let e = read_text("bmr.V2c", &text.replacen(from, to, 1), RecordSpec::default()).unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with(expected), "{m}");
    }
}

#[test]
fn a_v2_channel_reads_its_acceleration_and_leaves_the_velocity_after_it() {
    let text = text_of(AKBMR_V2C);
    let end = "End-of-data for ChanBNZ acceleration";
    let velocity = "   3 velocity     pts, approx  0 secs, units=cm/sec (05),Format=(1E15.6)\n\
                    1.0\n2.0\n3.0\nEnd-of-data for ChanBNZ velocity\n";
    let with_velocity = text.replacen(end, &format!("{velocity}{end}"), 1);
    let a = read_text("bmr.V2c", &text, RecordSpec::default()).unwrap();
    let b = read_text("bmr.V2c", &with_velocity, RecordSpec::default()).unwrap();
    assert_eq!(a.series, b.series);
}

#[test]
fn a_truncated_cosmos_file_and_a_wrong_count_name_their_lines() {
    let text = text_of(AKBMR_V2C);
    let lines: Vec<&str> = text.lines().collect();
    // Cut after 1000 of the 42000 values (data from line 54).
    let cut = lines[..53 + 1000].join("\n");
    let m = read_text("bmr.V2c", &cut, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert_eq!(m, "bmr.V2c:1053: 1000 values where line 53 announces 42000");
    // One value announced more than the file holds: the block ends at the
    // End-of-data line, 42054.
    let more = text.replacen("   42000 acceleration", "   42001 acceleration", 1);
    let m = read_text("bmr.V2c", &more, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert_eq!(m, "bmr.V2c:42054: 42000 values where line 53 announces 42001");
    let fewer = text.replacen("   42000 acceleration", "   41999 acceleration", 1);
    let m = read_text("bmr.V2c", &fewer, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert_eq!(m, "bmr.V2c:42054: 42000 values where line 53 announces 41999");
    // A header block that ends early.
    let short_header = lines[..20].join("\n");
    let m = read_text("bmr.V2c", &short_header, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with("bmr.V2c:20: COSMOS header: the file ends inside the integer-header"),
        "{m}"
    );
}

#[test]
fn an_unknown_cosmos_step_and_a_non_cosmos_v2_are_refused_naming_their_line() {
    let text = text_of(AKBMR_V2C);
    // Real-header value 62 (line 38, 2nd field) is the sampling interval.
    let unknown = text.replacen(
        "    -999.000000       5.000000     210.000000",
        "    -999.000000    -999.000000     210.000000",
        1,
    );
    let m = read_text("bmr.V2c", &unknown, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.starts_with("bmr.V2c:38: COSMOS header: real-header value 62 (the sampling interval, ms) is unknown"),
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
    // Channel 1's header with a data line of the fixed-width (10F8.5) form
    // some writers use, where values touch.
    let text = text_of(CE23837_V1C).replace('\r', "");
    let lines: Vec<&str> = text.lines().collect();
    let mut file = lines[..44].join("\n");
    file.push_str(
        "\n      12 acceleration pts, approx   0 secs, units=g (02),Format=(10F8.5)\n\
         -0.00003-0.00004 0.10000-0.12345 0.00001-1.00000 0.50000 0.25000-0.00002 0.00000\n\
         \x200.01000-0.02000\n\
         End-of-data for Chan  1 acceleration\n",
    );
    let r = read_text("glued.v1", &file, RecordSpec::default()).unwrap();
    let expected = [
        -0.00003, -0.00004, 0.1, -0.12345, 0.00001, -1.0, 0.5, 0.25, -0.00002, 0.0, 0.01, -0.02,
    ];
    assert_eq!(r.series.accel_g(), &expected);
    assert_eq!(r.series.times_s()[11], 11.0 * 0.005);
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

/// A real ESM file, when `ROCKING_ESM_FILE` names one: ESM's terms do not
/// let this project ship one (see tests/data/records/README.md), so this
/// test reads one a user or CI has downloaded. It checks the count, the
/// step and the peak against the file's own header (`NDATA`,
/// `SAMPLING_INTERVAL_S`, `PGA_CM/S^2` and `TIME_PGA_S`).
#[test]
fn a_real_esm_file_named_by_rocking_esm_file_reads_as_its_header_states() {
    let Some(path) = std::env::var_os("ROCKING_ESM_FILE") else {
        eprintln!("ROCKING_ESM_FILE not set: no real ESM file read");
        return;
    };
    let text = std::fs::read_to_string(&path).unwrap();
    let key = |k: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(k).and_then(|v| v.strip_prefix(':')))
            .unwrap()
            .trim()
            .to_owned()
    };
    let r = read_record_as(Path::new(&path), &RecordSpec::default()).unwrap();
    assert_eq!(r.format, RecordFormat::Esm);
    assert_eq!(r.unit, AccelUnit::parse(&key("UNITS")).unwrap());
    assert_eq!(r.series.len(), key("NDATA").parse::<usize>().unwrap());
    let dt: f64 = key("SAMPLING_INTERVAL_S").parse().unwrap();
    assert_eq!(r.series.times_s()[1], dt);
    let (peak, time) = peak_and_time(&r.series);
    let pga_cm: f64 = key("PGA_CM/S^2").parse().unwrap();
    // The header's PGA is written to 6 decimals, as the samples are.
    assert!((peak * 981.0 - pga_cm).abs() < 1e-9, "{} vs {pga_cm}", peak * 981.0);
    let time_pga: f64 = key("TIME_PGA_S").parse().unwrap();
    assert!((time - time_pga).abs() < dt / 2.0, "{time} vs {time_pga}");
}

#[test]
fn the_suite_sniffer_knows_cosmos_and_esm_by_name_and_by_header() {
    let cosmos = text_of(AKBMR_V2C);
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
}

#[test]
fn a_config_chooses_a_cosmos_channel_and_its_summary_repeats_the_choice() {
    use crate::io::config;
    let file = Path::new(RECORDS).join(CE23837_V1C).display().to_string();
    let sets = |extra: &[&str]| {
        let mut sets = vec![
            "excitation.kind=\"record\"".to_owned(),
            format!("excitation.file_h={file:?}"),
        ];
        sets.extend(extra.iter().map(|s| s.to_string()));
        sets
    };
    let s = config::load(None, None, &sets(&["excitation.channel_h=2"])).unwrap();
    let record = s.excitation.record_h.as_ref().unwrap();
    assert_eq!(record.channel, Some(2));
    // Channel 2 is the vertical (Up), whose header states 0.048757 g.
    assert_eq!(
        peak_and_time(&record.series).0,
        raw_channel(&text_of(CE23837_V1C), 2).peak
    );
    let json = config::to_json(&s);
    assert_eq!(json["excitation"]["channel_h"], 2);
    assert!(json["excitation"]["channel_v"].is_null());
    let e = config::load(None, None, &sets(&[])).unwrap_err().to_string();
    assert!(
        e.starts_with("excitation.channel_h: ") && e.contains("holds 3 channels"),
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
            text_of(CE23837_V1C).lines().take(100).collect::<Vec<_>>().join("\n")
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
