//! The scene file's schema as serde reads it, and the checks that turn its values into a scene's.

use std::path::Path;

use glam::Vec3;
use serde::Deserialize;

use crate::input::exact::Exact;

use super::{MAX_SUBDIVISION, Problem, SceneError};
use crate::world::scene::{Light, Orthographic, Perspective};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    /// The file format version it is written for (`input::format::SCENE`).
    pub(super) format: Option<u32>,
    pub(super) name: Option<String>,
    pub(super) image: Exact<2, u32>,
    pub(super) camera: ViewFile,
    pub(super) lights: Vec<LightFile>,
    pub(super) objects: Vec<ObjectFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ViewFile {
    pub(super) position: Exact<3>,
    pub(super) target: Exact<3>,
    pub(super) fov: f64,
    pub(super) near: f64,
    pub(super) far: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "lowercase")]
pub(super) enum LightFile {
    Spot {
        position: Exact<3>,
        target: Exact<3>,
        fov: f64,
        near: f64,
        far: f64,
        shadows: Option<bool>,
    },
    Directional {
        position: Exact<3>,
        target: Exact<3>,
        extent: f64,
        near: f64,
        far: f64,
        shadows: Option<bool>,
        /// Its cascades: a count, or their spelling (`"4,lambda=0.7"`).
        cascades: Option<CascadesText>,
    },
}

/// A light's `cascades`: a count, or the cascades' one spelling.
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum CascadesText {
    /// `cascades = 4`.
    Count(i64),
    /// `cascades = "4,lambda=0.7"`.
    Spelled(String),
}

impl CascadesText {
    /// The cascades it spells.
    pub(super) fn read(&self) -> Result<crate::world::cascade::Cascades, String> {
        match self {
            Self::Count(n) => n.to_string().parse(),
            Self::Spelled(s) => s.parse(),
        }
        .map_err(|e: crate::world::cascade::CascadesError| e.to_string())
    }
}

impl LightFile {
    /// Whether the light casts shadows (`shadows`, true unless it says not).
    pub(super) const fn casts(&self) -> bool {
        match self {
            Self::Spot { shadows, .. } | Self::Directional { shadows, .. } => !matches!(shadows, Some(false)),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectFile {
    pub(super) name: Option<String>,
    #[serde(deserialize_with = "mesh_file")]
    pub(super) mesh: MeshFile,
    pub(super) translate: Option<Exact<3>>,
    pub(super) rotate: Option<Exact<3>>,
    pub(super) scale: Option<f64>,
    pub(super) solid: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub(super) enum MeshFile {
    Obj(String),
    Shared(String),
    Box {
        min: Exact<3>,
        max: Exact<3>,
    },
    Quad {
        corner: Exact<3>,
        u: Exact<3>,
        v: Exact<3>,
    },
    Sphere {
        center: Exact<3>,
        radius: f64,
        stacks: u32,
        slices: u32,
    },
    Torus {
        center: Exact<3>,
        major: f64,
        minor: f64,
        rings: u32,
        sides: u32,
    },
    Table {
        width: f64,
        depth: f64,
        height: f64,
        top: f64,
        leg: f64,
    },
    Sheet {
        center: Exact<3>,
        width: f64,
        height: f64,
        bend: f64,
        nx: u32,
        ny: u32,
    },
    Figure {
        feet: Exact<3>,
        height: f64,
        head: Option<u32>,
    },
    Ell {
        min: Exact<3>,
        max: Exact<3>,
        thickness: f64,
    },
    Arrays {
        positions: Vec<Exact<3>>,
        triangles: Vec<Exact<3, u32>>,
    },
    /// `{ gltf = "file.glb", node = "name" }`: two keys, which an
    /// externally tagged variant cannot be, so [`mesh_file`] reads it.
    #[serde(skip)]
    Gltf {
        file: String,
        node: Option<String>,
    },
}

/// A glTF file's meshes, or those at and under one of its nodes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GltfFile {
    gltf: String,
    node: Option<String>,
}

/// An object's `mesh`: a table with a `gltf` key is a [`GltfFile`], any
/// other a [`MeshFile`]; either's error is reported at the `mesh` value.
fn mesh_file<'de, D: serde::Deserializer<'de>>(d: D) -> Result<MeshFile, D::Error> {
    use serde::de::Error;
    let value = toml::Value::deserialize(d)?;
    if value.as_table().is_some_and(|t| t.contains_key("gltf")) {
        let g: GltfFile = value.try_into().map_err(|e| D::Error::custom(e.message().trim()))?;
        return Ok(MeshFile::Gltf { file: g.gltf, node: g.node });
    }
    value.try_into().map_err(|e: toml::de::Error| D::Error::custom(e.message().trim()))
}

/// Checks with the file and the key at hand.
pub(super) struct Check<'a> {
    pub(super) file: &'a Path,
}

impl Check<'_> {
    pub(super) fn err(&self, key: impl Into<String>, problem: Problem) -> SceneError {
        SceneError { file: self.file.to_owned(), key: key.into(), problem }
    }

    #[allow(clippy::cast_possible_truncation, reason = "checked finite; the pipeline's vertex unit is f32")]
    fn num(&self, key: &str, v: f64) -> Result<f32, SceneError> {
        if v.is_finite() && v.abs() < 1e30 { Ok(v as f32) } else { Err(self.err(key, Problem::NonFinite { value: v })) }
    }

    pub(super) fn vec3(&self, key: &str, Exact(v): Exact<3>) -> Result<Vec3, SceneError> {
        Ok(Vec3::new(self.num(key, v[0])?, self.num(key, v[1])?, self.num(key, v[2])?))
    }

    pub(super) fn range(&self, key: &str, v: f64, min: f64, max: f64) -> Result<f32, SceneError> {
        let f = self.num(key, v)?;
        if v < min || v > max {
            return Err(self.err(key, Problem::Size { value: v, min, max }));
        }
        Ok(f)
    }

    pub(super) fn count(&self, key: &str, v: u32) -> Result<u32, SceneError> {
        self.range(key, f64::from(v), 1.0, f64::from(MAX_SUBDIVISION)).map(|_| v)
    }

    /// Near and far as the pipeline holds them: f32, near a normal
    /// positive number below far (checked after the conversion, so that a
    /// near plane that rounds to 0 or onto far is refused).
    pub(super) fn near_far(&self, key: &str, near: f64, far: f64) -> Result<(f32, f32), SceneError> {
        let (n, f) = (self.num(&format!("{key}.near"), near)?, self.num(&format!("{key}.far"), far)?);
        if !(n >= f32::MIN_POSITIVE && n < f) {
            return Err(self.err(format!("{key}.near"), Problem::NearFar { near, far }));
        }
        Ok((n, f))
    }

    /// A view's position and target as the pipeline holds them: distinct
    /// in f32.
    pub(super) fn eye(&self, key: &str, position: Exact<3>, target: Exact<3>) -> Result<(Vec3, Vec3), SceneError> {
        let p = self.vec3(&format!("{key}.position"), position)?;
        let t = self.vec3(&format!("{key}.target"), target)?;
        let along = t - p;
        if !(along.length_squared() > 0.0 && along.normalize().is_finite()) {
            return Err(self.err(format!("{key}.position"), Problem::LooksNowhere { position: p.to_array() }));
        }
        Ok((p, t))
    }

    /// A mesh as placed in the scene: every vertex finite and within
    /// [`MAX_COORDINATE`](super::MAX_COORDINATE), and, for a generated
    /// shape (whose triangles all have area as built), every triangle
    /// still of some area in f32.
    pub(super) fn placed(&self, key: &str, mesh: &crate::world::mesh::Mesh, generated: bool) -> Result<(), SceneError> {
        let max = super::MAX_COORDINATE;
        if let Some((vertex, p)) =
            mesh.positions.iter().enumerate().find(|(_, p)| !(p.is_finite() && p.abs().max_element() <= max))
        {
            return Err(self.err(key, Problem::Coordinate { vertex, position: p.to_array() }));
        }
        if generated {
            let corner = |i: u32| mesh.positions[i as usize];
            let flat = mesh
                .triangles
                .iter()
                .position(|&[a, b, c]| (corner(b) - corner(a)).cross(corner(c) - corner(a)).length_squared() == 0.0);
            if let Some(triangle) = flat {
                return Err(self.err(key, Problem::Degenerate { triangle }));
            }
        }
        Ok(())
    }

    /// A light as the file gives it, checked: a spot light's view, or a
    /// directional light's view and its cascades.
    pub(super) fn light(&self, key: &str, l: &LightFile) -> Result<Light, SceneError> {
        Ok(match l {
            LightFile::Spot { position, target, fov, near, far, .. } => Light::Spot(
                self.view(key, &ViewFile { position: *position, target: *target, fov: *fov, near: *near, far: *far })?,
            ),
            LightFile::Directional { position, target, extent, near, far, cascades, .. } => {
                let (near, far) = self.near_far(key, *near, *far)?;
                let (position, target) = self.eye(key, *position, *target)?;
                let extent = self.range(&format!("{key}.extent"), *extent, 1e-6, 1e6)?;
                let view = Orthographic { position, target, extent, near, far, up: Vec3::Y };
                let cascades = cascades
                    .as_ref()
                    .map(|t| t.read().map_err(|e| self.err(format!("{key}.cascades"), Problem::Syntax(e))))
                    .transpose()?
                    .unwrap_or_default();
                Light::Directional(view, cascades)
            }
        })
    }

    pub(super) fn view(&self, key: &str, v: &ViewFile) -> Result<Perspective, SceneError> {
        let (near, far) = self.near_far(key, v.near, v.far)?;
        let (position, target) = self.eye(key, v.position, v.target)?;
        Ok(Perspective {
            position,
            target,
            fov_degrees: self.range(&format!("{key}.fov"), v.fov, 1.0, 170.0)?,
            near,
            far,
            up: Vec3::Y,
        })
    }
}
