//! Output folders: files whole or absent, a manifest written last that
//! matches them, nothing stale beside new files, nothing touched that Umbra
//! did not write, nothing written outside.

use std::path::Path;

use umbra::sim::io::folder::{MANIFEST, OutputFolder, PENDING, RunManifest, write_all_synced};

use crate::common::scratch;

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).expect("dir").map(|e| e.expect("entry").file_name().to_string_lossy().into()).collect();
    v.sort();
    v
}

/// A full disk is an error, not a short file: `/dev/full` answers every
/// write with ENOSPC, and the writer reports it.
#[test]
fn a_full_disk_is_an_error() {
    let mut full = std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full exists on Linux");
    let err = write_all_synced(&mut full, &[7u8; 100_000]).expect_err("ENOSPC");
    assert_eq!(err.kind(), std::io::ErrorKind::StorageFull, "{err}");
}

#[test]
fn names_outside_the_folder_are_refused() {
    let base = scratch("folder-names");
    let mut f = OutputFolder::create(&base.join("out")).expect("folder");
    for bad in ["../escaped.txt", "/tmp/escaped.txt", "a/../../b", "", "a\\b", MANIFEST, PENDING] {
        assert!(f.write(bad, b"x").is_err(), "`{bad}` accepted");
    }
    f.write("sub/inside.txt", b"x").expect("a sub-folder is inside");
    f.finish(None).expect("finished");
    assert_eq!(names(&base), vec!["out".to_owned()], "nothing beside the folder");
    let _ = std::fs::remove_dir_all(&base);
}

/// A second run removes what the first wrote and it did not, keeps what
/// Umbra never wrote, and ends with a manifest matching the folder.
#[test]
fn no_stale_file_survives_and_foreign_files_are_kept() {
    let base = scratch("folder-stale");
    let dir = base.join("out");
    let mut first = OutputFolder::create(&dir).expect("folder");
    first.write("z1.png", b"one").and_then(|_| first.write("z2.png", b"two")).expect("written");
    first.finish(None).expect("finished");
    std::fs::write(dir.join("notes.txt"), "mine").expect("a user's file");
    std::fs::write(base.join("outside.txt"), "mine too").expect("a file beside the folder");
    let mut second = OutputFolder::create(&dir).expect("folder");
    second.write("z1.png", b"ONE").expect("written");
    let m = second.finish(None).expect("finished");
    assert_eq!(names(&dir), vec!["manifest.json", "notes.txt", "z1.png"]);
    assert_eq!(m.files.len(), 1);
    assert_eq!(RunManifest::verify(&dir, u64::MAX).expect("matches"), m);
    // A manifest that lists a path outside the folder is never acted on.
    let forged = std::fs::read_to_string(dir.join(MANIFEST)).expect("manifest").replace("z1.png", "../outside.txt");
    std::fs::write(dir.join(MANIFEST), forged).expect("forged");
    OutputFolder::create(&dir).and_then(|f| f.finish(None)).expect("a run");
    assert!(base.join("outside.txt").exists(), "a file outside the folder was removed");
    assert!(dir.join("notes.txt").exists(), "a file Umbra did not write was removed");
    let _ = std::fs::remove_dir_all(&base);
}

/// A run that stops before it finishes (killed, or failed) leaves a folder
/// that does not look complete; the next run still knows every file it
/// may have left.
#[test]
fn an_unfinished_run_is_visibly_incomplete() {
    let base = scratch("folder-killed");
    let dir = base.join("out");
    let mut done = OutputFolder::create(&dir).expect("folder");
    done.write("results.jsonl", b"1008 rows").expect("written");
    done.finish(None).expect("finished");
    RunManifest::verify(&dir, u64::MAX).expect("complete");
    let mut killed = OutputFolder::create(&dir).expect("folder");
    killed.write("partial.jsonl", b"336 rows").expect("written");
    drop(killed);
    let err = RunManifest::verify(&dir, u64::MAX).expect_err("incomplete");
    assert!(err.to_string().contains("did not finish"), "{err}");
    assert!(dir.join(PENDING).exists());
    let mut next = OutputFolder::create(&dir).expect("folder");
    next.write("summary.md", b"whole").expect("written");
    next.finish(None).expect("finished");
    assert_eq!(names(&dir), vec!["manifest.json", "summary.md"], "both earlier runs' files are gone");
    // A file changed after the run no longer matches.
    std::fs::write(dir.join("summary.md"), "whol").expect("truncate");
    let err = RunManifest::verify(&dir, u64::MAX).expect_err("changed");
    assert!(err.to_string().contains("summary.md") && err.to_string().contains("differs"), "{err}");
    let _ = std::fs::remove_dir_all(&base);
}
