//! Lookup culling: the tiles' stored bounds decide a lookup before any texel is read.

use super::{DepthTest, Filter, Lookup, MapCoord, MapView, Shadow, ShadowConfig, Texels, TileBounds, at_format};
use crate::depth::TileState;
use crate::depth::{DepthFormat, PlaneZ};
use crate::grid::TileRect;

/// The smallest and largest reference depth over the tiles under `r`, from
/// their stored bounds. A test that reads one buffer takes that buffer's
/// bounds; the others combine both per tile.
/// `tiles` are the bounds of one tiling of `map`.
#[inline]
pub(super) fn reference_bounds<F: DepthFormat>(
    map: &MapView<'_, F>,
    tiles: &TileBounds<'_, F::Texel>,
    test: DepthTest,
    r: &TileRect,
) -> (i64, i64) {
    match test {
        DepthTest::First => over_tiles(tiles, r, |t| (F::widen(t.z1_min), F::widen(t.z1_max))),
        DepthTest::Second => over_tiles(tiles, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (F::widen(z2_min), F::widen(z2_max))
        }),
        _ => over_tiles(tiles, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (test.reference(F::widen(t.z1_min), F::widen(z2_min)), test.reference(F::widen(t.z1_max), F::widen(z2_max)))
        }),
    }
}

/// The smallest and largest of `bounds` over the stored state of every
/// tile under `r` (most footprints lie in one tile: it is read alone).
#[inline(always)]
fn over_tiles<T>(tiles: &TileBounds<'_, T>, r: &TileRect, bounds: impl Fn(&TileState<T>) -> (i64, i64)) -> (i64, i64) {
    let shift = tiles.shift;
    let (tx0, tx1) = ((r.x0 >> shift) as usize, ((r.x1 - 1) >> shift) as usize);
    let (ty0, ty1) = ((r.y0 >> shift) as usize, ((r.y1 - 1) >> shift) as usize);
    if tx0 == tx1 && ty0 == ty1 {
        return tiles.tiles.get(ty0 * tiles.across + tx0).map_or((i64::MAX, i64::MIN), bounds);
    }
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for ty in ty0..=ty1 {
        let row = ty * tiles.across;
        for t in tiles.tiles.get(row + tx0..=row + tx1).unwrap_or_default() {
            let (a, b) = bounds(t);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
    }
    (lo, hi)
}

/// A region's lookups settled at once: the ordinary (no tangent plane)
/// lookups of every point whose map position lies in `[lo, hi]` (texels)
/// and whose receiver depth lies in `z` ([`PlaneZ`](crate::depth::PlaneZ)
/// bits), through a box filter with lookup culling — all lit, all
/// shadowed, or `None` when they differ. The union of the points'
/// footprints is the box from the footprint at `lo` to the one at `hi` (a
/// box's texels follow its point). The tiles' stored bounds over it are
/// consulted first; when they do not settle it, its references are read
/// texel by texel (up to [`SETTLE_TEXELS`] of them), as the points' own
/// lookups would read them. Either way a region is settled lit exactly
/// when every point's lookup is lit, and shadowed exactly when every one
/// is shadowed ([`super::filter`]'s front), bit for bit.
#[must_use]
pub(crate) fn settle_region<F: DepthFormat>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    lo: [MapCoord; 2],
    hi: [MapCoord; 2],
    z: (i64, i64),
) -> Option<Shadow> {
    if !cfg.cull_lookups || !matches!(cfg.filter, Filter::Box { .. }) {
        return None;
    }
    let (z_lo, z_hi) = z;
    if z_hi < 0 {
        // Nearer than the near plane: lit.
        return Some(Shadow::ZERO);
    }
    let at =
        |[x, y]: [MapCoord; 2]| Lookup { x, y, z: PlaneZ::ZERO, footprint: [MapCoord::ZERO; 2], seed: 0, slope: None };
    let (first, last) = (Texels::under(cfg.filter, &at(lo), None)?, Texels::under(cfg.filter, &at(hi), None)?);
    let union = Texels { x0: first.x0, y0: first.y0, x1: last.x1, y1: last.y1 };
    let (inside_map, whole) = union.clip(map.raster.width(), map.raster.height());
    // Every footprint off the map: lit.
    let Some(inside_map) = inside_map else { return Some(Shadow::ZERO) };
    let (bias_lo, bias_hi) = cfg.bias.bounds();
    // Every sample is lit when its reference is at or beyond `lit_from`,
    // and shadowed when it lies below `shadowed_below`.
    let lit_from = at_format::<F>(z_hi.saturating_sub(bias_lo));
    let shadowed_below = (whole && z_lo >= 0).then(|| at_format::<F>(z_lo.saturating_sub(bias_hi)));
    let settle = |(r_lo, r_hi): (i64, i64)| {
        if lit_from <= r_lo {
            Some(Shadow::ZERO)
        } else {
            shadowed_below.is_some_and(|s| s > r_hi).then_some(Shadow::ONE)
        }
    };
    settle(reference_bounds(map, &map.bounds, cfg.test, &inside_map))
        .or_else(|| (inside_map.area() <= SETTLE_TEXELS).then(|| settle(map.texel_bounds(cfg.test, &inside_map)))?)
}

/// The most texels [`settle_region`] reads to settle a region the tiles'
/// bounds do not: a 4×4 block of pixels over a 3×3 box at up to three
/// texels a pixel reads 225, an 8×8 block at about 1.6 texels a pixel 256.
const SETTLE_TEXELS: u32 = 256;
