//! The per-tile summaries of the depth unit.
//!
//! Reeves, Salesin & Cook 1987 §3.3 propose storing "a maximum z value with
//! each tile" of the map so that whole regions can be skipped; here the
//! light pass keeps it live to skip work, and the camera pass can use the
//! stored bounds to skip lookups.
//!
//! Each tile keeps the min of `z1` and `z2` as fragments land, and the
//! **max of the buffer that culling tests** (`z1` for single, `z2` for
//! dual) together with how many texels hold it. When a fragment lowers a
//! texel that held the max, the count drops; at zero the max is *stale* —
//! still an upper bound, so culling against it stays correct. A stale max
//! is made exact by a reduction over the tile only when a triangle's
//! nearest depth lies beyond the tile's min, the case where the exact max
//! may cull it: drawing front to back refreshes it once per
//! layer and then culls, drawing back to front never pays for it.
//! When the tile is stored, all four bounds are resolved exactly.

use crate::depth::Texel;

/// What the map keeps about one tile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileState<T> {
    /// Smallest `z1` in the tile.
    pub z1_min: T,
    /// Largest `z1` in the tile (exact once the tile is stored).
    pub z1_max: T,
    /// Smallest `z2` in the tile (dual only; the clear value otherwise).
    pub z2_min: T,
    /// Largest `z2` in the tile (dual only; the clear value otherwise).
    pub z2_max: T,
    /// Times the tile was written back to the map (a count that follows the
    /// pass's schedule: a banded pass flushes its own setup stores at other
    /// times than a serial one, so only whether it is 0 is the same).
    pub stores: u32,
    /// Live max of the culled buffer.
    pub(crate) cull_max: T,
    /// Texels of the culled buffer that hold `cull_max`.
    pub(crate) cull_count: u32,
}

impl<T: Copy> TileState<T> {
    /// A cleared tile of `texels` texels, every value `far`.
    #[must_use]
    pub const fn cleared(far: T, texels: u32) -> Self {
        Self { z1_min: far, z1_max: far, z2_min: far, z2_max: far, stores: 0, cull_max: far, cull_count: texels }
    }

    /// The same summary with every depth converted by `f` (which must be
    /// monotonic, e.g. widening to raw bits).
    #[must_use]
    pub fn map<U>(self, f: impl Fn(T) -> U) -> TileState<U> {
        TileState {
            z1_min: f(self.z1_min),
            z1_max: f(self.z1_max),
            z2_min: f(self.z2_min),
            z2_max: f(self.z2_max),
            stores: self.stores,
            cull_max: f(self.cull_max),
            cull_count: self.cull_count,
        }
    }

    /// The max stored depth that culling compares against.
    #[must_use]
    pub const fn cull_max(&self) -> T {
        self.cull_max
    }
}

/// The rows of a tile's rectangle `r` in a row-major buffer of `width` columns.
pub(crate) fn tile_rows<T>(buf: &[T], r: crate::grid::TileRect, width: usize) -> impl Iterator<Item = &[T]> {
    (r.y0..r.y1).filter_map(move |y| {
        let base = y as usize * width;
        buf.get(base + r.x0 as usize..base + r.x1 as usize)
    })
}

/// How many texels of a set of rows hold `value` (a vectorizable count).
pub(crate) fn count_of<'r, T: Copy + Eq + 'r>(rows: impl Iterator<Item = &'r [T]>, value: T) -> u32 {
    rows.map(|row| row.iter().map(|&t| u32::from(t == value)).sum::<u32>()).sum()
}

/// The min and max of a set of rows of texels (`far` and `0` when empty).
pub(crate) fn min_max<'r, T: Texel + 'r>(rows: impl Iterator<Item = &'r [T]>, far: T) -> (T, T) {
    let (lo, hi) = rows.fold((far.key(), T::default().key()), |(lo, hi), row| {
        row.iter().fold((lo, hi), |(lo, hi), &t| (lo.min(t.key()), hi.max(t.key())))
    });
    (T::from_key(lo), T::from_key(hi))
}
