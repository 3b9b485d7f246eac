//! The table of every config key, in the config file's order (sections as
//! a config file writes them; messages list known keys in this order).

use super::{Applies, Group, KeySpec, Range, Slot, Span};
use crate::sim::scenario::{AMPLITUDE_LIMIT, ExcitationKind as K, MAX_SIZE_M, MIN_SIZE_M};

mod assemblies;
mod block;
mod excitation;
mod run;

const fn at(group: Group, order: u8) -> Option<Slot> {
    Some(Slot { group, order })
}

const fn lin(min: f64, max: f64, step: f64) -> Option<Span> {
    Some(Span {
        min,
        max,
        step,
        log: false,
    })
}

const fn log(min: f64, max: f64, step: f64) -> Option<Span> {
    Some(Span {
        min,
        max,
        step,
        log: true,
    })
}

const UNIT_WORDS: &[&str] = &["g", "m/s2", "cm/s2"];
const HARMONIC_OR_PULSE: Applies = Applies::To(&[K::Harmonic, K::Pulse]);
const HARMONIC: Applies = Applies::To(&[K::Harmonic]);
const PULSE: Applies = Applies::To(&[K::Pulse]);
const RECORD: Applies = Applies::To(&[K::Record]);
// A floor filters records and harmonic motion; a pulse refuses it.
const FLOORED: Applies = Applies::To(&[K::Record, K::Harmonic]);

// Sizes from 0.1 mm to 10 km: beyond them ψ, p or 1/p leave the range
// where the run's numbers (τ = p t, amplitudes in ψg) mean anything, or
// overflow (docs/model.md §1.1).
fn size(x: f64) -> bool {
    (MIN_SIZE_M..=MAX_SIZE_M).contains(&x)
}
const SIZE: Option<Range> = Some(Range {
    ok: size,
    allowed: "in [1e-4, 1e4] metres",
});
fn non_negative(x: f64) -> bool {
    x >= 0.0
}
fn non_negative_finite(x: f64) -> bool {
    (0.0..f64::INFINITY).contains(&x)
}
const COEFFICIENT: Option<Range> = Some(Range {
    ok: non_negative,
    allowed: ">= 0 or inf",
});
fn unit_interval(x: f64) -> bool {
    (0.0..=1.0).contains(&x)
}
const UNIT_INTERVAL: Option<Range> = Some(Range {
    ok: unit_interval,
    allowed: "in [0, 1]",
});
fn amplitude(x: f64) -> bool {
    x.abs() <= AMPLITUDE_LIMIT
}
fn frequency(x: f64) -> bool {
    (1e-6..=1e6).contains(&x)
}
const FREQUENCY: Option<Range> = Some(Range {
    ok: frequency,
    allowed: "in [1e-6, 1e6] (units of p; the forcing period 2π/Ω is then at most 6.3e6 τ)",
});
fn phase(x: f64) -> bool {
    x.abs() <= 1e6
}
fn scale(x: f64) -> bool {
    x.abs() <= 1e3
}
const SCALE: Option<Range> = Some(Range {
    ok: scale,
    allowed: "|scale| <= 1000",
});
// Below these the error control asks for more than double precision can
// give and the step size underflows.
fn rtol(x: f64) -> bool {
    (1e-16..1.0).contains(&x)
}
fn atol(x: f64) -> bool {
    (1e-20..1.0).contains(&x)
}
fn open_unit(x: f64) -> bool {
    x > 0.0 && x < 1.0
}
fn tail(x: f64) -> bool {
    (0.0..=1e6).contains(&x)
}
fn spacing(x: f64) -> bool {
    x >= 0.0 && x.is_finite()
}
fn zeno(x: f64) -> bool {
    (0.0..1.0).contains(&x)
}

const B: KeySpec = KeySpec::BLANK;

/// `parts` one after another (the sections' tables as one), `N` entries.
const fn gather<const N: usize>(parts: &[&[KeySpec]]) -> [KeySpec; N] {
    let mut out = [B; N];
    let (mut n, mut k) = (0, 0);
    while k < parts.len() {
        let mut j = 0;
        while j < parts[k].len() {
            out[n] = parts[k][j];
            n += 1;
            j += 1;
        }
        k += 1;
    }
    assert!(n == N);
    out
}

/// How many entries `parts` hold together.
const fn total(parts: &[&[KeySpec]]) -> usize {
    let (mut n, mut k) = (0, 0);
    while k < parts.len() {
        n += parts[k].len();
        k += 1;
    }
    n
}

/// The sections, in the config file's order.
const SECTIONS: &[&[KeySpec]] = &[
    block::BLOCK,
    assemblies::STACK,
    assemblies::FRAME,
    block::FRICTION,
    block::IMPACT,
    excitation::EXCITATION,
    run::INITIAL,
    run::RUN,
    run::ANALYSIS,
    excitation::FLOOR,
];

/// Every key the config accepts, in the config file's order.
pub const CATALOGUE: &[KeySpec] = &gather::<{ total(SECTIONS) }>(SECTIONS);
