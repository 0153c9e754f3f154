//! A probe that totals the core's events, overall and per tile.

use serde::Serialize;
use umbra_core::probe::{Buffer, CullLevel, FlushReason, RejectReason};
use umbra_core::{Event, Probe, RasterConfig, TileId};

/// Event totals of a pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Totals {
    /// Triangles submitted.
    pub submitted: u64,
    /// Rejected: non-finite vertices.
    pub rejected_non_finite: u64,
    /// Rejected: zero area on the subpixel grid.
    pub rejected_degenerate: u64,
    /// Rejected: facing (culling).
    pub rejected_facing: u64,
    /// Rejected: outside near/far/guard band.
    pub rejected_clipped: u64,
    /// Rejected: no pixel centre in the bounding box.
    pub rejected_no_coverage: u64,
    /// Rejected: a snapped coordinate outside the integer budget.
    pub rejected_out_of_range: u64,
    /// Triangles set up (clipped pieces count separately).
    pub setups: u64,
    /// Bin entries written.
    pub bin_entries: u64,
    /// Bins drained because they were full.
    pub flushes_bin_full: u64,
    /// Bins drained because the setup store was full.
    pub flushes_setup_full: u64,
    /// Bins drained at the end of the pass.
    pub flushes_finish: u64,
    /// Tiles loaded back from the map.
    pub tile_loads: u64,
    /// Bytes of those loads.
    pub tile_load_bytes: u64,
    /// Tiles stored with geometry.
    pub tile_stores: u64,
    /// Tiles stored as a clear only.
    pub tile_clears: u64,
    /// Bytes of all stores (clears included).
    pub tile_store_bytes: u64,
    /// Fragments generated.
    pub fragments: u64,
    /// Triangle-in-tile pairs skipped by max-z culling.
    pub culled_triangles: u64,
    /// Fragment blocks skipped by max-z culling.
    pub culled_blocks: u64,
    /// Texels of the skipped regions.
    pub culled_texels: u64,
    /// Depth-unit texels read (`z1`, `z2`, ids).
    pub depth_reads: [u64; 4],
    /// Depth-unit texels written (`z1`, `z2`, ids).
    pub depth_writes: [u64; 4],
    /// Bytes of depth reads and writes on chip.
    pub depth_bytes: u64,
    /// Reductions recomputing a tile's max.
    pub tile_max_updates: u64,
    /// Map texels read by the shadow unit (`z1`, `z2`, ids).
    pub map_reads: [u64; 4],
    /// Bytes of those reads.
    pub map_read_bytes: u64,
    /// Lookups decided without reading a texel.
    pub lookups_culled: u64,
    /// Receiver depths evaluated on tangent planes.
    pub virtual_samples: u64,
    /// Tangent planes set up (pixels that needed virtual samples).
    pub tangent_setups: u64,
    /// Tangent planes too close to the light ray: ordinary comparison kept.
    pub tangent_fallbacks: u64,
    /// Pixels decided by the ordinary comparison alone.
    pub trivial_pixels: u64,
    /// Silhouette-pass fragments (Sen et al.'s silhouette fill).
    pub silhouette_fragments: u64,
    /// Silhouette points written.
    pub silhouette_stored: u64,
    /// Silhouette points read by the camera pass.
    pub silhouette_reads: u64,
    /// Shadow-volume fragments (Sen et al.'s volume fill).
    pub volume_fragments: u64,
    /// Stencil texels read.
    pub stencil_reads: u64,
    /// Stencil texels written.
    pub stencil_writes: u64,
}

/// What happened in one tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TileCounters {
    /// Fragments generated.
    pub fragments: u64,
    /// Bin flushes.
    pub flushes: u64,
    /// Triangles rasterized (bin entries drained).
    pub triangles: u64,
    /// Triangles and blocks skipped by max-z culling.
    pub culled: u64,
}

/// Totals every event; keeps per-tile counts.
#[derive(Clone, Debug, Default)]
pub struct Counters {
    /// Overall totals.
    pub totals: Totals,
    /// Per tile, row-major.
    pub tiles: Vec<TileCounters>,
    across: usize,
}

impl Counters {
    /// Counters for a target with this raster configuration.
    #[must_use]
    pub fn new(raster: &RasterConfig) -> Self {
        Self {
            totals: Totals::default(),
            tiles: vec![TileCounters::default(); raster.tile_count()],
            across: raster.tiles().0 as usize,
        }
    }

    fn tile(&mut self, t: TileId) -> Option<&mut TileCounters> {
        self.tiles.get_mut(usize::from(t.y) * self.across + usize::from(t.x))
    }
}

impl Probe for Counters {
    fn event(&mut self, event: Event) {
        let t = &mut self.totals;
        match event {
            Event::TriangleSubmitted => t.submitted += 1,
            Event::TriangleRejected { reason } => match reason {
                RejectReason::NonFinite => t.rejected_non_finite += 1,
                RejectReason::Degenerate => t.rejected_degenerate += 1,
                RejectReason::Facing => t.rejected_facing += 1,
                RejectReason::Clipped => t.rejected_clipped += 1,
                RejectReason::NoCoverage => t.rejected_no_coverage += 1,
                RejectReason::OutOfRange => t.rejected_out_of_range += 1,
            },
            Event::TriangleSetup => t.setups += 1,
            Event::TriangleBinned { tiles } => t.bin_entries += u64::from(tiles),
            Event::BinFlush { tile, triangles, reason } => {
                match reason {
                    FlushReason::BinFull => t.flushes_bin_full += 1,
                    FlushReason::SetupFull => t.flushes_setup_full += 1,
                    FlushReason::Finish => t.flushes_finish += 1,
                }
                if let Some(c) = self.tile(tile) {
                    c.flushes += 1;
                    c.triangles += u64::from(triangles);
                }
            }
            Event::TileLoad { bytes, .. } => {
                t.tile_loads += 1;
                t.tile_load_bytes += u64::from(bytes);
            }
            Event::TileStore { bytes, cleared, .. } => {
                if cleared {
                    t.tile_clears += 1;
                } else {
                    t.tile_stores += 1;
                }
                t.tile_store_bytes += u64::from(bytes);
            }
            Event::Fragments { tile, count } => {
                t.fragments += u64::from(count);
                if let Some(c) = self.tile(tile) {
                    c.fragments += u64::from(count);
                }
            }
            Event::Culled { tile, level, texels } => {
                match level {
                    CullLevel::Triangle => t.culled_triangles += 1,
                    CullLevel::Block => t.culled_blocks += 1,
                }
                t.culled_texels += u64::from(texels);
                if let Some(c) = self.tile(tile) {
                    c.culled += 1;
                }
            }
            Event::DepthRead { buffer, texels, bytes } => {
                t.depth_reads[buffer_index(buffer)] += u64::from(texels);
                t.depth_bytes += u64::from(bytes);
            }
            Event::DepthWrite { buffer, texels, bytes } => {
                t.depth_writes[buffer_index(buffer)] += u64::from(texels);
                t.depth_bytes += u64::from(bytes);
            }
            Event::TileMaxUpdate { .. } => t.tile_max_updates += 1,
            Event::MapRead { buffer, texels, bytes } => {
                t.map_reads[buffer_index(buffer)] += u64::from(texels);
                t.map_read_bytes += u64::from(bytes);
            }
            Event::LookupCulled { .. } => t.lookups_culled += 1,
            Event::VirtualSamples { count } => t.virtual_samples += u64::from(count),
            Event::TangentSetup => t.tangent_setups += 1,
            Event::TangentFallback => t.tangent_fallbacks += 1,
            Event::TrivialPixel { .. } => t.trivial_pixels += 1,
            Event::SilhouetteFragments { fragments, stored, .. } => {
                t.silhouette_fragments += u64::from(fragments);
                t.silhouette_stored += u64::from(stored);
            }
            Event::SilhouetteRead { points, .. } => t.silhouette_reads += u64::from(points),
            Event::VolumeFragments { fragments, .. } => t.volume_fragments += u64::from(fragments),
            Event::StencilRead { texels, .. } => t.stencil_reads += u64::from(texels),
            Event::StencilWrite { texels, .. } => t.stencil_writes += u64::from(texels),
            _ => {}
        }
    }
}

const fn buffer_index(b: Buffer) -> usize {
    match b {
        Buffer::Z1 => 0,
        Buffer::Z2 => 1,
        Buffer::Id => 2,
        Buffer::Silhouette => 3,
    }
}
