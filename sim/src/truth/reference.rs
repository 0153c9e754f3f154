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
    epsilon: f64,
}

impl Reference {
    /// Build the acceleration structure over the scene's triangles (in the
    /// order the visibility unit numbers them).
    ///
    /// # Errors
    /// [`ReferenceError`] for an empty or unusable scene.
    pub fn new(scene: &[SceneTriangle]) -> Result<Self, ReferenceError> {
        let triangles: Vec<[DVec3; 3]> = scene.iter().map(|t| t.positions.map(|p| p.as_dvec3())).collect();
        let usable: Vec<&[DVec3; 3]> = triangles
            .iter()
            .filter(|t| t.iter().all(|p| p.is_finite()) && (t[1] - t[0]).cross(t[2] - t[0]).length() > 0.0)
            .collect();
        if usable.is_empty() {
            return Err(ReferenceError::Empty);
        }
        let mut vertices = Vec::with_capacity(usable.len() * 3);
        let mut indices = Vec::with_capacity(usable.len());
        for (i, t) in usable.iter().enumerate() {
            vertices.extend(t.iter().map(|p| Vector::new(p.x, p.y, p.z)));
            let base = u32::try_from(3 * i).map_err(|e| ReferenceError::Mesh(e.to_string()))?;
            indices.push([base, base + 1, base + 2]);
        }
        let (lo, hi) = usable
            .iter()
            .flat_map(|t| t.iter())
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let mesh = TriMesh::new(vertices, indices).map_err(|e| ReferenceError::Mesh(format!("{e:?}")))?;
        Ok(Self { mesh, triangles, epsilon: 1e-9 * (hi - lo).length().max(1.0) })
    }

    /// Whether the point `p` of a surface with normal `n` sees the light.
    /// `None` when the surface faces away from it.
    #[must_use]
    pub fn sees_light(&self, p: DVec3, n: DVec3, light: &LightSource) -> Option<bool> {
        let (to_light, distance) = light.towards(p);
        if n.dot(to_light) <= 0.0 {
            return None;
        }
        let origin = p + to_light * self.epsilon * 16.0;
        let ray = Ray::new(Vector::new(origin.x, origin.y, origin.z), Vector::new(to_light.x, to_light.y, to_light.z));
        let max = if distance.is_finite() { distance - self.epsilon * 32.0 } else { f64::MAX };
        Some(self.mesh.cast_local_ray(&ray, max.max(0.0), false).is_none())
    }

    /// The truth for every camera pixel, given the ids the visibility unit
    /// recorded and the camera (world to clip); `n × n` points per pixel for
    /// the area-averaged visibility. Background pixels are `None`. Rows run
    /// in parallel (each pixel is a pure function of the scene, so the
    /// result does not depend on the thread count); `progress` is ticked
    /// once per row.
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
                let tri = self.triangles.get(usize::try_from(id).ok()?).filter(|_| id != NO_TRIANGLE)?;
                let (px, py) = ((i % width as usize) as f64, (i / width as usize) as f64);
                let point = |sx: f64, sy: f64| -> Option<(DVec3, DVec3)> {
                    let ndc = |z: f64| {
                        let v = inverse * DVec4::new(2.0 * sx / w - 1.0, 1.0 - 2.0 * sy / h, z, 1.0);
                        v.truncate() / v.w
                    };
                    let (near, far) = (ndc(0.0), ndc(1.0));
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
                };
                let (p, nrm) = point(px + 0.5, py + 0.5)?;
                let centre = self.sees_light(p, nrm, light);
                let mut seen = 0u32;
                for j in 0..n {
                    for k in 0..n {
                        let s = (px + (f64::from(k) + 0.5) / f64::from(n), py + (f64::from(j) + 0.5) / f64::from(n));
                        if let Some((q, m)) = point(s.0, s.1) {
                            seen += u32::from(self.sees_light(q, m, light) == Some(true));
                        }
                    }
                }
                Some(PixelTruth {
                    faces_light: centre.is_some(),
                    lit: centre == Some(true),
                    visibility: f64::from(seen) / f64::from((n * n).max(1)),
                    light_cos: nrm.normalize_or_zero().dot(light.towards(p).0),
                })
            })
            .collect()
    }
}
