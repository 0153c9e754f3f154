//! The scene file's schema as serde reads it, and the checks that turn its values into a scene's.

use std::path::Path;

use glam::Vec3;
use serde::Deserialize;

use super::{MAX_SUBDIVISION, Problem, SceneError};
use crate::world::scene::Perspective;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    pub(super) name: Option<String>,
    pub(super) image: [f64; 2],
    pub(super) camera: ViewFile,
    pub(super) lights: Vec<LightFile>,
    pub(super) objects: Vec<ObjectFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ViewFile {
    pub(super) position: [f64; 3],
    pub(super) target: [f64; 3],
    pub(super) fov: f64,
    pub(super) near: f64,
    pub(super) far: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "lowercase")]
pub(super) enum LightFile {
    Spot { position: [f64; 3], target: [f64; 3], fov: f64, near: f64, far: f64 },
    Directional { position: [f64; 3], target: [f64; 3], extent: f64, near: f64, far: f64 },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectFile {
    pub(super) name: Option<String>,
    pub(super) mesh: MeshFile,
    pub(super) translate: Option<[f64; 3]>,
    pub(super) rotate: Option<[f64; 3]>,
    pub(super) scale: Option<f64>,
    pub(super) solid: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub(super) enum MeshFile {
    Obj(String),
    Shared(String),
    Box { min: [f64; 3], max: [f64; 3] },
    Quad { corner: [f64; 3], u: [f64; 3], v: [f64; 3] },
    Sphere { center: [f64; 3], radius: f64, stacks: u32, slices: u32 },
    Torus { center: [f64; 3], major: f64, minor: f64, rings: u32, sides: u32 },
    Table { width: f64, depth: f64, height: f64, top: f64, leg: f64 },
    Sheet { center: [f64; 3], width: f64, height: f64, bend: f64, nx: u32, ny: u32 },
    Figure { feet: [f64; 3], height: f64, head: Option<u32> },
    Ell { min: [f64; 3], max: [f64; 3], thickness: f64 },
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

    pub(super) fn vec3(&self, key: &str, v: [f64; 3]) -> Result<Vec3, SceneError> {
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

    pub(super) fn near_far(&self, key: &str, near: f64, far: f64) -> Result<(f32, f32), SceneError> {
        let (n, f) = (self.num(&format!("{key}.near"), near)?, self.num(&format!("{key}.far"), far)?);
        if near <= 0.0 || near >= far {
            return Err(self.err(format!("{key}.near"), Problem::NearFar { near, far }));
        }
        Ok((n, f))
    }

    pub(super) fn view(&self, key: &str, v: &ViewFile) -> Result<Perspective, SceneError> {
        let (near, far) = self.near_far(key, v.near, v.far)?;
        Ok(Perspective {
            position: self.vec3(&format!("{key}.position"), v.position)?,
            target: self.vec3(&format!("{key}.target"), v.target)?,
            fov_degrees: self.range(&format!("{key}.fov"), v.fov, 1.0, 170.0)?,
            near,
            far,
        })
    }
}
