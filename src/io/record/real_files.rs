//! Tests of the COSMOS and ESM readers on real files, which the project
//! does not ship: they are read from the steering repository's
//! `shared/records/` (`../shared` beside the crate; the list of files and
//! their sources is in tests/data/records/README.md). Each test is ignored
//! unless asked for (`cargo test --lib real_files -- --ignored`). Each expected
//! value is the file's own header value, or is computed here from the raw
//! numbers by a reader written in the test. The format and refusal
//! properties are tested on written files, in `written_files`.

use super::test_helpers::{channel, peak_and_time, raw_channel};
use super::*;

/// Where the real COSMOS files are placed.
const COSMOS_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/records/cosmos/");

/// Where the real ESM files are placed.
const ESM_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/records/esm/");

/// CGS station 23837 (Pomona), 2018-08-29: three channels of COSMOS V1, in g.
const CE23837_V1C: &str = "CE23837.V1C";

/// USGS/AK station BMR, 2018-11-30 Anchorage M7.0, vertical: COSMOS V2 in cm/s².
const AKBMR_V2C: &str = "us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c";

fn path_of(name: &str) -> std::path::PathBuf {
    Path::new(COSMOS_DIR).join(name)
}

fn text_of(name: &str) -> String {
    let path = path_of(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
#[ignore = "needs the real COSMOS files in ../shared/records/cosmos (see tests/data/records/README.md); run with --ignored"]
fn each_channel_of_the_real_cosmos_v1_file_reads_as_its_header_states() {
    let text = text_of(CE23837_V1C);
    let path = path_of(CE23837_V1C);
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
    // Its channels named as its 9th text lines name them, when none is stated.
    let m = read_record_as(&path, &RecordSpec::default()).unwrap_err().to_string();
    assert!(
        m.ends_with("CE23837.V1C: holds 3 channels (1: 360 deg; 2: Up; 3: 90 deg); state which one to read (1 to 3)"),
        "{m}"
    );
}

#[test]
#[ignore = "needs the real COSMOS files in ../shared/records/cosmos (see tests/data/records/README.md); run with --ignored"]
fn the_real_cosmos_v2_file_reads_in_cm_s2_as_its_header_states() {
    let text = text_of(AKBMR_V2C);
    let raw = raw_channel(&text, 1);
    let r = read_record_as(&path_of(AKBMR_V2C), &RecordSpec::default()).unwrap();
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

/// Each real ESM file in `shared/records/esm/` (`.ASC`, any case): ESM's
/// terms do not let this project ship one (see tests/data/records/README.md).
/// Checks the count, the step and the peak against each file's own header
/// (`NDATA`, `SAMPLING_INTERVAL_S`, `PGA_CM/S^2` and `TIME_PGA_S`); a
/// folder without one fails, rather than passing on nothing.
#[test]
#[ignore = "needs real ESM files in ../shared/records/esm (see tests/data/records/README.md); run with --ignored"]
fn each_real_esm_file_reads_as_its_header_states() {
    let mut paths: Vec<std::path::PathBuf> = std::fs::read_dir(ESM_DIR)
        .unwrap_or_else(|e| panic!("{ESM_DIR}: {e}"))
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("asc")))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "{ESM_DIR}: no .ASC file");
    for path in &paths {
        let name = path.display();
        let text = std::fs::read_to_string(path).unwrap();
        let key = |k: &str| {
            text.lines()
                .find_map(|l| l.strip_prefix(k).and_then(|v| v.strip_prefix(':')))
                .unwrap_or_else(|| panic!("{name}: no {k}"))
                .trim()
                .to_owned()
        };
        let r = read_record_as(path, &RecordSpec::default()).unwrap();
        assert_eq!(r.format, RecordFormat::Esm, "{name}");
        assert_eq!(r.unit, AccelUnit::parse(&key("UNITS")).unwrap(), "{name}");
        assert_eq!(r.series.len(), key("NDATA").parse::<usize>().unwrap(), "{name}");
        let dt: f64 = key("SAMPLING_INTERVAL_S").parse().unwrap();
        assert_eq!(r.series.times_s()[1], dt, "{name}");
        let (peak, time) = peak_and_time(&r.series);
        let pga_cm: f64 = key("PGA_CM/S^2").parse().unwrap();
        // The header's PGA is written to 6 decimals, as the samples are.
        assert!(
            (peak * 981.0 - pga_cm).abs() < 1e-9,
            "{name}: {} vs {pga_cm}",
            peak * 981.0
        );
        let time_pga: f64 = key("TIME_PGA_S").parse().unwrap();
        assert!((time - time_pga).abs() < dt / 2.0, "{name}: {time} vs {time_pga}");
    }
}
