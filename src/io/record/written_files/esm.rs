//! The ESM reader on files written with the DYNA 1.2 header: count, step and unit from the header, and refusals naming their line.

use super::*;

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
pub(super) fn esm_file(data_type: &str, units: &str, ndata: usize, values: &[f64]) -> String {
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
