//! A view-projection matrix as `umbra depth --matrix` reads it: a
//! row-major 4×4 JSON array, each entry a finite f32.

use glam::Mat4;

/// Why a view-projection matrix could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MatrixError {
    /// Not JSON, or not an array of arrays of numbers.
    #[error("expected a row-major 4×4 JSON array of numbers: {0}")]
    Json(#[from] serde_json::Error),
    /// The wrong number of rows or columns.
    #[error("expected 4 rows of 4 numbers, found {rows} rows (row lengths {lengths:?})")]
    Shape {
        /// Rows found.
        rows: usize,
        /// Length of each row.
        lengths: Vec<usize>,
    },
    /// An entry is not a finite f32.
    #[error("entry [{row}][{col}] = {value} is not a finite f32")]
    NonFinite {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
        /// Its value.
        value: f64,
    },
}

/// Read a view-projection matrix written as a **row-major** 4×4 JSON array:
/// `clip = M · (x, y, z, 1)ᵀ`, so `M[r]` gives clip component `r` and a
/// translation sits in the last column. (glam stores columns, so this is
/// the transpose of its layout.)
///
/// # Errors
/// See [`MatrixError`].
pub fn parse_matrix(json: &str) -> Result<Mat4, MatrixError> {
    let rows: Vec<Vec<f64>> = serde_json::from_str(json)?;
    if rows.len() != 4 || rows.iter().any(|r| r.len() != 4) {
        return Err(MatrixError::Shape { rows: rows.len(), lengths: rows.iter().map(Vec::len).collect() });
    }
    let mut m = [[0f32; 4]; 4];
    for (row, values) in rows.iter().enumerate() {
        for (col, &value) in values.iter().enumerate() {
            #[allow(clippy::cast_possible_truncation, reason = "range checked against f32 next")]
            let f = value as f32;
            if !f.is_finite() {
                return Err(MatrixError::NonFinite { row, col, value });
            }
            m[row][col] = f;
        }
    }
    Ok(Mat4::from_cols_array_2d(&m).transpose())
}
