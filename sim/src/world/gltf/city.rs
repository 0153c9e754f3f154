//! A generated glTF city: one building mesh, its walls and roof cut into
//! a grid of window-sized quads, placed by a node per building (stored
//! once, instanced by translation and scale) on a ground plane, seen by a
//! camera over a corner and lit by a low sun and a spot light over the
//! middle street: large, real-shaped input for the loader and the passes.
//!
//! ```
//! use umbra_sim::world::gltf::{City, Gltf};
//! use umbra_sim::Limits;
//! let city = City { side: 2, columns: 2, storeys: 4 };
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("city.glb");
//! std::fs::write(&path, city.glb()?)?;
//! let read = Gltf::read(&path, None, &Limits::DEFAULT)?;
//! let triangles: usize = read.instances.iter().map(|i| i.mesh.triangles.len()).sum();
//! assert_eq!(triangles as u64, city.triangles());
//! assert_eq!((read.cameras.len(), read.lights.len()), (1, 2));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::borrow::Cow;

use glam::Vec3;
use serde_json::json;

use crate::input::limits::{Footprint, Limits};

/// A city of `side × side` buildings, each a box whose four walls are cut
/// into `columns` across and `storeys` up, its roof and floor
/// `columns × columns`; both counts powers of two, so that the walls'
/// edges meet the roof's exactly and every building is closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct City {
    /// Buildings along each side.
    pub side: u32,
    /// Window columns along each wall (a power of two).
    pub columns: u32,
    /// Storeys up each wall (a power of two).
    pub storeys: u32,
}

/// Why a city cannot be generated.
#[derive(Debug, thiserror::Error)]
pub enum CityError {
    /// A count of zero, or not a power of two, a building past u16
    /// indices, or a city past the limits: the options named, with the
    /// largest value allowed.
    #[error("{0}")]
    Counts(String),
    /// The `gltf` crate could not write the binary file.
    #[error("cannot write the binary glTF: {0}")]
    Write(String),
}

/// A building's vertex positions and triangles: a unit box on the ground,
/// `x` and `z` in −½..½, `y` in 0..1, its faces gridded, wound
/// counter-clockwise seen from outside.
fn building(columns: u32, storeys: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    let mut face = |o: Vec3, u: Vec3, v: Vec3, (n, m): (u32, u32)| {
        let base = u32::try_from(positions.len()).unwrap_or(u32::MAX);
        for j in 0..=m {
            for i in 0..=n {
                #[allow(clippy::cast_precision_loss, reason = "counts of at most 2¹⁰, exact in f32")]
                let (s, t) = (i as f32 / n as f32, j as f32 / m as f32);
                positions.push(o + u * s + v * t);
            }
        }
        let at = |i: u32, j: u32| base + j * (n + 1) + i;
        for j in 0..m {
            for i in 0..n {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    };
    let (h, up) = (0.5, Vec3::Y);
    let walls = (columns, storeys);
    face(Vec3::new(-h, 0.0, h), Vec3::X, up, walls);
    face(Vec3::new(h, 0.0, h), Vec3::NEG_Z, up, walls);
    face(Vec3::new(h, 0.0, -h), Vec3::NEG_X, up, walls);
    face(Vec3::new(-h, 0.0, -h), Vec3::Z, up, walls);
    face(Vec3::new(-h, 1.0, h), Vec3::X, Vec3::NEG_Z, (columns, columns));
    face(Vec3::new(-h, 0.0, -h), Vec3::X, Vec3::Z, (columns, columns));
    (positions, triangles)
}

/// A deterministic number in 0..1 for building `k` (a 32-bit mix).
fn hashed(k: u32) -> f32 {
    let mut x = k.wrapping_mul(0x9e37_79b9) ^ 0x85eb_ca6b;
    x ^= x >> 15;
    x = x.wrapping_mul(0x2c1b_3c6d);
    x ^= x >> 12;
    #[allow(clippy::cast_precision_loss, reason = "24 bits, exact in f32")]
    let unit = (x >> 8) as f32 / (1u32 << 24) as f32;
    unit
}

impl City {
    /// The city of the docs' million-triangle figures: 28 × 28 buildings
    /// of 8 columns and 16 storeys, 1 003 522 triangles.
    pub const MILLION: Self = Self { side: 28, columns: 8, storeys: 16 };

    /// The README's small example: 3 × 3 buildings of 4 columns and 8
    /// storeys.
    pub const SMALL: Self = Self { side: 3, columns: 4, storeys: 8 };

    /// Triangles of one building.
    #[must_use]
    pub const fn building_triangles(&self) -> u64 {
        let (c, s) = (self.columns as u64, self.storeys as u64);
        2 * (4 * c * s + 2 * c * c)
    }

    /// Triangles of the whole city: every building and the ground's two.
    #[must_use]
    pub const fn triangles(&self) -> u64 {
        self.side as u64 * self.side as u64 * self.building_triangles() + 2
    }

    /// Vertices of one building: each wall's and the roof's and floor's
    /// grid of corners.
    #[must_use]
    pub const fn building_vertices(&self) -> u64 {
        let (c, s) = (self.columns as u64 + 1, self.storeys as u64 + 1);
        4 * c * s + 2 * c * c
    }

    /// The most bytes a building's node takes in the file's JSON (its
    /// name, mesh, translation and scale, and its place in the scene's
    /// list; about 120 written).
    pub const JSON_PER_BUILDING: u64 = 160;

    /// The JSON besides the buildings' nodes, at most.
    const JSON_BASE: u64 = 4096;

    /// The largest of `n` powers of two (1, 2, 4, …) for which `fits`.
    fn largest_power(fits: impl Fn(u32) -> bool) -> Option<u32> {
        (0..16).map(|k| 1u32 << k).take_while(|&n| fits(n)).last()
    }

    /// Whether the city can be generated, and read back by a render within
    /// `limits`, checked before any of it is built: a side of at least 1,
    /// columns and storeys powers of two, a building within the 2¹⁶
    /// vertices its u16 indices number, and the whole within the
    /// triangles, the JSON and the memory `limits` allow. Each refusal
    /// names the options (`--side`, `--columns`, `--storeys`) and the
    /// largest value allowed.
    ///
    /// # Errors
    /// [`CityError::Counts`] naming what is wrong.
    pub fn check(&self, limits: &Limits) -> Result<(), CityError> {
        let Self { side, columns, storeys } = *self;
        let counts = |m: String| Err(CityError::Counts(m));
        if side == 0 || side > Self::MAX_SIDE || !columns.is_power_of_two() || !storeys.is_power_of_two() {
            return counts(format!(
                "--side {side} must be 1 to {}, --columns {columns} and --storeys {storeys} powers of two",
                Self::MAX_SIDE
            ));
        }
        let u16_vertices = u64::from(u16::MAX);
        if self.building_vertices() > u16_vertices {
            let with = |c: u32, s: u32| Self { side, columns: c, storeys: s }.building_vertices() <= u16_vertices;
            let most = |flag: &str, n: Option<u32>, (other, value): (&str, u32)| match n {
                Some(n) => format!("with {other} {value}, {flag} is at most {n}"),
                None => format!("with {other} {value}, no {flag} fits"),
            };
            return counts(format!(
                "--columns {columns} and --storeys {storeys} make a building of {} vertices, past the {u16_vertices} its 16-bit indices number: {}; {}",
                self.building_vertices(),
                most("--columns", Self::largest_power(|c| with(c, storeys)), ("--storeys", storeys)),
                most("--storeys", Self::largest_power(|s| with(columns, s)), ("--columns", columns)),
            ));
        }
        // The largest side every limit allows, for these buildings.
        let per = self.building_triangles();
        let by_triangles = ((limits.max_triangles.saturating_sub(2)) / per).isqrt();
        let by_text = (limits.max_text_bytes.saturating_sub(Self::JSON_BASE) / Self::JSON_PER_BUILDING).isqrt();
        let by_memory = (limits.max_memory.saturating_sub(Footprint::BASE) / Self::MEMORY_PER_BUILDING).isqrt();
        let most = by_triangles.min(by_text).min(by_memory);
        if u64::from(side) > most {
            let (what, limit) = if most == by_triangles {
                (format!("{} triangles", self.triangles()), format!("{} (`--max-triangles`)", limits.max_triangles))
            } else if most == by_text {
                (
                    format!("{} bytes of JSON", u64::from(side).pow(2) * Self::JSON_PER_BUILDING + Self::JSON_BASE),
                    format!("{} a render reads (`--max-text-bytes`)", limits.max_text_bytes),
                )
            } else {
                (
                    format!("{} MiB to generate", (u64::from(side).pow(2) * Self::MEMORY_PER_BUILDING) >> 20),
                    format!("{} MiB (`--max-memory`)", limits.max_memory >> 20),
                )
            };
            return counts(format!(
                "--side {side} makes {what}, above the limit of {limit}: with --columns {columns} and --storeys {storeys}, --side is at most {most}"
            ));
        }
        Ok(())
    }

    /// The largest side, whatever the limits: its buildings' places exact
    /// in f32.
    pub const MAX_SIDE: u32 = 4096;

    /// The most memory a building's node takes while the file is written
    /// (its JSON value, its text and its copy in the file).
    const MEMORY_PER_BUILDING: u64 = 4096;

    /// The city as a binary glTF file, within the default limits
    /// ([`City::glb_within`]).
    ///
    /// # Errors
    /// As [`City::glb_within`].
    pub fn glb(&self) -> Result<Vec<u8>, CityError> {
        self.glb_within(&Limits::DEFAULT)
    }

    /// The city as a binary glTF file, if [`City::check`] finds it within
    /// `limits`.
    ///
    /// # Errors
    /// [`CityError`] from [`City::check`], or from writing the file.
    pub fn glb_within(&self, limits: &Limits) -> Result<Vec<u8>, CityError> {
        let Self { side, columns, storeys } = *self;
        self.check(limits)?;
        let (positions, triangles) = building(columns, storeys);
        let ground = [
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(-1.0, 0.0, -1.0),
        ];
        // Buffer: building positions, building indices (u16), ground
        // positions, ground indices; each part 4-byte aligned.
        let mut bin: Vec<u8> = Vec::new();
        let push_positions = |bin: &mut Vec<u8>, points: &[Vec3]| {
            let at = bin.len();
            for p in points {
                for c in p.to_array() {
                    bin.extend_from_slice(&c.to_le_bytes());
                }
            }
            (at, bin.len() - at)
        };
        let push_indices = |bin: &mut Vec<u8>, tris: &[[u32; 3]]| {
            let at = bin.len();
            for i in tris.iter().flatten() {
                bin.extend_from_slice(&u16::try_from(*i).unwrap_or(u16::MAX).to_le_bytes());
            }
            let length = bin.len() - at;
            bin.resize(bin.len().next_multiple_of(4), 0);
            (at, length)
        };
        let (p0, pl0) = push_positions(&mut bin, &positions);
        let (i0, il0) = push_indices(&mut bin, &triangles);
        let (p1, pl1) = push_positions(&mut bin, &ground);
        let (i1, il1) = push_indices(&mut bin, &[[0, 1, 2], [0, 2, 3]]);
        let bounds = |points: &[Vec3]| {
            let lo = points.iter().fold(Vec3::INFINITY, |a, p| a.min(*p));
            let hi = points.iter().fold(Vec3::NEG_INFINITY, |a, p| a.max(*p));
            (lo.to_array(), hi.to_array())
        };
        let ((blo, bhi), (glo, ghi)) = (bounds(&positions), bounds(&ground));
        // Buildings on a grid of unit-spaced blocks centred on the origin,
        // each 0.5 to 0.8 of its block wide and 0.4 to 2.4 tall; the
        // ground reaches a block past the outer ones.
        #[allow(clippy::cast_precision_loss, reason = "a side of at most 4096, exact in f32")]
        let half = side as f32 / 2.0;
        let mut nodes = vec![json!({ "name": "ground", "mesh": 1, "scale": [half + 1.0, 1.0, half + 1.0] })];
        for k in 0..side * side {
            let (i, j) = (k % side, k / side);
            #[allow(clippy::cast_precision_loss, reason = "at most 4096, exact in f32")]
            let (x, z) = (i as f32 - half + 0.5, j as f32 - half + 0.5);
            let (w, d, h) = (0.5 + 0.3 * hashed(3 * k), 0.5 + 0.3 * hashed(3 * k + 1), 0.4 + 2.0 * hashed(3 * k + 2));
            nodes.push(
                json!({ "name": format!("building {k}"), "mesh": 0, "translation": [x, 0.0, z], "scale": [w, h, d] }),
            );
        }
        // The camera over the near corner, looking at the middle; the sun
        // low from the left; the spot light over the middle street.
        let camera_at = Vec3::new(-half - 2.5, half + 3.0, half + 2.5);
        // A node's rotation that turns its −Z from `from` towards `to`,
        // its +Y kept upright.
        let look = |from: Vec3, to: Vec3| {
            let forward = (to - from).normalize();
            let right = forward.cross(Vec3::Y).normalize();
            let up = right.cross(forward);
            glam::Quat::from_mat3(&glam::Mat3::from_cols(right, up, -forward)).normalize().to_array()
        };
        let n = nodes.len();
        nodes.push(json!({ "name": "camera", "camera": 0, "translation": camera_at.to_array(), "rotation": look(camera_at, Vec3::ZERO) }));
        let sun_from = Vec3::new(-3.0, 2.0, 1.0);
        nodes.push(json!({ "name": "sun", "rotation": look(sun_from, Vec3::ZERO),
            "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
        let lamp_at = Vec3::new(0.0, 2.0 + half * 0.5, 0.0);
        nodes.push(json!({ "name": "street lamp", "translation": lamp_at.to_array(),
            "rotation": look(lamp_at, Vec3::new(0.3, 0.0, 0.2)),
            "extensions": { "KHR_lights_punctual": { "light": 1 } } }));
        let document = json!({
            "asset": { "version": "2.0", "generator": concat!("umbra ", env!("CARGO_PKG_VERSION")) },
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": { "KHR_lights_punctual": { "lights": [
                { "name": "sun", "type": "directional", "intensity": 3.0 },
                { "name": "street lamp", "type": "spot", "intensity": 40.0,
                  "spot": { "innerConeAngle": 0.5, "outerConeAngle": 0.7 } }
            ] } },
            "scene": 0,
            "scenes": [{ "nodes": (0..n + 3).collect::<Vec<_>>() }],
            "nodes": nodes,
            "cameras": [{ "type": "perspective", "perspective": { "yfov": 0.8, "aspectRatio": 16.0 / 9.0, "znear": 0.5 } }],
            "meshes": [
                { "name": "building", "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] },
                { "name": "ground", "primitives": [{ "attributes": { "POSITION": 2 }, "indices": 3 }] }
            ],
            "buffers": [{ "byteLength": bin.len() }],
            "bufferViews": [
                { "buffer": 0, "byteOffset": p0, "byteLength": pl0 },
                { "buffer": 0, "byteOffset": i0, "byteLength": il0 },
                { "buffer": 0, "byteOffset": p1, "byteLength": pl1 },
                { "buffer": 0, "byteOffset": i1, "byteLength": il1 }
            ],
            "accessors": [
                { "bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3", "min": blo, "max": bhi },
                { "bufferView": 1, "componentType": 5123, "count": triangles.len() * 3, "type": "SCALAR" },
                { "bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3", "min": glo, "max": ghi },
                { "bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR" }
            ]
        });
        let json = serde_json::to_vec(&document).map_err(|e| CityError::Write(e.to_string()))?;
        let header = gltf::binary::Header { magic: *b"glTF", version: 2, length: 0 };
        gltf::binary::Glb { header, json: Cow::Owned(json), bin: Some(Cow::Owned(bin)) }
            .to_vec()
            .map_err(|e| CityError::Write(e.to_string()))
    }
}
