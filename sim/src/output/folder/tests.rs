//! Output folders: files whole or absent, a manifest written last that
//! matches them, nothing stale beside new files, nothing touched that Umbra
//! did not write, nothing written outside.

use std::path::Path;

use super::{LOCK, MANIFEST, OutputFolder, PENDING, RunManifest, sha256, write_all_synced};

/// A fresh directory of this test, kept for the test to remove.
fn scratch(name: &str) -> std::path::PathBuf {
    tempfile::Builder::new().prefix(&format!("umbra-{name}-")).tempdir().expect("temp dir").keep()
}

/// The folder's entries, but for its lock.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into())
        .filter(|n| n != LOCK)
        .collect();
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

/// A manifest (ours, forged or stale) that lists a file reached through a
/// symbolic link, or a file whose contents are no longer what a run
/// wrote, gets nothing deleted: the link's target outside the folder and
/// the user's own file of a listed name survive the next run.
#[cfg(unix)]
#[test]
fn a_listed_file_is_removed_only_inside_and_only_if_ours() {
    let base = scratch("folder-trust");
    let (dir, elsewhere) = (base.join("out"), base.join("elsewhere"));
    std::fs::create_dir_all(&elsewhere).expect("dir");
    std::fs::write(elsewhere.join("precious.txt"), "x").expect("a file outside");
    let mut first = OutputFolder::create(&dir).expect("folder");
    first.write("notes.md", b"x").expect("written");
    first.write("old.png", b"x").expect("written");
    first.finish(None).expect("finished");
    // The user replaces notes.md with their own, and links sub/ elsewhere;
    // a forged record lists sub/precious.txt with the hash of its contents.
    std::fs::write(dir.join("notes.md"), "my own notes").expect("a user's file");
    std::os::unix::fs::symlink(&elsewhere, dir.join("sub")).expect("a link");
    let text = std::fs::read_to_string(dir.join(MANIFEST)).expect("manifest");
    std::fs::write(dir.join(MANIFEST), text.replace("\"old.png\"", "\"sub/precious.txt\"")).expect("forged");
    let mut pending = format!(r#"{{"files":[{{"path":"old.png","bytes":1,"sha256":"{}"}}]}}"#, sha256(b"x"));
    std::fs::write(dir.join(PENDING), &pending).expect("a pending record");
    OutputFolder::create(&dir).and_then(|f| f.finish(None)).expect("a run");
    assert!(elsewhere.join("precious.txt").exists(), "a file through a link was deleted");
    assert_eq!(std::fs::read_to_string(dir.join("notes.md")).ok().as_deref(), Some("my own notes"));
    assert!(!dir.join("old.png").exists(), "a file of ours, as written, is removed");
    // Nor does a run write through the link.
    let mut f = OutputFolder::create(&dir).expect("folder");
    let err = f.write("sub/new.txt", b"x").expect_err("refused");
    assert!(err.to_string().contains("symbolic link"), "{err}");
    assert!(!elsewhere.join("new.txt").exists());
    pending.clear();
    let _ = std::fs::remove_dir_all(&base);
}

/// One run a folder: a second run into a folder in use fails at once,
/// naming it, and runs again once the first is done; a dead run's
/// temporaries are removed by the next run.
#[test]
fn a_folder_in_use_is_refused_and_dead_temporaries_removed() {
    let base = scratch("folder-lock");
    let dir = base.join("out");
    let first = OutputFolder::create(&dir).expect("folder");
    let err = OutputFolder::create(&dir).expect_err("in use");
    assert!(err.to_string().contains("in use") && err.to_string().contains("out"), "{err}");
    drop(first);
    std::fs::create_dir_all(dir.join("sub")).expect("dir");
    for t in [".umbra-ab12.tmp", "sub/.umbra-cd34.tmp"] {
        std::fs::write(dir.join(t), "half a file").expect("a dead run's temporary");
    }
    std::fs::write(dir.join("mine.tmp"), "a user's").expect("a user's file");
    let f = OutputFolder::create(&dir).expect("free again");
    assert!(!dir.join(".umbra-ab12.tmp").exists() && !dir.join("sub/.umbra-cd34.tmp").exists());
    assert!(dir.join("mine.tmp").exists());
    f.finish(None).expect("finished");
    let _ = std::fs::remove_dir_all(&base);
}

/// Files get the permissions the umask gives a new file, as `touch` makes
/// it, not a private 0600; a second run keeps them.
#[cfg(unix)]
#[test]
fn files_are_as_readable_as_the_umask_allows() {
    use std::os::unix::fs::PermissionsExt;
    let base = scratch("folder-mode");
    let dir = base.join("out");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(base.join("touched"), "").expect("touch");
    let touched = std::fs::metadata(base.join("touched")).expect("meta").permissions().mode() & 0o777;
    assert_ne!(touched, 0o600, "this test needs a umask that lets others read (022 makes 0644)");
    for _ in 0..2 {
        let mut f = OutputFolder::create(&dir).expect("folder");
        f.write("a.txt", b"x").expect("written");
        f.finish(None).expect("finished");
        for n in ["a.txt", MANIFEST] {
            let mode = std::fs::metadata(dir.join(n)).expect("meta").permissions().mode() & 0o777;
            assert_eq!(mode, touched, "{n}");
        }
    }
    let _ = std::fs::remove_dir_all(&base);
}

/// A run refused after it opened its folder but before it wrote a file (an
/// empty map, a bad scene found late) leaves the folder as it found it: a
/// folder it made is gone, a finished run's folder is still complete, a
/// user's own folder keeps its files and gains none. A run that wrote a
/// file still leaves its pending record.
#[test]
fn a_run_that_wrote_nothing_leaves_the_folder_as_it_was() {
    let base = scratch("folder-untouched");
    let made = base.join("made");
    drop(OutputFolder::create(&made).expect("folder"));
    assert!(!made.exists(), "the folder it made is removed");
    let done = base.join("done");
    let mut first = OutputFolder::create(&done).expect("folder");
    first.write("summary.md", b"whole").expect("written");
    first.finish(None).expect("finished");
    let record = std::fs::read(done.join(MANIFEST)).expect("a manifest");
    drop(OutputFolder::create(&done).expect("folder"));
    RunManifest::verify(&done, u64::MAX).expect("still complete");
    assert_eq!(std::fs::read(done.join(MANIFEST)).expect("a manifest"), record, "the same record");
    assert_eq!(names(&done), vec!["manifest.json", "summary.md"]);
    let mine = base.join("mine");
    std::fs::create_dir_all(&mine).expect("dir");
    std::fs::write(mine.join("notes.txt"), "mine").expect("a user's file");
    drop(OutputFolder::create(&mine).expect("folder"));
    assert_eq!(names(&mine), vec!["notes.txt"]);
    let mut partial = OutputFolder::create(&done).expect("folder");
    partial.write("rows.jsonl", b"1").expect("written");
    drop(partial);
    assert!(done.join(PENDING).exists() && !done.join(MANIFEST).exists(), "a partial run is visible");
    let _ = std::fs::remove_dir_all(&base);
}
