//! Times the block's Taylor expansions (order 28, the default scene's
//! forcing): the best of 30 batches, in ns per expansion, which shrugs off
//! the shared machine's time slices better than a median.
//!
//! `cargo run --release --example series_timing`

use std::hint::black_box;
use std::time::Instant;

use rocking::integrate::hybrid::HybridSystem;
use rocking::model::system::N;
use rocking::model::{BlockSystem, Mode, Sign};

fn main() {
    let cfg = rocking::io::config::load(Some("default"), None, &[]).expect("default preset");
    let sys = BlockSystem::new(cfg.model().expect("model"));
    let order: usize = std::env::var("ORDER")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| rocking::integrate::taylor::order_for(1e-10));
    let y = [0.05, -0.2, 0.0, 0.01, 0.0, 0.0];
    for (name, mode) in [
        ("rock", Mode::Rock { pivot: Sign::Pos }),
        (
            "slide-rock",
            Mode::SlideRock {
                pivot: Sign::Pos,
                slip: Sign::Neg,
            },
        ),
    ] {
        // `MODE=rock` or `MODE=slide-rock` times one of them only.
        if std::env::var("MODE").is_ok_and(|m| m != name) {
            continue;
        }
        let mut c = vec![[0.0; N]; order + 1];
        let mut best = f64::INFINITY;
        let batch = 20_000;
        let mut t = 0.0;
        for _ in 0..30 {
            let start = Instant::now();
            for _ in 0..batch {
                t += 1e-3;
                assert!(sys.taylor(mode, black_box(t), black_box(&y), order, &mut c));
                black_box(&c);
            }
            best = best.min(start.elapsed().as_secs_f64() / batch as f64);
        }
        println!(
            "{name}: {:.0} ns per expansion (order {order}, best of 30 batches)",
            best * 1e9
        );
    }
}
