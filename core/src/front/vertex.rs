//! The vertex unit: transform to light clip space, the trivial-accept test
//! against every clip plane, and the snap — with a small post-transform
//! cache, so a vertex shared by several triangles of an indexed mesh is
//! processed once, as vertex hardware does.

use glam::{Mat4, Vec3};

use crate::config::RasterConfig;
use crate::depth::DepthFormat;
use crate::front::clip::{ClipVertex, inside_all};
use crate::front::snap::{SnappedVertex, snap};

/// Entries of the default post-transform cache (direct-mapped by index): a
/// ring of a few hundred vertices, so that a strip of a mesh finds the
/// vertices the strip before it shared. A caller short of memory passes a
/// smaller [`VertexCache`]; results do not depend on its size.
pub const CACHE_ENTRIES: usize = 256;

/// A vertex after the vertex unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Processed {
    /// Light clip space, widened to f64.
    pub clip: ClipVertex,
    /// Every coordinate is finite.
    pub finite: bool,
    /// Snapped, when the vertex lies inside every clip plane (so a triangle
    /// of three such vertices needs no clipping).
    pub snapped: Option<SnappedVertex>,
}

impl Processed {
    /// Run one vertex through the unit.
    #[must_use]
    pub fn new<F: DepthFormat>(raster: &RasterConfig, transform: &Mat4, p: Vec3) -> Self {
        let v = *transform * p.extend(1.0);
        let clip = v.to_array().map(f64::from);
        let finite = v.is_finite();
        let snapped = if finite && inside_all(&clip, raster.guard()) { snap::<F>(raster, &clip) } else { None };
        Self { clip, finite, snapped }
    }
}

/// The vertex unit on vertex `index` of `positions` (a missing vertex is
/// NaN, and so rejected).
#[must_use]
pub(crate) fn process<F: DepthFormat>(
    raster: &RasterConfig,
    transform: &Mat4,
    positions: &[Vec3],
    index: u32,
) -> Processed {
    let p = positions.get(index as usize).copied().unwrap_or(Vec3::NAN);
    Processed::new::<F>(raster, transform, p)
}

/// The post-transform cache of one draw call, `N` entries direct-mapped by
/// vertex index (`N = 0`: none, every corner is processed). It keeps what
/// most triangles need, the snapped vertex of a vertex inside every clip
/// plane; the clipper's few triangles run their vertices through the unit
/// again. Its memory is `N · (4 + size_of::<Option<SnappedVertex>>())`
/// bytes: 36 an entry on Cortex-M and x86-64.
#[derive(Clone, Debug)]
pub struct VertexCache<const N: usize> {
    /// The cached vertex's index plus one; 0 for an empty entry (so that an
    /// empty cache is all zero bytes, and a `static` one costs no flash).
    tags: [u32; N],
    snapped: [Option<SnappedVertex>; N],
}

impl<const N: usize> Default for VertexCache<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> VertexCache<N> {
    /// An empty cache (filled as a draw call's vertices come).
    #[must_use]
    pub const fn new() -> Self {
        Self { tags: [0; N], snapped: [None; N] }
    }

    /// Forget every entry: the next draw call transforms anew.
    pub fn clear(&mut self) {
        self.tags.fill(0);
    }

    /// The snapped vertex `index`, from the cache or computed; `None` when
    /// it lies outside a clip plane or is not finite.
    #[inline]
    pub(crate) fn snapped<F: DepthFormat>(
        &mut self,
        raster: &RasterConfig,
        transform: &Mat4,
        positions: &[Vec3],
        index: u32,
    ) -> Option<SnappedVertex> {
        if N == 0 {
            return process::<F>(raster, transform, positions, index).snapped;
        }
        let slot = index as usize % N;
        // Index u32::MAX has no tag (its key wraps to "empty"): never cached.
        let key = index.wrapping_add(1);
        if let (Some(tag), Some(entry)) = (self.tags.get_mut(slot), self.snapped.get_mut(slot))
            && key != 0
        {
            if *tag != key {
                *entry = process::<F>(raster, transform, positions, index).snapped;
                *tag = key;
            }
            return *entry;
        }
        process::<F>(raster, transform, positions, index).snapped
    }
}
