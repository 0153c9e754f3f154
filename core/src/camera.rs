//! The camera pass's shading unit: for every pixel the visibility unit left
//! a triangle id in, the surface point in light space (fixed point), the
//! interpolated normal, and the shadow fraction from the [`crate::shadow`]
//! unit.
//!
//! # Projective interpolation
//! For a triangle with camera clip vertices `cᵢ`, the unnormalised
//! barycentrics of the pixel centre `s = (px + ½, py + ½, 1)` are
//! `β = K·s` with `K = [cₓ c_y c_w]⁻¹·A` (`A` maps pixels to NDC).
//! Everything linear in the vertices — light clip coordinates, normals,
//! world positions — is then linear in `s` up to one common scale. So the
//! setup unit forms, once per triangle and in f64, the map-space numerators
//! `U = (Λx + Λw)·W/2`, `V = (Λw − Λy)·H/2`, `Z = Λz` and the denominator
//! `Λw` as linear functions of the pixel, and scales them to integers; per
//! pixel the interpolator evaluates them in integers and divides once per
//! coordinate: `u = U/Λw` (texels, 16 fraction bits), `v`, `z = Z/Λw`
//! ([`PlaneZ`]). This is projective texture mapping, as shadow-map hardware
//! does it. A point with `Λw ≤ 0` is behind the light: lit.
//!
//! # The receiver's tangent plane
//! **Flat normals**: the tangent plane is the triangle's own plane, and its
//! slopes on the map are exactly the light pass's depth-plane steps for
//! this triangle (same snap, same setup): virtual samples reproduce the
//! depths the light pass stored, bit for bit up to two units of 2⁻³² LSB, so
//! a planar receiver does not shadow itself at bias 0 at any precision. The
//! receiver's depth is that plane at `(u, v)`. If the triangle cannot be set
//! up on the map (clipped by the light's near plane, off the guard band, or
//! edge-on to the light) the tangent plane is solved from its face normal.
//! **Smooth normals**: the plane through the interpolated world point with
//! the interpolated normal, moved to light space by the inverse transpose
//! (Wang & Molnar 1994 §3.2).
//!
//! The footprint for Reeves' filter is the pixel's extent on the map, from
//! the light-space points of its right and lower neighbours on the same
//! triangle's plane (two more evaluations, for the jittered filter only).

use glam::{Mat4, Vec3};

use crate::clip::inside_all;
use crate::config::{ConfigError, CullMode};
use crate::depth::{DepthFormat, PLANE_FRACTION_BITS, PlaneZ};
use crate::light_pass::NO_TRIANGLE;
use crate::probe::Probe;
use crate::round::saturate;
use crate::setup::{DepthPlane, Setup};
use crate::shadow::{
    Lookup, MapCoord, MapView, Shadow, ShadowConfig, Slope, TangentPlane, shadow, shadow_with_virtual_samples,
};
use crate::silhouette::{SilStore, SilhouetteMap};

/// One triangle of the scene, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneTriangle {
    /// Vertex positions.
    pub positions: [Vec3; 3],
    /// Vertex normals (for smooth shading and tangent planes).
    pub normals: [Vec3; 3],
}

/// Where the shading unit finds the triangle behind an id the visibility
/// unit recorded (the index of the submitted triangle).
pub trait TriangleSource {
    /// The triangle with this id, if there is one.
    fn triangle(&self, id: u32) -> Option<SceneTriangle>;
}

impl<T: Fn(u32) -> Option<SceneTriangle>> TriangleSource for T {
    fn triangle(&self, id: u32) -> Option<SceneTriangle> {
        self(id)
    }
}

/// Which normal the receiver's tangent plane uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Normals {
    /// The face's own plane.
    Flat,
    /// The interpolated vertex normal.
    Smooth,
}

/// Everything the shading unit needs besides its buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConfig {
    /// World to camera clip space.
    pub camera: Mat4,
    /// World to light clip space (the map's view-projection).
    pub light: Mat4,
    /// Camera target width in pixels.
    pub width: u32,
    /// Camera target height in pixels.
    pub height: u32,
    /// The shadow test and filter.
    pub shadow: ShadowConfig,
    /// Wang & Molnar's virtual samples for pixels whose samples disagree.
    pub virtual_samples: bool,
    /// Flat or smooth tangent planes.
    pub normals: Normals,
    /// Seed of the jittered filter (each pixel derives its own).
    pub seed: u64,
}

/// A surface point on the map. Packed to 4-byte alignment, as a result
/// buffer of 32-bit words holds it: a pixel's [`Shaded`] is then 40 bytes,
/// not 48 (the depth's 8-byte alignment would pad both).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, packed(4))]
pub struct LightPoint {
    /// Column, texels.
    pub x: MapCoord,
    /// Row (down), texels.
    pub y: MapCoord,
    /// Light-space depth.
    pub z: PlaneZ,
}

/// What the camera pass produces for one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaded {
    /// The visible triangle, or [`NO_TRIANGLE`].
    pub triangle: u32,
    /// The surface point in light space; `None` for the background and for
    /// points behind the light.
    pub light: Option<LightPoint>,
    /// The interpolated normal, perspective-correct but not normalised
    /// (only its direction is meaningful; zero for the background).
    pub normal: Vec3,
    /// The fraction in shadow.
    pub shadow: Shadow,
}

impl Shaded {
    /// A pixel no triangle covers.
    pub const BACKGROUND: Self = Self { triangle: NO_TRIANGLE, light: None, normal: Vec3::ZERO, shadow: Shadow::ZERO };
}

const _: () = assert!(size_of::<Shaded>() == 40, "a pixel's result is ten 32-bit words");

/// Entries of [`shade`]'s setup store (on the stack: small enough for a
/// microcontroller's).
pub const SETUP_STORE: usize = 16;

/// `2⁴⁴`: the scale of the denominator `Λw` over the target, so that the
/// numerators (up to `W/2` times larger) and their products with pixel
/// coordinates stay well inside `i128`, and the rounding of each coefficient
/// moves `u` by under 2⁻²⁰ texel.
const DENOMINATOR_SCALE: f64 = 17_592_186_044_416.0;

/// The light pass's depth plane of a triangle, with what the shading unit
/// needs of it at every pixel worked out once.
#[derive(Clone, Copy, Debug)]
struct MapPlane {
    plane: DepthPlane,
    /// The steps, when both fit 64 bits (all but the most extreme planes):
    /// then each is one 64 × 64 → 128-bit multiply.
    narrow: Option<(i64, i64)>,
    /// The steps saturated to the receiver's slope.
    slope: Slope,
}

impl MapPlane {
    fn new(plane: DepthPlane) -> Self {
        let narrow = i64::try_from(plane.a).ok().zip(i64::try_from(plane.b).ok());
        let slope = Slope { du: saturate(plane.a), dv: saturate(plane.b) };
        Self { plane, narrow, slope }
    }
}

/// `U, V, Z, Λw` as integer linear forms in `(px + ½, py + ½, 1)`,
/// evaluated at twice that (`2px + 1`, `2py + 1`, `2`) to stay in integers.
#[derive(Clone, Copy, Debug)]
struct LightForms {
    rows: [[i64; 3]; 4],
    /// Every form stays below [`NARROW_FORM`] in magnitude at every pixel
    /// of the target and one past its right and lower edges (where the
    /// jittered footprint looks): evaluated in `i64`, exactly.
    narrow: bool,
}

/// The bound below which a light form is evaluated in `i64`: it leaves the
/// reciprocal divider's fast path (denominators below 2⁶¹) open too.
const NARROW_FORM: i128 = 1 << 60;

impl LightForms {
    fn new(rows: [[i64; 3]; 4], width: u32, height: u32) -> Self {
        let (sx, sy) = (2 * i128::from(width) + 1, 2 * i128::from(height) + 1);
        let reach =
            |r: &[i64; 3]| i128::from(r[0]).abs() * sx + i128::from(r[1]).abs() * sy + 2 * i128::from(r[2]).abs();
        Self { rows, narrow: rows.iter().all(|r| reach(r) < NARROW_FORM) }
    }
}

/// A triangle's setup for the interpolator.
#[derive(Clone, Copy, Debug)]
struct Interp {
    id: u32,
    /// `U, V, Z, Λw` as integer linear forms.
    light: Option<LightForms>,
    /// Normal rows (x, y, z) over `s`, f64.
    normal: [[f64; 3]; 3],
    /// Homogeneous world point rows over `s`, f64.
    world: [[f64; 3]; 4],
    /// The light pass's depth plane of this triangle on the map.
    plane: Option<MapPlane>,
    /// Face normal and first vertex (flat tangent planes without a map plane).
    face: Vec3,
    corner: Vec3,
    footprint: [MapCoord; 2],
}

fn dot3(a: &[f64; 3], s: &[f64; 3]) -> f64 {
    a[0] * s[0] + a[1] * s[1] + a[2] * s[2]
}

/// `rows × K` for rows over the three vertices.
fn through<const R: usize>(rows: &[[f64; 3]; R], k: &[[f64; 3]; 3]) -> [[f64; 3]; R] {
    rows.map(|r| [0, 1, 2].map(|j| r[0] * k[0][j] + r[1] * k[1][j] + r[2] * k[2][j]))
}

/// The inverse of a 3×3 matrix, or `None` when it is (nearly) singular.
fn inverse3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c = |r: usize, k: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    if !det.is_finite() || det.abs() < f64::MIN_POSITIVE * 1e10 {
        return None;
    }
    // inverse[i][j] = cofactor(j, i) / det
    Some([0, 1, 2].map(|i| [0, 1, 2].map(|j| c(j, i) / det)))
}

impl Interp {
    /// A setup with nothing to interpolate: no light forms, no normal, no
    /// map plane (what a triangle whose vertices are singular keeps).
    const EMPTY: Self = Self {
        id: NO_TRIANGLE,
        light: None,
        normal: [[0.0; 3]; 3],
        world: [[0.0; 3]; 4],
        plane: None,
        face: Vec3::ZERO,
        corner: Vec3::ZERO,
        footprint: [MapCoord::ZERO; 2],
    };

    fn new<F: DepthFormat>(cfg: &CameraConfig, map: &MapView<'_, F>, id: u32, t: &SceneTriangle) -> Self {
        let to_clip = |m: &Mat4, p: Vec3| (*m * p.extend(1.0)).to_array().map(f64::from);
        let c = t.positions.map(|p| to_clip(&cfg.camera, p));
        let l = t.positions.map(|p| to_clip(&cfg.light, p));
        let (wc, hc) = (f64::from(cfg.width), f64::from(cfg.height));
        // Columns (cₓ, c_y, c_w) per vertex; A maps pixels to NDC.
        let m = [[c[0][0], c[1][0], c[2][0]], [c[0][1], c[1][1], c[2][1]], [c[0][3], c[1][3], c[2][3]]];
        let a = [[2.0 / wc, 0.0, -1.0], [0.0, -2.0 / hc, 1.0], [0.0, 0.0, 1.0]];
        let raster = *map.raster();
        let face = (t.positions[1] - t.positions[0]).cross(t.positions[2] - t.positions[0]);
        let mut out = Self { id, face, corner: t.positions[0], ..Self::EMPTY };
        let Some(minv) = inverse3(&m) else { return out };
        let k: [[f64; 3]; 3] = [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|x| minv[i][x] * a[x][j]).sum()));
        let light_rows: [[f64; 3]; 4] = [0, 1, 2, 3].map(|r| [l[0][r], l[1][r], l[2][r]]);
        let lr = through(&light_rows, &k);
        let (wm, hm) = (f64::from(raster.width()), f64::from(raster.height()));
        let u = [0, 1, 2].map(|j| (lr[0][j] + lr[3][j]) * wm / 2.0);
        let v = [0, 1, 2].map(|j| (lr[3][j] - lr[1][j]) * hm / 2.0);
        let forms = [u, v, lr[2], lr[3]];
        let normals: [[f64; 3]; 3] = [0, 1, 2].map(|r| t.normals.map(|n| f64::from(n.to_array()[r])));
        out.normal = through(&normals, &k);
        let world: [[f64; 3]; 4] =
            [0, 1, 2, 3].map(|r| t.positions.map(|p| if r == 3 { 1.0 } else { f64::from(p.to_array()[r]) }));
        out.world = through(&world, &k);
        // Scale so |Λw| stays near 2⁴⁴ over the target, in integers.
        let w = forms[3];
        let reach = w[0].abs() * wc + w[1].abs() * hc + w[2].abs();
        if reach.is_finite() && reach > 0.0 {
            let sigma = DENOMINATOR_SCALE / reach;
            let fixed = |x: f64| {
                let v = x * sigma;
                (v.is_finite() && v.abs() < 9.0e18).then(|| crate::round::round_ties_even(v))
            };
            let mut ints = [[0i64; 3]; 4];
            let mut ok = true;
            for (row, f) in ints.iter_mut().zip(&forms) {
                for (slot, &x) in row.iter_mut().zip(f) {
                    match fixed(x) {
                        Some(v) => *slot = v,
                        None => ok = false,
                    }
                }
            }
            if ok {
                out.light = Some(LightForms::new(ints, cfg.width, cfg.height));
            }
            // Reeves' footprint: the pixel's half-extent on the map at the centroid.
            let cs = [c[0], c[1], c[2]].map(|v| {
                if v[3] > 0.0 { [(v[0] / v[3] + 1.0) * wc / 2.0, (1.0 - v[1] / v[3]) * hc / 2.0] } else { [0.0, 0.0] }
            });
            let s = [(cs[0][0] + cs[1][0] + cs[2][0]) / 3.0, (cs[0][1] + cs[1][1] + cs[2][1]) / 3.0, 1.0];
            let wv = dot3(&w, &s);
            if wv > 0.0 {
                let d = |f: &[f64; 3], axis: usize| (f[axis] * wv - dot3(f, &s) * w[axis]) / (wv * wv);
                // NaN (a light matrix with NaN in a row `w` does not use):
                // no footprint, as for a point behind the camera.
                let half = |f: &[f64; 3]| {
                    let h = 0.5 * (d(f, 0).abs() + d(f, 1).abs());
                    if h.is_nan() { MapCoord::ZERO } else { MapCoord::saturating_from_num(h) }
                };
                out.footprint = [half(&u), half(&v)];
            }
        }
        // The light pass's own plane for this triangle, when it can be set up.
        let guard = raster.guard();
        if l.iter().all(|v| inside_all(v, guard))
            && let [Some(a), Some(b), Some(cc)] = l.map(|v| raster.snap::<F>(&v))
            && let Ok(setup) = Setup::new(&raster, [a, b, cc], CullMode::None, id)
        {
            out.plane = Some(MapPlane::new(setup.plane));
        }
        out
    }

    /// The light point of pixel `(px, py)`; `None` behind the light. The
    /// depth division is skipped (`z` left 0) unless `with_depth`. Pixels
    /// lie on the target or one past its right or lower edge.
    #[inline(always)]
    fn light_point<F: DepthFormat>(&self, px: u32, py: u32, with_depth: bool) -> Option<LightPoint> {
        let f = self.light.as_ref()?;
        let (sx, sy) = (i64::from(px) * 2 + 1, i64::from(py) * 2 + 1);
        if f.narrow {
            // Below 2⁶⁰ by construction: the wrapping never happens.
            let eval = |r: &[i64; 3]| {
                i128::from(r[0].wrapping_mul(sx).wrapping_add(r[1].wrapping_mul(sy)).wrapping_add(r[2].wrapping_mul(2)))
            };
            return project::<F>(&f.rows, eval, with_depth);
        }
        wide_point::<F>(&f.rows, sx, sy, with_depth)
    }

    /// Reeves' footprint of pixel `(px, py)`: half the extent on the map of
    /// the steps to its right and lower neighbours (the per-triangle
    /// centroid estimate where a neighbour is behind the light).
    #[inline(never)]
    fn footprint_at<F: DepthFormat>(&self, p: &LightPoint, px: u32, py: u32) -> [MapCoord; 2] {
        let (Some(r), Some(d)) = (
            self.light_point::<F>(px.saturating_add(1), py, false),
            self.light_point::<F>(px, py.saturating_add(1), false),
        ) else {
            return self.footprint;
        };
        let half = |a: MapCoord, b: MapCoord, c: MapCoord| {
            (a.saturating_sub(b).saturating_abs().saturating_add(c.saturating_sub(b).saturating_abs())) / 2
        };
        [half(r.x, p.x, d.x), half(r.y, p.y, d.y)]
    }

    /// The depth of the light pass's plane at a map position, and its slopes.
    #[inline]
    fn plane_at(&self, p: &LightPoint) -> Option<(PlaneZ, Slope)> {
        let MapPlane { plane, narrow, slope } = self.plane?;
        let off = |c: MapCoord| i64::from(c.to_bits()) - (1 << 15);
        let (dx, dy) = (off(p.x), off(p.y));
        let steps = match narrow {
            Some((a, b)) => i128::from(a) * i128::from(dx) + i128::from(b) * i128::from(dy),
            None => plane.a * i128::from(dx) + plane.b * i128::from(dy),
        };
        Some((PlaneZ::from_bits(saturate(plane.c + (steps >> 16))), slope))
    }

    /// Rows over `s = (px + ½, py + ½, 1)` at a pixel centre.
    #[inline]
    fn at_pixel<const R: usize>(rows: &[[f64; 3]; R], px: u32, py: u32) -> [f64; R] {
        let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
        rows.map(|r| r[0] * x + r[1] * y + r[2])
    }
}

/// The light point from the forms' values at a pixel (`eval`): `u = U/Λw`,
/// `v = V/Λw` and, `with_depth`, `z = Z/Λw`; `None` behind the light.
#[inline(always)]
fn project<F: DepthFormat>(
    rows: &[[i64; 3]; 4],
    eval: impl Fn(&[i64; 3]) -> i128,
    with_depth: bool,
) -> Option<LightPoint> {
    let w = eval(&rows[3]);
    if w <= 0 {
        return None;
    }
    let divider = Reciprocal::new(w);
    let z = if with_depth {
        let z = eval(&rows[2]).checked_mul(i128::from(F::SCALE) << PLANE_FRACTION_BITS)? / w;
        PlaneZ::from_bits(saturate(z))
    } else {
        PlaneZ::ZERO
    };
    Some(LightPoint { x: divider.coord(eval(&rows[0]))?, y: divider.coord(eval(&rows[1]))?, z })
}

/// [`project`] of forms that may reach beyond `i64`, out of line (rare, and
/// kept out of the shading loop's code).
#[inline(never)]
fn wide_point<F: DepthFormat>(rows: &[[i64; 3]; 4], sx: i64, sy: i64, with_depth: bool) -> Option<LightPoint> {
    // 64 × 64 → 128-bit products (one multiply each).
    let eval =
        |r: &[i64; 3]| i128::from(r[0]) * i128::from(sx) + i128::from(r[1]) * i128::from(sy) + 2 * i128::from(r[2]);
    project::<F>(rows, eval, with_depth)
}

/// A divider by `w > 0` with a reciprocal estimate, as hardware divides:
/// `n·2¹⁶ / w` (truncated toward zero as `i128` division is, saturated to
/// `i64`; `None` if `n·2¹⁶` overflows) is the f64 product `n · (2¹⁶/w)` (off by at most a unit or
/// two below 2⁵⁰), then corrected until the remainder `n·2¹⁶ − q·w` has the
/// sign of `n` and lies within `w` — the exact truncated quotient, bit for
/// bit. One reciprocal serves every numerator over the same `w` (the two
/// map coordinates of a pixel). Numerators or divisors outside `i64`, and
/// quotients beyond 2⁵⁰, take the exact `i128` division.
#[derive(Clone, Copy, Debug)]
struct Reciprocal {
    w: i128,
    /// `w` when it fits the fast path (below 2⁶¹, so remainders of a few
    /// `w` fit in `i64`).
    w64: Option<i64>,
    inverse: f64,
}

impl Reciprocal {
    #[inline]
    fn new(w: i128) -> Self {
        let w64 = i64::try_from(w).ok().filter(|&w| w > 0 && w < 1 << 61);
        #[allow(clippy::cast_precision_loss, reason = "an estimate, corrected after")]
        let inverse = w64.map_or(0.0, |w| 65_536.0 / w as f64);
        Self { w, w64, inverse }
    }

    /// `n·2¹⁶ / w` saturated to `i64`.
    #[inline]
    fn div_shifted(&self, n: i128) -> Option<i64> {
        if let Some(q) = self.div_shifted_narrow(n) {
            return Some(q);
        }
        Some(saturate(n.checked_mul(1 << 16)? / self.w))
    }

    /// `n·2¹⁶ / w` clamped to a map coordinate; `None` if `n·2¹⁶` overflows.
    #[inline]
    fn coord(&self, n: i128) -> Option<MapCoord> {
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
                let mut r = (n << 16).wrapping_sub(q.wrapping_mul(w));
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

/// A 64-bit mix of the seed and the pixel (splitmix64's finaliser).
fn pixel_seed(seed: u64, px: u32, py: u32) -> u64 {
    let mut z = seed ^ (u64::from(px) << 32 | u64::from(py)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Shade every pixel: `ids` from the visibility unit, `out` receives one
/// [`Shaded`] per pixel, row-major.
///
/// # Errors
/// [`ConfigError::BufferLength`] when `ids` or `out` is not `width × height`.
pub fn shade<F: DepthFormat, S: TriangleSource, P: Probe>(
    cfg: &CameraConfig,
    ids: &[u32],
    map: &MapView<'_, F>,
    scene: &S,
    out: &mut [Shaded],
    probe: &mut P,
) -> Result<(), ConfigError> {
    let mut setups = [ShadeSetup::EMPTY; SETUP_STORE];
    shade_with(cfg, ids, map, scene, out, &MapUnit, &mut setups, probe)
}

/// The unit that turns a pixel's lookup into its shadow fraction.
pub trait ShadowUnit<F: DepthFormat> {
    /// Decide one lookup against `map`; `tangent` solves the receiver's
    /// tangent plane on the map, for units that use virtual samples.
    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &CameraConfig,
        lookup: &Lookup,
        tangent: T,
        probe: &mut P,
    ) -> Shadow;
}

/// The shadow unit of [`crate::shadow`]: the configured test and filter,
/// with Wang & Molnar's virtual samples when the configuration asks.
#[derive(Clone, Copy, Debug, Default)]
pub struct MapUnit;

impl<F: DepthFormat> ShadowUnit<F> for MapUnit {
    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &CameraConfig,
        lookup: &Lookup,
        tangent: T,
        probe: &mut P,
    ) -> Shadow {
        if cfg.virtual_samples {
            shadow_with_virtual_samples(map, &cfg.shadow, lookup, tangent, probe)
        } else {
            shadow(map, &cfg.shadow, lookup, probe)
        }
    }
}

/// Sen et al.'s silhouette-map test ([`crate::silhouette`]) in place of the
/// filter: four corner tests, then the skewed quadrants.
#[derive(Debug)]
pub struct SilhouetteUnit<'s, 'a, S: SilStore>(pub &'s SilhouetteMap<'a, S>);

impl<F: DepthFormat, S: SilStore> ShadowUnit<F> for SilhouetteUnit<'_, '_, S> {
    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &CameraConfig,
        lookup: &Lookup,
        _tangent: T,
        probe: &mut P,
    ) -> Shadow {
        crate::silhouette::shadow(self.0, map, &cfg.shadow, lookup.x, lookup.y, lookup.z, probe)
    }
}

/// One entry of the shading unit's setup store: a triangle's interpolator
/// setup, kept while the pass meets the triangle again. Rows of pixels
/// cross the same triangles row after row, so a store as long as the
/// triangles one row crosses sets each up about once a pass.
#[derive(Clone, Copy, Debug)]
pub struct ShadeSetup(Option<Interp>);

impl ShadeSetup {
    /// An entry that holds nothing, to fill a store.
    pub const EMPTY: Self = Self(None);
}

/// [`shade`] with any [`ShadowUnit`], keeping triangle setups in `setups`
/// (direct-mapped by triangle id; emptied first, as setups depend on the
/// configuration; an empty store sets up every run of pixels anew).
///
/// # Errors
/// [`ConfigError::BufferLength`] when `ids` or `out` is not `width × height`.
#[allow(clippy::too_many_arguments, reason = "the unit's inputs, its store and its probe")]
pub fn shade_with<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, P: Probe>(
    cfg: &CameraConfig,
    ids: &[u32],
    map: &MapView<'_, F>,
    scene: &S,
    out: &mut [Shaded],
    unit: &U,
    setups: &mut [ShadeSetup],
    probe: &mut P,
) -> Result<(), ConfigError> {
    // Saturating: on a 32-bit target the product of two `u32` sides can overflow.
    let texels = (cfg.width as usize).saturating_mul(cfg.height as usize);
    for (buffer, found) in [("ids", ids.len()), ("out", out.len())] {
        if found != texels {
            return Err(ConfigError::BufferLength { buffer, expected: texels, found });
        }
    }
    let mut one = [ShadeSetup::EMPTY];
    let setups = if setups.is_empty() { &mut one[..] } else { setups };
    setups.fill(ShadeSetup::EMPTY);
    let light_inverse_transpose = cfg.light.inverse().transpose();
    let width = cfg.width as usize;
    if width == 0 {
        return Ok(());
    }
    // The store is consulted when the id changes along a row; the source
    // is asked only when the store misses.
    let (mut run, mut interp): (u32, Option<&Interp>) = (NO_TRIANGLE, None);
    for (py, (ids, out)) in (0u32..).zip(ids.chunks_exact(width).zip(out.chunks_exact_mut(width))) {
        for (px, (&id, o)) in (0u32..).zip(ids.iter().zip(out.iter_mut())) {
            if id != run {
                run = id;
                interp = None;
                if id != NO_TRIANGLE {
                    let slot = id as usize % setups.len();
                    if let Some(entry) = setups.get_mut(slot) {
                        interp = match entry {
                            ShadeSetup(Some(c)) if c.id == id => Some(&*c),
                            _ => scene.triangle(id).map(|tri| &*entry.0.insert(Interp::new::<F>(cfg, map, id, &tri))),
                        };
                    }
                }
            }
            *o = match interp {
                Some(i) => shade_pixel(cfg, map, unit, probe, &light_inverse_transpose, (px, py), i),
                None => Shaded::BACKGROUND,
            };
        }
    }
    Ok(())
}

/// One pixel of [`shade_with`].
#[inline]
fn shade_pixel<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    cfg: &CameraConfig,
    map: &MapView<'_, F>,
    unit: &U,
    probe: &mut P,
    light_inverse_transpose: &Mat4,
    (px, py): (u32, u32),
    interp: &Interp,
) -> Shaded {
    let id = interp.id;
    #[allow(clippy::cast_possible_truncation, reason = "a direction, normalised next")]
    let normal = Vec3::from_array(Interp::at_pixel(&interp.normal, px, py).map(|c| c as f32));
    // Flat receivers take their depth from the light pass's own plane.
    let flat_plane = cfg.normals == Normals::Flat && interp.plane.is_some();
    let Some(point) = interp.light_point::<F>(px, py, !flat_plane) else {
        return Shaded { triangle: id, light: None, normal, shadow: Shadow::ZERO };
    };
    let flat = if cfg.normals == Normals::Flat { interp.plane_at(&point) } else { None };
    let z = flat.map_or(point.z, |(z, _)| z);
    let lookup = Lookup {
        x: point.x,
        y: point.y,
        z,
        footprint: if matches!(cfg.shadow.filter(), crate::shadow::Filter::Jittered(_)) {
            interp.footprint_at::<F>(&point, px, py)
        } else {
            interp.footprint
        },
        seed: if cfg.shadow.draws_random() { pixel_seed(cfg.seed, px, py) } else { 0 },
        slope: None,
    };
    let raster = *map.raster();
    let tangent = || match (cfg.normals, flat) {
        (Normals::Flat, Some((_, slope))) => Some(slope),
        (Normals::Flat, None) => {
            TangentPlane::new(interp.corner, interp.face, light_inverse_transpose).slope::<F>(&raster)
        }
        (Normals::Smooth, _) => {
            let [x, y, zz, ww] = Interp::at_pixel(&interp.world, px, py);
            #[allow(clippy::cast_possible_truncation, reason = "a world point, as the scene gives it")]
            let p = Vec3::new((x / ww) as f32, (y / ww) as f32, (zz / ww) as f32);
            TangentPlane::new(p, normal, light_inverse_transpose).slope::<F>(&raster)
        }
    };
    let s = unit.decide(map, cfg, &lookup, tangent, probe);
    Shaded { triangle: id, light: Some(LightPoint { z, ..point }), normal, shadow: s }
}

#[cfg(test)]
mod tests {
    use super::{Interp, LightForms, Reciprocal};
    use crate::depth::{D24, DepthFormat, PLANE_FRACTION_BITS};

    fn div_shifted(n: i128, w: i128) -> Option<i64> {
        Reciprocal::new(w).div_shifted(n)
    }

    /// The two-division path gives the `i128` quotient (saturated to `i64`)
    /// for numerators of either sign, small and large denominators, and
    /// exact multiples.
    #[test]
    fn shifted_division_equals_the_wide_one() {
        let mut rng = oorandom::Rand64::new(0x5eed);
        let wide = |n: i128, w: i128| crate::round::saturate((n * 65_536) / w);
        let check = |n: i128, w: i128| assert_eq!(div_shifted(n, w), Some(wide(n, w)), "{n} / {w}");
        for (n, w) in [
            (0, 1),
            (-1, 1),
            (1, 3),
            (-1, 3),
            (i128::from(i64::MIN), 7),
            (i128::from(i64::MAX), (1 << 46) - 1),
            (i128::from(i64::MIN), 1),
            (i128::from(i64::MAX), i128::from(i64::MAX)),
        ] {
            check(n, w);
        }
        for _ in 0..100_000 {
            let bits = rng.rand_range(1..63);
            let w = i128::from(rng.rand_range(1..1 << bits));
            #[allow(clippy::cast_possible_wrap, reason = "any 64-bit pattern")]
            let n = i128::from(rng.rand_u64() as i64 >> rng.rand_range(0..40));
            check(n, w);
            check(-n, w);
            check(n / w * w, w);
        }
        // Outside i64: the wide path.
        assert_eq!(div_shifted(i128::from(i64::MAX) * 4, 3), Some(wide(i128::from(i64::MAX) * 4, 3)));
    }

    /// The light point, worked out by hand in `i128`: each form at
    /// `(2px + 1, 2py + 1, 2)`, then `u = ⌊U·2¹⁶ / Λw⌋` toward zero clamped to
    /// a map coordinate, `z = Z·SCALE·2³² / Λw` toward zero saturated to
    /// `i64`; `None` behind the light.
    fn by_hand(rows: &[[i64; 3]; 4], px: u32, py: u32) -> Option<(i32, i32, i64)> {
        let s = [2 * i128::from(px) + 1, 2 * i128::from(py) + 1, 2];
        let [u, v, z, w] = rows.map(|r| (0..3).map(|k| i128::from(r[k]) * s[k]).sum::<i128>());
        if w <= 0 {
            return None;
        }
        let coord = |n: i128| i32::try_from((n * 65_536 / w).clamp(i32::MIN.into(), i32::MAX.into())).ok();
        let depth = (z * (i128::from(D24::SCALE) << PLANE_FRACTION_BITS) / w).clamp(i64::MIN.into(), i64::MAX.into());
        Some((coord(u)?, coord(v)?, i64::try_from(depth).ok()?))
    }

    /// Forms below the narrow bound over the target take the `i64` path;
    /// the rest the `i128` one; both give the light point worked out by
    /// hand, for points on and far off the map and for any depth.
    #[test]
    fn light_points_equal_the_wide_division_on_both_paths() {
        let mut rng = oorandom::Rand64::new(0x11_9e);
        let (width, height) = (1920, 1080);
        let (mut narrow, mut wide) = (0, 0);
        for _ in 0..20_000 {
            let reach = rng.rand_range(44..62);
            #[allow(clippy::cast_possible_wrap, reason = "any 64-bit pattern")]
            let mut any = |bits: u64| (rng.rand_u64() as i64) >> (64 - bits);
            // Λw near 2⁴⁴ over the target, as setup scales it; numerators
            // within the map's reach or far beyond it.
            let w = [any(30), any(30), (1 << 43) + any(40)];
            let rows = [
                [any(reach - 11), any(reach - 11), any(reach)],
                [any(reach - 11), any(reach - 11), any(reach)],
                [any(34), any(34), any(45)],
                w,
            ];
            let interp = Interp { light: Some(LightForms::new(rows, width, height)), ..Interp::EMPTY };
            let form = interp.light.as_ref().map(|f| f.narrow);
            if form == Some(true) {
                narrow += 1
            } else {
                wide += 1
            }
            for _ in 0..8 {
                #[allow(clippy::cast_possible_truncation, reason = "below the target's sides")]
                let (px, py) =
                    (rng.rand_range(0..u64::from(width) + 1) as u32, rng.rand_range(0..u64::from(height) + 1) as u32);
                let got =
                    interp.light_point::<D24>(px, py, true).map(|p| (p.x.to_bits(), p.y.to_bits(), p.z.to_bits()));
                assert_eq!(got, by_hand(&rows, px, py), "rows {rows:?} at ({px}, {py})");
            }
        }
        assert!(narrow > 1_000 && wide > 1_000, "both paths taken: {narrow} narrow, {wide} wide");
    }
}
