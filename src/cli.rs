//! The `saltus` command line as a library function, so that a researcher's own binary can
//! link their closure crate and run the same program:
//!
//! ```no_run
//! fn main() -> std::process::ExitCode {
//!     // my_closures::link(); // keep the crate's registrations in the binary
//!     saltus::cli::main()
//! }
//! ```
//!
//! The program itself is `src/main.rs`, compiled here as a module as well as the `saltus`
//! binary (which keeps `main.rs` the one place where the commands are defined).

#[path = "main.rs"]
mod program;

/// Parse the process arguments, run the command, return its exit code: 0 on success, 2 on
/// bad input, 1 when `closure check` finds a failing check, the run codes of
/// [`crate::runner`] when a run stops early.
pub fn main() -> std::process::ExitCode {
    program::main()
}

/// [`main`] on `args` (the program name first) rather than the process arguments: the
/// exit code. `python -m saltus` runs the program so, in the Python process where the
/// scene's `[python] modules` registered their closures.
pub fn main_from(args: Vec<std::ffi::OsString>) -> u8 {
    program::main_from(args)
}
