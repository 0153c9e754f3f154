//! The shading unit's interpolators: a triangle's light-space forms over the camera's pixels.

use glam::{Mat4, Vec3};

use super::{LightPoint, Reciprocal, SceneTriangle, ShadeConfig};
use crate::budget::{DENOMINATOR_SCALE, MAP_FRACTION_BITS, MAP_HALF, NARROW_FORM_BITS, PLANE_FRACTION_BITS};
use crate::config::CullMode;
use crate::depth::{DepthFormat, PlaneZ};
use crate::front::clip::inside_all;
use crate::front::setup::{DepthPlane, Setup};
use crate::front::snap::snap;
use crate::light_pass::NO_TRIANGLE;
use crate::round::saturate;
use crate::shadow::{MapCoord, MapView, Slope};

/// The light pass's depth plane of a triangle, with what the shading unit
/// needs of it at every pixel worked out once.
#[derive(Clone, Copy, Debug)]
pub(super) struct MapPlane {
    plane: DepthPlane,
    /// The steps, when both fit 64 bits (all but the most extreme planes):
    /// then each is one 64 × 64 → 128-bit multiply.
    pub(super) narrow: Option<(i64, i64)>,
    /// The steps saturated to the receiver's slope.
    slope: Slope,
}

impl MapPlane {
    pub(super) fn new(plane: DepthPlane) -> Self {
        let narrow = i64::try_from(plane.a).ok().zip(i64::try_from(plane.b).ok());
        let slope = Slope { du: saturate(plane.a), dv: saturate(plane.b) };
        Self { plane, narrow, slope }
    }
}

/// `U, V, Z, Λw` as integer linear forms in `(px + ½, py + ½, 1)`,
/// evaluated at twice that (`2px + 1`, `2py + 1`, `2`) to stay in integers.
#[derive(Clone, Copy, Debug)]
pub(super) struct LightForms {
    rows: [[i64; 3]; 4],
    /// Every form stays below [`NARROW_FORM`] in magnitude at every pixel
    /// of the target and one past its right and lower edges (where the
    /// jittered footprint looks): evaluated in `i64`, exactly.
    pub(super) narrow: bool,
}

/// The bound below which a light form is evaluated in `i64`: it leaves the
/// reciprocal divider's fast path (denominators below 2⁶¹) open too.
const NARROW_FORM: i128 = 1 << NARROW_FORM_BITS;

impl LightForms {
    pub(super) fn new(rows: [[i64; 3]; 4], width: u32, height: u32) -> Self {
        let (sx, sy) = (2 * i128::from(width) + 1, 2 * i128::from(height) + 1);
        let reach =
            |r: &[i64; 3]| i128::from(r[0]).abs() * sx + i128::from(r[1]).abs() * sy + 2 * i128::from(r[2]).abs();
        Self { rows, narrow: rows.iter().all(|r| reach(r) < NARROW_FORM) }
    }
}

/// A triangle's setup for the interpolator.
#[derive(Clone, Copy, Debug)]
pub(super) struct Interp {
    pub(super) id: u32,
    /// `U, V, Z, Λw` as integer linear forms.
    pub(super) light: Option<LightForms>,
    /// Normal rows (x, y, z) over `s`, f64.
    pub(super) normal: [[f64; 3]; 3],
    /// Homogeneous world point rows over `s`, f64.
    pub(super) world: [[f64; 3]; 4],
    /// The light pass's depth plane of this triangle on the map.
    pub(super) plane: Option<MapPlane>,
    /// Face normal and first vertex (flat tangent planes without a map plane).
    pub(super) face: Vec3,
    pub(super) corner: Vec3,
    pub(super) footprint: [MapCoord; 2],
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
    pub(super) const EMPTY: Self = Self {
        id: NO_TRIANGLE,
        light: None,
        normal: [[0.0; 3]; 3],
        world: [[0.0; 3]; 4],
        plane: None,
        face: Vec3::ZERO,
        corner: Vec3::ZERO,
        footprint: [MapCoord::ZERO; 2],
    };

    pub(super) fn new<F: DepthFormat>(cfg: &ShadeConfig, map: &MapView<'_, F>, id: u32, t: &SceneTriangle) -> Self {
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
            && let [Some(a), Some(b), Some(cc)] = l.map(|v| snap::<F>(&raster, &v))
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
    pub(super) fn light_point<F: DepthFormat>(&self, px: u32, py: u32, with_depth: bool) -> Option<LightPoint> {
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
    pub(super) fn footprint_at<F: DepthFormat>(&self, p: &LightPoint, px: u32, py: u32) -> [MapCoord; 2] {
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
    pub(super) fn plane_at(&self, p: &LightPoint) -> Option<(PlaneZ, Slope)> {
        let MapPlane { plane, narrow, slope } = self.plane?;
        let off = |c: MapCoord| i64::from(c.to_bits()) - MAP_HALF;
        let (dx, dy) = (off(p.x), off(p.y));
        let steps = match narrow {
            Some((a, b)) => i128::from(a) * i128::from(dx) + i128::from(b) * i128::from(dy),
            None => plane.a * i128::from(dx) + plane.b * i128::from(dy),
        };
        Some((PlaneZ::from_bits(saturate(plane.c + (steps >> MAP_FRACTION_BITS))), slope))
    }

    /// Rows over `s = (px + ½, py + ½, 1)` at a pixel centre.
    #[inline]
    pub(super) fn at_pixel<const R: usize>(rows: &[[f64; 3]; R], px: u32, py: u32) -> [f64; R] {
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
