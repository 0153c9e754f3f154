//! Triangle setup: integer edge functions with the top-left fill rule, and
//! the depth plane `z = A·x + B·y + C` in fixed point.
//!
//! Setup computes; the rasterizer only adds.
//!
//! # Edge functions
//! For an edge from `a` to `b` (snapped, y down),
//! `E(X, Y) = (Xb − Xa)(Y − Ya) − (Yb − Ya)(X − Xa)`; vertices are ordered so
//! the interior has `E > 0` on all three edges. Pixel centres lie on the
//! subpixel grid (`X = px·2^s + 2^(s−1)`), so `E` is an exact integer there.
//! An [`Edge`] holds `E` at pixel `(0, 0)` and its steps per pixel.
//!
//! **Budget.** Snapped coordinates satisfy `|X|, |Y| ≤ 2^25` (the guard
//! band's `2^24` of [`crate::budget::COORD_BITS`], plus a window's shift:
//! [`crate::budget::WINDOW_COORD_BITS`]), so `|Xb − Xa| ≤ 2^26` and every value
//! of `E` at a pixel centre of the target is below `2·2^26·2^26 = 2^53`: an
//! `i64` accumulator cannot overflow (checked at compile time below).
//!
//! **Fill rule.** The D3D top-left rule in this y-down orientation: a pixel
//! centre exactly on an edge belongs to the triangle iff the edge is a *top*
//! edge (horizontal, interior below) or a *left* edge (interior to its
//! right). It is applied once, as a bias of −1 on the other edges, so the
//! rasterizer's test is always `E ≥ 0`.
//!
//! # Depth plane
//! Vertex depths are [`PlaneZ`] (format LSBs with 32 fraction bits). The
//! plane's per-pixel steps `A`, `B` and its value `C` at pixel `(0, 0)` are
//! solved exactly in `i128` and rounded once, so the depth at pixel
//! `(px, py)` is `C + A·px + B·py` whatever path the rasterizer took to get
//! there. The rasterizer steps it in `i64` with wrapping adds: the sum is
//! exact modulo 2⁶⁴, and at every pixel centre inside the triangle the true
//! value lies in `[0, 2^56]`, so wrapping never shows. The rounding of the
//! steps costs at most `½` unit of 2⁻³² LSB per pixel of distance from
//! vertex 0 (at most `2·2^16` pixels inside the guard band), plus `½` for
//! `C` and 2⁵ for an f64 setup: below 2⁻¹⁵ LSB. So a fragment inside the triangle lies within
//! 2⁻¹⁵ LSB of `[0, SCALE]`, and rounding it to a
//! texel is an add of half an LSB and a shift: no clamp
//! ([`crate::depth::DepthFormat::texel_inside`]).

use crate::budget::{SLOPE_F64_LIMIT, WINDOW_COORD_BITS};
use crate::config::{CullMode, RasterConfig};
use crate::depth::PlaneZ;
use crate::front::snap::SnappedVertex;
use crate::grid::TileRect;
use crate::probe::RejectReason;
use crate::round::i128_to_f64;

pub use super::plane::DepthPlane;

/// One edge function, evaluated at pixel centres: `E(px, py) = c + dx·px + dy·py`.
/// A pixel centre is inside the edge iff `E ≥ 0` (fill-rule bias included).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// Step per pixel to the right.
    pub dx: i64,
    /// Step per pixel down.
    pub dy: i64,
    /// Value at the centre of pixel `(0, 0)`, fill-rule bias included.
    pub c: i64,
}

impl Edge {
    /// The value at the centre of pixel `(px, py)`.
    #[inline(always)]
    #[must_use]
    pub const fn at(&self, px: i64, py: i64) -> i64 {
        // Never overflows for edges from [`Setup::new`] (see the budget);
        // wrapping keeps hand-made edges from panicking.
        self.c.wrapping_add(self.dx.wrapping_mul(px)).wrapping_add(self.dy.wrapping_mul(py))
    }

    /// The smallest and largest value over the pixel centres of `r`.
    #[inline]
    #[must_use]
    pub fn range_over(&self, r: &TileRect) -> (i64, i64) {
        self.range_from(self.at(i64::from(r.x0), i64::from(r.y0)), r)
    }

    /// [`Edge::range_over`] from `first`, the value at `r`'s first pixel:
    /// the extremes lie that value plus the steps across and down the
    /// rectangle, where they are negative (lowest) or positive (highest).
    #[inline(always)]
    #[must_use]
    pub fn range_from(&self, first: i64, r: &TileRect) -> (i64, i64) {
        let across = self.dx.wrapping_mul(i64::from(r.x1.saturating_sub(1)) - i64::from(r.x0));
        let down = self.dy.wrapping_mul(i64::from(r.y1.saturating_sub(1)) - i64::from(r.y0));
        let lo = first.wrapping_add(across.min(0)).wrapping_add(down.min(0));
        (lo, first.wrapping_add(across.max(0)).wrapping_add(down.max(0)))
    }
}

/// A triangle ready for rasterization.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Setup {
    /// The three edge functions.
    pub edges: [Edge; 3],
    /// The depth plane.
    pub plane: DepthPlane,
    /// Pixels whose centres may be covered, clipped to the target.
    pub bbox: TileRect,
    /// The nearest vertex depth: a lower bound on every fragment.
    pub z_min: PlaneZ,
    /// The farthest vertex depth: an upper bound on every fragment.
    pub z_max: PlaneZ,
    /// Index of the submitted triangle.
    pub triangle: u32,
}

/// The per-pixel steps `round(num · 2^s / d)` of both axes, `d > 0`.
///
/// In f64 when that is accurate enough: the quotient `q` carries a relative
/// error below 2⁻⁵¹, so if `(|q_a| + |q_b|)·extent < 2⁵⁶` the steps' error
/// moves no fragment of the triangle by more than 2⁵ units (2⁻²⁷ LSB) beyond
/// the rounding the exact path has too. Otherwise — slivers, whose depth
/// changes by more than 2²⁴ LSB across their extent — exactly in i128.
#[inline]
fn slopes(a_num: i128, b_num: i128, s: u32, d: i64, extent: f64) -> (i128, i128) {
    #[allow(clippy::cast_precision_loss, reason = "the error bound above accounts for it")]
    let (na, nb, df) = (i128_to_f64(a_num), i128_to_f64(b_num), d as f64);
    let scale = f64::from(1u32 << s);
    let (qa, qb) = (na * scale / df, nb * scale / df);
    if (qa.abs() + qb.abs()) * extent < SLOPE_F64_LIMIT {
        let r = |q: f64| i128::from(crate::round::round_ties_even(q));
        return (r(qa), r(qb));
    }
    let d = i128::from(d);
    (round_div(a_num << s, d), round_div(b_num << s, d))
}

/// The exact product `a·b`: one 64 × 64 → 128-bit multiply when `a` fits
/// 64 bits (every depth difference and step of the front end's vertices),
/// the full `i128` product otherwise (hand-made depths).
#[inline(always)]
fn mul(a: i128, b: i64) -> i128 {
    match i64::try_from(a) {
        Ok(a) => i128::from(a) * i128::from(b),
        Err(_) => a * i128::from(b),
    }
}

/// `round(n / d)` (half up) for `d > 0`.
#[inline]
fn round_div(n: i128, d: i128) -> i128 {
    (2 * n + d).div_euclid(2 * d)
}

/// The most pixel centres in a bounding box that [`Setup::covering`]
/// tests before it solves the depth plane.
const SMALL_BOX: u32 = 16;

/// `floor(v / 2^s)` and `ceil(v / 2^s)`.
#[inline]
const fn floor_shift(v: i64, s: u32) -> i64 {
    v >> s
}

#[inline]
const fn ceil_shift(v: i64, s: u32) -> i64 {
    -((-v) >> s)
}

impl Setup {
    /// A placeholder that covers nothing, to fill a setup store.
    pub const EMPTY: Self = Self {
        edges: [Edge { dx: 0, dy: 0, c: -1 }; 3],
        plane: DepthPlane { a: 0, b: 0, c: 0 },
        bbox: TileRect { x0: 0, y0: 0, x1: 0, y1: 0 },
        z_min: PlaneZ::ZERO,
        z_max: PlaneZ::ZERO,
        triangle: 0,
    };

    /// Set up a snapped triangle, or say why it produces nothing.
    ///
    /// # Errors
    /// [`RejectReason::OutOfRange`] for a coordinate outside the setup's
    /// `±2^25` budget (only a hand-made vertex can be);
    /// [`RejectReason::Degenerate`] for zero area on the subpixel grid,
    /// [`RejectReason::Facing`] when `cull` discards it,
    /// [`RejectReason::NoCoverage`] when no pixel centre of the target lies
    /// in its bounding box.
    pub fn new(cfg: &RasterConfig, v: [SnappedVertex; 3], cull: CullMode, triangle: u32) -> Result<Self, RejectReason> {
        Self::build(cfg, v, cull, triangle, false)
    }

    /// [`Setup::new`] as the rasterizer's front end sets up: a triangle
    /// whose bounding box holds at most 16 pixel centres has them tested
    /// before its depth plane is solved, and is rejected as
    /// [`RejectReason::NoCoverage`] when it covers none (most of a fine
    /// mesh's triangles, seen from afar). It draws what [`Setup::new`]'s
    /// setup draws; only the plane of a triangle that draws nothing is
    /// not solved.
    ///
    /// # Errors
    /// Those of [`Setup::new`].
    #[inline]
    pub fn covering(
        cfg: &RasterConfig,
        v: [SnappedVertex; 3],
        cull: CullMode,
        triangle: u32,
    ) -> Result<Self, RejectReason> {
        Self::build(cfg, v, cull, triangle, true)
    }

    #[inline(never)]
    fn build(
        cfg: &RasterConfig,
        v: [SnappedVertex; 3],
        cull: CullMode,
        triangle: u32,
        test_small: bool,
    ) -> Result<Self, RejectReason> {
        let limit = 1i64 << WINDOW_COORD_BITS;
        if v.iter().any(|p| !(-limit..=limit).contains(&p.x.0) || !(-limit..=limit).contains(&p.y.0)) {
            return Err(RejectReason::OutOfRange);
        }
        let [v0, mut v1, mut v2] = v;
        let area2 = |a: &SnappedVertex, b: &SnappedVertex, c: &SnappedVertex| {
            (b.x.0 - a.x.0) * (c.y.0 - a.y.0) - (b.y.0 - a.y.0) * (c.x.0 - a.x.0)
        };
        let mut d = area2(&v0, &v1, &v2);
        if d == 0 {
            return Err(RejectReason::Degenerate);
        }
        // d < 0: counter-clockwise in NDC (y up), i.e. facing the light.
        let facing_light = d < 0;
        match (cull, facing_light) {
            (CullMode::Back, false) | (CullMode::Front, true) => return Err(RejectReason::Facing),
            _ => {}
        }
        if d < 0 {
            core::mem::swap(&mut v1, &mut v2);
            d = -d;
        }

        let s = cfg.subpixel_bits();
        let half = 1i64 << (s - 1);
        let unit = 1i64 << s;
        let x_min = v0.x.0.min(v1.x.0).min(v2.x.0);
        let x_max = v0.x.0.max(v1.x.0).max(v2.x.0);
        let y_min = v0.y.0.min(v1.y.0).min(v2.y.0);
        let y_max = v0.y.0.max(v1.y.0).max(v2.y.0);
        let px0 = ceil_shift(x_min - half, s).max(0);
        let py0 = ceil_shift(y_min - half, s).max(0);
        let px1 = floor_shift(x_max - half, s).min(i64::from(cfg.width()) - 1);
        let py1 = floor_shift(y_max - half, s).min(i64::from(cfg.height()) - 1);
        if px0 > px1 || py0 > py1 {
            return Err(RejectReason::NoCoverage);
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to the target")]
        let bbox = TileRect { x0: px0 as u32, y0: py0 as u32, x1: px1 as u32 + 1, y1: py1 as u32 + 1 };

        let edge = |a: &SnappedVertex, b: &SnappedVertex| {
            let (ex, ey) = (b.x.0 - a.x.0, b.y.0 - a.y.0);
            let top_left = ey < 0 || (ey == 0 && ex > 0);
            let bias = if top_left { 0 } else { -1 };
            Edge { dx: -ey * unit, dy: ex * unit, c: ex * (half - a.y.0) - ey * (half - a.x.0) + bias }
        };
        let edges = [edge(&v0, &v1), edge(&v1, &v2), edge(&v2, &v0)];
        // A small triangle's few pixel centres are tested before its depth
        // plane is solved.
        if test_small && bbox.area() <= SMALL_BOX {
            let covers = (bbox.y0..bbox.y1)
                .any(|y| (bbox.x0..bbox.x1).any(|x| edges.iter().all(|e| e.at(i64::from(x), i64::from(y)) >= 0)));
            if !covers {
                return Err(RejectReason::NoCoverage);
            }
        }

        let z0 = i128::from(v0.z.to_bits());
        // Within the budget, so the differences of x and y are i64.
        let (dx1, dy1) = (v1.x.0 - v0.x.0, v1.y.0 - v0.y.0);
        let (dx2, dy2) = (v2.x.0 - v0.x.0, v2.y.0 - v0.y.0);
        let (dz1, dz2) = (i128::from(v1.z.to_bits()) - z0, i128::from(v2.z.to_bits()) - z0);
        let a_num = mul(dz1, dy2) - mul(dz2, dy1);
        let b_num = mul(dz2, dx1) - mul(dz1, dx2);
        // Pixel distance, bounding |p − v0| for every pixel p of the triangle.
        #[allow(clippy::cast_precision_loss, reason = "an estimate; below 2^26")]
        let extent = ((x_max - x_min + y_max - y_min) >> s) as f64 + 2.0;
        let (a, b) = slopes(a_num, b_num, s, d, extent);
        // The value at pixel (0, 0) from vertex 0 and the rounded per-pixel
        // steps: a multiply and a shift, no third division.
        let offset = mul(a, half - v0.x.0) + mul(b, half - v0.y.0);
        let plane = DepthPlane { a, b, c: z0 + ((offset + (1 << (s - 1))) >> s) };
        let z_min = v0.z.min(v1.z).min(v2.z);
        let z_max = v0.z.max(v1.z).max(v2.z);
        Ok(Self { edges, plane, bbox, z_min, z_max, triangle })
    }

    /// This setup, made for a target, as setup would make it for `window`,
    /// a window of that target ([`RasterConfig::window`]) whose origin lies
    /// `by` pixels past the target's; `None` when no pixel of the bounding
    /// box is in the window. Moving by whole pixels is exact: the edge
    /// functions and the plane are re-based at the window's first pixel in
    /// integers, so the window rasterizes exactly the fragments it would
    /// from its own snapped vertices (the light pass's bands set up once).
    #[must_use]
    pub fn in_window(&self, by: [u32; 2], window: &RasterConfig) -> Option<Self> {
        let seen = self.bbox.intersect(&window.target_rect().moved(by))?;
        let mut moved = *self;
        moved.move_by(by, seen);
        Some(moved)
    }

    /// Re-base this setup `by` pixels (the core of [`Setup::in_window`]):
    /// the edge functions and the plane at the window's first pixel, and
    /// the bounding box `seen` (in the old frame, inside the window) in the
    /// window's frame.
    #[inline]
    pub(crate) fn move_by(&mut self, by: [u32; 2], seen: TileRect) {
        let [dx, dy] = by;
        let (x, y) = (i64::from(dx), i64::from(dy));
        for e in &mut self.edges {
            e.c = e.at(x, y);
        }
        let p = &mut self.plane;
        p.c = p.c.wrapping_add(p.a.wrapping_mul(x.into())).wrapping_add(p.b.wrapping_mul(y.into()));
        self.bbox = TileRect { x0: seen.x0 - dx, y0: seen.y0 - dy, x1: seen.x1 - dx, y1: seen.y1 - dy };
    }

    /// Whether the centre of pixel `(px, py)` is covered.
    #[inline]
    #[must_use]
    pub fn covers(&self, px: i64, py: i64) -> bool {
        self.edges.iter().all(|e| e.at(px, py) >= 0)
    }

    /// How the triangle meets the pixel centres of `r`.
    #[inline]
    #[must_use]
    pub fn classify(&self, r: &TileRect) -> Coverage {
        let mut full = true;
        for e in &self.edges {
            let (lo, hi) = e.range_over(r);
            if hi < 0 {
                return Coverage::Empty;
            }
            full &= lo >= 0;
        }
        if full { Coverage::Full } else { Coverage::Partial }
    }
}

/// How a triangle meets a rectangle of pixel centres, from corner tests of
/// its edge functions (Mesa llvmpipe's trivial reject / accept).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coverage {
    /// Some edge excludes every centre.
    Empty,
    /// Every edge includes every centre.
    Full,
    /// Neither: test per pixel.
    Partial,
}

#[cfg(test)]
mod tests {
    use super::Setup;
    use crate::config::{CullMode, RasterConfig};
    use crate::depth::PlaneZ;
    use crate::front::snap::{SnappedVertex, SubPx};

    /// `round(n / d)`, half up, for `d ≠ 0`, worked from the definition.
    fn nearest(n: i128, d: i128) -> i128 {
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        (2 * n + d).div_euclid(2 * d)
    }

    /// The depth plane's steps against the exact slopes worked by hand,
    /// `(Δz₁Δy₂ − Δz₂Δy₁)·2ˢ / area` across and `(Δx₁Δz₂ − Δx₂Δz₁)·2ˢ / area`
    /// down, rounded to the nearest: within one unit, plus the f64 path's
    /// relative error of 2⁻⁵¹; and its value at pixel `(0, 0)` against the
    /// exact plane there. For depths in the front end's `[0, 2⁵⁶]` and for
    /// hand-made depths anywhere in `i64`, whose differences overflow 64
    /// bits.
    #[test]
    fn depth_steps_equal_the_exact_slopes_for_depths_of_any_size() {
        let cfg = RasterConfig::new(64, 64, 16, 8).expect("valid");
        let s = cfg.subpixel_bits();
        let mut rng = oorandom::Rand64::new(0x51_0be);
        let (mut set_up, mut wide) = (0, 0);
        for i in 0..40_000u32 {
            let vertex = |rng: &mut oorandom::Rand64| {
                #[allow(clippy::cast_possible_wrap, reason = "any bits of an i64")]
                let z = if i % 2 == 0 { rng.rand_u64() as i64 } else { rng.rand_i64().rem_euclid(1 << 56) };
                let mut c = || rng.rand_i64().rem_euclid(64 << s);
                SnappedVertex { x: SubPx(c()), y: SubPx(c()), z: PlaneZ::from_bits(z) }
            };
            let v = [vertex(&mut rng), vertex(&mut rng), vertex(&mut rng)];
            let Ok(setup) = Setup::new(&cfg, v, CullMode::None, 0) else { continue };
            let d = |f: fn(&SnappedVertex) -> i128, k: usize| f(&v[k]) - f(&v[0]);
            let (x, y, z) = (
                |p: &SnappedVertex| i128::from(p.x.0),
                |p: &SnappedVertex| i128::from(p.y.0),
                |p: &SnappedVertex| i128::from(p.z.to_bits()),
            );
            let area = d(x, 1) * d(y, 2) - d(y, 1) * d(x, 2);
            let across = nearest((d(z, 1) * d(y, 2) - d(z, 2) * d(y, 1)) << s, area);
            let down = nearest((d(x, 1) * d(z, 2) - d(x, 2) * d(z, 1)) << s, area);
            for (found, exact) in [(setup.plane.a, across), (setup.plane.b, down)] {
                assert!((found - exact).abs() <= 1 + (exact.abs() >> 50), "{found} against {exact} for {v:?}");
            }
            // The value at pixel (0, 0)'s centre, `s` bits of subpixel from
            // vertex 0, exactly; setup reaches it with the rounded steps, so
            // each step's error counts once per pixel of that distance.
            let half = 1i128 << (s - 1);
            let (ox, oy) = (half - x(&v[0]), half - y(&v[0]));
            let num = (d(z, 1) * d(y, 2) - d(z, 2) * d(y, 1)) * ox + (d(x, 1) * d(z, 2) - d(x, 2) * d(z, 1)) * oy;
            let at_origin = z(&v[0]) + nearest(num, area);
            let drift = ((1 + (across.abs() >> 50)) * ox.abs() + (1 + (down.abs() >> 50)) * oy.abs()) >> s;
            let found = setup.plane.c;
            assert!((found - at_origin).abs() <= 2 + drift, "{found} against {at_origin} for {v:?}");
            set_up += 1;
            wide += u32::from(i64::try_from(d(z, 1)).is_err() || i64::try_from(d(z, 2)).is_err());
        }
        assert!(set_up > 30_000 && wide > 1_000, "{set_up} set up, {wide} with wide depth differences");
    }
}
