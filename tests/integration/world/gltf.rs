//! glTF files: node transforms and instances against positions worked by
//! hand, primitive modes against the specification's numbering, cameras
//! and lights against views built by hand, and malformed files (written
//! here, and Debian's `assimp-testmodels`) each refused by name.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};
use umbra::core::glam::{Mat4, Vec3};
use umbra::sim::input::limits::Limits;
use umbra::sim::world::gltf::{Gltf, GltfProblem};
use umbra::sim::world::scene::{Camera, Light, Perspective, Scene};
use umbra::sim::world::scene_file::{Problem, SceneError};

use crate::common::scratch;

/// A binary glTF of `json` and `bin`, written by hand from the
/// specification (12-byte header, JSON chunk padded with spaces, BIN
/// chunk padded with zeros).
pub fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).expect("json");
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut b = bin.to_vec();
    b.resize(b.len().next_multiple_of(4), 0);
    let length = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(length as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    if !b.is_empty() {
        out.extend_from_slice(&(b.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&b);
    }
    out
}

/// The unit cube's 8 corners and 12 triangles, wound outward.
fn cube() -> (Vec<[f32; 3]>, Vec<u16>) {
    let p = (0..8).map(|k| [(k & 1) as f32, ((k >> 1) & 1) as f32, ((k >> 2) & 1) as f32]).collect();
    #[rustfmt::skip]
    let t = vec![
        0, 2, 1, 1, 2, 3, // z = 0, facing −z
        4, 5, 6, 5, 7, 6, // z = 1
        0, 1, 4, 1, 5, 4, // y = 0
        2, 6, 3, 3, 6, 7, // y = 1
        0, 4, 2, 2, 4, 6, // x = 0
        1, 3, 5, 3, 7, 5, // x = 1
    ];
    (p, t)
}

/// Positions then u16 indices as one buffer, with the glTF accessors and
/// views for them; `extra` JSON merged over the document.
fn mesh_file(positions: &[[f32; 3]], indices: &[u16], mode: u32, extra: Value) -> (Value, Vec<u8>) {
    let mut bin: Vec<u8> = positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
    let at = bin.len();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    let lo = positions.iter().fold([f32::MAX; 3], |a, p| [a[0].min(p[0]), a[1].min(p[1]), a[2].min(p[2])]);
    let hi = positions.iter().fold([f32::MIN; 3], |a, p| [a[0].max(p[0]), a[1].max(p[1]), a[2].max(p[2])]);
    let mut doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1, "mode": mode }] }],
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": at },
            { "buffer": 0, "byteOffset": at, "byteLength": bin.len() - at }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5123, "count": indices.len(), "type": "SCALAR" }
        ]
    });
    if let (Some(d), Value::Object(e)) = (doc.as_object_mut(), extra) {
        d.extend(e);
    }
    (doc, bin)
}

/// Write `bytes` as `name` in `dir`, a scratch folder of the test's.
fn file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

fn read(path: &Path) -> Result<Gltf, umbra::sim::world::gltf::GltfError> {
    Gltf::read(path, None, &Limits::DEFAULT)
}

/// A cube instanced by two child nodes of a parent turned 90° about y,
/// scaled by 2 and moved by (1, 0, 0); the second child is raised by 3.
/// Worked by hand: the parent maps `(x, y, z)` to `(2z + 1, 2y, −2x)`.
#[test]
fn node_transforms_and_instances_place_the_mesh_as_worked_by_hand() {
    let dir = scratch("gltf-instances");
    let (p, t) = cube();
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let nodes = json!({ "scenes": [{ "nodes": [0] }], "nodes": [
        { "name": "parent", "rotation": [0.0, s, 0.0, s], "scale": [2.0, 2.0, 2.0], "translation": [1.0, 0.0, 0.0], "children": [1, 2] },
        { "name": "low", "mesh": 0 },
        { "name": "high", "mesh": 0, "translation": [0.0, 3.0, 0.0] }
    ]});
    let (doc, bin) = mesh_file(&p, &t, 4, nodes);
    let g = read(&file(&dir, "cube.glb", &glb(&doc, &bin))).expect("reads");
    assert_eq!(g.instances.len(), 2, "one instance per node that places the mesh");
    let by_hand = |[x, y, z]: [f32; 3], raise: f32| Vec3::new(2.0 * z + 1.0, 2.0 * (y + raise), -2.0 * x);
    for (instance, raise) in g.instances.iter().zip([0.0, 3.0]) {
        assert_eq!(instance.mesh.triangles.len(), 12);
        for (got, corner) in instance.mesh.positions.iter().zip(&p) {
            let want = by_hand(*corner, raise);
            assert!((*got - want).abs().max_element() < 1e-6, "{}: {got} ≠ {want}", instance.name);
        }
        assert!(instance.mesh.is_closed(), "a rotation keeps the winding outward");
    }
    assert_eq!((g.instances[0].name.as_str(), g.instances[1].name.as_str()), ("low", "high"));
    // The same placement as a matrix (column-major) gives the same points.
    let m = Mat4::from_scale_rotation_translation(
        Vec3::splat(2.0),
        umbra::core::glam::Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
        Vec3::X,
    );
    let nodes = json!({ "scenes": [{ "nodes": [0] }], "nodes": [{ "matrix": m.to_cols_array(), "mesh": 0 }] });
    let (doc, bin) = mesh_file(&p, &t, 4, nodes);
    let g = read(&file(&dir, "matrix.glb", &glb(&doc, &bin))).expect("reads");
    for (got, corner) in g.instances[0].mesh.positions.iter().zip(&p) {
        assert!((*got - by_hand(*corner, 0.0)).abs().max_element() < 1e-6);
    }
}

/// A mirroring node (a negative scale) turns the winding back, so the
/// mirrored cube is still wound outward, as the glTF specification says.
#[test]
fn a_mirroring_node_keeps_faces_outward() {
    let dir = scratch("gltf-mirror");
    let (p, t) = cube();
    let nodes = json!({ "nodes": [{ "mesh": 0, "scale": [-1.0, 1.0, 1.0] }] });
    let (doc, bin) = mesh_file(&p, &t, 4, nodes);
    let g = read(&file(&dir, "m.glb", &glb(&doc, &bin))).expect("reads");
    let m = &g.instances[0].mesh;
    let centre = m.positions.iter().copied().sum::<Vec3>() / m.positions.len() as f32;
    for tri in &m.triangles {
        let [a, b, c] = tri.map(|i| m.positions[i as usize]);
        let outward = (b - a).cross(c - a).dot((a + b + c) / 3.0 - centre);
        assert!(outward > 0.0, "triangle {tri:?} faces in");
    }
}

/// Strips and fans number their triangles as the specification does;
/// points and lines are counted and left out.
#[test]
fn strips_fans_points_and_lines_follow_the_specification() {
    let dir = scratch("gltf-modes");
    let p: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [2.0, 0.5, 0.0]];
    let idx: Vec<u16> = vec![0, 1, 2, 3, 4];
    let tris = |mode| {
        read(&file(&dir, &format!("{mode}.glb"), &{
            let (d, b) = mesh_file(&p, &idx, mode, json!({}));
            glb(&d, &b)
        }))
    };
    // Strip: p_i = {v_i, v_(i+1+i%2), v_(i+2−i%2)}.
    assert_eq!(tris(5).expect("strip").instances[0].mesh.triangles, vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]);
    // Fan: p_i = {v_(i+1), v_(i+2), v_0}.
    assert_eq!(tris(6).expect("fan").instances[0].mesh.triangles, vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]);
    // Points alone: no triangle at all, refused as empty.
    let points = tris(0).expect_err("no triangle");
    assert!(matches!(points.problem, GltfProblem::Empty), "{points}");
    // Lines beside triangles: counted, left out.
    let two = json!({ "meshes": [{ "primitives": [
        { "attributes": { "POSITION": 0 }, "indices": 1, "mode": 4 },
        { "attributes": { "POSITION": 0 }, "indices": 1, "mode": 3 },
        { "attributes": { "POSITION": 0 }, "mode": 0 }
    ] }] });
    let (d, b) = mesh_file(&p, &[0, 1, 2], 4, two);
    let g = read(&file(&dir, "lines.glb", &glb(&d, &b))).expect("reads");
    let m = &g.instances[0].mesh;
    assert_eq!((m.triangles.len(), m.ignored.segments, m.ignored.points), (1, 2, 5));
}

/// A node's camera looks down its −Z with +Y up, its `yfov` the vertical
/// field of view: against a perspective built by hand for the same view.
/// A spot light's field of view is twice its outer cone angle, its far
/// plane its range.
#[test]
fn cameras_and_lights_follow_gltf_conventions() {
    let dir = scratch("gltf-views");
    let (p, t) = cube();
    // Turned 30° about x (looking down), at (0.5, 2, 4).
    let a = 15f32.to_radians();
    let down = [-a.sin(), 0.0, 0.0, a.cos()];
    let extra = json!({
        "scenes": [{ "nodes": [0, 1, 2] }],
        "nodes": [
            { "mesh": 0 },
            { "name": "eye", "camera": 0, "translation": [0.5, 2.0, 4.0], "rotation": down },
            { "name": "lamp", "translation": [0.5, 5.0, 0.5], "rotation": [-std::f32::consts::FRAC_1_SQRT_2, 0.0, 0.0, std::f32::consts::FRAC_1_SQRT_2],
              "extensions": { "KHR_lights_punctual": { "light": 0 } } }
        ],
        "cameras": [{ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.5, "zfar": 30.0, "aspectRatio": 2.0 } }],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [{ "type": "spot", "range": 9.0, "spot": { "outerConeAngle": 0.5 } }] } }
    });
    let (doc, bin) = mesh_file(&p, &t, 4, extra);
    let path = file(&dir, "views.glb", &glb(&doc, &bin));
    let scene = Scene::open(path.to_str().expect("utf-8"), &Limits::DEFAULT).expect("opens");
    assert_eq!(scene.image, [1080, 540], "the camera's aspect ratio at 540 rows");
    let (s, c) = (30f32.to_radians().sin(), 30f32.to_radians().cos());
    let by_hand = Perspective {
        position: Vec3::new(0.5, 2.0, 4.0),
        target: Vec3::new(0.5, 2.0 - s, 4.0 - c),
        fov_degrees: 0.8f32.to_degrees(),
        near: 0.5,
        far: 30.0,
        up: Vec3::new(0.0, c, -s),
    };
    let (got, want) = (scene.camera.view_projection_aspect(2.0), by_hand.view_projection_aspect(2.0));
    assert!(got.abs_diff_eq(want, 1e-5), "{got} ≠ {want}");
    let Some(Light::Cone(spot)) = scene.lights.first() else { panic!("a spot light: {:?}", scene.lights) };
    assert!((spot.fov_degrees - 1.0f32.to_degrees()).abs() < 1e-4, "{}", spot.fov_degrees);
    assert_eq!(spot.far, 9.0);
    assert!((spot.target - spot.position).normalize().abs_diff_eq(Vec3::NEG_Y, 1e-6), "straight down");
    assert_eq!(scene.notes, ["lights: lights[0] `lamp`"], "the light is named, no view stood in");
    assert!(matches!(scene.camera, Camera::Perspective(_)));
}

/// A file without a light: the spot light standing in is named with where
/// it stands, and `--light-from` moves it, worked by hand for the unit
/// cube (centre (0.5, 0.5, 0.5), bounding radius √3 / 2): from (0.5, 5.5,
/// 0.5), 5 above the centre, it looks straight down with a field of view
/// of 2 · asin(0.866 / 5) · 1.1 = 21.9°, near 5 − 1.2 · 0.866 = 3.96;
/// within 1.2 radii of the centre it is refused.
#[test]
fn a_substitute_light_is_named_and_moves() {
    use umbra::sim::world::relight::RelightError;
    let dir = scratch("gltf-relight");
    let (p, t) = cube();
    let (doc, bin) = mesh_file(&p, &t, 4, json!({}));
    let path = file(&dir, "dark.glb", &glb(&doc, &bin));
    let scene = Scene::open(path.to_str().expect("utf-8"), &Limits::DEFAULT).expect("opens");
    let Some(Light::Spot(standing)) = scene.lights.first().copied() else { panic!("{:?}", scene.lights) };
    let where_ = format!("a spot light at {},{},{}", standing.position.x, standing.position.y, standing.position.z);
    assert!(scene.notes.iter().any(|n| n.contains(&where_) && n.contains("--light-from")), "{:?}", scene.notes);
    let moved = scene.clone().with_light_from(Vec3::new(0.5, 5.5, 0.5)).expect("outside the cube");
    let Some(Light::Spot(view)) = moved.lights.first().copied() else { panic!("{:?}", moved.lights) };
    assert_eq!((view.position, view.target), (Vec3::new(0.5, 5.5, 0.5), Vec3::splat(0.5)));
    let radius = 3f32.sqrt() / 2.0;
    assert!((view.fov_degrees - 2.0 * (radius / 5.0).asin().to_degrees() * 1.1).abs() < 1e-4, "{}", view.fov_degrees);
    assert!((view.fov_degrees - 21.94).abs() < 0.01, "{}", view.fov_degrees);
    assert!((view.near - (5.0 - 1.2 * radius)).abs() < 1e-5 && (view.far - (5.0 + 1.2 * radius)).abs() < 1e-5);
    assert!(moved.arguments().ends_with("--light-from 0.5,5.5,0.5"), "{}", moved.arguments());
    let inside = scene.with_light_from(Vec3::new(0.5, 1.4, 0.5)).expect_err("0.9 from the centre");
    assert!(matches!(inside, RelightError::Inside { .. }), "{inside}");
}

/// What a scene file's `mesh = { gltf = …, node = … }` reads: the node and
/// what lies under it, placed where the glTF places it, then the scene
/// file's own transform.
#[test]
fn a_scene_file_takes_a_gltf_node() {
    let (p, t) = cube();
    let nodes = json!({ "scenes": [{ "nodes": [0, 2] }], "nodes": [
        { "name": "left", "translation": [-5.0, 0.0, 0.0], "children": [1] },
        { "name": "inner", "mesh": 0 },
        { "name": "right", "mesh": 0, "translation": [5.0, 0.0, 0.0] }
    ]});
    let (doc, bin) = mesh_file(&p, &t, 4, nodes);
    let dir = scratch("gltf-scene-file");
    std::fs::write(dir.join("two.glb"), glb(&doc, &bin)).expect("write");
    let text = crate::world::scenes::GOOD.replace(
        "mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.5, stacks = 8, slices = 16 } }",
        "mesh = { gltf = \"two.glb\", node = \"left\" }\ntranslate = [0.0, 1.0, 0.0]",
    );
    assert!(text.contains("two.glb"), "the scene's mesh line changed");
    let scene = Scene::parse(&text, &dir.join("s.toml"), &Limits::DEFAULT).expect("parses");
    let mesh = &scene.objects.iter().find(|o| o.mesh.triangles.len() == 12).expect("the cube").mesh;
    for (got, [x, y, z]) in mesh.positions.iter().zip(&p) {
        assert_eq!(*got, Vec3::new(x - 5.0, y + 1.0, *z));
    }
    assert!(scene.objects.iter().any(|o| o.solid && o.mesh.triangles.len() == 12), "a closed cube is solid");
    let bad = text.replace("node = \"left\"", "node = \"nowhere\"");
    let e = Scene::parse(&bad, &dir.join("s.toml"), &Limits::DEFAULT).expect_err("no such node");
    assert!(e.to_string().contains("two.glb") && e.to_string().contains("nowhere"), "{e}");
}

/// The error of a file that must be refused, with the JSON path it names.
fn refused(path: &Path) -> (String, GltfProblem) {
    let e = read(path).expect_err(&format!("{} must be refused", path.display()));
    assert_eq!(e.file, path, "{e}");
    (e.path, e.problem)
}

/// Files written wrong in each way a file can be: each refused by name,
/// never a panic or an allocation past the limits.
#[test]
fn malformed_files_are_refused_by_name() {
    let dir = scratch("gltf-malformed");
    let (p, t) = cube();
    let good = |extra: Value| {
        let (d, b) = mesh_file(&p, &t, 4, extra);
        glb(&d, &b)
    };
    let whole = good(json!({}));
    let write = |name: &str, bytes: &[u8]| file(&dir, name, bytes);
    // Truncated: the header says more than the file holds.
    let (at, problem) = refused(&write("truncated.glb", &whole[..whole.len() / 2]));
    assert!(at.starts_with('(') && matches!(problem, GltfProblem::Syntax(_)), "{at}: {problem}");
    // A header shorter than a header, and a length below the header's own.
    for (name, bytes) in
        [("short.glb", b"glTF\x02\0\0\0".to_vec()), ("tiny.glb", [&b"glTF\x02\0\0\0\x04\0\0\0"[..], &[0; 12]].concat())]
    {
        let (_, problem) = refused(&write(name, &bytes));
        assert!(matches!(problem, GltfProblem::Syntax(_)), "{name}: {problem}");
    }
    // A buffer view past its buffer.
    let past = good(json!({ "bufferViews": [
        { "buffer": 0, "byteOffset": 0, "byteLength": 96 },
        { "buffer": 0, "byteOffset": 96, "byteLength": 4000 }
    ]}));
    let (at, problem) = refused(&write("past.glb", &past));
    assert!(at == "bufferViews[1]" && matches!(problem, GltfProblem::Buffer(_)), "{at}: {problem}");
    // A count of 2³²: refused by the limits before anything is allocated.
    let huge = good(json!({ "accessors": [
        { "bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1] },
        { "bufferView": 1, "componentType": 5123, "count": 4_294_967_296u64, "type": "SCALAR" }
    ]}));
    let (at, problem) = refused(&write("huge.glb", &huge));
    assert!(at == "meshes" && matches!(problem, GltfProblem::Limit(_)), "{at}: {problem}");
    // An index past the vertices.
    let mut bad_index = t.clone();
    bad_index[5] = 8;
    let (d, b) = mesh_file(&p, &bad_index, 4, json!({}));
    let (at, problem) = refused(&write("index.glb", &glb(&d, &b)));
    assert!(
        at.ends_with(".indices") && matches!(problem, GltfProblem::Index { element: 5, vertices: 8 }),
        "{at}: {problem}"
    );
    // A NaN vertex.
    let mut nan = p.clone();
    nan[3][1] = f32::NAN;
    let (d, b) = mesh_file(&nan, &t, 4, json!({}));
    let (_, problem) = refused(&write("nan.glb", &glb(&d, &b)));
    assert!(matches!(problem, GltfProblem::NonFinite { element: 3, .. }), "{problem}");
    // A Draco-compressed primitive the file requires: refused by name.
    let draco = good(
        json!({ "extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"] }),
    );
    let (_, problem) = refused(&write("draco.glb", &draco));
    assert!(matches!(&problem, GltfProblem::Unsupported(n) if n == "KHR_draco_mesh_compression"), "{problem}");
    // A point light, named.
    let point = good(
        json!({ "scenes": [{ "nodes": [0, 1] }], "nodes": [{ "mesh": 0 }, { "extensions": { "KHR_lights_punctual": { "light": 0 } } }],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [{ "name": "bulb", "type": "point" }] } } }),
    );
    let (at, problem) = refused(&write("point.glb", &point));
    assert!(
        at.ends_with("lights[0]") && matches!(&problem, GltfProblem::PointLight(n) if n == "bulb"),
        "{at}: {problem}"
    );
    // A node its own ancestor, and a node with two parents.
    for (name, nodes) in [
        ("cycle.glb", json!([{ "mesh": 0, "children": [1] }, { "children": [0] }])),
        ("parents.glb", json!([{ "mesh": 0, "children": [2] }, { "children": [2] }, {}])),
    ] {
        let (at, problem) = refused(&write(name, &good(json!({ "scenes": [{ "nodes": [0] }], "nodes": nodes }))));
        assert!(at.starts_with("nodes[") && matches!(problem, GltfProblem::Nodes(_)), "{name}: {at}: {problem}");
    }
    // A missing buffer file and a data URI that is not base64.
    let (doc, _) = mesh_file(&p, &t, 4, json!({ "buffers": [{ "byteLength": 120, "uri": "absent.bin" }] }));
    let (at, problem) = refused(&write("missing.gltf", &serde_json::to_vec(&doc).expect("json")));
    assert!(at == "buffers[0].uri" && matches!(problem, GltfProblem::Read(_)), "{at}: {problem}");
    let (doc, _) = mesh_file(&p, &t, 4, json!({ "buffers": [{ "byteLength": 120, "uri": "data:text/plain,hello" }] }));
    let (at, problem) = refused(&write("data.gltf", &serde_json::to_vec(&doc).expect("json")));
    assert!(at == "buffers[0].uri" && matches!(problem, GltfProblem::Buffer(_)), "{at}: {problem}");
    // Not glTF at all.
    let (_, problem) = refused(&write("text.gltf", b"solid cube\nendsolid\n"));
    assert!(matches!(problem, GltfProblem::Syntax(_)), "{problem}");
    // A camera that is not there, through the scene.
    let e: SceneError =
        Scene::open_with_camera(write("good.glb", &whole).to_str().expect("utf-8"), Some("7"), &Limits::DEFAULT)
            .expect_err("no camera 7");
    assert!(matches!(e.problem, Problem::Gltf(GltfProblem::NoCamera { .. })), "{e}");
}

/// Debian's `assimp-testmodels`, where the package is installed.
const MODELS: &str = "/usr/share/assimp/models/glTF2";

/// The package's deliberately broken models, each refused by name.
#[test]
#[ignore = "needs Debian's assimp-testmodels: run with `cargo test --test integration -- --ignored --skip firmware --skip shared_mesh`"]
fn the_packages_broken_models_are_refused_by_name() {
    for (file, at, kind) in [
        ("IndexOutOfRange/IndexOutOfRange.gltf", "meshes[0].primitives[0].indices", "index"),
        ("IndexOutOfRange/AllIndicesOutOfRange.gltf", "meshes[0].primitives[0].indices", "index"),
        ("RecursiveNodes/RecursiveNodes.gltf", "nodes[0]", "nodes"),
        ("MissingBin/BoxTextured.gltf", "buffers[0].uri", "read"),
        ("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "meshes[0].primitives[0]", "invalid"),
        ("SchemaFailures/sceneWrongType.gltf", "(json)", "syntax"),
        ("TestNoRootNode/NoScene.gltf", "scene", "invalid"),
        ("TestNoRootNode/SceneWithoutNodes.gltf", "(json)", "syntax"),
        ("draco/2CylinderEngine.gltf", "extensionsRequired[0]", "unsupported"),
    ] {
        let path = Path::new(MODELS).join(file);
        let (got, problem) = refused(&path);
        let kind_of = match problem {
            GltfProblem::Index { .. } => "index",
            GltfProblem::Nodes(_) => "nodes",
            GltfProblem::Read(_) => "read",
            GltfProblem::Invalid(_) => "invalid",
            GltfProblem::Syntax(_) => "syntax",
            GltfProblem::Unsupported(_) => "unsupported",
            _ => "other",
        };
        assert!(got.starts_with(at) && kind_of == kind, "{file}: {got}: {problem}");
    }
}

/// Every model of the package outside the broken ones above opens as a
/// scene, or is refused for what Umbra states it does not read (an
/// extension it does not decode, a point light, no triangle); none is
/// refused by the checks of hostile input (a buffer outside the folder,
/// the specification's rules, the memory bound).
#[test]
#[ignore = "needs Debian's assimp-testmodels: run with `cargo test --test integration -- --ignored --skip firmware --skip shared_mesh`"]
fn every_valid_model_of_the_package_still_opens() {
    // The package's deliberately broken models: those above, and those
    // whose JSON breaks the schema (each refused by the `gltf` crate).
    let broken = [
        "IndexOutOfRange",
        "RecursiveNodes",
        "MissingBin",
        "BoxWithInfinites",
        "SchemaFailures",
        "TestNoRootNode",
        "IncorrectVertexArrays",
        "wrongTypes",
    ];
    let mut files = Vec::new();
    let mut stack = vec![PathBuf::from(MODELS)];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).expect("the package's folder").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "gltf" || x == "glb") {
                files.push(p);
            }
        }
    }
    files.sort();
    let (mut opened, mut stated, mut wrong) = (0, Vec::new(), Vec::new());
    for f in files.iter().filter(|f| !broken.iter().any(|b| f.to_string_lossy().contains(b))) {
        match Scene::of_gltf(f, None, &Limits::DEFAULT) {
            Ok(_) => opened += 1,
            Err(SceneError { problem: Problem::Gltf(p), key, .. })
                if matches!(p, GltfProblem::Unsupported(_) | GltfProblem::PointLight(_) | GltfProblem::Empty) =>
            {
                stated.push(format!("{}: {key}: {p}", f.display()));
            }
            Err(e) => wrong.push(e.to_string()),
        }
    }
    eprintln!("{opened} opened; refused as stated: {stated:#?}");
    assert!(wrong.is_empty(), "valid models refused: {wrong:#?}");
    // 22 open with Debian 12's package (and 10 are refused as stated): a
    // walk that found nothing, or a loader that refuses many, fails here.
    assert!(opened >= 20, "{opened} of {} opened", files.len());
}

/// The package's engine renders, and its file of two cameras gives both.
#[test]
#[ignore = "needs Debian's assimp-testmodels: run with `cargo test --test integration -- --ignored --skip firmware --skip shared_mesh`"]
fn the_packages_engine_renders_and_its_cameras_are_both_read() {
    use umbra::sim::render::{RenderConfig, TruthSource, render};
    let engine = format!("{MODELS}/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
    let scene = Scene::open(&engine, &Limits::DEFAULT).expect("opens");
    assert!(scene.objects.iter().map(|o| o.mesh.triangles.len()).sum::<usize>() > 100_000);
    let cfg = RenderConfig { width: 160, height: 160, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };
    let r = render(&cfg.check(&scene, &Limits::DEFAULT).expect("fits"), TruthSource::Quiet).expect("renders");
    assert!(r.metrics.evaluated > 5000, "{}", r.metrics.evaluated);
    let cameras = format!("{MODELS}/cameras/Cameras.gltf");
    let perspective = Scene::open_with_camera(&cameras, Some("0"), &Limits::DEFAULT).expect("camera 0");
    let orthographic = Scene::open_with_camera(&cameras, Some("1"), &Limits::DEFAULT).expect("camera 1");
    assert!(matches!(perspective.camera, Camera::Perspective(_)));
    assert!(matches!(orthographic.camera, Camera::Orthographic(o) if o.extent == 1.0));
    assert_eq!(orthographic.arguments(), format!("{cameras} --camera 1"));
}

/// The same mesh converted from OBJ to glTF by an independent tool
/// (`assimp export`) draws the same light-view maps, bit for bit.
#[test]
#[ignore = "needs Debian's assimp-utils: run with `cargo test --test integration -- --ignored --skip firmware --skip shared_mesh`"]
fn an_obj_converted_by_assimp_draws_the_same_maps() {
    use umbra::core::{CullMode, DepthUnit, LightPassConfig, RasterConfig};
    use umbra::sim::pass::light::{self, LightFrame, LightOptions};
    let dir = scratch("gltf-assimp");
    let obj = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/torus.obj");
    let out = dir.join("torus.gltf");
    let status = std::process::Command::new("assimp")
        .arg("export")
        .arg(&obj)
        .arg(&out)
        .arg("-fgltf2")
        .status()
        .expect("assimp runs");
    assert!(status.success(), "assimp export failed");
    let a = Scene::of_obj(&obj, &Limits::DEFAULT).expect("the OBJ");
    let b = Scene::open(out.to_str().expect("utf-8"), &Limits::DEFAULT).expect("the glTF");
    let view = a.light().view_projection();
    let raster = RasterConfig::new(512, 512, 32, 8).expect("raster");
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let maps = |s: &Scene| {
        let draws = s.draws(view, CullMode::None);
        let mut frame = LightFrame::new();
        let (m, _) = light::render::<umbra::core::D24, _, { light::DEFAULT_BIN_CAPACITY }>(
            &mut frame,
            config,
            &draws,
            LightOptions::default(),
            umbra::core::NoProbe,
        )
        .expect("draws");
        (m.z1.clone(), m.z2.clone())
    };
    let (za, zb) = (maps(&a), maps(&b));
    assert!(za.0.iter().any(|&z| z != za.0[0]), "the torus is in view");
    assert!(za == zb, "the converted file draws other maps");
}

/// The full Stanford bunny from Debian's `glmark2-data` (69 666 faces):
/// read, every face a triangle, and rendered.
#[test]
#[ignore = "needs Debian's glmark2-data: run with `cargo test --test integration -- --ignored --skip firmware --skip shared_mesh`"]
fn the_full_bunny_from_glmark2_renders() {
    use umbra::sim::render::{RenderConfig, TruthSource, render};
    let bunny = Path::new("/usr/share/glmark2/models/bunny.obj");
    let scene = Scene::of_obj(bunny, &Limits::DEFAULT).expect("reads");
    assert_eq!(scene.objects[0].mesh.triangles.len(), 69_666);
    let cfg = RenderConfig { width: 128, height: 128, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };
    let r = render(&cfg.check(&scene, &Limits::DEFAULT).expect("fits"), TruthSource::Quiet).expect("renders");
    // 2840 pixels measured: the bunny, framed, covers a sixth of the image
    // and faces the light on most of it; an empty or unlit render has none.
    assert!(r.metrics.evaluated > 2000, "{}", r.metrics.evaluated);
}

/// `examples/city.glb` is what `umbra scene city` writes at its default
/// size, byte for byte; every building closed (solid), both lights read.
#[test]
fn the_bundled_city_is_the_generated_one() {
    use umbra::sim::world::gltf::City;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/city.glb");
    let shipped = std::fs::read(&path).expect("examples/city.glb");
    assert!(
        shipped == City::SMALL.glb().expect("generates"),
        "regenerate it: cargo umbra scene city --out out/scene-city"
    );
    let scene = Scene::open(path.to_str().expect("utf-8"), &Limits::DEFAULT).expect("opens");
    let buildings: Vec<_> = scene.objects.iter().filter(|o| o.name.starts_with("building")).collect();
    assert_eq!(buildings.len(), 9);
    assert!(buildings.iter().all(|o| o.solid && o.mesh.triangles.len() as u64 == City::SMALL.building_triangles()));
    assert!(matches!(scene.lights.as_slice(), [Light::Directional(..), Light::Cone(_)]), "{:?}", scene.lights);
}
