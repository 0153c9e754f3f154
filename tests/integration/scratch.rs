//! A test's scratch folder, removed however the test ends: shared by the
//! integration tests and the `umbra` command's tests (included by path).

/// A scratch directory of a test, removed with everything in it when the
/// value is dropped: when the test ends, passes or fails (a panic unwinds
/// through the drop).
pub struct Scratch(pub std::path::PathBuf);

impl std::ops::Deref for Scratch {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::path::Path> for Scratch {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
