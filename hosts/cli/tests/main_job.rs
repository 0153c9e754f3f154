//! The main job, `cargo umbra` with no arguments, as a newcomer first
//! runs it: in a fresh folder, what it prints fits a screen — at most 40
//! lines of at most 100 columns — and names each folder it wrote, whose
//! files hold every figure.

mod common;

use std::process::Command;

/// The screen the main job's output must fit.
const LINES: usize = 40;
const COLUMNS: usize = 100;

#[test]
fn the_main_job_fits_a_screen_and_says_where_its_files_went() {
    let dir = common::dir("main-job");
    std::fs::create_dir_all(&*dir).expect("a scratch folder");
    let out = Command::new(env!("CARGO_BIN_EXE_umbra"))
        .current_dir(&*dir)
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("the command runs");
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stderr}");
    let lines: Vec<&str> = stdout.lines().chain(stderr.lines()).collect();
    println!("{stdout}{stderr}");
    assert!(lines.len() <= LINES, "{} lines", lines.len());
    let wide: Vec<&&str> = lines.iter().filter(|l| l.chars().count() > COLUMNS).collect();
    assert!(wide.is_empty(), "wider than {COLUMNS} columns: {wide:?}");
    for folder in ["out/depth", "out/render", "out/study"] {
        assert!(stdout.contains(folder), "{folder} is not named");
        assert!(dir.join(folder).join("manifest.json").is_file(), "{folder} is not finished");
    }
    // The headline of the study: each scene of the quick sweep, its fastest
    // design within the loosest budget.
    for scene in ["table-and-sphere", "weiskopf-l", "reeves-sphere"] {
        assert!(stdout.lines().any(|l| l.starts_with(&format!("{scene}: the fastest with"))), "{scene}");
    }
}
