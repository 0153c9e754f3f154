//! A lookup's point, footprint and receiver slopes, and the texels under them.

use fixed::types::U16F16;

use super::{Filter, HALF, Jitter, MapCoord};
use crate::budget::{MAP_FRACTION_BITS, MAP_HALF};
use crate::depth::PlaneZ;
use crate::grid::TileRect;

/// One lookup: a surface point in light space and its footprint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lookup {
    /// Column on the map, texels.
    pub x: MapCoord,
    /// Row on the map (down), texels.
    pub y: MapCoord,
    /// Light-space depth of the point.
    pub z: PlaneZ,
    /// Half-size of the pixel's footprint on the map, texels (for the
    /// jittered filter; Reeves' `sres`, `tres` in texels).
    pub footprint: [MapCoord; 2],
    /// Seed of this lookup's random numbers (the same seed, the same result).
    pub seed: u64,
    /// The receiver's tangent plane, when each sample compares its own
    /// depth (Wang & Molnar's virtual samples); `None` compares `z`.
    pub slope: Option<Slope>,
}

/// A receiver's tangent plane on the map: its depth rises by `du` per texel
/// to the right and `dv` per texel down ([`PlaneZ`] bits), through the
/// lookup's point. Wang & Molnar 1994 §3.2: "virtual samples".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Slope {
    /// Depth step per texel to the right.
    pub du: i64,
    /// Depth step per texel down.
    pub dv: i64,
}

/// `a · b / 2¹⁶`, floored, saturated to `i64`.
#[inline]
pub(crate) fn mul_shift(a: i64, b: i64) -> i64 {
    crate::round::saturate((i128::from(a) * i128::from(b)) >> MAP_FRACTION_BITS)
}

impl Lookup {
    /// The receiver's depth at the centre of texel `(x, y)`, evaluated
    /// directly: `z + ⌊du·Δu⌋ + ⌊dv·Δv⌋` with `Δu`, `Δv` the centre's offset
    /// from the point in 2⁻¹⁶ texels. Without a slope, `z`. Stepping one
    /// texel adds exactly `du` (or `dv`): the filters step by forward
    /// differences and get these same bits.
    #[must_use]
    pub fn depth_at(&self, x: i32, y: i32) -> i64 {
        self.depth_on(self.slope, x, y)
    }

    /// [`Lookup::depth_at`] for the receiver with slope `slope`.
    pub(super) fn depth_on(&self, slope: Option<Slope>, x: i32, y: i32) -> i64 {
        let z = self.z.to_bits();
        let Some(s) = slope else { return z };
        let centre = |t: i32, p: MapCoord| (i64::from(t) << MAP_FRACTION_BITS) + MAP_HALF - i64::from(p.to_bits());
        z.saturating_add(mul_shift(s.du, centre(x, self.x))).saturating_add(mul_shift(s.dv, centre(y, self.y)))
    }
}

/// An integer rectangle of texels, inclusive, possibly outside the map.
#[derive(Clone, Copy, Debug)]
pub(super) struct Texels {
    pub(super) x0: i32,
    pub(super) y0: i32,
    pub(super) x1: i32,
    pub(super) y1: i32,
}

/// Whole texels of a map coordinate (floor).
#[inline]
pub(super) fn floor(c: MapCoord) -> i32 {
    c.to_bits() >> MAP_FRACTION_BITS
}

impl Texels {
    /// The texels a filter reads around a lookup (for the jittered filter,
    /// its sample `grid`); `None` for a jittered filter without one.
    #[inline]
    pub(super) fn under(filter: Filter, l: &Lookup, grid: Option<([MapCoord; 2], [u32; 2])>) -> Option<Self> {
        Some(match (filter, grid) {
            (Filter::Point, _) => Self { x0: floor(l.x), y0: floor(l.y), x1: floor(l.x), y1: floor(l.y) },
            (Filter::Bilinear, _) => {
                let (x, y) = (floor(l.x.saturating_sub(HALF)), floor(l.y.saturating_sub(HALF)));
                Self { x0: x, y0: y, x1: x + 1, y1: y + 1 }
            }
            (Filter::Box { size }, _) => {
                // First texel: floor(x − (n − 1)/2), the n texel centres nearest x.
                let n = i32::from(size);
                let back = MapCoord::from_bits((n - 1) << 15);
                let (x, y) = (floor(l.x.saturating_sub(back)), floor(l.y.saturating_sub(back)));
                Self { x0: x, y0: y, x1: x + n - 1, y1: y + n - 1 }
            }
            (Filter::Jittered(_), Some((half, _))) => Self {
                x0: floor(l.x.saturating_sub(half[0])),
                y0: floor(l.y.saturating_sub(half[1])),
                x1: floor(l.x.saturating_add(half[0])),
                y1: floor(l.y.saturating_add(half[1])),
            },
            (Filter::Jittered(_), None) => return None,
        })
    }

    pub(super) fn count(&self) -> u32 {
        let side = |a: i32, b: i32| (i64::from(b) - i64::from(a) + 1).unsigned_abs();
        u32::try_from(side(self.x0, self.x1) * side(self.y0, self.y1)).unwrap_or(u32::MAX)
    }

    /// The part inside a `w × h` map, if any, and whether all of it is inside.
    #[inline]
    pub(super) fn clip(&self, w: u32, h: u32) -> (Option<TileRect>, bool) {
        let (w, h) = (i32::try_from(w).unwrap_or(i32::MAX), i32::try_from(h).unwrap_or(i32::MAX));
        let inside = self.x0 >= 0 && self.y0 >= 0 && self.x1 < w && self.y1 < h;
        let (x0, y0, x1, y1) = (self.x0.max(0), self.y0.max(0), self.x1.min(w - 1), self.y1.min(h - 1));
        if x0 > x1 || y0 > y1 {
            return (None, inside);
        }
        let r = TileRect {
            x0: x0.unsigned_abs(),
            y0: y0.unsigned_abs(),
            x1: x1.unsigned_abs() + 1,
            y1: y1.unsigned_abs() + 1,
        };
        (Some(r), inside)
    }
}

/// Reeves' sample grid for a footprint (Figure 4): the sampled region's
/// half-sizes in texels (footprint × `ResFactor`, at least `MinSize`) and
/// the number of samples along each axis.
#[must_use]
pub fn jitter_grid(j: &Jitter, footprint: [MapCoord; 2]) -> ([MapCoord; 2], [u32; 2]) {
    let half = footprint.map(|f| f.saturating_abs().saturating_mul(j.res_factor).max(j.min_size));
    let n = u32::from(j.num_samples);
    let (lo, hi) = (u32::from(j.min_samples), n);
    let round = |v: U16F16| v.saturating_add(U16F16::from_bits(1 << (MAP_FRACTION_BITS - 1))).to_num::<u32>();
    let unsigned = |v: MapCoord| U16F16::from_bits(v.to_bits().unsigned_abs());
    let (s, t) = (unsigned(half[0]), unsigned(half[1]));
    let area4 = s.saturating_mul(t).saturating_mul_int(4);
    let counts = if area4 < U16F16::saturating_from_num(n) {
        [round(s.saturating_mul_int(2)).clamp(lo, hi), round(t.saturating_mul_int(2)).clamp(lo, hi)]
    } else {
        // nt = sqrt(tres · N / sres) + ½, then ns = N / nt + ½ (both clamped).
        // A long, thin footprint saturates the ratio: `nt` is then clamped.
        let ratio = t.saturating_mul_int(n).saturating_div(s.max(U16F16::DELTA));
        let nt = ((u64::from(ratio.to_bits()) << MAP_FRACTION_BITS).isqrt() + (1 << (MAP_FRACTION_BITS - 1)))
            >> MAP_FRACTION_BITS;
        let nt = u32::try_from(nt).unwrap_or(hi).clamp(lo, hi);
        let ns = ((2 * n + nt) / (2 * nt)).clamp(lo, hi);
        [ns, nt]
    };
    (half, counts)
}
