//! A ground-motion record: where it came from, how a record's length decides where a run ends, and the doubts its peak raises about its unit.

use std::path::PathBuf;

use super::{ExcitationKind, IMPLAUSIBLE_PGA_G, IMPLAUSIBLY_SMALL_PGA_G, Scenario, readable_g};
use crate::model::excitation::Excitation;
use crate::model::excitation::record::Series;
use crate::model::units::AccelUnit;

/// How a record shipped inside the program is named in place of a path
/// (`shipped:kobe-1995.dat`): see `io::shipped`.
pub const SHIPPED_PREFIX: &str = "shipped:";

/// A ground-motion record read by the config layer, with where it came from
/// (for `summary.json`).
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The file, as the config named it (resolved against the config's
    /// folder), or `shipped:NAME` for a record shipped inside the program
    /// ([`SHIPPED_PREFIX`]).
    pub path: PathBuf,
    /// Its samples, accelerations converted to g.
    pub series: Series,
    /// The unit the file's accelerations were in (`excitation.unit_h`, or
    /// read from an AT2 header).
    pub unit: AccelUnit,
    /// The time step of a one-column file, s (`excitation.dt_h`); `None`
    /// for files that hold their times.
    pub dt: Option<f64>,
    /// CRC-32 of the file's bytes (`excitation.crc32_h`, written to
    /// `summary.json` so that a rerun notices a changed file).
    pub crc32: u32,
    /// The channel read, from 1, of a COSMOS file that holds several
    /// (`excitation.channel_h`); `None` for a file of one.
    pub channel: Option<usize>,
}

impl Record {
    /// The record's file name, for answers and labels: `kobe-1995.dat` for
    /// `/data/kobe-1995.dat` and for the shipped `shipped:kobe-1995.dat`.
    pub fn file_name(&self) -> String {
        record_file_name(&self.path.display().to_string())
    }

    /// Why the record's PGA as read (before any scale) suggests a wrong
    /// unit, if it does: `PGA 6.803 g as read in g is implausible for
    /// ground motion (above 5 g); check its unit`. A study scales records
    /// on purpose, so it is their PGA as read that tells a unit mistake.
    pub fn unit_doubt(&self) -> Option<String> {
        let pga = self.series.peak_abs_g();
        Scenario::pga_doubt(pga).map(|doubt| {
            format!(
                "PGA {} g as read in {} is {doubt}; check its unit",
                readable_g(pga),
                self.unit
            )
        })
    }
}

/// The file name in a record's path or `shipped:NAME` reference (the text
/// itself when it has none).
pub(crate) fn record_file_name(path: &str) -> String {
    let path = path.strip_prefix(SHIPPED_PREFIX).unwrap_or(path);
    std::path::Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The [`Record::path`] of a record given as samples (from memory, not
/// from a file): it names no file, so messages that show a record's path
/// say where it came from.
pub(crate) const IN_MEMORY: &str = "(samples in memory)";

impl Record {
    /// A record given as samples rather than read from a file (a caller
    /// that holds them, such as the Python package): `unit` is the unit the
    /// caller's accelerations were in (the series is in g), `dt` their time
    /// step if they were given as one. Its CRC-32 is of the series' bytes
    /// (times then accelerations, little-endian f64), so that two runs can
    /// tell whether they had the same samples; no file can be checked
    /// against it, and a config written from it names no file
    /// ([`Record::is_in_memory`]).
    pub fn in_memory(series: Series, unit: AccelUnit, dt: Option<f64>) -> Self {
        let mut hasher = crc32fast::Hasher::new();
        for x in series.times_s().iter().chain(series.accel_g()) {
            hasher.update(&x.to_le_bytes());
        }
        Self {
            path: PathBuf::from(IN_MEMORY),
            series,
            unit,
            dt,
            crc32: hasher.finalize(),
            channel: None,
        }
    }

    /// Whether the record was given as samples ([`Record::in_memory`]).
    pub fn is_in_memory(&self) -> bool {
        self.path.as_os_str() == IN_MEMORY
    }
}

impl Scenario {
    /// The end of the record in τ (the later of its two components' last
    /// samples, times p), for a record scenario.
    pub fn record_end_tau(&self) -> Option<f64> {
        let x = &self.excitation;
        if x.kind != ExcitationKind::Record {
            return None;
        }
        let h = x.record_h.as_ref()?.series.duration_s();
        let v = x.record_v.as_ref().map_or(0.0, |r| r.series.duration_s());
        Some(h.max(v) * self.geometry().p)
    }

    /// For a record, the τ after which a block at rest stays at rest for
    /// ever: the record's end, or on a floor the later time at which the
    /// building's ringing down can no longer lift or slide the block
    /// ([`FloorExcitation::quiet_after`](crate::model::excitation::FloorExcitation::quiet_after) at min(B/H, μ_s) g, the vertical
    /// being at rest then). `None` for other kinds.
    pub(crate) fn rest_after_tau(&self) -> Option<f64> {
        let end = self.record_end_tau()?;
        if self.floor.is_none() {
            return Some(end);
        }
        let level = (self.block.width / self.block.height).min(self.block.mu_s);
        match self.excitation() {
            Ok(Excitation::Floor(f)) => Some(end.max(f.quiet_after(end, level))),
            _ => Some(end),
        }
    }

    /// Where the run ends, τ: `run.tau_end`, or for a record whose length
    /// decides ([`RunSpec::record_tail_s`](super::RunSpec::record_tail_s)) the record's end plus the tail.
    pub fn tau_end(&self) -> f64 {
        match (self.record_end_tau(), self.run.record_tail_s) {
            (Some(end), Some(tail_s)) => end + tail_s * self.geometry().p,
            _ => self.run.tau_end,
        }
    }

    /// Whether the run covers the whole record (its end is at or after the
    /// record's last sample); `None` for other kinds. A run that overturns
    /// earlier still covered it in this sense: nothing was cut short by the
    /// user.
    pub fn record_complete(&self) -> Option<bool> {
        self.record_end_tau().map(|end| self.tau_end() >= end)
    }

    /// Why a record's PGA of `pga_g` (g) suggests a wrong unit, if it does:
    /// above [`IMPLAUSIBLE_PGA_G`] or below [`IMPLAUSIBLY_SMALL_PGA_G`].
    pub(crate) fn pga_doubt(pga_g: f64) -> Option<String> {
        if pga_g > IMPLAUSIBLE_PGA_G {
            Some(format!("implausible for ground motion (above {IMPLAUSIBLE_PGA_G} g)"))
        } else if pga_g < IMPLAUSIBLY_SMALL_PGA_G {
            Some(format!(
                "implausibly small for a record to run (below {IMPLAUSIBLY_SMALL_PGA_G} g)"
            ))
        } else {
            None
        }
    }

    /// One line per record whose peak suggests a wrong unit (PGA above
    /// [`IMPLAUSIBLE_PGA_G`] or below [`IMPLAUSIBLY_SMALL_PGA_G`] after unit
    /// and scale), naming the file and its PGA: the run goes on, but the
    /// user is told.
    pub fn warnings(&self) -> Vec<String> {
        let x = &self.excitation;
        if x.kind != ExcitationKind::Record {
            return Vec::new();
        }
        [
            ("excitation.unit_h", &x.record_h, x.scale_h),
            ("excitation.unit_v", &x.record_v, x.scale_v),
        ]
        .into_iter()
        .filter_map(|(key, r, scale)| {
            let r = r.as_ref()?;
            let pga = r.series.peak_abs_g() * scale.abs();
            let doubt = Self::pga_doubt(pga)?;
            Some(format!(
                "warning: {}: PGA {} g (read in {}, scaled by {}) is {doubt}; check {key}",
                r.path.display(),
                readable_g(pga),
                r.unit,
                scale,
            ))
        })
        .collect()
    }
}
