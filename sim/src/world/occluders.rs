//! Occluders as the silhouette and stencil units see them: each triangle's
//! facing with respect to the light, edge adjacency, and the silhouette
//! edges (Sen, Cammarano & Hanrahan 2003 §3.1: "an edge between a
//! light-facing and a light-averted triangle, or a boundary edge of an open
//! mesh"). Then the two passes that use them: the silhouette map and the
//! depth-fail shadow volumes.

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::OnceLock;

use glam::Vec3;

use crate::world::scene::{Light, Scene};

/// One occluder triangle, turned to face the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Occluder {
    /// World positions, counter-clockwise seen from the light.
    pub positions: [Vec3; 3],
    /// Whether edge `k` (`positions[k] → positions[k + 1]`) is a silhouette
    /// edge: no other occluder triangle shares it the other way round.
    pub sides: [bool; 3],
}

/// The occluders of a scene under its light.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Occluders {
    /// Every occluder triangle.
    pub triangles: Vec<Occluder>,
}

/// The scene as one of its shadow-casting lights alone lights it (the
/// scene itself when it has one light), and its occluders under that
/// light, worked out once, when first asked for: only the silhouette map
/// and shadow volumes read them, and every pass of a render (each tiling's,
/// each configuration's in a study) reads the same.
#[derive(Debug)]
pub(crate) struct Lit<'s> {
    /// The scene with this light alone.
    pub(crate) scene: Cow<'s, Scene>,
    occluders: OnceLock<Occluders>,
}

impl<'s> Lit<'s> {
    /// The scene lit by each of its shadow-casting lights in turn (by
    /// [`Scene::light`] when it has none).
    pub(crate) fn each(scene: &'s Scene) -> Vec<Self> {
        let lit = |scene| Self { scene, occluders: OnceLock::new() };
        if scene.lights.len() <= 1 {
            vec![lit(Cow::Borrowed(scene))]
        } else {
            (0..scene.lights.len()).map(|k| lit(Cow::Owned(scene.lit_by(k)))).collect()
        }
    }

    /// The occluders of the scene under this light.
    pub(crate) fn occluders(&self) -> &Occluders {
        self.occluders.get_or_init(|| Occluders::new(&self.scene))
    }
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
        Light::Spot(s) | Light::Cone(s) => s.position.as_dvec3() - (a + b + c) / 3.0,
        Light::Directional(..) => -light.direction().as_dvec3(),
    };
    n.dot(towards)
}

impl Occluders {
    /// Solids keep their light-facing triangles; open surfaces keep every
    /// triangle, turned to face the light (they cast shadows from both
    /// sides). Triangles edge-on to the light are left out.
    #[must_use]
    pub(crate) fn new(scene: &Scene) -> Self {
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
    pub(crate) fn silhouette_edges(&self) -> Vec<[Vec3; 2]> {
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
