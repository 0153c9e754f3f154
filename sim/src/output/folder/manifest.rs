//! The records a run leaves in its folder: `manifest.json` once it has
//! finished (every file with its size and SHA-256, the command line, the
//! version, the kind of results), `manifest.pending.json` while it is
//! under way; each read back and checked against the folder.

use std::path::{Component, Path};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::{RunKind, problem};
use crate::output::error::OutputError;

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
pub(super) struct Pending {
    /// Files an earlier or the current run may have left, each with the
    /// hash of the contents that run wrote (or was about to write).
    pub(super) files: Vec<FileRecord>,
    /// The results the run under way writes, and the command line (absent
    /// in records of earlier versions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) kind: Option<RunKind>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) command: Option<String>,
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
pub(super) fn checked_name<'a>(context: &Path, name: &'a str) -> Result<&'a Path, OutputError> {
    let path = Path::new(name);
    let plain = path.components().all(|c| matches!(c, Component::Normal(_)));
    if name.is_empty() || !plain || name.contains('\\') {
        return Err(problem(context, format!("`{name}` is not a file name inside the output folder")));
    }
    Ok(path)
}

/// Read a small regular file whole, refusing special files before opening
/// them.
pub(super) fn read_small(path: &Path) -> std::io::Result<Vec<u8>> {
    read_small_limit(path, MAX_MANIFEST_BYTES)
}

pub(super) fn read_small_limit(path: &Path, max: u64) -> std::io::Result<Vec<u8>> {
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
