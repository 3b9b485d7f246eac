//! The simulation thread's outbox: messages the bounded update channel has
//! not accepted yet, in order, under the runner's channel policy (see
//! [`super`]): samples may be dropped (the newest kept, the rest counted),
//! events, section points and control messages never are, and too many
//! waiting exact items stop the integration (backpressure).

use std::collections::VecDeque;

use crossbeam_channel::TrySendError;

use crate::sim::job::Link;
use crate::sim::protocol::{Batch, RunId, SimCommand, SimUpdate};

/// Most samples a merged batch in the outbox keeps (the newest). 2¹⁶
/// samples are 328 τ at [`super::LIVE_SAMPLE_DT`], more than the
/// time-history window shows.
pub const MAX_QUEUED_SAMPLES: usize = 1 << 16;

/// Events plus section points in the outbox beyond which the thread stops
/// integrating until the consumer catches up (about 10 MB).
pub const MAX_QUEUED_EXACT: usize = 1 << 17;

/// Messages not yet accepted by the channel, in order.
#[derive(Default)]
pub(super) struct Outbox {
    queue: VecDeque<SimUpdate>,
}

impl Outbox {
    /// Whether everything has been sent.
    pub(super) fn is_empty(&self) -> bool {
        self.queue.is_empty()
    }

    /// Queues `u` behind what waits.
    pub(super) fn push(&mut self, u: SimUpdate) {
        self.queue.push_back(u);
    }

    /// Drops the messages of runs before `run`: the consumer would drop
    /// them anyway, and they must not hold the new run back.
    pub(super) fn purge_before(&mut self, run: RunId) {
        self.queue.retain(|u| u.run() >= run);
    }

    /// Queues `batch` of `run`, merging it into a waiting batch of the same
    /// run (so a slow consumer costs samples, not memory).
    pub(super) fn push_batch(&mut self, run: RunId, batch: Batch) {
        if batch.is_empty() {
            return;
        }
        if let Some(SimUpdate::Batch { run: r, batch: waiting }) = self.queue.back_mut()
            && *r == run
        {
            merge(waiting, batch);
            return;
        }
        self.queue.push_back(SimUpdate::Batch { run, batch });
    }

    /// Whether so many events and section points wait that the thread
    /// must stop integrating until the consumer drains the channel.
    pub(super) fn backpressured(&self) -> bool {
        let exact: usize = self
            .queue
            .iter()
            .map(|u| match u {
                SimUpdate::Batch { batch, .. } => {
                    batch.events.len() + batch.section.len() + batch.stack_events.len() + batch.stack_section.len()
                }
                SimUpdate::Started { .. } | SimUpdate::Paused { .. } | SimUpdate::Finished { .. } => 0,
            })
            .sum();
        exact > MAX_QUEUED_EXACT
    }

    /// Sends what the channel accepts, in order; wakes the consumer once
    /// if anything went.
    pub(super) fn flush(&mut self, link: &Link<SimUpdate, SimCommand>) {
        let mut sent = false;
        while let Some(u) = self.queue.pop_front() {
            match link.try_send(u) {
                Ok(()) => sent = true,
                Err(TrySendError::Full(u)) => {
                    self.queue.push_front(u);
                    break;
                }
                Err(TrySendError::Disconnected(_)) => {
                    // The consumer is gone; the thread ends at its next
                    // look at the command channel.
                    self.queue.clear();
                    break;
                }
            }
        }
        if sent {
            link.wake();
        }
    }
}

/// Appends `next` to `waiting`, keeping at most [`MAX_QUEUED_SAMPLES`]
/// samples (the newest) and counting the dropped ones.
fn merge(waiting: &mut Batch, next: Batch) {
    waiting.samples.extend(next.samples);
    let excess = waiting.samples.len().saturating_sub(MAX_QUEUED_SAMPLES);
    if excess > 0 {
        waiting.samples.drain(..excess);
        waiting.dropped_samples += excess as u64;
    }
    waiting.dropped_samples += next.dropped_samples;
    waiting.events.extend(next.events);
    waiting.section.extend(next.section);
    waiting.stack_events.extend(next.stack_events);
    waiting.stack_section.extend(next.stack_section);
    if !next.ghosts.is_empty() {
        waiting.ghosts = next.ghosts;
    }
    waiting.tau = next.tau;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::protocol::Sample;

    fn sample(tau: f64) -> Sample {
        Sample::flat(tau, crate::model::Mode::Rest, 1.0)
    }

    #[test]
    fn merging_keeps_the_newest_samples_and_counts_the_dropped() {
        let mut a = Batch {
            samples: (0..MAX_QUEUED_SAMPLES).map(|k| sample(k as f64)).collect(),
            ..Batch::default()
        };
        let b = Batch {
            samples: (0..10).map(|k| sample((MAX_QUEUED_SAMPLES + k) as f64)).collect(),
            tau: 7.0,
            ..Batch::default()
        };
        merge(&mut a, b);
        assert_eq!(a.samples.len(), MAX_QUEUED_SAMPLES);
        assert_eq!(a.dropped_samples, 10);
        assert_eq!(a.samples[0].tau, 10.0);
        assert_eq!(a.samples.last().map(|s| s.tau), Some((MAX_QUEUED_SAMPLES + 9) as f64));
        assert_eq!(a.tau, 7.0);
    }
}
