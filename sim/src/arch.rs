//! Architecture models: probes that turn the core's events into cycles per
//! pipeline stage and bytes per memory, the way Sen et al.'s bandwidth model
//! counts a frame.
//!
//! Stages run pipelined; a pass takes as long as its slowest stage (the
//! bottleneck). Every cost is a parameter of the preset, and every
//! parameter says why it has its value.

use serde::Serialize;
use umbra_core::probe::{Buffer, CullLevel, Event};
use umbra_core::{DepthFormatKind, DepthUnit, Probe};

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

/// A probe charging an architecture's costs.
#[derive(Clone, Debug)]
pub struct ArchProbe {
    /// The parameters.
    pub params: ArchParams,
    format: DepthFormatKind,
    buffers: u64,
    /// Cycles per stage, in [`Stage::ALL`] order.
    pub cycles: [u64; 5],
    /// DRAM bytes.
    pub dram: Dram,
    /// Triangle-tile pairs rasterised.
    pub pairs: u64,
    /// Triangle-tile pairs and blocks skipped by max-z culling.
    pub culled: u64,
    /// Shadow lookups decided by the tiles' bounds.
    pub lookups_culled: u64,
    /// Map samples compared.
    pub samples: u64,
    /// Pixels that needed virtual samples.
    pub tangent_setups: u64,
    /// Pixels decided by the ordinary comparison.
    pub trivial: u64,
    /// Fragments generated (the scene fill of a camera pass).
    pub fragments: u64,
    /// Silhouette-pass fragments.
    pub silhouette_fragments: u64,
    /// Shadow-volume fragments.
    pub volume_fragments: u64,
    /// Per triangle-tile pair in processing order: the tile and the cycles it
    /// took (the slower of raster and depth), for the timeline.
    pub tile_cycles: Vec<(u16, u16, u64)>,
    timeline: bool,
}

impl ArchProbe {
    /// A probe for a light pass of `unit` in `format`.
    #[must_use]
    pub fn new(params: ArchParams, format: DepthFormatKind, unit: DepthUnit) -> Self {
        Self {
            params,
            format,
            buffers: u64::from(unit.buffers()),
            cycles: [0; 5],
            dram: Dram::default(),
            pairs: 0,
            culled: 0,
            lookups_culled: 0,
            samples: 0,
            tangent_setups: 0,
            trivial: 0,
            fragments: 0,
            silhouette_fragments: 0,
            volume_fragments: 0,
            tile_cycles: Vec::new(),
            timeline: false,
        }
    }

    /// Also keep the per-tile timeline (for `umbra trace`).
    #[must_use]
    pub const fn with_timeline(mut self) -> Self {
        self.timeline = true;
        self
    }

    #[inline]
    fn charge(&mut self, stage: Stage, cycles: u64) {
        if let Some(c) = self.cycles.get_mut(stage as usize) {
            *c += cycles;
        }
    }

    /// The bottleneck stage and its cycles.
    #[must_use]
    pub fn bottleneck(&self) -> (Stage, u64) {
        Stage::ALL.iter().zip(self.cycles).max_by_key(|(_, c)| *c).map_or((Stage::Setup, 0), |(s, c)| (*s, c))
    }

    /// On-chip depth storage, bytes.
    #[must_use]
    pub fn on_chip_bytes(&self) -> u64 {
        let texels = u64::from(self.params.tile) * u64::from(self.params.tile);
        if self.params.off_chip_depth {
            // The max-z cache: one value per tile (counted for a 1024² map).
            (1024 / u64::from(self.params.tile)).pow(2) * u64::from(self.format.bytes())
        } else {
            texels * u64::from(self.format.bytes()) * self.buffers
        }
    }
}

impl Probe for ArchProbe {
    #[inline]
    fn event(&mut self, e: Event) {
        let p = self.params;
        let bytes = u64::from(self.format.bytes());
        match e {
            Event::TriangleSetup => self.charge(Stage::Setup, p.setup_cycles),
            Event::TriangleBinned { tiles } => {
                // Written at binning, read back when the bin is drained.
                self.dram.bins += 2 * (u64::from(tiles) * p.bin_entry_bytes) + 2 * p.setup_record_bytes;
            }
            Event::Fragments { tile, count } => {
                let count = u64::from(count);
                self.pairs += 1;
                self.fragments += count;
                let raster = p.raster_cycles_per_tile
                    + count.div_ceil(p.fragments_per_clock.max(1)) * u64::from(p.fragments_per_clock > 0);
                let depth = if p.depth_fragments_per_clock > 0 {
                    count.div_ceil(p.depth_fragments_per_clock) * self.buffers
                } else {
                    p.depth_cycles_per_bit * u64::from(self.format.bits()) * self.buffers
                };
                self.charge(Stage::Raster, raster);
                self.charge(Stage::Depth, depth);
                if self.timeline {
                    self.tile_cycles.push((tile.x, tile.y, raster.max(depth)));
                }
                if p.off_chip_depth {
                    self.dram.map_rmw_reads += count * bytes * self.buffers;
                }
            }
            Event::DepthWrite { buffer, texels, .. } if p.off_chip_depth && buffer != Buffer::Id => {
                self.dram.map_writes += u64::from(texels) * bytes;
            }
            Event::Culled { level: CullLevel::Triangle | CullLevel::Block, .. } => self.culled += 1,
            Event::TileLoad { bytes: b, .. } if !p.off_chip_depth => self.dram.map_rmw_reads += u64::from(b),
            Event::TileStore { bytes: b, cleared, .. } if !p.off_chip_depth => {
                let written = if p.resolve_test_value_only { u64::from(b) / self.buffers.max(1) } else { u64::from(b) };
                let written = if cleared { 0 } else { written };
                self.dram.map_writes += written;
                self.charge(Stage::Resolve, written.div_ceil(p.dram_bytes_per_cycle.max(1)));
            }
            Event::MapRead { texels, bytes: b, .. } => {
                self.samples += u64::from(texels);
                self.dram.map_reads += u64::from(b);
                self.charge(Stage::Shadow, u64::from(texels).div_ceil(p.samples_per_clock.max(1)));
            }
            Event::LookupCulled { .. } => self.lookups_culled += 1,
            Event::TangentSetup => {
                self.tangent_setups += 1;
                self.charge(Stage::Shadow, p.tangent_setup_cycles);
            }
            Event::TrivialPixel { .. } => self.trivial += 1,
            Event::SilhouetteFragments { fragments, bytes: b, .. } => {
                // Conservative line rasterization at the scan converter's rate;
                // the points go to memory like map texels.
                self.silhouette_fragments += u64::from(fragments);
                self.charge(Stage::Raster, u64::from(fragments).div_ceil(p.fragments_per_clock.max(1)));
                self.dram.silhouette_writes += u64::from(b);
            }
            Event::SilhouetteRead { points, bytes: b } => {
                self.dram.silhouette_reads += u64::from(b);
                self.charge(Stage::Shadow, u64::from(points).div_ceil(p.samples_per_clock.max(1)));
            }
            Event::VolumeFragments { fragments, depth_bytes } => {
                // Volume fragments are scan converted and depth tested like
                // scene fragments; the scene depth and stencil live off chip.
                let n = u64::from(fragments);
                self.volume_fragments += n;
                self.charge(Stage::Raster, n.div_ceil(p.fragments_per_clock.max(1)));
                self.charge(Stage::Depth, n.div_ceil(p.depth_fragments_per_clock.max(1)));
                self.dram.volume_depth_reads += u64::from(depth_bytes);
            }
            Event::StencilRead { bytes: b, .. } | Event::StencilWrite { bytes: b, .. } => {
                self.dram.stencil += u64::from(b);
            }
            _ => {}
        }
    }
}

/// The cost of one render on one architecture.
#[derive(Clone, Debug, Serialize)]
pub struct CostReport {
    /// The architecture.
    pub arch: &'static str,
    /// Light-pass cycles per stage, in [`Stage::ALL`] order.
    pub light_cycles: [u64; 5],
    /// The light pass's bottleneck stage and its cycles.
    pub light_bottleneck: (Stage, u64),
    /// Camera-pass cycles per stage.
    pub camera_cycles: [u64; 5],
    /// The camera pass's bottleneck stage and its cycles.
    pub camera_bottleneck: (Stage, u64),
    /// Light-pass DRAM traffic.
    pub light_dram: Dram,
    /// Camera-pass DRAM traffic (map reads as requested by the shadow unit;
    /// visibility depth if off chip).
    pub camera_dram: Dram,
    /// Map and silhouette-point bytes actually fetched through the
    /// preset's map cache (the requested bytes when it has none).
    pub map_bytes_fetched: u64,
    /// On-chip depth storage, bytes.
    pub on_chip_bytes: u64,
    /// Triangle-tile pairs and blocks skipped by max-z culling, as a
    /// fraction of those considered, light pass and camera visibility.
    pub max_z_cull_rate: [f64; 2],
    /// Shadow lookups decided by the tiles' bounds, per shaded pixel.
    pub lookups_culled_per_pixel: f64,
    /// Pixels that needed virtual samples, as a fraction of shaded pixels.
    pub virtual_sample_fraction: f64,
    /// Camera pixels on geometry.
    pub pixels: u64,
    /// Simulated camera-pass map bytes per pixel.
    pub map_bytes_per_pixel: f64,
    /// Sen et al.'s analytic shadow-map figure: 4 bytes per depth sample,
    /// times the samples the filter takes per pixel.
    pub sen_shadow_map_bytes_per_pixel: f64,
    /// Simulated camera-pass shadow bytes per pixel: map, silhouette
    /// points, volume depth and stencil.
    pub shadow_bytes_per_pixel: f64,
    /// Fragments of the camera's visibility pass (Sen et al.'s scene fill).
    pub scene_fill: u64,
    /// Sen et al.'s `P`: silhouette fragments over scene fill.
    pub silhouette_fill: f64,
    /// Sen et al.'s `O`: shadow-volume fragments over scene fill.
    pub overdraw: f64,
    /// Sen et al.'s silhouette-map figure, `4 + 24·P` bytes per pixel.
    pub sen_silhouette_bytes_per_pixel: f64,
    /// Sen et al.'s shadow-volume figure, `5.5·O` bytes per pixel.
    pub sen_volume_bytes_per_pixel: f64,
}

#[allow(clippy::cast_precision_loss, reason = "ratios of counts")]
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

impl CostReport {
    /// Combine the probes of the light pass and of the camera pass.
    #[must_use]
    pub fn new(
        light: &ArchProbe,
        camera: &ArchProbe,
        fetched: Option<u64>,
        pixels: u64,
        samples_per_pixel: u64,
    ) -> Self {
        let lookups = camera.trivial + camera.tangent_setups;
        // Map texels and silhouette points go through the cache, when there is one.
        let requested = camera.dram.cached();
        let fetched = fetched.unwrap_or(requested);
        Self {
            arch: light.params.name,
            light_cycles: light.cycles,
            light_bottleneck: light.bottleneck(),
            camera_cycles: camera.cycles,
            camera_bottleneck: camera.bottleneck(),
            light_dram: light.dram,
            camera_dram: camera.dram,
            map_bytes_fetched: fetched,
            on_chip_bytes: light.on_chip_bytes(),
            max_z_cull_rate: [
                ratio(light.culled, light.culled + light.pairs),
                ratio(camera.culled, camera.culled + camera.pairs),
            ],
            lookups_culled_per_pixel: ratio(camera.lookups_culled, pixels),
            virtual_sample_fraction: ratio(camera.tangent_setups, lookups),
            pixels,
            map_bytes_per_pixel: ratio(fetched, pixels),
            #[allow(clippy::cast_precision_loss, reason = "a small count")]
            sen_shadow_map_bytes_per_pixel: 4.0 * samples_per_pixel as f64,
            shadow_bytes_per_pixel: ratio(camera.dram.camera_shadow_bytes() - requested + fetched, pixels),
            scene_fill: camera.fragments,
            silhouette_fill: ratio(light.silhouette_fragments, camera.fragments),
            overdraw: ratio(camera.volume_fragments, camera.fragments),
            sen_silhouette_bytes_per_pixel: 4.0 + 24.0 * ratio(light.silhouette_fragments, camera.fragments),
            sen_volume_bytes_per_pixel: 5.5 * ratio(camera.volume_fragments, camera.fragments),
        }
    }

    /// Light bottleneck plus camera bottleneck cycles: the passes run one
    /// after the other, each as slow as its slowest stage.
    #[must_use]
    pub const fn total_cycles(&self) -> u64 {
        self.light_bottleneck.1 + self.camera_bottleneck.1
    }

    /// Every DRAM byte of both passes, camera map reads as fetched through
    /// the cache.
    #[must_use]
    pub const fn total_bytes(&self) -> u64 {
        self.light_dram.total() + self.camera_dram.total() - self.camera_dram.cached() + self.map_bytes_fetched
    }

    /// The report as a Markdown table.
    #[must_use]
    pub fn markdown(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let _ = writeln!(s, "### {}\n", self.arch);
        let _ = writeln!(s, "| pass | setup | raster | depth | shadow | resolve | bottleneck |");
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---|");
        for (name, c, b) in [
            ("light", self.light_cycles, self.light_bottleneck),
            ("camera", self.camera_cycles, self.camera_bottleneck),
        ] {
            let _ = writeln!(
                s,
                "| {name} | {} | {} | {} | {} | {} | {:?} ({} cycles) |",
                c[0], c[1], c[2], c[3], c[4], b.0, b.1
            );
        }
        let d = &self.light_dram;
        let _ = writeln!(
            s,
            "\nDRAM bytes: map writes {}, light-pass depth reads {}, bins {}, camera map reads {} requested / {} fetched; on-chip depth {} bytes.",
            d.map_writes,
            d.map_rmw_reads,
            d.bins,
            self.camera_dram.map_reads,
            self.map_bytes_fetched,
            self.on_chip_bytes
        );
        let _ = writeln!(
            s,
            "Max-z culled: {:.1} % (light), {:.1} % (camera visibility); {:.2} lookups culled per pixel; virtual samples for {:.2} % of pixels.",
            100.0 * self.max_z_cull_rate[0],
            100.0 * self.max_z_cull_rate[1],
            self.lookups_culled_per_pixel,
            100.0 * self.virtual_sample_fraction
        );
        let _ = writeln!(
            s,
            "Camera-pass map bytes per pixel: simulated {:.2}, Sen's shadow-map model {:.1} (4 B per depth sample).",
            self.map_bytes_per_pixel, self.sen_shadow_map_bytes_per_pixel
        );
        let _ = writeln!(
            s,
            "Camera-pass shadow bytes per pixel (map, silhouette points, volume depth, stencil): simulated {:.2}; Sen's model: silhouette map 4 + 24·P = {:.2} (P = {:.3}), shadow volumes 5.5·O = {:.2} (O = {:.2}).",
            self.shadow_bytes_per_pixel,
            self.sen_silhouette_bytes_per_pixel,
            self.silhouette_fill,
            self.sen_volume_bytes_per_pixel,
            self.overdraw
        );
        s
    }

    /// A per-tile timeline of the light pass in Chrome trace-event JSON
    /// (opens in Perfetto): one slice per triangle-tile pair, in processing
    /// order, one microsecond per cycle, one track per tile row.
    #[must_use]
    pub fn trace(light: &ArchProbe) -> serde_json::Value {
        let mut t = 0u64;
        let events: Vec<serde_json::Value> = light
            .tile_cycles
            .iter()
            .map(|&(x, y, cycles)| {
                let e = serde_json::json!({
                    "name": format!("tile ({x}, {y})"),
                    "cat": "light",
                    "ph": "X",
                    "ts": t,
                    "dur": cycles.max(1),
                    "pid": 1,
                    "tid": y,
                });
                t += cycles.max(1);
                e
            })
            .collect();
        serde_json::json!({ "traceEvents": events, "displayTimeUnit": "ns" })
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
