//! Architecture models: architecture files ([`Arch`]) and the timing model
//! that turns the core's events into cycles per stage, bytes per memory and
//! energy per unit, tile by tile (see [`timing`]).

use serde::{Deserialize, Serialize};

pub mod derived;
pub mod file;
mod keys;
mod machine;
mod presets;
mod report;
pub mod timing;
mod units;
mod work;

pub use file::ArchError;
pub use keys::{Problem, Unit};
pub use machine::{Arch, Calibration};
pub use report::{Compared, Comparison, CostReport, SenFigures, trace, unit_of};
pub use timing::{ArchProbe, PassKind, PassTiming};
pub use work::{MemoryLimit, MemoryTime};

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
/// through its bandwidth (bytes at the peak rate) or its latency (requests
/// at the latency over those kept in flight, Little's law).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[repr(usize)]
pub enum Bottleneck {
    /// Triangle setup.
    #[default]
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
    /// DRAM, its requests at the latency over those in flight.
    DramLatency,
}

impl Bottleneck {
    /// Every bottleneck, in pipeline order.
    pub const ALL: [Self; 7] =
        [Self::Setup, Self::Raster, Self::Depth, Self::Shadow, Self::Shade, Self::DramBandwidth, Self::DramLatency];

    /// The bottleneck of `stage`, memory bound by `memory`.
    #[must_use]
    pub const fn of(stage: Stage, memory: MemoryLimit) -> Self {
        match (stage, memory) {
            (Stage::Setup, _) => Self::Setup,
            (Stage::Raster, _) => Self::Raster,
            (Stage::Depth, _) => Self::Depth,
            (Stage::Shadow, _) => Self::Shadow,
            (Stage::Shade, _) => Self::Shade,
            (Stage::Memory, MemoryLimit::Bandwidth) => Self::DramBandwidth,
            (Stage::Memory, MemoryLimit::Latency) => Self::DramLatency,
        }
    }

    /// The stage it is in.
    #[must_use]
    pub const fn stage(self) -> Stage {
        match self {
            Self::Setup => Stage::Setup,
            Self::Raster => Stage::Raster,
            Self::Depth => Stage::Depth,
            Self::Shadow => Stage::Shadow,
            Self::Shade => Stage::Shade,
            Self::DramBandwidth | Self::DramLatency => Stage::Memory,
        }
    }

    /// Its name in reports, rows and files.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::DramBandwidth => "dram-bandwidth",
            Self::DramLatency => "dram-latency",
            s => s.stage().name(),
        }
    }
}

impl core::str::FromStr for Bottleneck {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL.into_iter().find(|b| b.name() == s).ok_or_else(|| {
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

/// DRAM traffic per buffer, bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Dram {
    /// Map texels written by the resolve.
    pub map_writes: u64,
    /// Tiles loaded back by a later flush.
    pub map_rmw_reads: u64,
    /// Off-chip depth (and ids) read and written per fragment: cache lines
    /// fetched and written back, or each access when uncached.
    pub depth_rmw: u64,
    /// Map texels and silhouette points requested by the shadow unit
    /// (before any cache).
    pub map_reads: u64,
    /// Map and silhouette lines fetched through the map cache.
    pub map_fetched: u64,
    /// Shaded pixels' colour written to the frame buffer.
    pub colour: u64,
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
    /// Every purpose's bytes with its name, in declaration order.
    #[must_use]
    pub const fn fields(&self) -> [(&'static str, u64); 11] {
        [
            ("map_writes", self.map_writes),
            ("map_rmw_reads", self.map_rmw_reads),
            ("depth_rmw", self.depth_rmw),
            ("map_reads", self.map_reads),
            ("map_fetched", self.map_fetched),
            ("colour", self.colour),
            ("bins", self.bins),
            ("silhouette_writes", self.silhouette_writes),
            ("silhouette_reads", self.silhouette_reads),
            ("volume_depth_reads", self.volume_depth_reads),
            ("stencil", self.stencil),
        ]
    }

    /// Every byte that crossed the DRAM interface: map reads as fetched
    /// through the map cache when there is one.
    #[must_use]
    pub const fn total(&self, map_cached: bool) -> u64 {
        let map = if map_cached { self.map_fetched } else { self.map_reads + self.silhouette_reads };
        self.map_writes
            + self.map_rmw_reads
            + self.depth_rmw
            + map
            + self.colour
            + self.bins
            + self.silhouette_writes
            + self.volume_depth_reads
            + self.stencil
    }

    /// The camera pass's shadow traffic: map (as fetched), silhouette
    /// points, volume depth and stencil.
    #[must_use]
    pub const fn shadow_bytes(&self, map_cached: bool) -> u64 {
        let map = if map_cached { self.map_fetched } else { self.map_reads + self.silhouette_reads };
        map + self.volume_depth_reads + self.stencil
    }
}
