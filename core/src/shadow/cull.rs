//! Lookup culling: the tiles' stored bounds decide a lookup before any texel is read.

use super::{DepthTest, MapView};
use crate::depth::DepthFormat;
use crate::depth::TileState;
use crate::raster::tile::TileRect;

/// The smallest and largest reference depth over the tiles under `r`, from
/// their stored bounds. A test that reads one buffer takes that buffer's
/// bounds; the others combine both per tile.
#[inline]
pub(super) fn reference_bounds<F: DepthFormat>(map: &MapView<'_, F>, test: DepthTest, r: &TileRect) -> (i64, i64) {
    match test {
        DepthTest::First => over_tiles(map, r, |t| (F::widen(t.z1_min), F::widen(t.z1_max))),
        DepthTest::Second => over_tiles(map, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (F::widen(z2_min), F::widen(z2_max))
        }),
        _ => over_tiles(map, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (test.reference(F::widen(t.z1_min), F::widen(z2_min)), test.reference(F::widen(t.z1_max), F::widen(z2_max)))
        }),
    }
}

/// The smallest and largest of `bounds` over the stored state of every
/// tile under `r` (most footprints lie in one tile: it is read alone).
#[inline(always)]
fn over_tiles<F: DepthFormat>(
    map: &MapView<'_, F>,
    r: &TileRect,
    bounds: impl Fn(&TileState<F::Texel>) -> (i64, i64),
) -> (i64, i64) {
    let shift = map.raster.tile_shift();
    let (tx0, tx1) = ((r.x0 >> shift) as usize, ((r.x1 - 1) >> shift) as usize);
    let (ty0, ty1) = ((r.y0 >> shift) as usize, ((r.y1 - 1) >> shift) as usize);
    if tx0 == tx1 && ty0 == ty1 {
        return map.tiles.get(ty0 * map.across + tx0).map_or((i64::MAX, i64::MIN), bounds);
    }
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for ty in ty0..=ty1 {
        let row = ty * map.across;
        for t in map.tiles.get(row + tx0..=row + tx1).unwrap_or_default() {
            let (a, b) = bounds(t);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
    }
    (lo, hi)
}
