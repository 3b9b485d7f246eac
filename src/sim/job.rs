//! One background job: a named thread that works for a consumer (the app),
//! takes commands in, sends replies out, can be cancelled, and is joined
//! when its handle is dropped.
//!
//! The simulation thread ([`super::runner::SimHandle`]) and the app's
//! analysis views (the bifurcation sweep, the Lyapunov estimate) are all
//! such jobs; this type is the one place the pattern is written.
//!
//! Contract:
//! - The thread is named (`std::thread::spawn` is disallowed by
//!   `clippy.toml`: a named thread shows up in debuggers and panic messages).
//! - **Commands** go in over an unbounded channel: they come from user
//!   actions, so they are few, and none may be lost. A job that takes none
//!   has `Cmd = Infallible`.
//! - **Replies** go out over a bounded channel whose capacity the job
//!   chooses. When it is full, the thread decides what happens, through the
//!   method it sends with:
//!   - [`Link::send`] waits for room (backpressure: nothing is lost, the
//!     job slows to the consumer's pace), but gives up as soon as the job
//!     is cancelled or the consumer is gone, so a job whose consumer stopped
//!     draining can never hang its thread (nor the join in `Drop`).
//!   - [`Link::try_send`] never waits and hands the reply back: the thread
//!     keeps it (and may merge or drop it under its own documented policy;
//!     the simulation thread's outbox does).
//! - **Waking**: the consumer supplies a [`Waker`] (the app passes
//!   `ctx.request_repaint()`), so this layer never names a GUI toolkit.
//!   [`Link::send`] wakes after each reply; after [`Link::try_send`]s the
//!   thread calls [`Link::wake`] once for the burst.
//! - **Cancellation** is a flag the thread checks where it can stop
//!   cleanly ([`Link::cancelled`]); work already under way finishes and its
//!   result is not sent.
//! - **Drop** cancels, disconnects the command channel (a thread blocked on
//!   it wakes to `Disconnected`), and joins the thread: no job outlives its
//!   handle. A panic in the thread has already been printed by the panic
//!   hook; joining only reaps it.

use std::convert::Infallible;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use crossbeam_channel::{Receiver, RecvTimeoutError, SendTimeoutError, Sender, TrySendError};

/// Wakes the consumer after replies are sent (the app's repaint request).
pub type Waker = Box<dyn Fn() + Send + Sync>;

/// How often a [`Link::send`] waiting on a full channel looks at the cancel
/// flag: short against a user's reaction, long against a wake-up's cost.
const CANCEL_POLL: Duration = Duration::from_millis(10);

/// Why a [`Link::send`] did not deliver: the job was cancelled or the
/// consumer dropped its handle. Either way the thread should stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the job was cancelled or its consumer is gone")]
pub struct Stopped;

/// The consumer's handle to a running (or finished) job. Dropping it
/// cancels the job and joins its thread.
pub struct Job<Reply, Cmd = Infallible> {
    /// `None` only inside `Drop`, which disconnects it before the join.
    commands: Option<Sender<Cmd>>,
    replies: Receiver<Reply>,
    cancel: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

/// The thread's end of a job: its commands, its replies, its cancel flag
/// and the consumer's waker.
pub struct Link<Reply, Cmd = Infallible> {
    commands: Receiver<Cmd>,
    replies: Sender<Reply>,
    cancel: Arc<AtomicBool>,
    waker: Waker,
}

impl<Reply: Send + 'static, Cmd: Send + 'static> Job<Reply, Cmd> {
    /// Starts `work` on a thread named `name`, with a reply channel of
    /// `capacity` messages; `waker` is called after replies are sent.
    pub fn spawn(
        name: &str,
        capacity: usize,
        waker: Waker,
        work: impl FnOnce(Link<Reply, Cmd>) + Send + 'static,
    ) -> std::io::Result<Self> {
        let (cmd_tx, cmd_rx) = crossbeam_channel::unbounded();
        let (reply_tx, reply_rx) = crossbeam_channel::bounded(capacity);
        let cancel = Arc::new(AtomicBool::new(false));
        let link = Link {
            commands: cmd_rx,
            replies: reply_tx,
            cancel: Arc::clone(&cancel),
            waker,
        };
        let thread = std::thread::Builder::new()
            .name(name.into())
            .spawn(move || work(link))?;
        Ok(Self {
            commands: Some(cmd_tx),
            replies: reply_rx,
            cancel,
            thread: Some(thread),
        })
    }
}

impl<Reply, Cmd> Job<Reply, Cmd> {
    /// Sends `cmd` to the thread. Returns false if the thread has exited
    /// (it was told to, or it panicked): there is nobody to tell then.
    pub fn send(&self, cmd: Cmd) -> bool {
        self.commands.as_ref().is_some_and(|tx| tx.send(cmd).is_ok())
    }

    /// Asks the thread to stop at its next check.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// The next reply, without waiting.
    pub(crate) fn try_recv(&self) -> Option<Reply> {
        self.replies.try_recv().ok()
    }

    /// Every reply received so far, without waiting.
    pub fn drain(&self) -> Vec<Reply> {
        self.replies.try_iter().collect()
    }

    /// Waits up to `timeout` for the next reply (tests).
    pub fn recv_timeout(&self, timeout: Duration) -> Option<Reply> {
        self.replies.recv_timeout(timeout).ok()
    }

    /// Whether replies are waiting.
    pub fn has_pending(&self) -> bool {
        !self.replies.is_empty()
    }

    /// Whether the thread has ended (replies may still be waiting).
    pub fn finished(&self) -> bool {
        self.thread.as_ref().is_none_or(JoinHandle::is_finished)
    }
}

impl<Reply, Cmd> Drop for Job<Reply, Cmd> {
    fn drop(&mut self) {
        self.cancel();
        self.commands = None;
        if let Some(t) = self.thread.take() {
            // A panic in the thread has already been printed by the panic
            // hook; joining only reaps it.
            let _ = t.join();
        }
    }
}

impl<Reply, Cmd> Link<Reply, Cmd> {
    /// Whether the consumer cancelled the job (or dropped its handle).
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Sends `reply`, waiting while the channel is full, then wakes the
    /// consumer. Gives up with [`Stopped`] when the job is cancelled or
    /// the consumer is gone.
    pub fn send(&self, reply: Reply) -> Result<(), Stopped> {
        let mut reply = reply;
        loop {
            match self.replies.send_timeout(reply, CANCEL_POLL) {
                Ok(()) => {
                    (self.waker)();
                    return Ok(());
                }
                Err(SendTimeoutError::Timeout(r)) if !self.cancelled() => reply = r,
                Err(SendTimeoutError::Timeout(_) | SendTimeoutError::Disconnected(_)) => return Err(Stopped),
            }
        }
    }

    /// Sends `reply` if the channel has room, without waking the consumer
    /// (call [`Link::wake`] after a burst); otherwise hands it back.
    pub(crate) fn try_send(&self, reply: Reply) -> Result<(), TrySendError<Reply>> {
        self.replies.try_send(reply)
    }

    /// Wakes the consumer.
    pub(crate) fn wake(&self) {
        (self.waker)();
    }

    /// The next command, waiting at most `timeout` (forever if `None`).
    /// `Ok(None)` means none came in time; `Err(Stopped)` that the consumer
    /// dropped its handle, so the thread should end.
    pub(crate) fn next_command(&self, timeout: Option<Duration>) -> Result<Option<Cmd>, Stopped> {
        match timeout {
            None => self.commands.recv().map(Some).map_err(|_| Stopped),
            Some(d) => match self.commands.recv_timeout(d) {
                Ok(c) => Ok(Some(c)),
                Err(RecvTimeoutError::Timeout) => Ok(None),
                Err(RecvTimeoutError::Disconnected) => Err(Stopped),
            },
        }
    }

    /// The next command if one is waiting; `Err(Stopped)` as in
    /// [`Link::next_command`].
    pub(crate) fn try_command(&self) -> Result<Option<Cmd>, Stopped> {
        match self.commands.try_recv() {
            Ok(c) => Ok(Some(c)),
            Err(crossbeam_channel::TryRecvError::Empty) => Ok(None),
            Err(crossbeam_channel::TryRecvError::Disconnected) => Err(Stopped),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn replies_arrive_in_order_and_wake_the_consumer() {
        let wakes = Arc::new(AtomicUsize::new(0));
        let w = Arc::clone(&wakes);
        let job: Job<u32> = Job::spawn(
            "job-test",
            2,
            Box::new(move || {
                w.fetch_add(1, Ordering::SeqCst);
            }),
            |link| {
                for k in 0..5 {
                    if link.send(k).is_err() {
                        return;
                    }
                }
            },
        )
        .expect("thread starts");
        // Capacity 2 < 5 replies: the thread waits for the consumer.
        let got: Vec<u32> = (0..5)
            .filter_map(|_| job.recv_timeout(Duration::from_secs(5)))
            .collect();
        assert_eq!(got, vec![0, 1, 2, 3, 4]);
        while !job.finished() {
            std::thread::sleep(Duration::from_millis(1));
        }
        assert_eq!(wakes.load(Ordering::SeqCst), 5);
    }

    #[test]
    fn a_cancelled_job_blocked_on_a_full_channel_ends_and_drop_joins() {
        let job: Job<u32> = Job::spawn("job-test", 1, Box::new(|| {}), |link| {
            let mut k = 0;
            while link.send(k).is_ok() {
                k += 1;
            }
        })
        .expect("thread starts");
        // Nobody drains: the thread blocks on the second reply until cancelled.
        std::thread::sleep(Duration::from_millis(30));
        assert!(!job.finished());
        job.cancel();
        let t0 = std::time::Instant::now();
        while !job.finished() {
            assert!(t0.elapsed() < Duration::from_secs(5), "cancel ends the thread");
            std::thread::sleep(Duration::from_millis(1));
        }
        assert_eq!(job.drain(), vec![0]);
    }

    #[test]
    fn commands_reach_the_thread_and_drop_disconnects_them() {
        let (seen_tx, seen_rx) = crossbeam_channel::unbounded();
        let job: Job<(), u32> = Job::spawn("job-test", 1, Box::new(|| {}), move |link| {
            // Blocks forever on commands: only the disconnect in Drop ends it.
            while let Ok(Some(c)) = link.next_command(None) {
                let _ = seen_tx.send(c);
            }
        })
        .expect("thread starts");
        assert!(job.send(7));
        assert_eq!(seen_rx.recv_timeout(Duration::from_secs(5)), Ok(7));
        drop(job);
        assert!(seen_rx.recv().is_err(), "the thread ended and dropped its sender");
    }
}
