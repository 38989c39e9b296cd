//! Round trip of one cache line between two threads, to tell how closely the host placed
//! the cores a two-thread run gets (`docs/performance.md`): about 100 ns when they share a cache closely, about 380 ns on the 2-vCPU host
//! of those measurements when they do not, and a two-thread DEM run is 40 % slower then.
//!
//!     cargo run --release --example host_pingpong [round trips, default 1000000]
//!
//! Both threads spin, so on an otherwise idle two-core machine each holds its own core.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Most round trips asked for: about ten minutes at the far placement's 380 ns.
const MAX_TRIPS: u64 = 1_000_000_000;

fn main() {
    let n = match std::env::args().nth(1) {
        None => 1_000_000,
        Some(a) => match a.parse::<u64>() {
            Ok(n) if (1..=MAX_TRIPS).contains(&n) => n,
            _ => {
                eprintln!("host_pingpong: round trips `{a}`: a whole number from 1 to {MAX_TRIPS} is allowed");
                std::process::exit(2);
            }
        },
    };
    // two spinning threads on one core would hand the line over once per time slice
    if std::thread::available_parallelism().map_or(1, |c| c.get()) < 2 {
        eprintln!("host_pingpong needs two cores; this machine offers one");
        std::process::exit(2);
    }
    let flag = AtomicU64::new(0);
    let elapsed = std::thread::scope(|s| {
        s.spawn(|| {
            for i in 0..n {
                while flag.load(Ordering::Acquire) != 2 * i + 1 {
                    std::hint::spin_loop();
                }
                flag.store(2 * i + 2, Ordering::Release);
            }
        });
        let start = Instant::now();
        for i in 0..n {
            flag.store(2 * i + 1, Ordering::Release);
            while flag.load(Ordering::Acquire) != 2 * i + 2 {
                std::hint::spin_loop();
            }
        }
        start.elapsed()
    });
    println!("{:.1} ns per round trip ({n} round trips)", elapsed.as_secs_f64() * 1e9 / n as f64);
}
