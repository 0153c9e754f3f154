//! The shading unit on blocks of pixels: when only the shadow fraction is
//! kept, an 8×8 block of one flat triangle, or else each 4×4 block in it,
//! is settled at once when the shadow unit settles the region of the map
//! it covers: by the tiles' stored bounds, or else by the region's texels
//! ([`crate::shadow`]'s lookup culling, over a block's region). A block
//! no triangle covers is the background at once.
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
//! values, widened by the division's unit). [`ShadowUnit::settle`] decides
//! the lookups of that whole region or declines; a declined 4×4 block, and
//! any that is not one flat triangle, is shaded pixel by pixel. The
//! fractions are the pixel-by-pixel unit's, bit for bit (a test compares
//! them); the events would not be, so probes that watch events take the
//! pixel unit.

use glam::Mat4;

use super::{
    Interp, LightPoint, MapCoord, MapView, Normals, PixelResult, ShadeConfig, ShadeInputs, ShadeSetup, Shaded,
    ShadowUnit, TriangleSource, setup_of, setup_slot, shade_pixel,
};
use crate::depth::{DepthFormat, PlaneZ};
use crate::grid::TileRect;
use crate::light_pass::NO_TRIANGLE;
use crate::probe::NoProbe;
use crate::shadow::Filter;

/// The side of a block, pixels: a block that does not settle is tried
/// again as four of half the side, and those pixel by pixel.
const BLOCK: u32 = 8;

/// The side of the smallest block tried.
const SUB_BLOCK: u32 = 4;

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
pub(super) fn shade<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, R: PixelResult>(
    inputs: &ShadeInputs<'_, F, S, U>,
    rect: TileRect,
    (ids, out): (&[u32], &mut [R]),
    setups: &mut [ShadeSetup],
    light_inverse_transpose: &Mat4,
) {
    let &ShadeInputs { cfg, map, scene, unit } = inputs;
    let mut blocks = Blocks { cfg, rect, ids, map, scene, unit, setups, run: (NO_TRIANGLE, None) };
    for by in (rect.y0..rect.y1).step_by(BLOCK as usize) {
        for bx in (rect.x0..rect.x1).step_by(BLOCK as usize) {
            let block = blocks.block(bx, by, BLOCK);
            if blocks.fill(&block, out) {
                continue;
            }
            for sy in (block.y0..block.y1).step_by(SUB_BLOCK as usize) {
                for sx in (block.x0..block.x1).step_by(SUB_BLOCK as usize) {
                    let sub = blocks.block(sx, sy, SUB_BLOCK).intersect(&block).unwrap_or(block);
                    if !blocks.fill(&sub, out) {
                        blocks.pixels(&sub, out, light_inverse_transpose);
                    }
                }
            }
        }
    }
}

/// The block unit's state over one rectangle of the image.
struct Blocks<'c, 'm, 's, F: DepthFormat, S, U> {
    cfg: &'c ShadeConfig,
    rect: TileRect,
    ids: &'c [u32],
    map: &'c MapView<'m, F>,
    scene: &'c S,
    unit: &'c U,
    setups: &'s mut [ShadeSetup],
    /// The triangle last met and its setup's place in the store (the
    /// store is consulted when the id changes, as in the pixel unit).
    run: (u32, Option<usize>),
}

impl<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>> Blocks<'_, '_, '_, F, S, U> {
    /// The block of side `side` at `(x, y)`, cut to the rectangle.
    fn block(&self, x: u32, y: u32, side: u32) -> TileRect {
        TileRect { x0: x, y0: y, x1: (x + side).min(self.rect.x1), y1: (y + side).min(self.rect.y1) }
    }

    /// The rows of `block` in a buffer of the rectangle's pixels.
    fn rows(&self, block: &TileRect) -> impl Iterator<Item = core::ops::Range<usize>> + use<F, S, U> {
        let (width, x0, y0) = (self.rect.width() as usize, self.rect.x0, self.rect.y0);
        let (a, b) = ((block.x0 - x0) as usize, (block.x1 - x0) as usize);
        (block.y0 - y0..block.y1 - y0).map(move |y| y as usize * width + a..y as usize * width + b)
    }

    /// The setup of triangle `id`, from the last one met or the store.
    fn interp(&mut self, id: u32) -> Option<&Interp> {
        if id != self.run.0 {
            let found = setup_of(self.cfg, self.map, self.scene, self.setups, id).is_some();
            self.run = (id, found.then(|| setup_slot(id, self.setups.len())));
        }
        self.setups.get(self.run.1?)?.0.as_ref()
    }

    /// Fill `block` with one result when it can be settled at once: no
    /// triangle (the background), or one flat triangle whose map region
    /// the shadow unit settles. Whether it did.
    fn fill<R: PixelResult>(&mut self, block: &TileRect, out: &mut [R]) -> bool {
        let first = self.ids.get(self.rows(block).next().map_or(0, |r| r.start)).copied().unwrap_or(NO_TRIANGLE);
        if !self.rows(block).all(|r| self.ids.get(r).is_some_and(|row| row.iter().all(|&id| id == first))) {
            return false;
        }
        let result = if first == NO_TRIANGLE {
            R::BACKGROUND
        } else {
            let settled = self
                .interp(first)
                .and_then(|i| region::<F>(i, block))
                .and_then(|r| self.unit.settle(self.map, self.cfg, r.lo, r.hi, r.z));
            match settled {
                Some(shadow) => R::keep(Shaded { shadow, ..Shaded::BACKGROUND }),
                None => return false,
            }
        };
        for r in self.rows(block) {
            if let Some(row) = out.get_mut(r) {
                row.fill(result);
            }
        }
        true
    }

    /// Shade `block` pixel by pixel.
    fn pixels<R: PixelResult>(&mut self, block: &TileRect, out: &mut [R], light_inverse_transpose: &Mat4) {
        for (py, r) in (block.y0..).zip(self.rows(block)) {
            let (Some(ids), Some(out)) = (self.ids.get(r.clone()), out.get_mut(r)) else { continue };
            for (px, (&id, o)) in (block.x0..).zip(ids.iter().zip(out)) {
                let (cfg, map, unit) = (self.cfg, self.map, self.unit);
                *o = self.interp(id).map_or(R::BACKGROUND, |i| {
                    R::keep(shade_pixel(cfg, map, unit, &mut NoProbe, light_inverse_transpose, (px, py), i))
                });
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
