//! The machine an architecture file describes: every parameter of each of
//! its units, and what follows from them directly (its tiling, its DRAM's
//! bytes per clock and latency in clocks).

use serde::Serialize;

use super::units::{
    Bins, CacheParams, DepthRates, DramParams, Energy, Front, OnChip, Raster, Shade, ShadowRates, Technology,
};

/// An architecture: every parameter of the machine a render is costed on.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Arch {
    /// Name for reports and file names.
    pub name: String,
    /// What it models.
    pub description: String,
    /// Clock, hertz.
    pub clock: f64,
    /// Setup and binning.
    pub front: Front,
    /// Scan conversion.
    pub raster: Raster,
    /// The depth unit.
    pub depth: DepthRates,
    /// Buffers on chip.
    pub on_chip: OnChip,
    /// Bins.
    pub bins: Bins,
    /// The shadow unit.
    pub shadow: ShadowRates,
    /// Shading besides the shadow lookup.
    pub shade: Shade,
    /// DRAM.
    pub dram: DramParams,
    /// The shadow unit's map cache.
    pub map_cache: CacheParams,
    /// The cache for off-chip depth, ids and stencil.
    pub depth_cache: CacheParams,
    /// Energy per access.
    pub energy: Energy,
    /// The process: area per bit and per gate, leakage per area.
    pub technology: Technology,
    /// The parameters set from a measurement, each with the point of a
    /// correlation dataset it came from (`[calibration]`, key = point):
    /// that point then validates nothing.
    pub calibration: Vec<Calibration>,
}

/// A parameter fitted to a measurement.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Calibration {
    /// The dotted key of the parameter.
    pub key: String,
    /// The dataset point it was set from, `dataset/point`.
    pub point: String,
}

impl Arch {
    /// An immediate-mode machine: no bins, so each draw is finished before
    /// the next and timed as one unit.
    #[must_use]
    pub const fn immediate(&self) -> bool {
        self.bins.entry_bytes == 0 && self.bins.setup_record_bytes == 0
    }

    /// How the passes walk the target on this machine: its tiles, and draw
    /// by draw when it is immediate-mode.
    #[must_use]
    pub(crate) const fn tiling(&self) -> crate::base::maps::Tiling {
        crate::base::maps::Tiling { tile: self.raster.tile, per_draw: self.immediate() }
    }

    /// Bytes DRAM moves per clock.
    #[must_use]
    pub(crate) fn bytes_per_cycle(&self) -> f64 {
        self.dram.bandwidth / self.clock
    }

    /// DRAM latency in clocks.
    #[must_use]
    pub(crate) fn latency_cycles(&self) -> f64 {
        self.dram.latency * self.clock
    }
}
