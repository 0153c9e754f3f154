//! The geometry front end: the vertex unit, the clipper, the snap and
//! triangle setup — everything a triangle goes through before binning.
//!
//! ```text
//! triangle ─► vertex unit (cache) ─► trivially inside? ── yes ──► setup ─► piece
//!                                         └─ no ─► clip ─► fan ─► snap ─► setup ─► pieces
//! ```
//!
//! Each submitted triangle becomes zero or more set-up pieces (more than one
//! only when the clipper cuts it) or a rejection, reported in submission
//! order through a callback. The front end keeps no state across triangles
//! but the vertex cache, so a mesh can be split into runs of triangles and
//! each run set up on its own (on another core, say): with the same first
//! ids, the pieces are the same, bit for bit.

pub mod clip;
mod plane;
pub mod setup;
pub mod snap;
pub mod vertex;

use glam::{Mat4, Vec3};

use crate::config::{CullMode, RasterConfig};
use crate::depth::DepthFormat;
use crate::front::clip::{ClipVertex, Clipped, Polygon, clip_triangle};
use crate::front::setup::Setup;
use crate::front::snap::{SnappedVertex, snap};
use crate::front::vertex::{VertexCache, process};
use crate::probe::RejectReason;

/// What the front end reports, in submission order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output<'s> {
    /// A triangle entered the front end.
    Submitted,
    /// A piece of it is set up, ready to bin (lent: the receiver copies it
    /// where it keeps setups).
    Setup(&'s Setup),
    /// It (or a piece of it) produces nothing, and why.
    Rejected(RejectReason),
}

/// Check every index of a triangle list before anything is drawn.
///
/// # Errors
/// [`SubmitError::IndexOutOfRange`] for the first triangle naming a vertex
/// that does not exist.
pub fn check_indices(vertices: usize, triangles: &[[u32; 3]]) -> Result<(), SubmitError> {
    for (triangle, t) in triangles.iter().enumerate() {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= vertices) {
            return Err(SubmitError::IndexOutOfRange { triangle, index, vertices });
        }
    }
    Ok(())
}

/// Run an indexed mesh through the front end: positions in object space,
/// `transform` to light clip space (f32, the vertex unit), triangle ids
/// counting up from `first_id`. Indices must have passed
/// [`check_indices`]; a missing vertex is taken as NaN (and rejected).
/// `cache` is cleared first (a draw call's vertices are its own).
#[allow(clippy::too_many_arguments, reason = "one draw call's state")]
pub fn mesh<F: DepthFormat, const N: usize>(
    raster: &RasterConfig,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    transform: &Mat4,
    cull: CullMode,
    first_id: u32,
    cache: &mut VertexCache<N>,
    out: &mut impl FnMut(Output<'_>),
) {
    cache.clear();
    let mut id = first_id;
    for t in triangles {
        out(Output::Submitted);
        // Most triangles lie inside every clip plane: their snapped vertices
        // are all they need from the cache.
        if let [Some(a), Some(b), Some(c)] = t.map(|i| cache.snapped::<F>(raster, transform, positions, i)) {
            set_up(raster, [a, b, c], cull, id, out);
        } else {
            // Through the vertex unit again (the same values: the unit is a
            // function of the position), whole, for the clipper.
            let [a, b, c] = t.map(|i| process::<F>(raster, transform, positions, i));
            if a.finite && b.finite && c.finite {
                clip::<F>(raster, &[a.clip, b.clip, c.clip], cull, id, out);
            } else {
                out(Output::Rejected(RejectReason::NonFinite));
            }
        }
        id = id.wrapping_add(1);
    }
}

/// Clip a triangle of finite vertices, then snap and set up each piece.
pub fn clip<F: DepthFormat>(
    raster: &RasterConfig,
    v: &[ClipVertex; 3],
    cull: CullMode,
    id: u32,
    out: &mut impl FnMut(Output<'_>),
) {
    let mut p = Polygon::new();
    match clip_triangle(v, raster.guard(), &mut p) {
        Clipped::Inside => snap_and_set_up::<F>(raster, v, cull, id, out),
        Clipped::Polygon => {
            for i in 1..p.len().saturating_sub(1) {
                snap_and_set_up::<F>(raster, &[p[0], p[i], p[i + 1]], cull, id, out);
            }
        }
        Clipped::Outside => out(Output::Rejected(RejectReason::Clipped)),
    }
}

fn snap_and_set_up<F: DepthFormat>(
    raster: &RasterConfig,
    v: &[ClipVertex; 3],
    cull: CullMode,
    id: u32,
    out: &mut impl FnMut(Output<'_>),
) {
    match (snap::<F>(raster, &v[0]), snap::<F>(raster, &v[1]), snap::<F>(raster, &v[2])) {
        (Some(a), Some(b), Some(c)) => set_up(raster, [a, b, c], cull, id, out),
        _ => out(Output::Rejected(RejectReason::NonFinite)),
    }
}

fn set_up(raster: &RasterConfig, v: [SnappedVertex; 3], cull: CullMode, id: u32, out: &mut impl FnMut(Output<'_>)) {
    match Setup::covering(raster, v, cull, id) {
        Ok(s) => out(Output::Setup(&s)),
        Err(reason) => out(Output::Rejected(reason)),
    }
}

/// A triangle list that cannot be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SubmitError {
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        /// Position of the triangle in the index list.
        triangle: usize,
        /// The index it holds.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
}

impl core::fmt::Display for SubmitError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::IndexOutOfRange { triangle, index, vertices } => {
                write!(f, "triangle {triangle} names vertex {index}, but there are only {vertices} vertices")
            }
        }
    }
}

impl core::error::Error for SubmitError {}
