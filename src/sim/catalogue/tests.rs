use super::*;

#[test]
fn every_key_is_declared_once_and_every_param_has_its_entry() {
    let mut keys: Vec<String> = CATALOGUE.iter().map(|k| k.key.to_string()).collect();
    let n = keys.len();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), n, "a key is declared twice");
    for p in Param::ALL {
        let owners = CATALOGUE.iter().filter(|k| k.param == Some(p)).count();
        assert_eq!(owners, 1, "{p:?}");
        assert!(matches!(spec_of(p).value, Value::Quantity(_) | Value::Number), "{p:?}");
    }
}

#[test]
fn sections_keep_the_config_files_order() {
    assert_eq!(
        sections(),
        [
            "block",
            "stack",
            "frame",
            "friction",
            "impact",
            "excitation",
            "initial",
            "run",
            "analysis",
            "floor"
        ]
    );
    // The entries of a section are contiguous, so the order of a section's
    // keys is the table's.
    let mut seen: Vec<&str> = Vec::new();
    for k in CATALOGUE {
        if seen.last() != Some(&k.section()) {
            assert!(!seen.contains(&k.section()), "{} is split", k.section());
            seen.push(k.section());
        }
    }
}

#[test]
fn every_panel_slot_is_distinct_and_every_slider_is_usable() {
    for g in Group::ALL {
        let orders: Vec<u8> = panel_keys(g).iter().map(|k| k.slot.unwrap().order).collect();
        let mut distinct = orders.clone();
        distinct.dedup();
        assert_eq!(orders, distinct, "{g:?}");
        assert!(!orders.is_empty(), "{g:?} is empty");
    }
    for k in CATALOGUE {
        if let Some(s) = k.slider {
            assert!(k.slot.is_some(), "{}: a slider outside the panel", k.key);
            assert!(matches!(k.value, Value::Quantity(_) | Value::Number), "{}", k.key);
            assert!(s.min < s.max && s.step > 0.0 && s.step < s.max - s.min, "{}", k.key);
            assert!(!s.log || s.min > 0.0, "{}: a log slider from {}", k.key, s.min);
        }
    }
}

#[test]
fn every_range_admits_the_default_scene_and_refuses_a_value_beyond_it() {
    let s = crate::sim::Scenario::default();
    for k in CATALOGUE {
        let (Some(range), Some(p)) = (k.range, k.param) else {
            continue;
        };
        assert!((range.ok)(p.get(&s)), "{}: the default {} is refused", k.key, p.get(&s));
        assert!(!(range.ok)(f64::NAN), "{}: NaN is allowed", k.key);
        assert!(!(range.ok)(-1e300) || !(range.ok)(1e300), "{}: no bound", k.key);
    }
}

#[test]
fn every_key_has_words_for_each_surface() {
    for k in CATALOGUE {
        assert!(
            !k.meaning.is_empty() && !k.written.is_empty() && !k.doc.is_empty(),
            "{}",
            k.key
        );
        assert!(
            k.meaning.is_ascii() && k.written.is_ascii(),
            "{}: Python's words are ASCII",
            k.key
        );
        if k.slot.is_some() {
            assert!(!k.symbol.is_empty(), "{}: no label", k.key);
        }
    }
}

#[test]
fn markdown_table_has_a_row_a_key() {
    let t = markdown_table();
    assert_eq!(t.lines().count(), CATALOGUE.len() + 2);
    assert!(
        t.contains("| `excitation.a_v` | an acceleration: g, m/s2, cm/s2 (gal), g*tan(alpha) (bare: units of psi*g) | Vertical amplitude"),
        "{t}"
    );
}
