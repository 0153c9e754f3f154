//! Viewport transform and vertex snap to the subpixel grid.
//!
//! Raster orientation: x to the right, y **down**, row 0 at the top. A
//! vertex at NDC `(x, y)` lands at pixel coordinates
//! `((x + 1)·W/2, (1 − y)·H/2)`; pixel `(px, py)` samples its centre
//! `(px + ½, py + ½)`. Coordinates are snapped to `1/2^s` pixel, `s` the
//! subpixel bits: in f64, `x·(1/w)`, then `(· + 1)·(W/2)·2^s` rounded to
//! nearest with ties to even — the same on every target.
//!
//! # Integer budget
//! The guard band keeps every snapped coordinate inside `±2^GUARD_BITS`
//! pixels, so with at most 8 subpixel bits it fits in [`crate::budget::COORD_BITS`] bits
//! plus sign. Edge functions in [`crate::front::setup`] build on that bound.

use crate::budget::{BEYOND_FAR, COORD_BITS, PLANE_FRACTION_BITS, PLANE_ONE};
use crate::config::RasterConfig;
use crate::depth::{DepthFormat, PlaneZ};
use crate::front::clip::ClipVertex;

/// A coordinate on the subpixel grid: `value / 2^subpixel_bits` pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SubPx(pub i64);

/// A vertex after the viewport transform and snap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SnappedVertex {
    /// Column, in subpixels.
    pub x: SubPx,
    /// Row (down), in subpixels.
    pub y: SubPx,
    /// Depth in the interpolator's fixed point.
    pub z: PlaneZ,
}

/// Project a clipped vertex and snap it to the subpixel grid. `None` when
/// `w ≤ 0` (the one point of the guard-band cone with `w = 0`) or the
/// result is not finite.
#[must_use]
pub fn snap<F: DepthFormat>(raster: &RasterConfig, v: &ClipVertex) -> Option<SnappedVertex> {
    snap_to(raster, v, F::plane_z)
}

/// [`snap`] keeping depths beyond the far plane (up to
/// [`crate::budget::BEYOND_FAR`] times it) in the vertex, so that the plane through a
/// triangle that reaches past the far plane interpolates its nearer
/// fragments exactly; the depth clamp then happens per fragment, when a
/// fragment's depth is rounded to the format. The stencil unit's volumes
/// need this; everything else clips at the far plane.
#[must_use]
pub fn snap_beyond_far<F: DepthFormat>(raster: &RasterConfig, v: &ClipVertex) -> Option<SnappedVertex> {
    snap_to(raster, v, |z| {
        let reach = (F::SCALE << PLANE_FRACTION_BITS) * BEYOND_FAR;
        if z.is_nan() || z <= 0.0 {
            return PlaneZ::ZERO;
        }
        #[allow(clippy::cast_precision_loss, reason = "a power of two")]
        let bits = (z * (F::SCALE as f64) * PLANE_ONE).min(reach as f64);
        PlaneZ::from_bits(crate::round::round_ties_even(bits).clamp(0, reach))
    })
}

fn snap_to(raster: &RasterConfig, v: &ClipVertex, depth: impl Fn(f64) -> PlaneZ) -> Option<SnappedVertex> {
    let [x, y, z, w] = *v;
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let unit = f64::from(1u32 << raster.subpixel_bits());
    let limit = f64::from(1u32 << COORD_BITS);
    let inv_w = 1.0 / w;
    let [vw, vh] = raster.view();
    let sx = (x * inv_w + 1.0) * 0.5 * f64::from(vw) * unit;
    let sy = (1.0 - y * inv_w) * 0.5 * f64::from(vh) * unit;
    if !sx.is_finite() || !sy.is_finite() {
        return None;
    }
    // Rounding overshoot at the guard band is clamped; the band lies
    // far outside the target, so no sample moves. (`max`/`min` rather
    // than `clamp`: the same for finite `s`, without `clamp`'s panic path
    // for bounds it cannot see are ordered.)
    let snap = |s: f64| SubPx(crate::round::round_ties_even(s.max(-limit).min(limit)));
    // A window's coordinates: the whole target's, shifted exactly.
    let [ox, oy] = raster.origin().map(|o| i64::from(o) << raster.subpixel_bits());
    Some(SnappedVertex { x: SubPx(snap(sx).0 - ox), y: SubPx(snap(sy).0 - oy), z: depth(z * inv_w) })
}
