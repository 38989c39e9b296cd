//! Bake the git revision of a checkout into the manifest of every run.
fn git(args: &[&str]) -> Option<String> {
    std::process::Command::new("git")
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
}

fn main() {
    if let Some(r) = git(&["rev-parse", "--short=12", "HEAD"]) {
        println!("cargo:rustc-env=SALTUS_GIT_REVISION={r}");
    }
    // the git folder as git resolves it: in a worktree `../.git` is a file naming another
    // folder, and a path that does not exist would rebuild this crate every time
    match git(&["rev-parse", "--absolute-git-dir"]) {
        Some(dir) => {
            println!("cargo:rerun-if-changed={dir}/HEAD");
            println!("cargo:rerun-if-changed={dir}/refs");
        }
        None => println!("cargo:rerun-if-changed=build.rs"),
    }
}
