//! The shading unit on blocks of pixels: when only the shadow fraction is
//! kept, a 4×4 block of one flat triangle is settled at once when the
//! shadow unit settles the region of the map it covers: by the tiles'
//! stored bounds, or else by the region's texels.
//!
//! The light points of a block of pixels on one triangle lie in the convex
//! hull of its corner pixels' points: the map position is a projective
//! function of the pixel (`U/Λw`, `V/Λw`, with `Λw > 0` at the corners and
//! so over the block), and the divider truncates each quotient by less
//! than one unit of the last place. So the block's points lie in the
//! corners' bounding box widened by that unit, and a flat receiver's depth
//! — the light pass's plane, linear on the map, then floored — between its
//! values at that box's corners (or, for a triangle with no plane on the
//! map, its own depth `Z/Λw`, projective as well: between its corners'
//! values, widened by the division's unit). [`ShadowUnit::settle`] decides the lookups
//! of that whole region or declines; a declined block, and any block that
//! is not one flat triangle, is shaded pixel by pixel. The fractions are
//! the pixel-by-pixel unit's, bit for bit (a test compares them); the
//! events would not be, so probes that watch events take the pixel unit.

use glam::Mat4;

use super::{
    Interp, LightPoint, MapCoord, MapView, Normals, PixelResult, ShadeConfig, ShadeSetup, Shaded, ShadowUnit,
    TriangleSource, setup_of, shade_pixel,
};
use crate::depth::{DepthFormat, PlaneZ};
use crate::light_pass::NO_TRIANGLE;
use crate::probe::NoProbe;
use crate::raster::tile::TileRect;
use crate::shadow::Filter;

/// The side of a block, pixels.
const BLOCK: u32 = 4;

/// Whether blocks can be settled under `cfg`: flat receivers, and a box
/// filter whose ordinary lookup alone decides a pixel it settles (with
/// virtual samples, a box of at least 2×2 already reads the texels around
/// the point).
pub(super) fn settle(cfg: &ShadeConfig) -> bool {
    cfg.normals == Normals::Flat
        && match cfg.shadow.filter() {
            Filter::Box { size } => size >= 2 || !cfg.virtual_samples,
            _ => false,
        }
}

/// [`super::shade_rect`] by blocks, for a result that keeps the fraction
/// alone and a probe that watches no events.
#[allow(clippy::too_many_arguments, reason = "the unit's inputs, its store and the light's matrix")]
pub(super) fn shade<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, R: PixelResult>(
    cfg: &ShadeConfig,
    rect: TileRect,
    ids: &[u32],
    map: &MapView<'_, F>,
    scene: &S,
    out: &mut [R],
    unit: &U,
    setups: &mut [ShadeSetup],
    light_inverse_transpose: &Mat4,
) {
    let width = (rect.x1 - rect.x0) as usize;
    let at = |px: u32, py: u32| (py - rect.y0) as usize * width + (px - rect.x0) as usize;
    // The store is consulted when the id changes, as in the pixel unit.
    let (mut run, mut interp): (u32, Option<&Interp>) = (NO_TRIANGLE, None);
    for by in (rect.y0..rect.y1).step_by(BLOCK as usize) {
        for bx in (rect.x0..rect.x1).step_by(BLOCK as usize) {
            let block = TileRect { x0: bx, y0: by, x1: (bx + BLOCK).min(rect.x1), y1: (by + BLOCK).min(rect.y1) };
            let pixels = || (block.y0..block.y1).flat_map(move |py| (block.x0..block.x1).map(move |px| (px, py)));
            let first = ids.get(at(bx, by)).copied().unwrap_or(NO_TRIANGLE);
            let one_triangle = first != NO_TRIANGLE && pixels().all(|(px, py)| ids.get(at(px, py)) == Some(&first));
            let mut settled = None;
            if one_triangle {
                if first != run {
                    (run, interp) = (first, setup_of(cfg, map, scene, setups, first));
                }
                settled =
                    interp.and_then(|i| region::<F>(i, &block)).and_then(|r| unit.settle(map, cfg, r.lo, r.hi, r.z));
            }
            for (px, py) in pixels() {
                let k = at(px, py);
                let result = match settled {
                    Some(shadow) => R::keep(Shaded { shadow, ..Shaded::BACKGROUND }),
                    None => {
                        let id = ids.get(k).copied().unwrap_or(NO_TRIANGLE);
                        if id != run {
                            (run, interp) = (id, setup_of(cfg, map, scene, setups, id));
                        }
                        interp.map_or(R::BACKGROUND, |i| {
                            R::keep(shade_pixel(cfg, map, unit, &mut NoProbe, light_inverse_transpose, (px, py), i))
                        })
                    }
                };
                if let Some(o) = out.get_mut(k) {
                    *o = result;
                }
            }
        }
    }
}

/// A region of the map: its corners (texels) and the receiver's depths
/// over it ([`PlaneZ`] bits).
struct Region {
    lo: [MapCoord; 2],
    hi: [MapCoord; 2],
    z: (i64, i64),
}

/// The map region a block of one flat triangle covers: the bounding box
/// of its corner pixels' light points widened by one unit of the last
/// place, and the range of the receiver's depth over it (the light pass's
/// plane over the box, or the triangle's own depths at the corners when
/// it has no plane on the map); `None` when a corner is behind the light.
fn region<F: DepthFormat>(interp: &Interp, block: &TileRect) -> Option<Region> {
    let (x1, y1) = (block.x1 - 1, block.y1 - 1);
    let corners = [(block.x0, block.y0), (x1, block.y0), (block.x0, y1), (x1, y1)];
    // Without the light pass's plane, a receiver's depth is its own light
    // point's, `Z/Λw`: projective too, so bounded by the corners' (and the
    // truncated division by one unit).
    let own_depth = interp.plane.is_none();
    let mut lo = [MapCoord::MAX; 2];
    let mut hi = [MapCoord::MIN; 2];
    let (mut z_lo, mut z_hi) = (i64::MAX, i64::MIN);
    for (px, py) in corners {
        let p = interp.light_point::<F>(px, py, own_depth)?;
        lo = [lo[0].min(p.x), lo[1].min(p.y)];
        hi = [hi[0].max(p.x), hi[1].max(p.y)];
        (z_lo, z_hi) = (z_lo.min(p.z.to_bits().saturating_sub(1)), z_hi.max(p.z.to_bits().saturating_add(1)));
    }
    let lo = lo.map(|c| c.saturating_sub(MapCoord::DELTA));
    let hi = hi.map(|c| c.saturating_add(MapCoord::DELTA));
    if !own_depth {
        (z_lo, z_hi) = (i64::MAX, i64::MIN);
        for (x, y) in [(lo[0], lo[1]), (hi[0], lo[1]), (lo[0], hi[1]), (hi[0], hi[1])] {
            let (z, _) = interp.plane_at(&LightPoint { x, y, z: PlaneZ::ZERO })?;
            (z_lo, z_hi) = (z_lo.min(z.to_bits()), z_hi.max(z.to_bits()));
        }
    }
    Some(Region { lo, hi, z: (z_lo, z_hi) })
}
