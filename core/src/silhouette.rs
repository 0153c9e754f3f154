//! The silhouette unit: Sen, Cammarano & Hanrahan 2003, *Shadow Silhouette
//! Maps* — a map of one point per texel on the light-view silhouette, used
//! by the camera pass to reconstruct a piecewise-linear shadow boundary
//! where a depth map alone gives a staircase.
//!
//! # Grids
//! The silhouette map is the depth map's dual grid, **offset by half a
//! texel** (§2): silhouette texel `(i, j)` spans map coordinates
//! `[i − ½, i + ½) × [j − ½, j + ½)`, so its four corners are the centres of
//! depth texels `(i − 1, j − 1)`, `(i, j − 1)`, `(i − 1, j)` and `(i, j)`.
//! A `W × H` depth map has a `(W + 1) × (H + 1)` silhouette map. A point is
//! stored as its offset from its texel's top-left corner, 16 fraction bits
//! per axis ([`SilPoint`]), or packed to 4 bits per axis in one byte as Sen
//! suggests ([`Packed`]); an empty texel means its centre.
//!
//! # The silhouette pass (§3.1)
//! Each silhouette edge is clipped to the light's near and far planes,
//! projected (f64, as the vertex unit) and rasterized conservatively: every
//! texel within [`CORNER_SLACK`] of the segment gets a fragment, so the
//! fragments are 4-connected and a segment through a corner reaches all four
//! texels around it. Each fragment picks its point in integers: an endpoint
//! inside the texel; otherwise the segment's intersections with the texel's
//! two diagonals, accepted within the enlarged square — one: that point, two:
//! their midpoint, none: the fragment is killed. The point is clamped into
//! the texel. A fragment behind all four corner depths (a hidden silhouette)
//! is killed too. Last write wins.
//!
//! # The camera pass (§3.2)
//! The four corner depth tests (the shadow unit's test and bias); if they
//! agree, that is the verdict. Otherwise the texel's point and its four
//! neighbours' points split the texel into four skewed quadrants; eight
//! pie-shaped regions (rays from the texel's point to the neighbours and to
//! the corners) place the receiver in one, and it takes the verdict of that
//! quadrant's corner.

use glam::Mat4;

use crate::clip::ClipVertex;
use crate::config::ConfigError;
use crate::depth::{DepthFormat, PlaneZ};
use crate::probe::{Buffer, Event, NoProbe, Probe, TexelRead};
use crate::shadow::{MapCoord, MapView, Shadow, ShadowConfig};

/// One texel unit in the silhouette unit's fixed point (16 fraction bits).
const ONE: i64 = 1 << 16;

/// How far outside its texel a diagonal intersection still counts (Sen's
/// enlarged clip square): 2⁻⁸ texel, in 2⁻¹⁶ texels. A segment through a
/// corner then stores a point in all four texels around it.
pub const CORNER_SLACK: i64 = 1 << 8;

/// A silhouette point: its offset from the texel's top-left corner, in
/// 2⁻¹⁶ texels per axis (`0x8000` is the centre).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SilPoint {
    /// Offset to the right.
    pub x: u16,
    /// Offset down.
    pub y: u16,
}

impl SilPoint {
    /// The texel's centre: what an empty texel means.
    pub const CENTRE: Self = Self { x: 0x8000, y: 0x8000 };
}

/// How a silhouette map stores its points.
pub trait SilStore: Copy + Default + core::fmt::Debug + 'static {
    /// Bytes per texel.
    const BYTES: u32;
    /// Store a point.
    fn encode(p: SilPoint) -> Self;
    /// The stored point.
    fn decode(self) -> SilPoint;
}

impl Default for SilPoint {
    fn default() -> Self {
        Self::CENTRE
    }
}

/// Full precision: 16 bits per axis, 4 bytes per texel.
impl SilStore for SilPoint {
    const BYTES: u32 = 4;
    fn encode(p: SilPoint) -> Self {
        p
    }
    fn decode(self) -> SilPoint {
        self
    }
}

/// Sen's packed form: 4 bits per axis, one byte per texel. A nibble `q`
/// means `q/16` texel, so the centre (8, 8) is exact and the largest error
/// of a stored point is 1/32 texel per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Packed(pub u8);

impl Default for Packed {
    fn default() -> Self {
        Self::encode(SilPoint::CENTRE)
    }
}

impl SilStore for Packed {
    const BYTES: u32 = 1;
    fn encode(p: SilPoint) -> Self {
        let q = |v: u16| ((u32::from(v) + 0x800) >> 12).min(15);
        #[allow(clippy::cast_possible_truncation, reason = "two nibbles")]
        let byte = (q(p.x) << 4 | q(p.y)) as u8;
        Self(byte)
    }
    fn decode(self) -> SilPoint {
        SilPoint { x: u16::from(self.0 >> 4) << 12, y: u16::from(self.0 & 15) << 12 }
    }
}

/// The dual grid of a `map_width × map_height` depth map:
/// `(map_width + 1) × (map_height + 1)` texels.
fn dual(map_width: u32, map_height: u32, len: usize) -> Result<(u32, u32), ConfigError> {
    let (width, height) = (map_width.saturating_add(1), map_height.saturating_add(1));
    let expected = width as usize * height as usize;
    if len != expected {
        return Err(ConfigError::BufferLength { buffer: "silhouette", expected, found: len });
    }
    Ok((width, height))
}

/// The index of texel `(i, j)` of a `width × height` grid, if inside.
fn index(width: u32, height: u32, i: i64, j: i64) -> Option<usize> {
    let (i, j) = (u32::try_from(i).ok()?, u32::try_from(j).ok()?);
    (i < width && j < height).then(|| j as usize * width as usize + i as usize)
}

/// A finished silhouette map, as the camera pass reads it.
#[derive(Clone, Copy, Debug)]
pub struct SilhouetteMap<'a, S: SilStore> {
    width: u32,
    height: u32,
    texels: &'a [S],
}

impl<'a, S: SilStore> SilhouetteMap<'a, S> {
    /// View the silhouette map of a `map_width × map_height` depth map.
    ///
    /// # Errors
    /// [`ConfigError::BufferLength`] unless `texels` has
    /// `(map_width + 1) × (map_height + 1)` entries.
    pub fn view(map_width: u32, map_height: u32, texels: &'a [S]) -> Result<Self, ConfigError> {
        let (width, height) = dual(map_width, map_height, texels.len())?;
        Ok(Self { width, height, texels })
    }

    /// Texels across.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Texels down.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The stored point of texel `(i, j)`; the centre when empty or outside.
    #[must_use]
    pub fn point(&self, i: i64, j: i64) -> SilPoint {
        index(self.width, self.height, i, j).and_then(|k| self.texels.get(k)).map_or(SilPoint::CENTRE, |s| s.decode())
    }
}

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
    let fixed = |c: f64| crate::round::round_ties_even(c * 65_536.0);
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
    let o = [i * ONE, j * ONE];
    let a = [seg.a[0] - o[0], seg.a[1] - o[1]];
    let b = [seg.b[0] - o[0], seg.b[1] - o[1]];
    let d = [b[0] - a[0], b[1] - a[1]];
    let inside = |p: &[i64; 2], slack: i64| p.iter().all(|&c| (-slack..ONE + slack).contains(&c));
    let clamp = |c: i64| u16::try_from(c.clamp(0, ONE - 1)).unwrap_or(u16::MAX);
    let point = |p: [i64; 2]| SilPoint { x: clamp(p[0]), y: clamp(p[1]) };
    // The parameter of a point on the segment, along its longer axis.
    let along = |p: &[i64; 2]| {
        let k = usize::from(d[1].abs() > d[0].abs());
        if d[k] == 0 { 0 } else { ((i128::from(p[k] - a[k]) << 16) / i128::from(d[k])).clamp(0, 1 << 16) as i64 }
    };
    if inside(&a, 0) {
        return Some((point(a), 0));
    }
    if inside(&b, 0) {
        return Some((point(b), ONE));
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
    let h2 = hit(ONE - a[0] - a[1], d[0] + d[1]);
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
        let (j0, j1) = ((y_lo >> 16).max(0), (y_hi >> 16).min(h - 1));
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
            let (ya, yb) = ((j << 16) - CORNER_SLACK, ((j + 1) << 16) + CORNER_SLACK);
            let (xa, xb) = if d[1] == 0 { (seg.a[0], seg.b[0]) } else { (x_at(ya), x_at(yb)) };
            let (x_lo, x_hi) = (xa.min(xb) - CORNER_SLACK, xa.max(xb) + CORNER_SLACK);
            for i in (x_lo >> 16).max(0)..=(x_hi >> 16).min(w - 1) {
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
        corners(i, j).into_iter().all(|c| self.map.sample(test, c, z, bias, &mut NoProbe) == Some(true))
    }
}

/// The depth texels at the corners of silhouette texel `(i, j)`: top-left,
/// top-right, bottom-left, bottom-right.
const fn corners(i: i64, j: i64) -> [(i64, i64); 4] {
    [(i - 1, j - 1), (i, j - 1), (i - 1, j), (i, j)]
}

/// The camera pass's silhouette test for a lookup at map position
/// `(x, y)` with receiver depth `z`: Sen et al. 2003 §3.2. Outside the map
/// and behind the light is lit.
pub fn shadow<S: SilStore, F: DepthFormat, P: Probe>(
    sil: &SilhouetteMap<'_, S>,
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    x: MapCoord,
    y: MapCoord,
    z: PlaneZ,
    probe: &mut P,
) -> Shadow {
    if z < 0 {
        return Shadow::ZERO;
    }
    let (sx, sy) = (i64::from(x.to_bits()) + (ONE >> 1), i64::from(y.to_bits()) + (ONE >> 1));
    let (i, j) = (sx >> 16, sy >> 16);
    if i < 0 || j < 0 || i >= i64::from(sil.width) || j >= i64::from(sil.height) {
        return Shadow::ZERO;
    }
    let bias = cfg.bias().bounds().0;
    let mut reads = 0u32;
    let verdicts = corners(i, j).map(|c| match map.sample(cfg.test(), c, z.to_bits(), bias, probe) {
        Some(s) => {
            reads += 1;
            s
        }
        None => false,
    });
    if reads > 0 {
        for buffer in map.buffers_read(cfg.test()) {
            probe.event(Event::MapRead { buffer, texels: reads, bytes: reads * F::KIND.bytes() });
        }
    }
    let lit = |s: bool| if s { Shadow::ONE } else { Shadow::ZERO };
    if verdicts.iter().all(|&v| v == verdicts[0]) {
        probe.event(Event::TrivialPixel { lit: !verdicts[0] });
        return lit(verdicts[0]);
    }
    probe.event(Event::SilhouetteRead { points: 5, bytes: 5 * S::BYTES });
    if P::TEXELS {
        for (di, dj) in [(0, 0), (0, -1), (1, 0), (0, 1), (-1, 0)] {
            if let (Ok(x), Ok(y)) = (u32::try_from(i + di), u32::try_from(j + dj))
                && x < sil.width
                && y < sil.height
            {
                probe.texel_read(TexelRead { buffer: Buffer::Silhouette, x, y });
            }
        }
    }
    let at = |di: i64, dj: i64| {
        let p = sil.point(i + di, j + dj);
        [i64::from(p.x) + di * ONE, i64::from(p.y) + dj * ONE]
    };
    let p = [sx & (ONE - 1), sy & (ONE - 1)];
    lit(verdicts[quadrant(at(0, 0), [at(0, -1), at(1, 0), at(0, 1), at(-1, 0)], p)])
}

/// The skewed quadrant of the texel that holds `p` (0 top-left, 1
/// top-right, 2 bottom-left, 3 bottom-right), given the texel's point `c`
/// and its neighbours' points `[up, right, down, left]`, all relative to
/// the texel's corner (y down). Eight pie-shaped regions: the rays from `c`
/// to the neighbours and to the corners, in clockwise order. If `p` lies in
/// none (a degenerate fan), the quadrant of `p` relative to `c`.
#[must_use]
pub fn quadrant(c: [i64; 2], n: [[i64; 2]; 4], p: [i64; 2]) -> usize {
    let corner = [[ONE, 0], [ONE, ONE], [0, ONE], [0, 0]];
    // Clockwise (y down): up, top-right, right, bottom-right, down, bottom-left, left, top-left.
    let rays = [n[0], corner[0], n[1], corner[1], n[2], corner[2], n[3], corner[3]];
    let region = [1, 1, 3, 3, 2, 2, 0, 0];
    let rel = |q: [i64; 2]| [i128::from(q[0] - c[0]), i128::from(q[1] - c[1])];
    let cross = |u: [i128; 2], v: [i128; 2]| u[0] * v[1] - u[1] * v[0];
    let pr = rel(p);
    for k in 0..8 {
        let (r1, r2) = (rel(rays[k]), rel(rays[(k + 1) % 8]));
        if cross(r1, r2) > 0 && cross(r1, pr) >= 0 && cross(pr, r2) > 0 {
            return region[k];
        }
    }
    usize::from(pr[0] >= 0) + 2 * usize::from(pr[1] >= 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Segment {
        let f = |v: f64| crate::round::round_ties_even(v * 65_536.0);
        Segment { a: [f(a[0]), f(a[1])], b: [f(b[0]), f(b[1])], za: PlaneZ::ZERO, zb: PlaneZ::ZERO }
    }

    #[test]
    fn endpoint_inside_is_stored() {
        let (p, t) = select_point(&seg([2.25, 3.75], [9.0, 9.0]), 2, 3).unwrap();
        assert_eq!((p.x, p.y, t), (0x4000, 0xC000, 0));
    }

    #[test]
    fn one_diagonal_hit_is_stored() {
        // A horizontal segment at y = 0.25 across texel (0, 0) meets y = x at
        // (0.25, 0.25) and x + y = 1 at (0.75, 0.25): two hits, midpoint (0.5, 0.25).
        let (p, _) = select_point(&seg([-3.0, 0.25], [5.0, 0.25]), 0, 0).unwrap();
        assert_eq!((p.x, p.y), (0x8000, 0x4000));
        // A segment cutting the top-left corner, parallel to x + y = 1:
        // one hit, on y = x at (0.05, 0.05). The endpoints round to
        // (−32768, 39322) and (39322, −32768) in 2⁻¹⁶ texels, so the hit is
        // halfway, at −32768 + 72090/2 = 3277.
        let (p, _) = select_point(&seg([-0.5, 0.6], [0.6, -0.5]), 0, 0).unwrap();
        assert_eq!((p.x, p.y), (3277, 3277));
    }

    #[test]
    fn a_miss_is_killed() {
        assert!(select_point(&seg([-3.0, 1.5], [5.0, 1.5]), 0, 0).is_none());
    }

    #[test]
    fn packing_keeps_the_centre_and_rounds_to_sixteenths() {
        assert_eq!(Packed::encode(SilPoint::CENTRE).decode(), SilPoint::CENTRE);
        let p = Packed::encode(SilPoint { x: 0x4100, y: 0xFFFF }).decode();
        assert_eq!((p.x, p.y), (0x4000, 0xF000));
    }

    #[test]
    fn quadrants_of_a_centred_fan() {
        let c = [ONE / 2, ONE / 2];
        let n = [[ONE / 2, -ONE / 2], [3 * ONE / 2, ONE / 2], [ONE / 2, 3 * ONE / 2], [-ONE / 2, ONE / 2]];
        assert_eq!(quadrant(c, n, [ONE / 4, ONE / 4]), 0);
        assert_eq!(quadrant(c, n, [3 * ONE / 4, ONE / 4]), 1);
        assert_eq!(quadrant(c, n, [ONE / 4, 3 * ONE / 4]), 2);
        assert_eq!(quadrant(c, n, [3 * ONE / 4, 3 * ONE / 4]), 3);
    }
}
