//! The timing model: a probe that charges each event to the stage that does the work, and the bytes it moves to the memory that holds them.

use super::{ArchParams, Dram, Stage};
use umbra_core::probe::{Buffer, Event, Totals};
use umbra_core::{DepthFormatKind, DepthUnit, Probe};

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
    /// Every event of the pass, totalled.
    pub events: Totals,
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
            events: Totals::default(),
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
        self.events.add(e);
        match e {
            Event::TriangleSetup => self.charge(Stage::Setup, p.setup_cycles),
            Event::TriangleBinned { tiles } => {
                // Written at binning, read back when the bin is drained.
                self.dram.bins += 2 * (u64::from(tiles) * p.bin_entry_bytes) + 2 * p.setup_record_bytes;
            }
            Event::Fragments { tile, count } => {
                let count = u64::from(count);
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
            Event::DepthWrite { buffer, texels, .. } => {
                if p.off_chip_depth && buffer != Buffer::Id {
                    self.dram.map_writes += u64::from(texels) * bytes;
                }
            }
            Event::TileLoad { bytes: b, .. } => {
                if !p.off_chip_depth {
                    self.dram.map_rmw_reads += u64::from(b);
                }
            }
            Event::TileStore { bytes: b, cleared, .. } => {
                if !p.off_chip_depth {
                    let written =
                        if p.resolve_test_value_only { u64::from(b) / self.buffers.max(1) } else { u64::from(b) };
                    let written = if cleared { 0 } else { written };
                    self.dram.map_writes += written;
                    self.charge(Stage::Resolve, written.div_ceil(p.dram_bytes_per_cycle.max(1)));
                }
            }
            Event::MapRead { texels, bytes: b, .. } => {
                self.dram.map_reads += u64::from(b);
                self.charge(Stage::Shadow, u64::from(texels).div_ceil(p.samples_per_clock.max(1)));
            }
            Event::TangentSetup => self.charge(Stage::Shadow, p.tangent_setup_cycles),
            Event::SilhouetteFragments { fragments, bytes: b, .. } => {
                // Conservative line rasterization at the scan converter's rate;
                // the points go to memory like map texels.
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
                self.charge(Stage::Raster, n.div_ceil(p.fragments_per_clock.max(1)));
                self.charge(Stage::Depth, n.div_ceil(p.depth_fragments_per_clock.max(1)));
                self.dram.volume_depth_reads += u64::from(depth_bytes);
            }
            Event::StencilRead { bytes: b, .. } | Event::StencilWrite { bytes: b, .. } => {
                self.dram.stencil += u64::from(b);
            }
            // Work this model does not charge: counted in `events` only.
            Event::TriangleSubmitted
            | Event::TriangleRejected { .. }
            | Event::BinFlush { .. }
            | Event::Culled { .. }
            | Event::DepthRead { .. }
            | Event::TileMaxUpdate { .. }
            | Event::LookupCulled { .. }
            | Event::VirtualSamples { .. }
            | Event::TangentFallback
            | Event::TrivialPixel { .. } => {}
        }
    }
}
