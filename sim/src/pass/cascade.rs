//! A directional light's cascades in the passes: each cascade's light
//! fitted to its slice of the view ([`Plan::new`]), and the camera pass's
//! choice of a cascade per pixel by its depth (the core's
//! [`CascadeSelect`]), with each pixel in a blend band reading two maps
//! ([`Picks`]). Each cascade's map is an ordinary map, drawn and tested
//! as one light's; the shading unit reads them pixel by pixel, each
//! against its pick (`shade_cascades`).

use glam::{Mat4, Vec3, Vec4};
use umbra_core::depth::DepthFormat;
use umbra_core::shade::cascade::{CascadeSelect, Cascaded, Pick, shade_cascaded};
use umbra_core::shade::{SceneTriangle, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, ShadowUnit};
use umbra_core::shadow::MapView;
use umbra_core::{D24, NO_TRIANGLE};
use umbra_core::{Probe, TileRect};

use super::PassError;
use super::camera::{CameraFrame, CameraImage, CameraOptions, shade_config, shade_setups};
use crate::world::cascade::{Cascades, Fit};
use crate::world::scene::{Camera, Light, Orthographic, look_at};

/// Texels kept free at each side of a fitted cascade's map, so that a
/// filter's taps round a point at the edge of what the cascade holds
/// still read the map (the widest built-in filter reaches 2 texels, a
/// bilinear tap 1).
pub const MARGIN_TEXELS: u32 = 4;

/// The camera's view direction and its basis: where it looks from, the
/// unit vector it looks along, and its right and up vectors.
fn basis(camera: &Camera) -> (Vec3, Vec3, Vec3, Vec3) {
    let (eye, target, up) = match camera {
        Camera::Perspective(p) => (p.position, p.target, p.up),
        Camera::Orthographic(o) => (o.position, o.target, o.up),
    };
    let to_world = look_at(eye, target, up).inverse();
    let forward = to_world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
    (eye, forward, to_world.transform_vector3(Vec3::X), to_world.transform_vector3(Vec3::Y))
}

/// The point `d` along the camera's view axis.
#[must_use]
pub fn on_axis(camera: &Camera, d: f32) -> Vec3 {
    let (eye, forward, _, _) = basis(camera);
    eye + forward * d
}

/// The eight corners of the camera's view (for an image of `aspect =
/// width / height`) between the view distances `d0` and `d1`.
#[must_use]
pub fn slice_corners(camera: &Camera, aspect: f32, d0: f32, d1: f32) -> [Vec3; 8] {
    let (eye, forward, right, up) = basis(camera);
    let half = |d: f32| match camera {
        Camera::Perspective(p) => {
            let h = d * (p.fov_degrees.to_radians() / 2.0).tan();
            (h * aspect, h)
        }
        Camera::Orthographic(o) => (o.extent * aspect, o.extent),
    };
    let mut corners = [Vec3::ZERO; 8];
    for (k, corner) in corners.iter_mut().enumerate() {
        let d = if k < 4 { d0 } else { d1 };
        let (w, h) = half(d);
        let sx = if k & 1 == 0 { -1.0 } else { 1.0 };
        let sy = if k & 2 == 0 { -1.0 } else { 1.0 };
        *corner = eye + forward * d + right * (sx * w) + up * (sy * h);
    }
    corners
}

/// `light` moved across its own direction and narrowed to the least
/// square that holds `points` (within its own square: what it did not
/// cover, no cascade does), with [`MARGIN_TEXELS`] free at each side of
/// a `side`-texel map; its direction, depth range and up stay. `None`
/// for no point inside the light's square.
#[must_use]
pub fn fit(light: &Orthographic, points: impl IntoIterator<Item = Vec3>, side: u32) -> Option<Orthographic> {
    let view: Mat4 = look_at(light.position, light.target, light.up);
    let e = light.extent;
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::INFINITY), glam::Vec2::splat(f32::NEG_INFINITY));
    for p in points {
        let q = view.transform_point3(p).truncate().clamp(glam::Vec2::splat(-e), glam::Vec2::splat(e));
        lo = lo.min(q);
        hi = hi.max(q);
    }
    if !(lo.x <= hi.x && lo.y <= hi.y) {
        return None;
    }
    let centre = (lo + hi) / 2.0;
    let half = ((hi - lo) / 2.0).max_element().max(e * 1e-6);
    // The margin's texels out of the side.
    #[allow(clippy::cast_precision_loss, reason = "a map side below 2^14")]
    let free = side as f32 / (side.saturating_sub(2 * MARGIN_TEXELS).max(1)) as f32;
    let across = view.inverse().transform_vector3(centre.extend(0.0));
    Some(Orthographic {
        position: light.position + across,
        target: light.target + across,
        extent: (half * free).min(e * free),
        ..*light
    })
}

/// One directional light's cascades, planned for a view: each cascade's
/// light, its map side, the view distances that bound the slices, and the
/// selector's registers.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Each cascade's light: the scene's, fitted to its slice.
    pub lights: Vec<Light>,
    /// Each cascade's map side.
    pub sides: Vec<u32>,
    /// The view distances bounding the slices, `count + 1` of them.
    pub distances: Vec<f32>,
    /// The selector's split and band registers.
    pub select: CascadeSelect,
}

/// The visibility pass a plan reads: the camera's matrix, the image's
/// size, and its depth and ids.
#[derive(Clone, Copy, Debug)]
pub struct Seen<'a> {
    /// World to camera clip space.
    pub camera: Mat4,
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// The depth buffer, row-major, in [`D24`].
    pub depth: &'a [u32],
    /// The visible triangle per pixel.
    pub ids: &'a [u32],
}

impl Seen<'_> {
    /// The depth-buffer value at view distance `d` along the camera's axis.
    fn depth_at(&self, camera: &Camera, d: f32) -> u32 {
        let c = self.camera * on_axis(camera, d).extend(1.0);
        D24::quantize(if c.w > 0.0 { c.z / c.w } else { 0.0 })
    }

    /// Each visible pixel's world point, from its depth (f32: a fit needs
    /// no more) and its view distance.
    fn samples(&self, camera: &Camera) -> Vec<(Vec3, f32)> {
        let inverse = self.camera.inverse();
        let (eye, ahead) = (on_axis(camera, 0.0), on_axis(camera, 1.0) - on_axis(camera, 0.0));
        let (w, h) = self.size;
        #[allow(
            clippy::cast_precision_loss,
            clippy::cast_possible_truncation,
            reason = "pixel coordinates and 24-bit depths, for a fit"
        )]
        let point = |k: usize, z: u32| {
            let (x, y) = ((k % w as usize) as f32 + 0.5, (k / w as usize) as f32 + 0.5);
            let ndc = Vec4::new(2.0 * x / w as f32 - 1.0, 1.0 - 2.0 * y / h as f32, D24::unquantize(z) as f32, 1.0);
            let p = inverse * ndc;
            let p = p.truncate() / p.w;
            (p, (p - eye).dot(ahead))
        };
        let covered = self.ids.iter().zip(self.depth).enumerate().filter(|(_, (id, _))| **id != NO_TRIANGLE);
        covered.map(|(k, (_, &z))| point(k, z)).collect()
    }
}

impl Plan {
    /// The plan of `cascades` for the directional `light` seen by
    /// `camera` in `seen`, each map `map_size` texels a side unless the
    /// cascades give their own.
    ///
    /// # Errors
    /// [`PassError::Config`] for selector registers the core refuses.
    pub fn new(
        (light, cascades): (&Orthographic, &Cascades),
        camera: &Camera,
        seen: &Seen<'_>,
        map_size: u32,
    ) -> Result<Self, PassError> {
        let (near, far) = camera.planes();
        #[allow(clippy::cast_precision_loss, reason = "an aspect ratio")]
        let aspect = seen.size.0 as f32 / seen.size.1.max(1) as f32;
        let samples = if cascades.fit == Fit::Samples { seen.samples(camera) } else { Vec::new() };
        // Sample distribution: the depth range narrowed to the visible samples'.
        let range = samples.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), s| (lo.min(s.1), hi.max(s.1)));
        let (near, far) = if range.0 < range.1 { (range.0.max(near), range.1.min(far)) } else { (near, far) };
        // Given splits outside a narrowed range leave their cascades empty.
        let mut distances = cascades.distances(near, far);
        for k in 1..distances.len() {
            distances[k] = distances[k].clamp(distances[k - 1], far);
        }
        let n = cascades.count();
        let sides: Vec<u32> = (0..n).map(|c| cascades.side(c, map_size)).collect();
        let mut lights = Vec::with_capacity(n);
        for (c, d) in distances.windows(2).enumerate() {
            let inside: Vec<Vec3> = samples.iter().filter(|s| (d[0]..=d[1]).contains(&s.1)).map(|s| s.0).collect();
            let fitted = if inside.is_empty() {
                fit(light, slice_corners(camera, aspect, d[0], d[1]), sides[c])
            } else {
                fit(light, inside, sides[c])
            };
            lights.push(Light::Directional(fitted.unwrap_or(*light), Cascades::ONE));
        }
        let splits: Vec<u32> = distances[1..n].iter().map(|&d| seen.depth_at(camera, d)).collect();
        let bands: Vec<u32> = distances
            .windows(2)
            .take(n - 1)
            .map(|d| seen.depth_at(camera, d[1] - cascades.blend * (d[1] - d[0])))
            .collect();
        // Splits closer than a depth-buffer step apart are equal: the
        // cascade between them is empty.
        let mut registers = (Vec::with_capacity(n - 1), Vec::with_capacity(n - 1));
        for (&s, &b) in splits.iter().zip(&bands) {
            let previous = registers.0.last().copied().unwrap_or(0);
            registers.0.push(s.max(previous));
            registers.1.push(b.clamp(previous, s.max(previous)));
        }
        let select = CascadeSelect::new(&registers.0, &registers.1)?;
        Ok(Self { lights, sides, distances, select })
    }
}

/// Each pixel's pick: the cascade it reads, and the next's weight in a
/// blend band.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picks(Vec<Pick>);

impl Picks {
    /// The selector's pick for each pixel of `seen`.
    #[must_use]
    pub fn new(select: &CascadeSelect, seen: &Seen<'_>) -> Self {
        Self(seen.depth.iter().map(|&z| select.pick(z)).collect())
    }

    /// Each pixel's cascade.
    #[must_use]
    pub fn cascades(&self) -> Vec<u8> {
        self.0.iter().map(|p| p.cascade).collect()
    }

    /// Whether any pixel lies in a blend band.
    #[must_use]
    pub fn blends(&self) -> bool {
        self.0.iter().any(|p| p.next_weight.is_some())
    }
}

/// A cascaded light's shading over `frame`'s last visibility pass:
/// each pixel against the cascade the selector `select` picks for its
/// depth (the core's [`shade_cascaded`](umbra_core::shade::cascade::shade_cascaded)),
/// cascade `c`'s map `views[c]` drawn through `lights[c]` and read
/// through `units[c]`, bound as map `bound[c]`; the scene's
/// `Scene::triangles` beside them. The light's image, and, when `own`,
/// each pixel as its own cascade shaded it before a blend band mixed it.
///
/// # Errors
/// As the camera pass's, and [`PassError::Config`] for inputs of different
/// lengths.
#[allow(clippy::too_many_arguments, reason = "each cascade's map, light and unit, the selector, the probe")]
pub(crate) fn shade_cascades<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    frame: &mut CameraFrame,
    (lights, triangles): (&[Mat4], &[SceneTriangle]),
    (views, units): (&[MapView<'_, F>], &[U]),
    (select, bound): (&umbra_core::shade::cascade::CascadeSelect, &[u16]),
    options: &CameraOptions,
    own: bool,
    probe: &mut P,
) -> Result<(CameraImage, Option<Vec<Shaded>>), PassError> {
    let ((ids, z), store, camera, size) = frame.for_shading();
    let configs: Vec<ShadeConfig> = lights.iter().map(|&l| shade_config(l, camera, options)).collect();
    let source = |id: u32| triangles.get(id as usize).copied();
    let each: Vec<ShadeInputs<'_, F, _, U>> = configs
        .iter()
        .zip(views)
        .zip(units)
        .map(|((cfg, map), unit)| ShadeInputs { cfg, map, scene: &source, unit })
        .collect();
    if each.len() != lights.len() {
        return Err(umbra_core::ConfigError::Cascades { splits: lights.len(), bands: each.len() }.into());
    }
    let mut pixels = vec![Shaded::BACKGROUND; ids.len()];
    let mut unmixed = own.then(|| vec![Shaded::BACKGROUND; ids.len()]);
    store.resize(lights.len() * shade_setups(ids, size.0), ShadeSetup::EMPTY);
    let rect = TileRect { x0: 0, y0: 0, x1: size.0, y1: size.1 };
    let cascaded = Cascaded { each: &each, bound, select };
    shade_cascaded(&cascaded, rect, (ids, z), (&mut pixels, unmixed.as_deref_mut()), store, probe)?;
    Ok((CameraImage { width: size.0, height: size.1, pixels, camera }, unmixed))
}
