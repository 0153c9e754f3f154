//! Ctrl-C (SIGINT) and SIGTERM stop a study cleanly: the command says it
//! is stopping, takes no more configurations, leaves its folder marked
//! unfinished (the pending record, no manifest), removes its lock, exits
//! with 130, and the next run into the folder works.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{dir, umbra};

/// A sweep of 675 configurations at 320×180: many seconds of work, each
/// configuration a few milliseconds.
const LONG: &str = r#"
name = "long"
scenes = ["weiskopf-l"]
images = [[320, 180]]
reference_rays = 2
formats = ["d16", "d24", "f32"]
maps = [64, 128, 256, 512, 1024]
filters = ["point", "bilinear", "box3", "jitter4", "jitter16"]
archs = ["talisman"]
budgets = [1.0]
[[algorithms]]
algo = "first"
bias = [0.0, 0.0002, 0.0005, 0.001, 0.002, 0.005, 0.01]
[[algorithms]]
algo = "second"
[[algorithms]]
algo = "midpoint"
"#;

/// One configuration at 64×36.
const SHORT: &str = r#"
name = "short"
scenes = ["weiskopf-l"]
images = [[64, 36]]
reference_rays = 1
formats = ["d24"]
maps = [64]
filters = ["point"]
archs = ["talisman"]
budgets = [1.0]
[[algorithms]]
algo = "first"
bias = [0.002]
"#;

fn text(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 temp path")
}

/// Wait for `what` up to `limit`, every 20 ms.
fn wait_for(limit: Duration, mut what: impl FnMut() -> bool) -> bool {
    let start = Instant::now();
    while start.elapsed() < limit {
        if what() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    what()
}

/// Start the long study into a fresh folder, send `signal` once it is
/// under way, and check how it stops and that a run after it finishes.
fn stops_cleanly_on(signal: &str) {
    let scratch = dir(&format!("stop-{signal}"));
    std::fs::create_dir_all(&scratch).expect("scratch");
    let (long, short, out) = (scratch.join("long.toml"), scratch.join("short.toml"), scratch.join("out"));
    std::fs::write(&long, LONG).expect("write");
    std::fs::write(&short, SHORT).expect("write");
    let mut child = Command::new(env!("CARGO_BIN_EXE_umbra"))
        .args(["--threads", "2", "study", "--sweep", text(&long), "--out", text(&out)])
        .env("RUST_BACKTRACE", "0")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("umbra starts");
    // Under way: the folder is open and the reference is being built.
    let pending = out.join("manifest.pending.json");
    assert!(wait_for(Duration::from_secs(30), || pending.exists()), "the study never opened its folder");
    std::thread::sleep(Duration::from_millis(500));
    assert!(child.try_wait().expect("wait").is_none(), "the study ended before the signal: make it longer");
    let sent = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().expect("kill");
    assert!(sent.success());
    let ended = wait_for(Duration::from_secs(20), || child.try_wait().expect("wait").is_some());
    if !ended {
        let _ = child.kill();
    }
    let output = child.wait_with_output().expect("output");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(ended, "still running 20 s after SIGINT: {stderr}");
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    let said: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(said.len(), 1, "one line: {stderr}");
    assert!(said[0].starts_with("stopping: ") && said[0].contains("incomplete"), "{stderr}");
    assert!(!out.join(".umbra-lock").exists(), "the lock file is removed");
    assert!(pending.exists(), "the folder stays marked unfinished");
    assert!(!out.join("manifest.json").exists(), "a stopped run writes no manifest");
    // The next run into the folder takes it over and finishes.
    let again = umbra(&["study", "--sweep", text(&short), "--out", text(&out)]);
    assert!(again.status.success(), "{}", String::from_utf8_lossy(&again.stderr));
    assert!(out.join("manifest.json").exists() && !pending.exists());
}

#[test]
fn ctrl_c_stops_a_study_cleanly_and_the_next_run_takes_over() {
    stops_cleanly_on("INT");
}

#[test]
fn sigterm_stops_a_study_as_ctrl_c_does() {
    stops_cleanly_on("TERM");
}
