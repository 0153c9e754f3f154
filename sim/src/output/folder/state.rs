//! What a run left in an output folder, read without writing: a finished
//! run, one under way, one abandoned, a corrupt one, or none.

use std::path::Path;

use super::{LOCK, MANIFEST, PENDING, RunManifest};

/// What a run left in a folder, as far as can be told without writing.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum FolderState {
    /// A finished run: its manifest, every file checked against it.
    Complete(RunManifest),
    /// A run under way: its record is pending and it holds the lock.
    Running,
    /// A run that stopped before finishing (killed, lost): its record is
    /// pending and nobody holds the lock.
    Abandoned,
    /// A manifest that its files no longer match, or that cannot be read:
    /// what is wrong.
    Corrupt(String),
    /// No run's folder (no manifest, no pending record).
    Absent,
}

impl FolderState {
    /// The state of `dir` (files each at most `max_bytes`). Reads only: a
    /// lock it takes to look is released at once.
    #[must_use]
    pub(crate) fn of(dir: &Path, max_bytes: u64) -> Self {
        if dir.join(MANIFEST).exists() {
            return match RunManifest::verify(dir, max_bytes) {
                Ok(m) => Self::Complete(m),
                Err(e) => Self::Corrupt(e.to_string()),
            };
        }
        Self::unfinished(dir).unwrap_or(Self::Absent)
    }

    /// [`Self::Running`] or [`Self::Abandoned`] when `dir` holds an
    /// unfinished run's record (a pending record, no manifest); `None`
    /// otherwise, without reading any other file.
    #[must_use]
    pub(crate) fn unfinished(dir: &Path) -> Option<Self> {
        if dir.join(MANIFEST).exists() || !dir.join(PENDING).exists() {
            return None;
        }
        let held = std::fs::File::open(dir.join(LOCK))
            .map(|f| matches!(f.try_lock_shared(), Err(std::fs::TryLockError::WouldBlock)))
            .unwrap_or(false);
        Some(if held { Self::Running } else { Self::Abandoned })
    }
}
