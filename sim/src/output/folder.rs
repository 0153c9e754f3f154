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
//! its own input. [`OutputFolder::replaced`] names what a run replaces.
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
use std::path::{Component, Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::error::OutputError;

/// The manifest of a finished run.
pub const MANIFEST: &str = "manifest.json";
/// The record of a run under way (or killed).
pub const PENDING: &str = "manifest.pending.json";
/// Largest manifest read back (an earlier run's), bytes.
const MAX_MANIFEST_BYTES: u64 = 16 << 20;

/// One file a run wrote.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileRecord {
    /// Its path inside the folder, `/`-separated.
    pub path: String,
    /// Its size.
    pub bytes: u64,
    /// Its SHA-256, lower-case hex.
    pub sha256: String,
}

/// The results a folder holds: which command wrote them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum RunKind {
    /// Light-view maps (`umbra depth`).
    Depth,
    /// A render against the reference (`umbra render`).
    Render,
    /// Costs on architectures (`umbra cost`).
    Cost,
    /// A timeline (`umbra trace`).
    Trace,
    /// The model against measured hardware (`umbra correlate`).
    Correlation,
    /// A study, a shard of one, or shards merged (`umbra study`, `umbra merge`).
    Study,
    /// A plan (`umbra plan`).
    Plan,
    /// A generated scene (`umbra scene city`).
    Scene,
}

impl RunKind {
    /// Every kind.
    pub const ALL: [Self; 8] =
        [Self::Depth, Self::Render, Self::Cost, Self::Trace, Self::Correlation, Self::Study, Self::Plan, Self::Scene];

    /// What a folder of this kind holds, as a message names it.
    #[must_use]
    pub const fn describe(self) -> &'static str {
        match self {
            Self::Depth => "light-view maps",
            Self::Render => "a render",
            Self::Cost => "a cost report",
            Self::Trace => "a trace",
            Self::Correlation => "a correlation",
            Self::Study => "a study",
            Self::Plan => "a plan",
            Self::Scene => "a generated scene",
        }
    }

    /// The `umbra` subcommands that write it.
    const fn words(self) -> &'static [&'static str] {
        match self {
            Self::Depth => &["depth"],
            Self::Render => &["render"],
            Self::Cost => &["cost"],
            Self::Trace => &["trace"],
            Self::Correlation => &["correlate"],
            Self::Study => &["study", "merge"],
            Self::Plan => &["plan"],
            Self::Scene => &["scene"],
        }
    }

    /// The kind a manifest written before manifests named it holds: the
    /// first word of its command line that is a subcommand's; `None` for
    /// the bare `umbra` (which writes maps, a render and a study).
    fn of_command(command: &str) -> Option<Self> {
        command.split_whitespace().skip(1).find_map(|w| Self::ALL.into_iter().find(|k| k.words().contains(&w)))
    }
}

/// What a run asks of its output folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Claim {
    /// The results it writes.
    pub kind: RunKind,
    /// Replace another command's results, or files no run of Umbra
    /// wrote, deliberately (`--replace`). Files it does not rewrite are
    /// removed only if an earlier run listed them as it wrote them; files
    /// no run wrote, and files this process read, are never removed.
    pub replace: bool,
}

impl Claim {
    /// A run of `kind` that replaces nothing of another's.
    #[must_use]
    pub const fn new(kind: RunKind) -> Self {
        Self { kind, replace: false }
    }

    /// The same, replacing what is there when `replace`.
    #[must_use]
    pub const fn replacing(self, replace: bool) -> Self {
        Self { replace, ..self }
    }
}

/// What a run replaces in its folder: the earlier run's files, and the
/// files no run listed that `--replace` let it write over.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Replaced {
    /// The earlier run's command line, when the folder held a run.
    pub command: Option<String>,
    /// The files the earlier run listed that this one removed (it did not
    /// rewrite them).
    pub removed: Vec<String>,
    /// The files the earlier run listed that this one wrote anew.
    pub rewritten: Vec<String>,
    /// Files no run listed that this one wrote over (only with `--replace`).
    pub overwritten: Vec<String>,
}

/// `manifest.json`: what made the folder and every file in it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunManifest {
    /// The version that wrote it (with its git revision).
    pub umbra_version: String,
    /// The command line.
    pub command: String,
    /// The results it holds (absent in manifests of versions before 0.1.1:
    /// read from the command line).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<RunKind>,
    /// Every file the run wrote, in the order written.
    pub files: Vec<FileRecord>,
    /// The study's own record (sweep, shard, row counts), for `merge`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub study: Option<serde_json::Value>,
}

impl RunManifest {
    /// Read the manifest of `dir` and check every file it lists (each at
    /// most `max_bytes`) against its size and hash.
    ///
    /// # Errors
    /// `OutputError::Folder` naming the manifest or the file that does
    /// not match: a folder without a matching manifest is incomplete.
    pub fn verify(dir: &Path, max_bytes: u64) -> Result<Self, OutputError> {
        let path = dir.join(MANIFEST);
        let bytes = read_small(&path)
            .map_err(|e| problem(&path, format!("no manifest: the run that wrote this folder did not finish ({e})")))?;
        let m: Self = serde_json::from_slice(&bytes).map_err(|e| problem(&path, format!("not a manifest: {e}")))?;
        for f in &m.files {
            let file = dir.join(checked_name(&path, &f.path)?);
            if f.bytes > max_bytes {
                return Err(problem(&file, format!("listed at {} bytes, above the limit of {max_bytes}", f.bytes)));
            }
            let data = read_small_limit(&file, f.bytes.saturating_add(1))
                .map_err(|e| problem(&file, format!("listed in the manifest but unreadable: {e}")))?;
            if data.len() as u64 != f.bytes || sha256(&data) != f.sha256 {
                return Err(problem(&file, "differs from the manifest (truncated or changed since it was written)"));
            }
        }
        Ok(m)
    }
}

/// What `manifest.pending.json` holds.
#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Pending {
    /// Files an earlier or the current run may have left, each with the
    /// hash of the contents that run wrote (or was about to write).
    files: Vec<FileRecord>,
    /// The results the run under way writes, and the command line (absent
    /// in records of earlier versions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    kind: Option<RunKind>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    command: Option<String>,
}

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
    /// made removed (when nothing else is in it). A run that wrote a file
    /// leaves its pending record, so the folder tells it did not finish.
    fn drop(&mut self) {
        if self.finished || !self.written.is_empty() {
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

/// SHA-256 of `bytes` in lower-case hex.
#[must_use]
pub(crate) fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().fold(String::with_capacity(64), |mut s, b| {
        use std::fmt::Write as _;
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// `name` as a path inside a folder: relative, plain components only (no
/// `..`, no root, no prefix), not empty.
fn checked_name<'a>(context: &Path, name: &'a str) -> Result<&'a Path, OutputError> {
    let path = Path::new(name);
    let plain = path.components().all(|c| matches!(c, Component::Normal(_)));
    if name.is_empty() || !plain || name.contains('\\') {
        return Err(problem(context, format!("`{name}` is not a file name inside the output folder")));
    }
    Ok(path)
}

/// Read a small regular file whole, refusing special files before opening
/// them.
fn read_small(path: &Path) -> std::io::Result<Vec<u8>> {
    read_small_limit(path, MAX_MANIFEST_BYTES)
}

fn read_small_limit(path: &Path, max: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    if !std::fs::metadata(path)?.is_file() {
        return Err(std::io::Error::other("not a regular file"));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.take(max.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max {
        return Err(std::io::Error::other(format!("larger than the {max} bytes it may be")));
    }
    Ok(bytes)
}

/// What earlier runs left in a folder: the files their records list,
/// with their hashes, the results they hold and the command that wrote
/// them, as far as the records are ours; anything else lists nothing (and
/// so is never acted on).
#[derive(Debug, Default)]
struct Earlier {
    files: Vec<FileRecord>,
    kind: Option<RunKind>,
    command: Option<String>,
}

impl Earlier {
    /// The records in `dir`: its manifest, then its pending record.
    fn read(dir: &Path) -> Self {
        let mut earlier = Self::default();
        if let Ok(m) = read_small(&dir.join(MANIFEST)).and_then(|b| Ok(serde_json::from_slice::<RunManifest>(&b)?)) {
            earlier.kind = m.kind.or_else(|| RunKind::of_command(&m.command));
            earlier.command = Some(m.command);
            earlier.files = m.files;
        }
        if let Ok(p) = read_small(&dir.join(PENDING)).and_then(|b| Ok(serde_json::from_slice::<Pending>(&b)?)) {
            earlier.kind = earlier.kind.or(p.kind);
            earlier.command = earlier.command.or(p.command);
            for f in p.files {
                if !earlier.files.contains(&f) {
                    earlier.files.push(f);
                }
            }
        }
        earlier.files.retain(|f| checked_name(dir, &f.path).is_ok());
        earlier
    }

    /// Whether `name` (`/`-separated, inside the folder) is a file the
    /// records list or a folder one of them lies in.
    fn covers(&self, name: &str) -> bool {
        self.files.iter().any(|f| f.path == name || f.path.strip_prefix(name).is_some_and(|r| r.starts_with('/')))
    }
}

/// The entries of `dir` (its sub-folders too, where the records list a
/// file inside them) that no run of Umbra wrote: not the folder's own
/// records, lock or temporaries, not listed by `earlier`, and not a file
/// this process read. At most `max` entries are looked at.
fn foreign(dir: &Path, earlier: &Earlier, max: usize) -> Vec<String> {
    let mut found = Vec::new();
    let mut stack = vec![String::new()];
    let mut looked = 0usize;
    while let Some(prefix) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(dir.join(&prefix)) else { continue };
        let mut names: Vec<(String, bool)> = entries
            .flatten()
            .map(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                (name, e.file_type().is_ok_and(|t| t.is_dir()))
            })
            .collect();
        names.sort();
        for (name, is_dir) in names {
            looked += 1;
            if looked > max {
                return found;
            }
            let own = prefix.is_empty() && [MANIFEST, PENDING, LOCK].contains(&name.as_str());
            if own || (name.starts_with(".umbra-") && name.ends_with(".tmp")) {
                continue;
            }
            let path = format!("{prefix}{name}");
            if earlier.files.iter().any(|f| f.path == path) || crate::base::reads::was_read(&dir.join(&path)) {
                continue;
            }
            if is_dir && earlier.covers(&path) {
                stack.push(format!("{path}/"));
            } else {
                found.push(path);
            }
        }
    }
    found
}

/// `names` as a message lists them: the first few, and how many more.
fn list(names: &[String]) -> String {
    const SHOWN: usize = 4;
    let shown: Vec<&str> = names.iter().take(SHOWN).map(String::as_str).collect();
    let more = names.len().saturating_sub(SHOWN);
    if more > 0 { format!("{} and {more} more", shown.join(", ")) } else { shown.join(", ") }
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
fn lock(dir: &Path) -> Result<std::fs::File, OutputError> {
    let path = dir.join(LOCK);
    let file = std::fs::OpenOptions::new().create(true).truncate(false).write(true).open(&path).map_err(io(&path))?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(problem(
            dir,
            "is in use by another run of umbra (its lock .umbra-lock is held); wait for it or choose another --out",
        )),
        Err(std::fs::TryLockError::Error(e)) => Err(io(&path)(e)),
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
    /// Umbra wrote, is refused (naming them) unless `claim.replace`.
    pub fn create(dir: &Path, claim: Claim) -> Result<Self, OutputError> {
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
        if let Err(e) = Self::admit(dir, claim, &earlier) {
            drop(lock);
            if !had_lock {
                let _ = std::fs::remove_file(dir.join(LOCK));
            }
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

    /// Whether a run of `claim` may write into `dir`, which holds what
    /// `earlier` records: a folder of another command's results, one with
    /// files no run of Umbra wrote, and one whose earlier run wrote a file
    /// this process read (the run would write it again) are refused,
    /// the first two unless the claim replaces them.
    fn admit(dir: &Path, claim: Claim, earlier: &Earlier) -> Result<(), OutputError> {
        let names: Vec<String> = earlier.files.iter().map(|f| f.path.clone()).collect();
        let by = earlier.command.as_deref().map_or_else(String::new, |c| format!(", written by `{c}`"));
        let inputs: Vec<String> =
            names.iter().filter(|n| crate::base::reads::was_read(&dir.join(n))).cloned().collect();
        if !inputs.is_empty() && earlier.kind == Some(claim.kind) {
            return Err(problem(
                dir,
                format!(
                    "holds {}{by}, whose file {} this run reads and would write again: copy it elsewhere first, or choose another --out",
                    claim.kind.describe(),
                    list(&inputs)
                ),
            ));
        }
        if claim.replace {
            return Ok(());
        }
        if let Some(kind) = earlier.kind.filter(|&k| k != claim.kind && !names.is_empty()) {
            return Err(problem(
                dir,
                format!(
                    "holds {}{by} ({}), not {}: choose another --out, or add --replace to replace it deliberately (files this run reads are kept)",
                    kind.describe(),
                    list(&names),
                    claim.kind.describe()
                ),
            ));
        }
        let foreign = foreign(dir, earlier, 10_000);
        if !foreign.is_empty() {
            return Err(problem(
                dir,
                format!(
                    "holds files no run of umbra wrote here ({}): choose another --out (a new or empty folder), or add --replace to write beside them (a file of the same name is replaced; none is deleted)",
                    list(&foreign)
                ),
            ));
        }
        Ok(())
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
    /// written.
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

mod state;
#[cfg(test)]
mod tests;

pub(crate) use state::FolderState;
