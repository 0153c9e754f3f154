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

mod events;
mod shading;
mod tally;

use crate::cost::arch::{Arch, CacheParams};
use crate::cost::cache::{Cache, MapCache};
use crate::cost::dram::{Dram, Purpose, Requested};
use crate::cost::ledger::PassTiming;
use crate::cost::work::{Accesses, EnergySplit, Work};
use crate::cost::work::{Bottleneck, MemoryLimit, Stage};
use serde::Serialize;
use shading::ShadeCounts;
#[cfg(test)]
pub(crate) use shading::charges_event_by_event;
pub(crate) use tally::Tally;
use umbra_core::probe::Totals;
use umbra_core::{DepthFormatKind, RasterConfig, TileId};

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
pub(crate) const COLOUR_BYTES: u64 = 4;

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
    /// Depth samples a lookup takes, and whether it weighs them bilinearly
    /// (what a programmable filter's instructions depend on).
    filter: (u64, bool),
    /// Covered pixels whose lookup read silhouette points (Sen et al.'s
    /// bandwidth-model `P`, times the covered pixels).
    pub reconstructed_pixels: u64,
    /// The pixel being shaded has read silhouette points.
    reconstructed: bool,
    /// What the shadow unit asked of memory before any cache.
    pub requested: Requested,
    /// Accesses that cost energy.
    pub accesses: Accesses,
    /// Every event of the pass, totalled.
    pub events: Totals,
    map_cache: Option<MapCache>,
    depth_cache: Option<Cache>,
    /// Which of the tilings a shadow unit tests its lookups against is
    /// this architecture's ([`umbra_core::probe::Tilings`]): 0, the map's
    /// own, unless a shared shading says otherwise.
    pub(crate) tiling: usize,
    /// Per unit of `tiles`, the shading's events tallied, charged when
    /// the pass is finished.
    shading: Vec<ShadeCounts>,
    /// Charge the shading event by event instead (the tallies' reference).
    event_by_event: bool,
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
            filter: (1, false),
            reconstructed_pixels: 0,
            reconstructed: false,
            across: raster.tiles().0 as usize,
            requested: Requested::default(),
            accesses: Accesses::default(),
            events: Totals::default(),
            map_cache: cache(&arch.map_cache).map(|c| MapCache::new(c, 1, format.bytes())),
            // Without each fragment's address the cache cannot be modelled:
            // every access is then charged as uncached.
            depth_cache: if D { cache(&arch.depth_cache) } else { None },
            tiling: 0,
            shading: Vec::new(),
            event_by_event: shading::event_by_event(),
        }
    }

    /// A camera pass whose every shaded pixel looks up a map of `buffers`
    /// depth buffers (1 or 2) of `bytes`-byte texels and silhouette points
    /// of `silhouette_bytes`, through the map cache, with a filter of
    /// `filter.0` samples (bilinearly weighted when `filter.1`).
    #[must_use]
    pub(crate) fn reading(mut self, buffers: u32, bytes: u32, silhouette_bytes: u32, filter: (u64, bool)) -> Self {
        self.lookups = true;
        self.filter = filter;
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

    /// The index of the unit being worked on (one is opened if there is none).
    fn unit(&mut self) -> usize {
        if self.tiles.is_empty() {
            self.tiles.push(Work::default());
        }
        self.current.min(self.tiles.len() - 1)
    }

    fn work(&mut self) -> &mut Work {
        let i = self.unit();
        &mut self.tiles[i]
    }

    /// `bytes` of DRAM traffic for `purpose` streamed by the current tile
    /// (moved in bursts): charged to its ledger.
    fn traffic(&mut self, purpose: Purpose, bytes: u64) {
        self.work().stream(purpose, bytes);
    }

    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    fn per(count: u64, rate: f64) -> f64 {
        if rate > 0.0 { count as f64 / rate } else { 0.0 }
    }

    /// The shading program's cycles for one shaded pixel (or fragment):
    /// the shading, and the shadow test's own instructions when it looks
    /// up — per lookup, per sample and for bilinear weights — and, on a
    /// machine shading per fragment, its samples' fetches too (charged per
    /// texel read otherwise). Returns (shade, shadow) cycles.
    fn program(&self) -> (f64, f64) {
        let a = &self.arch;
        if !self.lookups {
            return (a.shade.cycles_per_pixel, 0.0);
        }
        let (samples, weighted) = self.filter;
        #[allow(clippy::cast_precision_loss, reason = "at most 256 samples")]
        let samples = samples as f64;
        let fetch = if a.shade.per_fragment { samples / a.shadow.samples_per_clock } else { 0.0 };
        let weights = if weighted { a.shadow.cycles_per_weights } else { 0.0 };
        (a.shade.cycles_per_pixel, a.shadow.cycles_per_lookup + samples * a.shadow.cycles_per_sample + weights + fetch)
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
            w.dram.add(Purpose::OffChipDepth, line);
            w.depth_misses += 1;
        }
        if writeback {
            w.stream(Purpose::OffChipDepth, line);
        }
    }

    /// Finish the pass: charge the shading's tallies as cycles, and write
    /// back what the depth cache still holds dirty.
    pub fn finish(&mut self) {
        self.charge_tallies();
        if let Some(c) = self.depth_cache.as_mut() {
            let bytes = c.flush() * c.line();
            self.drain.stream(Purpose::OffChipDepth, bytes);
        }
    }

    /// The pass's time, bytes and energy.
    #[must_use]
    pub fn timing(&self) -> PassTiming {
        let a = &self.arch;
        let mut t = PassTiming::default();
        // Cycles of the tiles each bottleneck bounds; memory cycles of the
        // work each memory limit bounds.
        let mut per_bound = [0.0f64; 9];
        let mut by_limit = [0.0f64; 4];
        let add = |t: &mut PassTiming, by_limit: &mut [f64; 4], w: &Work| {
            let s = w.stages(a);
            for (acc, c) in t.stages.iter_mut().zip(s) {
                *acc += c;
            }
            let m = w.memory(a);
            t.memory = t.memory.plus(&m);
            by_limit[m.limit() as usize] += m.cycles();
            s
        };
        let mut tile_memory = 0.0;
        for w in &self.tiles {
            let mut w = *w;
            w.scale(self.passes);
            let s = add(&mut t, &mut by_limit, &w);
            if let Some((b, slowest)) = w.bottleneck(a) {
                t.bound[b as usize] += 1;
                per_bound[b as usize] += slowest;
                t.tiles += slowest;
            }
            tile_memory += s[Stage::Memory as usize];
        }
        let mut front = self.front;
        front.scale(self.passes);
        let fs = add(&mut t, &mut by_limit, &front);
        t.front = fs.iter().copied().fold(0.0, f64::max);
        // Overlapped, the front end and the tiles share the DRAM: what
        // limits it is what limits the most of their memory cycles (the
        // first on a tie).
        let shared_limit = MemoryLimit::ALL
            .into_iter()
            .zip(by_limit)
            .fold((MemoryLimit::Bandwidth, 0.0), |b, (l, c)| if c > b.1 { (l, c) } else { b })
            .0;
        let front_bound = front.bottleneck(a).map_or(Bottleneck::Setup, |b| b.0);
        // The body's cycles, each charged to what bound it: overlapped, the
        // longest of the front end, the tiles and the DRAM they share;
        // else the front end, then the tiles.
        let shared = fs[Stage::Memory as usize] + tile_memory;
        if a.front.overlap && shared > t.tiles.max(t.front) {
            t.bound_cycles[Bottleneck::of(Stage::Memory, shared_limit) as usize] += shared;
        } else if a.front.overlap && t.front > t.tiles {
            t.bound_cycles[front_bound as usize] += t.front;
        } else {
            t.bound_cycles = per_bound;
            if !a.front.overlap {
                t.bound_cycles[front_bound as usize] += t.front;
            }
        }
        // The units after the tiles, each its slowest stage's.
        for (_, w) in &self.tail() {
            add(&mut t, &mut [0.0; 4], w);
            if let Some((b, slowest)) = w.bottleneck(a) {
                t.bound_cycles[b as usize] += slowest;
            }
        }
        // A pass that drew nothing (no light pass for shadow volumes, none
        // at all without shadows) waits for no host; a second depth by
        // passes waits for both light passes and the combining pass.
        let waits = if self.passes > 1 { self.passes + 1 } else { self.passes };
        #[allow(clippy::cast_precision_loss, reason = "1 to 3")]
        let overhead = if self.events.submitted > 0 { a.front.pass_overhead_cycles * waits as f64 } else { 0.0 };
        t.overhead = overhead;
        t.clock = a.clock;
        t.dram = self.dram();
        t.map_cache = self.map_cache.as_ref().filter(|_| self.lookups).map(|m| m.cache.stats());
        t.depth_cache = self.depth_cache.as_ref().map(|c| c.stats().times(self.passes));
        t.energy = self.energy(t.bytes());
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
            leakage: 0.0,
        }
    }

    /// The units that follow the tiles, in order, each with its name: the
    /// pass combining two maps (a second depth by a second pass: two reads
    /// and a write a texel, one fragment a texel), the silhouette pass,
    /// and the depth cache's final write-back (once per light pass).
    #[must_use]
    pub(crate) fn tail(&self) -> [(&'static str, Work); 3] {
        let mut combine = Work::default();
        if self.passes > 1 {
            let texels = self.raster.texel_count() as u64;
            combine.stream(Purpose::MapCombine, 3 * texels * u64::from(self.format.bytes()));
            combine.cycles[Stage::Raster as usize] = Self::per(texels, self.arch.raster.fragments_per_clock.max(1.0));
            #[allow(clippy::cast_precision_loss, reason = "texels far below 2^53")]
            let program = texels as f64 * self.arch.depth.combine_cycles;
            combine.cycles[Stage::Shade as usize] = program;
        }
        // Each light pass writes back what its depth cache holds dirty.
        let mut drain = self.drain;
        drain.scale(self.passes);
        [("combining the maps", combine), ("silhouette pass", self.silhouette), ("depth cache write-back", drain)]
    }

    /// Tiles a row of the pass's target, when it is timed per tile (row
    /// major); `None` when it is timed per draw.
    #[must_use]
    pub(crate) const fn tiles_across(&self) -> Option<usize> {
        if self.per_draw { None } else { Some(self.across) }
    }

    /// Bytes of on-chip depth storage the pass needs: the tile buffers, or
    /// on an off-chip machine the per-tile max-z bounds.
    #[must_use]
    pub fn on_chip_bytes(&self) -> u64 {
        // A pass that drew nothing (no light pass for shadow volumes)
        // stores nothing.
        if self.events.submitted == 0 {
            return 0;
        }
        let bytes = u64::from(self.format.bytes());
        if self.on_chip_depth() {
            let side = u64::from(self.arch.raster.tile);
            side * side * bytes * self.buffers
        } else {
            self.raster.tile_count() as u64 * bytes
        }
    }

    /// `texels` (or points) the shadow unit read, `bytes` in all, for
    /// `purpose` when no map cache stands between (its fills are charged
    /// per line otherwise).
    fn map_read(&mut self, texels: u64, bytes: u64, purpose: Purpose) {
        self.accesses.shadow_ops += texels;
        // A machine shading per fragment fetches in its program.
        self.shaded(&ShadeCounts { samples: texels, ..ShadeCounts::default() });
        if self.map_cache.is_none() {
            self.traffic(purpose, bytes);
        }
    }

    /// The pass's DRAM traffic by purpose: its units' ledgers added (the
    /// tiles and the front end once per light pass it takes).
    #[must_use]
    pub fn dram(&self) -> Dram {
        let drawn = self.tiles.iter().fold(self.front.dram, |a, w| a.plus(&w.dram)).times(self.passes);
        self.tail().iter().fold(drawn, |a, (_, w)| a.plus(&w.dram))
    }
}
