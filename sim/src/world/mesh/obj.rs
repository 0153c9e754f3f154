//! OBJ files through `tobj`: every record checked first, with its line,
//! polylines and points counted and left out, the limits applied before
//! anything is stored.

use std::path::Path;

use glam::Vec3;

use super::{Mesh, MeshError};
use crate::input::kind::FileKind;
use crate::input::limits::{FileError, LimitError, Limits};

/// OBJ records that are not surfaces, left out of a loaded mesh and counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Ignored {
    /// Line segments of `l` (polyline) records: `n − 1` for `n` vertices.
    pub segments: u64,
    /// Points of `p` records.
    pub points: u64,
}

impl Ignored {
    /// Nothing was left out.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.segments == 0 && self.points == 0
    }
}

impl std::fmt::Display for Ignored {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} polyline segments and {} points (not surfaces) ignored", self.segments, self.points)
    }
}

/// What [`check_obj`] counted.
struct ObjCounts {
    triangles: u64,
    ignored: Ignored,
}

/// Check every record of an OBJ file the loader reads (vertices, texture
/// coordinates, normals, faces, polylines, points, materials), so that a
/// truncated or foreign file is reported with its line (the loader reports
/// none), and count the triangles its faces make (a face of `n` corners
/// makes `n − 2`) and the segments and points it holds besides.
#[allow(clippy::too_many_lines, reason = "one arm per record kind, in the order of the OBJ specification")]
fn check_obj(path: &Path, bytes: &[u8]) -> Result<ObjCounts, MeshError> {
    let fail = |line: usize, problem: String| MeshError::Syntax { path: path.to_owned(), line, problem };
    // Vertices, texture coordinates and normals defined so far.
    let (mut vertices, mut texcoords, mut normals) = (0usize, 0usize, 0usize);
    let mut counts = ObjCounts { triangles: 0, ignored: Ignored::default() };
    let numbers = |words: &[&str]| words.iter().all(|w| w.parse::<f32>().is_ok());
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let text = std::str::from_utf8(raw).map_err(|_| fail(line, "not text".into()))?;
        let mut words = text.split_whitespace();
        let record = words.next();
        let rest: Vec<&str> = words.collect();
        match record {
            Some("v") => {
                // x y z, then nothing, a weight w ≠ 0, or an r g b colour.
                let w = rest.get(3).and_then(|w| w.parse::<f32>().ok());
                let ok = match rest.len() {
                    3 | 6 => numbers(&rest),
                    4 => numbers(&rest) && w != Some(0.0),
                    _ => false,
                };
                if !ok {
                    return Err(fail(line, format!("a vertex is x y z [w ≠ 0 | r g b]: `{}`", text.trim())));
                }
                vertices += 1;
            }
            Some("vt") => {
                if rest.len() < 2 || !numbers(&rest[..2]) {
                    return Err(fail(line, format!("a texture coordinate needs two numbers: `{}`", text.trim())));
                }
                texcoords += 1;
            }
            Some("vn") => {
                if rest.len() < 3 || !numbers(&rest[..3]) {
                    return Err(fail(line, format!("a normal needs three numbers: `{}`", text.trim())));
                }
                normals += 1;
            }
            Some(kind @ ("f" | "l" | "p")) => {
                let least = match kind {
                    "f" => 3,
                    "l" => 2,
                    _ => 1,
                };
                if rest.len() < least {
                    return Err(fail(line, format!("`{kind}` needs at least {least} vertices: `{}`", text.trim())));
                }
                // An index (1-based, or negative: back from the last one)
                // must name an element defined above it.
                let names = |index: &str, defined: usize| {
                    index
                        .parse::<i64>()
                        .is_ok_and(|v| v != 0 && usize::try_from(v.unsigned_abs()).is_ok_and(|v| v <= defined))
                };
                for c in &rest {
                    let parts: Vec<&str> = c.split('/').collect();
                    if parts.len() > 3 {
                        return Err(fail(line, format!("corner `{c}` is not v, v/vt, v//vn or v/vt/vn")));
                    }
                    if !names(parts[0], vertices) {
                        return Err(fail(line, format!("corner `{c}` names no vertex defined above it")));
                    }
                    for (part, defined, what) in [(1, texcoords, "texture coordinate"), (2, normals, "normal")] {
                        if parts.get(part).is_some_and(|i| !i.is_empty() && !names(i, defined)) {
                            return Err(fail(line, format!("corner `{c}` names no {what} defined above it")));
                        }
                    }
                }
                let n = u64::try_from(rest.len()).unwrap_or(u64::MAX);
                match kind {
                    "f" => counts.triangles += n - 2,
                    "l" => counts.ignored.segments += n - 1,
                    _ => counts.ignored.points += n,
                }
            }
            Some("usemtl") if rest.is_empty() => return Err(fail(line, "`usemtl` names no material".into())),
            _ => {}
        }
    }
    Ok(counts)
}

impl Mesh {
    /// Load every model of an OBJ file as one mesh (faces triangulated as
    /// fans) within `limits`: a file larger than
    /// [`Limits::max_file_bytes`] is rejected before it is read, and one whose
    /// faces, polyline segments and points together are more than
    /// [`Limits::max_triangles`] before any triangle is stored. Polylines
    /// (`l`) and points (`p`) are not surfaces: they are left out and
    /// counted in [`Mesh::ignored`]. Material libraries (`mtllib`) are not
    /// read.
    ///
    /// # Errors
    /// See [`MeshError`]; every malformed record is named with its line.
    pub fn load_obj(path: &Path, limits: &Limits) -> Result<Self, MeshError> {
        let bytes = limits.read_file(path).map_err(|e| match e {
            FileError::Io(source) => MeshError::Read { path: path.to_owned(), source },
            FileError::NotAFile => MeshError::NotAFile { path: path.to_owned() },
            FileError::Limit(source) => MeshError::Limit { path: path.to_owned(), source },
        })?;
        if let Some(kind) = FileKind::of(&bytes).filter(|&k| k != FileKind::Obj) {
            return Err(MeshError::Kind { path: path.to_owned(), kind });
        }
        let counts = check_obj(path, &bytes)?;
        let primitives = counts.triangles.saturating_add(counts.ignored.segments).saturating_add(counts.ignored.points);
        let over = |source| MeshError::Limit { path: path.to_owned(), source };
        limits.check_triangles(counts.triangles).map_err(over)?;
        if primitives > limits.max_triangles {
            let (triangles, max) = (counts.triangles, limits.max_triangles);
            return Err(over(LimitError::Primitives { primitives, triangles, max }));
        }
        // The loader would fill polylines as faces: blank their lines (the
        // line count stays, so the checked lines are the loaded ones).
        let surfaces: Vec<u8> = if counts.ignored.segments == 0 {
            bytes
        } else {
            let mut out = Vec::with_capacity(bytes.len());
            for (k, raw) in bytes.split(|&b| b == b'\n').enumerate() {
                if k > 0 {
                    out.push(b'\n');
                }
                let polyline = raw.split(u8::is_ascii_whitespace).find(|w| !w.is_empty()) == Some(b"l".as_slice());
                if !polyline {
                    out.extend_from_slice(raw);
                }
            }
            out
        };
        let opts = tobj::LoadOptions { triangulate: true, single_index: true, ..tobj::LoadOptions::default() };
        let (models, _) = tobj::load_obj_buf(&mut surfaces.as_slice(), &opts, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|source| MeshError::Load { path: path.to_owned(), source })?;
        let mut mesh = Self { ignored: counts.ignored, ..Self::default() };
        for m in models {
            let base = u32::try_from(mesh.positions.len()).unwrap_or(u32::MAX);
            for p in m.mesh.positions.chunks_exact(3) {
                if !p.iter().all(|c| c.is_finite()) {
                    return Err(MeshError::NonFinite { path: path.to_owned(), vertex: mesh.positions.len() });
                }
                mesh.positions.push(Vec3::new(p[0], p[1], p[2]));
            }
            for t in m.mesh.indices.chunks_exact(3) {
                mesh.triangles.push([base + t[0], base + t[1], base + t[2]]);
            }
        }
        if mesh.triangles.is_empty() {
            return Err(MeshError::Empty { path: path.to_owned() });
        }
        let n = mesh.positions.len();
        if let Some(triangle) = mesh.triangles.iter().position(|t| t.iter().any(|&i| i as usize >= n)) {
            return Err(MeshError::BadIndex { path: path.to_owned(), triangle });
        }
        Ok(mesh)
    }
}
