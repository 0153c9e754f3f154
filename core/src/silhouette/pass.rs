//! The silhouette pass (Sen et al. 2003 §3.1): edges projected and rasterized conservatively.

use glam::Mat4;

use super::{CORNER_SLACK, SilPoint, SilStore, corners, dual, index};
use crate::budget::{MAP_FRACTION_BITS, MAP_ONE, MAP_SCALE};
use crate::config::ConfigError;
use crate::depth::{DepthFormat, PlaneZ};
use crate::front::clip::ClipVertex;
use crate::probe::{Event, NoProbe, Probe};
use crate::shadow::{MapView, ShadowConfig};

/// A projected segment in silhouette-map coordinates (2⁻¹⁶ texels; texel
/// `(i, j)` spans `[i, i + 1) × [j, j + 1)`), with its depths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segment {
    /// First endpoint `(x, y)`.
    pub a: [i64; 2],
    /// Second endpoint.
    pub b: [i64; 2],
    /// Depth at `a`.
    pub za: PlaneZ,
    /// Depth at `b`.
    pub zb: PlaneZ,
}

/// Clip the segment `a → b` (light clip space) to `0 ≤ z ≤ w`, project it
/// onto a `width × height` depth map's silhouette grid, and clip it to the
/// grid (plus a texel). `None` when nothing is left or a value is not finite.
#[must_use]
pub fn project<F: DepthFormat>(a: &ClipVertex, b: &ClipVertex, width: u32, height: u32) -> Option<Segment> {
    if a.iter().chain(b).any(|v| !v.is_finite()) {
        return None;
    }
    // Homogeneous clipping, parameter range [t0, t1] of a → b.
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let planes = |v: &ClipVertex| [v[2], v[3] - v[2], v[3] - 1e-12 * v[3].abs()];
    let (da, db) = (planes(a), planes(b));
    for k in 0..3 {
        let (p, q) = (da[k], db[k]);
        if p < 0.0 && q < 0.0 {
            return None;
        }
        if p < 0.0 {
            t0 = t0.max(p / (p - q));
        } else if q < 0.0 {
            t1 = t1.min(p / (p - q));
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| [0, 1, 2, 3].map(|k| a[k] + t * (b[k] - a[k]));
    let (w, h) = (f64::from(width), f64::from(height));
    // Map coordinates, then + ½: the silhouette grid.
    let to_grid = |v: [f64; 4]| -> Option<[f64; 3]> {
        if v[3] <= 0.0 {
            return None;
        }
        let x = (v[0] / v[3] + 1.0) * 0.5 * w + 0.5;
        let y = (1.0 - v[1] / v[3]) * 0.5 * h + 0.5;
        Some([x, y, v[2] / v[3]])
    };
    let (mut p, mut q) = (to_grid(at(t0))?, to_grid(at(t1))?);
    // 2-D Liang–Barsky against the grid plus one texel on every side.
    let (lo, hi) = ([-1.0, -1.0], [w + 2.0, h + 2.0]);
    let (mut s0, mut s1) = (0.0f64, 1.0f64);
    for axis in 0..2 {
        let d = q[axis] - p[axis];
        for (edge, sign) in [(lo[axis], 1.0), (hi[axis], -1.0)] {
            let (num, den) = (sign * (p[axis] - edge), -sign * d);
            if den == 0.0 {
                if num < 0.0 {
                    return None;
                }
            } else {
                let r = num / den;
                if den < 0.0 { s0 = s0.max(r) } else { s1 = s1.min(r) }
            }
        }
    }
    if s0 > s1 || !s0.is_finite() || !s1.is_finite() {
        return None;
    }
    let lerp = |u: &[f64; 3], v: &[f64; 3], s: f64| [0, 1, 2].map(|k| u[k] + s * (v[k] - u[k]));
    (p, q) = (lerp(&p, &q, s0), lerp(&p, &q, s1));
    let fixed = |c: f64| crate::round::round_ties_even(c * MAP_SCALE);
    Some(Segment {
        a: [fixed(p[0]), fixed(p[1])],
        b: [fixed(q[0]), fixed(q[1])],
        za: F::plane_z(p[2]),
        zb: F::plane_z(q[2]),
    })
}

/// The point a fragment of texel `(i, j)` stores for `seg`, as an offset
/// from the texel's corner, or `None` when the segment misses the enlarged
/// texel (Sen et al. 2003, Figure 4), with the parameter along the segment
/// (2⁻¹⁶ units) for the depth.
#[must_use]
pub fn select_point(seg: &Segment, i: i64, j: i64) -> Option<(SilPoint, i64)> {
    let o = [i * MAP_ONE, j * MAP_ONE];
    let a = [seg.a[0] - o[0], seg.a[1] - o[1]];
    let b = [seg.b[0] - o[0], seg.b[1] - o[1]];
    let d = [b[0] - a[0], b[1] - a[1]];
    let inside = |p: &[i64; 2], slack: i64| p.iter().all(|&c| (-slack..MAP_ONE + slack).contains(&c));
    let clamp = |c: i64| u16::try_from(c.clamp(0, MAP_ONE - 1)).unwrap_or(u16::MAX);
    let point = |p: [i64; 2]| SilPoint { x: clamp(p[0]), y: clamp(p[1]) };
    // The parameter of a point on the segment, along its longer axis.
    let along = |p: &[i64; 2]| {
        let k = usize::from(d[1].abs() > d[0].abs());
        #[allow(clippy::cast_possible_truncation, reason = "clamped to [0, MAP_ONE]")]
        if d[k] == 0 {
            0
        } else {
            ((i128::from(p[k] - a[k]) << MAP_FRACTION_BITS) / i128::from(d[k])).clamp(0, MAP_ONE.into()) as i64
        }
    };
    if inside(&a, 0) {
        return Some((point(a), 0));
    }
    if inside(&b, 0) {
        return Some((point(b), MAP_ONE));
    }
    // Diagonal 1: y = x; diagonal 2: x + y = 1. Intersection a + t·d.
    let hit = |num: i64, den: i64| -> Option<[i64; 2]> {
        if den == 0 {
            return None;
        }
        let (num, den) =
            if den < 0 { (-i128::from(num), -i128::from(den)) } else { (i128::from(num), i128::from(den)) };
        if num < 0 || num > den {
            return None;
        }
        let p = [0, 1].map(|k| i128::from(a[k]) + (i128::from(d[k]) * num).div_euclid(den));
        let p = [i64::try_from(p[0]).ok()?, i64::try_from(p[1]).ok()?];
        inside(&p, CORNER_SLACK).then_some(p)
    };
    let h1 = hit(a[0] - a[1], d[1] - d[0]);
    let h2 = hit(MAP_ONE - a[0] - a[1], d[0] + d[1]);
    let p = match (h1, h2) {
        (Some(p), None) | (None, Some(p)) => p,
        (Some(p), Some(q)) => [(p[0] + q[0]) >> 1, (p[1] + q[1]) >> 1],
        (None, None) => return None,
    };
    Some((point(p), along(&p)))
}

/// The silhouette pass: writes silhouette points for edges into
/// caller-owned texels (cleared to empty first), killing those hidden
/// behind the depth map.
pub struct SilhouettePass<'m, S: SilStore, F: DepthFormat> {
    width: u32,
    height: u32,
    texels: &'m mut [S],
    map: &'m MapView<'m, F>,
    cfg: ShadowConfig,
}

impl<'m, S: SilStore, F: DepthFormat> SilhouettePass<'m, S, F> {
    /// A pass writing into `texels`, the dual grid of `map`, testing
    /// visibility against `map` with the test and bias of `cfg`.
    ///
    /// # Errors
    /// [`ConfigError::BufferLength`] when `texels` is not `map`'s dual grid.
    pub fn new(texels: &'m mut [S], map: &'m MapView<'m, F>, cfg: ShadowConfig) -> Result<Self, ConfigError> {
        let r = map.raster();
        let (width, height) = dual(r.width(), r.height(), texels.len())?;
        texels.fill(S::default());
        Ok(Self { width, height, texels, map, cfg })
    }

    /// Draw the edge `a → b`, given in light clip space (the light pass's
    /// transform of its endpoints).
    pub fn draw_clip<P: Probe>(&mut self, a: &ClipVertex, b: &ClipVertex, probe: &mut P) {
        let r = *self.map.raster();
        if let Some(seg) = project::<F>(a, b, r.width(), r.height()) {
            self.draw(&seg, probe);
        }
    }

    /// Draw an edge given in world space through the light's transform
    /// (f32, as the vertex unit).
    pub fn draw_world<P: Probe>(&mut self, light: &Mat4, a: glam::Vec3, b: glam::Vec3, probe: &mut P) {
        let clip = |p: glam::Vec3| (*light * p.extend(1.0)).to_array().map(f64::from);
        self.draw_clip(&clip(a), &clip(b), probe);
    }

    /// Rasterize a projected segment conservatively, one fragment per texel
    /// within [`CORNER_SLACK`] of it, row by row.
    pub fn draw<P: Probe>(&mut self, seg: &Segment, probe: &mut P) {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let (y_lo, y_hi) = (seg.a[1].min(seg.b[1]) - CORNER_SLACK, seg.a[1].max(seg.b[1]) + CORNER_SLACK);
        let (j0, j1) = ((y_lo >> MAP_FRACTION_BITS).max(0), (y_hi >> MAP_FRACTION_BITS).min(h - 1));
        let (mut fragments, mut stored) = (0u32, 0u32);
        let d = [seg.b[0] - seg.a[0], seg.b[1] - seg.a[1]];
        let x_at = |y: i64| -> i64 {
            let y = y.clamp(seg.a[1].min(seg.b[1]), seg.a[1].max(seg.b[1]));
            if d[1] == 0 {
                return seg.a[0];
            }
            let v = i128::from(seg.a[0]) + i128::from(y - seg.a[1]) * i128::from(d[0]) / i128::from(d[1]);
            i64::try_from(v).unwrap_or(seg.a[0])
        };
        for j in j0..=j1 {
            // The segment's x-range over the row's slab, widened by the slack.
            let (ya, yb) = ((j << MAP_FRACTION_BITS) - CORNER_SLACK, ((j + 1) << MAP_FRACTION_BITS) + CORNER_SLACK);
            let (xa, xb) = if d[1] == 0 { (seg.a[0], seg.b[0]) } else { (x_at(ya), x_at(yb)) };
            let (x_lo, x_hi) = (xa.min(xb) - CORNER_SLACK, xa.max(xb) + CORNER_SLACK);
            for i in (x_lo >> MAP_FRACTION_BITS).max(0)..=(x_hi >> MAP_FRACTION_BITS).min(w - 1) {
                fragments = fragments.saturating_add(1);
                let Some((p, t)) = select_point(seg, i, j) else { continue };
                let z = seg
                    .za
                    .to_bits()
                    .saturating_add(crate::shadow::mul_shift(seg.zb.to_bits().saturating_sub(seg.za.to_bits()), t));
                if self.hidden(i, j, z) {
                    continue;
                }
                if let Some(k) = index(self.width, self.height, i, j)
                    && let Some(slot) = self.texels.get_mut(k)
                {
                    *slot = S::encode(p);
                    stored += 1;
                }
            }
        }
        probe.event(Event::SilhouetteFragments { fragments, stored, bytes: stored.saturating_mul(S::BYTES) });
    }

    /// Whether depth `z` lies behind all four corner depths of texel `(i, j)`.
    fn hidden(&self, i: i64, j: i64, z: i64) -> bool {
        let bias = self.cfg.bias().bounds().0;
        let test = self.cfg.test();
        corners(i, j).into_iter().all(|c| self.map.sample(test, c, z, bias, 1, &mut NoProbe) == Some(true))
    }
}
