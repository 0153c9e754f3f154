//! Scenes from glTF files: the file's meshes as objects, its cameras and
//! its lights as Umbra's views (glTF's −Z forward, +Y up), a view framing
//! the scene where the file has none, and a scene file's mesh taken from
//! a glTF file.

use std::path::Path;

use glam::{DVec3, Vec3};

use super::{Check, Problem, SceneError};
use crate::input::limits::Limits;
use crate::world::gltf::{Gltf, GltfError, Lamp, Lens, Placed};
use crate::world::mesh::Mesh;
use crate::world::scene::{Camera, Light, Object, Orthographic, Perspective, Scene, point_text};

/// A glTF problem as a scene's: the file, the JSON path, the problem.
impl From<GltfError> for SceneError {
    fn from(e: GltfError) -> Self {
        Self { file: e.file, key: e.path, problem: Problem::Gltf(e.problem) }
    }
}

/// The largest far / near ratio a camera's f32 projection keeps: beyond
/// 2²⁵ its depth term `(far + near) / (far − near)` rounds to 1 in f32, and
/// no surface is told from the far plane (a render of such a camera
/// names its planes).
const DEPTH_RANGE: f64 = 33_554_432.0;

/// The image height a glTF scene is rendered at; its width follows the
/// camera's aspect ratio (16:9 where it gives none).
const HEIGHT: u32 = 540;

/// The sphere round a set of meshes: its centre and radius.
#[derive(Clone, Copy)]
struct Sphere {
    center: DVec3,
    radius: f64,
}

impl Sphere {
    /// The distances from `p` to the sphere's nearest and farthest points.
    fn reach(&self, p: DVec3) -> (f64, f64) {
        let d = (self.center - p).length();
        (d - self.radius, d + self.radius)
    }
}

/// f32 as the pipeline takes it, checked against the scene's range.
#[allow(clippy::cast_possible_truncation, reason = "the pipeline's f32; checked finite by the caller's checks")]
const fn f32_of(x: f64) -> f32 {
    x as f32
}

/// A view's eye, target and up in f32, the target far enough along
/// `forward` to stay apart from the eye in f32.
fn eye<T>(p: &Placed<T>, sphere: Sphere) -> (Vec3, Vec3, Vec3) {
    let reach = sphere.radius.max(p.position.length() * 1e-3).max(1e-3);
    (p.position.as_vec3(), (p.position + p.forward * reach).as_vec3(), p.up.as_vec3())
}

/// A problem with a view at `path`.
fn view_fault(path: &str, problem: String) -> (String, crate::world::gltf::GltfProblem) {
    (path.to_owned(), crate::world::gltf::GltfProblem::View(problem))
}

/// A field of view in degrees, within what Umbra's views take (1° to 170°).
fn fov(path: &str, what: &str, degrees: f64) -> Result<f32, (String, crate::world::gltf::GltfProblem)> {
    if (1.0..=170.0).contains(&degrees) {
        Ok(f32_of(degrees))
    } else {
        Err(view_fault(path, format!("{what} makes a field of view of {degrees:.1}°; Umbra's views take 1° to 170°")))
    }
}

/// Near and far for a view at `p` that the file leaves open: hugging the
/// scene, the near plane at least a thousandth of the far one.
fn hugging(sphere: Sphere, p: DVec3) -> (f64, f64) {
    let (nearest, farthest) = sphere.reach(p);
    let far = farthest * 1.01;
    (f64::max(nearest * 0.99, far * 1e-3), far)
}

/// A glTF camera as the scene's camera, and the aspect ratio it asks for.
fn camera(
    c: &Placed<Lens>,
    sphere: Sphere,
) -> Result<(Camera, Option<f32>), (String, crate::world::gltf::GltfProblem)> {
    let (position, target, up) = eye(c, sphere);
    match c.what {
        Lens::Perspective { yfov, znear, zfar, aspect } => {
            let fov_degrees = fov(&c.path, "yfov", f64::from(yfov).to_degrees())?;
            let far = zfar.unwrap_or_else(|| f32_of(hugging(sphere, c.position).1));
            if !(znear > 0.0 && far > znear) {
                return Err(view_fault(
                    &c.path,
                    format!("znear {znear} must be positive and below the far plane {far}"),
                ));
            }
            // The f32 depth of the camera pass tells surfaces apart only
            // while far / near stays within its 24 bits of mantissa.
            if f64::from(far) / f64::from(znear) > DEPTH_RANGE {
                return Err(view_fault(
                    &format!("{}.perspective.znear", c.path),
                    format!(
                        "znear {znear:e} is below the far plane {far} / 2^25 = {:.3e}: the camera's f32 depth cannot tell a surface from the far plane, and the view shows none; raise znear",
                        f64::from(far) / DEPTH_RANGE
                    ),
                ));
            }
            Ok((Camera::Perspective(Perspective { position, target, fov_degrees, near: znear, far, up }), aspect))
        }
        Lens::Orthographic { xmag, ymag, znear, zfar } => {
            if !(xmag > 0.0 && ymag > 0.0 && znear >= 0.0 && zfar > znear) {
                let problem =
                    format!("xmag {xmag} and ymag {ymag} must be positive, znear {znear} ≥ 0 and below zfar {zfar}");
                return Err(view_fault(&c.path, problem));
            }
            let view = Orthographic { position, target, extent: ymag, near: znear, far: zfar, up };
            Ok((Camera::Orthographic(view), Some(xmag / ymag)))
        }
    }
}

/// A `KHR_lights_punctual` light as one of the scene's: a spot light's
/// field of view twice its outer cone angle and its far plane at its range
/// (else past the scene); a directional light's map framing the scene.
fn light(l: &Placed<Lamp>, sphere: Sphere) -> Result<Light, (String, crate::world::gltf::GltfProblem)> {
    let (position, target, up) = eye(l, sphere);
    match l.what {
        Lamp::Spot { outer, range } => {
            let fov_degrees = fov(&l.path, "twice the outer cone angle", 2.0 * f64::from(outer).to_degrees())?;
            let (near, far) = hugging(sphere, l.position);
            if let Some(range) = range.filter(|&r| f64::from(r) <= sphere.reach(l.position).0.max(0.0)) {
                return Err(view_fault(
                    &format!("{}.range", l.path),
                    format!(
                        "range {range} ends before the nearest of the scene ({:.4} away): the light's map would receive nothing",
                        sphere.reach(l.position).0
                    ),
                ));
            }
            let far = range.map_or(far, f64::from);
            let near = near.min(far * 0.5);
            if !(near > 0.0 && far > near) {
                return Err(view_fault(
                    &l.path,
                    format!("the range {far} leaves no depth before the light's near plane"),
                ));
            }
            Ok(Light::Cone(Perspective { position, target, fov_degrees, near: f32_of(near), far: f32_of(far), up }))
        }
        Lamp::Directional => {
            let r = sphere.radius.max(1e-6);
            let position = sphere.center - l.forward * 2.0 * r;
            Ok(Light::Directional(
                Orthographic {
                    position: position.as_vec3(),
                    target: sphere.center.as_vec3(),
                    extent: f32_of(r * 1.01),
                    near: f32_of(r * 0.99),
                    far: f32_of(r * 3.01),
                    up,
                },
                crate::world::cascade::Cascades::ONE,
            ))
        }
    }
}

/// Every instance's meshes as one, each moved in turn.
fn merged(gltf: Gltf) -> Mesh {
    let mut all = Mesh::default();
    for i in gltf.instances {
        if all.positions.is_empty() && all.triangles.is_empty() {
            all = i.mesh;
        } else {
            all.append(&i.mesh);
        }
    }
    all
}

/// Every instance's bounds as the two corners of a mesh: what
/// [`Perspective::framing`] and [`sphere_of`] read, without a copy of the
/// scene.
fn bounds_of(gltf: &Gltf) -> Mesh {
    let corners =
        gltf.instances.iter().filter_map(|i| i.mesh.bounds()).reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)));
    Mesh { positions: corners.map(|(lo, hi)| vec![lo, hi]).unwrap_or_default(), ..Mesh::default() }
}

/// The sphere round a mesh's bounds.
fn sphere_of(mesh: &Mesh) -> Option<Sphere> {
    let (lo, hi) = mesh.bounds()?;
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    Some(Sphere { center: (lo + hi) / 2.0, radius: ((hi - lo).length() / 2.0).max(1e-9) })
}

impl Scene {
    /// A glTF file as a scene (`umbra render model.glb`): an object per
    /// mesh instance, solid where its mesh is closed and consistently
    /// wound; the camera `camera` names (a name, or an index into the
    /// file's cameras in the order of its node tree), else its first; its
    /// `KHR_lights_punctual` spot and directional lights. Where the file
    /// has no camera, or no light, a spot light that frames the scene
    /// stands in (from the front for a camera, from above for a light),
    /// and [`Scene::notes`] says so.
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the JSON path and the problem.
    pub fn of_gltf(path: &Path, camera_choice: Option<&str>, limits: &Limits) -> Result<Self, SceneError> {
        let c = Check { file: path };
        let gltf = Gltf::read(path, None, limits)?;
        let fault = |(key, problem)| SceneError { file: path.to_owned(), key, problem: Problem::Gltf(problem) };
        let objects = u64::try_from(gltf.instances.len()).unwrap_or(u64::MAX);
        limits.check_objects(objects).map_err(|l| c.err("nodes", Problem::Limit(l)))?;
        let all = bounds_of(&gltf);
        let sphere = sphere_of(&all).ok_or_else(|| c.err("meshes", Problem::NoVertices))?;
        let mut notes = Vec::new();
        let chosen = match camera_choice {
            None => gltf.cameras.first(),
            Some(asked) => Some(
                gltf.cameras
                    .iter()
                    .find(|k| k.name == asked || k.path == asked)
                    .or_else(|| asked.parse::<usize>().ok().and_then(|k| gltf.cameras.get(k)))
                    .ok_or_else(|| {
                        let known: Vec<String> =
                            gltf.cameras.iter().enumerate().map(|(k, c)| format!("{k} `{}`", c.name)).collect();
                        let known = if known.is_empty() { "none".to_owned() } else { known.join(", ") };
                        c.err(
                            "cameras",
                            Problem::Gltf(crate::world::gltf::GltfProblem::NoCamera { asked: asked.to_owned(), known }),
                        )
                    })?,
            ),
        };
        let (camera, aspect) = match chosen {
            Some(k) => camera(k, sphere).map_err(fault)?,
            None => {
                notes.push("the file has no camera: one framing the scene from the front stands in".to_owned());
                let view = Perspective::framing_along(&all, Vec3::new(0.0, 0.5, 1.0))
                    .ok_or_else(|| c.err("meshes", Problem::NoVertices))?;
                (Camera::Perspective(view), None)
            }
        };
        let mut lights = gltf.lights.iter().map(|l| light(l, sphere)).collect::<Result<Vec<_>, _>>().map_err(fault)?;
        if lights.is_empty() {
            let spot = Perspective::framing(&all).ok_or_else(|| c.err("meshes", Problem::NoVertices))?;
            notes.push(format!(
                "the file has no KHR_lights_punctual light: a spot light at {}, aimed at {}, casts the shadows (`--light-from X,Y,Z` moves it)",
                point_text(spot.position),
                point_text(spot.target)
            ));
            lights.push(Light::Spot(spot));
        } else {
            let names: Vec<String> =
                gltf.lights.iter().enumerate().map(|(k, l)| format!("{} `{}`", Scene::light_key(k), l.name)).collect();
            notes.push(format!("lights: {}", names.join(", ")));
        }
        // The width the camera's aspect ratio makes, within the limits (a
        // ratio past them is the file's camera's, named).
        let camera_key = chosen.map_or_else(|| "cameras".to_owned(), |k| k.path.clone());
        let wide = aspect.map_or(960.0, |a| (f64::from(a) * f64::from(HEIGHT)).round());
        if !(1.0..=f64::from(limits.max_image_side)).contains(&wide) {
            let problem = format!(
                "its aspect ratio {} makes an image {wide} pixels wide at {HEIGHT} high; the limit is 1 to {} (`--max-image-side`)",
                aspect.unwrap_or_default(),
                limits.max_image_side
            );
            return Err(c.err(&camera_key, Problem::Gltf(crate::world::gltf::GltfProblem::View(problem))));
        }
        #[allow(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "checked within 1..=the largest side"
        )]
        let width = wide as u32;
        let image = [width, HEIGHT];
        limits.check_image(width, HEIGHT).map_err(|l| c.err(&camera_key, Problem::Limit(l)))?;
        let mut objects: Vec<Object> = Vec::new();
        let mut ignored = crate::world::mesh::Ignored::default();
        for i in gltf.instances {
            ignored.segments += i.mesh.ignored.segments;
            ignored.points += i.mesh.ignored.points;
            if i.mesh.triangles.is_empty() {
                continue;
            }
            c.placed(&i.node, &i.mesh, false)?;
            let solid = i.mesh.is_closed();
            objects.push(Object { name: i.name, mesh: Mesh { ignored: Default::default(), ..i.mesh }, solid });
        }
        if let Some(first) = objects.first_mut() {
            first.mesh.ignored = ignored;
        }
        let name = path.file_stem().map_or_else(|| "gltf".into(), |s| s.to_string_lossy().into_owned());
        Ok(Self {
            name,
            objects,
            lights,
            camera,
            image,
            source: path.display().to_string(),
            camera_choice: camera_choice.map(str::to_owned),
            light_from: None,
            shadowless: Vec::new(),
            notes,
        })
    }
}

/// A scene file's `mesh = { gltf = "file.glb", node = "…" }`: the meshes
/// the file's scene places (at and under `node`, if given), in the file's
/// world space, as one mesh.
pub(super) fn gltf_mesh(
    c: &Check<'_>,
    key: &str,
    (file, node): (&str, Option<&str>),
    dir: &Path,
    limits: &Limits,
) -> Result<Mesh, SceneError> {
    let gltf = Gltf::read(&dir.join(file), node, limits).map_err(|e| c.err(key, Problem::GltfMesh(Box::new(e))))?;
    Ok(merged(gltf))
}
