//! The stencil unit: depth-fail ("Carmack's reverse") shadow volumes on the
//! camera's raster, the exact hard-shadow reference inside the pipeline
//! that Sen, Cammarano & Hanrahan 2003 (§4) compare silhouette maps with.
//!
//! # Volumes
//! An occluder triangle faces the light (solids keep their light-facing
//! triangles; open surfaces turn every triangle to face it). Its volume is
//! closed by a near cap (the triangle), a far cap (the triangle extruded
//! away from the light, reversed) and, for each edge not shared with
//! another occluder triangle — a silhouette edge — a side quad. Extrusion
//! is linear in homogeneous camera clip space: a vertex `v` moves to
//! `v + t·(w_λ·v − λ)` with `λ` the light's clip-space position (`w_λ = 1`)
//! or direction towards it (`w_λ = 0`), so every side quad lies in the plane
//! through the light and its edge. [`Volume`] emits the triangles, wound
//! outwards.
//!
//! # Counting
//! Each volume triangle is clipped (near plane and guard band; depth
//! beyond the far plane is clamped per fragment, not clipped, so far caps
//! survive and side quads reaching past the far plane keep their true
//! planes), snapped and set up exactly like scene triangles, and every fragment
//! compares its depth with the scene depth the visibility unit stored.
//! Where the volume lies at or behind the scene (the depth test fails),
//! a face turned away from the camera increments the stencil and a face
//! turned towards it decrements it, wrapping modulo 2⁸. A pixel with a
//! non-zero stencil is in shadow. Near caps coincide with the occluders'
//! own visible surfaces bit for bit (same vertex unit, same setup), and
//! count as failing there, so a lit face does not shadow itself.

mod volume;

pub use volume::{Volume, VolumeLight};

use crate::config::{ConfigError, CullMode, RasterConfig};
use crate::depth::DepthFormat;
use crate::front::clip::{ClipVertex, Clipped, DepthClip, Polygon, clip_triangle_with};
use crate::front::setup::{Coverage, Setup};
use crate::front::snap::{SnappedVertex, snap_beyond_far};
use crate::grid::{TileId, TileRect};
use crate::probe::{Event, Probe, RejectReason};
use crate::raster::mask::{LANE_GROUP, LANES, Lanes, RowMask, Serial, WIDEST};

/// Pixel bounds `(x0, y0, x1, y1)`, half-open.
type Rect = (u32, u32, u32, u32);

/// Bytes of one stencil texel.
pub const STENCIL_BYTES: u32 = 1;

/// Whether the snapped triangle faces the camera: counter-clockwise in NDC
/// (y up), as [`Setup::new`] decides facing.
fn front_facing(v: &[SnappedVertex; 3]) -> bool {
    let d = (v[1].x.0 - v[0].x.0) * (v[2].y.0 - v[0].y.0) - (v[1].y.0 - v[0].y.0) * (v[2].x.0 - v[0].x.0);
    d < 0
}

/// The stencil unit over caller-owned buffers: the scene depth the
/// visibility unit stored and one stencil byte per pixel.
pub struct StencilPass<'a, F: DepthFormat> {
    raster: RasterConfig,
    depth: &'a [F::Texel],
    stencil: &'a mut [u8],
}

impl<'a, F: DepthFormat> StencilPass<'a, F> {
    /// A pass over the camera target `raster`; the stencil is cleared.
    ///
    /// # Errors
    /// [`ConfigError::BufferLength`] naming a buffer of the wrong length.
    pub fn new(raster: RasterConfig, depth: &'a [F::Texel], stencil: &'a mut [u8]) -> Result<Self, ConfigError> {
        let texels = raster.texel_count();
        for (buffer, found) in [("depth", depth.len()), ("stencil", stencil.len())] {
            if found != texels {
                return Err(ConfigError::BufferLength { buffer, expected: texels, found });
            }
        }
        stencil.fill(0);
        Ok(Self { raster, depth, stencil })
    }

    /// Count one volume triangle (camera clip space). Any input is
    /// accepted; what cannot be drawn draws nothing and is reported as a
    /// rejection, as the front end reports the scene's triangles.
    pub fn draw<P: Probe>(&mut self, tri: &[ClipVertex; 3], probe: &mut P) {
        probe.event(Event::TriangleSubmitted);
        if tri.iter().flatten().any(|c| !c.is_finite()) {
            probe.event(Event::TriangleRejected { reason: RejectReason::NonFinite });
            return;
        }
        let mut poly = Polygon::new();
        match clip_triangle_with(tri, self.raster.guard(), DepthClip::Near, &mut poly) {
            Clipped::Inside => self.draw_snapped(tri, probe),
            Clipped::Polygon => {
                for i in 1..poly.len().saturating_sub(1) {
                    self.draw_snapped(&[poly[0], poly[i], poly[i + 1]], probe);
                }
            }
            Clipped::Outside => probe.event(Event::TriangleRejected { reason: RejectReason::Clipped }),
        }
    }

    fn draw_snapped<P: Probe>(&mut self, tri: &[ClipVertex; 3], probe: &mut P) {
        let r = self.raster;
        let snap = |v: &ClipVertex| snap_beyond_far::<F>(&r, v);
        let (Some(a), Some(b), Some(c)) = (snap(&tri[0]), snap(&tri[1]), snap(&tri[2])) else {
            probe.event(Event::TriangleRejected { reason: RejectReason::NonFinite });
            return;
        };
        let v = [a, b, c];
        let setup = match Setup::new(&r, v, CullMode::None, 0) {
            Ok(setup) => setup,
            Err(reason) => {
                probe.event(Event::TriangleRejected { reason });
                return;
            }
        };
        probe.event(Event::TriangleSetup);
        let step: u8 = if front_facing(&v) { u8::MAX } else { 1 };
        let b = setup.bbox;
        let s = r.tile_shift();
        // Binned to every tile its bounding box overlaps, and counted tile
        // by tile, as a tiler draws it (each pixel is updated once, so the
        // order of the tiles changes no bit).
        let (tx0, ty0) = (b.x0 >> s, b.y0 >> s);
        let (tx1, ty1) = (b.x1.saturating_sub(1).max(b.x0) >> s, b.y1.saturating_sub(1).max(b.y0) >> s);
        probe.event(Event::TriangleBinned { tiles: (tx1 - tx0 + 1) * (ty1 - ty0 + 1) });
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
                let tile = TileId { x: tx as u16, y: ty as u16 };
                let rect = r.tile_rect(tile);
                let (x0, x1) = (rect.x0.max(b.x0), rect.x1.min(b.x1));
                let (y0, y1) = (rect.y0.max(b.y0), rect.y1.min(b.y1));
                self.count_in(&setup, step, (x0, y0, x1, y1), tile, probe);
            }
        }
    }

    /// Count one set-up volume triangle's fragments in `[x0, x1) × [y0, y1)`
    /// of `tile`: the coverage-mask unit ([`crate::raster::mask`]) finds the
    /// covered pixels a row at a time, in strips at most [`WIDEST`] wide
    /// (a side quad's bounding box is mostly empty), and each is compared
    /// with the scene depth.
    fn count_in<P: Probe>(&mut self, setup: &Setup, step: u8, (x0, y0, x1, y1): Rect, tile: TileId, probe: &mut P) {
        let (mut fragments, mut writes) = (0u32, 0u32);
        let mut strip = x0;
        while strip < x1 {
            let rect = TileRect { x0: strip, y0, x1: x1.min(strip.saturating_add(WIDEST)), y1 };
            let width = rect.width();
            let counted = match setup.classify(&rect) {
                Coverage::Empty => (0, 0),
                // Every pixel: a mask of the strip's columns on every row.
                Coverage::Full => self.count_rows(setup, step, &rect, Whole(u64::MAX >> (u64::BITS - width))),
                Coverage::Partial if !LANES => self.count_rows(setup, step, &rect, Serial::new(setup, &rect)),
                Coverage::Partial => {
                    let lanes = if width <= LANE_GROUP {
                        Lanes::<1>::new(setup, &rect).map(|m| self.count_rows(setup, step, &rect, m))
                    } else if width <= 2 * LANE_GROUP {
                        Lanes::<2>::new(setup, &rect).map(|m| self.count_rows(setup, step, &rect, m))
                    } else if width <= 4 * LANE_GROUP {
                        Lanes::<4>::new(setup, &rect).map(|m| self.count_rows(setup, step, &rect, m))
                    } else {
                        Lanes::<8>::new(setup, &rect).map(|m| self.count_rows(setup, step, &rect, m))
                    };
                    lanes.unwrap_or_else(|| self.count_rows(setup, step, &rect, Serial::new(setup, &rect)))
                }
            };
            fragments += counted.0;
            writes += counted.1;
            strip = rect.x1;
        }
        if fragments > 0 {
            probe.event(Event::VolumeFragments { tile, fragments, depth_bytes: fragments * F::KIND.bytes() });
            probe.event(Event::StencilRead { tile, texels: fragments, bytes: fragments * STENCIL_BYTES });
        }
        if writes > 0 {
            probe.event(Event::StencilWrite { tile, texels: writes, bytes: writes * STENCIL_BYTES });
        }
    }

    /// The fragments of `rect` whose rows `masks` cover, and the stencil
    /// texels they wrote (where the volume lies at or behind the scene).
    #[inline(always)]
    fn count_rows<M: RowMask>(&mut self, setup: &Setup, step: u8, rect: &TileRect, mut masks: M) -> (u32, u32) {
        let (mut fragments, mut writes) = (0u32, 0u32);
        let width = self.raster.width() as usize;
        for py in rect.y0..rect.y1 {
            let mut mask = masks.next_row();
            fragments += mask.count_ones();
            while mask != 0 {
                let px = rect.x0 + mask.trailing_zeros();
                mask &= mask - 1;
                let k = py as usize * width + px as usize;
                let (Some(&scene), Some(s)) = (self.depth.get(k), self.stencil.get_mut(k)) else { continue };
                if F::texel(setup.plane.at(i64::from(px), i64::from(py))) >= scene {
                    *s = s.wrapping_add(step);
                    writes += 1;
                }
            }
        }
        (fragments, writes)
    }

    /// The stencil: non-zero where the pixel is in shadow.
    #[must_use]
    pub fn stencil(&self) -> &[u8] {
        self.stencil
    }
}

/// A strip every one of whose pixels the triangle covers: the same mask
/// on every row.
struct Whole(u64);

impl RowMask for Whole {
    const WIDTH: u32 = WIDEST;

    #[inline(always)]
    fn next_row(&mut self) -> u64 {
        self.0
    }
}
