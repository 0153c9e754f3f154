//! The vertex unit: transform to light clip space, the trivial-accept test
//! against every clip plane, and the snap — with a small post-transform
//! cache, so a vertex shared by several triangles of an indexed mesh is
//! processed once, as vertex hardware does.

use glam::{Mat4, Vec3};

use crate::clip::{ClipVertex, inside_all};
use crate::config::RasterConfig;
use crate::depth::DepthFormat;
use crate::snap::SnappedVertex;

/// Entries of the post-transform cache (direct-mapped by index).
pub const CACHE_ENTRIES: usize = 32;

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
        let snapped = if finite && inside_all(&clip, raster.guard()) { raster.snap::<F>(&clip) } else { None };
        Self { clip, finite, snapped }
    }
}

/// The post-transform cache of one draw call.
pub(crate) struct VertexCache {
    tags: [u32; CACHE_ENTRIES],
    entries: [Processed; CACHE_ENTRIES],
}

impl VertexCache {
    pub(crate) const fn new() -> Self {
        const EMPTY: Processed = Processed { clip: [0.0; 4], finite: false, snapped: None };
        Self { tags: [u32::MAX; CACHE_ENTRIES], entries: [EMPTY; CACHE_ENTRIES] }
    }

    /// The processed vertex `index`, from the cache or computed (a copy:
    /// the next fetch may evict it).
    #[inline]
    pub(crate) fn fetch<F: DepthFormat>(
        &mut self,
        raster: &RasterConfig,
        transform: &Mat4,
        positions: &[Vec3],
        index: u32,
    ) -> Processed {
        let slot = index as usize % CACHE_ENTRIES;
        if self.tags[slot] != index {
            let p = positions.get(index as usize).copied().unwrap_or(Vec3::NAN);
            self.entries[slot] = Processed::new::<F>(raster, transform, p);
            self.tags[slot] = index;
        }
        self.entries[slot]
    }
}
