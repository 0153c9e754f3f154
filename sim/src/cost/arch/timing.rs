//! The timing model: a probe that charges every event of a pass to the
//! stage that does the work and the memory that holds its bytes, tile by
//! tile, and the time those charges take on an architecture.
//!
//! A tile (chunk, region; the rasterizer's screen tile on an
//! immediate-mode machine) takes as long as the slowest of its stages,
//! memory among them; a pass is the sum over its tiles, with the front end
//! (setup, binning) overlapped with them when the architecture says so.
//! Memory takes the longer of its bytes at the bandwidth and its requests
//! at the latency over the requests kept in flight (Little's law): the
//! latency the architecture cannot hide.

use super::file::{Arch, CacheParams};
use super::{Dram, Stage};
use crate::cost::cache::{Cache, MapCache, morton};
use serde::Serialize;
use umbra_core::probe::{Buffer, Event, Fragment, TexelRead, Totals};
use umbra_core::{DepthFormatKind, Probe, RasterConfig, TileId};

/// Which pass a probe counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PassKind {
    /// The light pass (the map), with its depth buffers.
    Light,
    /// The camera pass: visibility, then shading with the shadow unit or
    /// the stencil unit.
    Camera,
}

/// Bytes of one shaded pixel's colour written to the frame buffer.
pub const COLOUR_BYTES: u64 = 4;

/// What one tile (or the front end) did, in the units the timing charges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Work {
    /// Compute cycles per stage, in [`Stage::ALL`] order (memory's slot is
    /// filled by [`Work::memory_cycles`]).
    pub cycles: [f64; 6],
    /// DRAM bytes.
    pub bytes: u64,
    /// Bytes streamed: written or read in order, coalesced into bursts.
    pub streamed: u64,
    /// Scattered DRAM requests, one access each (uncached off-chip depth).
    pub requests: u64,
    /// Map-cache misses.
    pub map_misses: u64,
    /// Depth-cache misses.
    pub depth_misses: u64,
    /// Triangles drained from bins.
    pub triangles: u64,
    /// Fragments generated.
    pub fragments: u64,
    /// Pixels shaded.
    pub pixels: u64,
}

impl Work {
    fn charge(&mut self, stage: Stage, cycles: f64) {
        if let Some(c) = self.cycles.get_mut(stage as usize) {
            *c += cycles;
        }
    }

    /// Memory cycles: the bytes at the bandwidth, or the requests at the
    /// latency over those in flight, whichever is longer.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    pub fn memory_cycles(&self, arch: &Arch) -> f64 {
        let lat = arch.latency_cycles();
        let window = |c: &CacheParams| c.misses_in_flight.max(1) as f64;
        let requests = self.streamed.div_ceil(arch.dram.burst.max(1)) + self.requests;
        let latency_bound = requests as f64 * lat / arch.dram.requests_in_flight.max(1) as f64
            + self.map_misses as f64 * lat / window(&arch.map_cache)
            + self.depth_misses as f64 * lat / window(&arch.depth_cache);
        (self.bytes as f64 / arch.bytes_per_cycle()).max(latency_bound)
    }

    /// Cycles per stage, memory included; a shadow test that runs in the
    /// shading program adds to the shading.
    #[must_use]
    pub fn stages(&self, arch: &Arch) -> [f64; 6] {
        let mut c = self.cycles;
        c[Stage::Memory as usize] = self.memory_cycles(arch);
        if arch.shadow.in_shader {
            c[Stage::Shade as usize] += c[Stage::Shadow as usize];
            c[Stage::Shadow as usize] = 0.0;
        }
        c
    }

    fn scale(&mut self, k: u64) {
        #[allow(clippy::cast_precision_loss, reason = "k is 1 or 2")]
        for c in &mut self.cycles {
            *c *= k as f64;
        }
        self.bytes *= k;
        self.streamed *= k;
        self.requests *= k;
        self.map_misses *= k;
        self.depth_misses *= k;
    }
}

/// Accesses that cost energy.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Accesses {
    /// On-chip buffer accesses (tile buffers, stencil).
    pub buffer: u64,
    /// Cache accesses (map and depth caches).
    pub cache: u64,
    /// Fragment operations of the raster and depth units.
    pub raster_ops: u64,
    /// Sample comparisons of the shadow unit.
    pub shadow_ops: u64,
}

/// Energy of a pass or a frame, joules, by unit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EnergySplit {
    /// DRAM.
    pub dram: f64,
    /// On-chip buffers.
    pub buffers: f64,
    /// Caches.
    pub caches: f64,
    /// Scan conversion and depth testing.
    pub raster: f64,
    /// The shadow unit.
    pub shadow: f64,
}

impl EnergySplit {
    /// The sum over units.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.dram + self.buffers + self.caches + self.raster + self.shadow
    }

    /// Both added.
    #[must_use]
    pub fn plus(&self, o: &Self) -> Self {
        Self {
            dram: self.dram + o.dram,
            buffers: self.buffers + o.buffers,
            caches: self.caches + o.caches,
            raster: self.raster + o.raster,
            shadow: self.shadow + o.shadow,
        }
    }
}

/// A pass's time on an architecture.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PassTiming {
    /// Cycles per stage summed over the tiles (the front end's in setup and
    /// memory), in [`Stage::ALL`] order.
    pub stages: [f64; 6],
    /// The front end's cycles (setup and bin writes).
    pub front: f64,
    /// The tiles' cycles: each tile its slowest stage, summed.
    pub tiles: f64,
    /// The pass: front end and tiles as the architecture overlaps them,
    /// plus its fixed overhead.
    pub cycles: f64,
    /// Tiles with work bound by each stage, in [`Stage::ALL`] order.
    pub bound: [u64; 6],
    /// The stage that bounds the most cycles.
    pub bottleneck: Stage,
    /// DRAM bytes.
    pub bytes: u64,
    /// Energy by unit.
    pub energy: EnergySplit,
}

impl PassTiming {
    /// The pass-level bound: the slowest stage summed over the whole pass.
    #[must_use]
    pub fn pass_bound(&self) -> f64 {
        self.stages.iter().copied().fold(0.0, f64::max)
    }

    /// Every stage's cycles added, as if nothing overlapped.
    #[must_use]
    pub fn serial(&self) -> f64 {
        self.stages.iter().sum()
    }
}

/// Where a pass timed per draw is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Submitting a draw's triangles.
    Front,
    /// Drawing its bins.
    Back,
    /// Shading the covered pixels.
    Shade,
}

/// A probe charging an architecture's costs for one pass.
///
/// With `FRAGMENT_DETAIL`, off-chip depth is read and written through the
/// architecture's depth cache, fragment by fragment; without it, every
/// off-chip access is charged as uncached (one request each).
#[derive(Clone, Debug)]
pub struct ArchProbe<const FRAGMENT_DETAIL: bool = false> {
    /// The architecture.
    pub arch: Arch,
    kind: PassKind,
    raster: RasterConfig,
    format: DepthFormatKind,
    /// Depth buffers updated per fragment in one pass.
    buffers: u64,
    /// Light passes the depth takes (2 for a second depth by a second pass).
    passes: u64,
    /// The front end: setup and bin writes.
    pub front: Work,
    /// The silhouette pass, when there is one.
    pub silhouette: Work,
    /// The depth cache's final write-back, after the tiles.
    pub drain: Work,
    /// The units a pass is timed in: per tile of the target, row-major; on
    /// an immediate-mode machine ([`Arch::immediate`]), per draw, in order
    /// (each draw finished before the next), the shading after them one
    /// more, the shadow volumes one more.
    pub tiles: Vec<Work>,
    current: usize,
    across: usize,
    /// Timed per draw, not per tile.
    per_draw: bool,
    /// Where a per-draw pass is: in the front end, drawing, or shading.
    phase: Phase,
    /// Each shaded pixel looks the map up (a shadowed camera pass).
    lookups: bool,
    /// Covered pixels whose lookup read silhouette points (Sen et al.'s
    /// bandwidth-model `P`, times the covered pixels).
    pub reconstructed_pixels: u64,
    /// The pixel being shaded has read silhouette points.
    reconstructed: bool,
    /// DRAM bytes by purpose.
    pub dram: Dram,
    /// Accesses that cost energy.
    pub accesses: Accesses,
    /// Every event of the pass, totalled.
    pub events: Totals,
    map_cache: Option<MapCache>,
    depth_cache: Option<Cache>,
}

/// A cache of `c`'s geometry, or none when its size is 0.
fn cache(c: &CacheParams) -> Option<Cache> {
    u32::try_from(c.line)
        .ok()
        .zip(u32::try_from(c.ways).ok())
        .and_then(|(line, ways)| Cache::new(c.size, line, ways).ok())
        .filter(|_| c.size > 0)
}

impl<const D: bool> ArchProbe<D> {
    /// A probe for a pass of `kind` over `raster` with `buffers` depth
    /// buffers of `format` (the light pass's unit; 1 for the camera pass).
    /// A light pass on an architecture that computes the second depth by a
    /// second pass counts one buffer per pass and two passes.
    #[must_use]
    pub fn new(arch: &Arch, kind: PassKind, raster: RasterConfig, format: DepthFormatKind, buffers: u32) -> Self {
        let buffers = u64::from(buffers.max(1));
        let (buffers, passes) =
            if kind == PassKind::Light && buffers == 2 && arch.depth.second_depth_pass { (1, 2) } else { (buffers, 1) };
        Self {
            arch: arch.clone(),
            kind,
            raster,
            format,
            buffers,
            passes,
            front: Work::default(),
            silhouette: Work::default(),
            drain: Work::default(),
            tiles: if arch.immediate() { Vec::new() } else { vec![Work::default(); raster.tile_count()] },
            per_draw: arch.immediate(),
            phase: Phase::Front,
            current: 0,
            lookups: false,
            reconstructed_pixels: 0,
            reconstructed: false,
            across: raster.tiles().0 as usize,
            dram: Dram::default(),
            accesses: Accesses::default(),
            events: Totals::default(),
            map_cache: cache(&arch.map_cache).map(|c| MapCache::new(c, 1, format.bytes())),
            // Without each fragment's address the cache cannot be modelled:
            // every access is then charged as uncached.
            depth_cache: if D { cache(&arch.depth_cache) } else { None },
        }
    }

    /// A camera pass whose every shaded pixel looks up a map of `buffers`
    /// depth buffers (1 or 2) of `bytes`-byte texels and silhouette points
    /// of `silhouette_bytes`, through the map cache.
    #[must_use]
    pub fn reading(mut self, buffers: u32, bytes: u32, silhouette_bytes: u32) -> Self {
        self.lookups = true;
        self.map_cache =
            self.map_cache.map(|m| MapCache::new(m.cache, buffers, bytes).with_silhouette(silhouette_bytes));
        self
    }

    fn on_chip_depth(&self) -> bool {
        match self.kind {
            PassKind::Light => self.arch.on_chip.light_depth,
            PassKind::Camera => self.arch.on_chip.camera_depth,
        }
    }

    fn select(&mut self, tile: TileId) {
        if !self.per_draw {
            self.current = usize::from(tile.y) * self.across + usize::from(tile.x);
        }
    }

    /// A pass timed per draw enters `phase`: a draw's first triangle after
    /// the last one's bins, or the first shaded pixel, opens a unit.
    fn enter(&mut self, phase: Phase) {
        if !self.per_draw || phase == self.phase {
            return;
        }
        if phase != Phase::Back || self.tiles.is_empty() {
            self.tiles.push(Work::default());
            self.current = self.tiles.len() - 1;
        }
        self.phase = phase;
    }

    fn work(&mut self) -> &mut Work {
        let i = self.current.min(self.tiles.len().saturating_sub(1));
        if self.tiles.is_empty() {
            self.tiles.push(Work::default());
        }
        &mut self.tiles[i]
    }

    /// Streamed bytes of the current tile: moved in bursts.
    fn stream(&mut self, bytes: u64) {
        let w = self.work();
        w.bytes += bytes;
        w.streamed += bytes;
    }

    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    fn per(count: u64, rate: f64) -> f64 {
        if rate > 0.0 { count as f64 / rate } else { 0.0 }
    }

    /// Raster and depth cycles of `count` fragments of one triangle in one
    /// tile (`buffers` depth buffers each).
    fn fragments(&mut self, count: u64, buffers: u64) {
        let a = &self.arch;
        let raster = if a.raster.fragments_per_clock > 0.0 {
            Self::per(count, a.raster.fragments_per_clock)
        } else {
            a.raster.cycles_per_tile
        };
        #[allow(clippy::cast_precision_loss, reason = "small counts")]
        let depth = if a.depth.fragments_per_clock > 0.0 {
            Self::per(count * buffers, a.depth.fragments_per_clock)
        } else {
            a.depth.cycles_per_bit * f64::from(self.format.bits()) * buffers as f64
        };
        self.accesses.raster_ops += count;
        let w = self.work();
        w.charge(Stage::Raster, raster);
        w.charge(Stage::Depth, depth);
        w.fragments += count;
    }

    /// A depth-cache access at `address`; a miss fetches a line, a dirty
    /// victim is written back.
    fn depth_access(&mut self, address: u64) {
        let Some(c) = self.depth_cache.as_mut() else { return };
        self.accesses.cache += 1;
        let (hit, writeback) = c.access_write(address);
        let line = c.line();
        let w = self.work();
        if !hit {
            w.bytes += line;
            w.depth_misses += 1;
        }
        if writeback {
            w.bytes += line;
            w.streamed += line;
        }
        let rmw = if hit { 0 } else { line } + if writeback { line } else { 0 };
        self.dram.depth_rmw += rmw;
    }

    /// Finish the pass: write back what the depth cache still holds dirty.
    pub fn finish(&mut self) {
        if let Some(c) = self.depth_cache.as_mut() {
            let bytes = c.flush() * c.line();
            self.dram.depth_rmw += bytes;
            self.drain.bytes += bytes;
            self.drain.streamed += bytes;
        }
    }

    /// The pass's time, bytes and energy.
    #[must_use]
    pub fn timing(&self) -> PassTiming {
        let a = &self.arch;
        let mut t = PassTiming::default();
        let mut per_stage_bound = [0.0f64; 6];
        let mut tile_memory = 0.0;
        for w in &self.tiles {
            let mut w = *w;
            w.scale(self.passes);
            let s = w.stages(a);
            let slowest = s.iter().copied().fold(0.0, f64::max);
            if slowest > 0.0 {
                let stage = s.iter().position(|&c| c == slowest).unwrap_or(0);
                t.bound[stage] += 1;
                per_stage_bound[stage] += slowest;
            }
            for (acc, c) in t.stages.iter_mut().zip(s) {
                *acc += c;
            }
            tile_memory += s[Stage::Memory as usize];
            t.tiles += slowest;
            t.bytes += w.bytes;
        }
        let mut front = self.front;
        front.scale(self.passes);
        let fs = front.stages(a);
        t.front = fs.iter().copied().fold(0.0, f64::max);
        for (acc, c) in t.stages.iter_mut().zip(fs) {
            *acc += c;
        }
        t.bytes += front.bytes;
        // A second depth by a second pass ends with a pass combining the two
        // maps: two reads and a write per texel, one fragment per texel.
        let mut combine = Work::default();
        if self.passes > 1 {
            let texels = self.raster.texel_count() as u64;
            combine.bytes = 3 * texels * u64::from(self.format.bytes());
            combine.streamed = combine.bytes;
            combine.cycles[Stage::Raster as usize] = Self::per(texels, a.raster.fragments_per_clock.max(1.0));
        }
        let cs = combine.stages(a);
        let combine_cycles = cs.iter().copied().fold(0.0, f64::max);
        for (acc, c) in t.stages.iter_mut().zip(cs) {
            *acc += c;
        }
        t.bytes += combine.bytes;
        // The silhouette pass and the depth cache's write-back follow the
        // tiles, each with its own stages.
        let mut after = 0.0;
        for w in [&self.silhouette, &self.drain] {
            let ws = w.stages(a);
            after += ws.iter().copied().fold(0.0, f64::max);
            for (acc, c) in t.stages.iter_mut().zip(ws) {
                *acc += c;
            }
            t.bytes += w.bytes;
        }
        // A pass that drew nothing (no light pass for shadow volumes, none
        // at all without shadows) waits for no host.
        #[allow(clippy::cast_precision_loss, reason = "1 or 2")]
        let overhead = if self.events.submitted > 0 { a.front.pass_overhead_cycles * self.passes as f64 } else { 0.0 };
        // Overlapped, the front end and the tiles still share the DRAM.
        let shared = fs[Stage::Memory as usize] + tile_memory;
        let body = if a.front.overlap { t.front.max(t.tiles).max(shared) } else { t.front + t.tiles };
        t.cycles = overhead + body + combine_cycles + after;
        t.bottleneck = if a.front.overlap && shared > t.tiles.max(t.front) {
            Stage::Memory
        } else if a.front.overlap && t.front > t.tiles {
            if fs[Stage::Memory as usize] > fs[Stage::Setup as usize] { Stage::Memory } else { Stage::Setup }
        } else {
            Stage::ALL
                .iter()
                .zip(per_stage_bound)
                .fold((Stage::Setup, -1.0), |b, (&s, c)| if c > b.1 { (s, c) } else { b })
                .0
        };
        t.energy = self.energy(t.bytes);
        t
    }

    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    fn energy(&self, bytes: u64) -> EnergySplit {
        let e = &self.arch.energy;
        let k = self.passes as f64;
        EnergySplit {
            dram: bytes as f64 * e.dram_byte,
            buffers: self.accesses.buffer as f64 * e.buffer_access * k,
            caches: self.accesses.cache as f64 * e.cache_access * k,
            raster: self.accesses.raster_ops as f64 * e.fragment_op * k,
            shadow: self.accesses.shadow_ops as f64 * e.fragment_op,
        }
    }

    /// Bytes of on-chip depth storage the pass needs: the tile buffers, or
    /// on an off-chip machine the per-tile max-z bounds.
    #[must_use]
    pub fn on_chip_bytes(&self) -> u64 {
        let bytes = u64::from(self.format.bytes());
        if self.on_chip_depth() {
            let side = u64::from(self.arch.raster.tile);
            side * side * bytes * self.buffers
        } else {
            self.raster.tile_count() as u64 * bytes
        }
    }

    fn map_read(&mut self, texels: u64, bytes: u64) {
        self.accesses.shadow_ops += texels;
        let spc = self.arch.shadow.samples_per_clock;
        self.work().charge(Stage::Shadow, Self::per(texels, spc));
        if self.map_cache.is_none() {
            self.stream(bytes);
        }
    }
}

impl<const D: bool> Probe for ArchProbe<D> {
    const FRAGMENTS: bool = D;
    const TEXELS: bool = true;

    #[inline]
    #[allow(clippy::too_many_lines, reason = "one arm per event: the exhaustive account")]
    fn event(&mut self, e: Event) {
        self.events.add(e);
        let n = u64::from;
        let bytes = n(self.format.bytes());
        let on_chip = self.on_chip_depth();
        let cached = self.depth_cache.is_some();
        match e {
            // Counted in `events`; the work is the setup that follows, or none.
            Event::TriangleSubmitted => {
                if self.phase == Phase::Back {
                    self.enter(Phase::Front);
                }
            }
            Event::TriangleRejected { .. } => {}
            Event::TriangleSetup => self.front.charge(Stage::Setup, self.arch.front.setup_cycles),
            Event::TriangleBinned { tiles } => {
                // The entries and the setup record, written at binning.
                let b =
                    n(tiles) * self.arch.bins.entry_bytes + self.arch.bins.setup_record_bytes * u64::from(tiles > 0);
                self.dram.bins += b;
                self.front.bytes += b;
                self.front.streamed += b;
            }
            Event::BinFlush { tile, triangles, .. } => {
                // The entries and their setup records, read back.
                self.enter(Phase::Back);
                self.select(tile);
                let b = n(triangles) * (self.arch.bins.entry_bytes + self.arch.bins.setup_record_bytes);
                self.dram.bins += b;
                self.stream(b);
                self.work().triangles += n(triangles);
            }
            Event::TileLoad { tile, bytes: b } => {
                self.select(tile);
                if on_chip {
                    self.dram.map_rmw_reads += n(b);
                    self.stream(n(b));
                }
            }
            Event::TileStore { tile, bytes: b, cleared } => {
                self.select(tile);
                // The camera's visibility stays on chip for shading; a
                // cleared tile is a fast clear.
                if on_chip && self.kind == PassKind::Light && !cleared {
                    let written =
                        if self.arch.on_chip.resolve_test_value_only { n(b) / self.buffers.max(1) } else { n(b) };
                    self.dram.map_writes += written;
                    self.stream(written);
                }
            }
            Event::Fragments { tile, count } => {
                self.select(tile);
                self.fragments(n(count), self.buffers);
                if !on_chip && !cached {
                    // Uncached: every fragment reads each buffer, one request each.
                    let (b, requests) = (n(count) * bytes * self.buffers, n(count) * self.buffers);
                    self.dram.depth_rmw += b;
                    let w = self.work();
                    w.bytes += b;
                    w.requests += requests;
                }
            }
            Event::Culled { tile, .. } => {
                // One max-z compare in the rasterizer's slot.
                self.select(tile);
                self.work().charge(Stage::Raster, 1.0);
            }
            Event::DepthRead { texels, .. } => {
                if on_chip {
                    self.accesses.buffer += n(texels);
                }
            }
            Event::DepthWrite { buffer, texels, bytes: b } => {
                if on_chip {
                    self.accesses.buffer += n(texels);
                } else if !cached && (buffer != Buffer::Id || self.kind == PassKind::Camera) {
                    // Uncached: each texel written is its own request.
                    self.dram.depth_rmw += n(b);
                    let w = self.work();
                    w.bytes += n(b);
                    w.requests += n(texels);
                }
            }
            Event::TileMaxUpdate { tile } => {
                // A reduction over the tile's texels at the depth unit's rate.
                self.select(tile);
                let texels = u64::from(self.arch.raster.tile).pow(2);
                let dfpc = self.arch.depth.fragments_per_clock;
                let cycles = if dfpc > 0.0 {
                    Self::per(texels, dfpc)
                } else {
                    self.arch.depth.cycles_per_bit * f64::from(self.format.bits())
                };
                self.work().charge(Stage::Depth, cycles);
            }
            Event::MapRead { texels, bytes: b, .. } => {
                self.dram.map_reads += n(b);
                self.map_read(n(texels), n(b));
            }
            Event::LookupCulled { .. } => {
                // One compare against the tiles' bounds.
                self.accesses.shadow_ops += 1;
                let spc = self.arch.shadow.samples_per_clock;
                self.work().charge(Stage::Shadow, Self::per(1, spc));
            }
            Event::VirtualSamples { count } => {
                // Forward differences: an add and a compare per sample.
                self.accesses.shadow_ops += n(count);
                let spc = self.arch.shadow.samples_per_clock;
                self.work().charge(Stage::Shadow, Self::per(n(count), spc));
            }
            Event::TangentSetup => {
                // A division occupies one of the dividers for its latency.
                #[allow(clippy::cast_precision_loss, reason = "a small count")]
                let d = self.arch.shadow.divider_cycles / self.arch.shadow.dividers.max(1) as f64;
                self.work().charge(Stage::Shadow, d);
            }
            // Counted in `events`: decisions about work charged above.
            Event::TangentFallback | Event::TrivialPixel { .. } => {}
            Event::PixelShaded { x, y } => {
                self.enter(Phase::Shade);
                self.reconstructed = false;
                let s = self.raster.tile_shift();
                #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
                self.select(TileId { x: (x >> s) as u16, y: (y >> s) as u16 });
                let c = self.arch.shade.cycles_per_pixel;
                let lookup = if self.lookups { self.arch.shadow.cycles_per_lookup } else { 0.0 };
                let w = self.work();
                w.charge(Stage::Shade, c);
                w.charge(Stage::Shadow, lookup);
                w.pixels += 1;
                self.dram.colour += COLOUR_BYTES;
                self.stream(COLOUR_BYTES);
            }
            Event::SilhouetteFragments { fragments, bytes: b, .. } => {
                // Conservative line rasterization at the scan converter's
                // rate; the points stream to memory.
                let a = &self.arch;
                let raster = if a.raster.fragments_per_clock > 0.0 {
                    Self::per(n(fragments), a.raster.fragments_per_clock)
                } else {
                    a.raster.cycles_per_tile
                };
                self.accesses.raster_ops += n(fragments);
                self.dram.silhouette_writes += n(b);
                let w = &mut self.silhouette;
                w.charge(Stage::Raster, raster);
                w.fragments += n(fragments);
                w.bytes += n(b);
                w.streamed += n(b);
            }
            Event::SilhouetteRead { points, bytes: b } => {
                // Once per pixel, however many of its samples needed it.
                self.reconstructed_pixels += u64::from(!self.reconstructed);
                self.reconstructed = true;
                self.dram.silhouette_reads += n(b);
                self.map_read(n(points), n(b));
            }
            Event::VolumeFragments { tile, fragments, depth_bytes } => {
                // Scan converted and depth tested like scene fragments,
                // against the scene depth on chip or in DRAM.
                self.select(tile);
                self.fragments(n(fragments), 1);
                if self.arch.on_chip.stencil {
                    self.accesses.buffer += n(fragments);
                } else {
                    self.dram.volume_depth_reads += n(depth_bytes);
                    self.stream(n(depth_bytes));
                }
            }
            Event::StencilRead { tile, texels, bytes: b } | Event::StencilWrite { tile, texels, bytes: b } => {
                self.select(tile);
                if self.arch.on_chip.stencil {
                    self.accesses.buffer += n(texels);
                } else {
                    self.dram.stencil += n(b);
                    self.stream(n(b));
                }
            }
        }
    }

    #[inline]
    fn fragment(&mut self, f: Fragment) {
        // Off-chip depth through the depth cache: each buffer's texel (and
        // the id on the camera pass), Morton-ordered, planes side by side.
        if self.on_chip_depth() {
            return;
        }
        let bytes = u64::from(self.format.bytes());
        let planes = if self.kind == PassKind::Camera { 2 } else { self.buffers };
        let s = self.raster.tile_shift();
        #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
        self.select(TileId { x: (f.x >> s) as u16, y: (f.y >> s) as u16 });
        for plane in 0..planes {
            self.depth_access((morton(f.x, f.y) * planes + plane) * bytes.max(4));
        }
    }

    #[inline]
    fn texel_read(&mut self, r: TexelRead) {
        let Some(m) = self.map_cache.as_mut() else { return };
        let address = m.address(r);
        self.accesses.cache += 1;
        if !m.cache.access(address) {
            let line = m.cache.line();
            self.dram.map_fetched += line;
            let w = self.work();
            w.bytes += line;
            w.map_misses += 1;
        }
    }
}
