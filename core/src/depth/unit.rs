//! The depth units, updated per fragment, and the per-tile summaries.
//!
//! * **Single**: `z1 ← min(z1, z)` — the nearest depth (Williams 1978; with
//!   front-face culling, the nearest light-averted surface: Wang & Molnar
//!   1994 §3.4).
//! * **Dual**: nearest and second nearest, both updated per fragment
//!   (Wang & Molnar 1994 §3.1: "two depth buffers … updated appropriately
//!   as each primitive is rasterized"):
//!   `z2 ← min(z2, max(z1, z))`, then `z1 ← min(z1, z)`. After any sequence
//!   of fragments, `(z1, z2)` are the two smallest depths that landed (as a
//!   multiset: two equal fragments give `z1 = z2`), whatever their order.
//!
//! * **Single with ids** (visibility, for the camera pass): `z1` as single,
//!   and the id of the triangle whose fragment passed.
//!
//! A depth test passes when the fragment is strictly nearer than what it
//! replaces; equal depths change nothing (so of equally near triangles the
//! first drawn stays visible).

use crate::depth::{DepthFormat, Texel};

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

/// The edge functions of a span: their values at the first pixel and their
/// steps per pixel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpanEdges {
    pub e: [i64; 3],
    pub de: [i64; 3],
}

/// Run one row of fragments through the depth unit.
///
/// `z` is the depth at the first pixel as [`PlaneZ`] bits plus
/// [`crate::depth::ROUND_HALF`], and `dz` its step; with `MASKED`, only
/// pixels whose three edge values are `≥ 0` are covered, otherwise all are
/// (and all lie inside the triangle). `DUAL` selects the unit, `COUNT_MAX`
/// whether the texels holding the culled buffer's max are counted. The loop only adds.
#[inline(always)]
#[allow(clippy::too_many_arguments, reason = "the hot path's state, passed flat")]
pub(crate) fn span<F: DepthFormat, const DUAL: bool, const IDS: bool, const MASKED: bool, const COUNT_MAX: bool>(
    z1: &mut [F::Texel],
    z2: &mut [F::Texel],
    ids: &mut [u32],
    id: u32,
    z: i64,
    dz: i64,
    edges: SpanEdges,
    cull_max: F::Texel,
) -> SpanOut<F::Texel> {
    let mut out = SpanOut::new(F::FAR);
    let mut fragments = 0u32;
    let mut z = z;
    let [mut e0, mut e1, mut e2] = edges.e;
    let [d0, d1, d2] = edges.de;
    let mut next = || {
        let inside = !MASKED || (e0 | e1 | e2) >= 0;
        let q = F::texel_inside(z);
        let q = if inside { q } else { F::FAR };
        z = z.wrapping_add(dz);
        if MASKED {
            e0 = e0.wrapping_add(d0);
            e1 = e1.wrapping_add(d1);
            e2 = e2.wrapping_add(d2);
            fragments += u32::from(inside);
        }
        q
    };
    if DUAL {
        for (a, b) in z1.iter_mut().zip(z2.iter_mut()) {
            let q = next();
            out.dual::<COUNT_MAX>(a, b, q, cull_max);
        }
    } else if IDS {
        for (a, t) in z1.iter_mut().zip(ids.iter_mut()) {
            let q = next();
            out.visible::<COUNT_MAX>(a, t, id, q, cull_max);
        }
    } else {
        for a in z1.iter_mut() {
            let q = next();
            out.single::<COUNT_MAX>(a, q, cull_max);
        }
    }
    #[allow(clippy::cast_possible_truncation, reason = "a span is at most one tile row")]
    let n = z1.len() as u32;
    out.fragments = if MASKED { fragments } else { n };
    out
}

/// The depth comparators: texels compared by their [`Texel::key`]. Whether
/// `a` lies strictly nearer than `b`.
#[inline(always)]
fn nearer<T: Texel>(a: T, b: T) -> bool {
    a.key() < b.key()
}

/// The nearer of two texels.
#[inline(always)]
fn nearest_of<T: Texel>(a: T, b: T) -> T {
    T::from_key(a.key().min(b.key()))
}

/// The farther of two texels.
#[inline(always)]
fn farthest_of<T: Texel>(a: T, b: T) -> T {
    T::from_key(a.key().max(b.key()))
}

impl<T: Texel> SpanOut<T> {
    pub(crate) const fn new(far: T) -> Self {
        Self { fragments: 0, written1: 0, written2: 0, lost_max: 0, min1: far, min2: far }
    }

    pub(crate) fn add(&mut self, o: &Self) {
        self.fragments += o.fragments;
        self.written1 += o.written1;
        self.written2 += o.written2;
        self.lost_max += o.lost_max;
        self.min1 = nearest_of(self.min1, o.min1);
        self.min2 = nearest_of(self.min2, o.min2);
    }

    /// The single unit at one texel: `z1 ← min(z1, q)`. `COUNT_MAX` tracks
    /// texels that held the tile's max `cull_max` and were lowered.
    #[inline(always)]
    pub(crate) fn single<const COUNT_MAX: bool>(&mut self, a: &mut T, q: T, cull_max: T) {
        let old = *a;
        *a = nearest_of(old, q);
        self.written1 += u32::from(nearer(q, old));
        if COUNT_MAX {
            self.lost_max += u32::from(old == cull_max && nearer(q, old));
        }
        self.min1 = nearest_of(self.min1, q);
    }

    /// The visibility unit at one texel: the nearest depth and the
    /// triangle that put it there.
    #[inline(always)]
    pub(crate) fn visible<const COUNT_MAX: bool>(&mut self, a: &mut T, t: &mut u32, id: u32, q: T, cull_max: T) {
        let old = *a;
        let pass = nearer(q, old);
        *a = if pass { q } else { old };
        *t = if pass { id } else { *t };
        self.written1 += u32::from(pass);
        if COUNT_MAX {
            self.lost_max += u32::from(old == cull_max && pass);
        }
        self.min1 = nearest_of(self.min1, q);
    }

    /// The dual unit at one texel: `z2 ← min(z2, max(z1, q))`, then
    /// `z1 ← min(z1, q)`.
    #[inline(always)]
    pub(crate) fn dual<const COUNT_MAX: bool>(&mut self, a: &mut T, b: &mut T, q: T, cull_max: T) {
        let (old1, old2) = (*a, *b);
        let new2 = nearest_of(old2, farthest_of(old1, q));
        *a = nearest_of(old1, q);
        *b = new2;
        self.written1 += u32::from(nearer(q, old1));
        self.written2 += u32::from(nearer(new2, old2));
        if COUNT_MAX {
            self.lost_max += u32::from(old2 == cull_max && nearer(new2, old2));
        }
        self.min1 = nearest_of(self.min1, q);
        self.min2 = nearest_of(self.min2, new2);
    }
}
