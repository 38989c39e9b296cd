//! The fixed chunking of every parallel loop of the DEM and of the drag: the work items,
//! and with them every rounding, do not depend on the number of threads.

/// Particles per parallel work item: large enough to amortise scheduling, small enough
/// to balance two cores. Every parallel loop of the DEM cuts its arrays into chunks of
/// this fixed size (never into one chunk per thread), so the work items, and with them
/// every rounding, are the same whatever the number of threads.
pub const CHUNK: usize = 256;

/// The most chunks one task of a parallel loop runs in a row. rayon's splitter hands each
/// thread a run of many chunks that the other cannot steal from once it has started; in a
/// large system such a run outlasts the other thread's work, which then idles long enough
/// to fall asleep and must be woken at the next loop (about once per step from 4660
/// grains on). Single-chunk tasks keep the tail of every loop short. On one thread the
/// splitting would only cost, so it is left to rayon there. The chunks, and with them every
/// rounding, are the same either way.
pub fn chunks_per_task() -> usize {
    if rayon::current_num_threads() > 1 {
        1
    } else {
        usize::MAX
    }
}
