//! Reference data that lives outside the repository (`../shared/data` beside a checkout).
//!
//! Tests that compare with published data read it from there. A user's checkout may not
//! have it, and such a test then skips its comparison; CI has it, and sets
//! `SALTUS_REQUIRE_DATA=1` so that a moved or renamed file fails the test instead of
//! silently skipping the comparison it exists for.

use std::path::Path;

/// Name of the environment variable that turns a missing reference file into a failure.
pub const REQUIRE_DATA: &str = "SALTUS_REQUIRE_DATA";

/// Whether missing reference data must fail (`SALTUS_REQUIRE_DATA` set to anything but
/// empty or `0`).
pub fn required() -> bool {
    std::env::var(REQUIRE_DATA).is_ok_and(|v| !v.is_empty() && v != "0")
}

/// Account for reference data at `path` that could not be read: panics (failing the test)
/// when [`required`], else tells on stderr that `what` is skipped.
pub fn missing(path: &Path, what: &str) {
    if required() {
        panic!("{REQUIRE_DATA} is set but {} is missing: {what} cannot be checked", path.display());
    }
    eprintln!("skipping {what}: {} not found (set {REQUIRE_DATA}=1 to make this a failure)", path.display());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn required_follows_the_variable() {
        // one test owns the variable: tests of this crate run in threads of one process
        std::env::set_var(REQUIRE_DATA, "1");
        assert!(required());
        let r = std::panic::catch_unwind(|| missing(Path::new("/nonexistent/file.txt"), "a comparison"));
        assert!(r.is_err(), "a missing file must fail when data are required");
        std::env::set_var(REQUIRE_DATA, "0");
        assert!(!required());
        missing(Path::new("/nonexistent/file.txt"), "a comparison");
        std::env::remove_var(REQUIRE_DATA);
        assert!(!required());
    }
}
