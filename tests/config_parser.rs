//! Property tests of the config parser (issue 5, "bad input"): random TOML
//! built from the real keys and hostile values, presets with one value
//! replaced, random `--set` assignments and random bytes. Whatever comes in,
//! the parser returns a config whose every number is valid, or a one-line
//! error that names the key or the file and line; it never panics.
//!
//! The record parsers have their own property tests next to them
//! (`src/model/excitation/record.rs`).

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use rocking::io::config::{self, KNOWN_KEYS, Source};
use rocking::io::presets;
use rocking::sim::Scenario;

/// 400 cases in CI; `ROCKING_STRESS=1` runs the extended tier of 10⁵.
fn proptest_config() -> ProptestConfig {
    let stress = std::env::var("ROCKING_STRESS").is_ok_and(|v| v == "1");
    ProptestConfig {
        cases: if stress { 100_000 } else { 400 },
        // Fixed seed: CI runs the same cases every time.
        rng_seed: RngSeed::Fixed(0x5eed_c0f1),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Values a user (or a broken script) might write: valid ones, edge ones,
/// non-finite ones, wrong types.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        // Plain numbers of every size and sign.
        (-1e3f64..1e3).prop_map(|x| format!("{x}")),
        (0.0f64..1.0).prop_map(|x| format!("{x}")),
        (-300i32..300).prop_map(|e| format!("1e{e}")),
        (-5i64..1_000_000).prop_map(|i| format!("{i}")),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e308".to_string()),
        Just("-1e308".to_string()),
        Just("5e-324".to_string()),
        Just("0".to_string()),
        Just("-0.0".to_string()),
        Just("9223372036854775807".to_string()),
        Just("true".to_string()),
        Just("\"\"".to_string()),
        Just("\"inf\"".to_string()),
        Just("\"nan\"".to_string()),
        Just("[1, 2]".to_string()),
        Just("{ a = 1 }".to_string()),
        "\"[a-z_./]{0,12}\"",
    ]
}

/// A known `section.key`, or a misspelt one.
fn key() -> impl Strategy<Value = (String, String)> {
    let known: Vec<(String, String)> = KNOWN_KEYS
        .iter()
        .flat_map(|(s, ks)| ks.iter().map(move |k| (s.to_string(), k.to_string())))
        .collect();
    prop_oneof![
        9 => proptest::sample::select(known),
        1 => ("[a-z]{1,8}", "[a-z_]{1,8}"),
    ]
}

/// A TOML document of up to 12 assignments, grouped into sections.
fn document() -> impl Strategy<Value = String> {
    proptest::collection::vec((key(), value()), 0..12).prop_map(|pairs| {
        let mut sections: Vec<(String, Vec<(String, String)>)> = Vec::new();
        for ((s, k), v) in pairs {
            match sections.iter_mut().find(|(name, _)| *name == s) {
                Some((_, kv)) if !kv.iter().any(|(kk, _)| *kk == k) => kv.push((k, v)),
                Some(_) => {}
                None => sections.push((s, vec![(k, v)])),
            }
        }
        let mut text = String::new();
        for (s, kv) in sections {
            text.push_str(&format!("[{s}]\n"));
            for (k, v) in kv {
                text.push_str(&format!("{k} = {v}\n"));
            }
        }
        text
    })
}

/// A valid config's numbers are all usable: finite where they must be, and
/// the model builds or says why not.
fn check_valid(cfg: &Scenario) {
    let opts = cfg.run_options();
    assert!(
        opts.tau_end.is_finite() && opts.tau_end > 0.0,
        "tau_end {}",
        opts.tau_end
    );
    assert!(opts.tol.rtol > 0.0 && opts.tol.rtol < 1.0);
    assert!(opts.tol.atol > 0.0 && opts.tol.atol < 1.0);
    let init = cfg.initial;
    assert!(init.theta.is_finite() && init.theta_dot.is_finite());
    let geo = cfg.geometry();
    assert!(geo.psi.is_finite() && geo.psi > 0.0);
    match cfg.model() {
        Ok(m) => assert!(m.mu_k <= m.mu_s),
        Err(e) => assert_one_line(&e.to_string()),
    }
    // What summary.json would hold has no NaN: JSON has none, so serde
    // would write null. Only the optional keys may be null.
    #[rustfmt::skip]
    const NULLABLE: [&str; 13] = [
        "file_h", "file_v", "unit_h", "unit_v", "dt_h", "dt_v", "crc32_h", "crc32_v", "channel_h", "channel_v", "x_dot",
        "tau_end", "tail_s",
    ];
    fn no_nan(v: &serde_json::Value, key: &str) {
        match v {
            serde_json::Value::Null => {
                assert!(NULLABLE.contains(&key), "{key} is null (NaN?)");
            }
            serde_json::Value::Object(m) => m.iter().for_each(|(k, v)| no_nan(v, k)),
            _ => {}
        }
    }
    no_nan(&config::to_json(cfg), "");
}

fn assert_one_line(msg: &str) {
    assert!(!msg.trim().is_empty(), "empty error");
    assert!(!msg.contains('\n'), "multi-line error: {msg:?}");
}

/// Parses `text` as a file named `file` would be.
fn parse(text: &str, file: &str) -> Result<Scenario, String> {
    let table = config::parse_toml(text, file).map_err(|e| e.to_string())?;
    config::from_table(&table, &Source::preset()).map_err(|e| e.to_string())
}

proptest! {
    #![proptest_config(proptest_config())]

    #[test]
    fn random_documents_give_a_valid_config_or_an_error_naming_the_key(text in document()) {
        match parse(&text, "random.toml") {
            Ok(cfg) => check_valid(&cfg),
            Err(msg) => {
                assert_one_line(&msg);
                // Either a TOML syntax error with file:line, or a key error
                // naming one of the keys written.
                let names_a_key = text.lines().filter_map(|l| l.split(" = ").next()).any(|k| msg.contains(k.trim()));
                let names_a_section = text.lines().any(|l| l.starts_with('[') && msg.contains(l.trim_matches(|c| c == '[' || c == ']')));
                prop_assert!(
                    msg.starts_with("random.toml:") || names_a_key || names_a_section,
                    "error names neither the file nor a key: {msg}\n{text}"
                );
            }
        }
    }

    #[test]
    fn a_preset_with_one_value_replaced_is_valid_or_names_that_key(
        which in 0usize..64,
        line_pick in 0usize..64,
        v in value(),
    ) {
        let names = presets::names();
        let name = names[which % names.len()];
        let text = presets::get(name).expect("listed preset");
        let lines: Vec<&str> = text.lines().collect();
        let assignments: Vec<usize> = (0..lines.len())
            .filter(|&i| !lines[i].trim_start().starts_with('#') && lines[i].contains(" = "))
            .collect();
        prop_assume!(!assignments.is_empty());
        let i = assignments[line_pick % assignments.len()];
        let key = lines[i].split(" = ").next().expect("split").trim().to_string();
        let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        edited[i] = format!("{key} = {v}");
        let edited = edited.join("\n");
        match parse(&edited, "edited.toml") {
            Ok(cfg) => check_valid(&cfg),
            Err(msg) => {
                assert_one_line(&msg);
                prop_assert!(
                    msg.contains(&key) || msg.starts_with("edited.toml:"),
                    "error does not name {key}: {msg}"
                );
            }
        }
    }

    #[test]
    fn random_set_assignments_are_applied_or_refused_by_name(
        (section, k) in key(),
        v in value(),
        preset in proptest::sample::select(vec!["default", "fig4", "fig12", "fig19"]),
    ) {
        let set = format!("{section}.{k}={v}");
        match config::load(Some(preset), None, std::slice::from_ref(&set)) {
            Ok(cfg) => check_valid(&cfg),
            Err(e) => {
                let msg = e.to_string();
                assert_one_line(&msg);
                prop_assert!(
                    msg.contains(&format!("{section}.{k}")) || msg.contains(&section) || msg.contains("--set"),
                    "error does not name {section}.{k}: {msg}"
                );
            }
        }
    }

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(msg) = parse(&text, "bytes.toml") {
            assert_one_line(&msg);
        }
    }
}

#[test]
fn every_preset_parses_and_validates() {
    for name in presets::names() {
        let cfg = config::load(Some(name), None, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_valid(&cfg);
    }
}

#[test]
fn a_missing_file_is_an_error_naming_it() {
    let err = config::load(None, Some(Path::new("/nonexistent/rocking.toml")), &[])
        .expect_err("no such file")
        .to_string();
    assert!(err.contains("/nonexistent/rocking.toml"), "{err}");
    assert_one_line(&err);
}

/// Issue 14: every impact-law and pulse-shape name of the config is
/// accepted with its meaning, and a near miss (the Rust spelling, or a
/// shortening) is refused in one line naming the key.
#[test]
fn impact_law_and_pulse_shape_names() {
    use rocking::sim::scenario::{LawKind, ShapeKind};
    let laws = [
        ("housner", LawKind::Housner),
        ("corner-momentum", LawKind::CornerMomentum),
        ("ratio", LawKind::Ratio),
        ("impulse", LawKind::Impulse),
    ];
    for (name, law) in laws {
        let cfg = parse(&format!("[impact]\nlaw = \"{name}\"\n"), "law.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((cfg.impact.law, law.name()), (law, name));
    }
    let shapes = [
        ("one-sine", ShapeKind::OneSine),
        ("one-cosine", ShapeKind::OneCosine),
        ("type-c", ShapeKind::TypeC),
        ("rectangular", ShapeKind::Rectangular),
        ("half-sine", ShapeKind::HalfSine),
    ];
    for (name, shape) in shapes {
        let text = format!("[excitation]\nkind = \"pulse\"\na_h = 3\nomega_h = 2\nshape = \"{name}\"\n");
        let cfg = parse(&text, "shape.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((cfg.excitation.shape, shape.name()), (shape, name));
        cfg.model().unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    for (section, key, bad) in [
        ("impact", "law", "corner_momentum"),
        ("impact", "law", "cornermomentum"),
        ("excitation", "shape", "half_sine"),
        ("excitation", "shape", "rect"),
    ] {
        let msg = parse(&format!("[{section}]\n{key} = \"{bad}\"\n"), "bad.toml").expect_err(bad);
        assert_one_line(&msg);
        assert!(msg.contains(&format!("{section}.{key}")), "{bad}: {msg}");
    }
}

/// Every key of the catalogue is a field of the config's serde shape: a
/// value of its kind is never refused as an unknown key or an unknown
/// field (a key added to the catalogue alone fails here).
#[test]
fn every_catalogue_key_is_read_by_the_config_parser() {
    use rocking::sim::catalogue::{CATALOGUE, Dimension, Value};
    for k in CATALOGUE {
        let value = match k.value {
            Value::Quantity(Dimension::Pga) => "\"0.3 g\"".to_string(),
            Value::Quantity(_) | Value::Number => "0.5".to_string(),
            Value::Count => "2".to_string(),
            Value::Choice(words) => format!("\"{}\"", words[0]),
            Value::Path => "\"no-such-record.dat\"".to_string(),
            Value::Checksum => "\"00000000\"".to_string(),
            Value::Flag => "true".to_string(),
            Value::Tables => "[{ period = 1.0 }]".to_string(),
        };
        let (section, name) = k.key.split_once('.').expect("section.name");
        let text = format!("[{section}]\n{name} = {value}\n");
        if let Err(e) = parse(&text, "key.toml") {
            assert!(!e.contains("unknown"), "{}: {e}", k.key);
        }
    }
}
