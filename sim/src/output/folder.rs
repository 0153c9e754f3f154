//! An output folder as a run leaves it: every file whole or absent, and a
//! manifest, written last, that says which files the run wrote.
//!
//! A run opens its folder before its long work (so an unwritable `--out`
//! fails first), writes each file to a temporary beside it and renames it
//! into place only after the data reached the disk, and finishes by
//! removing what an earlier run listed and this one did not write, then
//! writing `manifest.json` (files, sizes, SHA-256, command line, version).
//! While a run is under way the folder has no `manifest.json`, only
//! `manifest.pending.json` listing every file an earlier or the current
//! run may have left, so a killed run's folder is visibly incomplete and
//! the next run still knows what to clean.
//!
//! A folder holds one command's results. A run opens a folder that is
//! new, empty, or holds an earlier run of its own [`RunKind`] and nothing
//! else; a folder holding another command's results, or files no
//! manifest of its own lists, is refused, naming them, unless the run is
//! told to replace them ([`Claim::replace`]: the `umbra` command's
//! `--replace`). Even then it never deletes a file no run of Umbra wrote,
//! nor a file this process read ([`crate::base::reads`]): a render whose
//! model lies in its output folder keeps it, and a run never writes over
//! its own input. [`OutputFolder::finish_replacing`] names what a run replaces.
//!
//! The folder trusts nothing it did not write and verify: a file an
//! earlier record lists is removed only if its path lies inside the folder
//! without passing through a symbolic link and its contents still hash to
//! what the record says (a user's own file of the same name is kept); a run
//! holds the folder's lock (`.umbra-lock`, an OS lock the kernel releases
//! if the run dies), so a second run into it fails at once; temporaries a
//! dead run left (`.umbra-*.tmp`) are removed by the next. Files are
//! created as the process's umask allows (as `touch` would), not private.
//!
//! A run stopped on request ([`crate::base::stop`]: the `umbra` command's
//! Ctrl-C) does not finish: it keeps its pending record, so the folder is
//! an unfinished run's that the next run resumes or replaces, and removes
//! its lock file as it releases the lock. A folder is not opened once a
//! stop is requested.
//!
//! ```
//! use umbra_sim::output::folder::{Claim, OutputFolder, RunKind, RunManifest};
//! let scratch = tempfile::tempdir()?;
//! let out = scratch.path().join("out");
//! let mut folder = OutputFolder::create(&out, Claim::new(RunKind::Render))?;
//! folder.write("notes.txt", b"hello")?;
//! assert!(!out.join("manifest.json").exists(), "not yet finished");
//! let manifest = folder.finish(None)?;
//! assert_eq!(manifest.files.len(), 1);
//! // The folder as it is on disk, checked against its manifest.
//! assert_eq!(RunManifest::verify(&out, u64::MAX)?, manifest);
//! // A study into the render's folder is refused, and nothing is deleted.
//! let refused = OutputFolder::create(&out, Claim::new(RunKind::Study)).unwrap_err();
//! assert!(refused.to_string().contains("--replace"), "{refused}");
//! assert!(out.join("notes.txt").exists());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};

use super::error::OutputError;

/// The folder's lock file: held (an OS lock) for the whole run.
pub(crate) const LOCK: &str = ".umbra-lock";

/// An output folder being written by one run.
#[derive(Debug)]
pub struct OutputFolder {
    dir: PathBuf,
    /// What this run writes.
    claim: Claim,
    /// Files earlier runs listed, with the hashes they recorded (removed at
    /// the end unless rewritten, and only if they still match).
    earlier: Vec<FileRecord>,
    /// The earlier run's command line.
    earlier_command: Option<String>,
    written: Vec<FileRecord>,
    /// Files no run listed that this one wrote over (with `--replace`).
    overwritten: Vec<String>,
    /// The lock, released when the folder is dropped.
    _lock: std::fs::File,
    /// The permissions a new file gets under the process's umask.
    #[cfg(unix)]
    mode: u32,
    /// What the folder was before this run, so that a run that ends
    /// without writing a file (refused after the folder was opened)
    /// leaves it as it found it.
    before: Before,
    /// `finish` ran.
    finished: bool,
}

/// The folder as a run found it.
#[derive(Debug, Default)]
struct Before {
    /// It did not exist.
    absent: bool,
    /// Its `manifest.json`, when it had one (of at most [`Before::MANIFEST_BYTES`]).
    manifest: Option<Vec<u8>>,
    /// It held a pending record.
    pending: bool,
}

impl Before {
    /// The largest manifest kept to be put back.
    const MANIFEST_BYTES: u64 = 16 << 20;
}

impl Drop for OutputFolder {
    /// A run that wrote no file leaves the folder as it found it: the
    /// earlier manifest back, its own pending record gone, and a folder it
    /// made removed (when nothing else is in it). A run that wrote a file,
    /// or was stopped, leaves its pending record, so the folder tells it did
    /// not finish; a stopped run removes its lock file too.
    fn drop(&mut self) {
        if self.finished {
            return;
        }
        if crate::base::stop::requested() {
            // Removed while held (the lock goes with the field, after this):
            // a run that opened it meanwhile finds it gone and takes a new one.
            let _ = std::fs::remove_file(self.dir.join(LOCK));
            return;
        }
        if !self.written.is_empty() {
            return;
        }
        if let Some(bytes) = &self.before.manifest
            && self.atomic(&self.dir.join(MANIFEST), bytes).is_err()
        {
            return;
        }
        if !self.before.pending {
            let _ = std::fs::remove_file(self.dir.join(PENDING));
        }
        if self.before.absent {
            let _ = std::fs::remove_file(self.dir.join(LOCK));
            let _ = std::fs::remove_dir(&self.dir);
        }
    }
}

fn problem(path: &Path, problem: impl Into<String>) -> OutputError {
    OutputError::Folder { path: path.to_owned(), problem: problem.into() }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io { path: path.to_owned(), source }
}

/// Whether `name` lies inside `dir` with no symbolic link on the way: each
/// part of it that exists a real folder or file, not a link (a part that
/// does not exist yet is created as a real folder).
fn plainly_inside(dir: &Path, name: &Path) -> bool {
    let mut at = dir.to_owned();
    name.components().all(|c| {
        at.push(c);
        match std::fs::symlink_metadata(&at) {
            Ok(m) => !m.file_type().is_symlink(),
            Err(e) => e.kind() == std::io::ErrorKind::NotFound,
        }
    })
}

/// Remove the temporaries (`.umbra-*.tmp`) a dead run left in `dir` and
/// its sub-folders (not through links); only the lock's holder calls this.
fn remove_dead_temporaries(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let Ok(kind) = entry.file_type() else { continue };
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if kind.is_dir() {
            remove_dead_temporaries(&entry.path());
        } else if kind.is_file() && name.starts_with(".umbra-") && name.ends_with(".tmp") {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Take the lock of `dir` for this run, or say that another run holds it.
///
/// A run that ends removes the lock file while it holds it, so a lock
/// taken on a file no longer at the lock's path guards nothing: the file
/// now there (or a new one) is locked instead.
fn lock(dir: &Path) -> Result<std::fs::File, OutputError> {
    const TRIES: usize = 16;
    let path = dir.join(LOCK);
    for _ in 0..TRIES {
        let file =
            std::fs::OpenOptions::new().create(true).truncate(false).write(true).open(&path).map_err(io(&path))?;
        match file.try_lock() {
            Ok(()) if at_path(&file, &path) => return Ok(file),
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(problem(
                    dir,
                    "is in use by another run of umbra (its lock .umbra-lock is held); wait for it or choose another --out",
                ));
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(io(&path)(e)),
        }
    }
    Err(problem(dir, "its lock .umbra-lock keeps being replaced by other runs; wait for them or choose another --out"))
}

/// Whether `file` is the file at `path` now (not one removed since it was
/// opened).
fn at_path(file: &std::fs::File, path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (file.metadata(), std::fs::metadata(path)) {
            (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = (file, path);
        true
    }
}

impl OutputFolder {
    /// Open `dir` for a run that writes what `claim` says: create it,
    /// prove it writable, and mark it under way (its `manifest.json` is
    /// gone until [`finish`](Self::finish)).
    ///
    /// # Errors
    /// `OutputError::Io` or `OutputError::Folder` naming the folder; a
    /// folder that holds another command's results, or files no run of
    /// Umbra wrote, is refused (naming them) unless `claim.replace`;
    /// `OutputError::Stopped` once a stop was requested.
    pub fn create(dir: &Path, claim: Claim) -> Result<Self, OutputError> {
        crate::base::stop::check()?;
        if std::fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) && !dir.exists() {
            return Err(problem(dir, "is a symbolic link to nothing (dangling, or a loop): give a folder"));
        }
        if dir.exists() && !dir.is_dir() {
            return Err(problem(dir, "exists and is not a folder"));
        }
        let absent = std::fs::symlink_metadata(dir).is_err();
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let had_lock = dir.join(LOCK).exists();
        let lock = lock(dir)?;
        let earlier = Earlier::read(dir);
        if let Err(e) = admit(dir, claim, &earlier) {
            // Removed while held, as a stopped run's ([`lock`]).
            if !had_lock {
                let _ = std::fs::remove_file(dir.join(LOCK));
            }
            drop(lock);
            return Err(e);
        }
        let manifest = dir.join(MANIFEST);
        let before = Before {
            absent,
            manifest: std::fs::symlink_metadata(&manifest)
                .is_ok_and(|m| m.is_file() && m.len() <= Before::MANIFEST_BYTES)
                .then(|| std::fs::read(&manifest).ok())
                .flatten(),
            pending: dir.join(PENDING).exists(),
        };
        remove_dead_temporaries(dir);
        // A file created as `touch` creates one: its mode is the umask's.
        let probe_path = dir.join(format!(".umbra-probe-{}.tmp", std::process::id()));
        let mut probe = std::fs::OpenOptions::new().write(true).create_new(true).open(&probe_path).map_err(io(dir))?;
        let written = probe.write_all(b"umbra").and_then(|()| probe.sync_all()).and_then(|()| probe.metadata());
        let _ = std::fs::remove_file(&probe_path);
        #[cfg_attr(not(unix), allow(unused_variables))]
        let metadata = written.map_err(io(dir))?;
        let folder = Self {
            dir: dir.to_owned(),
            claim,
            earlier: earlier.files,
            earlier_command: earlier.command,
            written: Vec::new(),
            overwritten: Vec::new(),
            _lock: lock,
            #[cfg(unix)]
            mode: std::os::unix::fs::PermissionsExt::mode(&metadata.permissions()) & 0o777,
            before,
            finished: false,
        };
        folder.record_pending()?;
        match std::fs::remove_file(dir.join(MANIFEST)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(io(&dir.join(MANIFEST))(e)),
            _ => {}
        }
        Ok(folder)
    }

    /// The folder.
    #[must_use]
    pub(crate) fn dir(&self) -> &Path {
        &self.dir
    }

    fn record_pending(&self) -> Result<(), OutputError> {
        let mut files = self.earlier.clone();
        files.extend(self.written.iter().filter(|f| !self.earlier.contains(f)).cloned());
        // Strings and numbers always serialise.
        let pending = Pending { files, kind: Some(self.claim.kind), command: Some(super::provenance::command_line()) };
        let text = serde_json::to_string_pretty(&pending).unwrap_or_default();
        self.atomic(&self.dir.join(PENDING), text.as_bytes())
    }

    /// [`atomic`], the file given the umask's permissions.
    fn atomic(&self, path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
        #[cfg(unix)]
        let mode = Some(self.mode);
        #[cfg(not(unix))]
        let mode = None;
        atomic(path, bytes, mode)
    }

    /// Write `bytes` as `name` (a path inside the folder): whole, or not at
    /// all. Returns the file's path.
    ///
    /// # Errors
    /// `OutputError::Folder` for a name outside the folder or one of the
    /// manifests; `OutputError::Io` naming the file for any write error.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        let relative = checked_name(&self.dir, name)?;
        if name == MANIFEST || name == PENDING {
            return Err(problem(&self.dir, format!("`{name}` is the folder's own record")));
        }
        let path = self.dir.join(relative);
        if crate::base::reads::was_read(&path) {
            return Err(problem(
                &path,
                "is a file this run read: a run never writes over its input; choose another --out",
            ));
        }
        let listed = self.earlier.iter().chain(&self.written).any(|f| f.path == name);
        if !listed && std::fs::symlink_metadata(&path).is_ok() && !self.overwritten.iter().any(|n| n == name) {
            self.overwritten.push(name.to_owned());
        }
        let record = FileRecord { path: name.to_owned(), bytes: bytes.len() as u64, sha256: sha256(bytes) };
        self.written.retain(|f| f.path != name);
        self.written.push(record);
        self.record_pending()?;
        if !plainly_inside(&self.dir, relative.parent().unwrap_or(Path::new(""))) {
            return Err(problem(
                &path,
                "its folder is reached through a symbolic link: a run writes only inside --out",
            ));
        }
        self.atomic(&path, bytes)?;
        Ok(path)
    }

    /// Write UTF-8 text as `name`.
    ///
    /// # Errors
    /// As `write`.
    pub fn write_text(&mut self, name: &str, text: &str) -> Result<PathBuf, OutputError> {
        self.write(name, text.as_bytes())
    }

    /// End the run: remove the files earlier runs listed that this one did
    /// not write, write `manifest.json`, drop the pending record.
    ///
    /// # Errors
    /// `OutputError::Io` naming the file that could not be removed or
    /// written; `OutputError::Stopped` once a stop was requested (the
    /// folder then stays marked unfinished).
    pub fn finish(self, study: Option<serde_json::Value>) -> Result<RunManifest, OutputError> {
        self.finish_replacing(study).map(|(manifest, _)| manifest)
    }

    /// [`finish`](Self::finish), and what the run replaced: the earlier
    /// run's files it removed or wrote anew, and the files no run listed
    /// that it wrote over.
    ///
    /// # Errors
    /// As [`finish`](Self::finish).
    pub fn finish_replacing(
        mut self,
        study: Option<serde_json::Value>,
    ) -> Result<(RunManifest, Replaced), OutputError> {
        crate::base::stop::check()?;
        let mut replaced = Replaced {
            command: self.earlier_command.clone(),
            overwritten: std::mem::take(&mut self.overwritten),
            ..Replaced::default()
        };
        for old in &self.earlier {
            if self.written.iter().any(|f| f.path == old.path) {
                if !replaced.rewritten.contains(&old.path) {
                    replaced.rewritten.push(old.path.clone());
                }
                continue;
            }
            let name = Path::new(&old.path);
            let path = self.dir.join(name);
            // Only a regular file inside the folder, reached through no link,
            // whose contents are still what a run of ours wrote, and which
            // this process did not read.
            if !plainly_inside(&self.dir, name)
                || !std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file())
                || crate::base::reads::was_read(&path)
            {
                continue;
            }
            let ours = read_small_limit(&path, old.bytes)
                .is_ok_and(|data| data.len() as u64 == old.bytes && sha256(&data) == old.sha256);
            if ours {
                std::fs::remove_file(&path).map_err(io(&path))?;
                replaced.removed.push(old.path.clone());
            }
        }
        let manifest = RunManifest {
            umbra_version: super::provenance::version(),
            command: super::provenance::command_line(),
            kind: Some(self.claim.kind),
            files: self.written.clone(),
            study,
        };
        // Strings, numbers and a JSON value always serialise.
        let text = serde_json::to_string_pretty(&manifest).unwrap_or_default();
        self.atomic(&self.dir.join(MANIFEST), text.as_bytes())?;
        let pending = self.dir.join(PENDING);
        std::fs::remove_file(&pending).map_err(io(&pending))?;
        self.finished = true;
        Ok((manifest, replaced))
    }
}

/// Write `bytes` to a temporary beside `path`, flush it to the disk, and
/// rename it into place, with the permissions `mode` (Unix) when given; on
/// any error nothing is left.
fn atomic(path: &Path, bytes: &[u8], mode: Option<u32>) -> Result<(), OutputError> {
    let parent = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io(path))?;
    let mut tmp = tempfile::Builder::new().prefix(".umbra-").suffix(".tmp").tempfile_in(parent).map_err(io(path))?;
    #[cfg(unix)]
    if let Some(mode) = mode {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file().set_permissions(std::fs::Permissions::from_mode(mode)).map_err(io(path))?;
    }
    #[cfg(not(unix))]
    let _ = mode;
    write_all_synced(tmp.as_file_mut(), bytes).map_err(io(path))?;
    tmp.persist(path).map_err(|e| io(path)(e.error))?;
    Ok(())
}

/// Write `bytes` to `sink` and make sure they reached it: any error —
/// a full disk included — is returned, never lost in a buffer.
///
/// # Errors
/// The OS error.
pub(crate) fn write_all_synced(sink: &mut std::fs::File, bytes: &[u8]) -> std::io::Result<()> {
    sink.write_all(bytes)?;
    sink.flush()?;
    sink.sync_all()
}

mod claim;
mod manifest;
mod state;
#[cfg(test)]
mod tests;

pub use claim::{Claim, Replaced, RunKind};
use claim::{Earlier, admit};
pub(crate) use manifest::sha256;
pub use manifest::{FileRecord, MANIFEST, PENDING, RunManifest};
use manifest::{Pending, checked_name, read_small, read_small_limit};
pub(crate) use state::FolderState;
