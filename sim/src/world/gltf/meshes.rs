//! A glTF mesh as triangles: each primitive's triangles (strips and fans
//! numbered as the specification says; points and lines counted and left
//! out), each keeping only the vertices it draws, placed by a node's
//! transform; and the memory reading the meshes takes, estimated from the
//! counts the file declares before any buffer is read.

use glam::{DMat4, Vec3};
use gltf::mesh::Mode;

use super::{Fault, GltfProblem, accessors, buffers, nodes};
use crate::input::limits::Footprint;
use crate::world::mesh::{Ignored, Mesh};

/// The triangles `n` vertices make in `mode`, and the segments and points
/// it makes that are not surfaces.
pub(super) const fn primitives(mode: Mode, n: u64) -> (u64, Ignored) {
    let none = Ignored { segments: 0, points: 0 };
    match mode {
        Mode::Triangles => (n / 3, none),
        Mode::TriangleStrip | Mode::TriangleFan => (n.saturating_sub(2), none),
        Mode::Points => (0, Ignored { segments: 0, points: n }),
        Mode::Lines => (0, Ignored { segments: n / 2, points: 0 }),
        Mode::LineStrip => (0, Ignored { segments: n.saturating_sub(1), points: 0 }),
        Mode::LineLoop => (0, Ignored { segments: if n > 1 { n } else { 0 }, points: 0 }),
    }
}

/// The vertex count a primitive draws: its indices', else its positions'.
pub(super) fn drawn(p: &gltf::Primitive<'_>) -> u64 {
    p.indices().or_else(|| p.get(&gltf::Semantic::Positions)).map_or(0, |a| a.count() as u64)
}

/// The indices of `order` that `mode` draws triangles from (a list's
/// whole triples, a strip's or fan's every index once there are three).
fn drawn_indices(mode: Mode, order: &[u32]) -> &[u32] {
    match mode {
        Mode::Triangles => &order[..order.len() / 3 * 3],
        _ if order.len() >= 3 => order,
        _ => &[],
    }
}

/// `points` cut to the vertices `used` names (each index below
/// `points.len()`), in their order, and each of `used` renumbered to
/// match: a primitive holds only the vertices it draws (all of them, bit
/// for bit, when it draws every one).
fn compacted(points: &[[f32; 3]], used: &mut [u32]) -> Vec<Vec3> {
    let mut remap = vec![u32::MAX; points.len()];
    for &i in used.iter() {
        remap[i as usize] = 0;
    }
    let mut kept = Vec::new();
    for (slot, p) in remap.iter_mut().zip(points) {
        if *slot == 0 {
            *slot = u32::try_from(kept.len()).unwrap_or(u32::MAX);
            kept.push(Vec3::from_array(*p));
        }
    }
    for i in used.iter_mut() {
        *i = remap.get(*i as usize).copied().unwrap_or(u32::MAX);
    }
    kept
}

/// Mesh `m` in its own space: every triangle primitive's triangles (strips
/// and fans made triangles as the glTF specification numbers them), with
/// the vertices they use, its other primitives counted in
/// [`Mesh::ignored`]; at most `max` vertices an accessor.
pub(super) fn local_mesh(buffers: &[Vec<u8>], m: &gltf::Mesh<'_>, max: usize) -> Result<Mesh, Fault> {
    let mut mesh = Mesh::default();
    for p in m.primitives() {
        let path = format!("meshes[{}].primitives[{}]", m.index(), p.index());
        let (_, ignored) = primitives(p.mode(), drawn(&p));
        mesh.ignored.segments += ignored.segments;
        mesh.ignored.points += ignored.points;
        if !matches!(p.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            continue;
        }
        let Some(positions) = p.get(&gltf::Semantic::Positions) else {
            let problem = "has no POSITION attribute (a Draco-compressed primitive is refused by name when required)";
            return Err((path, GltfProblem::Accessor(problem.into())));
        };
        let points = accessors::positions(buffers, &positions, max)?;
        let mut order: Vec<u32> = match p.indices() {
            Some(a) => accessors::indices(buffers, &a, max)?,
            None => (0..u32::try_from(points.len()).unwrap_or(u32::MAX)).collect(),
        };
        if let Some(element) = order.iter().position(|i| *i as usize >= points.len()) {
            return Err((format!("{path}.indices"), GltfProblem::Index { element, vertices: points.len() }));
        }
        order.truncate(drawn_indices(p.mode(), &order).len());
        let kept = compacted(&points, &mut order);
        drop(points);
        let base = u32::try_from(mesh.positions.len()).unwrap_or(u32::MAX);
        mesh.positions.extend(kept);
        let v = |k: usize| base + order[k];
        match p.mode() {
            Mode::TriangleStrip => {
                mesh.triangles.extend((0..order.len().saturating_sub(2)).map(|i| {
                    let odd = i % 2;
                    [v(i), v(i + 1 + odd), v(i + 2 - odd)]
                }));
            }
            Mode::TriangleFan => {
                mesh.triangles.extend((0..order.len().saturating_sub(2)).map(|i| [v(i + 1), v(i + 2), v(0)]));
            }
            _ => mesh.triangles.extend(order.chunks_exact(3).map(|t| [base + t[0], base + t[1], base + t[2]])),
        }
    }
    Ok(mesh)
}

/// What reading the meshes the chosen nodes place takes, from the counts
/// the file declares: its JSON held, its buffers, the nodes walked, each
/// mesh decoded once (its accessors' positions and indices, the vertices
/// renumbered) and kept, and each placement's copy twice over (the scene's
/// objects and, for a scene file's mesh, their merge); an upper bound of
/// the read's peak, checked against [`Limits::max_memory`] before a buffer
/// is read.
pub(super) fn estimate(document: &gltf::Document, chosen: &[&nodes::Placed], json_bytes: u64) -> u64 {
    let all: Vec<gltf::Node<'_>> = document.nodes().collect();
    let buffers: u64 = document.buffers().map(|b| b.length() as u64).sum();
    let mut decoded = vec![false; document.meshes().len()];
    let mut total = buffers::parse_footprint(json_bytes)
        .saturating_add(buffers)
        .saturating_add((all.len() as u64).saturating_mul(Footprint::PER_GLTF_NODE));
    for w in chosen {
        let Some(m) = all[w.node].mesh() else { continue };
        let first = !std::mem::replace(&mut decoded[m.index()], true);
        for p in m.primitives() {
            if !matches!(p.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
                continue;
            }
            let vertices = p.get(&gltf::Semantic::Positions).map_or(0, |a| a.count() as u64);
            let indices = drawn(&p);
            let (triangles, _) = primitives(p.mode(), indices);
            let kept = vertices
                .min(indices)
                .saturating_mul(Footprint::PER_VERTEX)
                .saturating_add(triangles.saturating_mul(Footprint::PER_MESH_TRIANGLE));
            if first {
                total = total
                    .saturating_add(vertices.saturating_mul(Footprint::PER_VERTEX_DECODED))
                    .saturating_add(indices.saturating_mul(Footprint::PER_INDEX_DECODED))
                    .saturating_add(kept);
            }
            total = total.saturating_add(kept.saturating_mul(2));
        }
    }
    total
}

/// `mesh` placed by `world`: positions transformed in f64 and rounded to
/// f32 (an identity leaves them as they are, bit for bit), the winding
/// turned back where the transform mirrors.
pub(super) fn placed(mesh: &Mesh, world: &DMat4) -> Mesh {
    if *world == DMat4::IDENTITY {
        return mesh.clone();
    }
    #[allow(clippy::cast_possible_truncation, reason = "the f32 the pipeline takes; placed coordinates are checked")]
    let positions = mesh.positions.iter().map(|p| world.transform_point3(p.as_dvec3()).as_vec3()).collect();
    let mirrored = world.determinant() < 0.0;
    let triangles =
        if mirrored { mesh.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect() } else { mesh.triangles.clone() };
    Mesh { positions, triangles, ignored: mesh.ignored }
}
