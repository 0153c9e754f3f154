//! The map as the shadow unit sees it: texels, tiles and their stored bounds.

use super::{DepthTest, at_format};
use crate::config::RasterConfig;
use crate::depth::DepthFormat;
use crate::depth::{Texel, TileState};
use crate::grid::TileRect;
use crate::probe::{Buffer, Probe, Tap, TexelRead};

/// A light pass's maps, as the shadow unit reads them.
#[derive(Clone, Copy, Debug)]
pub struct MapView<'a, F: DepthFormat> {
    pub(super) raster: RasterConfig,
    z1: &'a [F::Texel],
    z2: &'a [F::Texel],
    /// The map's own tiles' stored bounds (tiling 0).
    pub(super) bounds: TileBounds<'a, F::Texel>,
    /// Other tilings' bounds over the same texels, each tested too.
    #[cfg(feature = "tilings")]
    pub(super) others: &'a [TileBounds<'a, F::Texel>],
    /// The second depth is the single buffer of a front-face-culled pass.
    second_in_z1: bool,
}

/// The stored bounds of a map's tiles in one tiling: what lookup culling
/// reads. The same texels drawn in tiles of another side (PixelFlow's 128
/// against Talisman's 32) have other bounds; a shadow unit given several
/// ([`MapView::with_tilings`]) reports each tiling's culls and reads from
/// one lookup.
#[derive(Clone, Copy, Debug)]
pub struct TileBounds<'a, T> {
    /// log₂ of the tile side.
    pub(super) shift: u32,
    /// Tiles in a row of the map.
    pub(super) across: usize,
    pub(super) tiles: &'a [TileState<T>],
}

impl<'a, T> TileBounds<'a, T> {
    /// The bounds of `raster`'s tiles.
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] when `tiles` is not one state a tile.
    pub fn new(raster: RasterConfig, tiles: &'a [TileState<T>]) -> Result<Self, crate::ConfigError> {
        if tiles.len() != raster.tile_count() {
            return Err(crate::ConfigError::BufferLength {
                buffer: "tiles",
                expected: raster.tile_count(),
                found: tiles.len(),
            });
        }
        Ok(Self { shift: raster.tile_shift(), across: raster.tiles().0 as usize, tiles })
    }
}

impl<'a, F: DepthFormat> MapView<'a, F> {
    /// The map's raster configuration.
    #[must_use]
    pub const fn raster(&self) -> &RasterConfig {
        &self.raster
    }

    /// View finished maps. `z2` may be empty when no test reads it.
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] naming a buffer of the wrong length.
    pub fn new(
        raster: RasterConfig,
        z1: &'a [F::Texel],
        z2: &'a [F::Texel],
        tiles: &'a [TileState<F::Texel>],
    ) -> Result<Self, crate::ConfigError> {
        let texels = raster.texel_count();
        let wrong = |buffer, expected, found| crate::ConfigError::BufferLength { buffer, expected, found };
        if z1.len() != texels {
            return Err(wrong("z1", texels, z1.len()));
        }
        if !z2.is_empty() && z2.len() != texels {
            return Err(wrong("z2", texels, z2.len()));
        }
        let bounds = TileBounds::new(raster, tiles)?;
        Ok(Self {
            raster,
            z1,
            z2,
            bounds,
            #[cfg(feature = "tilings")]
            others: &[],
            second_in_z1: false,
        })
    }

    /// The same view, its lookups also tested against `others`: the
    /// bounds of the same texels in other tilings (tiling `k + 1` is
    /// `others[k]`). A lookup that some tilings cull and others do not
    /// reads its texels for those that do not, reported to them alone
    /// ([`Probe::event_for`]); the shadow is the same whichever culls.
    ///
    /// A datapath the simulator builds in (the `tilings` feature, which
    /// costs the firmware's flash budget some 700 bytes it does not have).
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] naming `tilings` when there are
    /// more than [`Tilings::MAX`](crate::probe::Tilings::MAX) in all.
    #[cfg(feature = "tilings")]
    pub fn with_tilings(self, others: &'a [TileBounds<'a, F::Texel>]) -> Result<Self, crate::ConfigError> {
        let most = crate::probe::Tilings::MAX - 1;
        if others.len() > most {
            return Err(crate::ConfigError::BufferLength { buffer: "tilings", expected: most, found: others.len() });
        }
        Ok(Self { others, ..self })
    }

    /// View the map of a single-depth pass with front-face culling: its one
    /// buffer holds the second depth (Wang & Molnar 1994 §3.4), which
    /// [`DepthTest::Second`] then reads (so do the tests that need `z1`:
    /// there is no first depth in such a map).
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] naming a buffer of the wrong length.
    pub fn front_culled(
        raster: RasterConfig,
        z: &'a [F::Texel],
        tiles: &'a [TileState<F::Texel>],
    ) -> Result<Self, crate::ConfigError> {
        Ok(Self { second_in_z1: true, ..Self::new(raster, z, &[], tiles)? })
    }

    /// Texel `(x, y)` of `buf` widened to [`PlaneZ`] bits; the far value
    /// when `buf` is empty (no second depth: nothing behind).
    #[inline]
    fn texel(&self, buf: &[F::Texel], x: u32, y: u32) -> i64 {
        let i = y as usize * self.raster.width() as usize + x as usize;
        F::widen(buf.get(i).copied().unwrap_or(F::FAR))
    }

    /// One sample: whether a receiver at depth `z` less `bias` ([`PlaneZ`]
    /// bits), rounded to the map's format, lies behind the test's reference
    /// at texel `(x, y)`, the texels read reported to probes that ask;
    /// `None` outside the map (lit, nothing read).
    /// A probe that watches taps ([`Probe::TAPS`]) is told the sample, with
    /// its `weight` in the filter.
    #[inline]
    pub(crate) fn sample<P: Probe>(
        &self,
        test: DepthTest,
        (x, y): (i64, i64),
        z: i64,
        bias: i64,
        weight: u64,
        probe: &mut P,
    ) -> Option<bool> {
        let inside = match (u32::try_from(x), u32::try_from(y)) {
            (Ok(u), Ok(v)) if u < self.raster.width() && v < self.raster.height() => Some((u, v)),
            _ => None,
        };
        let shadowed = inside.map(|(u, v)| self.compare(test, u, v, at_format::<F>(z.saturating_sub(bias)), probe));
        if P::TAPS {
            let first = inside.filter(|_| !self.second_in_z1).map(|(u, v)| self.texel(self.z1, u, v));
            probe.tap(Tap {
                x,
                y,
                receiver: at_format::<F>(z),
                bias,
                reference: inside.map(|(u, v)| self.reference(test, u, v)),
                first,
                shadowed: shadowed.unwrap_or(false),
                weight,
            });
        }
        shadowed
    }

    /// The sample of texel `(x, y)`, inside the map, for a receiver already
    /// biased and rounded to the map's format: whether it lies behind the
    /// test's reference, the texels read reported to probes that ask.
    #[inline]
    pub(super) fn compare<P: Probe>(&self, test: DepthTest, x: u32, y: u32, receiver: i64, probe: &mut P) -> bool {
        if P::TEXELS {
            for buffer in self.buffers_read(test) {
                probe.texel_read(TexelRead { buffer, x, y });
            }
        }
        receiver > self.reference(test, x, y)
    }

    /// The buffers a test reads from this map (one, or both).
    pub(crate) fn buffers_read(&self, test: DepthTest) -> impl Iterator<Item = Buffer> {
        let z1 = test.needs_z1() || (test.needs_z2() && self.second_in_z1);
        let z2 = test.needs_z2() && !self.second_in_z1;
        [(z1, Buffer::Z1), (z2, Buffer::Z2)].into_iter().filter_map(|(read, b)| read.then_some(b))
    }

    /// A tile's stored bounds of the second depth: `z2`'s, the single
    /// buffer's in a front-face-culled map, the far value when there is none.
    #[inline]
    pub(super) fn second_bounds(&self, t: &TileState<F::Texel>) -> (F::Texel, F::Texel) {
        if self.second_in_z1 {
            (t.z1_min, t.z1_max)
        } else if self.z2.is_empty() {
            (F::FAR, F::FAR)
        } else {
            (t.z2_min, t.z2_max)
        }
    }

    /// The smallest and largest reference over the texels of `r` (inside
    /// the map), read row by row: a test that reads one buffer reduces its
    /// texels and widens the two it keeps.
    pub(super) fn texel_bounds(&self, test: DepthTest, r: &TileRect) -> (i64, i64) {
        let second = if self.second_in_z1 { self.z1 } else { self.z2 };
        let one = match test {
            DepthTest::First => Some(self.z1),
            DepthTest::Second => Some(second),
            _ => None,
        };
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        match one {
            // No second depth: nothing behind.
            Some([]) => return (F::widen(F::FAR), F::widen(F::FAR)),
            Some(buf) => {
                let w = self.raster.width() as usize;
                let (x0, x1) = (r.x0 as usize, r.x1 as usize);
                for y in r.y0 as usize..r.y1 as usize {
                    let row = buf.get(y * w + x0..y * w + x1).unwrap_or_default();
                    if let (Some(a), Some(b)) = (row.iter().map(|t| t.key()).min(), row.iter().map(|t| t.key()).max()) {
                        (lo, hi) = (lo.min(F::widen(F::Texel::from_key(a))), hi.max(F::widen(F::Texel::from_key(b))));
                    }
                }
            }
            None => {
                for y in r.y0..r.y1 {
                    for x in r.x0..r.x1 {
                        let reference = self.reference(test, x, y);
                        (lo, hi) = (lo.min(reference), hi.max(reference));
                    }
                }
            }
        }
        (lo, hi)
    }

    pub(super) fn reference(&self, test: DepthTest, x: u32, y: u32) -> i64 {
        let z1 = if test.needs_z1() { self.texel(self.z1, x, y) } else { 0 };
        let second = if self.second_in_z1 { self.z1 } else { self.z2 };
        let z2 = if test.needs_z2() { self.texel(second, x, y) } else { 0 };
        test.reference(z1, z2)
    }
}
