//! The meshes a scene file names: generated shapes and OBJ files, counted against the limits before they are built.

use std::path::Path;

use super::{Check, MeshFile, Problem, SceneError, shared_meshes};
use crate::input::exact::Exact;
use crate::input::limits::Limits;
use crate::world::mesh::Mesh;
use glam::Vec3;

/// The head's slices of a `figure` that does not say.
const FIGURE_HEAD: u32 = 16;

/// The triangles a generator makes, from its validated counts (0 for mesh
/// files, which are counted as they load).
pub(super) fn generated_triangles(c: &Check<'_>, key: &str, m: &MeshFile) -> Result<u64, SceneError> {
    let field = |f: &str| format!("{key}.{f}");
    let count = |f: &str, v: u32| c.count(&field(f), v).map(u64::from);
    Ok(match m {
        MeshFile::Obj(_) | MeshFile::Shared(_) | MeshFile::Gltf { .. } => 0,
        MeshFile::Arrays { triangles, .. } => u64::try_from(triangles.len()).unwrap_or(u64::MAX),
        MeshFile::Quad { .. } => 2,
        MeshFile::Box { .. } => 12,
        MeshFile::Table { .. } => 5 * 12,
        // Five boxes and a sphere of `head` slices, `head / 2 + 2` stacks.
        MeshFile::Figure { head, .. } => {
            let head = count("head", head.unwrap_or(FIGURE_HEAD))?.max(3);
            5 * 12 + 2 * head * (head / 2 + 1)
        }
        MeshFile::Ell { .. } => 20,
        MeshFile::Sphere { stacks, slices, .. } => {
            2 * count("slices", *slices)?.max(3) * (count("stacks", *stacks)?.max(2) - 1)
        }
        MeshFile::Torus { rings, sides, .. } => 2 * count("rings", *rings)?.max(3) * count("sides", *sides)?.max(3),
        MeshFile::Sheet { nx, ny, .. } => 2 * count("nx", *nx)? * count("ny", *ny)?,
    })
}

impl MeshFile {
    /// A mesh read from a file or given as arrays, not generated: its
    /// triangles are taken as they are (one of no area draws nothing).
    pub(super) const fn loaded(&self) -> bool {
        matches!(self, Self::Obj(_) | Self::Shared(_) | Self::Arrays { .. } | Self::Gltf { .. })
    }
}

/// A mesh given as vertex positions and triangles of vertex indices
/// (counter-clockwise seen from outside), each index checked.
fn arrays(c: &Check<'_>, key: &str, positions: &[Exact<3>], triangles: &[Exact<3, u32>]) -> Result<Mesh, SceneError> {
    if triangles.is_empty() {
        return Err(c.err(format!("{key}.triangles"), Problem::Missing("triangle")));
    }
    let positions = positions
        .iter()
        .enumerate()
        .map(|(i, &p)| c.vec3(&format!("{key}.positions[{i}]"), p))
        .collect::<Result<Vec<_>, _>>()?;
    let vertices = positions.len();
    for (triangle, Exact(t)) in triangles.iter().enumerate() {
        if let Some(&vertex) = t.iter().find(|&&v| v as usize >= vertices) {
            return Err(c.err(format!("{key}.triangles[{triangle}]"), Problem::BadIndex { triangle, vertex, vertices }));
        }
    }
    Ok(Mesh { positions, triangles: triangles.iter().map(|t| t.0).collect(), ..Mesh::default() })
}

pub(super) fn build_mesh(
    c: &Check<'_>,
    key: &str,
    m: &MeshFile,
    dir: &Path,
    limits: &Limits,
) -> Result<Mesh, SceneError> {
    let field = |f: &str| format!("{key}.{f}");
    Ok(match m {
        MeshFile::Obj(path) => Mesh::load_obj(&dir.join(path), limits).map_err(|e| c.err(key, Problem::Mesh(e)))?,
        MeshFile::Shared(name) => {
            let folder = shared_meshes();
            let path = folder.join(format!("{name}.obj"));
            if !path.is_file() {
                return Err(c.err(key, Problem::UnknownShared { name: name.clone(), folder }));
            }
            Mesh::load_obj(&path, limits).map_err(|e| c.err(key, Problem::Mesh(e)))?
        }
        MeshFile::Gltf { file, node } => super::gltf::gltf_mesh(c, key, (file, node.as_deref()), dir, limits)?,
        MeshFile::Arrays { positions, triangles } => arrays(c, &field("arrays"), positions, triangles)?,
        MeshFile::Box { min, max } => {
            let (lo, hi) = corners(c, &field, *min, *max)?;
            Mesh::cuboid(lo, hi)
        }
        MeshFile::Quad { corner, u, v } => {
            Mesh::quad(c.vec3(&field("corner"), *corner)?, c.vec3(&field("u"), *u)?, c.vec3(&field("v"), *v)?)
        }
        MeshFile::Sphere { center, radius, stacks, slices } => Mesh::sphere(
            c.vec3(&field("center"), *center)?,
            c.range(&field("radius"), *radius, 1e-6, 1e6)?,
            c.count(&field("stacks"), *stacks)?,
            c.count(&field("slices"), *slices)?,
        ),
        MeshFile::Torus { center, major, minor, rings, sides } => Mesh::torus(
            c.vec3(&field("center"), *center)?,
            c.range(&field("major"), *major, 1e-6, 1e6)?,
            // A tube wider than the ring's radius passes through itself.
            c.range(&field("minor"), *minor, 1e-6, major.min(1e6) * 0.999)?,
            c.count(&field("rings"), *rings)?,
            c.count(&field("sides"), *sides)?,
        ),
        MeshFile::Table { width, depth, height, top, leg } => {
            let (w, d) = (c.range(&field("width"), *width, 1e-6, 1e6)?, c.range(&field("depth"), *depth, 1e-6, 1e6)?);
            let h = c.range(&field("height"), *height, 1e-6, 1e6)?;
            // The top is part of the height, and two legs of a side must
            // not meet (their centres are a leg in from the edges).
            let top = c.range(&field("top"), *top, 1e-6, f64::from(h) * 0.999)?;
            let leg = c.range(&field("leg"), *leg, 1e-6, f64::from(w.min(d)) / 3.0 * 0.999)?;
            Mesh::table(w, d, h, top, leg)
        }
        MeshFile::Sheet { center, width, height, bend, nx, ny } => Mesh::sheet(
            c.vec3(&field("center"), *center)?,
            c.range(&field("width"), *width, 1e-6, 1e6)?,
            c.range(&field("height"), *height, 1e-6, 1e6)?,
            c.range(&field("bend"), *bend, -6.3, 6.3)?,
            c.count(&field("nx"), *nx)?,
            c.count(&field("ny"), *ny)?,
        ),
        MeshFile::Figure { feet, height, head } => Mesh::figure(
            c.vec3(&field("feet"), *feet)?,
            c.range(&field("height"), *height, 1e-6, 1e6)?,
            c.count(&field("head"), head.unwrap_or(FIGURE_HEAD))?.max(3),
        ),
        MeshFile::Ell { min, max, thickness } => {
            let (lo, hi) = corners(c, &field, *min, *max)?;
            // The upright and the base must leave a concave corner.
            let t =
                c.range(&field("thickness"), *thickness, 1e-9, f64::from((hi.x - lo.x).min(hi.y - lo.y)) * 0.999)?;
            Mesh::ell(lo, hi, t)
        }
    })
}

/// A generator's `min` and `max` corners, `max` above `min` on every axis
/// (a box of no room would have no volume: its faces would be of no area).
fn corners(
    c: &Check<'_>,
    field: &dyn Fn(&str) -> String,
    min: Exact<3>,
    max: Exact<3>,
) -> Result<(Vec3, Vec3), SceneError> {
    let (lo, hi) = (c.vec3(&field("min"), min)?, c.vec3(&field("max"), max)?);
    for (axis, (l, h)) in ['x', 'y', 'z'].into_iter().zip(lo.to_array().into_iter().zip(hi.to_array())) {
        if h <= l {
            return Err(c.err(field("max"), Problem::Corners { axis, min: l, max: h }));
        }
    }
    Ok((lo, hi))
}
