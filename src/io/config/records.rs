//! The records a config names: each component's record keys, the file read in its unit (or the record given as samples, or kept from an earlier read), and its scale.

use std::path::PathBuf;

use super::quantity::{Dimension, Quantity};
use super::raw::Finite;
use super::{ConfigError, Source};
use crate::io::record::{self, RecordError, RecordSpec};
use crate::io::shipped;
use crate::model::Geometry;
use crate::model::units::AccelUnit;
use crate::sim::scenario::Record;

/// One component's record keys: `file`, `unit`, `dt`, `crc32` and
/// `channel`, named with their suffix (`_h` or `_v`).
pub(super) struct RecordKeys<'a> {
    pub(super) suffix: &'static str,
    pub(super) file: Option<&'a str>,
    pub(super) unit: Option<&'a str>,
    pub(super) dt: Option<Quantity>,
    pub(super) crc32: Option<&'a str>,
    pub(super) channel: Option<u64>,
}

impl RecordKeys<'_> {
    fn key(&self, name: &str) -> String {
        format!("excitation.{name}{}", self.suffix)
    }
}

/// Reads the record file `keys.file` names in its stated unit (and time
/// step), naming the key at fault in errors; `None` when no file is named.
fn read_record(keys: &RecordKeys<'_>, source: &Source) -> Result<Option<Record>, ConfigError> {
    let unit = match keys.unit {
        None => None,
        Some(text) => Some(AccelUnit::parse(text).ok_or_else(|| {
            let case = AccelUnit::case_hint(text).map_or(String::new(), |h| {
                format!(": units are case-sensitive, did you mean \"{h}\"?")
            });
            ConfigError::key(
                &keys.key("unit"),
                format!("unknown unit \"{text}\"{case} (known: g, m/s2, cm/s2)"),
            )
        })?),
    };
    let dt = keys
        .dt
        .map(|q| q.resolve(&keys.key("dt"), Dimension::Seconds, &Geometry::new(1.0, 1.0)))
        .transpose()?;
    // Channels are counted from 1, as COSMOS numbers them.
    let channel = match keys.channel {
        None => None,
        Some(n) => Some(
            usize::try_from(n)
                .ok()
                .filter(|&n| n >= 1)
                .ok_or_else(|| ConfigError::key(&keys.key("channel"), format!("{n}: channels are counted from 1")))?,
        ),
    };
    let Some(p) = keys.file else {
        for (name, given) in [
            ("unit", unit.is_some()),
            ("dt", dt.is_some()),
            ("crc32", keys.crc32.is_some()),
            ("channel", channel.is_some()),
        ] {
            if given {
                return Err(ConfigError::key(&keys.key(name), format!("needs {}", keys.key("file"))));
            }
        }
        return Ok(None);
    };
    let spec = RecordSpec { unit, dt, channel };
    let (path, loaded) = match shipped::name_of(p) {
        Some(name) => {
            let bytes = shipped::get(name).ok_or_else(|| {
                ConfigError::key(
                    &keys.key("file"),
                    format!(
                        "{p}: no such shipped record (shipped: {})",
                        shipped::references().join(", ")
                    ),
                )
            })?;
            (PathBuf::from(p), record::read_record_bytes(p, bytes, &spec))
        }
        None => {
            let p = PathBuf::from(p);
            let path = if p.is_absolute() { p } else { source.base_dir.join(p) };
            let loaded = record::read_record_as(&path, &spec);
            (path, loaded)
        }
    };
    let loaded = loaded.map_err(|e| {
        let key = match e {
            RecordError::NoUnit { .. }
            | RecordError::HeaderNoUnit { .. }
            | RecordError::NoHeaderUnit { .. }
            | RecordError::UnitConflict { .. } => keys.key("unit"),
            RecordError::NoStep { .. } | RecordError::StatedStep { .. } | RecordError::Columns { expected: 1, .. } => {
                keys.key("dt")
            }
            RecordError::Channels { .. } | RecordError::NoSuchChannel { .. } | RecordError::OneChannel { .. } => {
                keys.key("channel")
            }
            _ => keys.key("file"),
        };
        ConfigError::Record {
            key,
            file: path.display().to_string(),
            message: e.to_string(),
        }
    })?;
    // A summary.json names the checksum of the file it ran: a file changed
    // since is refused rather than silently giving another answer.
    if let Some(expected) = keys.crc32 {
        let found = format!("{:08x}", loaded.crc32);
        if !expected.eq_ignore_ascii_case(&found) {
            let what = if shipped::name_of(p).is_some() {
                "is not the record this config was written with: this program ships other bytes under that name"
            } else {
                "has changed since this config was written"
            };
            return Err(ConfigError::key(
                &keys.key("crc32"),
                format!(
                    "{} {what} (CRC-32 {found}, expected {expected}); remove {} to run the file as it is now",
                    path.display(),
                    keys.key("crc32")
                ),
            ));
        }
    }
    // Absolute, so that summary.json repeats the run from any folder (a
    // shipped record's name is the same from any folder).
    let path = if shipped::name_of(p).is_some() {
        path
    } else {
        path.canonicalize().unwrap_or(path)
    };
    Ok(Some(Record {
        path,
        series: loaded.series,
        unit: loaded.unit,
        dt,
        crc32: loaded.crc32,
        channel,
    }))
}

/// Where a resolution takes one record from.
#[derive(Clone, Copy)]
pub(super) enum RecordFrom<'a> {
    /// The file the keys name, if any.
    Read,
    /// Given as samples ([`from_table_with`](super::from_table_with)): a file's keys beside it are
    /// an error.
    Given(&'a Record),
    /// Already read from the file the keys name ([`from_table_keeping`](super::from_table_keeping)).
    Kept(&'a Record),
}

impl<'a> RecordFrom<'a> {
    pub(super) fn given(record: Option<&'a Record>) -> Self {
        record.map_or(Self::Read, Self::Given)
    }

    pub(super) fn kept(record: Option<&'a Record>) -> Self {
        record.map_or(Self::Read, Self::Kept)
    }
}

/// The record given as samples, or kept from an earlier read of the same
/// keys, or else the file the keys name.
pub(super) fn given_or_read(
    keys: &RecordKeys<'_>,
    source: &Source,
    from: RecordFrom<'_>,
) -> Result<Option<Record>, ConfigError> {
    let given = match from {
        RecordFrom::Read => return read_record(keys, source),
        // A clone shares the samples: no file is read, nothing copied.
        RecordFrom::Kept(kept) if keys.file.is_some() => return Ok(Some(kept.clone())),
        RecordFrom::Kept(_) => return read_record(keys, source),
        RecordFrom::Given(given) => given,
    };
    let named = [
        ("file", keys.file.is_some()),
        ("unit", keys.unit.is_some()),
        ("dt", keys.dt.is_some()),
        ("crc32", keys.crc32.is_some()),
        ("channel", keys.channel.is_some()),
    ];
    if let Some((name, _)) = named.iter().find(|(_, set)| *set) {
        return Err(ConfigError::key(
            &keys.key(name),
            "the record is given as samples; a file's keys do not apply to it",
        ));
    }
    Ok(Some(given.clone()))
}

/// The scale factor on a record: `excitation.scale_*`, or the one that
/// makes its PGA `excitation.pga_*`; both at once is an error.
pub(super) fn record_scale(
    keys: &RecordKeys<'_>,
    record: Option<&Record>,
    scale: Option<Finite>,
    pga: Option<Quantity>,
    geo: &Geometry,
    default: f64,
) -> Result<f64, ConfigError> {
    let Some(pga) = pga else {
        return Ok(scale.map_or(default, |s| s.0));
    };
    let key = keys.key("pga");
    if scale.is_some() {
        return Err(ConfigError::key(
            &key,
            format!("give either {} or {key}, not both", keys.key("scale")),
        ));
    }
    let Some(record) = record else {
        return Err(ConfigError::key(&key, format!("needs {}", keys.key("file"))));
    };
    let target = pga.resolve(&key, Dimension::Pga, geo)?;
    if target.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(ConfigError::key(&key, format!("must be > 0, got {target} g")));
    }
    let peak = record.series.peak_abs_g();
    if peak == 0.0 {
        return Err(ConfigError::key(
            &key,
            format!(
                "{} has no motion (PGA 0), it cannot be scaled to a PGA",
                record.path.display()
            ),
        ));
    }
    Ok(target / peak)
}
