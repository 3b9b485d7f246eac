//! `cargo bench --bench stacks`: a stack of blocks' solver time against
//! the targets of docs/performance.md ("Stacks of blocks"): a two-block
//! stack under El Centro 1940 to rest, the harmonic `stack-patterns`
//! scene's τ per second, and a 200-size spectrum of the tombstone under
//! Kobe 1995.

use std::hint::black_box;

use rocking::analysis::engineering::Drive;
use rocking::analysis::engineering::rocking_spectrum::{SizeAxis, SizeRange, SpectrumSpec, rocking_spectrum};
use rocking::analysis::engineering::stack_response::stack_size;
use rocking::sim::Scenario;
use rocking::sim::stack_run::simulate_stack;

fn main() {
    divan::main();
}

/// A shipped preset with `sets`, as `--preset NAME --set …` reads it.
fn preset(name: &str, sets: &[&str]) -> Scenario {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    rocking::io::config::load(Some(name), None, &sets).expect("shipped preset")
}

fn run(s: &Scenario) {
    let geo = s.stack_geometry().expect("a stack");
    black_box(
        simulate_stack(
            geo,
            s.excitation().expect("excitation"),
            s.run.zeno_eps,
            &s.run_options(),
        )
        .expect("runs"),
    );
}

/// `statue-on-pedestal` (two blocks, El Centro 1940) up to t = 18.7 s,
/// where it comes to rest: 183 impacts, no history. Target: < 2 ms.
#[divan::bench(sample_count = 40)]
fn statue_on_pedestal_to_rest(bencher: divan::Bencher) {
    let s = preset("statue-on-pedestal", &["run.output_dt=0", "run.t_end=\"18.7 s\""]);
    bencher.bench(|| run(&s));
}

/// `stack-patterns` (two blocks, harmonic) over τ 0–200, no history:
/// τ per second is 200 over this time. Target: ≥ 30,000 τ/s (≤ 6.7 ms).
#[divan::bench(sample_count = 20)]
fn stack_patterns_200_tau(bencher: divan::Bencher) {
    let s = preset("stack-patterns", &["run.output_dt=0", "run.tau_end=200"]);
    bencher.bench(|| run(&s));
}

/// 200 sizes (R = 0.3–3 m) of the three-stone tombstone under Kobe 1995,
/// as `rocking spectrum --preset tombstone --record kobe-1995.dat --unit
/// m/s2 --from 0.3 --to 3 --count 200`, on rayon's pool. Target: < 2 s.
#[divan::bench(sample_count = 10)]
fn tombstone_spectrum_200_sizes(bencher: divan::Bencher) {
    let base = preset("tombstone", &[]);
    let record = base.excitation.record_h.clone().expect("the preset's record");
    let drive = Drive::Record(record);
    let own = stack_size(base.stack.as_ref().expect("a stack"));
    let spec = SpectrumSpec {
        base: &base,
        drive: &drive,
        scale: 1.0,
        sizes: SizeRange::new(SizeAxis::HalfDiagonal, 0.3, 3.0, 200).expect("sizes"),
        b_over_h: vec![own.width_m / own.height_m],
        overturn: None,
    };
    bencher.bench(|| black_box(rocking_spectrum(&spec, &rocking::analysis::silent).expect("runs")));
}
