//! A record given as samples (`Record::in_memory`, for a caller that holds
//! a ground motion in memory): it runs where a file would, and a config
//! written from it names no file, so it cannot claim to repeat the run.

use rocking::io::config::{self, Source};
use rocking::model::excitation::record::Series;
use rocking::model::units::AccelUnit;
use rocking::sim::scenario::Record;

fn samples() -> Record {
    let times: Vec<f64> = (0..200).map(|i| f64::from(i) * 0.01).collect();
    let accel: Vec<f64> = times
        .iter()
        .map(|t| 0.4 * (std::f64::consts::TAU * 2.0 * t).sin())
        .collect();
    Record::in_memory(Series::new(times, accel).unwrap(), AccelUnit::G, Some(0.01))
}

fn record_table(extra: &[&str]) -> toml::Table {
    let mut sets = vec!["excitation.kind=\"record\"".to_string()];
    sets.extend(extra.iter().map(|s| (*s).to_string()));
    let mut table = toml::Table::new();
    config::apply_sets(&mut table, &sets).unwrap();
    table
}

#[test]
fn a_record_given_as_samples_resolves_and_its_config_names_no_file() {
    let rec = samples();
    assert!(rec.is_in_memory());
    let s = config::from_table_with(&record_table(&[]), &Source::default(), [Some(&rec), None]).unwrap();
    assert_eq!(s.excitation.record_h.as_ref(), Some(&rec));
    let x = &config::to_json(&s)["excitation"];
    for key in ["file_h", "unit_h", "dt_h", "crc32_h"] {
        assert!(x[key].is_null(), "{key} = {}", x[key]);
    }
    assert_eq!(x["kind"], "record");
    // Without its samples the same table is refused, naming the file key.
    let e = config::from_table(&record_table(&[]), &Source::default()).unwrap_err();
    assert!(e.to_string().contains("excitation.file_h"), "{e}");
}

#[test]
fn a_file_named_as_well_as_samples_is_refused() {
    let rec = samples();
    let table = record_table(&["excitation.file_h=\"motion.dat\"", "excitation.unit_h=\"g\""]);
    let e = config::from_table_with(&table, &Source::default(), [Some(&rec), None]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("excitation.file_h: the record is given as samples"),
        "{e}"
    );
}

#[test]
fn the_same_samples_have_the_same_checksum() {
    assert_eq!(samples().crc32, samples().crc32);
    let other = Record::in_memory(
        Series::new(vec![0.0, 0.01], vec![0.0, 0.1]).unwrap(),
        AccelUnit::G,
        None,
    );
    assert_ne!(samples().crc32, other.crc32);
}

/// A table resolved with the records a scene already holds (a slider
/// drag's edit of another key) gives the scene reading the files gives,
/// reads no record, and shares the samples rather than copying them. The
/// keys that move the block's size resolve every value with a unit again
/// (the preset's `output_dt = "0.01 s"` is 0.01 s × p in τ).
#[test]
fn a_table_resolved_keeping_a_scenes_records_reads_none_and_equals_reading_them() {
    let text = config::preset_text("kobe-rack-5th-floor").unwrap();
    let (mut table, source) = (config::parse_toml(text, "preset").unwrap(), Source::preset());
    let read = config::from_table(&table, &source).unwrap();
    for set in [
        "block.width=0.45",
        "block.height=\"1.9 m\"",
        "floor.period=0.8",
        "excitation.pga_h=\"0.5 g\"",
    ] {
        config::set_dotted(&mut table, set).unwrap();
        let reads = rocking::io::record::reads_on_this_thread();
        let kept = config::from_table_keeping(&table, &source, &read).unwrap();
        assert_eq!(
            rocking::io::record::reads_on_this_thread(),
            reads,
            "{set}: read a record"
        );
        let fresh = config::from_table(&table, &source).unwrap();
        assert_eq!(
            rocking::io::record::reads_on_this_thread(),
            reads + 1,
            "{set}: reading counts"
        );
        assert_eq!(config::to_json(&kept), config::to_json(&fresh), "{set}");
        assert!(kept == fresh, "{set}");
        let (a, b) = (&kept.excitation.record_h, &read.excitation.record_h);
        let (a, b) = (a.as_ref().unwrap(), b.as_ref().unwrap());
        assert!(
            std::ptr::eq(a.series.accel_g().as_ptr(), b.series.accel_g().as_ptr()),
            "{set}: copied"
        );
    }
    // p = sqrt(3 g / (4 R)) for the final 0.45 m × 1.9 m block, R the half-diagonal.
    let r = 0.5 * (0.45_f64.powi(2) + 1.9_f64.powi(2)).sqrt();
    let p = (3.0 * 9.81 / (4.0 * r)).sqrt();
    let kept = config::from_table_keeping(&table, &source, &read).unwrap();
    assert!(
        (kept.run.output_dt - 0.01 * p).abs() < 1e-12 * p,
        "{} vs {}",
        kept.run.output_dt,
        0.01 * p
    );
}
