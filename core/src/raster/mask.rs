//! The coverage-mask unit: a small rectangle of one triangle, a row at a
//! time, as a mask with one bit a pixel (bit `k` for column `x0 + k`), set
//! where the pixel centre passes all three edge functions (`e ≥ 0`, the
//! fill-rule bias already in `e`).
//!
//! An edge that does not cross the rectangle passes or fails all of its
//! pixels alike, and one that crosses it takes small values there. So the
//! unit first tests each edge at the rectangle's corners: an edge that fails
//! every pixel empties it, one that passes every pixel drops out, and one
//! that crosses it is evaluated in lanes of 32 bits — [`LANE_GROUP`] pixels
//! of a row at once, the width of a SIMD unit — stepped from row to row by
//! adds. The bits are those of the 64-bit edge functions. An edge whose
//! values over the rectangle do not fit in 32 bits (a huge triangle at a
//! steep angle) sends the rectangle to the serial unit: 64 bits, one pixel
//! at a time. Targets without a SIMD unit use the serial unit throughout
//! ([`LANES`]).

use wide::i32x8;

use crate::front::setup::{Edge, Setup};
use crate::grid::TileRect;

/// Whether the rasterizer draws masks in lanes: on targets with a SIMD
/// unit (x86-64's SSE2, AArch64's NEON, WebAssembly's SIMD128). Elsewhere
/// — a Cortex-M4, say — lanes would be emulated one at a time, for no gain
/// over the serial unit, which gives the same bits in 37 KB less code there.
pub const LANES: bool = cfg!(any(target_feature = "sse2", target_feature = "neon", target_feature = "simd128"));

/// Pixels of a row one group of lanes evaluates at once.
pub const LANE_GROUP: u32 = 8;

/// The widest rectangle the unit takes: eight groups of lanes, a 64-bit mask.
pub const WIDEST: u32 = 8 * LANE_GROUP;

/// Lanes whose index has bit 0, bit 1, bit 2 set (all ones there).
const ODD: i32x8 = i32x8::new([0, -1, 0, -1, 0, -1, 0, -1]);
const PAIRS: i32x8 = i32x8::new([0, 0, -1, -1, 0, 0, -1, -1]);
const QUADS: i32x8 = i32x8::new([0, 0, 0, 0, -1, -1, -1, -1]);
const _: () = assert!(LANE_GROUP == 8, "the lane masks are for groups of eight");

/// A row's coverage, a bit a pixel.
pub(crate) trait RowMask {
    /// The widest row the unit draws.
    const WIDTH: u32;

    /// The current row's mask; then step to the next row.
    fn next_row(&mut self) -> u64;
}

/// The crossing edges in `G` groups of 32-bit lanes (an edge that passes
/// every pixel as zeros, which pass).
pub(crate) struct Lanes<const G: usize> {
    /// Each edge's values at the current row's pixels.
    values: [[i32x8; G]; 3],
    /// Each edge's step to the next row, in every lane.
    down: [i32x8; 3],
    /// The bits of the rectangle's columns (none when an edge fails every
    /// pixel).
    columns: u64,
}

impl<const G: usize> Lanes<G> {
    /// The lanes of `rect` (at most `G` groups wide) for the triangle `s`;
    /// `None` when some crossing edge does not fit in them.
    #[inline(always)]
    pub(crate) fn new(s: &Setup, rect: &TileRect) -> Option<Self> {
        let (x0, y0) = (i64::from(rect.x0), i64::from(rect.y0));
        let columns = u64::MAX >> (u64::BITS - rect.width().clamp(1, WIDEST));
        let mut lanes = Self { values: [[i32x8::ZERO; G]; 3], down: [i32x8::ZERO; 3], columns };
        for ((e, values), down) in s.edges.iter().zip(&mut lanes.values).zip(&mut lanes.down) {
            // The corner tests, from the value at the first pixel.
            let first = e.at(x0, y0);
            let (lo, hi) = e.range_from(first, rect);
            if hi < 0 {
                lanes.columns = 0;
                return Some(lanes);
            }
            if lo >= 0 {
                continue;
            }
            // Crossing. Every value over the rectangle lies in [lo, hi]; once
            // both fit in 32 bits, so does each value, and 32-bit wrapping
            // arithmetic on the truncated steps gives it exactly. The lanes
            // past the rectangle's width may wrap: they are masked off.
            let (Ok(_), Ok(_)) = (i32::try_from(lo), i32::try_from(hi)) else {
                return None;
            };
            #[allow(clippy::cast_possible_truncation, reason = "exact modulo 2^32, see above")]
            let [first, dx, dy] = [first, e.dx, e.dy].map(|v| v as i32);
            // `first + k·dx` in lane k, from the bits of k: adds and masks.
            let mut group = i32x8::splat(first)
                + (ODD & i32x8::splat(dx))
                + (PAIRS & i32x8::splat(dx.wrapping_mul(2)))
                + (QUADS & i32x8::splat(dx.wrapping_mul(4)));
            let across = i32x8::splat(dx.wrapping_mul(LANE_GROUP.cast_signed()));
            for lanes in values.iter_mut() {
                *lanes = group;
                group += across;
            }
            *down = i32x8::splat(dy);
        }
        Some(lanes)
    }
}

impl<const G: usize> RowMask for Lanes<G> {
    #[allow(clippy::cast_possible_truncation, reason = "at most eight groups")]
    const WIDTH: u32 = G as u32 * LANE_GROUP;

    #[inline(always)]
    fn next_row(&mut self) -> u64 {
        let mut outside = 0u64;
        for (g, shift) in (0..G).zip((0..).step_by(LANE_GROUP as usize)) {
            let [a, b, c] = [self.values[0][g], self.values[1][g], self.values[2][g]];
            // The sign bits: some edge below zero.
            outside |= u64::from((a | b | c).to_bitmask()) << shift;
        }
        for (values, &down) in self.values.iter_mut().zip(&self.down) {
            for group in values {
                *group += down;
            }
        }
        !outside & self.columns
    }
}

/// Every edge in 64 bits, pixel by pixel.
pub(crate) struct Serial {
    /// Each edge's value at the current row's last pixel.
    last: [i64; 3],
    /// The edges' steps.
    edges: [Edge; 3],
    /// The rectangle's width.
    width: u32,
}

impl Serial {
    /// The serial unit on `rect` for the triangle `s`.
    pub(crate) fn new(s: &Setup, rect: &TileRect) -> Self {
        let last = i64::from(rect.x0) + i64::from(rect.width()) - 1;
        let last = s.edges.map(|e| e.at(last, i64::from(rect.y0)));
        Self { last, edges: s.edges, width: rect.width() }
    }
}

impl RowMask for Serial {
    const WIDTH: u32 = WIDEST;

    #[inline(always)]
    fn next_row(&mut self) -> u64 {
        // Stepped leftwards from the last pixel: each bit is shifted in
        // from the right.
        let [mut e0, mut e1, mut e2] = self.last;
        let mut mask = 0u64;
        for _ in 0..self.width {
            mask = mask << 1 | u64::from((e0 | e1 | e2) >= 0);
            e0 = e0.wrapping_sub(self.edges[0].dx);
            e1 = e1.wrapping_sub(self.edges[1].dx);
            e2 = e2.wrapping_sub(self.edges[2].dx);
        }
        for (e, edge) in self.last.iter_mut().zip(&self.edges) {
            *e = e.wrapping_add(edge.dy);
        }
        mask
    }
}

#[cfg(test)]
mod tests {
    use super::{Lanes, RowMask, Serial, WIDEST};
    use crate::config::{CullMode, RasterConfig};
    use crate::depth::PlaneZ;
    use crate::front::setup::Setup;
    use crate::front::snap::{SnappedVertex, SubPx};
    use crate::grid::TileRect;

    /// A rectangle's row masks (at most 16 rows here).
    type Rows = heapless::Vec<u64, 16>;

    /// The rows of `rect` as masks worked directly from the edge functions
    /// at each pixel centre.
    fn direct(s: &Setup, rect: &TileRect) -> impl Iterator<Item = u64> {
        (rect.y0..rect.y1).map(move |y| {
            (rect.x0..rect.x1).rev().fold(0u64, |mask, x| {
                let inside = s.edges.iter().all(|e| e.at(i64::from(x), i64::from(y)) >= 0);
                mask << 1 | u64::from(inside)
            })
        })
    }

    /// On random rectangles of random triangles — small, large, and huge
    /// ones whose edges overflow 32 bits — the lanes (where they take the
    /// rectangle) and the serial unit give every row's mask as the edge
    /// functions do pixel by pixel.
    #[test]
    fn lanes_and_the_serial_unit_agree_on_random_rectangles() {
        let cfg = RasterConfig::new(1024, 1024, 32, 8).expect("valid");
        let mut rng = oorandom::Rand64::new(0x5eed_c0de);
        let (mut compared, mut in_lanes) = (0u32, 0u32);
        for case in 0..20_000u32 {
            // Subpixel coordinates: within the target, or far out in the
            // guard band (2^24 subpixels) every fourth case; every other
            // case at pixel centres 48 pixels apart at most, so that edges
            // run through pixel centres and the fill rule decides them.
            let reach: u64 = if case % 4 == 0 { 1 << 24 } else { 1024 << 8 };
            let coord = |rng: &mut oorandom::Rand64| {
                #[allow(clippy::cast_possible_wrap, reason = "below 2^25")]
                let c = if case % 2 == 1 {
                    (500 + rng.rand_range(0..48) as i64) * 256 + 128
                } else {
                    rng.rand_range(0..2 * reach) as i64 - (reach as i64 - (512 << 8))
                };
                SubPx(c)
            };
            let v = [(); 3].map(|()| SnappedVertex { x: coord(&mut rng), y: coord(&mut rng), z: PlaneZ::ZERO });
            let Ok(s) = Setup::new(&cfg, v, CullMode::None, 0) else { continue };
            // A rectangle inside the bounding box, up to WIDEST wide.
            let pick = |rng: &mut oorandom::Rand64, lo: u32, hi: u32| {
                #[allow(clippy::cast_possible_truncation, reason = "below the target's side")]
                let v = rng.rand_range(u64::from(lo)..u64::from(hi)) as u32;
                v
            };
            let (x0, y0) = (pick(&mut rng, s.bbox.x0, s.bbox.x1), pick(&mut rng, s.bbox.y0, s.bbox.y1));
            let w = pick(&mut rng, 1, WIDEST + 1).min(s.bbox.x1 - x0);
            let h = pick(&mut rng, 1, 17).min(s.bbox.y1 - y0);
            let rect = TileRect { x0, y0, x1: x0 + w, y1: y0 + h };
            let want: Rows = direct(&s, &rect).collect();
            let mut serial = Serial::new(&s, &rect);
            let got: Rows = (0..h).map(|_| serial.next_row()).collect();
            assert_eq!(got, want, "serial unit, case {case}: {rect:?}");
            if let Some(mut lanes) = Lanes::<8>::new(&s, &rect) {
                let got: Rows = (0..h).map(|_| lanes.next_row()).collect();
                assert_eq!(got, want, "lanes, case {case}: {rect:?}");
                in_lanes += 1;
            }
            compared += 1;
        }
        // Both paths were exercised: most rectangles fit the lanes, and the
        // huge triangles send some to the serial unit alone.
        assert!(compared > 15_000 && in_lanes > 10_000 && in_lanes < compared, "{compared} {in_lanes}");
    }
}
