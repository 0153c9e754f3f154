//! The parameters of each hardware unit an architecture file describes:
//! the front end, the rasterizer, the depth unit, on-chip buffers, bins,
//! the shadow unit, shading, DRAM, the caches and energy per access.

use serde::Serialize;

/// The front end: setup and binning.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Front {
    /// Cycles per triangle set up (the setup engine's issue interval).
    pub setup_cycles: f64,
    /// Setup and binning run concurrently with the tiles (a frame ahead on
    /// a tiler, pipelined on an immediate-mode machine).
    pub overlap: bool,
    /// Fixed cycles per pass spent waiting for the host.
    pub pass_overhead_cycles: f64,
    /// Fixed cycles per frame spent in the host and the driver (a frame
    /// that draws anything).
    pub frame_overhead_cycles: f64,
}

/// Scan conversion.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Raster {
    /// Side of the tile (chunk, region) in pixels.
    pub tile: u32,
    /// Fragments scan-converted per clock (0: an evaluator instead).
    pub fragments_per_clock: f64,
    /// PixelFlow's linear-expression evaluator: cycles per triangle per
    /// tile it touches, whatever its fragment count.
    pub cycles_per_tile: f64,
}

/// The depth unit.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DepthRates {
    /// Fragments depth-tested per clock, per buffer (0: bit-serial).
    pub fragments_per_clock: f64,
    /// Bit-serial processors: cycles per depth bit per buffer per triangle
    /// per tile.
    pub cycles_per_bit: f64,
    /// The second depth takes a second light pass and a pass combining the
    /// two maps (a machine with one depth buffer per fragment), instead of
    /// a second buffer updated per fragment.
    pub second_depth_pass: bool,
    /// Cycles per light-pass fragment that passes the depth test of a
    /// fragment program writing the map (a colour target on a machine
    /// without depth textures); 0 for a fixed-function depth unit.
    pub program_cycles: f64,
    /// The second light pass's further cycles per such fragment: reading
    /// the first map and discarding what it holds.
    pub peel_cycles: f64,
    /// Cycles per texel of the pass combining the two maps' program.
    pub combine_cycles: f64,
}

/// Which buffers live on chip.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct OnChip {
    /// The light pass's depth buffers (else read-modify-written in DRAM per
    /// fragment).
    pub light_depth: bool,
    /// The camera pass's visibility depth and ids.
    pub camera_depth: bool,
    /// The stencil and the scene depth shadow-volume fragments test.
    pub stencil: bool,
    /// The resolve writes only the value the shadow test reads.
    pub resolve_test_value_only: bool,
}

/// Bins in memory (tilers).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Bins {
    /// Bytes of one bin entry.
    pub entry_bytes: u64,
    /// Bytes of one triangle's setup record, written at binning and read at
    /// each flush of a tile it is binned to.
    pub setup_record_bytes: u64,
}

/// The shadow unit.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ShadowRates {
    /// Map samples compared per clock.
    pub samples_per_clock: f64,
    /// Latency of one division (a tangent-plane setup), not pipelined.
    pub divider_cycles: f64,
    /// Dividers working in parallel.
    pub dividers: u64,
    /// Cycles per pixel looked up besides the samples: a programmable
    /// shadow test's own instructions (0 for fixed function).
    pub cycles_per_lookup: f64,
    /// Cycles per sample besides its fetch: a programmable filter's
    /// offset, compare and accumulate (0 for fixed function).
    pub cycles_per_sample: f64,
    /// Cycles per bilinear lookup computing its weights from the
    /// fractional texel coordinates (0 for fixed function).
    pub cycles_per_weights: f64,
    /// The shadow test runs in the shading program on the same units: its
    /// cycles add to the shading's instead of overlapping them.
    pub in_shader: bool,
}

/// The shading work besides the shadow lookup.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Shade {
    /// Cycles per shaded pixel (throughput, whole chip; 0 for fixed function).
    pub cycles_per_pixel: f64,
    /// Shading runs for every camera fragment that passes the depth test
    /// as it arrives (an immediate-mode machine without deferred shading),
    /// not once per covered pixel.
    pub per_fragment: bool,
}

/// DRAM.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DramParams {
    /// Bytes per second.
    pub bandwidth: f64,
    /// Seconds from request to data.
    pub latency: f64,
    /// Bytes of one access.
    pub burst: u64,
    /// Requests the memory system keeps in flight.
    pub requests_in_flight: u64,
}

/// A cache (size 0: none).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CacheParams {
    /// Bytes.
    pub size: u64,
    /// Bytes of a line.
    pub line: u64,
    /// Associativity.
    pub ways: u64,
    /// Misses outstanding at once.
    pub misses_in_flight: u64,
}

/// Energy per access, joules.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Energy {
    /// Per DRAM byte.
    pub dram_byte: f64,
    /// Per on-chip buffer access.
    pub buffer_access: f64,
    /// Per cache access.
    pub cache_access: f64,
    /// Per fragment operation (a fragment scan-converted and depth-tested,
    /// a sample compared).
    pub fragment_op: f64,
}

/// The process the units are built in: what a bit of storage, a gate of
/// logic and a square millimetre's leakage cost there
/// ([`crate::cost::silicon`]). An empty node with every figure 0 (a file
/// written before format 3) models no silicon: no area and no static
/// energy, as before.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Technology {
    /// The process node the figures are for (`TSMC N5`); empty for none.
    pub node: String,
    /// Area of one high-density 6T SRAM bit cell, square metres.
    pub sram_bit: f64,
    /// The bit cells' share of an SRAM array's area (the rest is
    /// decoders, sense amplifiers, drivers and assist circuits).
    pub array_efficiency: f64,
    /// Area of one NAND2 gate equivalent of logic, placed and routed,
    /// square metres.
    pub gate: f64,
    /// Leakage power per square metre of the units, watts.
    pub leakage: f64,
}
