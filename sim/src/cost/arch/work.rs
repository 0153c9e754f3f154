//! What the timing model charges: a tile's (or the front end's) work in
//! cycles per stage and DRAM traffic, the accesses that cost energy, and a
//! pass's time.

use super::file::{Arch, CacheParams};
use super::{Bottleneck, Stage};
use crate::cost::cache::CacheStats;
use serde::Serialize;

/// What limits memory time: the bytes at the bandwidth, or the requests at
/// the latency over those kept in flight.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MemoryLimit {
    /// Bytes at the DRAM's bandwidth.
    #[default]
    Bandwidth,
    /// Requests at the latency over those in flight (Little's law).
    Latency,
}

/// Memory time, cycles, as each limit would make it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct MemoryTime {
    /// The bytes at the bandwidth.
    pub bandwidth_cycles: f64,
    /// The requests (bursts, scattered accesses, cache misses) at the
    /// latency over those in flight.
    pub latency_cycles: f64,
}

impl MemoryTime {
    /// The time memory takes: the longer of the two.
    #[must_use]
    pub const fn cycles(&self) -> f64 {
        self.bandwidth_cycles.max(self.latency_cycles)
    }

    /// Which of the two it is (bandwidth on a tie).
    #[must_use]
    pub fn limit(&self) -> MemoryLimit {
        if self.latency_cycles > self.bandwidth_cycles { MemoryLimit::Latency } else { MemoryLimit::Bandwidth }
    }

    /// Both added.
    #[must_use]
    pub fn plus(&self, o: &Self) -> Self {
        Self {
            bandwidth_cycles: self.bandwidth_cycles + o.bandwidth_cycles,
            latency_cycles: self.latency_cycles + o.latency_cycles,
        }
    }
}

/// What one tile (or the front end) did, in the units the timing charges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Work {
    /// Compute cycles per stage, in [`Stage::ALL`] order (memory's slot is
    /// filled by [`Work::memory`]).
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
    pub(super) fn charge(&mut self, stage: Stage, cycles: f64) {
        if let Some(c) = self.cycles.get_mut(stage as usize) {
            *c += cycles;
        }
    }

    /// Memory time: the bytes at the bandwidth, and the requests at the
    /// latency over those in flight.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    pub fn memory(&self, arch: &Arch) -> MemoryTime {
        let lat = arch.latency_cycles();
        let window = |c: &CacheParams| c.misses_in_flight.max(1) as f64;
        let requests = self.streamed.div_ceil(arch.dram.burst.max(1)) + self.requests;
        MemoryTime {
            bandwidth_cycles: self.bytes as f64 / arch.bytes_per_cycle(),
            latency_cycles: requests as f64 * lat / arch.dram.requests_in_flight.max(1) as f64
                + self.map_misses as f64 * lat / window(&arch.map_cache)
                + self.depth_misses as f64 * lat / window(&arch.depth_cache),
        }
    }

    /// What bounds this work: its slowest stage, memory told as bandwidth
    /// or latency; and that stage's cycles. `None` for no work.
    #[must_use]
    pub fn bottleneck(&self, arch: &Arch) -> Option<(Bottleneck, f64)> {
        let memory = self.memory(arch);
        let s = self.stages_with(arch, memory);
        let slowest = s.iter().copied().fold(0.0, f64::max);
        (slowest > 0.0).then(|| {
            let stage = Stage::ALL[s.iter().position(|&c| c == slowest).unwrap_or(0)];
            (Bottleneck::of(stage, memory.limit()), slowest)
        })
    }

    /// Cycles per stage, memory included; a shadow test that runs in the
    /// shading program adds to the shading.
    #[must_use]
    pub fn stages(&self, arch: &Arch) -> [f64; 6] {
        self.stages_with(arch, self.memory(arch))
    }

    /// [`Work::stages`] with the memory time already worked out.
    fn stages_with(&self, arch: &Arch, memory: MemoryTime) -> [f64; 6] {
        let mut c = self.cycles;
        c[Stage::Memory as usize] = memory.cycles();
        if arch.shadow.in_shader {
            c[Stage::Shade as usize] += c[Stage::Shadow as usize];
            c[Stage::Shadow as usize] = 0.0;
        }
        c
    }

    pub(super) fn scale(&mut self, k: u64) {
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

    /// Every unit's energy with its name.
    #[must_use]
    pub const fn fields(&self) -> [(&'static str, f64); 5] {
        [
            ("dram", self.dram),
            ("buffers", self.buffers),
            ("caches", self.caches),
            ("raster", self.raster),
            ("shadow", self.shadow),
        ]
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
    #[serde(rename = "stage_cycles", serialize_with = "by_stage")]
    pub stages: [f64; 6],
    /// The front end's cycles (setup and bin writes).
    #[serde(rename = "front_cycles")]
    pub front: f64,
    /// The tiles' cycles: each tile its slowest stage, summed.
    #[serde(rename = "tile_cycles")]
    pub tiles: f64,
    /// The pass: front end and tiles as the architecture overlaps them,
    /// plus its fixed overhead.
    pub cycles: f64,
    /// The fixed overhead: cycles waiting for the host.
    #[serde(rename = "overhead_cycles")]
    pub overhead: f64,
    /// Tiles (draws) with work bound by each bottleneck, in
    /// [`Bottleneck::ALL`] order.
    #[serde(rename = "tiles_bound", serialize_with = "by_bottleneck")]
    pub bound: [u64; 7],
    /// What bounds the most cycles.
    pub bottleneck: Bottleneck,
    /// Memory time summed over the pass, as each limit would make it.
    pub memory: MemoryTime,
    /// DRAM bytes.
    #[serde(rename = "dram_bytes")]
    pub bytes: u64,
    /// DRAM bytes over the pass's time, bytes a second.
    pub achieved_bytes_per_second: f64,
    /// The map cache, when the pass reads through one.
    pub map_cache: Option<CacheStats>,
    /// The depth cache, when the pass keeps depth off chip through one.
    pub depth_cache: Option<CacheStats>,
    /// Energy by unit, joules.
    #[serde(rename = "energy_joules")]
    pub energy: EnergySplit,
}

/// Per-stage figures as a map from the stage's name.
fn by_stage<S: serde::Serializer>(v: &[f64; 6], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(Stage::ALL.iter().map(|st| st.name()).zip(v))
}

/// Per-bottleneck counts as a map from the bottleneck's name.
fn by_bottleneck<S: serde::Serializer>(v: &[u64; 7], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(Bottleneck::ALL.iter().map(|b| b.name()).zip(v))
}

impl PassTiming {
    /// The pass-level bound: the slowest stage summed over the whole pass.
    #[must_use]
    pub fn pass_bound(&self) -> f64 {
        self.overhead + self.stages.iter().copied().fold(0.0, f64::max)
    }

    /// Every stage's cycles added, as if nothing overlapped.
    #[must_use]
    pub fn serial(&self) -> f64 {
        self.overhead + self.stages.iter().sum::<f64>()
    }
}
