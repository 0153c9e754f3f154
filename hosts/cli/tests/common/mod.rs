//! What every test of the `umbra` command needs: running it, and a fresh
//! folder of this test process.

#![allow(dead_code, reason = "each test binary uses what it needs")]

use std::process::{Command, Output};

/// Run `umbra` with `args`, without backtraces in its errors.
pub fn umbra(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_umbra"))
        .args(args)
        .env("RUST_BACKTRACE", "0")
        .env("RUST_LIB_BACKTRACE", "0")
        .output()
        .expect("the command runs")
}

#[path = "../../../../tests/integration/scratch.rs"]
mod scratch;
pub use scratch::Scratch;

/// A folder of this test process for `name`, absent until the test makes
/// it, and removed when the value is dropped.
pub fn dir(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("umbra-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    Scratch(d)
}
