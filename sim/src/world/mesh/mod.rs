//! Triangle meshes: OBJ files through `tobj`, and procedural generators.
//!
//! Every generator winds triangles counter-clockwise seen from outside, so
//! `(b − a) × (c − a)` is the outward normal.
//!
//! ```
//! use umbra_sim::Mesh;
//! use umbra_sim::glam::Vec3;
//! // A unit cube: four corners and two triangles a face, closed once its
//! // corners are welded by position.
//! let cube = Mesh::cuboid(Vec3::ZERO, Vec3::ONE);
//! assert_eq!((cube.positions.len(), cube.triangles.len()), (24, 12));
//! assert!(cube.is_closed());
//! assert!(!Mesh::quad(Vec3::ZERO, Vec3::X, Vec3::Y).is_closed());
//! ```

use std::f32::consts::TAU;
use std::path::PathBuf;

use glam::{Mat4, Vec3};

use crate::input::limits::LimitError;

mod obj;

pub use obj::Ignored;

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// What an OBJ file held besides surfaces, left out.
    pub ignored: Ignored,
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
    /// The file is another kind than a mesh.
    #[error("{path}: {} (not an OBJ mesh): {}", kind.what(), kind.read_by())]
    Kind {
        /// The file.
        path: PathBuf,
        /// What it is.
        kind: crate::input::kind::FileKind,
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
    /// The file cannot be read (missing, unreadable).
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A line of the file is not OBJ (a truncated record, a bad number, bytes
    /// that are not text).
    #[error("{path}:{line}: {problem}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        problem: String,
    },
    /// The path is a directory, a device or a pipe.
    #[error("{path}: not a regular file")]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// The file or its triangle count is beyond the [`Limits`](crate::input::limits::Limits).
    #[error("{path}: {source}")]
    Limit {
        /// The file.
        path: PathBuf,
        /// Which limit.
        source: LimitError,
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
    /// Append another mesh.
    pub(crate) fn append(&mut self, other: &Self) {
        let base = u32::try_from(self.positions.len()).unwrap_or(u32::MAX);
        self.positions.extend_from_slice(&other.positions);
        self.triangles.extend(other.triangles.iter().map(|t| t.map(|i| base + i)));
        self.ignored.segments += other.ignored.segments;
        self.ignored.points += other.ignored.points;
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

    /// A closed UV sphere: one vertex at each pole, `stacks − 1` rings of
    /// `slices` vertices between them.
    #[must_use]
    pub fn sphere(center: Vec3, radius: f32, stacks: u32, slices: u32) -> Self {
        let (stacks, slices) = (stacks.max(2), slices.max(3));
        let mut m = Self::default();
        m.positions.push(center + Vec3::Y * radius);
        for i in 1..stacks {
            #[allow(clippy::cast_precision_loss, reason = "small counts")]
            let theta = std::f32::consts::PI * i as f32 / stacks as f32;
            for j in 0..slices {
                #[allow(clippy::cast_precision_loss, reason = "small counts")]
                let phi = TAU * j as f32 / slices as f32;
                m.positions
                    .push(center + radius * Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin()));
            }
        }
        let bottom = 1 + (stacks - 1) * slices;
        m.positions.push(center - Vec3::Y * radius);
        let ring = |i: u32, j: u32| 1 + (i - 1) * slices + j % slices;
        for j in 0..slices {
            m.triangles.push([0, ring(1, j), ring(1, j + 1)]);
            m.triangles.push([ring(stacks - 1, j), bottom, ring(stacks - 1, j + 1)]);
        }
        for i in 1..stacks - 1 {
            for j in 0..slices {
                let (a, b, c, d) = (ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
                m.triangles.push([a, b, d]);
                m.triangles.push([b, c, d]);
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

    /// Whether the surface is closed and consistently wound: with vertices
    /// welded by position, every directed edge appears once and its reverse
    /// once (so back- and front-face culling are meaningful).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        use std::collections::HashMap;
        // `+ 0.0` turns −0 into +0, so the two weld.
        let key = |p: Vec3| p.to_array().map(|c| (c + 0.0).to_bits());
        let mut weld: HashMap<[u32; 3], usize> = HashMap::new();
        let ids: Vec<usize> = self
            .positions
            .iter()
            .map(|&p| {
                let n = weld.len();
                *weld.entry(key(p)).or_insert(n)
            })
            .collect();
        let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
        for t in &self.triangles {
            let v = t.map(|i| ids.get(i as usize).copied().unwrap_or(usize::MAX));
            for k in 0..3 {
                *edges.entry((v[k], v[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        !edges.is_empty() && edges.iter().all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    /// An open, curved, two-sided sheet: an arc of `bend` radians of a
    /// cylinder about the y axis, `width` long and `height` tall, centred at
    /// `center` (a flat rectangle when `bend` is 0).
    #[must_use]
    pub fn sheet(center: Vec3, width: f32, height: f32, bend: f32, nx: u32, ny: u32) -> Self {
        let (nx, ny) = (nx.max(1), ny.max(1));
        let mut m = Self::default();
        for j in 0..=ny {
            for i in 0..=nx {
                #[allow(clippy::cast_precision_loss, reason = "small counts")]
                let (u, v) = (i as f32 / nx as f32 - 0.5, j as f32 / ny as f32 - 0.5);
                let p = if bend.abs() < 1e-6 {
                    Vec3::new(u * width, v * height, 0.0)
                } else {
                    let r = width / bend;
                    let a = u * bend;
                    Vec3::new(r * a.sin(), v * height, r * (1.0 - a.cos()))
                };
                m.positions.push(center + p);
            }
        }
        let at = |i: u32, j: u32| j * (nx + 1) + i;
        for j in 0..ny {
            for i in 0..nx {
                m.triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                m.triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        m
    }

    /// A simple character standing on `y = 0` at `feet`, `height` tall: two
    /// legs, a body and arms as boxes, a head as a sphere of `head` slices
    /// and `head / 2 + 2` stacks — each part closed.
    #[must_use]
    pub fn figure(feet: Vec3, height: f32, head: u32) -> Self {
        let u = height / 8.0;
        let part = |lo: Vec3, hi: Vec3| Self::cuboid(feet + lo * u, feet + hi * u);
        let mut m = part(Vec3::new(-0.9, 0.0, -0.4), Vec3::new(-0.1, 3.6, 0.4));
        m.append(&part(Vec3::new(0.1, 0.0, -0.4), Vec3::new(0.9, 3.6, 0.4)));
        m.append(&part(Vec3::new(-1.1, 3.7, -0.6), Vec3::new(1.1, 6.3, 0.6)));
        m.append(&part(Vec3::new(-1.7, 3.9, -0.3), Vec3::new(-1.2, 6.2, 0.3)));
        m.append(&part(Vec3::new(1.2, 3.9, -0.3), Vec3::new(1.7, 6.2, 0.3)));
        m.append(&Self::sphere(feet + Vec3::new(0.0, 7.1, 0.0) * u, 0.8 * u, head / 2 + 2, head));
        m
    }

    /// Weiskopf & Ertl's L (their Figure 5) as one closed solid: a profile in
    /// the x–y plane, a base `thickness` tall along the bottom of the box
    /// `min`–`max` and an upright `thickness` wide at its +x end, extruded
    /// along z. The inner crease is a concave edge of a single surface, not
    /// two boxes touching, so the light pass sees one object with one back.
    #[must_use]
    pub fn ell(min: Vec3, max: Vec3, thickness: f32) -> Self {
        let (x0, y0, x1, y1, t) = (min.x, min.y, max.x, max.y, thickness);
        // Counter-clockwise seen from +z; vertex 4 is the reflex corner.
        let profile = [(x0, y0), (x1, y0), (x1, y1), (x1 - t, y1), (x1 - t, y0 + t), (x0, y0 + t)];
        let mut m = Self::default();
        for z in [min.z, max.z] {
            m.positions.extend(profile.iter().map(|&(x, y)| Vec3::new(x, y, z)));
        }
        // Each cap a fan from the reflex corner, which sees every vertex;
        // the back cap (z = min) wound the other way.
        for k in [5, 0, 1, 2] {
            let next = (k + 1) % 6;
            m.triangles.push([4, next, k]);
            m.triangles.push([10, 6 + k, 6 + next]);
        }
        // The six sides, each facing out of the profile.
        for k in 0..6 {
            let next = (k + 1) % 6;
            m.triangles.push([k, next, 6 + next]);
            m.triangles.push([k, 6 + next, 6 + k]);
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
