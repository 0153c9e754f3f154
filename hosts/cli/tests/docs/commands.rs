//! Every documented `umbra` command runs, in order, page by page, and
//! loses no file; the main job fits a screen.

use std::path::{Path, PathBuf};

use super::{common, pages, root, shell_lines};

/// `args` (after `umbra`) at small sizes: renders and maps at 64×36 and
/// 64², one reference ray; everything else as written.
pub(super) fn small(mut args: Vec<String>) -> Vec<String> {
    let set = |args: &mut Vec<String>, flag: &str, value: &str| {
        let mut k = 0;
        let mut found = false;
        while k < args.len() {
            if args[k] == flag && k + 1 < args.len() {
                if found {
                    args.drain(k..k + 2);
                    continue;
                }
                args[k + 1] = value.to_owned();
                found = true;
            }
            k += 1;
        }
        if !found {
            args.extend([flag.to_owned(), value.to_owned()]);
        }
    };
    let command =
        ["render", "cost", "trace", "depth", "study", "plan"].into_iter().find(|c| args.iter().any(|a| a == c));
    match command {
        Some("render" | "cost" | "trace") => {
            for (flag, value) in [("--width", "64"), ("--height", "36"), ("--map", "64"), ("--reference-rays", "1")] {
                set(&mut args, flag, value);
            }
        }
        Some("depth") => set(&mut args, "--map", "64"),
        Some("study" | "plan") => {
            for (flag, value) in [("--image", "64x36"), ("--maps", "64")] {
                set(&mut args, flag, value);
            }
            if command == Some("study") {
                set(&mut args, "--reference-rays", "1");
            }
        }
        _ => {}
    }
    args
}

/// Every file under `dir`, following the links to the shipped folders.
fn files(dir: &Path) -> std::collections::BTreeSet<PathBuf> {
    let mut out = std::collections::BTreeSet::new();
    let mut todo = vec![dir.to_owned()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let path = e.path();
            if path.is_dir() {
                todo.push(path)
            } else {
                out.insert(path);
            }
        }
    }
    out
}

/// The files the manifests among `files` list: what Umbra wrote, which a
/// later run of the same kind into the same folder may replace.
fn written_by_umbra(files: &std::collections::BTreeSet<PathBuf>) -> std::collections::BTreeSet<PathBuf> {
    let mut out = std::collections::BTreeSet::new();
    for manifest in files.iter().filter(|f| f.file_name().is_some_and(|n| n == "manifest.json")) {
        let folder = manifest.parent().expect("a folder");
        let record: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(manifest).expect("a manifest")).expect("JSON");
        for f in record["files"].as_array().into_iter().flatten() {
            out.insert(folder.join(f["path"].as_str().expect("a path")));
        }
    }
    out
}

/// The screen the main command's output must fit.
const SCREEN: (usize, usize) = (40, 100);

/// Every line of the README's and the guide's shell blocks that runs
/// `cargo umbra` (alone, or after a `cp` of a shipped file) runs, in
/// order, page by page, in a scratch folder holding the repository's
/// shipped files, at small sizes ([`small`]); each must succeed and lose
/// no file (a file gone after it must be one a manifest listed: results a
/// run of the same kind replaced). The bare `cargo umbra`, the main job,
/// runs as written, and its output fits a screen (40 lines of 100
/// columns) naming each folder it wrote. Lines of other tools (cargo's
/// own commands, Slurm, pip, QEMU) are run by CI's own stages.
#[test]
fn every_documented_command_runs() {
    let mut ran = 0;
    let mut main_job = false;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        let name = page.file_stem().and_then(|s| s.to_str()).unwrap_or("page").to_owned();
        let scratch = common::dir(&format!("docs-run-{name}"));
        std::fs::create_dir_all(&scratch).expect("scratch");
        for shipped in ["examples", "arch", "scenes", "sweeps", "data"] {
            std::os::unix::fs::symlink(root().join(shipped), scratch.join(shipped)).expect("a link");
        }
        for t in shell_lines(&text).into_iter().filter(|t| t.contains("cargo umbra") || t.starts_with("cp ")) {
            for part in t.split("&&").map(str::trim) {
                let words = shlex::split(part).unwrap_or_else(|| panic!("{}: `{part}` does not parse", page.display()));
                let before = files(&scratch);
                let replaceable = written_by_umbra(&before);
                match words.first().map(String::as_str) {
                    Some("cp") => {
                        std::fs::copy(scratch.join(&words[1]), scratch.join(&words[2])).expect("cp");
                    }
                    Some("cargo") => {
                        // The main job as written; every other command small.
                        let bare = words.len() == 2;
                        let args = if bare { Vec::new() } else { small(words[2..].to_vec()) };
                        let o = std::process::Command::new(env!("CARGO_BIN_EXE_umbra"))
                            .args(&args)
                            .current_dir(&scratch)
                            .env("RUST_BACKTRACE", "0")
                            .output()
                            .expect("umbra runs");
                        assert!(
                            o.status.success(),
                            "{}: `{part}` (run as `umbra {}`) failed: {}",
                            page.display(),
                            args.join(" "),
                            String::from_utf8_lossy(&o.stderr)
                        );
                        if bare {
                            fits_a_screen(&o, &scratch);
                            main_job = true;
                        }
                        ran += 1;
                    }
                    _ => panic!("{}: `{part}`: only `cp` and `cargo umbra` are run here", page.display()),
                }
                let after = files(&scratch);
                let lost: Vec<&PathBuf> = before.difference(&after).filter(|f| !replaceable.contains(*f)).collect();
                assert!(lost.is_empty(), "{}: `{part}` lost {lost:?}", page.display());
            }
        }
        let _ = std::fs::remove_dir_all(&scratch);
    }
    assert!(ran >= 60, "only {ran} documented commands ran");
    assert!(main_job, "no page shows the main job, `cargo umbra`");
}

/// The main job's output `o`, run in `dir`, fits [`SCREEN`] and names
/// each folder it wrote, each finished, and the study's headline: each
/// scene of the quick sweep with its fastest design.
fn fits_a_screen(o: &std::process::Output, dir: &Path) {
    let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    let lines: Vec<&str> = stdout.lines().chain(stderr.lines()).collect();
    assert!(lines.len() <= SCREEN.0, "the main job printed {} lines:\n{stdout}{stderr}", lines.len());
    let wide: Vec<&&str> = lines.iter().filter(|l| l.chars().count() > SCREEN.1).collect();
    assert!(wide.is_empty(), "wider than {} columns: {wide:?}", SCREEN.1);
    for folder in ["out/depth", "out/render", "out/study"] {
        assert!(stdout.contains(folder), "{folder} is not named");
        assert!(dir.join(folder).join("manifest.json").is_file(), "{folder} is not finished");
    }
    for scene in ["table-and-sphere", "weiskopf-l", "reeves-sphere"] {
        assert!(stdout.lines().any(|l| l.starts_with(&format!("{scene}: the fastest with"))), "{scene}");
    }
}
