//! Scenes: objects in world space, lights and a camera.

use glam::{DMat4, DVec3, Mat4, Vec3};
use umbra_core::CullMode;

use crate::world::mesh::Mesh;

mod matrix;
pub use matrix::{MatrixError, parse_matrix};

/// A mesh placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// A name for reports.
    pub name: String,
    /// World-space mesh.
    pub mesh: Mesh,
    /// A closed, consistently wound surface (may be back- or front-face culled).
    pub solid: bool,
}

/// How far from the centre of a scene's bounding sphere, in radii, a
/// framing view's eye lies at least: its near plane then clears the
/// sphere.
pub const CLEARANCE: f32 = 1.2;

/// A point as the flag and [`Scene::arguments`] write it: `x,y,z`, each
/// the shortest decimal that reads back as the same f32.
#[must_use]
pub fn point_text(p: Vec3) -> String {
    format!("{},{},{}", p.x, p.y, p.z)
}

/// The centre and radius of the sphere round `mesh`'s bounds.
#[must_use]
pub(crate) fn bounding_sphere(mesh: &crate::world::mesh::Mesh) -> Option<(Vec3, f32)> {
    let (lo, hi) = mesh.bounds()?;
    Some(((lo + hi) / 2.0, ((hi - lo).length() / 2.0).max(f32::MIN_POSITIVE)))
}

/// A perspective view: a spot light, or the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    /// Where the eye is.
    pub position: Vec3,
    /// The point it looks at.
    pub target: Vec3,
    /// Vertical (and horizontal) field of view, degrees.
    pub fov_degrees: f32,
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
    /// Which way is up in the view (`Vec3::Y` unless a glTF node turns
    /// it); looking along it, `Vec3::Z` is up instead.
    pub up: Vec3,
}

impl Perspective {
    /// A spot light that frames `mesh`, looking down at it from above and
    /// to the side, its near and far planes hugging the mesh's bounding
    /// sphere: the view `umbra depth --mesh` and the peer benches draw a
    /// mesh from. `None` for a mesh without vertices.
    #[must_use]
    pub fn framing(mesh: &crate::world::mesh::Mesh) -> Option<Self> {
        Self::framing_along(mesh, Vec3::new(1.0, 2.0, 1.5))
    }

    /// A view framing `mesh` as [`Perspective::framing`] does, from the
    /// side `towards` points to (from the mesh's centre).
    #[must_use]
    pub fn framing_along(mesh: &crate::world::mesh::Mesh, towards: Vec3) -> Option<Self> {
        let (center, radius) = bounding_sphere(mesh)?;
        let distance = 3.0 * radius;
        Some(Self::aimed(center, radius, center + towards.normalize() * distance, distance))
    }

    /// A view from `position` aimed at the centre of `mesh`'s bounds, as
    /// [`Perspective::framing`] frames them. `None` for a mesh without
    /// vertices, or a position within [`CLEARANCE`] radii of the centre.
    #[must_use]
    pub fn framing_from(mesh: &crate::world::mesh::Mesh, position: Vec3) -> Option<Self> {
        let (center, radius) = bounding_sphere(mesh)?;
        let distance = (position - center).length();
        (distance >= CLEARANCE * radius).then(|| Self::aimed(center, radius, position, distance))
    }

    /// A view from `position`, `distance` from `center`, aimed at it: its
    /// field of view holds the sphere of `radius` with a tenth to spare,
    /// its near and far planes hug the sphere.
    fn aimed(center: Vec3, radius: f32, position: Vec3, distance: f32) -> Self {
        Self {
            position,
            target: center,
            fov_degrees: 2.0 * (radius / distance).asin().to_degrees() * 1.1,
            near: distance - CLEARANCE * radius,
            far: distance + CLEARANCE * radius,
            up: Vec3::Y,
        }
    }

    /// World space to clip space (depth `[0, 1]`, y up, right-handed).
    #[must_use]
    pub fn view_projection(&self) -> Mat4 {
        self.view_projection_aspect(1.0)
    }

    /// The same for a target `aspect = width / height` (the field of view
    /// is vertical).
    #[must_use]
    pub fn view_projection_aspect(&self, aspect: f32) -> Mat4 {
        let view = look_at(self.position, self.target, self.up);
        let proj =
            glam::camera::rh::proj::directx::perspective(self.fov_degrees.to_radians(), aspect, self.near, self.far);
        proj * view
    }
}

/// An orthographic view: a directional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orthographic {
    /// A point on the light's side of the scene.
    pub position: Vec3,
    /// The point it looks at (the light shines from `position` to `target`).
    pub target: Vec3,
    /// Half the side of the square the map covers.
    pub extent: f32,
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
    /// Which way is up in the view, as for [`Perspective::up`].
    pub up: Vec3,
}

impl Orthographic {
    /// World space to clip space for a target `aspect = width / height`:
    /// `extent` is half the height, `extent · aspect` half the width.
    #[must_use]
    pub fn view_projection_aspect(&self, aspect: f32) -> Mat4 {
        let (h, w) = (self.extent, self.extent * aspect);
        glam::camera::rh::proj::directx::orthographic(-w, w, -h, h, self.near, self.far)
            * look_at(self.position, self.target, self.up)
    }
}

/// The camera: a perspective view, or an orthographic one (a glTF
/// file's orthographic camera).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Camera {
    /// A perspective camera.
    Perspective(Perspective),
    /// An orthographic camera.
    Orthographic(Orthographic),
}

impl Camera {
    /// Its near and far planes.
    #[must_use]
    pub const fn planes(&self) -> (f32, f32) {
        match self {
            Self::Perspective(p) => (p.near, p.far),
            Self::Orthographic(o) => (o.near, o.far),
        }
    }

    /// World space to clip space for a target `aspect = width / height`.
    #[must_use]
    pub fn view_projection_aspect(&self, aspect: f32) -> Mat4 {
        match self {
            Self::Perspective(p) => p.view_projection_aspect(aspect),
            Self::Orthographic(o) => o.view_projection_aspect(aspect),
        }
    }

    /// A light where the camera is, looking where it looks.
    #[must_use]
    pub const fn as_light(&self) -> Light {
        match *self {
            Self::Perspective(p) => Light::Spot(p),
            Self::Orthographic(o) => Light::Directional(o, crate::world::cascade::Cascades::ONE),
        }
    }
}

/// A light of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A perspective spot light as the papers set theirs up (a scene
    /// file's `spot`): a point light of which the map sees what its
    /// frustum holds; the exact reference lights every way from it.
    Spot(Perspective),
    /// A spot light with a cone (a glTF file's): it lights what its
    /// cone holds (half its field of view about its axis) and nothing
    /// else, so a surface outside it is not lit by it, nor measured
    /// against it.
    Cone(Perspective),
    /// An orthographic directional light, drawn through one map or
    /// through cascades ([`crate::world::cascade`]).
    Directional(Orthographic, crate::world::cascade::Cascades),
}

/// A view matrix looking from `eye` at `target` with `up` up, or `Vec3::Z`
/// when the view looks along `up`.
pub(crate) fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    let dir = (target - eye).normalize_or(Vec3::NEG_Y);
    let up = if dir.cross(up).length_squared() < 1e-6 { Vec3::Z } else { up };
    glam::camera::rh::view::look_at_mat4(eye, target, up)
}

impl Light {
    /// Its near and far planes.
    #[must_use]
    pub const fn planes(&self) -> (f32, f32) {
        match self {
            Self::Spot(p) | Self::Cone(p) => (p.near, p.far),
            Self::Directional(o, _) => (o.near, o.far),
        }
    }

    /// World space to light clip space.
    #[must_use]
    pub fn view_projection(&self) -> Mat4 {
        match self {
            Self::Spot(p) | Self::Cone(p) => p.view_projection(),
            Self::Directional(o, _) => o.view_projection_aspect(1.0),
        }
    }

    /// The direction the light shines in (from the light into the scene).
    #[must_use]
    pub(crate) fn direction(&self) -> Vec3 {
        match self {
            Self::Spot(p) | Self::Cone(p) => p.target - p.position,
            Self::Directional(o, _) => o.target - o.position,
        }
    }

    /// The light as the exact reference sees it.
    #[must_use]
    pub fn source(&self) -> LightSource {
        match self {
            Self::Spot(p) => LightSource::Point(p.position.as_dvec3()),
            Self::Cone(p) => {
                LightSource::Spot { position: p.position.as_dvec3(), frustum: p.view_projection().as_dmat4() }
            }
            Self::Directional(..) => LightSource::Directional(self.direction().as_dvec3()),
        }
    }
}

/// Objects, lights, a camera and an image size.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// A name for reports.
    pub name: String,
    /// The objects.
    pub objects: Vec<Object>,
    /// The lights that cast shadows: each gets a light pass and a map, and
    /// the camera pass tests each.
    pub lights: Vec<Light>,
    /// Lights that cast no shadows (a scene file's `shadows = false`):
    /// they light the shaded picture, with no pass and no lookup.
    pub shadowless: Vec<Light>,
    /// The camera.
    pub camera: Camera,
    /// Image width and height in pixels.
    pub image: [u32; 2],
    /// How `umbra` commands name it again: the bundled scene's name or the
    /// file it was loaded from (empty for a scene built in code).
    pub source: String,
    /// The camera of a glTF file chosen by name or index (`--camera`),
    /// which commands that name the scene again pass on; `None` for the
    /// file's first, and for every other scene.
    pub camera_choice: Option<String>,
    /// What the scene's loader supplied that its file did not say (a
    /// default camera or light), for hosts to print.
    pub notes: Vec<String>,
    /// Where the first light was moved to (`--light-from`,
    /// [`Scene::with_light_from`]), which commands that name the scene
    /// again pass on; `None` where it stands as its file put it.
    pub light_from: Option<Vec3>,
}

impl Scene {
    /// The bundled default: Wang & Molnar's table on a floor (legs touching
    /// the floor, the case no bias fixes), with a sphere beside it, lit by a
    /// spot light from above (`scenes/table-and-sphere.toml`).
    ///
    /// # Panics
    /// Never: the bundled scenes are validated by the tests.
    #[must_use]
    pub fn default_scene() -> Self {
        Self::bundled("table-and-sphere").expect("the bundled table-and-sphere scene is valid")
    }

    /// The arguments of an `umbra` command that name this scene again:
    /// its source, shell-quoted, the `--camera` chosen and where
    /// `--light-from` moved its light.
    #[must_use]
    pub fn arguments(&self) -> String {
        let mut words = crate::output::provenance::shell_word(&self.source);
        if let Some(c) = &self.camera_choice {
            words += &format!(" --camera {}", crate::output::provenance::shell_word(c));
        }
        if let Some(p) = self.light_from {
            words += &format!(" --light-from {}", point_text(p));
        }
        words
    }

    /// The scene as light `k` alone lights it: the same objects and
    /// camera, `lights` that light only. A render of several lights draws
    /// each light's passes from its own.
    #[must_use]
    pub fn lit_by(&self, k: usize) -> Self {
        Self { lights: self.lights.get(k).copied().into_iter().collect(), shadowless: Vec::new(), ..self.clone() }
    }

    /// Each light's name in files and messages: `lights[k]`.
    #[must_use]
    pub fn light_key(k: usize) -> String {
        format!("lights[{k}]")
    }

    /// The light whose shadows the pipeline renders: the first.
    ///
    /// # Panics
    /// Never for a scene from [`Scene::default_scene`] or a scene file, which
    /// validate that there is a light.
    #[must_use]
    pub fn light(&self) -> Light {
        self.lights.first().copied().unwrap_or_else(|| self.camera.as_light())
    }

    /// The polyline segments and points the scene's OBJ files held,
    /// left out of its meshes.
    #[must_use]
    pub fn ignored(&self) -> crate::world::mesh::Ignored {
        let mut all = crate::world::mesh::Mesh::default();
        for o in &self.objects {
            all.ignored.segments += o.mesh.ignored.segments;
            all.ignored.points += o.mesh.ignored.points;
        }
        all.ignored
    }

    /// Every triangle of every object in draw order, with flat normals: the
    /// ids the visibility unit records index this list.
    #[must_use]
    pub fn triangles(&self) -> Vec<umbra_core::shade::SceneTriangle> {
        self.objects
            .iter()
            .flat_map(|o| {
                o.mesh.triangles.iter().map(|t| {
                    let p = t.map(|i| o.mesh.positions.get(i as usize).copied().unwrap_or(Vec3::ZERO));
                    let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
                    umbra_core::shade::SceneTriangle { positions: p, normals: [n; 3] }
                })
            })
            .collect()
    }

    /// The object each of [`Scene::triangles`] belongs to, by index.
    #[must_use]
    pub fn triangle_objects(&self) -> Vec<u32> {
        (0u32..).zip(&self.objects).flat_map(|(k, o)| core::iter::repeat_n(k, o.mesh.triangles.len())).collect()
    }

    /// One draw call per object under `transform`, all with cull mode `cull`.
    #[must_use]
    pub fn draws(&self, transform: Mat4, cull: CullMode) -> Vec<Draw<'_>> {
        self.draws_culled(transform, |_| cull)
    }

    /// One draw call per object, culled by whether the object is solid
    /// (Weiskopf & Ertl cull solids and leave open surfaces two-sided).
    #[must_use]
    pub(crate) fn draws_culled(&self, transform: Mat4, cull: impl Fn(bool) -> CullMode) -> Vec<Draw<'_>> {
        self.objects
            .iter()
            .map(|o| Draw {
                positions: &o.mesh.positions,
                triangles: &o.mesh.triangles,
                transform,
                cull: cull(o.solid),
            })
            .collect()
    }
}

/// One draw call: a mesh, its transform to light clip space and its cull mode.
#[derive(Clone, Copy, Debug)]
pub struct Draw<'a> {
    /// Object-space positions.
    pub positions: &'a [Vec3],
    /// Vertex indices, three per triangle.
    pub triangles: &'a [[u32; 3]],
    /// Object space to light clip space.
    pub transform: Mat4,
    /// Which facing to discard.
    pub cull: CullMode,
}

/// Where the light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSource {
    /// A point light at this position, shining every way.
    Point(DVec3),
    /// A spot light at `position` that lights what its cone holds: the
    /// circle inscribed in the view its map is drawn through (`frustum`,
    /// its view-projection, whose field of view is twice the cone's
    /// angle): a point outside it is not lit by this light at all.
    Spot {
        /// Where the light is.
        position: DVec3,
        /// World to the light's clip space.
        frustum: DMat4,
    },
    /// A directional light shining along this direction.
    Directional(DVec3),
}

impl LightSource {
    /// The unit direction from `p` towards the light and the distance to it.
    pub(crate) fn towards(&self, p: DVec3) -> (DVec3, f64) {
        match *self {
            Self::Point(l) | Self::Spot { position: l, .. } => {
                let d = l - p;
                (d.normalize_or_zero(), d.length())
            }
            Self::Directional(dir) => (-dir.normalize_or_zero(), f64::INFINITY),
        }
    }

    /// Whether the light reaches `p` at all: a spot light only inside its
    /// cone (between its near and far planes, within half its field of
    /// view of its axis: the circle its square frustum's sides touch,
    /// where `x² + y² ≤ w²` in clip space); every other light everywhere.
    pub(crate) fn reaches(&self, p: DVec3) -> bool {
        match *self {
            Self::Spot { frustum, .. } => {
                let c = frustum * p.extend(1.0);
                c.w > 0.0 && c.x * c.x + c.y * c.y <= c.w * c.w && (0.0..=c.w).contains(&c.z)
            }
            Self::Point(_) | Self::Directional(_) => true,
        }
    }
}

#[cfg(test)]
mod tests;
