//! The depth units, updated per fragment, and the per-tile summaries.
//!
//! * **Single**: `z1 ← min(z1, z)` — the nearest depth (Williams 1978; with
//!   front-face culling, the nearest light-averted surface: Wang & Molnar
//!   1994 §3.1).
//! * **Dual**: nearest and second nearest, both updated per fragment
//!   (Wang & Molnar 1994 §3.1, "two z-buffers"):
//!   `z2 ← min(z2, max(z1, z))`, then `z1 ← min(z1, z)`. After any sequence
//!   of fragments, `(z1, z2)` are the two smallest depths that landed (as a
//!   multiset: two equal fragments give `z1 = z2`), whatever their order.
//!
//! A depth test passes when the fragment is strictly nearer than what it
//! replaces; equal depths change nothing.
//!
//! # Per-tile summaries
//! Each tile keeps the min of `z1` and `z2` as fragments land, and the exact
//! **max of the buffer that culling tests** (`z1` for single, `z2` for
//! dual) together with how many texels hold it: when a fragment lowers a
//! texel that held the max, the count drops, and when it reaches zero the
//! max is recomputed by a reduction over the tile — so the max is exact
//! after every triangle, at a cost of one reduction per "layer" of depth.
//! When the tile is stored, all four bounds are resolved exactly.

use crate::depth::{DepthFormat, PlaneZ};

/// What the map keeps about one tile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileState<T> {
    /// Smallest `z1` in the tile.
    pub z1_min: T,
    /// Largest `z1` in the tile (exact once the tile is stored).
    pub z1_max: T,
    /// Smallest `z2` in the tile (dual only; the clear value otherwise).
    pub z2_min: T,
    /// Largest `z2` in the tile (dual only; the clear value otherwise).
    pub z2_max: T,
    /// Times the tile was written back to the map.
    pub stores: u32,
    /// Live max of the culled buffer.
    pub(crate) cull_max: T,
    /// Texels of the culled buffer that hold `cull_max`.
    pub(crate) cull_count: u32,
}

impl<T: Copy> TileState<T> {
    /// A cleared tile of `texels` texels, every value `far`.
    #[must_use]
    pub const fn cleared(far: T, texels: u32) -> Self {
        Self { z1_min: far, z1_max: far, z2_min: far, z2_max: far, stores: 0, cull_max: far, cull_count: texels }
    }

    /// The same summary with every depth converted by `f` (which must be
    /// monotonic, e.g. widening to raw bits).
    #[must_use]
    pub fn map<U>(self, f: impl Fn(T) -> U) -> TileState<U> {
        TileState {
            z1_min: f(self.z1_min),
            z1_max: f(self.z1_max),
            z2_min: f(self.z2_min),
            z2_max: f(self.z2_max),
            stores: self.stores,
            cull_max: f(self.cull_max),
            cull_count: self.cull_count,
        }
    }

    /// The max stored depth that culling compares against.
    #[must_use]
    pub const fn cull_max(&self) -> T {
        self.cull_max
    }
}

/// What one span of fragments did.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpanOut<T> {
    /// Fragments generated (covered pixel centres).
    pub fragments: u32,
    /// `z1` texels changed.
    pub written1: u32,
    /// `z2` texels changed.
    pub written2: u32,
    /// Culled-buffer texels that held the tile max and were lowered.
    pub lost_max: u32,
    /// Smallest `z1` written.
    pub min1: T,
    /// Smallest `z2` written.
    pub min2: T,
}

impl<T: Copy + Ord> SpanOut<T> {
    pub(crate) const fn new(far: T) -> Self {
        Self { fragments: 0, written1: 0, written2: 0, lost_max: 0, min1: far, min2: far }
    }

    pub(crate) fn add(&mut self, o: &Self) {
        self.fragments += o.fragments;
        self.written1 += o.written1;
        self.written2 += o.written2;
        self.lost_max += o.lost_max;
        self.min1 = self.min1.min(o.min1);
        self.min2 = self.min2.min(o.min2);
    }
}

/// The edge functions of a span: their values at the first pixel and their
/// steps per pixel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpanEdges {
    pub e: [i64; 3],
    pub de: [i64; 3],
}

/// Run one row of fragments through the depth unit.
///
/// `z` is the depth at the first pixel and `dz` its step; with `MASKED`,
/// only pixels whose three edge values are `≥ 0` are covered, otherwise all
/// are. `DUAL` selects the unit, `CULL` whether the culled buffer's max is
/// tracked. The loop only adds.
#[inline(always)]
pub(crate) fn span<F: DepthFormat, const DUAL: bool, const MASKED: bool, const CULL: bool>(
    z1: &mut [F::Texel],
    z2: &mut [F::Texel],
    z: PlaneZ,
    dz: PlaneZ,
    edges: SpanEdges,
    cull_max: F::Texel,
) -> SpanOut<F::Texel> {
    let mut out = SpanOut::new(F::FAR);
    let mut z = z.to_bits();
    let dz = dz.to_bits();
    let [mut e0, mut e1, mut e2] = edges.e;
    let [d0, d1, d2] = edges.de;
    let mut covered = || {
        let inside = !MASKED || (e0 | e1 | e2) >= 0;
        let q = F::texel(PlaneZ::from_bits(z));
        z = z.wrapping_add(dz);
        if MASKED {
            e0 += d0;
            e1 += d1;
            e2 += d2;
        }
        (inside, q)
    };
    if DUAL {
        for (a, b) in z1.iter_mut().zip(z2.iter_mut()) {
            let (inside, q) = covered();
            let (old1, old2) = (*a, *b);
            let q = if inside { q } else { F::FAR };
            let new1 = old1.min(q);
            let new2 = old2.min(old1.max(q));
            *a = new1;
            *b = new2;
            out.fragments += u32::from(inside);
            out.written1 += u32::from(new1 != old1);
            out.written2 += u32::from(new2 != old2);
            if CULL {
                out.lost_max += u32::from(old2 == cull_max && new2 != old2);
            }
            out.min1 = out.min1.min(new1);
            out.min2 = out.min2.min(new2);
        }
    } else {
        for a in z1.iter_mut() {
            let (inside, q) = covered();
            let old = *a;
            let q = if inside { q } else { F::FAR };
            let new = old.min(q);
            *a = new;
            out.fragments += u32::from(inside);
            out.written1 += u32::from(new != old);
            if CULL {
                out.lost_max += u32::from(old == cull_max && new != old);
            }
            out.min1 = out.min1.min(new);
        }
    }
    out
}

/// The rows of a tile's rectangle `r` in a row-major buffer of `width` columns.
pub(crate) fn tile_rows<T>(buf: &[T], r: crate::tile::TileRect, width: usize) -> impl Iterator<Item = &[T]> {
    (r.y0..r.y1).filter_map(move |y| {
        let base = y as usize * width;
        buf.get(base + r.x0 as usize..base + r.x1 as usize)
    })
}

/// The max of a set of rows of texels and how many texels hold it.
pub(crate) fn max_and_count<'r, T: Copy + Ord + Default + 'r>(rows: impl Iterator<Item = &'r [T]>) -> (T, u32) {
    let (mut max, mut count) = (T::default(), 0u32);
    for row in rows {
        for &t in row {
            if t > max {
                (max, count) = (t, 0);
            }
            count += u32::from(t == max);
        }
    }
    (max, count)
}

/// The min and max of a set of rows of texels (`far` and `0` when empty).
pub(crate) fn min_max<'r, T: Copy + Ord + Default + 'r>(rows: impl Iterator<Item = &'r [T]>, far: T) -> (T, T) {
    let (mut lo, mut hi) = (far, T::default());
    for row in rows {
        for &t in row {
            lo = lo.min(t);
            hi = hi.max(t);
        }
    }
    (lo, hi)
}
