//! The simulation thread without a GUI: ordering, run ids, the backpressure
//! policy, pacing, and shutdown joined on drop.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use rocking::io::config::load;
use rocking::sim::protocol::{Batch, RunEnd, RunId, RunInfo, Sample, SimUpdate, Speed, StartFrom};
use rocking::sim::runner::{LIVE_SAMPLE_DT, SimHandle, record};
use rocking::sim::{RunOptions, Scenario, simulate};

fn preset(name: &str, sets: &[&str]) -> Scenario {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    load(Some(name), None, &sets).expect("preset loads")
}

fn no_waker() -> Box<dyn Fn() + Send + Sync> {
    Box::new(|| {})
}

/// Receives updates until `done` says stop or `timeout` passes.
fn collect(h: &SimHandle, timeout: Duration, mut done: impl FnMut(&[SimUpdate]) -> bool) -> Vec<SimUpdate> {
    let start = Instant::now();
    let mut got = Vec::new();
    while start.elapsed() < timeout {
        if let Some(u) = h.recv_timeout(Duration::from_millis(20)) {
            got.push(u);
            if done(&got) {
                break;
            }
        }
    }
    got
}

fn batches(updates: &[SimUpdate], run: RunId) -> Vec<&Batch> {
    updates
        .iter()
        .filter_map(|u| match u {
            SimUpdate::Batch { run: r, batch } if *r == run => Some(batch),
            _ => None,
        })
        .collect()
}

/// A paused thread on the default scene stepped `tau` forward, and the
/// last sample it sent (the state the app shows).
fn paused_after(tau: f64) -> (SimHandle, Sample) {
    let h = SimHandle::spawn(preset("default", &[]), Speed::RealTime(1.0), true, no_waker()).expect("thread starts");
    h.step(tau);
    let got = collect(&h, Duration::from_secs(5), |u| {
        u.iter()
            .any(|x| matches!(x, SimUpdate::Paused { tau, .. } if *tau > 0.0))
    });
    let last = *batches(&got, RunId(1))
        .iter()
        .rev()
        .find_map(|b| b.samples.last())
        .expect("samples");
    (h, last)
}

/// The start message of run `run` among `updates`.
fn started(updates: &[SimUpdate], run: RunId) -> &RunInfo {
    updates
        .iter()
        .find_map(|u| match u {
            SimUpdate::Started { run: r, info } if *r == run => Some(info),
            _ => None,
        })
        .expect("the run started")
}

fn sample_index(tau: f64) -> i64 {
    (tau / LIVE_SAMPLE_DT).round() as i64
}

#[test]
fn live_section_points_equal_the_batch_run_bit_for_bit() {
    // Chunk ends put no stops in the step sequence (a chunk ends with the
    // whole step that reaches its end), so the live trajectory is the batch
    // trajectory, up to the batch run's last step: that one is shortened to
    // end on τ_end, so what falls in it is compared only to the tolerance.
    let cfg = preset("default", &[]);
    let tau_end = 60.0;
    let updates = record(RunId(1), &cfg, tau_end);
    let live = batches(&updates, RunId(1));
    assert_eq!(live.len(), 1);
    let opts = RunOptions {
        tau_end,
        ..cfg.run_options()
    };
    let batch = simulate(cfg.model().expect("model"), &cfg.initial, &opts).expect("batch run");
    assert!(batch.section.len() > 50, "a 60 τ run at Ω = 8 has 76 section points");
    let n = batch.section.len().min(live[0].section.len());
    assert!(n + 1 >= batch.section.len(), "live run lost section points");
    // Steps at the default tolerance are under 0.1 τ.
    let before_last_step = tau_end - 0.5;
    for (a, b) in batch.section.iter().zip(&live[0].section).take(n) {
        assert_eq!(a.k, b.k);
        assert_eq!(a.tau.to_bits(), b.tau.to_bits());
        if a.tau < before_last_step {
            assert_eq!(a.theta.to_bits(), b.theta.to_bits(), "Θ at k = {}", a.k);
            assert_eq!(a.theta_dot.to_bits(), b.theta_dot.to_bits(), "Θ' at k = {}", a.k);
        } else {
            assert!((a.theta - b.theta).abs() < 1e-9 && (a.theta_dot - b.theta_dot).abs() < 1e-9);
        }
    }
    let early = |e: &&rocking::model::EventRecord| e.tau < before_last_step;
    let (ea, eb): (Vec<_>, Vec<_>) = (
        batch.events.iter().filter(early).collect(),
        live[0].events.iter().filter(early).collect(),
    );
    assert!(ea.len() > 50, "{} events", ea.len());
    assert_eq!(ea.len(), eb.len());
    for (a, b) in ea.iter().zip(&eb) {
        assert_eq!(a.tau.to_bits(), b.tau.to_bits());
        assert_eq!(a.kind, b.kind);
    }
}

#[test]
fn updates_come_in_order_with_the_run_id_and_nothing_exact_is_lost() {
    let h = SimHandle::spawn(preset("default", &[]), Speed::Max, false, no_waker()).expect("thread starts");
    let got = collect(&h, Duration::from_secs(20), |u| {
        batches(u, RunId(1)).iter().map(|b| b.section.len()).sum::<usize>() > 400
    });
    assert!(
        matches!(got.first(), Some(SimUpdate::Started { run: RunId(1), .. })),
        "first update is Started(1)"
    );
    assert!(got.iter().all(|u| u.run() == RunId(1)));
    let bs = batches(&got, RunId(1));
    let ks: Vec<u64> = bs.iter().flat_map(|b| b.section.iter().map(|p| p.k)).collect();
    assert!(ks.len() > 400, "got {} section points", ks.len());
    for (i, k) in ks.iter().enumerate() {
        assert_eq!(*k, i as u64, "section points arrive consecutively from k = 0");
    }
    let taus: Vec<f64> = bs.iter().flat_map(|b| b.events.iter().map(|e| e.tau)).collect();
    assert!(taus.windows(2).all(|w| w[0] <= w[1]), "events in time order");
    let samples: Vec<f64> = bs.iter().flat_map(|b| b.samples.iter().map(|s| s.tau)).collect();
    assert!(samples.windows(2).all(|w| w[0] < w[1]), "samples in time order");
}

#[test]
fn a_reset_starts_a_new_run_and_no_stale_update_follows_its_start() {
    let mut h = SimHandle::spawn(preset("default", &[]), Speed::Max, false, no_waker()).expect("thread starts");
    let _ = collect(&h, Duration::from_secs(10), |u| !batches(u, RunId(1)).is_empty());
    let run = h.reset();
    assert_eq!(run, RunId(2));
    assert_eq!(h.current_run(), RunId(2));
    let got = collect(&h, Duration::from_secs(10), |u| !batches(u, RunId(2)).is_empty());
    let start = got
        .iter()
        .position(|u| matches!(u, SimUpdate::Started { run: RunId(2), .. }))
        .expect("run 2 started");
    assert!(
        got[start..].iter().all(|u| u.run() == RunId(2)),
        "an update of run 1 came after run 2 started"
    );
    let SimUpdate::Started { info, .. } = &got[start] else {
        unreachable!()
    };
    assert_eq!(info.tau0, 0.0, "a reset starts from τ = 0");
    let first = batches(&got, RunId(2))[0].samples.first().expect("samples").tau;
    assert!(first < 1.0, "run 2 restarted from τ = 0, first sample at {first}");

    // drain() passes on only the current run.
    let third = h.set_params(preset("fig16", &[]));
    let mut seen = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(10);
    while seen.is_empty() && Instant::now() < deadline {
        h.drain(Duration::from_millis(10), 1000, |u| seen.push(u));
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(!seen.is_empty());
    assert!(seen.iter().all(|u| u.run() == third));
    let SimUpdate::Started { info, .. } = &seen[0] else {
        panic!("first is Started")
    };
    assert_eq!(info.scenario.excitation.a_h, 3.0, "run 3 runs the new parameters");
}

#[test]
fn a_consumer_that_falls_behind_loses_samples_but_no_section_point_or_event() {
    let h = SimHandle::spawn(preset("default", &[]), Speed::Max, false, no_waker()).expect("thread starts");
    // Fill the channel and the outbox: read nothing for a while.
    std::thread::sleep(Duration::from_secs(3));
    let got = collect(&h, Duration::from_secs(5), |_| false);
    let bs = batches(&got, RunId(1));
    let ks: Vec<u64> = bs.iter().flat_map(|b| b.section.iter().map(|p| p.k)).collect();
    assert!(!ks.is_empty());
    for (i, k) in ks.iter().enumerate() {
        assert_eq!(*k, i as u64, "no section point dropped");
    }
    // Every sample index from the first to the last is either delivered or
    // counted as dropped.
    let delivered: usize = bs.iter().map(|b| b.samples.len()).sum();
    let dropped: u64 = bs.iter().map(|b| b.dropped_samples).sum();
    let first = bs.iter().find_map(|b| b.samples.first()).expect("samples").tau;
    let last = bs.iter().rev().find_map(|b| b.samples.last()).expect("samples").tau;
    let span = (sample_index(last) - sample_index(first) + 1) as u64;
    assert_eq!(
        delivered as u64 + dropped,
        span,
        "samples delivered + dropped = samples produced"
    );
    assert!(dropped > 0, "3 s unread at full speed overflows the outbox's samples");
    // Backpressure bounds what the thread ran ahead: the last section
    // point's τ is within what the outbox limit allows.
    let last_tau = bs.iter().rev().find_map(|b| b.section.last()).expect("section").tau;
    assert!(last_tau.is_finite());
}

#[test]
fn pause_stops_output_and_step_advances_by_exactly_the_step() {
    let h = SimHandle::spawn(preset("default", &[]), Speed::RealTime(1.0), true, no_waker()).expect("thread starts");
    let got = collect(&h, Duration::from_millis(600), |_| false);
    assert!(matches!(got.first(), Some(SimUpdate::Started { .. })));
    assert!(
        got.iter()
            .any(|u| matches!(u, SimUpdate::Paused { paused: true, tau, .. } if *tau == 0.0))
    );
    // A paused start shows its first frame (the block where it starts,
    // "what will it do?"), and nothing after it.
    let first = batches(&got, RunId(1));
    assert_eq!(first.len(), 1, "a paused start sends the first frame only");
    assert_eq!(first[0].samples.len(), 1);
    assert_eq!(first[0].samples[0].tau, 0.0);
    assert_eq!(first[0].tau, 0.0);
    assert_eq!(
        (first[0].samples[0].theta, first[0].samples[0].theta_dot),
        (0.0, 0.0),
        "the default scene starts at rest, upright"
    );

    h.step(1.0);
    let got = collect(&h, Duration::from_secs(5), |u| {
        u.iter().any(|x| matches!(x, SimUpdate::Paused { .. }))
    });
    let bs = batches(&got, RunId(1));
    let last = bs
        .iter()
        .rev()
        .find_map(|b| b.samples.last())
        .expect("a step releases samples");
    assert!((last.tau - 1.0).abs() < 1e-9, "last sample at τ = {}", last.tau);
    assert!(
        got.iter()
            .any(|u| matches!(u, SimUpdate::Paused { paused: true, tau, .. } if (*tau - 1.0).abs() < 1e-12))
    );
    let after = collect(&h, Duration::from_millis(400), |_| false);
    assert!(batches(&after, RunId(1)).is_empty(), "still paused after the step");

    h.resume();
    let got = collect(&h, Duration::from_secs(5), |u| !batches(u, RunId(1)).is_empty());
    assert!(!batches(&got, RunId(1)).is_empty(), "resumed");
}

#[test]
fn real_time_playback_advances_p_tau_per_second() {
    let cfg = preset("default", &[]);
    let p = cfg.geometry().p;
    let h = SimHandle::spawn(cfg, Speed::RealTime(2.0), false, no_waker()).expect("thread starts");
    let start = Instant::now();
    let got = collect(&h, Duration::from_millis(1500), |_| false);
    let wall = start.elapsed().as_secs_f64();
    let tau = batches(&got, RunId(1)).iter().map(|b| b.tau).fold(0.0, f64::max);
    let expected = 2.0 * p * wall;
    // The playhead never runs ahead of the clock; on a loaded machine it may
    // lag (it waits for the integrator), but not by half.
    assert!(tau <= expected * 1.05 + 0.05, "τ {tau} ran ahead of {expected}");
    assert!(tau >= 0.5 * expected, "τ {tau} far behind {expected}");
}

#[test]
fn a_perturbed_reset_continues_from_the_shown_state_with_theta_plus_eps() {
    let (mut h, last) = paused_after(5.0);
    let eps = 1e-3;
    let run = h.reset_perturbed(eps);
    h.step(0.1);
    let got = collect(&h, Duration::from_secs(5), |u| !batches(u, run).is_empty());
    let info = started(&got, run);
    assert_eq!(info.tau0, last.tau, "continues from the shown τ");
    let first = batches(&got, run)[0].samples[0];
    assert_eq!(first.tau, last.tau);
    assert_eq!(first.theta, last.theta + eps);
}

#[test]
fn new_parameters_from_the_current_state_continue_at_the_shown_tau_and_state() {
    let (mut h, last) = paused_after(5.0);
    let run = h.set_params_from(preset("default", &["excitation.a_v=2.0"]), StartFrom::Current);
    h.step(0.1);
    let got = collect(&h, Duration::from_secs(5), |u| !batches(u, run).is_empty());
    let info = started(&got, run);
    assert_eq!(info.tau0, last.tau, "τ runs on from the shown τ");
    assert_eq!(info.scenario.excitation.a_v, 2.0);
    let first = batches(&got, run)[0].samples[0];
    assert_eq!(
        (first.tau, first.theta, first.theta_dot),
        (last.tau, last.theta, last.theta_dot)
    );

    // From the initial state: τ = 0 again.
    let run = h.set_params_from(preset("default", &["excitation.a_v=1.5"]), StartFrom::Initial);
    h.step(0.1);
    let got = collect(&h, Duration::from_secs(5), |u| !batches(u, run).is_empty());
    assert_eq!(batches(&got, run)[0].samples[0].tau, 0.0);
}

#[test]
fn a_section_phase_puts_the_points_at_that_forcing_phase_and_the_motion_goes_on() {
    let mut h = SimHandle::spawn(preset("default", &[]), Speed::Max, true, no_waker()).expect("thread starts");
    h.step(3.0);
    let _ = collect(&h, Duration::from_secs(5), |u| {
        u.iter()
            .any(|x| matches!(x, SimUpdate::Paused { tau, .. } if *tau > 0.0))
    });
    let phi = 2.5;
    let run = h.set_section_phase(phi);
    h.step(10.0);
    let got = collect(&h, Duration::from_secs(10), |u| {
        u.iter()
            .any(|x| matches!(x, SimUpdate::Paused { run: r, tau, .. } if *r == run && *tau > 12.0))
    });
    let info = started(&got, run);
    assert_eq!(info.section_phase, phi);
    assert!(info.tau0 > 2.5, "the motion goes on from τ = {}", info.tau0);
    let omega = info.scenario.excitation.omega_h;
    let points: Vec<_> = batches(&got, run).iter().flat_map(|b| b.section.clone()).collect();
    assert!(points.len() >= 12, "{} points in 10 τ at Ω_h = 8", points.len());
    for p in &points {
        let miss = omega * p.tau - phi - std::f64::consts::TAU * p.k as f64;
        assert!(miss.abs() <= 1e-12, "Ω τ_k − φ − 2πk = {miss:e} at k = {}", p.k);
    }
}

#[test]
fn ghosts_stream_their_latest_states() {
    let h = SimHandle::spawn(preset("default", &[]), Speed::Max, false, no_waker()).expect("thread starts");
    h.set_ghosts(5, 1e-3);
    let got = collect(&h, Duration::from_secs(10), |u| {
        batches(u, RunId(1)).iter().filter(|b| b.ghosts.len() == 5).count() > 3
    });
    let with = batches(&got, RunId(1))
        .into_iter()
        .filter(|b| b.ghosts.len() == 5)
        .count();
    assert!(with > 3, "batches carry 5 ghost states");
}

#[test]
fn a_run_that_tumbles_ends_with_an_explicit_finished_message() {
    // A hard shake of a slender block without sliding tumbles it.
    let cfg = preset(
        "default",
        &[
            "friction.static=\"inf\"",
            "excitation.a_h=6",
            "excitation.a_v=0",
            "excitation.omega_h=2",
        ],
    );
    let h = SimHandle::spawn(cfg, Speed::Max, false, no_waker()).expect("thread starts");
    let got = collect(&h, Duration::from_secs(20), |u| {
        u.iter().any(|x| matches!(x, SimUpdate::Finished { .. }))
    });
    let end = got
        .iter()
        .find_map(|u| match u {
            SimUpdate::Finished { end, .. } => Some(end.clone()),
            _ => None,
        })
        .expect("the run finished");
    assert!(matches!(end, RunEnd::Terminal { .. }), "{end:?}");
    // Finished is the last message of the run.
    assert!(matches!(got.last(), Some(SimUpdate::Finished { .. })));
}

struct SetOnDrop(Arc<AtomicBool>);
impl Drop for SetOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::SeqCst);
    }
}

#[test]
fn dropping_the_handle_shuts_the_thread_down_and_joins_it() {
    for speed in [Speed::Max, Speed::RealTime(1.0)] {
        let gone = Arc::new(AtomicBool::new(false));
        let wakes = Arc::new(AtomicUsize::new(0));
        let guard = SetOnDrop(gone.clone());
        let w = wakes.clone();
        // The waker is owned by the thread: it is dropped when the thread ends.
        let waker = Box::new(move || {
            let _ = &guard;
            w.fetch_add(1, Ordering::SeqCst);
        });
        let h = SimHandle::spawn(preset("default", &[]), speed, false, waker).expect("thread starts");
        std::thread::sleep(Duration::from_millis(300));
        assert!(h.is_alive());
        assert!(wakes.load(Ordering::SeqCst) > 0, "the waker is called after sends");
        let start = Instant::now();
        drop(h);
        assert!(gone.load(Ordering::SeqCst), "thread ended before drop returned");
        assert!(start.elapsed() < Duration::from_secs(2), "shutdown is prompt");
    }
}

/// The live app ends a rocking frame's scene as `--batch` does: the lone
/// columns overturn at the batch run's tumble time, bit for bit, and the
/// frame under its heavy beam comes to rest with the batch run's peak.
#[test]
fn a_frame_ends_live_as_its_batch_run_ends() {
    for (sets, tumbles) in [(&["frame.beam_mass_ratio=0"][..], true), (&[][..], false)] {
        let cfg = preset("rocking-frame", sets);
        let batch = simulate(cfg.model().expect("model"), &cfg.initial, &cfg.run_options()).expect("batch run");
        let h = SimHandle::spawn(cfg, Speed::Max, false, no_waker()).expect("thread starts");
        let got = collect(&h, Duration::from_secs(60), |u| {
            u.iter().any(|x| matches!(x, SimUpdate::Finished { .. }))
        });
        let end = got
            .iter()
            .find_map(|u| match u {
                SimUpdate::Finished { end, .. } => Some(end.clone()),
                _ => None,
            })
            .expect("the run finished");
        match end {
            RunEnd::Terminal { tau, .. } => {
                assert!(tumbles, "{end:?}");
                assert_eq!(Some(tau), batch.tumble_tau);
            }
            RunEnd::Rest { tau, max_abs_theta, .. } => {
                assert!(!tumbles, "{end:?}");
                // The live run stops on the chunk grid after coming to rest
                // where the batch run did, with the same peak.
                let last_rest = batch.tallies.last_rest_tau.expect("the batch run rests");
                assert!(tau >= last_rest, "stopped at τ {tau} before the rest at {last_rest}");
                assert_eq!(max_abs_theta, batch.max_abs_theta);
            }
            other => panic!("{other:?}"),
        }
    }
}
