//! Why an output file could not be written.

use std::path::PathBuf;

/// Why an output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// Creating or writing the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// Drawing a picture's text failed (no usable font).
    #[error("{path}: {problem}")]
    Font {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        problem: String,
    },
    /// The folder cannot take the file: a name outside it, a folder that
    /// is a file, a manifest that does not match.
    #[error("{path}: {problem}")]
    Folder {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// Encoding the image failed.
    #[error("{path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The encoder's error.
        source: image::ImageError,
    },
    /// A stop was requested before the run finished: its folder is left
    /// marked unfinished.
    #[error(transparent)]
    Stopped(#[from] crate::base::stop::Stopped),
}
