//! The one exhaustive account of events: [`Totals`] sums every field of
//! every [`Event`] into fixed integer fields, with no allocation, so the
//! simulator's counters, its architecture models and the firmware all
//! report the same numbers. Its `match` has no wildcard arm: a new event
//! does not compile until it is accounted for here.

use super::{Buffer, CullLevel, Event, FlushReason, Probe, RejectReason};

/// What a field of [`Totals`] counts in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counted {
    /// Events or items (triangles, fragments, tiles, lookups).
    Count,
    /// Bytes.
    Bytes,
}

/// Declares [`Totals`] and its list of named fields from one list — name,
/// unit and meaning each once — so the names the firmware prints, the
/// fields and their units cannot drift apart.
macro_rules! totals {
    ($($(#[doc = $doc:literal])+ $name:ident: $unit:ident,)+) => {
        /// Event totals of one pass: every field of every [`Event`], summed.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize))]
        pub struct Totals {
            $($(#[doc = $doc])+ pub $name: u64,)+
        }

        /// The names of [`Totals`]' fields, in declaration order.
        pub const NAMES: &[&str] = &[$(stringify!($name)),+];

        impl Totals {
            /// Nothing counted yet (a `const`, for a `static`).
            pub const ZERO: Self = Self { $($name: 0,)+ };

            /// What each field counts (its doc comment), in declaration
            /// order.
            pub const DOCS: [&'static str; NAMES.len()] = [$(concat!($($doc),+)),+];

            /// What each field is counted in, in declaration order.
            pub const UNITS: [Counted; NAMES.len()] = [$(Counted::$unit),+];

            /// Both counts added, field by field (two passes' totals as one).
            #[must_use]
            pub const fn plus(&self, o: &Self) -> Self {
                Self { $($name: self.$name.saturating_add(o.$name),)+ }
            }

            /// Every field with its name, in declaration order (the names
            /// the firmware prints).
            #[must_use]
            pub const fn fields(&self) -> [(&'static str, u64); NAMES.len()] {
                [$((stringify!($name), self.$name)),+]
            }
        }
    };
}

totals! {
    /// Triangles submitted ([`Event::TriangleSubmitted`]).
    submitted: Count,
    /// Rejected before setup: a vertex not finite.
    rejected_non_finite: Count,
    /// Rejected: zero area on the subpixel grid.
    rejected_degenerate: Count,
    /// Rejected: facing (culling).
    rejected_facing: Count,
    /// Rejected: outside near, far or the guard band.
    rejected_clipped: Count,
    /// Rejected: no pixel centre in the bounding box.
    rejected_no_coverage: Count,
    /// Rejected: a snapped coordinate outside the integer budget.
    rejected_out_of_range: Count,
    /// Triangles set up, clipped pieces and shadow-volume triangles included
    /// ([`Event::TriangleSetup`]).
    setups: Count,
    /// Bin entries written, summed over [`Event::TriangleBinned`].
    bin_entries: Count,
    /// Bins drained because they were full.
    flushes_bin_full: Count,
    /// Bins drained because the setup store was full.
    flushes_setup_full: Count,
    /// Bins drained at the end of the pass.
    flushes_finish: Count,
    /// Bins drained at the end of a draw.
    flushes_draw: Count,
    /// Triangles drained from bins, summed over [`Event::BinFlush`].
    flushed_triangles: Count,
    /// Tiles loaded back from the map ([`Event::TileLoad`]).
    tile_loads: Count,
    /// Bytes of those loads.
    tile_load_bytes: Bytes,
    /// Tiles stored with geometry ([`Event::TileStore`]).
    tile_stores: Count,
    /// Tiles stored as a clear only.
    tile_clears: Count,
    /// Bytes of all stores, clears included.
    tile_store_bytes: Bytes,
    /// Fragments generated, summed over [`Event::Fragments`].
    fragments: Count,
    /// Triangle-in-tile pairs that generated fragments ([`Event::Fragments`]).
    rasterized: Count,
    /// Triangle-in-tile pairs skipped by max-z culling ([`Event::Culled`]).
    culled_triangles: Count,
    /// Fragment blocks skipped by max-z culling.
    culled_blocks: Count,
    /// Texels of the skipped regions.
    culled_texels: Count,
    /// `z1` texels read by the depth unit ([`Event::DepthRead`]).
    depth_reads_z1: Count,
    /// `z2` texels read by the depth unit.
    depth_reads_z2: Count,
    /// Id texels read by the depth unit.
    depth_reads_id: Count,
    /// Silhouette texels read by the depth unit.
    depth_reads_silhouette: Count,
    /// Bytes of the depth unit's reads.
    depth_read_bytes: Bytes,
    /// `z1` texels written by the depth unit ([`Event::DepthWrite`]).
    depth_writes_z1: Count,
    /// `z2` texels written by the depth unit.
    depth_writes_z2: Count,
    /// Id texels written by the depth unit.
    depth_writes_id: Count,
    /// Silhouette texels written by the depth unit.
    depth_writes_silhouette: Count,
    /// Bytes of the depth unit's writes.
    depth_write_bytes: Bytes,
    /// Reductions recomputing a tile's max ([`Event::TileMaxUpdate`]).
    tile_max_updates: Count,
    /// `z1` texels read by the shadow unit ([`Event::MapRead`]).
    map_reads_z1: Count,
    /// `z2` texels read by the shadow unit.
    map_reads_z2: Count,
    /// Id texels read by the shadow unit.
    map_reads_id: Count,
    /// Silhouette texels read by the shadow unit.
    map_reads_silhouette: Count,
    /// Bytes of the shadow unit's reads.
    map_read_bytes: Bytes,
    /// Lookups decided without reading a texel ([`Event::LookupCulled`]).
    lookups_culled: Count,
    /// Texels those lookups did not read.
    lookup_culled_texels: Count,
    /// Receiver depths evaluated on tangent planes ([`Event::VirtualSamples`]).
    virtual_samples: Count,
    /// Tangent planes set up ([`Event::TangentSetup`]).
    tangent_setups: Count,
    /// Tangent planes too close to the light ray ([`Event::TangentFallback`]).
    tangent_fallbacks: Count,
    /// Pixels decided lit by the ordinary comparison ([`Event::TrivialPixel`]).
    trivial_lit: Count,
    /// Pixels decided shadowed by the ordinary comparison.
    trivial_shadowed: Count,
    /// Silhouette-pass fragments ([`Event::SilhouetteFragments`]).
    silhouette_fragments: Count,
    /// Silhouette points written.
    silhouette_stored: Count,
    /// Bytes of those writes.
    silhouette_write_bytes: Bytes,
    /// Silhouette points read by the camera pass ([`Event::SilhouetteRead`]).
    silhouette_reads: Count,
    /// Bytes of those reads.
    silhouette_read_bytes: Bytes,
    /// Covered pixels shaded ([`Event::PixelShaded`]).
    pixels_shaded: Count,
    /// Shadow-volume fragments ([`Event::VolumeFragments`]).
    volume_fragments: Count,
    /// Scene depth bytes those fragments read.
    volume_depth_bytes: Bytes,
    /// Stencil texels read ([`Event::StencilRead`]).
    stencil_reads: Count,
    /// Bytes of those reads.
    stencil_read_bytes: Bytes,
    /// Stencil texels written ([`Event::StencilWrite`]).
    stencil_writes: Count,
    /// Bytes of those writes.
    stencil_write_bytes: Bytes,
}

impl Totals {
    /// Pixels decided by the ordinary comparison, lit or shadowed.
    #[must_use]
    pub const fn trivial_pixels(&self) -> u64 {
        self.trivial_lit + self.trivial_shadowed
    }

    /// Triangles rejected before setup, every reason.
    #[must_use]
    pub const fn rejected(&self) -> u64 {
        self.rejected_non_finite
            + self.rejected_degenerate
            + self.rejected_facing
            + self.rejected_clipped
            + self.rejected_no_coverage
            + self.rejected_out_of_range
    }

    /// Bins drained, every reason.
    #[must_use]
    pub const fn flushes(&self) -> u64 {
        self.flushes_bin_full + self.flushes_setup_full + self.flushes_finish + self.flushes_draw
    }

    /// Texels the shadow unit read, every buffer.
    #[must_use]
    pub const fn map_reads(&self) -> u64 {
        self.map_reads_z1 + self.map_reads_z2 + self.map_reads_id + self.map_reads_silhouette
    }

    /// Texels the depth unit read, every buffer.
    #[must_use]
    pub const fn depth_reads(&self) -> u64 {
        self.depth_reads_z1 + self.depth_reads_z2 + self.depth_reads_id + self.depth_reads_silhouette
    }

    /// Texels the depth unit wrote, every buffer.
    #[must_use]
    pub const fn depth_writes(&self) -> u64 {
        self.depth_writes_z1 + self.depth_writes_z2 + self.depth_writes_id + self.depth_writes_silhouette
    }

    /// Add one event to the totals.
    #[inline]
    pub fn add(&mut self, event: Event) {
        let n = u64::from;
        match event {
            Event::TriangleSubmitted => self.submitted += 1,
            Event::TriangleRejected { reason } => {
                *match reason {
                    RejectReason::NonFinite => &mut self.rejected_non_finite,
                    RejectReason::Degenerate => &mut self.rejected_degenerate,
                    RejectReason::Facing => &mut self.rejected_facing,
                    RejectReason::Clipped => &mut self.rejected_clipped,
                    RejectReason::NoCoverage => &mut self.rejected_no_coverage,
                    RejectReason::OutOfRange => &mut self.rejected_out_of_range,
                } += 1;
            }
            Event::TriangleSetup => self.setups += 1,
            Event::TriangleBinned { tiles } => self.bin_entries += n(tiles),
            Event::BinFlush { tile: _, triangles, reason } => {
                *match reason {
                    FlushReason::BinFull => &mut self.flushes_bin_full,
                    FlushReason::SetupFull => &mut self.flushes_setup_full,
                    FlushReason::Finish => &mut self.flushes_finish,
                    FlushReason::Draw => &mut self.flushes_draw,
                } += 1;
                self.flushed_triangles += n(triangles);
            }
            Event::TileLoad { tile: _, bytes } => {
                self.tile_loads += 1;
                self.tile_load_bytes += n(bytes);
            }
            Event::TileStore { tile: _, bytes, cleared } => {
                *if cleared { &mut self.tile_clears } else { &mut self.tile_stores } += 1;
                self.tile_store_bytes += n(bytes);
            }
            Event::Fragments { tile: _, count } => {
                self.fragments += n(count);
                self.rasterized += 1;
            }
            Event::Culled { tile: _, level, texels } => {
                *match level {
                    CullLevel::Triangle => &mut self.culled_triangles,
                    CullLevel::Block => &mut self.culled_blocks,
                } += 1;
                self.culled_texels += n(texels);
            }
            Event::DepthRead { buffer, texels, bytes } => {
                *of(
                    buffer,
                    [
                        &mut self.depth_reads_z1,
                        &mut self.depth_reads_z2,
                        &mut self.depth_reads_id,
                        &mut self.depth_reads_silhouette,
                    ],
                ) += n(texels);
                self.depth_read_bytes += n(bytes);
            }
            Event::DepthWrite { buffer, texels, bytes } => {
                *of(
                    buffer,
                    [
                        &mut self.depth_writes_z1,
                        &mut self.depth_writes_z2,
                        &mut self.depth_writes_id,
                        &mut self.depth_writes_silhouette,
                    ],
                ) += n(texels);
                self.depth_write_bytes += n(bytes);
            }
            Event::TileMaxUpdate { tile: _ } => self.tile_max_updates += 1,
            Event::MapRead { buffer, texels, bytes } => {
                *of(
                    buffer,
                    [
                        &mut self.map_reads_z1,
                        &mut self.map_reads_z2,
                        &mut self.map_reads_id,
                        &mut self.map_reads_silhouette,
                    ],
                ) += n(texels);
                self.map_read_bytes += n(bytes);
            }
            Event::LookupCulled { texels } => {
                self.lookups_culled += 1;
                self.lookup_culled_texels += n(texels);
            }
            Event::VirtualSamples { count } => self.virtual_samples += n(count),
            Event::TangentSetup => self.tangent_setups += 1,
            Event::TangentFallback => self.tangent_fallbacks += 1,
            Event::TrivialPixel { lit } => *if lit { &mut self.trivial_lit } else { &mut self.trivial_shadowed } += 1,
            Event::SilhouetteFragments { fragments, stored, bytes } => {
                self.silhouette_fragments += n(fragments);
                self.silhouette_stored += n(stored);
                self.silhouette_write_bytes += n(bytes);
            }
            Event::SilhouetteRead { points, bytes } => {
                self.silhouette_reads += n(points);
                self.silhouette_read_bytes += n(bytes);
            }
            Event::PixelShaded { x: _, y: _ } => self.pixels_shaded += 1,
            Event::VolumeFragments { tile: _, fragments, depth_bytes } => {
                self.volume_fragments += n(fragments);
                self.volume_depth_bytes += n(depth_bytes);
            }
            Event::StencilRead { tile: _, texels, bytes } => {
                self.stencil_reads += n(texels);
                self.stencil_read_bytes += n(bytes);
            }
            Event::StencilWrite { tile: _, texels, bytes } => {
                self.stencil_writes += n(texels);
                self.stencil_write_bytes += n(bytes);
            }
        }
    }
}

/// The field of `buffer` among one count's per-buffer fields, given in
/// [`Buffer`] order.
const fn of(buffer: Buffer, [z1, z2, id, silhouette]: [&mut u64; 4]) -> &mut u64 {
    match buffer {
        Buffer::Z1 => z1,
        Buffer::Z2 => z2,
        Buffer::Id => id,
        Buffer::Silhouette => silhouette,
    }
}

impl Probe for Totals {
    #[inline]
    fn event(&mut self, event: Event) {
        self.add(event);
    }
}
