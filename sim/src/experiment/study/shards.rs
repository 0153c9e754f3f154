//! Rows written as JSON lines, read back, and shards merged into one run.

use std::path::{Path, PathBuf};

use super::{Row, StudyError, sort_rows, write_outputs};
use crate::io::limits::Limits;
use crate::io::output::write_text;

/// The rows as JSON lines.
pub(super) fn jsonl(rows: &[Row]) -> String {
    let mut s = String::new();
    for r in rows {
        // A Row holds only strings, numbers, booleans and options: it always serialises.
        s.push_str(&serde_json::to_string(r).unwrap_or_default());
        s.push('\n');
    }
    s
}

/// Write a shard's partial `results.jsonl` into `dir`.
///
/// # Errors
/// [`StudyError::Output`].
pub fn write_partial(dir: &Path, rows: &[Row]) -> Result<(), StudyError> {
    write_text(&dir.join("results.jsonl"), &jsonl(rows))?;
    Ok(())
}

/// Read the rows of a `results.jsonl` (or of the one in a folder), a file
/// of at most [`Limits::max_file_bytes`].
///
/// # Errors
/// [`StudyError::Read`] or [`StudyError::Parse`] naming the file and line
/// (a line that is not UTF-8 is not a row).
pub fn read_rows(path: &Path, limits: &Limits) -> Result<Vec<Row>, StudyError> {
    let file = if path.is_dir() { path.join("results.jsonl") } else { path.to_owned() };
    let bytes = limits.read_file(&file).map_err(|source| StudyError::Read { path: file.clone(), source })?;
    let text = String::from_utf8_lossy(&bytes);
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|source| StudyError::Parse { path: file.clone(), line: i + 1, source })
        })
        .collect()
}

/// Read shard outputs (folders or files), check that no row appears twice,
/// and write the whole run's files into `out`. Returns the number of rows.
///
/// # Errors
/// See [`StudyError`].
pub fn merge(inputs: &[PathBuf], out: &Path, limits: &Limits) -> Result<usize, StudyError> {
    let mut rows = Vec::new();
    for p in inputs {
        rows.extend(read_rows(p, limits)?);
    }
    sort_rows(&mut rows);
    if let Some(w) = rows.windows(2).find(|w| (w[0].index, w[0].arch_index) == (w[1].index, w[1].arch_index)) {
        return Err(StudyError::Duplicate { index: w[0].index, arch: w[0].arch.clone() });
    }
    write_outputs(out, &rows)?;
    Ok(rows.len())
}
