//! One shading's events and texel addresses recorded once ([`Tally`])
//! for every architecture that reads them, each costed from them at the
//! end.
//!
//! A [`Tally`] counts the integers each architecture's probe counts
//! ([`super::shading`]) once for several architectures, per tile of the
//! finest of their tilings, with each tiling's lookups and culls
//! ([`umbra_core::probe::Tilings`]), and sends each texel address once
//! through every map cache the architectures name (one pass of stack
//! distances for every geometry of one line, [`crate::cost::stack`]);
//! [`ArchProbe::absorb`] adds an architecture's share, tile by tile, to
//! what its own passes left. The integers it adds are those its own probe
//! would have counted, so a report costed from a tally is its own
//! render's, bit for bit.

use umbra_core::TileId;
use umbra_core::probe::{Event, Probe, TexelRead, TexelRect, Tilings, Totals};

use super::shading::ShadeCounts;
use super::{ArchProbe, COLOUR_BYTES, Phase, cache};
use crate::cost::arch::CacheParams;
use crate::cost::cache::{Cache, MapCache, morton, morton_next_x};
use crate::cost::dram::Purpose;
use crate::cost::stack::StackDistances;

impl<const D: bool> ArchProbe<D> {
    /// What a tally of the shading this camera probe reads needs of it:
    /// its tiles' shift, its map cache's parameters, how it addresses texels.
    pub(crate) fn tallied_as(&self) -> (u32, &CacheParams, Option<&MapCache>) {
        (self.raster.tile_shift(), &self.arch.map_cache, self.map_cache.as_ref())
    }

    /// Add to this camera probe the shading `tally` recorded, as tiling
    /// `tiling` of the tally saw it: every tile's counts, its traffic, and
    /// the misses of the tally's cache of this probe's geometry, when it has
    /// a map cache. The same integers, tile by tile, as this probe would
    /// have counted from the events themselves.
    pub(crate) fn absorb(&mut self, tally: &Tally, tiling: usize) {
        let Some(part) = tally.parts.get(tiling) else { return };
        let (common, own) = (&tally.common, &part.own);
        self.events = self.events.plus(&common.totals).plus(&own.totals);
        self.reconstructed_pixels += common.reconstructed_pixels + own.reconstructed_pixels;
        let geometry = self.map_cache.as_ref().and_then(|m| tally.geometry(&m.cache));
        let line = self.map_cache.as_ref().map_or(0, |m| m.cache.line());
        if common.pixels + own.pixels > 0 {
            self.enter(Phase::Shade);
        }
        let shift = tally.shift;
        let per = tally.geometries.len();
        let (mut hits, mut misses) = (0, 0);
        for (i, (c, o)) in common.tiles.iter().zip(&own.tiles).enumerate() {
            let t = c.plus(o);
            if t.counts.pixels == 0 && t.reads == 0 {
                continue;
            }
            // The fine tile's first pixel, in this probe's tiles.
            let s = self.raster.tile_shift();
            let (fx, fy) = ((i % tally.across) << shift, (i / tally.across) << shift);
            #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
            self.select(TileId { x: (fx >> s) as u16, y: (fy >> s) as u16 });
            self.shaded(&t.counts);
            let pixels = t.counts.pixels;
            self.accesses.shadow_ops += t.counts.samples + t.counts.culled + t.counts.virtual_samples;
            self.requested.map += t.map_bytes;
            self.requested.silhouette += t.silhouette_bytes;
            let cached = self.map_cache.is_some();
            let missed = geometry.and_then(|g| part.misses.get(i * per + g)).map_or(0, |&m| u64::from(m));
            if cached {
                self.accesses.cache += t.reads;
                (hits, misses) = (hits + t.reads - missed, misses + missed);
            }
            let w = self.work();
            w.pixels += pixels;
            w.stream(Purpose::Colour, COLOUR_BYTES * pixels);
            if cached {
                w.dram.add(Purpose::MapCacheFills, missed * line);
            } else {
                w.stream(Purpose::MapReads, t.map_bytes);
                w.stream(Purpose::SilhouetteReads, t.silhouette_bytes);
            }
            w.map_misses += missed;
        }
        if let Some(m) = self.map_cache.as_mut() {
            m.cache.hits += hits;
            m.cache.misses += misses;
        }
    }
}

/// One tile's tally: the shading's counts, its map traffic, and its reads
/// through the map cache.
#[derive(Clone, Copy, Debug, Default)]
struct TileTally {
    counts: ShadeCounts,
    map_bytes: u64,
    silhouette_bytes: u64,
    reads: u64,
}

impl TileTally {
    /// Both tallies added.
    fn plus(&self, o: &Self) -> Self {
        let mut counts = self.counts;
        counts.add(&o.counts);
        Self {
            counts,
            map_bytes: self.map_bytes + o.map_bytes,
            silhouette_bytes: self.silhouette_bytes + o.silhouette_bytes,
            reads: self.reads + o.reads,
        }
    }
}

/// What a shading's events count: their totals, each tile's tally, the
/// pixels shaded and those that read silhouette points, and the reads
/// since the last pixel (not yet counted in its tile).
#[derive(Clone, Debug, Default)]
struct Counts {
    totals: Totals,
    tiles: Vec<TileTally>,
    pixels: u64,
    reconstructed_pixels: u64,
    reconstructed: bool,
    pending_reads: u64,
}

impl Counts {
    /// Count `e` in tile `current`; whether the tally can cost it.
    fn count(&mut self, e: Event, current: usize) -> bool {
        self.totals.add(e);
        let Some(t) = self.tiles.get_mut(current) else { return false };
        let n = u64::from;
        match e {
            Event::PixelShaded { .. } => {
                self.pixels += 1;
                t.counts.pixels += 1;
            }
            Event::MapRead { texels, bytes, .. } => {
                t.counts.samples += n(texels);
                t.map_bytes += n(bytes);
            }
            Event::SilhouetteRead { points, bytes } => {
                self.reconstructed_pixels += u64::from(!self.reconstructed);
                self.reconstructed = true;
                t.counts.samples += n(points);
                t.silhouette_bytes += n(bytes);
            }
            Event::LookupCulled { .. } => t.counts.culled += 1,
            Event::VirtualSamples { count } => t.counts.virtual_samples += n(count),
            Event::TangentSetup => t.counts.tangents += 1,
            Event::TangentFallback | Event::TrivialPixel { .. } => {}
            _ => return false,
        }
        true
    }

    /// Count the pending reads in tile `current`.
    fn settle_reads(&mut self, current: usize) {
        if let Some(t) = self.tiles.get_mut(current) {
            t.reads += self.pending_reads;
        }
        self.pending_reads = 0;
    }
}

/// What only one tiling saw of a shading (the lookups other tilings'
/// bounds culled), and its map caches' misses per tile.
#[derive(Clone, Debug, Default)]
struct Part {
    own: Counts,
    /// Per tile, per geometry.
    misses: Vec<u32>,
    caches: Vec<Caches>,
    /// The line (of the smallest line size) read last.
    last: Option<u64>,
}

/// The map caches of one line size that one tiling's texel reads go
/// through, in one pass of stack distances: each geometry's index, its
/// number of sets' place in the pass, and its ways.
#[derive(Clone, Debug)]
struct Caches(StackDistances, Vec<(usize, usize, u32)>);

/// A shading's events and texel reads, recorded once for every
/// architecture that reads it: per tile of the finest of their tilings
/// (tiles `1 << shift` pixels on a side, `across` to a row), for each
/// tiling the shadow unit tested its lookups against.
#[derive(Clone, Debug)]
pub(crate) struct Tally {
    shift: u32,
    across: usize,
    current: usize,
    /// What every tiling saw, counted once.
    common: Counts,
    parts: Vec<Part>,
    /// Every tiling's bit.
    all: Tilings,
    /// The map caches' geometries: size, line, ways.
    geometries: Vec<(u64, u32, u32)>,
    /// How a texel's address is formed (`None` when no architecture has a map cache).
    addressing: Option<MapCache>,
    /// The texel read last and its Morton index.
    texel: (u32, u32, u64),
    /// log₂ of the smallest line of the geometries.
    line_shift: u32,
    /// An event the tally cannot cost: a shading reports none.
    pub(crate) unexpected: bool,
}

impl Tally {
    /// A tally of an image of `width × height` pixels in tiles of
    /// `1 << shift`, for `tilings` tilings and the map caches of `caches`
    /// (the architectures' map-cache parameters), texel addresses formed as
    /// `addressing` forms them.
    pub(crate) fn new(
        (width, height, shift): (u32, u32, u32),
        tilings: usize,
        caches: &[(usize, &CacheParams)],
        addressing: Option<MapCache>,
    ) -> Self {
        let across = width.div_ceil(1 << shift) as usize;
        let tiles = across * height.div_ceil(1 << shift) as usize;
        let mut geometries: Vec<(u64, u32, u32)> = Vec::new();
        let mut read_by: Vec<Vec<usize>> = vec![Vec::new(); tilings.max(1)];
        for &(tiling, c) in caches {
            let Some(g) = cache(c).map(|c| c.geometry()) else { continue };
            let k = geometries.iter().position(|&o| o == g).unwrap_or_else(|| {
                geometries.push(g);
                geometries.len() - 1
            });
            if let Some(wanted) = read_by.get_mut(tiling).filter(|w| !w.contains(&k)) {
                wanted.push(k);
            }
        }
        // Each tiling's reads go through the caches of its own architectures.
        let counts = Counts { tiles: vec![TileTally::default(); tiles], ..Counts::default() };
        let parts: Vec<Part> = read_by
            .iter()
            .map(|wanted| Part {
                own: counts.clone(),
                misses: vec![0; tiles * geometries.len()],
                caches: banks(&geometries, wanted),
                last: None,
            })
            .collect();
        let line_shift = geometries.iter().map(|g| g.1.trailing_zeros()).min().unwrap_or(0);
        Self {
            shift,
            across,
            current: 0,
            common: counts,
            all: Tilings(u8::MAX >> (Tilings::MAX - parts.len().min(Tilings::MAX))),
            parts,
            geometries,
            addressing,
            texel: (u32::MAX, u32::MAX, morton(u32::MAX, u32::MAX)),
            line_shift,
            unexpected: false,
        }
    }

    /// The index of `cache`'s geometry among the tally's.
    fn geometry(&self, cache: &Cache) -> Option<usize> {
        let g = cache.geometry();
        self.geometries.iter().position(|&o| o == g)
    }

    /// Record `e` for the tilings in `tilings`: once for all of them, or
    /// for each of those it is theirs alone.
    fn record(&mut self, tilings: Tilings, e: Event) {
        if let Event::PixelShaded { x, y } = e {
            self.settle_reads();
            self.current = (y >> self.shift) as usize * self.across + (x >> self.shift) as usize;
            self.common.reconstructed = false;
            self.parts.iter_mut().for_each(|p| p.own.reconstructed = false);
        }
        let current = self.current;
        let counted = if tilings.0 & self.all.0 == self.all.0 {
            self.common.count(e, current)
        } else {
            let mut all = true;
            for (_, part) in self.parts.iter_mut().enumerate().filter(|(k, _)| tilings.has(*k)) {
                all &= part.own.count(e, current);
            }
            all
        };
        self.unexpected |= !counted;
    }

    /// Record a texel read for the tilings in `tilings`: counted, and its
    /// address sent through each map cache.
    fn read(&mut self, tilings: Tilings, r: TexelRead) {
        if self.addressing.is_none() {
            return;
        }
        self.count_reads(tilings, 1);
        self.access(tilings, r);
    }

    /// Record a rectangle of texel reads for the tilings in `tilings`:
    /// counted at once, and each address sent through the map caches of
    /// those tilings that have one, in the order the unit read them.
    fn read_rect(&mut self, tilings: Tilings, rect: TexelRect) {
        if self.addressing.is_none() {
            return;
        }
        self.count_reads(tilings, rect.count());
        if self.parts.iter().enumerate().any(|(k, p)| tilings.has(k) && !p.caches.is_empty()) {
            rect.reads().for_each(|r| self.access(tilings, r));
        }
    }

    /// Count `n` reads for the tilings in `tilings`, in the pixel's tile
    /// once it is settled: once for all of them, or for each of those
    /// they are theirs alone.
    fn count_reads(&mut self, tilings: Tilings, n: u64) {
        if tilings.0 & self.all.0 == self.all.0 {
            self.common.pending_reads += n;
        } else {
            for (_, part) in self.parts.iter_mut().enumerate().filter(|(k, _)| tilings.has(*k)) {
                part.own.pending_reads += n;
            }
        }
    }

    /// Send texel `r`'s address through the map caches of the tilings in
    /// `tilings`, counting each cache's misses in the current tile.
    fn access(&mut self, tilings: Tilings, r: TexelRead) {
        let Some(addressing) = self.addressing.as_ref() else { return };
        // Both depths of a texel are read in turn, and a row's texels one
        // after another: the Morton index of the last, or one step along x.
        let (x, y, m) = self.texel;
        if (r.x, r.y) != (x, y) {
            let along = r.y == y && r.x == x.wrapping_add(1);
            self.texel = (r.x, r.y, if along { morton_next_x(m) } else { morton(r.x, r.y) });
        }
        let address = addressing.address_at(r, self.texel.2);
        let line = address >> self.line_shift;
        let (current, per) = (self.current, self.geometries.len());
        for k in 0..self.parts.len() {
            if !tilings.has(k) {
                continue;
            }
            let part = &mut self.parts[k];
            if part.caches.is_empty() {
                continue;
            }
            // The line read last, again: a hit in every cache, and already
            // the most recent in its set (its LRU order unchanged).
            if part.last == Some(line) {
                continue;
            }
            part.last = Some(line);
            let misses = part.misses.get_mut(current * per..(current + 1) * per).unwrap_or_default();
            for Caches(stack, geometries) in &mut part.caches {
                let d = stack.access(address);
                for &(g, k, ways) in geometries.iter() {
                    if d[k] >= ways {
                        misses[g] += 1;
                    }
                }
            }
        }
    }

    /// Count each tiling's reads since the last pixel in the current tile.
    fn settle_reads(&mut self) {
        let current = self.current;
        self.common.settle_reads(current);
        self.parts.iter_mut().for_each(|p| p.own.settle_reads(current));
    }

    /// The tally once the shading is over: every read counted in its tile.
    #[must_use]
    pub(crate) fn closed(mut self) -> Self {
        self.settle_reads();
        self
    }
}

/// The caches for the geometries `wanted` of `geometries`: one pass of
/// stack distances for each line size, for every number of sets and up to
/// the most ways its geometries name.
fn banks(geometries: &[(u64, u32, u32)], wanted: &[usize]) -> Vec<Caches> {
    let sets = |g: usize| {
        let (size, line, ways) = geometries[g];
        size / (u64::from(line) * u64::from(ways))
    };
    let mut lines: Vec<u32> = wanted.iter().map(|&g| geometries[g].1).collect();
    lines.sort_unstable();
    lines.dedup();
    lines
        .into_iter()
        .filter_map(|line| {
            let of_line: Vec<usize> = wanted.iter().copied().filter(|&g| geometries[g].1 == line).collect();
            let mut counts: Vec<u64> = of_line.iter().map(|&g| sets(g)).collect();
            counts.sort_unstable();
            counts.dedup();
            let most_ways = of_line.iter().map(|&g| geometries[g].2).max().unwrap_or(1);
            let stack = StackDistances::new(line, &counts, most_ways).ok()?;
            let members: Option<Vec<_>> =
                of_line.iter().map(|&g| Some((g, stack.index(sets(g))?, geometries[g].2))).collect();
            members.map(|m| Caches(stack, m))
        })
        .collect()
}

impl Probe for Tally {
    const TEXELS: bool = true;

    #[inline]
    fn event(&mut self, e: Event) {
        self.record(Tilings(u8::MAX), e);
    }

    #[inline]
    fn event_for(&mut self, tilings: Tilings, e: Event) {
        self.record(tilings, e);
    }

    #[inline]
    fn texel_read(&mut self, r: TexelRead) {
        self.read(Tilings(u8::MAX), r);
    }

    #[inline]
    fn texel_read_for(&mut self, tilings: Tilings, r: TexelRead) {
        self.read(tilings, r);
    }

    #[inline]
    fn texels_read(&mut self, rect: TexelRect) {
        self.read_rect(Tilings(u8::MAX), rect);
    }

    #[inline]
    fn texels_read_for(&mut self, tilings: Tilings, rect: TexelRect) {
        self.read_rect(tilings, rect);
    }

    fn map_bound(&mut self, light: u16) {
        if let Some(m) = self.addressing.as_mut() {
            m.map_bound(light);
        }
        self.parts.iter_mut().for_each(|p| p.last = None);
    }
}
