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

mod blocks;
pub mod cascade;
mod divider;
mod interp;
pub mod stream;
mod unit;

use glam::{Mat4, Vec3};

use crate::config::ConfigError;
use crate::depth::{DepthFormat, PlaneZ};
use crate::grid::TileRect;
use crate::light_pass::NO_TRIANGLE;
use crate::probe::{Event, Probe};
use crate::shadow::{Built, Lookup, MapCoord, MapView, Shadow, ShadowConfig, TangentPlane};
use divider::Reciprocal;
use interp::Interp;
pub use unit::{MapUnit, MapUnitWith, ShadowUnit, SilhouetteUnit};

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
pub struct ShadeConfig {
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

/// What the shading unit writes for a pixel: the whole [`Shaded`] result,
/// or the part of it a caller asks for — [`Shadow`], the fraction alone,
/// 4 bytes rather than 40 (and the interpolated normal, which the fraction
/// does not need, is then not worked out).
pub trait PixelResult: Copy {
    /// The result of a pixel no triangle covers.
    const BACKGROUND: Self;
    /// Whether [`keep`](Self::keep) reads the shadow fraction and nothing
    /// else: then the unit may settle a block of pixels at once, without
    /// their light points ([`ShadowUnit::settle`]).
    const FRACTION_ONLY: bool = false;

    /// The part of a pixel's result kept.
    fn keep(shaded: Shaded) -> Self;
}

impl PixelResult for Shaded {
    const BACKGROUND: Self = Self::BACKGROUND;

    #[inline(always)]
    fn keep(shaded: Shaded) -> Self {
        shaded
    }
}

impl PixelResult for Shadow {
    const BACKGROUND: Self = Self::ZERO;
    const FRACTION_ONLY: bool = true;

    #[inline(always)]
    fn keep(shaded: Shaded) -> Self {
        shaded.shadow
    }
}

/// Entries of [`shade`]'s setup store (on the stack: small enough for a
/// microcontroller's).
pub const SETUP_STORE: usize = 16;

/// A 64-bit mix of the seed and the pixel (splitmix64's finaliser).
fn pixel_seed(seed: u64, px: u32, py: u32) -> u64 {
    let mut z = seed ^ (u64::from(px) << 32 | u64::from(py)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Shade every pixel: `ids` from the visibility unit, `out` receives one
/// result per pixel, row-major — the whole [`Shaded`], or the part of it
/// a [`PixelResult`] keeps.
///
/// # Errors
/// [`ConfigError::BufferLength`] when `ids` or `out` is not `width × height`.
pub fn shade<F: DepthFormat, S: TriangleSource, R: PixelResult, P: Probe>(
    cfg: &ShadeConfig,
    ids: &[u32],
    map: &MapView<'_, F>,
    scene: &S,
    out: &mut [R],
    probe: &mut P,
) -> Result<(), ConfigError> {
    let mut setups = [ShadeSetup::EMPTY; SETUP_STORE];
    let inputs = ShadeInputs { cfg, map, scene, unit: &MapUnit };
    shade_with(&inputs, ids, out, &mut setups, probe)
}

/// What a shading pass reads, whichever part of the image it shades: the
/// configuration, the map, the scene's triangles and the shadow unit
/// ([`shade_with`], [`shade_rect`]). The ids, the results, the setup
/// store and the probe are each call's own.
pub struct ShadeInputs<'a, F: DepthFormat, S, U> {
    /// The camera, the light and the shadow lookup's configuration.
    pub cfg: &'a ShadeConfig,
    /// The map the shadow unit reads.
    pub map: &'a MapView<'a, F>,
    /// The scene's triangles, by id.
    pub scene: &'a S,
    /// The shadow unit.
    pub unit: &'a U,
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
pub fn shade_with<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, R: PixelResult, P: Probe>(
    inputs: &ShadeInputs<'_, F, S, U>,
    ids: &[u32],
    out: &mut [R],
    setups: &mut [ShadeSetup],
    probe: &mut P,
) -> Result<(), ConfigError> {
    let whole = TileRect { x0: 0, y0: 0, x1: inputs.cfg.width, y1: inputs.cfg.height };
    shade_rect(inputs, whole, ids, out, setups, probe)
}

/// [`shade_with`] over one rectangle of the image (a tile of a camera pass
/// streamed by tile): `ids` and `out` are the rectangle's, row-major, and
/// every pixel keeps its place in the whole image, so the rectangle's
/// results are the bits the whole image has there.
///
/// # Errors
/// [`ConfigError::Window`] when `rect` is empty or leaves the image;
/// [`ConfigError::BufferLength`] when `ids` or `out` is not its size.
pub fn shade_rect<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, R: PixelResult, P: Probe>(
    inputs: &ShadeInputs<'_, F, S, U>,
    rect: TileRect,
    ids: &[u32],
    out: &mut [R],
    setups: &mut [ShadeSetup],
    probe: &mut P,
) -> Result<(), ConfigError> {
    let &ShadeInputs { cfg, map, scene, unit } = inputs;
    if let Some(missing) = U::Built::missing(&cfg.shadow, cfg.normals == Normals::Smooth) {
        return Err(ConfigError::ShadowNotBuilt { missing });
    }
    let TileRect { x0, y0, x1, y1 } = rect;
    if x0 > x1 || y0 > y1 || x1 > cfg.width || y1 > cfg.height {
        return Err(ConfigError::Window { x0, y0, width: x1.wrapping_sub(x0), height: y1.wrapping_sub(y0) });
    }
    // Saturating: on a 32-bit target the product of two `u32` sides can overflow.
    let texels = ((x1 - x0) as usize).saturating_mul((y1 - y0) as usize);
    for (buffer, found) in [("ids", ids.len()), ("out", out.len())] {
        if found != texels {
            return Err(ConfigError::BufferLength { buffer, expected: texels, found });
        }
    }
    let mut one = [ShadeSetup::EMPTY];
    let setups = if setups.is_empty() { &mut one[..] } else { setups };
    setups.fill(ShadeSetup::EMPTY);
    let light_inverse_transpose = cfg.light.inverse().transpose();
    let width = (x1 - x0) as usize;
    if width == 0 {
        return Ok(());
    }
    if R::FRACTION_ONLY && !P::EVENTS && blocks::settle(cfg) {
        blocks::shade(inputs, rect, (ids, out), setups, &light_inverse_transpose);
        return Ok(());
    }
    // The store is consulted when the id changes along a row; the source
    // is asked only when the store misses.
    let (mut run, mut interp): (u32, Option<&Interp>) = (NO_TRIANGLE, None);
    for (py, (ids, out)) in (y0..).zip(ids.chunks_exact(width).zip(out.chunks_exact_mut(width))) {
        for (px, (&id, o)) in (x0..).zip(ids.iter().zip(out.iter_mut())) {
            if id != run {
                run = id;
                interp = setup_of(cfg, map, scene, setups, id);
            }
            *o = match interp {
                Some(i) => {
                    probe.event(Event::PixelShaded { x: px, y: py });
                    R::keep(shade_pixel(cfg, map, unit, probe, &light_inverse_transpose, (px, py), i))
                }
                None => R::BACKGROUND,
            };
        }
    }
    Ok(())
}

/// The interpolator setup of triangle `id` from the store (direct-mapped
/// by id), set up from the scene when the store misses; `None` for no
/// triangle, or one the scene does not have.
#[inline]
fn setup_of<'s, F: DepthFormat, S: TriangleSource>(
    cfg: &ShadeConfig,
    map: &MapView<'_, F>,
    scene: &S,
    setups: &'s mut [ShadeSetup],
    id: u32,
) -> Option<&'s Interp> {
    if id == NO_TRIANGLE {
        return None;
    }
    let slot = setup_slot(id, setups.len());
    let entry = setups.get_mut(slot)?;
    if entry.0.as_ref().is_none_or(|c| c.id != id) {
        let tri = scene.triangle(id)?;
        entry.0 = Some(Interp::new::<F>(cfg, map, id, &tri));
    }
    entry.0.as_ref()
}

/// The entry of a direct-mapped setup store of `len` entries that holds
/// triangle `id`'s setup.
#[inline]
fn setup_slot(id: u32, len: usize) -> usize {
    id as usize % len
}

/// One pixel of [`shade_with`].
#[inline]
fn shade_pixel<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    cfg: &ShadeConfig,
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
        footprint: if U::Built::JITTERED && matches!(cfg.shadow.filter(), crate::shadow::Filter::Jittered(_)) {
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
        (Normals::Smooth, _) if U::Built::SMOOTH_TANGENTS => {
            let [x, y, zz, ww] = Interp::at_pixel(&interp.world, px, py);
            #[allow(clippy::cast_possible_truncation, reason = "a world point, as the scene gives it")]
            let p = Vec3::new((x / ww) as f32, (y / ww) as f32, (zz / ww) as f32);
            TangentPlane::new(p, normal, light_inverse_transpose).slope::<F>(&raster)
        }
        // Refused before shading.
        (Normals::Smooth, _) => None,
    };
    let s = unit.decide(map, cfg, &lookup, tangent, probe);
    Shaded { triangle: id, light: Some(LightPoint { z, ..point }), normal, shadow: s }
}

#[cfg(test)]
mod tests {
    use super::divider::Reciprocal;
    use super::interp::{Interp, LightForms};
    use crate::budget::{MAP_ONE, PLANE_FRACTION_BITS};
    use crate::depth::{D24, DepthFormat};

    fn div_shifted(n: i128, w: i128) -> Option<i64> {
        Reciprocal::new(w).div_shifted(n)
    }

    /// The two-division path gives the `i128` quotient (saturated to `i64`)
    /// for numerators of either sign, small and large denominators, and
    /// exact multiples.
    #[test]
    fn shifted_division_equals_the_wide_one() {
        let mut rng = oorandom::Rand64::new(0x5eed);
        let wide = |n: i128, w: i128| crate::round::saturate((n * i128::from(MAP_ONE)) / w);
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
        let coord = |n: i128| i32::try_from((n * i128::from(MAP_ONE) / w).clamp(i32::MIN.into(), i32::MAX.into())).ok();
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
