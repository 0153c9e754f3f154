//! Output folders: files whole or absent, a manifest written last that
//! matches them, nothing stale beside new files, nothing touched that Umbra
//! did not write, nothing written outside.

use std::path::Path;

use super::{Claim, LOCK, MANIFEST, OutputFolder, PENDING, RunKind, RunManifest, sha256, write_all_synced};

/// A render's claim on its folder.
const RENDER: Claim = Claim::new(RunKind::Render);

/// A fresh directory of this test, removed when the value is dropped
/// (when the test ends, however it ends).
fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new().prefix(&format!("umbra-{name}-")).tempdir().expect("temp dir")
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
    let scratch_dir = scratch("folder-names");
    let base = scratch_dir.path().to_owned();
    let mut f = OutputFolder::create(&base.join("out"), RENDER).expect("folder");
    for bad in ["../escaped.txt", "/tmp/escaped.txt", "a/../../b", "", "a\\b", MANIFEST, PENDING] {
        assert!(f.write(bad, b"x").is_err(), "`{bad}` accepted");
    }
    f.write("sub/inside.txt", b"x").expect("a sub-folder is inside");
    f.finish(None).expect("finished");
    assert_eq!(names(&base), vec!["out".to_owned()], "nothing beside the folder");
}

/// A second run removes what the first wrote and it did not, keeps what
/// Umbra never wrote, and ends with a manifest matching the folder.
#[test]
fn no_stale_file_survives_and_foreign_files_are_kept() {
    let scratch_dir = scratch("folder-stale");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    let mut first = OutputFolder::create(&dir, RENDER).expect("folder");
    first.write("z1.png", b"one").and_then(|_| first.write("z2.png", b"two")).expect("written");
    first.finish(None).expect("finished");
    std::fs::write(dir.join("notes.txt"), "mine").expect("a user's file");
    std::fs::write(base.join("outside.txt"), "mine too").expect("a file beside the folder");
    let err = OutputFolder::create(&dir, RENDER).expect_err("a file no run wrote");
    assert!(err.to_string().contains("notes.txt") && err.to_string().contains("--replace"), "{err}");
    let mut second = OutputFolder::create(&dir, RENDER.replacing(true)).expect("folder");
    second.write("z1.png", b"ONE").expect("written");
    let m = second.finish(None).expect("finished");
    assert_eq!(names(&dir), vec!["manifest.json", "notes.txt", "z1.png"]);
    assert_eq!(m.files.len(), 1);
    assert_eq!(RunManifest::verify(&dir, u64::MAX).expect("matches"), m);
    // A manifest that lists a path outside the folder is never acted on.
    let forged = std::fs::read_to_string(dir.join(MANIFEST)).expect("manifest").replace("z1.png", "../outside.txt");
    std::fs::write(dir.join(MANIFEST), forged).expect("forged");
    OutputFolder::create(&dir, RENDER.replacing(true)).and_then(|f| f.finish(None)).expect("a run");
    assert!(base.join("outside.txt").exists(), "a file outside the folder was removed");
    assert!(dir.join("notes.txt").exists(), "a file Umbra did not write was removed");
}

/// A run that stops before it finishes (killed, or failed) leaves a folder
/// that does not look complete; the next run still knows every file it
/// may have left.
#[test]
fn an_unfinished_run_is_visibly_incomplete() {
    let scratch_dir = scratch("folder-killed");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    let mut done = OutputFolder::create(&dir, RENDER).expect("folder");
    done.write("results.jsonl", b"1008 rows").expect("written");
    done.finish(None).expect("finished");
    RunManifest::verify(&dir, u64::MAX).expect("complete");
    let mut killed = OutputFolder::create(&dir, RENDER).expect("folder");
    killed.write("partial.jsonl", b"336 rows").expect("written");
    drop(killed);
    let err = RunManifest::verify(&dir, u64::MAX).expect_err("incomplete");
    assert!(err.to_string().contains("did not finish"), "{err}");
    assert!(dir.join(PENDING).exists());
    let mut next = OutputFolder::create(&dir, RENDER).expect("folder");
    next.write("summary.md", b"whole").expect("written");
    next.finish(None).expect("finished");
    assert_eq!(names(&dir), vec!["manifest.json", "summary.md"], "both earlier runs' files are gone");
    // A file changed after the run no longer matches.
    std::fs::write(dir.join("summary.md"), "whol").expect("truncate");
    let err = RunManifest::verify(&dir, u64::MAX).expect_err("changed");
    assert!(err.to_string().contains("summary.md") && err.to_string().contains("differs"), "{err}");
}

/// A manifest (ours, forged or stale) that lists a file reached through a
/// symbolic link, or a file whose contents are no longer what a run
/// wrote, gets nothing deleted: the link's target outside the folder and
/// the user's own file of a listed name survive the next run.
#[cfg(unix)]
#[test]
fn a_listed_file_is_removed_only_inside_and_only_if_ours() {
    let scratch_dir = scratch("folder-trust");
    let base = scratch_dir.path().to_owned();
    let (dir, elsewhere) = (base.join("out"), base.join("elsewhere"));
    std::fs::create_dir_all(&elsewhere).expect("dir");
    std::fs::write(elsewhere.join("precious.txt"), "x").expect("a file outside");
    let mut first = OutputFolder::create(&dir, RENDER).expect("folder");
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
    OutputFolder::create(&dir, RENDER.replacing(true)).and_then(|f| f.finish(None)).expect("a run");
    assert!(elsewhere.join("precious.txt").exists(), "a file through a link was deleted");
    assert_eq!(std::fs::read_to_string(dir.join("notes.md")).ok().as_deref(), Some("my own notes"));
    assert!(!dir.join("old.png").exists(), "a file of ours, as written, is removed");
    // Nor does a run write through the link.
    let mut f = OutputFolder::create(&dir, RENDER.replacing(true)).expect("folder");
    let err = f.write("sub/new.txt", b"x").expect_err("refused");
    assert!(err.to_string().contains("symbolic link"), "{err}");
    assert!(!elsewhere.join("new.txt").exists());
    pending.clear();
}

/// One run a folder: a second run into a folder in use fails at once,
/// naming it, and runs again once the first is done; a dead run's
/// temporaries are removed by the next run.
#[test]
fn a_folder_in_use_is_refused_and_dead_temporaries_removed() {
    let scratch_dir = scratch("folder-lock");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    let first = OutputFolder::create(&dir, RENDER).expect("folder");
    let err = OutputFolder::create(&dir, RENDER).expect_err("in use");
    assert!(err.to_string().contains("in use") && err.to_string().contains("out"), "{err}");
    drop(first);
    std::fs::create_dir_all(dir.join("sub")).expect("dir");
    for t in [".umbra-ab12.tmp", "sub/.umbra-cd34.tmp"] {
        std::fs::write(dir.join(t), "half a file").expect("a dead run's temporary");
    }
    std::fs::write(dir.join("mine.tmp"), "a user's").expect("a user's file");
    let f = OutputFolder::create(&dir, RENDER.replacing(true)).expect("free again");
    assert!(!dir.join(".umbra-ab12.tmp").exists() && !dir.join("sub/.umbra-cd34.tmp").exists());
    assert!(dir.join("mine.tmp").exists());
    f.finish(None).expect("finished");
}

/// A stopped run removes its lock file while it holds it: a second run
/// that opened the file before, and locks it once it is free, holds a lock
/// on a removed file, which guards nothing; [`super::lock`] takes the file
/// now at the path instead, and that one keeps a third run out.
#[cfg(unix)]
#[test]
fn a_lock_on_a_removed_lock_file_is_not_the_folders() {
    let scratch_dir = scratch("folder-relock");
    let dir = scratch_dir.path().join("out");
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join(LOCK);
    let first = super::lock(&dir).expect("free");
    let second = std::fs::OpenOptions::new().write(true).open(&path).expect("opened while held");
    std::fs::remove_file(&path).expect("removed while held");
    drop(first);
    second.try_lock().expect("the removed file's lock is free");
    assert!(!super::at_path(&second, &path), "a lock on a removed file is taken for the folder's");
    let third = super::lock(&dir).expect("a new lock file");
    assert!(super::at_path(&third, &path));
    let err = super::lock(&dir).expect_err("held");
    assert!(err.to_string().contains("in use"), "{err}");
}

/// Files get the permissions the umask gives a new file, as `touch` makes
/// it, not a private 0600; a second run keeps them.
#[cfg(unix)]
#[test]
fn files_are_as_readable_as_the_umask_allows() {
    use std::os::unix::fs::PermissionsExt;
    let scratch_dir = scratch("folder-mode");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(base.join("touched"), "").expect("touch");
    let touched = std::fs::metadata(base.join("touched")).expect("meta").permissions().mode() & 0o777;
    assert_ne!(touched, 0o600, "this test needs a umask that lets others read (022 makes 0644)");
    for _ in 0..2 {
        let mut f = OutputFolder::create(&dir, RENDER).expect("folder");
        f.write("a.txt", b"x").expect("written");
        f.finish(None).expect("finished");
        for n in ["a.txt", MANIFEST] {
            let mode = std::fs::metadata(dir.join(n)).expect("meta").permissions().mode() & 0o777;
            assert_eq!(mode, touched, "{n}");
        }
    }
}

/// A run refused after it opened its folder but before it wrote a file (an
/// empty map, a bad scene found late) leaves the folder as it found it: a
/// folder it made is gone, a finished run's folder is still complete, a
/// user's own folder keeps its files and gains none. A run that wrote a
/// file still leaves its pending record.
#[test]
fn a_run_that_wrote_nothing_leaves_the_folder_as_it_was() {
    let scratch_dir = scratch("folder-untouched");
    let base = scratch_dir.path().to_owned();
    let made = base.join("made");
    drop(OutputFolder::create(&made, RENDER).expect("folder"));
    assert!(!made.exists(), "the folder it made is removed");
    let done = base.join("done");
    let mut first = OutputFolder::create(&done, RENDER).expect("folder");
    first.write("summary.md", b"whole").expect("written");
    first.finish(None).expect("finished");
    let record = std::fs::read(done.join(MANIFEST)).expect("a manifest");
    drop(OutputFolder::create(&done, RENDER).expect("folder"));
    RunManifest::verify(&done, u64::MAX).expect("still complete");
    assert_eq!(std::fs::read(done.join(MANIFEST)).expect("a manifest"), record, "the same record");
    assert_eq!(names(&done), vec!["manifest.json", "summary.md"]);
    let mine = base.join("mine");
    std::fs::create_dir_all(&mine).expect("dir");
    std::fs::write(mine.join("notes.txt"), "mine").expect("a user's file");
    OutputFolder::create(&mine, RENDER).expect_err("a folder of files no run wrote");
    assert_eq!(names(&mine), vec!["notes.txt"], "nothing left behind, the lock included");
    assert!(!mine.join(LOCK).exists());
    drop(OutputFolder::create(&mine, RENDER.replacing(true)).expect("folder"));
    assert_eq!(names(&mine), vec!["notes.txt"]);
    let mut partial = OutputFolder::create(&done, RENDER).expect("folder");
    partial.write("rows.jsonl", b"1").expect("written");
    drop(partial);
    assert!(done.join(PENDING).exists() && !done.join(MANIFEST).exists(), "a partial run is visible");
}

/// A folder holds one command's results: a study into a render's folder
/// (and a render into a study's) is refused, naming the earlier command
/// and its files, and deletes nothing; `--replace` replaces them and says
/// which; a manifest of an earlier version, without its kind, is read by
/// its command line.
#[test]
fn another_commands_results_are_refused_unless_replaced() {
    let scratch_dir = scratch("folder-kinds");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    let mut render = OutputFolder::create(&dir, RENDER).expect("folder");
    render.write("shaded.png", b"pixels").and_then(|_| render.write("metrics.json", b"{}")).expect("written");
    render.finish(None).expect("finished");
    let study = Claim::new(RunKind::Study);
    let err = OutputFolder::create(&dir, study).expect_err("a render's folder").to_string();
    for word in ["a render", "shaded.png", "metrics.json", "--replace", "a study"] {
        assert!(err.contains(word), "`{word}` not in: {err}");
    }
    assert_eq!(names(&dir), vec!["manifest.json", "metrics.json", "shaded.png"], "nothing deleted");
    RunManifest::verify(&dir, u64::MAX).expect("still complete");
    let mut replacing = OutputFolder::create(&dir, study.replacing(true)).expect("replaced deliberately");
    replacing.write("summary.md", b"rows").expect("written");
    let (m, replaced) = replacing.finish_replacing(None).expect("finished");
    assert_eq!(m.kind, Some(RunKind::Study));
    assert_eq!(replaced.removed, vec!["shaded.png", "metrics.json"]);
    assert_eq!(names(&dir), vec!["manifest.json", "summary.md"]);
    // A manifest without its kind (an earlier version's) names its command.
    let text = std::fs::read_to_string(dir.join(MANIFEST)).expect("manifest");
    let legacy: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let mut legacy = legacy.as_object().expect("an object").clone();
    legacy.remove("kind");
    legacy.insert("command".into(), "./umbra study --quick --out out".into());
    std::fs::write(dir.join(MANIFEST), serde_json::to_string(&legacy).expect("JSON")).expect("legacy");
    let err = OutputFolder::create(&dir, RENDER).expect_err("a study's folder").to_string();
    assert!(err.contains("a study") && err.contains("umbra study --quick"), "{err}");
    OutputFolder::create(&dir, study).expect("a study into a study's folder").finish(None).expect("finished");
}

/// A file this process read is never removed nor written over, whatever
/// an earlier run's manifest lists: a render of a model another command
/// wrote into the same folder keeps it; a run of the kind that wrote it
/// (which would write it again) is refused before it starts.
#[test]
fn a_file_the_run_read_is_kept() {
    let scratch_dir = scratch("folder-input");
    let base = scratch_dir.path().to_owned();
    let dir = base.join("out");
    let mut scene = OutputFolder::create(&dir, Claim::new(RunKind::Scene)).expect("folder");
    let model = scene.write("city.glb", b"a model").expect("written");
    scene.finish(None).expect("finished");
    crate::base::reads::note(&model); // as reading it through the limits notes it
    let err = OutputFolder::create(&dir, Claim::new(RunKind::Scene)).expect_err("would write it again").to_string();
    assert!(err.contains("city.glb") && err.contains("reads"), "{err}");
    let err = OutputFolder::create(&dir, RENDER).expect_err("a scene's folder").to_string();
    assert!(err.contains("city.glb") && err.contains("--replace"), "{err}");
    let mut render = OutputFolder::create(&dir, RENDER.replacing(true)).expect("replaced deliberately");
    let err = render.write("city.glb", b"over").expect_err("its own input").to_string();
    assert!(err.contains("read"), "{err}");
    render.write("shaded.png", b"pixels").expect("written");
    let (_, replaced) = render.finish_replacing(None).expect("finished");
    assert!(replaced.removed.is_empty(), "{replaced:?}");
    assert_eq!(std::fs::read(&model).expect("kept"), b"a model");
    // The model, now a file no manifest lists, is still this run's input.
    OutputFolder::create(&dir, RENDER).expect("its input is no stranger").finish(None).expect("finished");
    assert!(model.exists());
}
