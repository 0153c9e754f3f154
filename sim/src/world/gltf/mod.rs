//! glTF 2.0 files (`.gltf` with its buffers, and `.glb`) read through the
//! `gltf` crate: every triangle primitive of every mesh each node of the
//! scene places (strips and fans made triangles; points and lines counted
//! and left out, as an OBJ file's are), in world space; the cameras and the
//! `KHR_lights_punctual` lights its nodes place.
//!
//! A mesh several nodes place is read from its buffers once and placed
//! once per node, each placement holding only the vertices its triangles
//! use. The file is treated as an adversary wrote it: nothing the `gltf`
//! crate would index unchecked reaches it, the specification's rules it
//! leaves out are checked (`spec`), a buffer is read only from the
//! model's own folder, every count is checked against the [`Limits`] and
//! the memory the whole read takes is estimated from the counts the file
//! declares (`meshes`) before any buffer is read, every byte range is
//! checked before it is read, and every problem is named with the file and
//! the JSON path of what is wrong, never with bytes of a file.

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::input::limits::{LimitError, Limits};
use crate::world::mesh::Mesh;

mod accessors;
mod buffers;
mod city;
mod meshes;
mod nodes;
mod spec;

pub use city::{City, CityError};
use meshes::{drawn, estimate, local_mesh, placed, primitives};

/// A problem at a JSON path (`meshes[0].primitives[1]`), before the file is named.
type Fault = (String, GltfProblem);

/// What is wrong with a glTF file, and where.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {path}: {problem}")]
pub struct GltfError {
    /// The glTF file.
    pub file: PathBuf,
    /// The JSON path of what is wrong (`accessors[3]`), or `(file)`.
    pub path: String,
    /// What is wrong.
    pub problem: GltfProblem,
}

/// The kinds of problem a glTF file can have.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GltfProblem {
    /// The file (or a buffer's file) cannot be read.
    #[error("cannot read: {0}")]
    Read(std::io::Error),
    /// The path is a directory, a device or a pipe.
    #[error("not a regular file")]
    NotAFile,
    /// Beyond the [`Limits`].
    #[error(transparent)]
    Limit(LimitError),
    /// Not glTF: not JSON, a broken `.glb` header or chunk.
    #[error("not glTF 2.0: {0}")]
    Syntax(String),
    /// The JSON breaks the glTF schema (the `gltf` crate's validation).
    #[error("invalid glTF: {0}")]
    Invalid(String),
    /// An extension the file requires that Umbra does not read.
    #[error(
        "the file requires the extension `{0}`, which Umbra does not read (write the file without it, e.g. uncompressed)"
    )]
    Unsupported(String),
    /// A buffer or buffer view that does not hold what it declares.
    #[error("{0}")]
    Buffer(String),
    /// A buffer's URI that leads out of the model's folder, or to a
    /// scheme or a system file: refused before any byte is read.
    #[error("{0}")]
    Outside(String),
    /// What the glTF specification forbids and the `gltf` crate lets
    /// through (a camera's planes, a node's transform, a stride).
    #[error("{0}")]
    Spec(String),
    /// An accessor of the wrong type, or one reaching past its data.
    #[error("{0}")]
    Accessor(String),
    /// A triangle's index names no vertex (its value is not shown: an
    /// error never echoes a file's bytes).
    #[error("element {element} is an index past the last vertex: POSITION has {vertices}")]
    Index {
        /// Where it is among the primitive's indices.
        element: usize,
        /// The vertices there are.
        vertices: usize,
    },
    /// A vertex coordinate that is NaN or infinite.
    #[error("element {element} is not finite (a coordinate is NaN or infinite)")]
    NonFinite {
        /// The element.
        element: usize,
    },
    /// Nodes that do not form a tree, or a transform that is not finite.
    #[error("{0}")]
    Nodes(String),
    /// A point light: it casts shadows in every direction, which one map
    /// does not hold.
    #[error(
        "`{0}` is a point light; Umbra renders the shadows of spot and directional lights (a point light would need six maps)"
    )]
    PointLight(String),
    /// A spot light or camera Umbra's views cannot take.
    #[error("{0}")]
    View(String),
    /// No camera of that name or index.
    #[error("no camera `{asked}`; the file's cameras: {known}")]
    NoCamera {
        /// What was asked for.
        asked: String,
        /// The cameras there are.
        known: String,
    },
    /// The scene (or the node asked for) places no triangle.
    #[error("places no triangle")]
    Empty,
}

/// A camera as the file defines it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// `yfov` in radians, `znear`, `zfar` (none: infinite), the aspect ratio if given.
    Perspective {
        /// Vertical field of view, radians.
        yfov: f32,
        /// Near plane.
        znear: f32,
        /// Far plane, if finite.
        zfar: Option<f32>,
        /// Width over height, if given.
        aspect: Option<f32>,
    },
    /// Half the width and height, `znear`, `zfar`.
    Orthographic {
        /// Half the width.
        xmag: f32,
        /// Half the height.
        ymag: f32,
        /// Near plane.
        znear: f32,
        /// Far plane.
        zfar: f32,
    },
}

/// A light as the file defines it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lamp {
    /// A spot light of this outer cone half-angle (radians) and range.
    Spot {
        /// The outer cone's half-angle, radians.
        outer: f32,
        /// Where the light ends, if it does.
        range: Option<f32>,
    },
    /// A directional light.
    Directional,
}

/// A camera or a light as a node places it.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed<T> {
    /// Its JSON path (`cameras[1]`, `KHR_lights_punctual.lights[0]`).
    pub path: String,
    /// Its name: its own, else its node's, else its path.
    pub name: String,
    /// What it is.
    pub what: T,
    /// Where it is: the origin of its node's world transform.
    pub position: DVec3,
    /// Where it looks: its node's −Z.
    pub forward: DVec3,
    /// Its up: its node's +Y.
    pub up: DVec3,
}

/// A mesh as a node places it, in world space.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The node's name, else `nodes[i]`.
    pub name: String,
    /// The node's JSON path.
    pub node: String,
    /// Its triangles in world space, wound counter-clockwise seen from
    /// their front (a mirroring transform's winding turned back).
    pub mesh: Mesh,
}

/// What a glTF file's scene holds.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Gltf {
    /// One mesh per node that places one.
    pub instances: Vec<Instance>,
    /// The cameras, in the order of the walk.
    pub cameras: Vec<Placed<Lens>>,
    /// The lights, in the order of the walk.
    pub lights: Vec<Placed<Lamp>>,
}

/// The `KHR_lights_punctual` light `node` places, if any: its JSON path,
/// its name and what it is (read from the JSON, whose spot parameters the
/// `gltf` crate would unwrap); a point light is refused by name.
fn lamp(json: &gltf::json::Root, node: &gltf::Node<'_>) -> Result<Option<(String, String, Lamp)>, Fault> {
    use gltf::json::extensions::scene::khr_lights_punctual::Type;
    use gltf::json::validation::Checked;
    let at = format!("nodes[{}]", node.index());
    let placed =
        json.nodes.get(node.index()).and_then(|n| n.extensions.as_ref()).and_then(|e| e.khr_lights_punctual.as_ref());
    let Some(placed) = placed else { return Ok(None) };
    let k = placed.light.value();
    let path = format!("extensions.KHR_lights_punctual.lights[{k}]");
    let defined = json.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()).and_then(|e| e.lights.get(k));
    let Some(light) = defined else {
        let problem = format!("names light {k}, which the file does not define");
        return Err((format!("{at}.extensions.KHR_lights_punctual.light"), GltfProblem::Nodes(problem)));
    };
    let name = name_of(light.name.as_deref().or(node.name()), &path);
    let what = match light.type_ {
        Checked::Valid(Type::Directional) => Lamp::Directional,
        Checked::Valid(Type::Spot) => Lamp::Spot {
            outer: light.spot.as_ref().map_or(std::f32::consts::FRAC_PI_4, |s| s.outer_cone_angle),
            range: light.range,
        },
        Checked::Valid(Type::Point) => return Err((path, GltfProblem::PointLight(name))),
        Checked::Invalid => return Err((format!("{path}.type"), GltfProblem::Invalid("an unknown light type".into()))),
    };
    Ok(Some((path, name, what)))
}

/// A node's name, else its path.
fn name_of(name: Option<&str>, path: &str) -> String {
    name.filter(|n| !n.is_empty()).map_or_else(|| path.to_owned(), str::to_owned)
}

/// The node named `name`, or at index `name` (`nodes[3]` or `3`).
fn node_named(document: &gltf::Document, name: &str) -> Option<usize> {
    let bare = name.strip_prefix("nodes[").and_then(|n| n.strip_suffix(']')).unwrap_or(name);
    document.nodes().find(|n| n.name() == Some(name)).map(|n| n.index()).or_else(|| bare.parse().ok())
}

impl Gltf {
    /// Read the glTF file at `path` within `limits`: the meshes its
    /// scene's nodes place (only those at and under the node `under`
    /// names, by name or index, when it is given), its cameras and lights.
    ///
    /// # Errors
    /// [`GltfError`] naming the file, the JSON path and the problem.
    pub fn read(path: &Path, under: Option<&str>, limits: &Limits) -> Result<Self, GltfError> {
        Self::read_faults(path, under, limits).map_err(|(at, problem)| GltfError {
            file: path.to_owned(),
            path: at,
            problem,
        })
    }

    fn read_faults(path: &Path, under: Option<&str>, limits: &Limits) -> Result<Self, Fault> {
        let mut parsed = buffers::parse(path, limits)?;
        let document = &parsed.document;
        let target = match under {
            Some(name) => {
                Some(node_named(document, name).filter(|&n| n < document.nodes().len()).ok_or_else(|| {
                    ("nodes".to_owned(), GltfProblem::Nodes(format!("no node named `{name}` (nor of that index)")))
                })?)
            }
            None => None,
        };
        let walked = nodes::walk(document, target)?;
        if target.is_some_and(|t| !walked.iter().any(|w| w.node == t)) {
            let problem = format!("`{}` is not in the file's scene", under.unwrap_or_default());
            return Err(("nodes".to_owned(), GltfProblem::Nodes(problem)));
        }
        let chosen: Vec<&nodes::Placed> = walked.iter().filter(|w| target.is_none() || w.inside).collect();
        let all: Vec<gltf::Node<'_>> = document.nodes().collect();
        // Every instance's triangles and other primitives, and the memory
        // the read takes, counted against the limits before any buffer is
        // read.
        let mut counted = 0u64;
        for w in &chosen {
            for p in all[w.node].mesh().iter().flat_map(gltf::Mesh::primitives) {
                let (triangles, ignored) = primitives(p.mode(), drawn(&p));
                counted = counted.saturating_add(triangles + ignored.segments + ignored.points);
            }
        }
        let over = |l| ("meshes".to_owned(), GltfProblem::Limit(l));
        limits.check_triangles(counted).map_err(over)?;
        limits
            .check_memory("reading the glTF file's meshes", estimate(document, &chosen, parsed.json_bytes))
            .map_err(over)?;
        let buffers = buffers::load(document, &mut parsed.blob, path, limits)?;
        let max = usize::try_from(limits.max_triangles.saturating_mul(3)).unwrap_or(usize::MAX);
        let mut meshes: Vec<Option<Mesh>> = vec![None; document.meshes().len()];
        let mut out = Self::default();
        let json = document.as_json();
        for w in chosen {
            let node = &all[w.node];
            let at = format!("nodes[{}]", w.node);
            let position = w.world.transform_point3(DVec3::ZERO);
            let forward = w.world.transform_vector3(DVec3::NEG_Z).normalize_or_zero();
            let up = w.world.transform_vector3(DVec3::Y).normalize_or_zero();
            if let Some(m) = node.mesh() {
                let local = match &mut meshes[m.index()] {
                    Some(mesh) => mesh,
                    slot => slot.insert(local_mesh(&buffers, &m, max)?),
                };
                if !local.triangles.is_empty() || !local.ignored.is_empty() {
                    let name = name_of(node.name(), &at);
                    out.instances.push(Instance { name, node: at.clone(), mesh: placed(local, &w.world) });
                }
            }
            let aimless = forward == DVec3::ZERO || up == DVec3::ZERO || forward.cross(up).length() < 1e-6;
            let aimed = |what: String| {
                let problem = format!(
                    "places {what} with a transform that leaves it no direction (its −Z or +Y is zero, a zero scale, or the two are parallel)"
                );
                (at.clone(), GltfProblem::Nodes(problem))
            };
            if let Some(c) = node.camera() {
                if aimless {
                    return Err(aimed(format!("cameras[{}]", c.index())));
                }
                let lens = match c.projection() {
                    gltf::camera::Projection::Perspective(p) => {
                        Lens::Perspective { yfov: p.yfov(), znear: p.znear(), zfar: p.zfar(), aspect: p.aspect_ratio() }
                    }
                    gltf::camera::Projection::Orthographic(o) => {
                        Lens::Orthographic { xmag: o.xmag(), ymag: o.ymag(), znear: o.znear(), zfar: o.zfar() }
                    }
                };
                let path = format!("cameras[{}]", c.index());
                let name = name_of(c.name().or(node.name()), &path);
                out.cameras.push(Placed { path, name, what: lens, position, forward, up });
            }
            if let Some((path, name, what)) = lamp(json, node)? {
                if aimless {
                    return Err(aimed(path));
                }
                out.lights.push(Placed { path, name, what, position, forward, up });
            }
        }
        if out.instances.iter().all(|i| i.mesh.triangles.is_empty()) {
            return Err((under.map_or_else(|| "scenes".to_owned(), |u| format!("nodes `{u}`")), GltfProblem::Empty));
        }
        Ok(out)
    }
}
