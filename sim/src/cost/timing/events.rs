//! The timing probe's account of each event: an exhaustive match, so an
//! event without a charge does not compile.

use super::{ArchProbe, COLOUR_BYTES, PassKind, Phase, ShadeCounts};
use crate::cost::cache::morton;
use crate::cost::dram::Purpose;
use crate::cost::work::Stage;
use umbra_core::probe::{Buffer, Event, Fragment, TexelRead, Tilings};
use umbra_core::{Probe, TileId};

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
                self.front.stream(Purpose::Bins, b);
            }
            Event::BinFlush { tile, triangles, .. } => {
                // The entries and their setup records, read back.
                self.enter(Phase::Back);
                self.select(tile);
                let b = n(triangles) * (self.arch.bins.entry_bytes + self.arch.bins.setup_record_bytes);
                self.traffic(Purpose::Bins, b);
                self.work().triangles += n(triangles);
            }
            Event::TileLoad { tile, bytes: b } => {
                self.select(tile);
                if on_chip {
                    self.traffic(Purpose::TileReloads, n(b));
                }
            }
            Event::TileStore { tile, bytes: b, cleared } => {
                self.select(tile);
                // The camera's visibility stays on chip for shading; a
                // cleared tile is a fast clear.
                if on_chip && self.kind == PassKind::Light && !cleared {
                    let written =
                        if self.arch.on_chip.resolve_test_value_only { n(b) / self.buffers.max(1) } else { n(b) };
                    self.traffic(Purpose::MapWrites, written);
                }
            }
            Event::Fragments { tile, count } => {
                self.select(tile);
                self.fragments(n(count), self.buffers);
                if !on_chip && !cached {
                    // Uncached: every fragment reads each buffer, one request each.
                    let (b, requests) = (n(count) * bytes * self.buffers, n(count) * self.buffers);
                    let w = self.work();
                    w.dram.add(Purpose::OffChipDepth, b);
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
                self.programs(buffer, n(texels));
                if on_chip {
                    self.accesses.buffer += n(texels);
                } else if !cached && (buffer != Buffer::Id || self.kind == PassKind::Camera) {
                    // Uncached: each texel written is its own request.
                    let w = self.work();
                    w.dram.add(Purpose::OffChipDepth, n(b));
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
                self.requested.map += n(b);
                self.map_read(n(texels), n(b), Purpose::MapReads);
            }
            Event::LookupCulled { .. } => {
                // One compare against the tiles' bounds.
                self.accesses.shadow_ops += 1;
                self.shaded(&ShadeCounts { culled: 1, ..ShadeCounts::default() });
            }
            Event::VirtualSamples { count } => {
                // Forward differences: an add and a compare per sample.
                self.accesses.shadow_ops += n(count);
                self.shaded(&ShadeCounts { virtual_samples: n(count), ..ShadeCounts::default() });
            }
            Event::TangentSetup => {
                // A division occupies one of the dividers for its latency.
                self.shaded(&ShadeCounts { tangents: 1, ..ShadeCounts::default() });
            }
            // Counted in `events`: decisions about work charged above.
            Event::TangentFallback | Event::TrivialPixel { .. } => {}
            Event::PixelShaded { x, y } => {
                self.enter(Phase::Shade);
                self.reconstructed = false;
                let s = self.raster.tile_shift();
                #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
                self.select(TileId { x: (x >> s) as u16, y: (y >> s) as u16 });
                self.shaded(&ShadeCounts { pixels: 1, ..ShadeCounts::default() });
                self.work().pixels += 1;
                self.traffic(Purpose::Colour, COLOUR_BYTES);
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
                let w = &mut self.silhouette;
                w.stream(Purpose::SilhouetteWrites, n(b));
                w.charge(Stage::Raster, raster);
                w.fragments += n(fragments);
            }
            Event::SilhouetteRead { points, bytes: b } => {
                // Once per pixel, however many of its samples needed it.
                self.reconstructed_pixels += u64::from(!self.reconstructed);
                self.reconstructed = true;
                self.requested.silhouette += n(b);
                self.map_read(n(points), n(b), Purpose::SilhouetteReads);
            }
            Event::VolumeFragments { tile, fragments, depth_bytes } => {
                // Scan converted and depth tested like scene fragments,
                // against the scene depth on chip or in DRAM.
                self.select(tile);
                self.fragments(n(fragments), 1);
                if self.arch.on_chip.stencil {
                    self.accesses.buffer += n(fragments);
                } else {
                    self.traffic(Purpose::VolumeDepthReads, n(depth_bytes));
                }
            }
            Event::StencilRead { tile, texels, bytes: b } | Event::StencilWrite { tile, texels, bytes: b } => {
                self.select(tile);
                if self.arch.on_chip.stencil {
                    self.accesses.buffer += n(texels);
                } else {
                    self.traffic(Purpose::Stencil, n(b));
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

    fn map_bound(&mut self, light: u16) {
        if let Some(m) = self.map_cache.as_mut() {
            m.map_bound(light);
        }
    }

    #[inline]
    fn event_for(&mut self, tilings: Tilings, e: Event) {
        if tilings.has(self.tiling) {
            self.event(e);
        }
    }

    #[inline]
    fn texel_read_for(&mut self, tilings: Tilings, r: TexelRead) {
        if tilings.has(self.tiling) {
            self.texel_read(r);
        }
    }

    #[inline]
    fn texel_read(&mut self, r: TexelRead) {
        let Some(m) = self.map_cache.as_mut() else { return };
        let address = m.address(r);
        self.accesses.cache += 1;
        if !m.cache.access(address) {
            let line = m.cache.line();
            let w = self.work();
            w.dram.add(Purpose::MapCacheFills, line);
            w.map_misses += 1;
        }
    }
}

impl<const D: bool> ArchProbe<D> {
    /// The fragment programs run for `texels` fragments that passed the
    /// depth test and wrote `buffer`: the map-writing program of a light
    /// pass (and, on a second light pass, its peeling: half a pass's
    /// worth here, as the light pass's work is counted twice), and the
    /// shading of a camera pass on a machine shading per fragment.
    fn programs(&mut self, buffer: Buffer, texels: u64) {
        if buffer != Buffer::Z1 {
            return;
        }
        #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
        let k = texels as f64;
        let d = &self.arch.depth;
        match self.kind {
            PassKind::Light => {
                let peel = if self.passes > 1 { d.peel_cycles / 2.0 } else { 0.0 };
                let cycles = k * (d.program_cycles + peel);
                self.work().charge(Stage::Shade, cycles);
            }
            PassKind::Camera if self.arch.shade.per_fragment => {
                let (shade, lookup) = self.program();
                let w = self.work();
                w.charge(Stage::Shade, k * shade);
                w.charge(Stage::Shadow, k * lookup);
            }
            PassKind::Camera => {}
        }
    }
}
