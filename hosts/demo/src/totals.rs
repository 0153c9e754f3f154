//! A probe that totals the core's events by kind into fixed integer fields
//! (no allocation), so both targets can report them the same way.

use umbra_core::probe::{Buffer, CullLevel, Event, Probe};

/// Event totals of one pass, one field per kind of [`Event`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EventTotals {
    /// [`Event::TriangleSubmitted`].
    pub submitted: u64,
    /// [`Event::TriangleRejected`], every reason.
    pub rejected: u64,
    /// [`Event::TriangleSetup`].
    pub setups: u64,
    /// Bins written, summed over [`Event::TriangleBinned`].
    pub bin_entries: u64,
    /// [`Event::BinFlush`], every reason.
    pub flushes: u64,
    /// [`Event::TileLoad`].
    pub tile_loads: u64,
    /// [`Event::TileStore`] of tiles with geometry.
    pub tile_stores: u64,
    /// [`Event::TileStore`] of tiles holding only the clear value.
    pub tile_clears: u64,
    /// Fragments, summed over [`Event::Fragments`].
    pub fragments: u64,
    /// [`Event::Culled`] of whole triangles in a tile.
    pub culled_triangles: u64,
    /// [`Event::Culled`] of fragment blocks.
    pub culled_blocks: u64,
    /// Texels read by the depth unit, summed over [`Event::DepthRead`].
    pub depth_reads: u64,
    /// Texels written by the depth unit, summed over [`Event::DepthWrite`].
    pub depth_writes: u64,
    /// [`Event::TileMaxUpdate`].
    pub tile_max_updates: u64,
    /// `z1` texels read by the shadow unit ([`Event::MapRead`]).
    pub map_reads_z1: u64,
    /// `z2` texels read by the shadow unit ([`Event::MapRead`]).
    pub map_reads_z2: u64,
    /// [`Event::LookupCulled`].
    pub lookups_culled: u64,
    /// Virtual samples, summed over [`Event::VirtualSamples`].
    pub virtual_samples: u64,
    /// [`Event::TangentSetup`].
    pub tangent_setups: u64,
    /// [`Event::TangentFallback`].
    pub tangent_fallbacks: u64,
    /// [`Event::TrivialPixel`] decided lit.
    pub trivial_lit: u64,
    /// [`Event::TrivialPixel`] decided shadowed.
    pub trivial_shadowed: u64,
    /// Silhouette fragments, summed over [`Event::SilhouetteFragments`].
    pub silhouette_fragments: u64,
    /// Silhouette points read, summed over [`Event::SilhouetteRead`].
    pub silhouette_reads: u64,
    /// Shadow-volume fragments, summed over [`Event::VolumeFragments`].
    pub volume_fragments: u64,
    /// Stencil texels read, summed over [`Event::StencilRead`].
    pub stencil_reads: u64,
    /// Stencil texels written, summed over [`Event::StencilWrite`].
    pub stencil_writes: u64,
    /// Events this probe does not sort: map reads of the id buffer, and
    /// kinds added to the core after it.
    pub other: u64,
}

/// Number of fields of [`EventTotals`].
pub const FIELDS: usize = 28;

impl EventTotals {
    /// Every field with its name, in declaration order (the names the
    /// firmware prints).
    #[must_use]
    pub const fn fields(&self) -> [(&'static str, u64); FIELDS] {
        [
            ("submitted", self.submitted),
            ("rejected", self.rejected),
            ("setups", self.setups),
            ("bin_entries", self.bin_entries),
            ("flushes", self.flushes),
            ("tile_loads", self.tile_loads),
            ("tile_stores", self.tile_stores),
            ("tile_clears", self.tile_clears),
            ("fragments", self.fragments),
            ("culled_triangles", self.culled_triangles),
            ("culled_blocks", self.culled_blocks),
            ("depth_reads", self.depth_reads),
            ("depth_writes", self.depth_writes),
            ("tile_max_updates", self.tile_max_updates),
            ("map_reads_z1", self.map_reads_z1),
            ("map_reads_z2", self.map_reads_z2),
            ("lookups_culled", self.lookups_culled),
            ("virtual_samples", self.virtual_samples),
            ("tangent_setups", self.tangent_setups),
            ("tangent_fallbacks", self.tangent_fallbacks),
            ("trivial_lit", self.trivial_lit),
            ("trivial_shadowed", self.trivial_shadowed),
            ("silhouette_fragments", self.silhouette_fragments),
            ("silhouette_reads", self.silhouette_reads),
            ("volume_fragments", self.volume_fragments),
            ("stencil_reads", self.stencil_reads),
            ("stencil_writes", self.stencil_writes),
            ("other", self.other),
        ]
    }
}

impl Probe for EventTotals {
    fn event(&mut self, event: Event) {
        let n = |v: u32| u64::from(v);
        match event {
            Event::TriangleSubmitted => self.submitted += 1,
            Event::TriangleRejected { .. } => self.rejected += 1,
            Event::TriangleSetup => self.setups += 1,
            Event::TriangleBinned { tiles } => self.bin_entries += n(tiles),
            Event::BinFlush { .. } => self.flushes += 1,
            Event::TileLoad { .. } => self.tile_loads += 1,
            Event::TileStore { cleared: false, .. } => self.tile_stores += 1,
            Event::TileStore { cleared: true, .. } => self.tile_clears += 1,
            Event::Fragments { count, .. } => self.fragments += n(count),
            Event::Culled { level: CullLevel::Triangle, .. } => self.culled_triangles += 1,
            Event::Culled { level: CullLevel::Block, .. } => self.culled_blocks += 1,
            Event::DepthRead { texels, .. } => self.depth_reads += n(texels),
            Event::DepthWrite { texels, .. } => self.depth_writes += n(texels),
            Event::TileMaxUpdate { .. } => self.tile_max_updates += 1,
            Event::MapRead { buffer: Buffer::Z1, texels, .. } => self.map_reads_z1 += n(texels),
            Event::MapRead { buffer: Buffer::Z2, texels, .. } => self.map_reads_z2 += n(texels),
            Event::LookupCulled { .. } => self.lookups_culled += 1,
            Event::VirtualSamples { count } => self.virtual_samples += n(count),
            Event::TangentSetup => self.tangent_setups += 1,
            Event::TangentFallback => self.tangent_fallbacks += 1,
            Event::TrivialPixel { lit: true } => self.trivial_lit += 1,
            Event::TrivialPixel { lit: false } => self.trivial_shadowed += 1,
            Event::SilhouetteFragments { fragments, .. } => self.silhouette_fragments += n(fragments),
            Event::SilhouetteRead { points, .. } => self.silhouette_reads += n(points),
            Event::VolumeFragments { fragments, .. } => self.volume_fragments += n(fragments),
            Event::StencilRead { texels, .. } => self.stencil_reads += n(texels),
            Event::StencilWrite { texels, .. } => self.stencil_writes += n(texels),
            _ => self.other += 1,
        }
    }
}
