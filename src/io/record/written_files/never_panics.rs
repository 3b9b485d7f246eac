//! Never panics: COSMOS and ESM files with lines changed, cut or replaced by odd ones are read or refused in one line.

use super::esm::esm_file;
use super::*;

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
