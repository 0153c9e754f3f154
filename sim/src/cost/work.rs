//! What the timing model charges: the stages a tile's time is the slowest
//! of and what bounds it, a tile's (or the front end's) work in cycles per
//! stage and DRAM traffic, the accesses that cost energy, and a pass's
//! time.

use crate::cost::arch::Arch;
use crate::cost::dram::{Dram, Purpose};
use serde::{Deserialize, Serialize};

/// The stages a tile's time is the slowest of.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
#[repr(usize)]
pub enum Stage {
    /// Triangle setup (the front end).
    #[default]
    Setup,
    /// Scan conversion.
    Raster,
    /// The depth unit.
    Depth,
    /// The shadow unit (camera pass).
    Shadow,
    /// Shading besides the shadow lookup (camera pass).
    Shade,
    /// DRAM.
    Memory,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Self; 6] = [Self::Setup, Self::Raster, Self::Depth, Self::Shadow, Self::Shade, Self::Memory];

    /// The stage's name in reports.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Setup => "setup",
            Self::Raster => "raster",
            Self::Depth => "depth",
            Self::Shadow => "shadow",
            Self::Shade => "shade",
            Self::Memory => "memory",
        }
    }
}

/// What bounds a tile, a pass or a frame: a compute stage, or memory
/// through its bandwidth (bytes at the peak rate) or through one of its
/// finite queues, each a ceiling of its own by Little's law (its requests
/// at the DRAM latency over those it keeps in flight): the DRAM's requests
/// and each cache's misses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[repr(usize)]
pub enum Bottleneck {
    /// Triangle setup.
    Setup,
    /// Scan conversion.
    Raster,
    /// The depth unit.
    Depth,
    /// The shadow unit.
    Shadow,
    /// Shading.
    Shade,
    /// DRAM, its bytes at the bandwidth.
    DramBandwidth,
    /// DRAM, its requests (bursts, scattered accesses and every cache's
    /// misses) at the latency over `dram.requests_in_flight`.
    DramLatency,
    /// The map cache, its misses at the DRAM latency over
    /// `map_cache.misses_in_flight`.
    MapCacheMissesInFlight,
    /// The depth cache, its misses at the DRAM latency over
    /// `depth_cache.misses_in_flight`.
    DepthCacheMissesInFlight,
    /// Nothing: the pass did no work (no light pass for shadow volumes).
    #[default]
    #[serde(rename = "none")]
    Nothing,
}

impl Bottleneck {
    /// Every bottleneck, in pipeline order: a bottleneck's code in the
    /// stats file is its place here ([`Bottleneck::Nothing`]'s is the
    /// next).
    pub const ALL: [Self; 9] = [
        Self::Setup,
        Self::Raster,
        Self::Depth,
        Self::Shadow,
        Self::Shade,
        Self::DramBandwidth,
        Self::DramLatency,
        Self::MapCacheMissesInFlight,
        Self::DepthCacheMissesInFlight,
    ];

    /// The bottleneck of `stage`, memory bound by `memory`.
    #[must_use]
    pub(crate) const fn of(stage: Stage, memory: MemoryLimit) -> Self {
        match (stage, memory) {
            (Stage::Setup, _) => Self::Setup,
            (Stage::Raster, _) => Self::Raster,
            (Stage::Depth, _) => Self::Depth,
            (Stage::Shadow, _) => Self::Shadow,
            (Stage::Shade, _) => Self::Shade,
            (Stage::Memory, MemoryLimit::Bandwidth) => Self::DramBandwidth,
            (Stage::Memory, MemoryLimit::DramRequests) => Self::DramLatency,
            (Stage::Memory, MemoryLimit::MapCacheMisses) => Self::MapCacheMissesInFlight,
            (Stage::Memory, MemoryLimit::DepthCacheMisses) => Self::DepthCacheMissesInFlight,
        }
    }

    /// The stage it is in.
    #[must_use]
    pub(crate) const fn stage(self) -> Stage {
        match self {
            Self::Setup => Stage::Setup,
            Self::Raster => Stage::Raster,
            Self::Depth => Stage::Depth,
            Self::Shadow => Stage::Shadow,
            Self::Shade => Stage::Shade,
            Self::DramBandwidth | Self::DramLatency | Self::MapCacheMissesInFlight | Self::DepthCacheMissesInFlight => {
                Stage::Memory
            }
            Self::Nothing => Stage::Setup,
        }
    }

    /// Its name in reports, rows and files.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::DramBandwidth => "dram-bandwidth",
            Self::DramLatency => "dram-latency",
            Self::MapCacheMissesInFlight => "map-cache-misses-in-flight",
            Self::DepthCacheMissesInFlight => "depth-cache-misses-in-flight",
            Self::Nothing => "none",
            s => s.stage().name(),
        }
    }
}

impl Bottleneck {
    /// As a sentence ends with it: "bound by {words}".
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::Nothing => "nothing (no work)",
            s => s.name(),
        }
    }
}

impl core::str::FromStr for Bottleneck {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL.into_iter().chain([Self::Nothing]).find(|b| b.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Self::ALL.iter().map(|b| b.name()).collect();
            format!("`{s}` is not a bottleneck (one of {})", names.join(", "))
        })
    }
}

impl core::fmt::Display for Bottleneck {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// What limits memory time: the bytes at the bandwidth, or one queue's
/// requests at the latency over those it keeps in flight.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[repr(usize)]
pub(crate) enum MemoryLimit {
    /// Bytes at the DRAM's bandwidth.
    #[default]
    Bandwidth,
    /// Every DRAM request at the latency over `dram.requests_in_flight`.
    DramRequests,
    /// Map-cache misses at the latency over `map_cache.misses_in_flight`.
    MapCacheMisses,
    /// Depth-cache misses at the latency over `depth_cache.misses_in_flight`.
    DepthCacheMisses,
}

impl MemoryLimit {
    /// The bandwidth, then the queues in [`MemoryTime::queue_cycles`] order.
    pub(crate) const ALL: [Self; 4] =
        [Self::Bandwidth, Self::DramRequests, Self::MapCacheMisses, Self::DepthCacheMisses];
}

/// The finite queues' names, in [`MemoryTime::queue_cycles`] order.
pub(crate) const QUEUE_NAMES: [&str; 3] = ["dram_requests", "map_cache_misses", "depth_cache_misses"];

/// Memory time, cycles, as each limit would make it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct MemoryTime {
    /// The bytes at the bandwidth.
    pub bandwidth_cycles: f64,
    /// The queue that binds: the longest of `queue_cycles` (summed over
    /// tiles, each tile's longest).
    pub latency_cycles: f64,
    /// Each finite queue by Little's law, its requests at the latency over
    /// those it keeps in flight: every DRAM
    /// request (bursts, scattered accesses, both caches' misses) over
    /// `dram.requests_in_flight`, the map cache's misses over its
    /// `misses_in_flight`, the depth cache's over its own.
    #[serde(serialize_with = "by_queue")]
    pub queue_cycles: [f64; 3],
}

impl MemoryTime {
    /// The time memory takes: the longest of the bandwidth and the queues.
    #[must_use]
    pub(crate) const fn cycles(&self) -> f64 {
        self.bandwidth_cycles.max(self.latency_cycles)
    }

    /// Which limit it is: the bandwidth on a tie, else the first of the
    /// longest queues.
    #[must_use]
    pub(crate) fn limit(&self) -> MemoryLimit {
        let mut limit = MemoryLimit::Bandwidth;
        let mut longest = self.bandwidth_cycles;
        for (&q, c) in MemoryLimit::ALL[1..].iter().zip(self.queue_cycles) {
            if c > longest {
                (limit, longest) = (q, c);
            }
        }
        limit
    }

    /// Both added.
    #[must_use]
    pub(crate) fn plus(&self, o: &Self) -> Self {
        let mut queue_cycles = self.queue_cycles;
        for (a, b) in queue_cycles.iter_mut().zip(o.queue_cycles) {
            *a += b;
        }
        Self {
            bandwidth_cycles: self.bandwidth_cycles + o.bandwidth_cycles,
            latency_cycles: self.latency_cycles + o.latency_cycles,
            queue_cycles,
        }
    }
}

/// Per-queue figures as a map from the queue's name.
fn by_queue<S: serde::Serializer>(v: &[f64; 3], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(QUEUE_NAMES.iter().zip(v))
}

/// What one tile (or the front end) did, in the units the timing charges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Work {
    /// Compute cycles per stage, in [`Stage::ALL`] order (memory's slot is
    /// filled by `Work::memory`).
    pub cycles: [f64; 6],
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
    /// Its DRAM traffic by purpose: its entries in the pass's ledger.
    pub dram: Dram,
}

impl Work {
    /// Its DRAM bytes: the sum of its purposes.
    #[must_use]
    pub fn bytes(&self) -> u64 {
        self.dram.total()
    }

    /// `bytes` streamed for `purpose`: written or read in order.
    pub(crate) const fn stream(&mut self, purpose: Purpose, bytes: u64) {
        self.dram.add(purpose, bytes);
        self.streamed += bytes;
    }

    pub(super) fn charge(&mut self, stage: Stage, cycles: f64) {
        if let Some(c) = self.cycles.get_mut(stage as usize) {
            *c += cycles;
        }
    }

    /// Memory time: the bytes at the bandwidth, and each queue's requests
    /// at the latency over those it keeps in flight (Little's law). A
    /// cache's miss is a DRAM request too: it waits in both queues.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    pub(crate) fn memory(&self, arch: &Arch) -> MemoryTime {
        let lat = arch.latency_cycles();
        let wait = |requests: u64, in_flight: u64| requests as f64 * lat / in_flight.max(1) as f64;
        let dram = self.streamed.div_ceil(arch.dram.burst.max(1)) + self.requests + self.map_misses + self.depth_misses;
        let queue_cycles = [
            wait(dram, arch.dram.requests_in_flight),
            wait(self.map_misses, arch.map_cache.misses_in_flight),
            wait(self.depth_misses, arch.depth_cache.misses_in_flight),
        ];
        MemoryTime {
            bandwidth_cycles: self.bytes() as f64 / arch.bytes_per_cycle(),
            latency_cycles: queue_cycles.iter().copied().fold(0.0, f64::max),
            queue_cycles,
        }
    }

    /// What bounds this work: its slowest stage, memory told as bandwidth
    /// or latency; and that stage's cycles. `None` for no work.
    #[must_use]
    pub(crate) fn bottleneck(&self, arch: &Arch) -> Option<(Bottleneck, f64)> {
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
    pub(crate) fn stages(&self, arch: &Arch) -> [f64; 6] {
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
        self.streamed *= k;
        self.requests *= k;
        self.map_misses *= k;
        self.depth_misses *= k;
        self.dram = self.dram.times(k);
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
    /// Static: the units' leakage over the time
    /// ([`crate::cost::silicon::Silicon::leakage_watts`]).
    pub leakage: f64,
}

impl EnergySplit {
    /// The sum over units, dynamic and static.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.dynamic() + self.leakage
    }

    /// The dynamic energy: every access's.
    #[must_use]
    pub fn dynamic(&self) -> f64 {
        self.dram + self.buffers + self.caches + self.raster + self.shadow
    }

    /// Every unit's energy with its name.
    #[must_use]
    pub(crate) const fn fields(&self) -> [(&'static str, f64); 6] {
        [
            ("dram", self.dram),
            ("buffers", self.buffers),
            ("caches", self.caches),
            ("raster", self.raster),
            ("shadow", self.shadow),
            ("leakage", self.leakage),
        ]
    }

    /// Both added.
    #[must_use]
    pub(crate) fn plus(&self, o: &Self) -> Self {
        Self {
            dram: self.dram + o.dram,
            buffers: self.buffers + o.buffers,
            caches: self.caches + o.caches,
            raster: self.raster + o.raster,
            shadow: self.shadow + o.shadow,
            leakage: self.leakage + o.leakage,
        }
    }
}
