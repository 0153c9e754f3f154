//! The files this process has read as input, so that no output folder
//! removes or writes over one of them: a render whose model lies in its
//! output folder keeps it, whatever an earlier run's manifest lists. And
//! the folders beyond its own a model may read its buffers from
//! ([`allow_folder`]: the `umbra` command's `--allow-read`).
//!
//! Every input file is read through the limits (`Limits::read_file`; a
//! study's own rows, read back to merge, are not inputs and not noted),
//! which notes it here (its canonical path) as it reads it; an output
//! folder asks [`was_read`] before it removes or replaces a file.
//!
//! ```
//! use umbra_sim::Limits;
//! use umbra_sim::base::reads::was_read;
//! let dir = tempfile::tempdir()?;
//! let model = dir.path().join("model.obj");
//! std::fs::write(&model, "v 0 0 0\n")?;
//! assert!(!was_read(&model));
//! Limits::DEFAULT.read_file(&model)?;
//! assert!(was_read(&model) && was_read(&dir.path().join(".").join("model.obj")));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The canonical paths read so far.
static READ: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());

/// The folders (canonical) a model's buffers may come from besides its own.
static ALLOWED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Let every model read files in `dir` and below (a shared folder of
/// buffers or textures), besides its own folder.
///
/// # Errors
/// The OS error when `dir` does not exist or cannot be resolved.
pub fn allow_folder(dir: &Path) -> std::io::Result<()> {
    let canonical = std::fs::canonicalize(dir)?;
    if !canonical.is_dir() {
        return Err(std::io::Error::other(format!("{} is not a folder", dir.display())));
    }
    ALLOWED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(canonical);
    Ok(())
}

/// Whether `canonical` (a canonical path) lies in a folder
/// [`allow_folder`] allowed.
#[must_use]
pub(crate) fn allowed(canonical: &Path) -> bool {
    ALLOWED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).iter().any(|d| canonical.starts_with(d))
}

/// Note that `path` (an existing file) was read.
pub(crate) fn note(path: &Path) {
    if let Ok(canonical) = std::fs::canonicalize(path) {
        READ.lock().unwrap_or_else(std::sync::PoisonError::into_inner).insert(canonical);
    }
}

/// Whether this process read the file at `path` (the same file, by
/// whatever path it was named).
#[must_use]
pub fn was_read(path: &Path) -> bool {
    std::fs::canonicalize(path)
        .is_ok_and(|c| READ.lock().unwrap_or_else(std::sync::PoisonError::into_inner).contains(&c))
}
