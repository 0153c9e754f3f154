//! Scene files: TOML naming meshes (OBJ files, the shared meshes by name,
//! procedural generators), per-object transforms, solid/open flags, lights,
//! the camera and the image size — validated, every error naming the file,
//! the key and the problem.
//!
//! ```toml
//! name = "sphere over a wall"
//! image = [960, 540]
//!
//! [camera]
//! position = [0.0, 2.0, 6.0]
//! target = [0.0, 1.0, 0.0]
//! fov = 50.0
//! near = 0.5
//! far = 30.0
//!
//! [[lights]]
//! kind = "spot"          # or "directional" with `extent` instead of `fov`
//! shadows = true         # optional: `false` lights the picture, casts no shadow
//! position = [-5.0, 3.0, 2.0]
//! target = [0.0, 1.0, 0.0]
//! fov = 60.0
//! near = 1.0
//! far = 20.0
//!
//! [[objects]]
//! name = "ball"
//! mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.6, stacks = 24, slices = 48 } }
//! translate = [0.0, 0.0, 0.0]  # optional, as are `rotate` (degrees about x, y, z) and `scale`
//! solid = true                 # optional: detected from the mesh's closedness
//! ```
//!
//! Meshes: `obj = "path"` (relative to the scene file), `shared = "bunny"`
//! (from `../shared/meshes/` of the working directory, or `$UMBRA_MESHES`),
//! `box`, `quad`, `sphere`, `torus`, `table`, `sheet`, `figure`.

use crate::input::exact::Exact;
use std::path::{Path, PathBuf};

use glam::{EulerRot, Mat4, Quat, Vec3};

use crate::input::kind::FileKind;
use crate::input::limits::{FileError, LimitError, Limits};
use crate::world::mesh::MeshError;
use crate::world::scene::{Camera, Object, Scene};
use meshes::{build_mesh, generated_triangles};
use schema::{Check, LightFile, MeshFile, SceneFile};

mod gltf;
mod meshes;
mod schema;

/// The bundled scenes, by name: the papers' set-ups, built procedurally.
pub const BUNDLED: [(&str, &str); 16] = [
    ("table-and-sphere", include_str!("../../../../scenes/table-and-sphere.toml")),
    ("wang-molnar-4", include_str!("../../../../scenes/wang-molnar-4.toml")),
    ("reeves-sphere", include_str!("../../../../scenes/reeves-sphere.toml")),
    ("weiskopf-l", include_str!("../../../../scenes/weiskopf-l.toml")),
    ("weiskopf-l-boxes", include_str!("../../../../scenes/weiskopf-l-boxes.toml")),
    ("double-torus", include_str!("../../../../scenes/double-torus.toml")),
    ("thin", include_str!("../../../../scenes/thin.toml")),
    ("open-sheet", include_str!("../../../../scenes/open-sheet.toml")),
    ("crowd", include_str!("../../../../scenes/crowd.toml")),
    ("crowd-zoom", include_str!("../../../../scenes/crowd-zoom.toml")),
    ("crowd-overhead", include_str!("../../../../scenes/crowd-overhead.toml")),
    ("crowd-grazing", include_str!("../../../../scenes/crowd-grazing.toml")),
    ("grazing", include_str!("../../../../scenes/grazing.toml")),
    ("street", include_str!("../../../../scenes/street.toml")),
    ("factory", include_str!("../../../../scenes/factory.toml")),
    ("quad", include_str!("../../../../scenes/quad.toml")),
];

/// Largest magnitude of a vertex coordinate once placed (2⁴⁰): the
/// triangle setup's edge functions multiply three coordinate differences,
/// which stay finite in f32 below (2·2⁴⁰)³ = 2¹²³.
pub(crate) const MAX_COORDINATE: f32 = 1_099_511_627_776.0;

/// Largest procedural subdivision count.
pub(crate) const MAX_SUBDIVISION: u32 = 1024;

/// What is wrong with a scene file.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {key}: {problem}")]
pub struct SceneError {
    /// The scene file.
    pub file: PathBuf,
    /// The key, as a dotted path (`objects[2].mesh`).
    pub key: String,
    /// What is wrong.
    pub problem: Problem,
}

/// The kinds of problem a scene file can have.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Problem {
    /// The file cannot be read.
    #[error("cannot read: {0}")]
    Read(std::io::Error),
    /// The file is another kind than a scene file.
    #[error("{} (not a scene file): {}", .0.what(), .0.read_by())]
    Kind(FileKind),
    /// Not valid TOML, an unknown key, or a value of the wrong type.
    #[error("{0}")]
    Syntax(String),
    /// A number is NaN, infinite, or of magnitude 10³⁰ or more (beyond what
    /// the f32 vertex unit can transform without overflow).
    #[error("{value} is not a finite number below 1e30 in magnitude")]
    NonFinite {
        /// The value.
        value: f64,
    },
    /// `near` is not below `far`, or not positive, in the f32 the pipeline
    /// uses (a near plane of 1e-50 is 0 there).
    #[error("near {near} must be positive and below far {far} in f32, as the pipeline computes")]
    NearFar {
        /// Near.
        near: f64,
        /// Far.
        far: f64,
    },
    /// A view whose position is its target in the f32 the pipeline uses:
    /// it looks nowhere.
    #[error("the position {position:?} is the target (in f32, as the pipeline computes): the view looks nowhere")]
    LooksNowhere {
        /// The position, f32.
        position: [f32; 3],
    },
    /// A mesh file that holds no vertex.
    #[error("the mesh has no vertices")]
    NoVertices,
    /// A box's (or an ell's) `max` corner not beyond its `min` corner on
    /// some axis.
    #[error(
        "max.{axis} {max} is not above min.{axis} {min} (in f32, as the pipeline computes): `min` and `max` are opposite corners, each of max's coordinates above min's"
    )]
    Corners {
        /// `x`, `y` or `z`.
        axis: char,
        /// `min` on that axis.
        min: f32,
        /// `max` on that axis.
        max: f32,
    },
    /// A size is zero, negative or absurd.
    #[error("{value} is outside {min}..={max}")]
    Size {
        /// The value.
        value: f64,
        /// Smallest allowed.
        min: f64,
        /// Largest allowed.
        max: f64,
    },
    /// The mesh file is missing or malformed.
    #[error(transparent)]
    Mesh(MeshError),
    /// No shared mesh by that name.
    #[error(
        "no shared mesh `{name}` in {folder}: shared meshes are third-party OBJ files laid out beside the checkout, not shipped with it; set UMBRA_MESHES to the folder that holds them, or use `obj = \"file.obj\"` or a generator"
    )]
    UnknownShared {
        /// The name asked for.
        name: String,
        /// Where it was looked for.
        folder: PathBuf,
    },
    /// An open mesh was marked solid.
    #[error("the mesh is open (not closed and consistently wound), so it cannot be solid")]
    OpenMarkedSolid,
    /// The path is a directory, a device or a pipe.
    #[error("not a regular file")]
    NotAFile,
    /// The file, the image or the scene's triangles are beyond the [`Limits`].
    #[error(transparent)]
    Limit(LimitError),
    /// A vertex, as placed in the scene, beyond `MAX_COORDINATE` (or
    /// not finite): the f32 vertex and setup units would overflow.
    #[error(
        "vertex {vertex} is at {position:?} once placed, beyond ±{MAX_COORDINATE:e} (the f32 pipeline's products of coordinates would overflow)"
    )]
    Coordinate {
        /// The vertex, from 0 in the mesh's order.
        vertex: usize,
        /// Where it lands, f32.
        position: [f32; 3],
    },
    /// A generated shape with a triangle of no area once placed: its
    /// sizes are too small for its position in f32.
    #[error(
        "triangle {triangle} has no area once placed in f32: the shape's sizes are too small for where it stands (or for the scale)"
    )]
    Degenerate {
        /// The triangle, from 0 in the mesh's order.
        triangle: usize,
    },
    /// An `arrays` mesh's triangle names a vertex it does not have.
    #[error("triangle {triangle} names vertex {vertex}, but the mesh has {vertices} vertices")]
    BadIndex {
        /// The triangle, from 0.
        triangle: usize,
        /// The vertex it names.
        vertex: u32,
        /// The vertices there are.
        vertices: usize,
    },
    /// The glTF file is malformed, or holds what Umbra cannot take.
    #[error(transparent)]
    Gltf(crate::world::gltf::GltfProblem),
    /// A glTF file a mesh names is malformed (its file and JSON path named).
    #[error(transparent)]
    GltfMesh(Box<crate::world::gltf::GltfError>),
    /// `--camera` for a scene that has no cameras to choose from.
    #[error("`--camera {0}` chooses among a glTF file's cameras; this scene has one camera")]
    CameraChoice(String),
    /// A scene needs at least one light and one object.
    #[error("a scene needs at least one {0}")]
    Missing(&'static str),
}

/// Where shared meshes are looked for.
#[must_use]
pub fn shared_meshes() -> PathBuf {
    std::env::var_os("UMBRA_MESHES").map_or_else(|| PathBuf::from("../shared/meshes"), PathBuf::from)
}

impl Scene {
    /// Load and validate a scene file within `limits` (the file's size, the
    /// image and the triangles of every mesh, counted before any is built).
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key and the problem.
    pub fn load(file: &Path, limits: &Limits) -> Result<Self, SceneError> {
        let c = Check { file };
        let bytes = limits.read_text_file(file).map_err(|e| {
            c.err(
                "(file)",
                match e {
                    FileError::Io(e) => Problem::Read(e),
                    FileError::NotAFile => Problem::NotAFile,
                    FileError::Limit(l) => Problem::Limit(l),
                },
            )
        })?;
        let mut scene = Self::parse_bytes(&bytes, file, limits)?;
        scene.source = file.display().to_string();
        Ok(scene)
    }

    /// Parse and validate the bytes of a scene file within `limits`; bytes
    /// that are not UTF-8 are an error naming the line.
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key and the problem.
    pub fn parse_bytes(bytes: &[u8], file: &Path, limits: &Limits) -> Result<Self, SceneError> {
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let before = bytes.get(..e.valid_up_to()).unwrap_or_default();
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            Check { file }
                .err(format!("line {line}"), Problem::Syntax(format!("not UTF-8 text at byte {}", e.valid_up_to())))
        })?;
        if let Some(kind) = FileKind::of(bytes).filter(|&k| k != FileKind::Scene) {
            return Err(Check { file }.err("(file)", Problem::Kind(kind)));
        }
        Self::parse(text, file, limits)
    }

    /// The scene file `name` when it is one (or names one: a path with a
    /// folder or a `.toml` extension, which then must exist), or else the
    /// bundled scene of that name; within `limits` either way.
    ///
    /// ```
    /// use umbra_sim::{Limits, Scene};
    /// let table = Scene::open("table-and-sphere", &Limits::DEFAULT)?;
    /// assert_eq!(table.image, [960, 540]);
    /// let err = Scene::open("no-such-scene.toml", &Limits::DEFAULT).unwrap_err();
    /// assert!(err.to_string().contains("no-such-scene.toml"));
    /// # Ok::<(), umbra_sim::world::scene_file::SceneError>(())
    /// ```
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key and the problem.
    pub fn open(name: &str, limits: &Limits) -> Result<Self, SceneError> {
        Self::open_with_camera(name, None, limits)
    }

    /// [`Scene::open`], and for a glTF file (`.gltf` or `.glb`,
    /// [`Scene::of_gltf`]) the camera `camera` names; a scene of another
    /// kind refuses a `camera`.
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key and the problem.
    pub fn open_with_camera(name: &str, camera: Option<&str>, limits: &Limits) -> Result<Self, SceneError> {
        let path = Path::new(name);
        let extension = path.extension().map(|e| e.to_ascii_lowercase());
        if extension.as_ref().is_some_and(|e| e == "gltf" || e == "glb") {
            return Self::of_gltf(path, camera, limits);
        }
        if let Some(camera) = camera {
            return Err(Check { file: path }.err("--camera", Problem::CameraChoice(camera.to_owned())));
        }
        let names_a_file = extension.is_some_and(|e| e == "toml") || path.components().count() > 1;
        if path.is_file() || names_a_file {
            return Self::load(path, limits);
        }
        Self::from_bundle(name, limits)
    }

    /// One OBJ mesh as a scene (`umbra depth --mesh`): the mesh where it
    /// is, not solid, seen by a spot light that frames it
    /// ([`Perspective::framing`](crate::world::scene::Perspective::framing)),
    /// the camera at the light. Checked as a scene file's mesh is: every
    /// vertex finite and within reach of the pipeline's f32 products.
    ///
    /// # Errors
    /// [`SceneError`] naming the file and `mesh` (or a vertex of it).
    pub fn of_obj(path: &Path, limits: &Limits) -> Result<Self, SceneError> {
        use crate::world::scene::{Light, Object, Perspective};
        let c = Check { file: path };
        let mesh = crate::world::mesh::Mesh::load_obj(path, limits).map_err(|e| c.err("mesh", Problem::Mesh(e)))?;
        c.placed("mesh", &mesh, false)?;
        let light = Perspective::framing(&mesh).ok_or_else(|| c.err("mesh", Problem::NoVertices))?;
        let name = path.file_stem().map_or_else(|| "mesh".into(), |s| s.to_string_lossy().into_owned());
        Ok(Self {
            name: name.clone(),
            objects: vec![Object { name, mesh, solid: false }],
            lights: vec![Light::Spot(light)],
            camera: Camera::Perspective(light),
            image: [512, 512],
            source: path.display().to_string(),
            camera_choice: None,
            light_from: None,
            shadowless: Vec::new(),
            notes: Vec::new(),
        })
    }

    /// One of the bundled scenes by name (see [`BUNDLED`]).
    ///
    /// # Errors
    /// [`SceneError`] with key `(name)` for an unknown name.
    pub fn bundled(name: &str) -> Result<Self, SceneError> {
        Self::from_bundle(name, &Limits::DEFAULT)
    }

    /// [`Scene::bundled`] within `limits`.
    fn from_bundle(name: &str, limits: &Limits) -> Result<Self, SceneError> {
        let file = PathBuf::from(format!("scenes/{name}.toml"));
        match BUNDLED.iter().find(|(n, _)| *n == name) {
            Some((_, text)) => {
                let mut scene = Self::parse(text, &file, limits)?;
                scene.source = name.to_owned();
                Ok(scene)
            }
            None => Err(Check { file: &file }.err(
                "(name)",
                Problem::Syntax(match umbra_core::spelling::closest(name, BUNDLED.iter().map(|(n, _)| *n)) {
                    Some(near) => format!("no bundled scene `{name}`: did you mean `{near}`?"),
                    None => format!("no bundled scene `{name}`; there are {}", BUNDLED.map(|(n, _)| n).join(", ")),
                }),
            )),
        }
    }

    /// Parse and validate scene text within `limits`; `file` names it in
    /// errors and anchors relative mesh paths.
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key and the problem.
    pub fn parse(text: &str, file: &Path, limits: &Limits) -> Result<Self, SceneError> {
        let c = Check { file };
        let parsed: SceneFile = toml::from_str(text).map_err(|e| {
            let key = e.span().map_or_else(|| "(file)".to_owned(), |s| crate::input::at_line(text, s.start));
            c.err(key, Problem::Syntax(e.message().trim().to_owned()))
        })?;
        crate::input::format::SCENE
            .stated(parsed.format.map(i64::from))
            .map_err(|e| c.err("format", Problem::Syntax(e)))?;
        // Whole pixels (integers, read as such); then the limits, which
        // name themselves.
        let image = parsed.image.0;
        for (k, &side) in image.iter().enumerate() {
            c.range(&format!("image[{k}]"), f64::from(side), 1.0, f64::from(u32::MAX))?;
        }
        limits.check_image(image[0], image[1]).map_err(|l| c.err("image", Problem::Limit(l)))?;
        let camera = c.view("camera", &parsed.camera)?;
        if parsed.lights.is_empty() {
            return Err(c.err("lights", Problem::Missing("light")));
        }
        if !parsed.lights.iter().any(LightFile::casts) {
            return Err(c.err("lights", Problem::Missing("light that casts shadows (`shadows = false` on every one)")));
        }
        let (mut lights, mut shadowless) = (Vec::new(), Vec::new());
        for (i, l) in parsed.lights.iter().enumerate() {
            let key = format!("lights[{i}]");
            let into = if l.casts() { &mut lights } else { &mut shadowless };
            into.push(c.light(&key, l)?);
        }
        if parsed.objects.is_empty() {
            return Err(c.err("objects", Problem::Missing("object")));
        }
        let objects = u64::try_from(parsed.objects.len()).unwrap_or(u64::MAX);
        limits.check_objects(objects).map_err(|l| c.err("objects", Problem::Limit(l)))?;
        // Every generator's triangles, counted before any mesh is built.
        let mut generated = 0u64;
        for (i, o) in parsed.objects.iter().enumerate() {
            generated = generated.saturating_add(generated_triangles(&c, &format!("objects[{i}].mesh"), &o.mesh)?);
        }
        limits.check_triangles(generated).map_err(|l| c.err("objects", Problem::Limit(l)))?;
        let dir = file.parent().unwrap_or_else(|| Path::new("."));
        let mut objects = Vec::new();
        let mut loaded = 0u64;
        for (i, o) in parsed.objects.iter().enumerate() {
            let key = format!("objects[{i}]");
            // Files get what the generators and the files before them leave.
            let left = Limits {
                max_triangles: limits.max_triangles.saturating_sub(generated.saturating_add(loaded)),
                ..*limits
            };
            let mesh = build_mesh(&c, &format!("{key}.mesh"), &o.mesh, dir, &left)?;
            if o.mesh.loaded() {
                loaded += u64::try_from(mesh.triangles.len()).unwrap_or(u64::MAX);
            }
            let t = c.vec3(&format!("{key}.translate"), o.translate.unwrap_or(Exact([0.0; 3])))?;
            let r = c.vec3(&format!("{key}.rotate"), o.rotate.unwrap_or(Exact([0.0; 3])))?;
            let s = c.range(&format!("{key}.scale"), o.scale.unwrap_or(1.0), 1e-6, 1e6)?;
            let rotation = Quat::from_euler(EulerRot::XYZ, r.x.to_radians(), r.y.to_radians(), r.z.to_radians());
            let mesh = mesh.transformed(&Mat4::from_scale_rotation_translation(Vec3::splat(s), rotation, t));
            c.placed(&format!("{key}.mesh"), &mesh, !o.mesh.loaded())?;
            let closed = mesh.is_closed();
            let solid = match o.solid {
                Some(true) if !closed => return Err(c.err(format!("{key}.solid"), Problem::OpenMarkedSolid)),
                Some(s) => s,
                None => closed,
            };
            objects.push(Object { name: o.name.clone().unwrap_or_else(|| format!("object {i}")), mesh, solid });
        }
        let name = parsed
            .name
            .unwrap_or_else(|| file.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned()));
        Ok(Self {
            name,
            objects,
            lights,
            camera: Camera::Perspective(camera),
            image,
            source: String::new(),
            camera_choice: None,
            light_from: None,
            shadowless,
            notes: Vec::new(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counts taken before building agree with what each generator builds.
    #[test]
    fn generated_triangle_counts_match_the_generators() {
        let text = BUNDLED.iter().map(|(_, t)| *t).collect::<Vec<_>>();
        let file = Path::new("probe.toml");
        let c = Check { file };
        let mut kinds = std::collections::HashSet::new();
        for t in text {
            let parsed: SceneFile = toml::from_str(t).expect("bundled scenes parse");
            for o in &parsed.objects {
                let mesh = build_mesh(&c, "m", &o.mesh, Path::new("."), &Limits::DEFAULT).expect("builds");
                let n = generated_triangles(&c, "m", &o.mesh).expect("counts");
                assert_eq!(n, mesh.triangles.len() as u64);
                kinds.insert(std::mem::discriminant(&o.mesh));
            }
        }
        assert_eq!(kinds.len(), 8, "the bundled scenes use every generator");
    }
}
