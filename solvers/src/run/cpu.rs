//! CPU time of the calling thread: a run's cost in CPU seconds (summary.json `cpu_time_s`,
//! a sweep point's line in the manifest).

/// CPU time the calling thread has used (s); `None` where the system does not say.
pub fn thread_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
        // SAFETY: `t` is a valid timespec for the call to fill; the clock id is a constant
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        (rc == 0).then_some(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}
