//! DRAM traffic by purpose: what each pass moved, in bytes, for the map,
//! the depth, the bins, the colour, silhouettes and shadow volumes.

use serde::Serialize;

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
    /// Both passes' bytes added, purpose by purpose.
    #[must_use]
    pub(crate) const fn plus(&self, o: &Self) -> Self {
        Self {
            map_writes: self.map_writes + o.map_writes,
            map_rmw_reads: self.map_rmw_reads + o.map_rmw_reads,
            depth_rmw: self.depth_rmw + o.depth_rmw,
            map_reads: self.map_reads + o.map_reads,
            map_fetched: self.map_fetched + o.map_fetched,
            colour: self.colour + o.colour,
            bins: self.bins + o.bins,
            silhouette_writes: self.silhouette_writes + o.silhouette_writes,
            silhouette_reads: self.silhouette_reads + o.silhouette_reads,
            volume_depth_reads: self.volume_depth_reads + o.volume_depth_reads,
            stencil: self.stencil + o.stencil,
        }
    }

    /// Every purpose `k` times.
    #[must_use]
    pub(crate) const fn times(&self, k: u64) -> Self {
        Self {
            map_writes: self.map_writes * k,
            map_rmw_reads: self.map_rmw_reads * k,
            depth_rmw: self.depth_rmw * k,
            map_reads: self.map_reads * k,
            map_fetched: self.map_fetched * k,
            colour: self.colour * k,
            bins: self.bins * k,
            silhouette_writes: self.silhouette_writes * k,
            silhouette_reads: self.silhouette_reads * k,
            volume_depth_reads: self.volume_depth_reads * k,
            stencil: self.stencil * k,
        }
    }

    /// The map bytes DRAM moved for the shadow unit: the lines fetched
    /// through the map cache when there is one, else every byte requested.
    #[must_use]
    pub(crate) const fn map_as_fetched(&self, cached: bool) -> u64 {
        if cached { self.map_fetched } else { self.map_reads }
    }

    /// The DRAM traffic by purpose with its name: every purpose, the map's
    /// reads as fetched ([`Dram::map_as_fetched`]).
    #[must_use]
    pub(crate) fn traffic(&self, cached: bool) -> Vec<(&'static str, u64)> {
        self.fields()
            .into_iter()
            .filter(|(name, _)| *name != "map_fetched")
            .map(|(name, b)| if name == "map_reads" { (name, self.map_as_fetched(cached)) } else { (name, b) })
            .collect()
    }

    /// Every purpose's bytes with its name, in declaration order.
    #[must_use]
    pub(crate) const fn fields(&self) -> [(&'static str, u64); 11] {
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
}
