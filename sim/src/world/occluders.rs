//! Occluders as the silhouette and stencil units see them: each triangle's
//! facing with respect to the light, edge adjacency, and the silhouette
//! edges (Sen, Cammarano & Hanrahan 2003 §3.1: "an edge between a
//! light-facing and a light-averted triangle, or a boundary edge of an open
//! mesh"). Then the two passes that use them: the silhouette map and the
//! depth-fail shadow volumes.

use std::collections::HashMap;

use glam::{DVec3, Mat4, Vec3};
use umbra_core::front::clip::ClipVertex;
use umbra_core::probe::Probe;
use umbra_core::shadow::{MapView, ShadowConfig};
use umbra_core::silhouette::{SilStore, SilhouettePass};
use umbra_core::stencil::{StencilPass, Volume, VolumeLight};
use umbra_core::{ConfigError, DepthFormat, RasterConfig};

use crate::world::scene::{Light, Scene};

/// One occluder triangle, turned to face the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Occluder {
    /// World positions, counter-clockwise seen from the light.
    pub positions: [Vec3; 3],
    /// Whether edge `k` (`positions[k] → positions[k + 1]`) is a silhouette
    /// edge: no other occluder triangle shares it the other way round.
    pub sides: [bool; 3],
}

/// The occluders of a scene under its light.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Occluders {
    /// Every occluder triangle.
    pub triangles: Vec<Occluder>,
}

/// The bit pattern of a position: edges are matched by exact position, so
/// meshes with split vertices (flat normals) still find their neighbours.
fn key(p: Vec3) -> [u32; 3] {
    p.to_array().map(f32::to_bits)
}

/// How much a triangle faces the light: positive facing, negative averted.
fn facing(light: &Light, p: &[Vec3; 3]) -> f64 {
    let [a, b, c] = p.map(|v| v.as_dvec3());
    let n = (b - a).cross(c - a);
    let towards = match light {
        Light::Spot(s) => s.position.as_dvec3() - (a + b + c) / 3.0,
        Light::Directional(_) => -light.direction().as_dvec3(),
    };
    n.dot(towards)
}

impl Occluders {
    /// Solids keep their light-facing triangles; open surfaces keep every
    /// triangle, turned to face the light (they cast shadows from both
    /// sides). Triangles edge-on to the light are left out.
    #[must_use]
    pub fn new(scene: &Scene) -> Self {
        let light = scene.light();
        let mut triangles = Vec::new();
        for o in &scene.objects {
            for t in &o.mesh.triangles {
                let p = t.map(|i| o.mesh.positions.get(i as usize).copied().unwrap_or(Vec3::ZERO));
                let f = facing(&light, &p);
                if !(f.is_finite() && f != 0.0) || (o.solid && f < 0.0) {
                    continue;
                }
                let positions = if f > 0.0 { p } else { [p[0], p[2], p[1]] };
                triangles.push(Occluder { positions, sides: [false; 3] });
            }
        }
        let mut directed: HashMap<([u32; 3], [u32; 3]), u32> = HashMap::new();
        for t in &triangles {
            for k in 0..3 {
                *directed.entry((key(t.positions[k]), key(t.positions[(k + 1) % 3]))).or_default() += 1;
            }
        }
        for t in &mut triangles {
            for k in 0..3 {
                let (a, b) = (key(t.positions[k]), key(t.positions[(k + 1) % 3]));
                t.sides[k] = !directed.contains_key(&(b, a));
            }
        }
        Self { triangles }
    }

    /// Each silhouette edge once (a fold of an open surface is a side of
    /// both its triangles), in a fixed order.
    #[must_use]
    pub fn silhouette_edges(&self) -> Vec<[Vec3; 2]> {
        let mut seen = std::collections::HashSet::new();
        let mut edges = Vec::new();
        for t in &self.triangles {
            for k in (0..3).filter(|&k| t.sides[k]) {
                let (a, b) = (t.positions[k], t.positions[(k + 1) % 3]);
                let (ka, kb) = (key(a), key(b));
                if seen.insert(if ka < kb { (ka, kb) } else { (kb, ka) }) {
                    edges.push([a, b]);
                }
            }
        }
        edges
    }
}

fn clip(m: &Mat4, p: Vec3) -> ClipVertex {
    (*m * p.extend(1.0)).to_array().map(f64::from)
}

/// The silhouette map of `occluders` on the depth map `map` (`light` is
/// its view-projection), its visibility tested with `cfg`'s test and bias.
///
/// # Errors
/// [`ConfigError`] when `map` is unusable.
pub fn silhouette_map<S: SilStore, F: DepthFormat, P: Probe>(
    occluders: &Occluders,
    light: &Mat4,
    map: &MapView<'_, F>,
    cfg: ShadowConfig,
    probe: &mut P,
) -> Result<Vec<S>, ConfigError> {
    let r = *map.raster();
    let mut texels = vec![S::default(); (r.width() as usize + 1) * (r.height() as usize + 1)];
    let mut pass = SilhouettePass::new(&mut texels, map, cfg)?;
    for [a, b] in occluders.silhouette_edges() {
        pass.draw_clip(&clip(light, a), &clip(light, b), probe);
    }
    Ok(texels)
}

/// The light as the volumes need it under `camera`, with an extrusion
/// that carries every volume past every point of the scene: a point
/// light's to twice the scene's farthest distance from it, a directional
/// light's by twice the scene's diagonal.
#[must_use]
pub fn volume_light(scene: &Scene, camera: &Mat4) -> VolumeLight {
    let points = scene.objects.iter().flat_map(|o| o.mesh.positions.iter().map(|p| p.as_dvec3()));
    let light = scene.light();
    let clip4 = |v: glam::Vec4| (*camera * v).to_array().map(f64::from);
    match light {
        Light::Spot(s) => {
            let l = s.position.as_dvec3();
            let (near, far) = points.fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
                let d = (p - l).length();
                (lo.min(d), hi.max(d))
            });
            let t = if near > 0.0 && near.is_finite() { (2.0 * far / near).min(1e6) } else { 1e6 };
            VolumeLight { clip: clip4(s.position.extend(1.0)), point: true, t }
        }
        Light::Directional(_) => {
            let (lo, hi) = points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
            let diagonal = (hi - lo).length();
            let towards = (-light.direction()).normalize_or_zero();
            let t = if diagonal.is_finite() { 2.0 * diagonal } else { 0.0 };
            VolumeLight { clip: clip4(towards.extend(0.0)), point: false, t }
        }
    }
}

/// Count the shadow volumes of `occluders` into a stencil over the camera
/// target `raster`, against the scene depth `depth` the visibility unit
/// stored under `camera`. Non-zero stencil: in shadow.
///
/// # Errors
/// [`ConfigError`] when a buffer does not fit `raster`.
pub fn stencil<F: DepthFormat, P: Probe>(
    scene: &Scene,
    occluders: &Occluders,
    camera: &Mat4,
    raster: RasterConfig,
    depth: &[F::Texel],
    probe: &mut P,
) -> Result<Vec<u8>, ConfigError> {
    let light = volume_light(scene, camera);
    let mut stencil = vec![0u8; raster.texel_count()];
    let mut pass = StencilPass::<F>::new(raster, depth, &mut stencil)?;
    for t in &occluders.triangles {
        let volume = Volume { tri: t.positions.map(|p| clip(camera, p)), sides: t.sides };
        for tri in volume.triangles(&light) {
            pass.draw(&tri, probe);
        }
    }
    Ok(stencil)
}
