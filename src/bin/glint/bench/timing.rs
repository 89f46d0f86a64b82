//! Timing helper shared by the benchmarks.

use std::time::{Duration, Instant};

/// Fastest of `repeat` runs of `f` (at least one), with its last result.
pub fn fastest<T>(repeat: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut best = Duration::MAX;
    let mut result = None;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        let r = f();
        best = best.min(start.elapsed());
        result = Some(r);
    }
    (best, result.expect("at least one run"))
}
