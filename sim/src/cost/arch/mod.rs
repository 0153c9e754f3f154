//! Architecture models: architecture files ([`Arch`]) and the timing model
//! that turns the core's events into cycles per stage, bytes per memory and
//! energy per unit, tile by tile (see [`timing`]).

use serde::Serialize;

pub mod derived;
pub mod file;
mod keys;
mod report;
pub mod timing;
mod units;
mod work;

pub use file::{Arch, ArchError};
pub use report::{CostReport, SenFigures};
pub use timing::{ArchProbe, PassKind, PassTiming};

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
