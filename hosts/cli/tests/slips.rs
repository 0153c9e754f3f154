//! The commonest slips get an error that suggests the fix: a name a letter
//! off gets what it was nearly, a value written as the help capitalises
//! it is read, a file of another kind is named for what it is with what
//! reads it, and each error is said once.

mod common;

use common::umbra;

/// A file the repository ships, by its path from the workspace root.
fn shipped(path: &str) -> String {
    format!("{}/../../{path}", env!("CARGO_MANIFEST_DIR"))
}

/// The command's error line, asserting it failed with one.
fn error(args: &[&str]) -> String {
    let out = umbra(args);
    assert!(!out.status.success(), "{args:?} succeeded");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(stderr.lines().count() <= 3, "{args:?}: {stderr}");
    stderr
}

#[test]
fn a_name_a_letter_off_is_answered_with_what_it_was_nearly() {
    assert!(error(&["render", "tabel-and-sphere"]).contains("did you mean `table-and-sphere`?"));
    let key = error(&["cost", "--set", "dram.bandwith=1GB/s"]);
    assert!(key.contains("did you mean `dram.bandwidth`?"), "{key}");
    assert!(key.len() < 300, "the key's error lists every key: {} bytes", key.len());
    assert!(error(&["render", "--algo", "secnod"]).contains("did you mean `second`?"));
    assert!(error(&["render", "--filter", "bilinaer"]).contains("did you mean bilinear?"));
    assert!(error(&["render", "--filter", "jiter8"]).contains("did you mean jitter?"));
    assert!(error(&["render", "--filter", "jitter8,res-factr=1"]).contains("did you mean res-factor?"));
    // Nothing near: the names, not a guess.
    let far = error(&["render", "teapot"]);
    assert!(!far.contains("did you mean") && far.contains("table-and-sphere"), "{far}");
}

#[test]
fn values_are_read_as_the_help_writes_them() {
    let dir = common::dir("slips-case");
    let out = dir.join("render");
    let args = ["render", "--algo", "Second", "--filter", "Point", "--depth", "D16", "--map", "64"];
    let small = ["--width", "32", "--height", "18", "--reference-rays", "1", "--out", out.to_str().expect("utf-8")];
    let run = umbra(&[&args[..], &small[..]].concat());
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let metrics = std::fs::read_to_string(out.join("metrics.json")).expect("metrics");
    // Written in the one spelling.
    assert!(metrics.contains("\"second\"") && metrics.contains("\"point\""), "{metrics}");
}

#[test]
fn a_file_of_another_kind_is_named_for_what_it_is() {
    let obj = error(&["render", &shipped("examples/torus.obj")]);
    assert!(obj.contains("an OBJ mesh (not a scene file)") && obj.contains("umbra depth --mesh"), "{obj}");
    let dir = common::dir("slips-kind");
    let out = dir.to_str().expect("utf-8");
    let scene = error(&["depth", "--mesh", &shipped("examples/scene.toml"), "--out", out]);
    assert!(scene.contains("a scene file (not an OBJ mesh)") && scene.contains("umbra render"), "{scene}");
}

#[test]
fn an_error_is_said_once() {
    let e = error(&["render", "--out", "/proc/umbra-no-such/x"]);
    let os = "No such file or directory";
    assert_eq!(e.matches(os).count(), 1, "{e}");
}
