//! A probe that totals the core's events, overall and per tile.

use serde::Serialize;
use umbra_core::probe::Totals;
use umbra_core::{Event, Probe, RasterConfig, TileId};

/// What happened in one tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TileCounters {
    /// Fragments generated.
    pub fragments: u64,
    /// Bin flushes.
    pub flushes: u64,
    /// Triangles rasterized (bin entries drained).
    pub triangles: u64,
    /// Triangles and blocks skipped by max-z culling.
    pub culled: u64,
}

/// Totals every event; keeps per-tile counts.
#[derive(Clone, Debug, Default)]
pub struct Counters {
    /// Overall totals.
    pub totals: Totals,
    /// Per tile, row-major.
    pub tiles: Vec<TileCounters>,
    across: usize,
}

impl Counters {
    /// Counters for a target with this raster configuration.
    #[must_use]
    pub fn new(raster: &RasterConfig) -> Self {
        Self {
            totals: Totals::default(),
            tiles: vec![TileCounters::default(); raster.tile_count()],
            across: raster.tiles().0 as usize,
        }
    }

    fn tile(&mut self, t: TileId) -> Option<&mut TileCounters> {
        self.tiles.get_mut(usize::from(t.y) * self.across + usize::from(t.x))
    }
}

impl Probe for Counters {
    fn event(&mut self, event: Event) {
        self.totals.add(event);
        match event {
            Event::BinFlush { tile, triangles, .. } => {
                if let Some(c) = self.tile(tile) {
                    c.flushes += 1;
                    c.triangles += u64::from(triangles);
                }
            }
            Event::Fragments { tile, count } => {
                if let Some(c) = self.tile(tile) {
                    c.fragments += u64::from(count);
                }
            }
            Event::Culled { tile, .. } => {
                if let Some(c) = self.tile(tile) {
                    c.culled += 1;
                }
            }
            // Events of no one tile's rasterization: in the totals only.
            Event::TriangleSubmitted
            | Event::TriangleRejected { .. }
            | Event::TriangleSetup
            | Event::TriangleBinned { .. }
            | Event::TileLoad { .. }
            | Event::TileStore { .. }
            | Event::DepthRead { .. }
            | Event::DepthWrite { .. }
            | Event::TileMaxUpdate { .. }
            | Event::MapRead { .. }
            | Event::LookupCulled { .. }
            | Event::VirtualSamples { .. }
            | Event::TangentSetup
            | Event::TangentFallback
            | Event::TrivialPixel { .. }
            | Event::PixelShaded { .. }
            | Event::SilhouetteFragments { .. }
            | Event::SilhouetteRead { .. }
            | Event::VolumeFragments { .. }
            | Event::StencilRead { .. }
            | Event::StencilWrite { .. } => {}
        }
    }
}
