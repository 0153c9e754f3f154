//! The study's runs, shards, merges and summary, tested beside the
//! internals they need (writing a run, reading its manifest, the render
//! every configuration would have without sharing).

mod merge;
#[path = "../../../../../tests/integration/scratch.rs"]
mod scratch;
mod shared;
mod study;
mod summary;
mod tallies;

/// A scratch folder of this test process, `prefix-<pid>-name`, emptied:
/// removed with what it holds when dropped, however the test ends.
fn scratch_dir(prefix: &str, name: &str) -> scratch::Scratch {
    let d = std::env::temp_dir().join(format!("{prefix}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    scratch::Scratch(d)
}
