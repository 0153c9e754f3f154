//! glTF files as an adversary writes them: buffers that name files
//! outside the model's folder, JSON the `gltf` crate's validation would
//! index unchecked, declared counts far past the memory allowed, cameras,
//! transforms and strides the specification forbids, and `.glb` chunks
//! that lie. Each is refused by name, before the work it would cost, and
//! no message echoes a byte of another file.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};
use umbra::sim::base::reads::{allow_folder, was_read};
use umbra::sim::input::limits::{LimitError, Limits};
use umbra::sim::world::gltf::{Gltf, GltfProblem};
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::Problem;

use super::gltf::glb;
use crate::common::scratch;

/// A one-triangle model whose positions and indices are in `buffer`
/// (`uri`, or the `.glb`'s chunk when `None`), `extra` merged over it.
fn triangle(uri: Option<&str>, extra: Value) -> Value {
    let mut buffer = json!({ "byteLength": 44 });
    if let Some(uri) = uri {
        buffer["uri"] = uri.into();
    }
    let mut doc = json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [buffer],
        "bufferViews": [{ "buffer": 0, "byteLength": 36 }, { "buffer": 0, "byteOffset": 36, "byteLength": 8 }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ]
    });
    if let (Some(d), Value::Object(e)) = (doc.as_object_mut(), extra) {
        d.extend(e);
    }
    doc
}

/// The triangle's 44 bytes: (0, 0, 0), (1, 0, 0), (0, 1, 0), indices 0 1 2
/// and two bytes of padding.
fn triangle_bytes() -> Vec<u8> {
    let p: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let mut b: Vec<u8> = p.iter().flat_map(|c| c.to_le_bytes()).collect();
    b.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    b
}

/// Write `json` as `name` in `dir`.
fn write(dir: &Path, name: &str, json: &Value) -> PathBuf {
    std::fs::create_dir_all(dir).expect("dir");
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(json).expect("json")).expect("write");
    path
}

/// The JSON path and problem of a refused read.
fn refused(path: &Path, limits: &Limits) -> (String, GltfProblem) {
    match Gltf::read(path, None, limits) {
        Ok(_) => panic!("{} was read", path.display()),
        Err(e) => (e.path, e.problem),
    }
}

/// Every way a buffer's URI can name a file outside the model's folder —
/// a relative `..`, the same percent-encoded, an absolute path, a scheme,
/// a system file, a symbolic link out — is refused by name before the
/// file is opened (it is never read, and its bytes are in no message);
/// the same file in the folder, or in a folder the user allowed, is read.
#[cfg(unix)]
#[test]
fn a_buffer_outside_the_models_folder_is_refused_before_it_is_read() {
    let base = scratch("gltf-confined");
    let (model, outside) = (base.join("model"), base.join("outside"));
    std::fs::create_dir_all(&outside).expect("dir");
    let secret = outside.join("secret.bin");
    let mut bytes = triangle_bytes();
    bytes[..4].copy_from_slice(b"PRET");
    std::fs::write(&secret, &bytes).expect("a file outside");
    std::os::unix::fs::symlink(&secret, {
        std::fs::create_dir_all(&model).expect("dir");
        model.join("link.bin")
    })
    .expect("a link out");
    let absolute = secret.to_str().expect("UTF-8").to_owned();
    for (uri, why) in [
        ("../outside/secret.bin", "climbs out"),
        ("sub/../../outside/secret.bin", "climbs out"),
        ("%2e%2e/outside/secret.bin", "climbs out"),
        ("..%2Foutside%2Fsecret.bin", "climbs out"),
        (absolute.as_str(), "absolute path"),
        ("/proc/self/environ", "absolute path"),
        ("file:///etc/passwd", "`file:` URI"),
        ("https://example.com/a.bin", "`https:` URI"),
        ("link.bin", "symbolic link"),
    ] {
        let (at, problem) = refused(&write(&model, "m.gltf", &triangle(Some(uri), json!({}))), &Limits::DEFAULT);
        let message = problem.to_string();
        assert!(at == "buffers[0].uri" && matches!(problem, GltfProblem::Outside(_)), "{uri}: {at}: {message}");
        assert!(message.contains(why) && message.contains("--allow-read"), "{uri}: {message}");
        assert!(!message.contains("PRET") && !message.contains("1413829200"), "{uri}: echoes the file: {message}");
    }
    assert!(!was_read(&secret), "the file outside was opened");
    // The same bytes in the model's folder are read, and a folder the user
    // allows is read through the link.
    std::fs::write(model.join("own.bin"), triangle_bytes()).expect("a buffer beside it");
    let g = Gltf::read(&write(&model, "own.gltf", &triangle(Some("own.bin"), json!({}))), None, &Limits::DEFAULT)
        .expect("its own folder");
    assert_eq!(g.instances[0].mesh.triangles.len(), 1);
    allow_folder(&outside).expect("allowed");
    Gltf::read(&write(&model, "l.gltf", &triangle(Some("link.bin"), json!({}))), None, &Limits::DEFAULT)
        .expect("read through a folder the user allowed");
    assert!(was_read(&secret), "an allowed folder is read");
}

/// A primitive that names an accessor the file does not have: the `gltf`
/// crate's validation indexes it unchecked (a panic); Umbra refuses it
/// naming the attribute, as a file, a scene file's mesh and through
/// `Scene::open`.
#[test]
fn an_accessor_that_does_not_exist_is_refused_not_a_panic() {
    let base = scratch("gltf-panic");
    let doc =
        json!({ "asset": { "version": "2.0" }, "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 } }] }] });
    let path = write(&base, "p.gltf", &doc);
    let (at, problem) = refused(&path, &Limits::DEFAULT);
    assert_eq!(at, "meshes[0].primitives[0].attributes.POSITION");
    assert!(problem.to_string().contains("names accessors[0]; the file has 0 accessors"), "{problem}");
    let text = crate::world::scenes::GOOD.replace(
        "mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.5, stacks = 8, slices = 16 } }",
        "mesh = { gltf = \"p.gltf\" }",
    );
    assert!(text.contains("p.gltf"), "the scene's mesh line changed");
    let e = Scene::parse(&text, &base.join("s.toml"), &Limits::DEFAULT).expect_err("refused");
    assert!(matches!(e.problem, Problem::GltfMesh(_)) && e.to_string().contains("attributes.POSITION"), "{e}");
    let e = Scene::open(path.to_str().expect("UTF-8"), &Limits::DEFAULT).expect_err("refused");
    assert!(e.to_string().contains("attributes.POSITION"), "{e}");
}

/// A kilobyte file that declares twelve million vertices (a sparse
/// `POSITION` with no buffer view, three of them drawn) placed by ten
/// nodes: its read is estimated from the counts before any buffer is read
/// — refused under a bound below the estimate without opening its buffer
/// file, read under one above it — and each placement holds only the
/// three vertices it draws (the old loader kept 10 copies of 144 MB).
#[test]
fn declared_counts_are_bounded_before_a_buffer_is_read() {
    let base = scratch("gltf-declared");
    let n = 12_000_000u64;
    let buffer = base.join("small.bin");
    // One sparse entry (index 1 → (1, 0, 0)), one more vertex (0, 1, 0)
    // at index 2, and the indices 0 1 2.
    let mut bin: Vec<u8> = [1u32, 2].iter().flat_map(|i| i.to_le_bytes()).collect();
    bin.extend([1.0f32, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|c| c.to_le_bytes()));
    bin.extend([0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(&buffer, &bin).expect("buffer");
    let nodes: Vec<Value> =
        (0..10).map(|k| json!({ "mesh": 0, "translation": [f64::from(k) * 2.0, 0.0, 0.0] })).collect();
    let doc = json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": (0..10).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "uri": "small.bin", "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteLength": 8 },
            { "buffer": 0, "byteOffset": 8, "byteLength": 24 },
            { "buffer": 0, "byteOffset": 32, "byteLength": 12 }
        ],
        "accessors": [
            { "componentType": 5126, "count": n, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
              "sparse": { "count": 2, "indices": { "bufferView": 0, "componentType": 5125 }, "values": { "bufferView": 1 } } },
            { "bufferView": 2, "componentType": 5125, "count": 3, "type": "SCALAR" }
        ]
    });
    let path = write(&base, "sparse.gltf", &doc);
    assert!(std::fs::metadata(&path).expect("written").len() < 1200, "a kilobyte of JSON");
    // Decoding alone takes 16 bytes a declared vertex: 192 MB.
    let tight = Limits { max_memory: 160 << 20, ..Limits::DEFAULT };
    let (at, problem) = refused(&path, &tight);
    let GltfProblem::Limit(LimitError::Memory { what, bytes, .. }) = problem else { panic!("{at}: {problem}") };
    assert_eq!((at.as_str(), what), ("meshes", "reading the glTF file's meshes"));
    assert!(bytes >= n * 16, "the estimate {bytes} counts each declared vertex");
    assert!(!was_read(&buffer), "refused before its buffer was read");
    let g = Gltf::read(&path, None, &Limits { max_memory: 1 << 30, ..Limits::DEFAULT }).expect("read within 1 GiB");
    assert_eq!(g.instances.len(), 10);
    for (k, i) in g.instances.iter().enumerate() {
        assert_eq!(i.mesh.triangles, vec![[0, 1, 2]], "{}", i.name);
        let x = k as f32 * 2.0;
        assert_eq!(i.mesh.positions, [[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0]].map(Into::into).to_vec());
    }
}

/// What the specification forbids and the `gltf` crate lets through is
/// refused naming its JSON path; what it allows (`extras` of any JSON
/// type) is read.
#[test]
fn the_specifications_rules_are_checked_by_json_path() {
    let base = scratch("gltf-spec");
    let bin = base.join("t.bin");
    std::fs::write(&bin, triangle_bytes()).expect("buffer");
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let camera = |projection: Value| json!({ "cameras": [projection], "nodes": [{ "mesh": 0 }, { "camera": 0, "translation": [0, 0, 3] }], "scenes": [{ "nodes": [0, 1] }] });
    let perspective = |p: Value| camera(json!({ "type": "perspective", "perspective": p }));
    let cases: Vec<(&str, Value, &str, &str)> = vec![
        ("version 1", json!({ "asset": { "version": "1.0" } }), "asset.version", "2.x"),
        ("version 3", json!({ "asset": { "version": "3.0" } }), "asset.version", "2.x"),
        (
            "aspect 0",
            perspective(json!({ "yfov": 0.8, "znear": 0.1, "aspectRatio": 0.0 })),
            "cameras[0].perspective.aspectRatio",
            "positive",
        ),
        (
            "aspect −2",
            perspective(json!({ "yfov": 0.8, "znear": 0.1, "aspectRatio": -2.0 })),
            "cameras[0].perspective.aspectRatio",
            "positive",
        ),
        ("znear 0", perspective(json!({ "yfov": 0.8, "znear": 0.0 })), "cameras[0].perspective.znear", "positive"),
        (
            "zfar ≤ znear",
            perspective(json!({ "yfov": 0.8, "znear": 1.0, "zfar": 0.5 })),
            "cameras[0].perspective.zfar",
            "beyond znear",
        ),
        (
            "xmag 0",
            camera(
                json!({ "type": "orthographic", "orthographic": { "xmag": 0.0, "ymag": 1.0, "znear": 0.0, "zfar": 5.0 } }),
            ),
            "cameras[0].orthographic.xmag",
            "not zero",
        ),
        (
            "rotation",
            json!({ "nodes": [{ "mesh": 0, "rotation": [0.0, 0.5, 0.0, 0.5] }] }),
            "nodes[0].rotation",
            "unit quaternion",
        ),
        (
            "projective",
            json!({ "nodes": [{ "mesh": 0, "matrix": [1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }] }),
            "nodes[0].matrix",
            "affine",
        ),
        (
            "zero row",
            json!({ "nodes": [{ "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0] }] }),
            "nodes[0].matrix",
            "affine",
        ),
        (
            "both",
            json!({ "nodes": [{ "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "translation": [1, 0, 0] }] }),
            "nodes[0]",
            "one or the other",
        ),
        (
            "stride 13",
            json!({ "bufferViews": [{ "buffer": 0, "byteLength": 36, "byteStride": 13 }, { "buffer": 0, "byteOffset": 36, "byteLength": 8 }] }),
            "bufferViews[0].byteStride",
            "multiple of 4",
        ),
        (
            "offset 2",
            json!({ "bufferViews": [{ "buffer": 0, "byteOffset": 2, "byteLength": 34 }, { "buffer": 0, "byteOffset": 36, "byteLength": 8 }] }),
            "accessors[0].byteOffset",
            "multiple of its component",
        ),
    ];
    for (what, extra, path, words) in cases {
        let (at, problem) = refused(&write(&base, "m.gltf", &triangle(Some("t.bin"), extra)), &Limits::DEFAULT);
        assert!(at == path && problem.to_string().contains(words), "{what}: {at}: {problem}");
    }
    // A camera the specification allows but whose image the limits do not:
    // named, not clamped.
    for (what, projection) in [
        (
            "aspect 1e6",
            json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.1, "aspectRatio": 1e6 } }),
        ),
        (
            "xmag 1e30",
            json!({ "type": "orthographic", "orthographic": { "xmag": 1e30, "ymag": 1.0, "znear": 0.0, "zfar": 5.0 } }),
        ),
    ] {
        let file = write(&base, "wide.gltf", &triangle(Some("t.bin"), camera(projection)));
        let e = Scene::of_gltf(&file, None, &Limits::DEFAULT).expect_err(what);
        assert!(e.key == "cameras[0]" && e.to_string().contains("--max-image-side"), "{what}: {e}");
    }
    // A unit rotation (90° about y) and `extras` of every JSON type are read.
    for extras in [json!([1, 2]), Value::Null, json!("text"), json!(7), json!({ "k": true })] {
        let extra =
            json!({ "extras": extras, "nodes": [{ "mesh": 0, "rotation": [0.0, s, 0.0, s], "extras": extras }] });
        Gltf::read(&write(&base, "ok.gltf", &triangle(Some("t.bin"), extra)), None, &Limits::DEFAULT)
            .unwrap_or_else(|e| panic!("extras {extras}: {e}"));
    }
}

/// A `.glb` whose chunks lie, a BOM, a degenerate camera node and two
/// buffers past the file limit each get a message that names the cause.
#[test]
fn broken_files_are_named_by_their_cause() {
    let base = scratch("gltf-causes");
    let good = glb(&triangle(None, json!({})), &triangle_bytes());
    let mut long_json = good.clone();
    long_json[12..16].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
    let mut not_json = good.clone();
    not_json[16..20].copy_from_slice(b"\"{:\"");
    let mut long_bin = good.clone();
    let at = 20 + u32::from_le_bytes(good[12..16].try_into().expect("4 bytes")) as usize;
    long_bin[at..at + 4].copy_from_slice(&1000u32.to_le_bytes());
    let mut bom = b"\xEF\xBB\xBF".to_vec();
    bom.extend(serde_json::to_vec(&triangle(None, json!({}))).expect("json"));
    for (name, bytes, at, words) in [
        ("long-json.glb", &long_json, "(glb chunk 0)", "the JSON chunk declares 4294967280 bytes"),
        ("not-json.glb", &not_json, "(glb chunk 0)", "of type `\"{:\"`, not `JSON`"),
        ("long-bin.glb", &long_bin, "(glb chunk 1)", "`BIN` declares 1000 bytes; the file has 44"),
        ("bom.gltf", &bom, "(json)", "byte-order mark"),
    ] {
        let path = base.join(name);
        std::fs::write(&path, bytes).expect("write");
        let (got, problem) = refused(&path, &Limits::DEFAULT);
        assert!(got == at && problem.to_string().contains(words), "{name}: {got}: {problem}");
    }
    // A camera node scaled to nothing: named, not "no surface" at render.
    let flat = triangle(
        None,
        json!({ "cameras": [{ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.1 } }],
                "nodes": [{ "mesh": 0 }, { "camera": 0, "scale": [0, 0, 0] }], "scenes": [{ "nodes": [0, 1] }] }),
    );
    let path = base.join("flat.glb");
    std::fs::write(&path, glb(&flat, &triangle_bytes())).expect("write");
    let (at, problem) = refused(&path, &Limits::DEFAULT);
    assert!(
        at == "nodes[1]" && problem.to_string().contains("cameras[0]") && problem.to_string().contains("no direction"),
        "{at}: {problem}"
    );
    // Two buffers past the file limit together: each named with its size.
    let mut padded = triangle_bytes();
    padded.resize(4000, 0);
    std::fs::write(base.join("a.bin"), padded).expect("buffer");
    let two = triangle(
        Some("a.bin"),
        json!({ "buffers": [{ "uri": "a.bin", "byteLength": 4000 }, { "uri": "a.bin", "byteLength": 4000 }] }),
    );
    let limits = Limits { max_file_bytes: 6000, ..Limits::DEFAULT };
    let (at, problem) = refused(&write(&base, "two.gltf", &two), &limits);
    let words = "together are 8000 bytes (buffers[0] 4000 bytes, buffers[1] 4000 bytes)";
    assert!(at == "buffers[1]" && problem.to_string().contains(words), "{at}: {problem}");
}
