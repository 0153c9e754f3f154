//! What the units report: one event per batch of work, and the per-fragment
//! and per-texel detail probes may ask for.

use crate::grid::TileId;

/// A buffer the units read or write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Buffer {
    /// Nearest depth.
    Z1,
    /// Second-nearest depth.
    Z2,
    /// Visible-triangle ids (the camera pass's visibility).
    Id,
    /// Silhouette points (Sen et al. 2003).
    Silhouette,
}

/// Why a submitted triangle produced no fragments before binning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RejectReason {
    /// A vertex (or the clipper's arithmetic on it) is not finite.
    NonFinite,
    /// The triangle has zero area on the subpixel grid.
    Degenerate,
    /// Discarded by the cull mode.
    Facing,
    /// Entirely outside the near/far planes or the guard band.
    Clipped,
    /// Covers no pixel centre of the target.
    NoCoverage,
    /// A snapped coordinate outside the integer budget (a hand-made vertex).
    OutOfRange,
}

/// Why a tile's bin was rasterized.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FlushReason {
    /// The bin was full; the tile is rasterized early and binning retries.
    BinFull,
    /// The shared triangle-setup store was full; every bin is drained.
    SetupFull,
    /// End of the pass.
    Finish,
    /// The caller ended a draw: an immediate-mode machine finishes each
    /// draw before the next ([`crate::LightPass::flush`]).
    Draw,
}

/// The unit of work a max-z cull skipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CullLevel {
    /// A whole triangle in a tile.
    Triangle,
    /// A block of fragments of a triangle in a tile.
    Block,
}

/// One unit event. Counts are batched: one event may stand for many texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// A triangle entered the pipeline (before clipping): a scene triangle
    /// at the front end, or a shadow-volume triangle at the stencil unit.
    TriangleSubmitted,
    /// A submitted triangle was dropped before setup.
    TriangleRejected {
        /// Why.
        reason: RejectReason,
    },
    /// A (clipped) triangle was set up: edge functions and depth plane, by
    /// the front end or by the stencil unit.
    TriangleSetup,
    /// A set-up triangle was written to this many tile bins.
    TriangleBinned {
        /// Bins written.
        tiles: u32,
    },
    /// A tile's bin was rasterized.
    BinFlush {
        /// The tile.
        tile: TileId,
        /// Triangles in the bin.
        triangles: u32,
        /// Why now.
        reason: FlushReason,
    },
    /// A tile's depth was brought on chip from the map (a later flush of a
    /// tile that was stored before).
    TileLoad {
        /// The tile.
        tile: TileId,
        /// Bytes read from the map.
        bytes: u32,
    },
    /// A tile's depth was written back to the map. A tile that received no
    /// geometry is stored as a clear (`cleared`), which a fast-clear
    /// memory may not need to write.
    TileStore {
        /// The tile.
        tile: TileId,
        /// Bytes written to the map.
        bytes: u32,
        /// The tile holds only the clear value.
        cleared: bool,
    },
    /// Pixel centres covered by a triangle in a tile: fragments generated.
    Fragments {
        /// The tile.
        tile: TileId,
        /// How many.
        count: u32,
    },
    /// Work skipped by max-z culling: the triangle's nearest depth in the
    /// region lies at or beyond the tile's max stored depth.
    Culled {
        /// The tile.
        tile: TileId,
        /// A whole triangle in the tile, or one block of it.
        level: CullLevel,
        /// Texels of the skipped region (an upper bound on its fragments).
        texels: u32,
    },
    /// Depth values read by the depth unit (on chip).
    DepthRead {
        /// Which buffer.
        buffer: Buffer,
        /// Texels read.
        texels: u32,
        /// Bytes read at the format's width.
        bytes: u32,
    },
    /// Depth values written by the depth unit (on chip): texels whose value changed.
    DepthWrite {
        /// Which buffer.
        buffer: Buffer,
        /// Texels written.
        texels: u32,
        /// Bytes written at the format's width.
        bytes: u32,
    },
    /// The tile's max stored depth was recomputed because every texel that
    /// held it has been lowered (a reduction over the tile).
    TileMaxUpdate {
        /// The tile.
        tile: TileId,
    },
    /// Texels of the map read by the shadow unit (memory traffic).
    MapRead {
        /// Which buffer.
        buffer: Buffer,
        /// Texels read.
        texels: u32,
        /// Bytes read at the format's width.
        bytes: u32,
    },
    /// A lookup decided by the tiles' stored bounds (or lying wholly outside
    /// the map): no texel read.
    LookupCulled {
        /// Texels of the footprint not read.
        texels: u32,
    },
    /// Receiver depths evaluated on a tangent plane (virtual samples).
    VirtualSamples {
        /// How many.
        count: u32,
    },
    /// A receiver's tangent plane was moved to light space and solved for
    /// its slopes (one division).
    TangentSetup,
    /// The tangent plane was nearly parallel to the light ray: the lookup
    /// fell back to the ordinary comparison.
    TangentFallback,
    /// Every sample of the ordinary comparison agreed: the pixel was decided
    /// without virtual samples.
    TrivialPixel {
        /// Decided lit (else shadowed).
        lit: bool,
    },
    /// One silhouette edge through the silhouette pass (Sen et al. 2003
    /// §3.1): fragments of its conservative rasterization, and the points
    /// they stored (the rest were killed: outside the texel or hidden).
    SilhouetteFragments {
        /// Fragments generated.
        fragments: u32,
        /// Points written.
        stored: u32,
        /// Bytes written.
        bytes: u32,
    },
    /// Silhouette points read by the camera pass (the texel's and its four
    /// neighbours').
    SilhouetteRead {
        /// Points read.
        points: u32,
        /// Bytes read.
        bytes: u32,
    },
    /// The shading unit began a covered pixel: the shadow events up to the
    /// next one are this pixel's.
    PixelShaded {
        /// Column.
        x: u32,
        /// Row (row 0 at the top).
        y: u32,
    },
    /// Fragments of one shadow-volume triangle in one tile of the camera's
    /// raster, each reading the scene depth.
    VolumeFragments {
        /// The tile.
        tile: TileId,
        /// Fragments generated.
        fragments: u32,
        /// Scene depth bytes read.
        depth_bytes: u32,
    },
    /// Stencil texels read by the volume fragments of one triangle in one tile.
    StencilRead {
        /// The tile.
        tile: TileId,
        /// Texels read.
        texels: u32,
        /// Bytes read.
        bytes: u32,
    },
    /// Stencil texels written (incremented or decremented) by the volume
    /// fragments of one triangle in one tile that failed the depth test.
    StencilWrite {
        /// The tile.
        tile: TileId,
        /// Texels written.
        texels: u32,
        /// Bytes written.
        bytes: u32,
    },
}

/// One fragment in detail, for probes that ask for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Fragment {
    /// Column of the pixel.
    pub x: u32,
    /// Row of the pixel (row 0 at the top).
    pub y: u32,
    /// The quantised depth, as the format's raw bits.
    pub depth: u32,
    /// Index of the submitted triangle (clipped pieces share it).
    pub triangle: u32,
}

/// One sample the shadow unit compared: where, the receiver's depth and
/// bias, the depth it was compared against and the outcome — what a
/// judge of the unit's errors needs to say *why* a pixel came out wrong
/// (acne: the reference is the receiver's own surface; detachment: only
/// the bias moved the receiver past an occluder the map holds; a leak:
/// the reference lies behind the receiver under a first-layer occluder).
/// Reported only to probes that set [`Probe::TAPS`](crate::Probe::TAPS).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Tap {
    /// Column of the texel (outside the map for a sample off it).
    pub x: i64,
    /// Row of the texel.
    pub y: i64,
    /// The receiver's depth at this sample before the bias, rounded to
    /// the map's format ([`PlaneZ`](crate::depth::PlaneZ) bits): the
    /// point's depth, or its tangent plane at the texel's centre.
    pub receiver: i64,
    /// The bias subtracted from the receiver for this sample (`PlaneZ` bits).
    pub bias: i64,
    /// The depth the test compared against (`PlaneZ` bits): `z1`, `z2`,
    /// their midpoint or the dual depth; `None` off the map (lit).
    pub reference: Option<i64>,
    /// The map's first layer, `z1`, at the texel (`PlaneZ` bits); `None`
    /// off the map or for a map without one (front-face culled).
    pub first: Option<i64>,
    /// Whether the sample came out shadowed.
    pub shadowed: bool,
    /// The sample's weight in the filter (the filter's own units: 1 for
    /// point, box, jittered and silhouette samples; the fixed-point
    /// bilinear weight, out of 2³², for bilinear ones).
    pub weight: u64,
}

/// One texel of the map read by the shadow unit, for probes that model
/// memory (caches, address streams).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TexelRead {
    /// Which buffer.
    pub buffer: Buffer,
    /// Column of the texel.
    pub x: u32,
    /// Row of the texel.
    pub y: u32,
}

/// A rectangle of the map's texels read by the shadow unit at once (a box
/// filter's footprint, all on the map): columns `x0..x1` of rows `y0..y1`,
/// each texel's `buffers` in turn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TexelRect {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
    /// The buffers read at each texel, in order (one or two).
    pub buffers: [Option<Buffer>; 2],
}

impl TexelRect {
    /// Its texels' reads, one at a time, in the order the unit reads them:
    /// row by row from the top, each row from the left, each texel's
    /// buffers in turn.
    pub fn reads(self) -> impl Iterator<Item = TexelRead> {
        (self.y0..self.y1).flat_map(move |y| {
            (self.x0..self.x1)
                .flat_map(move |x| self.buffers.into_iter().flatten().map(move |buffer| TexelRead { buffer, x, y }))
        })
    }

    /// How many reads it is: texels times buffers.
    #[must_use]
    pub fn count(&self) -> u64 {
        let side = |a: u32, b: u32| u64::from(b.saturating_sub(a));
        side(self.x0, self.x1) * side(self.y0, self.y1) * self.buffers.iter().flatten().count() as u64
    }
}
