//! The τ grid a live run's chunks end on, and the section phase it is shifted by.

/// The τ grid of chunk ends: each forcing period split into `parts`,
/// the periods starting at the section times. With no phase offset,
/// period boundaries are computed as `k · period`, exactly as the driver
/// computes section times, so they coincide bit for bit; with an offset
/// φ/Ω_h, as `offset + (k − 1) · period` (the first period, k = 0, starts
/// before τ = 0, so that no chunk exceeds [`MAX_CHUNK`](super::MAX_CHUNK)).
#[derive(Clone, Copy, Debug)]
pub(super) struct ChunkGrid {
    pub(super) period: f64,
    pub(super) parts: u64,
    /// φ/Ω_h, in [0, period).
    pub(super) offset: f64,
}

impl ChunkGrid {
    /// Start of the grid's `k`-th period.
    fn period_start(&self, k: u64) -> f64 {
        if self.offset == 0.0 {
            k as f64 * self.period
        } else {
            self.offset + (k as f64 - 1.0) * self.period
        }
    }

    /// The `j`-th chunk end.
    pub(super) fn end(&self, j: u64) -> f64 {
        let (k, i) = (j / self.parts, j % self.parts);
        let start = self.period_start(k);
        if i == 0 {
            start
        } else {
            start + i as f64 * (self.period / self.parts as f64)
        }
    }

    /// The section index k of chunk end `j`, if it is a section time
    /// (τ_k = offset + k · period).
    pub(super) fn section_index(&self, j: u64) -> Option<u64> {
        let (k, i) = (j / self.parts, j % self.parts);
        match (i, self.offset == 0.0) {
            (0, true) => Some(k),
            (0, false) => k.checked_sub(1),
            _ => None,
        }
    }
}

/// `phase` taken into [0, 2π); non-finite phases are 0.
pub fn normalise_phase(phase: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    if !phase.is_finite() {
        return 0.0;
    }
    let p = phase.rem_euclid(two_pi);
    // rem_euclid can round up to 2π itself for tiny negative phases.
    if p >= two_pi { 0.0 } else { p }
}
