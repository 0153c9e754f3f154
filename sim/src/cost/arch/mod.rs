//! Architecture models: probes that turn the core's events into cycles per
//! pipeline stage and bytes per memory, the way Sen et al.'s bandwidth model
//! counts a frame.
//!
//! Stages run pipelined; a pass takes as long as its slowest stage (the
//! bottleneck). Every cost is a parameter of the preset, and every
//! parameter says why it has its value.

use serde::Serialize;
use umbra_core::Probe;
use umbra_core::probe::Event;

mod report;
mod timing;

pub use report::CostReport;
pub use timing::ArchProbe;

/// The pipeline stages a cost is charged to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[repr(usize)]
pub enum Stage {
    /// Triangle setup.
    Setup,
    /// Scan conversion.
    Raster,
    /// The depth unit.
    Depth,
    /// The shadow unit (camera pass).
    Shadow,
    /// Writing tiles back (resolve).
    Resolve,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Self; 5] = [Self::Setup, Self::Raster, Self::Depth, Self::Shadow, Self::Resolve];
}

/// The parameters of an architecture. See the presets for values and reasons.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ArchParams {
    /// Name for reports.
    pub name: &'static str,
    /// Cycles to set up one triangle.
    pub setup_cycles: u64,
    /// Raster cycles per triangle per tile it touches, whatever its
    /// fragment count (a linear-expression evaluator); 0 if fragment-bound.
    pub raster_cycles_per_tile: u64,
    /// Fragments scan-converted per clock (0: not fragment-bound).
    pub fragments_per_clock: u64,
    /// Depth-unit cycles per triangle per tile for each depth bit and
    /// buffer (bit-serial processors; 0 if per fragment).
    pub depth_cycles_per_bit: u64,
    /// Depth-unit fragments per clock (0: bit-serial instead).
    pub depth_fragments_per_clock: u64,
    /// The depth buffers live off chip, read and written per fragment.
    pub off_chip_depth: bool,
    /// The resolve writes only the value the shadow test needs (one buffer).
    pub resolve_test_value_only: bool,
    /// Bytes of one bin entry in memory.
    pub bin_entry_bytes: u64,
    /// Bytes of one triangle's setup record in memory (written at binning,
    /// read at each flush of a tile it is binned to).
    pub setup_record_bytes: u64,
    /// DRAM bytes per cycle (for the resolve stage).
    pub dram_bytes_per_cycle: u64,
    /// Shadow-unit map samples compared per clock.
    pub samples_per_clock: u64,
    /// Cycles of one tangent-plane setup (a division).
    pub tangent_setup_cycles: u64,
    /// Side of the on-chip tile (region, chunk) in pixels.
    pub tile: u32,
    /// The shadow unit's map cache: bytes, line bytes, ways (none: every
    /// sample reads memory).
    pub map_cache: Option<(u64, u32, u32)>,
}

impl ArchParams {
    /// PixelFlow-style (Molnar, Eyles & Poulton 1992): 128×128 SIMD regions
    /// fed by a linear-expression evaluator; bit-serial pixel processors.
    pub const PIXELFLOW: Self = Self {
        name: "pixelflow",
        // The geometry processors' setup of edge and depth coefficients.
        setup_cycles: 100,
        // The evaluator broadcasts 4 linear expressions (3 edges, depth) to a
        // region: a fixed cost per region touched, not per fragment.
        raster_cycles_per_tile: 4 * 32,
        fragments_per_clock: 0,
        // Bit-serial compare and conditional write: 2 cycles per bit per buffer,
        // all pixels of the region at once.
        depth_cycles_per_bit: 2,
        depth_fragments_per_clock: 0,
        off_chip_depth: false,
        resolve_test_value_only: false,
        bin_entry_bytes: 4,
        setup_record_bytes: 48,
        // A 64-bit DRAM interface at the pixel clock.
        dram_bytes_per_cycle: 8,
        // Bit-serial shading processors: a sample compare costs about a cycle
        // per region-parallel pixel; modelled as one sample per clock per pixel lane.
        samples_per_clock: 1,
        tangent_setup_cycles: 30,
        tile: 128,
        // No texture cache: each region's map reads stream from memory.
        map_cache: None,
    };

    /// Talisman-style (Torborg & Kajiya 1996): 32×32 chunks, triangles binned
    /// per chunk, scan conversion at 2 fragments per clock into on-chip
    /// chunk depth buffers; DRAM traffic for bins and at resolve only.
    pub const TALISMAN: Self = Self {
        name: "talisman",
        // A fixed-function setup engine, pipelined: a triangle every 20 cycles.
        setup_cycles: 20,
        raster_cycles_per_tile: 0,
        // Talisman's polygon engine rasterises 2 pixels per clock.
        fragments_per_clock: 2,
        depth_cycles_per_bit: 0,
        // The on-chip chunk z-buffer keeps up with the rasteriser.
        depth_fragments_per_clock: 2,
        off_chip_depth: false,
        // The resolve writes only what the shadow test reads.
        resolve_test_value_only: true,
        // A 32-bit pointer to the setup record per bin entry.
        bin_entry_bytes: 4,
        // Three edges and a depth plane at 32 bits each, plus bounds.
        setup_record_bytes: 64,
        dram_bytes_per_cycle: 8,
        // A texture-filter-like unit: 4 samples per clock.
        samples_per_clock: 4,
        tangent_setup_cycles: 20,
        tile: 32,
        // A small on-chip texture cache, as Talisman's texture unit had.
        map_cache: Some((16 * 1024, 64, 4)),
    };

    /// An immediate-mode baseline: depth buffers off chip, read-modify-written
    /// per fragment, an on-chip max-z per tile.
    pub const IMMEDIATE: Self = Self {
        name: "immediate",
        setup_cycles: 20,
        raster_cycles_per_tile: 0,
        fragments_per_clock: 2,
        depth_cycles_per_bit: 0,
        depth_fragments_per_clock: 2,
        off_chip_depth: true,
        resolve_test_value_only: false,
        bin_entry_bytes: 0,
        setup_record_bytes: 0,
        dram_bytes_per_cycle: 8,
        samples_per_clock: 4,
        tangent_setup_cycles: 20,
        tile: 32,
        // A conventional 16 KB, 4-way texture cache with 64-byte lines.
        map_cache: Some((16 * 1024, 64, 4)),
    };

    /// The presets by name.
    pub const PRESETS: [Self; 3] = [Self::PIXELFLOW, Self::TALISMAN, Self::IMMEDIATE];
}

/// DRAM traffic per buffer, bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Dram {
    /// Map texels written (resolve, or per-fragment writes off chip).
    pub map_writes: u64,
    /// Depth read back by the light pass (tile loads, or per-fragment reads off chip).
    pub map_rmw_reads: u64,
    /// Map texels read by the camera pass.
    pub map_reads: u64,
    /// Bins and setup records written and read.
    pub bins: u64,
    /// Silhouette points written by the silhouette pass.
    pub silhouette_writes: u64,
    /// Silhouette points read by the camera pass.
    pub silhouette_reads: u64,
    /// Scene depth read by shadow-volume fragments.
    pub volume_depth_reads: u64,
    /// Stencil read and written by shadow-volume fragments.
    pub stencil: u64,
}

impl Dram {
    /// Every byte of this pass's traffic.
    #[must_use]
    pub const fn total(&self) -> u64 {
        self.map_writes
            + self.map_rmw_reads
            + self.map_reads
            + self.bins
            + self.silhouette_writes
            + self.silhouette_reads
            + self.volume_depth_reads
            + self.stencil
    }

    /// The reads that go through a preset's map cache: map texels and
    /// silhouette points.
    #[must_use]
    pub const fn cached(&self) -> u64 {
        self.map_reads + self.silhouette_reads
    }

    /// The camera pass's shadow traffic: map, silhouette, volume depth and stencil.
    #[must_use]
    pub const fn camera_shadow_bytes(&self) -> u64 {
        self.map_reads + self.silhouette_reads + self.volume_depth_reads + self.stencil
    }
}

/// Forwards every event, fragment and texel read to two probes.
#[derive(Clone, Debug, Default)]
pub struct Tee<A, B>(pub A, pub B);

impl<A: Probe, B: Probe> Probe for Tee<A, B> {
    const FRAGMENTS: bool = A::FRAGMENTS || B::FRAGMENTS;
    const TEXELS: bool = A::TEXELS || B::TEXELS;
    const EVENTS: bool = A::EVENTS || B::EVENTS;

    #[inline]
    fn event(&mut self, e: Event) {
        self.0.event(e);
        self.1.event(e);
    }

    #[inline]
    fn fragment(&mut self, f: umbra_core::probe::Fragment) {
        self.0.fragment(f);
        self.1.fragment(f);
    }

    #[inline]
    fn texel_read(&mut self, r: umbra_core::probe::TexelRead) {
        self.0.texel_read(r);
        self.1.texel_read(r);
    }
}
