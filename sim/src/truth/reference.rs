//! Exact shadow truth in f64, by ray casting.
//!
//! For each camera pixel the pipeline's visible triangle is taken as given;
//! the camera ray through the pixel centre meets that triangle's plane (in
//! f64) at the surface point, and a ray from there towards the light is cast
//! against every triangle of the scene through a bounding-volume hierarchy
//! (`parry3d-f64`'s triangle mesh). A point whose surface faces away from
//! the light counts as shadowed, as shading makes it. The area-averaged
//! visibility repeats this for `n × n` points spread over the pixel, all on
//! the same triangle's plane.

use glam::{DMat4, DVec3, DVec4, Mat4};
use indicatif::ProgressBar;
use parry3d_f64::math::Vector;
use parry3d_f64::query::{Ray, RayCast};
use parry3d_f64::shape::TriMesh;
use rayon::prelude::*;
use umbra_core::NO_TRIANGLE;
use umbra_core::shade::SceneTriangle;

use crate::world::scene::LightSource;

/// Why the reference could not be built.
#[derive(Debug, thiserror::Error)]
pub enum ReferenceError {
    /// The scene has no usable triangle.
    #[error("the scene has no triangles to cast rays against")]
    Empty,
    /// The acceleration structure rejected the mesh.
    #[error("cannot build the ray-casting mesh: {0}")]
    Mesh(String),
}

/// The truth for one camera pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelTruth {
    /// The surface faces the light (the pixel is evaluated by the metrics).
    pub faces_light: bool,
    /// The surface point at the pixel centre sees the light.
    pub lit: bool,
    /// Fraction of the pixel's area that sees the light.
    pub visibility: f64,
    /// The cosine between the surface's geometric normal (the side the
    /// camera sees) and the direction to the light at the pixel centre:
    /// near 0 on a terminator, where the surface turns from the light.
    pub light_cos: f64,
}

/// The scene as rays see it.
pub struct Reference {
    mesh: TriMesh,
    triangles: Vec<[DVec3; 3]>,
    /// The object of each triangle of the ray-casting mesh (which leaves
    /// out degenerate triangles).
    objects: Vec<u32>,
    /// The scene's bounding box's diagonal (at least 1): farther than any
    /// two of its points lie apart.
    reach: f64,
}

impl core::fmt::Debug for Reference {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Reference").field("triangles", &self.triangles.len()).finish_non_exhaustive()
    }
}

impl Reference {
    /// Build the acceleration structure over the scene's triangles (in the
    /// order the visibility unit numbers them).
    ///
    /// # Errors
    /// [`ReferenceError`] for an empty or unusable scene.
    pub fn new(scene: &[SceneTriangle]) -> Result<Self, ReferenceError> {
        Self::with_objects(scene, &[])
    }

    /// The reference of `scene`: its triangles in the order the visibility
    /// unit numbers them, each with its object.
    ///
    /// # Errors
    /// [`ReferenceError`] for an empty or unusable scene.
    pub(crate) fn of(scene: &crate::world::scene::Scene) -> Result<Self, ReferenceError> {
        Self::with_objects(&scene.triangles(), &scene.triangle_objects())
    }

    /// Triangle `id` (the visibility unit's number), in f64.
    #[must_use]
    pub(crate) fn triangle(&self, id: u32) -> Option<&[DVec3; 3]> {
        self.triangles.get(usize::try_from(id).ok()?)
    }

    /// [`Reference::new`] with the object each triangle belongs to
    /// ([`Scene::triangle_objects`](crate::world::scene::Scene::triangle_objects);
    /// a triangle beyond `objects` is object 0): occluders are then told
    /// apart by object.
    ///
    /// # Errors
    /// [`ReferenceError`] for an empty or unusable scene.
    pub(crate) fn with_objects(scene: &[SceneTriangle], objects: &[u32]) -> Result<Self, ReferenceError> {
        let triangles: Vec<[DVec3; 3]> = scene.iter().map(|t| t.positions.map(|p| p.as_dvec3())).collect();
        let usable: Vec<(usize, &[DVec3; 3])> = triangles
            .iter()
            .enumerate()
            .filter(|(_, t)| t.iter().all(|p| p.is_finite()) && (t[1] - t[0]).cross(t[2] - t[0]).length() > 0.0)
            .collect();
        if usable.is_empty() {
            return Err(ReferenceError::Empty);
        }
        let mut vertices = Vec::with_capacity(usable.len() * 3);
        let mut indices = Vec::with_capacity(usable.len());
        for (i, (_, t)) in usable.iter().enumerate() {
            vertices.extend(t.iter().map(|p| Vector::new(p.x, p.y, p.z)));
            let base = u32::try_from(3 * i).map_err(|e| ReferenceError::Mesh(e.to_string()))?;
            indices.push([base, base + 1, base + 2]);
        }
        let (lo, hi) = usable
            .iter()
            .flat_map(|(_, t)| t.iter())
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let objects = usable.iter().map(|&(k, _)| objects.get(k).copied().unwrap_or(0)).collect();
        let mesh = TriMesh::new(vertices, indices).map_err(|e| ReferenceError::Mesh(format!("{e:?}")))?;
        Ok(Self { mesh, triangles, objects, reach: (hi - lo).length().max(1.0) })
    }

    /// The reference's tolerance: a billionth of the scene's size.
    fn epsilon(&self) -> f64 {
        1e-9 * self.reach
    }

    /// The ray from `from` towards `to` (a unit direction) and the
    /// segment's length; `None` for a segment of no length.
    fn segment(from: DVec3, to: DVec3) -> Option<(Ray, f64)> {
        let d = to - from;
        let length = d.length();
        let dir = d / length;
        (length.is_finite() && length > 0.0)
            .then(|| (Ray::new(Vector::new(from.x, from.y, from.z), Vector::new(dir.x, dir.y, dir.z)), length))
    }

    /// The object of the first surface on the segment from `from` to just
    /// short of `to` (by the reference's own tolerance): an occluder in
    /// front of a receiver at `to`, seen from `from`; `None` when nothing
    /// lies there.
    #[must_use]
    pub(crate) fn first_on(&self, from: DVec3, to: DVec3) -> Option<u32> {
        let (ray, length) = Self::segment(from, to).filter(|&(_, l)| l > self.epsilon() * 64.0)?;
        let hit = self.mesh.cast_local_ray_and_get_normal(&ray, length - self.epsilon() * 32.0, false)?;
        Some(self.object_of(hit.subshape))
    }

    /// The object of the first surface on the segment from `from` to `to`
    /// that lies in front of the plane through `on` with normal `normal`
    /// (on `from`'s side, by more than the reference's tolerance): a
    /// surface in that plane — the receiver's own, or one lying in it —
    /// is not in front, however grazing the segment.
    #[must_use]
    pub(crate) fn first_in_front(&self, (from, to): (DVec3, DVec3), (on, normal): (DVec3, DVec3)) -> Option<u32> {
        let normal = normal.try_normalize()?;
        let (ray, length) = Self::segment(from, to)?;
        let hit = self.mesh.cast_local_ray_and_get_normal(&ray, length, false)?;
        let at = ray.point_at(hit.time_of_impact);
        let gap = (DVec3::new(at.x, at.y, at.z) - on).dot(normal) * (from - on).dot(normal).signum();
        (gap > self.epsilon() * 64.0).then(|| self.object_of(hit.subshape))
    }

    /// Where the light is seen from `p`: its position, or for a
    /// directional light a point beyond the whole scene towards it.
    pub(crate) fn light_from(&self, p: DVec3, light: &LightSource) -> DVec3 {
        let (to_light, distance) = light.towards(p);
        p + to_light * if distance.is_finite() { distance } else { 2.0 * self.reach + p.length() }
    }

    /// The ray from point `p` towards the light, started just off the
    /// surface, and how far it may go before it reaches the light.
    fn towards_light(&self, p: DVec3, light: &LightSource) -> (Ray, f64) {
        let (to_light, distance) = light.towards(p);
        let origin = p + to_light * self.epsilon() * 16.0;
        let ray = Ray::new(Vector::new(origin.x, origin.y, origin.z), Vector::new(to_light.x, to_light.y, to_light.z));
        let max = if distance.is_finite() { distance - self.epsilon() * 32.0 } else { f64::MAX };
        (ray, max.max(0.0))
    }

    /// The object that hides point `p` from the light (`None` when the
    /// point sees it).
    #[must_use]
    pub(crate) fn occluder_of(&self, p: DVec3, light: &LightSource) -> Option<u32> {
        let (ray, max) = self.towards_light(p, light);
        let hit = self.mesh.cast_local_ray_and_get_normal(&ray, max, false)?;
        Some(self.object_of(hit.subshape))
    }

    /// Whether the point `p` of a surface with normal `n` sees the light.
    /// `None` when the surface faces away from it.
    #[must_use]
    pub(crate) fn sees_light(&self, p: DVec3, n: DVec3, light: &LightSource) -> Option<bool> {
        if n.dot(light.towards(p).0) <= 0.0 || !light.reaches(p) {
            return None;
        }
        let (ray, max) = self.towards_light(p, light);
        Some(self.mesh.cast_local_ray(&ray, max, false).is_none())
    }

    /// The object of the ray-casting mesh's triangle `t`.
    fn object_of(&self, t: u32) -> u32 {
        usize::try_from(t).ok().and_then(|t| self.objects.get(t)).copied().unwrap_or(0)
    }

    /// Whether a surface lies on the segment from `from` to just short of
    /// `to` ([`Reference::first_on`]).
    #[must_use]
    pub(crate) fn blocked(&self, from: DVec3, to: DVec3) -> bool {
        self.first_on(from, to).is_some()
    }

    /// The truth for every camera pixel, given the ids the visibility unit
    /// recorded and the camera (world to clip); `n × n` points per pixel for
    /// the area-averaged visibility. Background pixels are `None`. Rows run
    /// in parallel (each pixel is a pure function of the scene, so the
    /// result does not depend on the thread count); `progress` is ticked
    /// once per row. Once a stop is requested ([`crate::base::stop`]) the
    /// pixels left are `None`: the caller checks for the stop and drops
    /// the image.
    #[must_use]
    #[allow(clippy::too_many_arguments, reason = "the camera, the light and the sampling, each a separate choice")]
    pub fn image(
        &self,
        ids: &[u32],
        camera: &Mat4,
        width: u32,
        height: u32,
        light: &LightSource,
        n: u32,
        progress: &ProgressBar,
    ) -> Vec<Option<PixelTruth>> {
        let inverse: DMat4 = camera.as_dmat4().inverse();
        let (w, h) = (f64::from(width), f64::from(height));
        let row = width as usize;
        ids.par_chunks(row.max(1))
            .enumerate()
            .flat_map_iter(|(y, chunk)| {
                progress.inc(1);
                chunk.iter().enumerate().map(move |(x, &id)| (y * row + x, id))
            })
            .map(|(i, id)| {
                if crate::base::stop::requested() {
                    return None;
                }
                let tri = self.triangles.get(usize::try_from(id).ok()?).filter(|_| id != NO_TRIANGLE)?;
                let (px, py) = ((i % width as usize) as f64, (i / width as usize) as f64);
                let near_of = |sx: f64, sy: f64| camera_ray(&inverse, (sx, sy), (w, h)).0;
                let point = |sx: f64, sy: f64| surface_point(&inverse, (sx, sy), (w, h), tri);
                let (p, nrm) = point(px + 0.5, py + 0.5)?;
                let centre = self.sees_light(p, nrm, light);
                // Each point of the pixel's area on the triangle's plane:
                // whether it sees the light, and the camera ray's start.
                let samples: Vec<(bool, DVec3, Option<DVec3>)> = (0..n * n)
                    .map(|i| {
                        let s = (
                            px + (f64::from(i % n) + 0.5) / f64::from(n),
                            py + (f64::from(i / n) + 0.5) / f64::from(n),
                        );
                        let q = point(s.0, s.1);
                        let sees = q.is_some_and(|(q, m)| self.sees_light(q, m, light) == Some(true));
                        (sees, near_of(s.0, s.1), q.map(|(q, _)| q))
                    })
                    .collect();
                // Where the points disagree, the pixel straddles an edge:
                // a point the camera does not see on this plane (the plane
                // continued behind another surface at a crease) is left out.
                let mixed = samples.iter().any(|s| s.0 != samples[0].0);
                let counted: Vec<bool> = samples
                    .iter()
                    .filter(|(_, near, q)| !mixed || q.is_some_and(|q| !self.blocked(*near, q)))
                    .map(|s| s.0)
                    .collect();
                let seen = counted.iter().filter(|&&s| s).count();
                #[allow(clippy::cast_precision_loss, reason = "at most 256 points")]
                let visibility = if counted.is_empty() {
                    f64::from(u8::from(centre == Some(true)))
                } else {
                    seen as f64 / counted.len() as f64
                };
                Some(PixelTruth {
                    faces_light: centre.is_some(),
                    lit: centre == Some(true),
                    visibility,
                    light_cos: if light.reaches(p) { nrm.normalize_or_zero().dot(light.towards(p).0) } else { 0.0 },
                })
            })
            .collect()
    }
}

impl Reference {
    /// Each pixel's cosine to `light` at its surface point (the pixel
    /// centre's, on the triangle `ids` names), 0 for the background, for a
    /// surface facing away and for one the light does not reach: how a
    /// light that casts no shadow lights the picture.
    #[must_use]
    pub fn facing(&self, ids: &[u32], camera: &Mat4, (width, height): (u32, u32), light: &LightSource) -> Vec<f64> {
        let inverse: DMat4 = camera.as_dmat4().inverse();
        let (w, h) = (f64::from(width), f64::from(height));
        let row = (width as usize).max(1);
        ids.par_iter()
            .enumerate()
            .map(|(i, &id)| {
                let Some(tri) = self.triangles.get(usize::try_from(id).unwrap_or(usize::MAX)) else { return 0.0 };
                let centre = ((i % row) as f64 + 0.5, (i / row) as f64 + 0.5);
                surface_point(&inverse, centre, (w, h), tri).map_or(0.0, |(p, n)| {
                    if light.reaches(p) { n.normalize_or_zero().dot(light.towards(p).0).max(0.0) } else { 0.0 }
                })
            })
            .collect()
    }
}

/// The ray through screen point `(sx, sy)` of a `(w, h)` target seen
/// through `inverse`, the inverse of a view-projection (the camera's, or
/// the light's with the map as the target): its points on the near and
/// far planes.
#[must_use]
pub(crate) fn camera_ray(inverse: &DMat4, (sx, sy): (f64, f64), (w, h): (f64, f64)) -> (DVec3, DVec3) {
    let ndc = |z: f64| {
        let v = *inverse * DVec4::new(2.0 * sx / w - 1.0, 1.0 - 2.0 * sy / h, z, 1.0);
        v.truncate() / v.w
    };
    (ndc(0.0), ndc(1.0))
}

/// Where the camera ray through screen point `(sx, sy)` meets the plane of
/// triangle `tri`, and the plane's normal on the side the camera sees;
/// `None` for a ray along the plane.
#[must_use]
pub(crate) fn surface_point(
    inverse: &DMat4,
    (sx, sy): (f64, f64),
    (w, h): (f64, f64),
    tri: &[DVec3; 3],
) -> Option<(DVec3, DVec3)> {
    let (near, far) = camera_ray(inverse, (sx, sy), (w, h));
    let dir = far - near;
    let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    let denom = normal.dot(dir);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let t = normal.dot(tri[0] - near) / denom;
    let p = near + dir * t;
    // The side the camera sees.
    let n = if normal.dot(near - p) < 0.0 { -normal } else { normal };
    p.is_finite().then_some((p, n))
}
