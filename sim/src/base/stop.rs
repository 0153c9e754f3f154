//! A request that the process stop its long work, made by a host (the
//! `umbra` command on Ctrl-C or SIGTERM) and read by the work between its
//! units: a study between configurations, a reference between pixels.
//! Work that sees it ends with [`Stopped`]; an output folder it was
//! writing keeps its pending record and gives up its lock, so the next run
//! finds it unfinished (`crate::output::folder`).
//!
//! The request is the process's, once made it stays: nothing in the
//! process finishes a run after it.
//!
//! ```
//! use umbra_sim::base::stop;
//! // No host asked: work runs to its end.
//! assert!(!stop::requested());
//! ```

use std::sync::atomic::{AtomicBool, Ordering};

/// Whether a stop was requested.
static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Ask every long work of this process to stop at its next unit of work.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Whether [`request`] was called.
#[must_use]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// `Err(Stopped)` once a stop was requested.
///
/// # Errors
/// [`Stopped`] after [`request`].
pub(crate) fn check() -> Result<(), Stopped> {
    if requested() { Err(Stopped) } else { Ok(()) }
}

/// Work that ended early because a stop was requested.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("stopped before finishing: a stop was requested")]
pub struct Stopped;
