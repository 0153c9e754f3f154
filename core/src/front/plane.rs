//! The depth-plane interpolator: a triangle's depth `z = A·x + B·y + C`
//! over pixel centres, in [`PlaneZ`] bits, as the rasterizer steps it
//! (the plane is solved by [`super::setup`], whose documentation gives its
//! budget).

use crate::depth::PlaneZ;
use crate::grid::TileRect;

/// The depth plane in [`PlaneZ`] bits: `z(px, py) = c + a·px + b·py`,
/// exact coefficients (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthPlane {
    /// Step per pixel to the right.
    pub a: i128,
    /// Step per pixel down.
    pub b: i128,
    /// Value at the centre of pixel `(0, 0)`.
    pub c: i128,
}

/// Reduce modulo 2⁶⁴: the interpolator's wrapping representation.
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "modular arithmetic by design")]
const fn wrap(v: i128) -> i64 {
    v as i64
}

impl DepthPlane {
    /// The value at the centre of pixel `(px, py)` as the rasterizer steps
    /// it: modulo 2⁶⁴, exact inside the triangle.
    #[inline(always)]
    #[must_use]
    pub const fn at(&self, px: i64, py: i64) -> PlaneZ {
        PlaneZ::from_bits(
            wrap(self.c).wrapping_add(wrap(self.a).wrapping_mul(px)).wrapping_add(wrap(self.b).wrapping_mul(py)),
        )
    }

    /// The step per pixel to the right, as the rasterizer adds it.
    #[inline(always)]
    #[must_use]
    pub const fn step_x(&self) -> PlaneZ {
        PlaneZ::from_bits(wrap(self.a))
    }

    /// The step per pixel down, as the rasterizer adds it.
    #[inline(always)]
    #[must_use]
    pub const fn step_y(&self) -> PlaneZ {
        PlaneZ::from_bits(wrap(self.b))
    }

    /// The smallest value over the pixel centres of `r`, saturated to [`PlaneZ`].
    /// A plane takes its minimum over a rectangle at a corner, so this bounds
    /// every fragment of the triangle in `r` from below.
    #[inline]
    #[must_use]
    pub fn min_over(&self, r: &TileRect) -> PlaneZ {
        self.range_over(r).0
    }

    /// [`Self::range_over`] in `i64`, or `None` if anything overflows.
    #[inline]
    fn range_i64(&self, x0: i64, x1: i64, y0: i64, y1: i64) -> Option<(i64, i64)> {
        let (a, b, c) = (i64::try_from(self.a).ok()?, i64::try_from(self.b).ok()?, i64::try_from(self.c).ok()?);
        let (xa, xb) = (a.checked_mul(x0)?, a.checked_mul(x1)?);
        let (ya, yb) = (b.checked_mul(y0)?, b.checked_mul(y1)?);
        let lo = c.checked_add(xa.min(xb))?.checked_add(ya.min(yb))?;
        let hi = c.checked_add(xa.max(xb))?.checked_add(ya.max(yb))?;
        Some((lo, hi))
    }

    /// The smallest and largest values over the pixel centres of `r`,
    /// saturated to [`PlaneZ`].
    #[inline]
    #[must_use]
    pub fn range_over(&self, r: &TileRect) -> (PlaneZ, PlaneZ) {
        let (x0, x1) = (i64::from(r.x0), i64::from(r.x1.saturating_sub(1)));
        let (y0, y1) = (i64::from(r.y0), i64::from(r.y1.saturating_sub(1)));
        // Most planes fit in i64 over the target: checked arithmetic there,
        // i128 (exact, saturated to PlaneZ) for the steep rest.
        if let Some((lo, hi)) = self.range_i64(x0, x1, y0, y1) {
            return (PlaneZ::from_bits(lo), PlaneZ::from_bits(hi));
        }
        let x = |px: i64| self.a.saturating_mul(i128::from(px));
        let y = |py: i64| self.b.saturating_mul(i128::from(py));
        let (xa, xb) = (x(x0), x(x1));
        let (ya, yb) = (y(y0), y(y1));
        let sat = |v: i128| PlaneZ::from_bits(crate::round::saturate(v));
        let lo = self.c.saturating_add(xa.min(xb)).saturating_add(ya.min(yb));
        (sat(lo), sat(self.c.saturating_add(xa.max(xb)).saturating_add(ya.max(yb))))
    }
}
