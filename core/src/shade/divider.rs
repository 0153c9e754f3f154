//! The shading unit's divider: one reciprocal per pixel, exact truncated quotients.

use crate::budget::{DIVIDER_BITS, MAP_FRACTION_BITS, MAP_ONE, MAP_SCALE};
use crate::round::saturate;
use crate::shadow::MapCoord;

/// A divider by `w > 0` with a reciprocal estimate, as hardware divides:
/// `n·2¹⁶ / w` (truncated toward zero as `i128` division is, saturated to
/// `i64`; `None` if `n·2¹⁶` overflows) is the f64 product `n · (2¹⁶/w)` (off by at most a unit or
/// two below 2⁵⁰), then corrected until the remainder `n·2¹⁶ − q·w` has the
/// sign of `n` and lies within `w` — the exact truncated quotient, bit for
/// bit. One reciprocal serves every numerator over the same `w` (the two
/// map coordinates of a pixel). Numerators or divisors outside `i64`, and
/// quotients beyond 2⁵⁰, take the exact `i128` division.
#[derive(Clone, Copy, Debug)]
pub(super) struct Reciprocal {
    w: i128,
    /// `w` when it fits the fast path (below 2⁶¹, so remainders of a few
    /// `w` fit in `i64`).
    w64: Option<i64>,
    inverse: f64,
}

impl Reciprocal {
    #[inline]
    pub(super) fn new(w: i128) -> Self {
        let w64 = i64::try_from(w).ok().filter(|&w| w > 0 && w < 1 << DIVIDER_BITS);
        #[allow(clippy::cast_precision_loss, reason = "an estimate, corrected after")]
        let inverse = w64.map_or(0.0, |w| MAP_SCALE / w as f64);
        Self { w, w64, inverse }
    }

    /// `n·2¹⁶ / w` saturated to `i64`.
    #[inline]
    pub(super) fn div_shifted(&self, n: i128) -> Option<i64> {
        if let Some(q) = self.div_shifted_narrow(n) {
            return Some(q);
        }
        Some(saturate(n.checked_mul(i128::from(MAP_ONE))? / self.w))
    }

    /// `n·2¹⁶ / w` clamped to a map coordinate; `None` if `n·2¹⁶` overflows.
    #[inline]
    pub(super) fn coord(&self, n: i128) -> Option<MapCoord> {
        let q = self.div_shifted(n)?;
        #[allow(clippy::cast_possible_truncation, reason = "clamped to i32")]
        Some(MapCoord::from_bits(q.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32))
    }

    /// The estimate-and-correct path of [`Reciprocal::div_shifted`]; `None`
    /// where it does not apply.
    #[inline]
    fn div_shifted_narrow(&self, n: i128) -> Option<i64> {
        if let (Some(w), Ok(n)) = (self.w64, i64::try_from(n)) {
            #[allow(clippy::cast_precision_loss, reason = "an estimate, corrected below")]
            let estimate = n as f64 * self.inverse;
            if estimate.abs() < 1.0e15 {
                // The cast truncates toward zero, as the division does.
                #[allow(clippy::cast_possible_truncation, reason = "below 2^50")]
                let mut q = estimate as i64;
                // The true remainder is within a few `w` of zero, so the
                // wrapping 64-bit arithmetic gives it exactly.
                let mut r = (n << MAP_FRACTION_BITS).wrapping_sub(q.wrapping_mul(w));
                if n >= 0 {
                    while r < 0 {
                        (q, r) = (q - 1, r + w);
                    }
                    while r >= w {
                        (q, r) = (q + 1, r - w);
                    }
                } else {
                    while r > 0 {
                        (q, r) = (q + 1, r - w);
                    }
                    while r <= -w {
                        (q, r) = (q - 1, r + w);
                    }
                }
                return Some(q);
            }
        }
        None
    }
}
