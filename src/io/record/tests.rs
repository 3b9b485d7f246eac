//! Tests of the record reader: the sample files, every header form and
//! error message of both formats, and property tests that no input panics.

use super::*;
use proptest::prelude::*;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

const SAMPLE_AT2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sample.AT2");
const SAMPLE_V: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sample_v.txt");
const BAD_LINE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bad_line.txt");

/// Reads `path` as a record in g (the unit of every test file here unless a
/// test states another).
fn read_record(path: &Path) -> Result<Series, RecordError> {
    read_record_as(path, &RecordSpec::stated(AccelUnit::G)).map(|r| r.series)
}

/// A uniquely named temporary file, removed on drop.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, content: &[u8]) -> Self {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("rocking-record-{}-{unique}-{name}", std::process::id()));
        std::fs::write(&path, content).unwrap();
        Self(path)
    }

    fn read(&self) -> Result<Series, RecordError> {
        read_record(&self.0)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

fn read_str(name: &str, content: &str) -> Result<Series, RecordError> {
    TempFile::new(name, content.as_bytes()).read()
}

fn err_str(name: &str, content: &str) -> String {
    let error = read_str(name, content).unwrap_err();
    let message = error.to_string();
    assert!(!message.contains('\n'), "multi-line message: {message}");
    message
}

// ---- Reading: test data files ----

#[test]
fn reads_sample_at2() {
    let s = read_record(Path::new(SAMPLE_AT2)).unwrap();
    assert_eq!(s.len(), 40);
    for (k, &t) in s.times_s().iter().enumerate() {
        assert_eq!(t, k as f64 * 0.01);
    }
    assert_eq!(s.accel_g()[0], 0.0);
    assert!((s.accel_g()[1] - 0.7497104e-01).abs() < 1e-12);
    assert!((s.duration_s() - 0.39).abs() < 1e-15);
    assert!(s.peak_abs_g() > 0.1 && s.peak_abs_g() < 0.3);
}

#[test]
fn reads_sample_two_column() {
    let s = read_record(Path::new(SAMPLE_V)).unwrap();
    assert_eq!(s.len(), 21);
    assert_eq!(s.times_s()[0], 0.0);
    assert_eq!(s.times_s()[1], 0.01);
    assert_eq!(s.accel_g()[2], 0.0231);
    assert_eq!(s.duration_s(), 0.2);
}

#[test]
fn bad_line_names_line_4() {
    let error = read_record(Path::new(BAD_LINE)).unwrap_err();
    assert!(matches!(error, RecordError::Columns { line: 4, found: 3, .. }));
    let message = error.to_string();
    assert!(
        message.ends_with("bad_line.txt:4: expected 2 columns, found 3"),
        "{message}"
    );
}

// ---- Reading: AT2 header forms ----

const AT2_HEAD: &str = "PEER NGA STRONG MOTION DATABASE RECORD\n\
    Test Event, 01/01/2000, Test Station, 090\n\
    ACCELERATION TIME SERIES IN UNITS OF G\n";

fn at2(count_line: &str, data: &str) -> String {
    format!("{AT2_HEAD}{count_line}\n{data}")
}

#[test]
fn accepts_all_count_line_forms() {
    let data = "  .1000000E-01  -.2000000E-01   .3000000E+00\n";
    for count_line in [
        "NPTS=     3, DT=   .0050 SEC",
        "NPTS=3, DT=.005 SEC,",
        "NPTS=3 DT=0.005",
        "NPTS=3, DT=0.005",
        "NPTS= 3 DT= 0.005 SEC",
        "NPTS=3 DT=0.005 SEC,",
        "npts=3, dt=.005sec",
        "    3   0.00500   NPTS, DT",
        "3 .005 NPTS DT",
    ] {
        let s = read_str("form.at2", &at2(count_line, data)).unwrap_or_else(|e| panic!("{count_line:?}: {e}"));
        assert_eq!(s.times_s(), &[0.0, 0.005, 0.01], "{count_line:?}");
        assert_eq!(s.accel_g(), &[0.01, -0.02, 0.3], "{count_line:?}");
    }
}

#[test]
fn at2_detected_by_content_and_crlf_and_d_exponent() {
    let content = at2("NPTS=4, DT=0.02 SEC", "1.0D-02, 2.0d-2\n-3E-2 4.0e-02\n\n").replace('\n', "\r\n");
    let s = read_str("record.dat", &content).unwrap();
    assert_eq!(s.accel_g(), &[0.01, 0.02, -0.03, 0.04]);
    assert_eq!(s.times_s(), &[0.0, 0.02, 0.04, 0.06]);
}

#[test]
fn at2_extension_any_case() {
    let content = at2("NPTS=2, DT=0.02 SEC", "0.1 0.2\n");
    for name in ["a.at2", "b.AT2", "c.At2"] {
        assert_eq!(read_str(name, &content).unwrap().len(), 2);
    }
}

#[test]
fn at2_header_errors() {
    let m = err_str("ground.at2", &at2("NPTS: many, DT: small", "0.1 0.2\n"));
    assert!(
        m.ends_with("ground.at2:4: cannot read NPTS/DT from header \"NPTS: many, DT: small\""),
        "{m}"
    );
    let m = err_str("ground.at2", &at2("NPTS=2.5, DT=0.01", "0.1 0.2\n"));
    assert!(m.contains(":4: cannot read NPTS/DT"), "{m}");
    let m = err_str("ground.at2", &at2("NPTS=-2, DT=0.01", "0.1 0.2\n"));
    assert!(m.contains(":4: cannot read NPTS/DT"), "{m}");
    let m = err_str("ground.at2", &at2("NPTS=0, DT=0.01", ""));
    assert!(m.ends_with("ground.at2:4: NPTS = 0, the record has no samples"), "{m}");
    for dt in ["0", "-0.01", "nan", "inf"] {
        let m = err_str("ground.at2", &at2(&format!("NPTS=2, DT={dt}"), "0.1 0.2\n"));
        assert!(m.contains("ground.at2:4: invalid time step DT"), "{m}");
    }
    let m = err_str("ground.at2", &at2("NPTS=3, DT=1e308", "0.1 0.2 0.3\n"));
    assert!(m.contains(":4: invalid time step DT = 1e308 s"), "{m}");
    let m = err_str("short.at2", "PEER NGA STRONG MOTION DATABASE RECORD\nx\n");
    assert!(m.ends_with("short.at2: AT2 header has 3 lines, expected 4"), "{m}");
}

#[test]
fn at2_rejects_other_units_and_quantities() {
    for line3 in [
        "VELOCITY TIME SERIES IN UNITS OF CM/SEC",
        "DISPLACEMENT TIME SERIES IN UNITS OF CM",
        "ACCELERATION TIME SERIES IN UNITS OF FT/S/S",
    ] {
        let content = format!("TITLE\nEVENT\n{line3}\nNPTS=2, DT=0.01 SEC\n0.1 0.2\n");
        let m = err_str("units.at2", &content);
        assert!(m.contains("units.at2:3: not an acceleration record"), "{m}");
    }
    let content = "TITLE\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G.\nNPTS=2, DT=0.01\n0.1 0.2\n";
    assert_eq!(read_str("ok.at2", content).unwrap().len(), 2);
}

#[test]
fn at2_value_count_must_match() {
    let m = err_str("x.at2", &at2("NPTS=  5590, DT=   .0050 SEC", "0.1 0.2\n"));
    assert!(m.ends_with("x.at2: expected 5590 values, found 2"), "{m}");
    let m = err_str("x.at2", &at2("NPTS=2, DT=.005", "0.1 0.2\n0.3\n"));
    assert!(m.ends_with("x.at2: expected 2 values, found 3"), "{m}");
    let m = err_str("x.at2", &at2("NPTS=1, DT=.005", "0.1\n"));
    assert!(m.ends_with("x.at2: need at least 2 samples, found 1"), "{m}");
}

#[test]
fn at2_bad_values_name_their_line() {
    let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 nan\n"));
    assert!(m.ends_with("v.at2:6: non-finite value \"nan\""), "{m}");
    let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 1e999\n"));
    assert!(m.ends_with("v.at2:6: non-finite value \"1e999\""), "{m}");
    let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 0.4x\n"));
    assert!(m.ends_with("v.at2:6: cannot parse \"0.4x\" as a number"), "{m}");
    let m = err_str("v.at2", &at2("NPTS=4, DT=.005", "0.1 0.2\n0.3 -981.0\n"));
    assert!(
        m.ends_with("v.at2:6: |acceleration| of -981 g exceeds the 100 g sanity limit"),
        "{m}"
    );
}

// ---- Reading: two-column ----

#[test]
fn two_column_separators_comments_and_header() {
    let content =
        "# comment\n\n   # indented comment\ntime_s, accel_g\n0.0, 0.1\n0.1 ,0.2\n0.2\t-0.3\n0.3,-0.4\r\n\n# end\n";
    let s = read_str("rec.txt", content).unwrap();
    assert_eq!(s.times_s(), &[0.0, 0.1, 0.2, 0.3]);
    assert_eq!(s.accel_g(), &[0.1, 0.2, -0.3, -0.4]);
    // Without a header, and starting after t = 0.
    let s = read_str("rec.txt", "0.5 0\n1.5 0.25\n").unwrap();
    assert_eq!(s.accel_at(1.0), 0.125);
    assert_eq!(s.accel_at(0.25), 0.0);
}

#[test]
fn two_column_errors_name_their_line() {
    let cases: &[(&str, &str)] = &[
        ("t a\n0 0\n0.1 0.2 0.3\n", "rec.txt:3: expected 2 columns, found 3"),
        ("0 0\n0.1\n", "rec.txt:2: expected 2 columns, found 1"),
        ("0 0\n , ,\n", "rec.txt:2: expected 2 columns, found 0"),
        (
            "0 0\n0.2 0\n0.2 0.1\n",
            "rec.txt:3: time 0.2 does not increase (previous 0.2)",
        ),
        (
            "0 0\n0.2 0\n0.1 0.1\n",
            "rec.txt:3: time 0.1 does not increase (previous 0.2)",
        ),
        ("0 0\n0.2 nan\n", "rec.txt:2: non-finite value \"nan\""),
        ("0 0\ninf 0.1\n", "rec.txt:2: non-finite value \"inf\""),
        ("-0.1 0\n0.2 0\n", "rec.txt:1: negative time -0.1 s"),
        (
            "0 0\n0.1 150\n",
            "rec.txt:2: |acceleration| of 150 g exceeds the 100 g sanity limit",
        ),
        (
            "time accel\n0 0\nagain header\n",
            "rec.txt:3: cannot parse \"again\" as a number",
        ),
        ("h1\nh2 x\n", "rec.txt:2: cannot parse \"h2\" as a number"),
        ("# only\ntime accel\n", "rec.txt: need at least 2 samples, found 0"),
        ("0 0\n", "rec.txt: need at least 2 samples, found 1"),
        ("", "rec.txt: empty file"),
        (" \n\t\r\n\n", "rec.txt: empty file"),
    ];
    for (content, expected) in cases {
        let m = err_str("rec.txt", content);
        assert!(m.ends_with(expected), "{content:?}: got {m}, want {expected}");
    }
}

#[test]
fn io_errors_name_the_path() {
    let missing = std::env::temp_dir().join("rocking-record-does-not-exist.txt");
    let error = read_record(&missing).unwrap_err();
    assert!(matches!(error, RecordError::Io { .. }));
    assert!(
        error.to_string().starts_with(&format!("{}: ", missing.display())),
        "{error}"
    );
    let dir = std::env::temp_dir();
    let error = read_record(&dir).unwrap_err();
    assert_eq!(error.to_string(), format!("{}: is a directory", dir.display()));
}

#[test]
fn invalid_utf8_is_an_error_not_a_panic() {
    let f = TempFile::new("latin1.txt", b"# Station M\xfcller\n0 0\n0.1 0.\xff\n");
    let m = f.read().unwrap_err().to_string();
    assert!(m.contains(":3: cannot parse"), "{m}");
    let f = TempFile::new("latin1ok.txt", b"# Station M\xfcller\n0 0\n0.1 0.5\n");
    assert_eq!(f.read().unwrap().len(), 2);
}

// ---- Never panics ----

fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("NPTS=".to_owned()),
        Just("DT=".to_owned()),
        Just("SEC".to_owned()),
        Just(",".to_owned()),
        Just(" ".to_owned()),
        Just("\n".to_owned()),
        Just("\r\n".to_owned()),
        Just("#".to_owned()),
        Just("nan".to_owned()),
        Just("-inf".to_owned()),
        Just("1e999".to_owned()),
        Just("UNITS OF G".to_owned()),
        Just(".1234567E-02".to_owned()),
        any::<f64>().prop_map(|x| x.to_string()),
        any::<u32>().prop_map(|x| x.to_string()),
        (0_u32..5).prop_map(|x| x.to_string()),
        "[a-zA-Z0-9.,=+ -]{0,8}",
    ]
}

fn tokens_file() -> impl Strategy<Value = Vec<u8>> {
    (any::<bool>(), prop::collection::vec(token(), 0..60)).prop_map(|(head, tokens)| {
        let body: String = tokens.concat();
        let text = if head { format!("{AT2_HEAD}{body}") } else { body };
        text.into_bytes()
    })
}

proptest! {
    // 300 cases in CI; `ROCKING_STRESS=1` runs the extended tier of 10⁵.
    #![proptest_config(ProptestConfig::with_cases(
        if std::env::var("ROCKING_STRESS").is_ok_and(|v| v == "1") { 100_000 } else { 300 }
    ))]

    #[test]
    fn arbitrary_bytes_never_panic(
        content in prop::collection::vec(any::<u8>(), 0..600),
        ext in prop::sample::select(vec!["at2", "AT2", "txt", "csv", "", "V2", "v1c", "ASC"]),
    ) {
        let file = TempFile::new(&format!("fuzz.{ext}"), &content);
        let _ = file.read();
    }

    #[test]
    fn arbitrary_token_soup_never_panics(
        content in tokens_file(),
        ext in prop::sample::select(vec!["at2", "txt", "V2"]),
    ) {
        let file = TempFile::new(&format!("soup.{ext}"), &content);
        if let Ok(s) = file.read() {
            // Whatever is accepted satisfies the Series invariants.
            prop_assert!(Series::new(s.times_s().to_vec(), s.accel_g().to_vec()).is_ok());
        }
    }
}

// ---- Units and formats ----

fn read_as(name: &str, content: &str, spec: RecordSpec) -> Result<LoadedRecord, RecordError> {
    let f = TempFile::new(name, content.as_bytes());
    read_record_as(&f.0, &spec)
}

#[test]
fn the_same_motion_in_g_m_s2_and_cm_s2_reads_as_the_same_g() {
    let g = crate::model::geometry::G;
    let values = [0.0, 0.125, -0.3, 0.02];
    let text = |factor: f64| -> String {
        values
            .iter()
            .enumerate()
            .map(|(k, v)| format!("{} {}\n", k as f64 * 0.01, v * factor))
            .collect()
    };
    for (unit, factor) in [
        (AccelUnit::G, 1.0),
        (AccelUnit::MetresPerSecond2, g),
        (AccelUnit::CentimetresPerSecond2, 100.0 * g),
    ] {
        let r = read_as("u.txt", &text(factor), RecordSpec::stated(unit)).unwrap();
        assert_eq!(r.unit, unit);
        assert_eq!(r.format, RecordFormat::TwoColumn);
        for (a, v) in r.series.accel_g().iter().zip(values) {
            assert!((a - v).abs() <= 1e-15, "{unit}: {a} vs {v}");
        }
    }
}

#[test]
fn a_text_record_without_a_stated_unit_is_refused() {
    let m = read_as("nounit.txt", "0 0.1\n0.01 0.2\n", RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.ends_with("nounit.txt: a text record does not say its unit; state it (g, m/s2 or cm/s2)"),
        "{m}"
    );
}

#[test]
fn at2_units_come_from_the_header_and_a_contradiction_is_an_error() {
    let g = crate::model::geometry::G;
    let body = |unit: &str| {
        format!("TITLE\nEVENT\nACCELERATION TIME SERIES IN UNITS OF {unit}\nNPTS=2, DT=0.01 SEC\n98.1 -9.81\n")
    };
    let r = read_as("cm.at2", &body("CM/S/S"), RecordSpec::default()).unwrap();
    assert_eq!(r.unit, AccelUnit::CentimetresPerSecond2);
    assert!((r.series.accel_g()[0] - 0.1).abs() < 1e-15 && (r.series.accel_g()[1] + 0.01).abs() < 1e-15);
    let r = read_as("cmsec.at2", &body("CM/SEC/SEC"), RecordSpec::default()).unwrap();
    assert_eq!(r.unit, AccelUnit::CentimetresPerSecond2);
    let r = read_as(
        "g.at2",
        &body("G").replace("98.1 -9.81", "0.5 0.25"),
        RecordSpec::default(),
    )
    .unwrap();
    assert_eq!((r.unit, r.series.accel_g()[0]), (AccelUnit::G, 0.5));
    let m = read_as(
        "conflict.at2",
        &body("G"),
        RecordSpec::stated(AccelUnit::MetresPerSecond2),
    )
    .unwrap_err()
    .to_string();
    assert!(
        m.ends_with("conflict.at2:3: the header says the unit is g, but m/s2 was stated"),
        "{m}"
    );
    // A header naming no unit takes the stated one, and without one is refused.
    let silent = "TITLE\nEVENT\nACCELERATION TIME SERIES\nNPTS=2, DT=0.01 SEC\n9.81 0\n";
    let r = read_as("silent.at2", silent, RecordSpec::stated(AccelUnit::MetresPerSecond2)).unwrap();
    assert!((r.series.accel_g()[0] - 1.0).abs() < 1e-15, "{}", g);
    let m = read_as("silent.at2", silent, RecordSpec::default())
        .unwrap_err()
        .to_string();
    assert!(
        m.ends_with("silent.at2:3: the AT2 header names no unit (\"UNITS OF ...\"); state it (g, m/s2 or cm/s2)"),
        "{m}"
    );
}

#[test]
fn one_column_records_need_a_step_and_take_comments_and_semicolons() {
    let content = "% exported by a strong-motion network\n! unit: cm/s2\n// dt 0.005 s\naccel\n1.0\n-2.0\n\n3.0\n";
    let spec = RecordSpec {
        unit: Some(AccelUnit::CentimetresPerSecond2),
        dt: Some(0.005),
        channel: None,
    };
    let r = read_as("one.txt", content, spec).unwrap();
    assert_eq!(r.format, RecordFormat::OneColumn);
    assert_eq!(r.series.times_s(), &[0.0, 0.005, 0.01]);
    assert!((r.series.accel_g()[2] - 3.0 / 981.0).abs() < 1e-15);
    let m = read_as("one.txt", content, RecordSpec::stated(AccelUnit::G))
        .unwrap_err()
        .to_string();
    assert!(
        m.ends_with("one.txt:5: one value per line: a one-column record needs its time step (s) stated"),
        "{m}"
    );
    let m = read_as("two.txt", "0;0.1\n0.01;0.2\n", spec).unwrap_err().to_string();
    assert!(
        m.ends_with("two.txt:1: expected 1 column (a time step is set), found 2"),
        "{m}"
    );
    let r = read_as("semi.txt", "0;0.1\n0.01 ; 0.2\n", RecordSpec::stated(AccelUnit::G)).unwrap();
    assert_eq!(r.series.accel_g(), &[0.1, 0.2]);
    for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let spec = RecordSpec {
            unit: Some(AccelUnit::G),
            dt: Some(dt),
            channel: None,
        };
        let m = read_as("dt.txt", "0.1\n0.2\n", spec).unwrap_err().to_string();
        assert!(m.contains("dt.txt: invalid time step"), "{m}");
    }
    let m = read_as("single.txt", "0.1\n", spec).unwrap_err().to_string();
    assert!(m.ends_with("single.txt: need at least 2 samples, found 1"), "{m}");
}

#[test]
fn the_sanity_limit_applies_after_conversion() {
    // 2000 m/s² is 204 g: refused; 2000 cm/s² is 2 g: read.
    let content = "0 0\n0.01 2000\n";
    let m = read_as("big.txt", content, RecordSpec::stated(AccelUnit::MetresPerSecond2))
        .unwrap_err()
        .to_string();
    assert!(m.contains("big.txt:2: |acceleration| of 203."), "{m}");
    assert!(read_as("big.txt", content, RecordSpec::stated(AccelUnit::CentimetresPerSecond2)).is_ok());
}

#[test]
fn time_steps_outside_1e_5_to_10_s_are_refused_in_every_format() {
    // AT2: the header's DT.
    for dt in ["1e-300", "1e-6", "20"] {
        let m = err_str("ground.at2", &at2(&format!("NPTS=2, DT={dt}"), "0.1 0.2\n"));
        assert!(
            m.contains("ground.at2:4: invalid time step DT") && m.contains("(need 1e-5 s <= DT <= 10 s)"),
            "{m}"
        );
    }
    assert!(read_as("edge.at2", &at2("NPTS=2, DT=1e-5", "0.1 0.2\n"), RecordSpec::default()).is_ok());
    // One column: the stated step, printed readably.
    for dt in [1e-300, 9e-6, 10.5] {
        let spec = RecordSpec {
            unit: Some(AccelUnit::G),
            dt: Some(dt),
            channel: None,
        };
        let m = read_as("dt.txt", "0.1\n0.2\n", spec).unwrap_err().to_string();
        assert!(m.contains(&format!("dt.txt: invalid time step {dt:?} s")), "{m}");
    }
    // Two columns: each step, naming its line.
    let m = read_as(
        "two.txt",
        "0 0.1\n0.01 0.2\n0.010000001 0.3\n",
        RecordSpec::stated(AccelUnit::G),
    )
    .unwrap_err()
    .to_string();
    assert!(
        m.contains("two.txt:3: time step") && m.contains("outside [1e-5 s, 10 s]"),
        "{m}"
    );
    let m = read_as("gap.txt", "0 0.1\n0.01 0.2\n30 0.3\n", RecordSpec::stated(AccelUnit::G))
        .unwrap_err()
        .to_string();
    assert!(m.contains("gap.txt:3: time step 29.99 s"), "{m}");
    // Steps of exactly 1e-5 s written as decimals pass despite rounding.
    let fine: String = (0..50).map(|k| format!("{:.5} 0.1\n", k as f64 * 1e-5)).collect();
    assert!(read_as("fine.txt", &fine, RecordSpec::stated(AccelUnit::G)).is_ok());
}

#[test]
fn at2_headers_keep_reading_upper_case_units() {
    for (units, unit) in [
        ("UNITS OF G", AccelUnit::G),
        ("UNITS OF CM/S/S", AccelUnit::CentimetresPerSecond2),
        ("UNITS OF M/S/S", AccelUnit::MetresPerSecond2),
    ] {
        let content = format!("TITLE\nEVENT\nACCELERATION TIME SERIES IN {units}\nNPTS=2, DT=0.01 SEC\n0.1 0.2\n");
        let r = read_as("upper.at2", &content, RecordSpec::default()).unwrap();
        assert_eq!(r.unit, unit, "{units}");
    }
}
