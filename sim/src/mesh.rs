//! Triangle meshes: OBJ files through `tobj`, and procedural generators.
//!
//! Every generator winds triangles counter-clockwise seen from outside, so
//! `(b − a) × (c − a)` is the outward normal.

use std::f32::consts::TAU;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// Why a mesh could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The OBJ loader failed (missing file, unreadable, malformed).
    #[error("{path}: cannot load OBJ: {source}")]
    Load {
        /// The file.
        path: PathBuf,
        /// The loader's error.
        source: tobj::LoadError,
    },
    /// The file holds no triangles.
    #[error("{path}: no triangles")]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("{path}: vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Index of the vertex.
        vertex: usize,
    },
    /// A face names a vertex that does not exist.
    #[error("{path}: triangle {triangle} names a vertex that does not exist")]
    BadIndex {
        /// The file.
        path: PathBuf,
        /// Index of the triangle.
        triangle: usize,
    },
}

impl Mesh {
    /// Load every model of an OBJ file as one mesh (faces triangulated as fans).
    ///
    /// # Errors
    /// See [`MeshError`].
    pub fn load_obj(path: &Path) -> Result<Self, MeshError> {
        let opts = tobj::LoadOptions { triangulate: true, single_index: true, ..tobj::LoadOptions::default() };
        let (models, _) =
            tobj::load_obj(path, &opts).map_err(|source| MeshError::Load { path: path.to_owned(), source })?;
        let mut mesh = Self::default();
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

    /// Append another mesh.
    pub fn append(&mut self, other: &Self) {
        let base = u32::try_from(self.positions.len()).unwrap_or(u32::MAX);
        self.positions.extend_from_slice(&other.positions);
        self.triangles.extend(other.triangles.iter().map(|t| t.map(|i| base + i)));
    }

    /// The mesh with every position transformed.
    #[must_use]
    pub fn transformed(mut self, m: &Mat4) -> Self {
        for p in &mut self.positions {
            *p = m.transform_point3(*p);
        }
        self
    }

    /// Axis-aligned bounds `(min, max)`; `None` for an empty mesh.
    #[must_use]
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))))
    }

    fn push_quad(&mut self, a: Vec3, b: Vec3, c: Vec3, d: Vec3) {
        let base = u32::try_from(self.positions.len()).unwrap_or(u32::MAX);
        self.positions.extend_from_slice(&[a, b, c, d]);
        self.triangles.push([base, base + 1, base + 2]);
        self.triangles.push([base, base + 2, base + 3]);
    }

    /// A one-sided rectangle from `corner` spanning `u` and `v`; it faces `u × v`.
    #[must_use]
    pub fn quad(corner: Vec3, u: Vec3, v: Vec3) -> Self {
        let mut m = Self::default();
        m.push_quad(corner, corner + u, corner + u + v, corner + v);
        m
    }

    /// A closed axis-aligned box.
    #[must_use]
    pub fn cuboid(min: Vec3, max: Vec3) -> Self {
        let mut m = Self::default();
        let s = max - min;
        let (x, y, z) = (Vec3::X * s.x, Vec3::Y * s.y, Vec3::Z * s.z);
        m.append(&Self::quad(min, y, x)); // −z
        m.append(&Self::quad(min + z, x, y)); // +z
        m.append(&Self::quad(min, z, y)); // −x
        m.append(&Self::quad(min + x, y, z)); // +x
        m.append(&Self::quad(min, x, z)); // −y
        m.append(&Self::quad(min + y, z, x)); // +y
        m
    }

    /// A closed UV sphere.
    #[must_use]
    pub fn sphere(center: Vec3, radius: f32, stacks: u32, slices: u32) -> Self {
        let (stacks, slices) = (stacks.max(2), slices.max(3));
        let mut m = Self::default();
        #[allow(clippy::cast_precision_loss, reason = "small counts")]
        let point = |i: u32, j: u32| {
            let theta = std::f32::consts::PI * i as f32 / stacks as f32;
            let phi = TAU * (j % slices) as f32 / slices as f32;
            center + radius * Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin())
        };
        for i in 0..=stacks {
            for j in 0..slices {
                m.positions.push(point(i, j));
            }
        }
        let idx = |i: u32, j: u32| i * slices + j % slices;
        for i in 0..stacks {
            for j in 0..slices {
                let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
                if i != 0 {
                    m.triangles.push([a, b, d]);
                }
                if i != stacks - 1 {
                    m.triangles.push([b, c, d]);
                }
            }
        }
        m
    }

    /// A closed torus around the y axis: ring radius `major`, tube radius `minor`.
    #[must_use]
    pub fn torus(center: Vec3, major: f32, minor: f32, rings: u32, sides: u32) -> Self {
        let (rings, sides) = (rings.max(3), sides.max(3));
        let mut m = Self::default();
        for i in 0..rings {
            #[allow(clippy::cast_precision_loss, reason = "small counts")]
            let u = TAU * i as f32 / rings as f32;
            for j in 0..sides {
                #[allow(clippy::cast_precision_loss, reason = "small counts")]
                let v = TAU * j as f32 / sides as f32;
                let r = major + minor * v.cos();
                m.positions.push(center + Vec3::new(r * u.cos(), minor * v.sin(), -r * u.sin()));
            }
        }
        let idx = |i: u32, j: u32| (i % rings) * sides + j % sides;
        for i in 0..rings {
            for j in 0..sides {
                let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
                m.triangles.push([a, b, c]);
                m.triangles.push([a, c, d]);
            }
        }
        m
    }

    /// Wang & Molnar's table: a top on four legs standing on `y = 0`.
    #[must_use]
    pub fn table(width: f32, depth: f32, height: f32, top: f32, leg: f32) -> Self {
        let (hw, hd) = (width / 2.0, depth / 2.0);
        let mut m = Self::cuboid(Vec3::new(-hw, height - top, -hd), Vec3::new(hw, height, hd));
        for (sx, sz) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let c = Vec3::new(sx * (hw - leg), 0.0, sz * (hd - leg));
            m.append(&Self::cuboid(
                c - Vec3::new(leg / 2.0, 0.0, leg / 2.0),
                c + Vec3::new(leg / 2.0, height - top, leg / 2.0),
            ));
        }
        m
    }
}
