//! Hostile scene files, OBJ files and render requests: each ends in a typed
//! error naming the problem, before anything large is allocated — never a
//! panic, a hang or running out of memory. (`hostile.rs` does the same for
//! the core's own inputs; `scenes.rs` covers the ordinary mistakes.)

use std::path::Path;

use umbra::core::DepthFormatKind;
use umbra::core::shadow::Filter;
use umbra::sim::Algorithm;
use umbra::sim::input::limits::{LimitError, Limits};
use umbra::sim::render::{RenderConfig, RenderError, TruthSource, render};
use umbra::sim::world::mesh::{Mesh, MeshError};
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::{Problem, SceneError};

use crate::common::scratch;
use crate::world::scenes::{GOOD, with};

/// The problem of a rejected scene, after checking the key it names.
fn problem(r: Result<Scene, SceneError>, key: &str) -> Problem {
    let e = r.expect_err("must be rejected");
    // A line is named with its text: `line 3, \`image = [0, 48]\``.
    assert!(e.key == key || e.key.starts_with(&format!("{key}, `")), "{key}: {e}");
    e.problem
}

#[test]
fn infinities_and_huge_numbers_are_named() {
    for (from, to, key) in [
        ("position = [0.0, 2.0, 5.0]", "position = [inf, 2.0, 5.0]", "camera.position"),
        ("target = [0.0, 0.0, 0.0]\nfov", "target = [0.0, -inf, 0.0]\nfov", "camera.target"),
        ("fov = 50.0", "fov = nan", "camera.fov"),
        ("extent = 3.0", "extent = inf", "lights[0].extent"),
        ("mesh = { sphere", "translate = [1e38, 0.0, 0.0]\nmesh = { sphere", "objects[0].translate"),
        ("mesh = { sphere", "rotate = [0.0, -1e300, 0.0]\nmesh = { sphere", "objects[0].rotate"),
    ] {
        let p = problem(with(from, to), key);
        assert!(matches!(p, Problem::NonFinite { .. }), "{to}: {p}");
    }
    // 1e38 is a finite f32, but the vertex unit would overflow on it: the
    // message says which numbers are accepted.
    let p = problem(with("position = [0.0, 2.0, 5.0]", "position = [0.0, 1e38, 5.0]"), "camera.position");
    assert_eq!(p.to_string(), "100000000000000000000000000000000000000 is not a finite number below 1e30 in magnitude");
}

#[test]
fn negative_and_zero_sizes_are_named() {
    let sphere = "mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.5, stacks = 8, slices = 16 } }";
    for (to, key) in [
        (format!("{sphere}\nscale = -2.0"), "objects[0].scale"),
        (format!("{sphere}\nscale = 0.0"), "objects[0].scale"),
        (sphere.replace("stacks = 8", "stacks = 0"), "objects[0].mesh.stacks"),
        (sphere.replace("slices = 16", "slices = 100000"), "objects[0].mesh.slices"),
        ("mesh = { box = { min = [0.0, 0.0, 0.0], max = [1.0, -1.0, 1.0] } }".into(), "objects[0].mesh.max"),
        (
            "mesh = { torus = { center = [0.0, 0.0, 0.0], major = 1.0, minor = -0.2, rings = 8, sides = 8 } }".into(),
            "objects[0].mesh.minor",
        ),
    ] {
        let p = problem(with(sphere, &to), key);
        let corners = matches!(p, Problem::Corners { axis: 'y', .. }) && to.contains("box");
        assert!(matches!(p, Problem::Size { .. }) || corners, "{to}: {p}");
    }
    // The image is whole pixels: a negative side, a fraction or a third
    // element is refused at its line, never rounded or dropped.
    for (to, says) in [
        ("image = [-64, 48]", "integer `-64`"),
        ("image = [64.5, 48]", "floating point `64.5`"),
        ("image = [64, 48, 7]", "invalid length 3, expected 2 values"),
        ("image = [64]", "invalid length 1, expected 2 values"),
    ] {
        let p = problem(with("image = [64, 48]", to), "line 3");
        assert!(matches!(&p, Problem::Syntax(s) if s.contains(says)), "{to}: {p}");
    }
    // So is every fixed-length array: a fourth coordinate is not dropped.
    let p = problem(with("position = [0.0, 2.0, 5.0]", "position = [0.0, 2.0, 5.0, 1.0]"), "line 6");
    assert!(matches!(&p, Problem::Syntax(s) if s.contains("expected 3 values")), "{p}");
}

/// Values are checked as the f32 pipeline holds them: a near plane that is
/// 0 in f32, near and far equal in f32, a camera or a light at its target
/// are each refused naming the key, where checks in f64 let them through.
#[test]
fn values_that_vanish_in_f32_are_named() {
    for (from, to, key) in [
        ("near = 0.5", "near = 1e-50", "camera.near"),
        ("near = 0.5\nfar = 20.0", "near = 20.0\nfar = 20.0000001", "camera.near"),
        ("near = 1.0\nfar = 10.0", "near = 1e-46\nfar = 10.0", "lights[0].near"),
    ] {
        // In f64 each pair is positive and ordered: only f32 sees the problem.
        let p = problem(with(from, to), key);
        assert!(matches!(p, Problem::NearFar { .. }), "{to}: {p}");
    }
    for (from, to, key) in [
        ("target = [0.0, 0.0, 0.0]\nfov", "target = [0.0, 2.0, 5.0000000001]\nfov", "camera.position"),
        ("position = [0.0, 5.0, 0.0]", "position = [0.0, 0.0, 0.0]", "lights[0].position"),
    ] {
        let p = problem(with(from, to), key);
        assert!(matches!(p, Problem::LooksNowhere { .. }), "{to}: {p}");
    }
}

/// Five spheres of 1024 × 1024 make 5 · 2 · 1024 · 1023 = 10 475 520
/// triangles: refused before the first is built.
#[test]
fn ten_million_triangles_are_refused_before_building() {
    let big = "mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.5, stacks = 1024, slices = 1024 } }";
    let object = format!("\n[[objects]]\n{big}\n");
    let text = GOOD.replacen(
        "mesh = { sphere = { center = [0.0, 1.0, 0.0], radius = 0.5, stacks = 8, slices = 16 } }",
        big,
        1,
    ) + &object.repeat(4);
    let p = problem(Scene::parse(&text, Path::new("probe.toml"), &Limits::DEFAULT), "objects");
    assert!(
        matches!(p, Problem::Limit(LimitError::Triangles { triangles: 10_475_520, max }) if max == Limits::DEFAULT.max_triangles),
        "{p}"
    );
    assert!(p.to_string().contains("10475520 triangles"), "{p}");
}

/// A file larger than the limit is refused from its size alone: a sparse
/// 300 MiB file is never read.
#[test]
fn an_oversized_obj_is_refused_unread() {
    let dir = scratch("hostile-big");
    let big = dir.join("big.obj");
    std::fs::File::create(&big).and_then(|f| f.set_len(300 << 20)).expect("sparse file");
    let err = Mesh::load_obj(&big, &Limits::DEFAULT).expect_err("too large");
    assert!(
        matches!(err, MeshError::Limit { source: LimitError::FileBytes { bytes: 314_572_800, max: 268_435_456 }, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("big.obj"), "{err}");
    // The same through a scene file.
    let scene = dir.join("scene.toml");
    let text = GOOD.replacen("mesh = { sphere", "mesh = { obj = \"big.obj\" }\n#", 1);
    std::fs::write(&scene, text).expect("write");
    let p = problem(Scene::load(&scene, &Limits::DEFAULT), "objects[0].mesh");
    assert!(matches!(p, Problem::Mesh(MeshError::Limit { .. })), "{p}");
    std::fs::remove_file(&big).expect("remove");
}

/// A mesh file gets the triangles the generators leave: with a limit of 120,
/// an 8 × 16 sphere (2 · 16 · 7 = 224) is refused outright, and after a
/// 4 × 8 sphere (2 · 8 · 3 = 48) a file of 100 triangles is refused, counted
/// from its faces before any is stored.
#[test]
fn the_triangle_limit_spans_generators_and_files() {
    let limits = Limits { max_triangles: 120, ..Limits::DEFAULT };
    let p = problem(Scene::parse(GOOD, Path::new("probe.toml"), &limits), "objects");
    assert!(matches!(p, Problem::Limit(LimitError::Triangles { triangles: 224, max: 120 })), "{p}");
    let dir = scratch("hostile-faces");
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n");
    for _ in 0..50 {
        obj.push_str("f 1 2 3 4\n"); // two triangles each
    }
    std::fs::write(dir.join("fan.obj"), &obj).expect("write");
    let small = GOOD.replacen("stacks = 8, slices = 16", "stacks = 4, slices = 8", 1)
        + "\n[[objects]]\nmesh = { obj = \"fan.obj\" }\n";
    let file = dir.join("scene.toml");
    let p = problem(Scene::parse(&small, &file, &limits), "objects[1].mesh");
    assert!(
        matches!(p, Problem::Mesh(MeshError::Limit { source: LimitError::Triangles { triangles: 100, max: 72 }, .. })),
        "{p}"
    );
    let roomy = Limits { max_triangles: 148, ..Limits::DEFAULT };
    let s = Scene::parse(&small, &file, &roomy).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.objects[1].mesh.triangles.len(), 100);
}

#[test]
fn limits_on_files_and_images_are_configurable() {
    let dir = scratch("hostile-limits");
    let file = dir.join("scene.toml");
    std::fs::write(&file, GOOD).expect("write");
    let tiny = Limits { max_text_bytes: 100, ..Limits::DEFAULT };
    let bytes = GOOD.len() as u64;
    let p = problem(Scene::load(&file, &tiny), "(file)");
    assert!(matches!(p, Problem::Limit(LimitError::TextBytes { bytes: b, max: 100 }) if b == bytes), "{p}");
    // 8192 × 8192 is within the side limit but has 2²⁶ pixels.
    let p = problem(with("image = [64, 48]", "image = [8192, 8192]"), "image");
    assert!(matches!(p, Problem::Limit(LimitError::ImagePixels { width: 8192, height: 8192, .. })), "{p}");
    let narrow = Limits { max_image_side: 32, ..Limits::DEFAULT };
    let p = problem(Scene::parse(GOOD, Path::new("probe.toml"), &narrow), "image");
    assert!(matches!(p, Problem::Limit(LimitError::ImageSide { side: 64, max: 32 })), "{p}");
    assert!(p.to_string().contains("max_image_side"), "{p}");
}

fn render_config(map_size: u32, width: u32, height: u32) -> RenderConfig {
    RenderConfig {
        algorithm: Algorithm::Second,
        format: DepthFormatKind::D24,
        map_size,
        filter: Filter::Bilinear,
        bias: 0.0,
        virtual_samples: true,
        width,
        height,
        reference_rays: 1,
        ..RenderConfig::DEFAULT
    }
}

/// A 65536² map is four times the core's largest target and a 16384² one
/// a 2 GiB dual map: both refused before any buffer exists, as is an image
/// past the limits.
#[test]
fn huge_maps_and_images_are_refused_before_allocating() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let hidden = indicatif::ProgressBar::hidden();
    for side in [65_536u32, 16_384] {
        let err = render_config(side, 64, 48)
            .check(&scene, &Limits::DEFAULT)
            .and_then(|job| render(&job, TruthSource::Build(&hidden)))
            .err()
            .expect("refused");
        assert!(matches!(err, RenderError::Limit(LimitError::MapSide { side: s, max: 8192 }) if s == side), "{err}");
        assert!(err.to_string().contains(&format!("map side {side}")), "{err}");
    }
    let err = render_config(64, 100_000, 1)
        .check(&scene, &Limits::DEFAULT)
        .and_then(|job| render(&job, TruthSource::Build(&hidden)))
        .err()
        .expect("refused");
    assert!(matches!(err, RenderError::Limit(LimitError::ImageSide { side: 100_000, .. })), "{err}");
    let err = render_config(64, 8192, 8192)
        .check(&scene, &Limits::DEFAULT)
        .and_then(|job| render(&job, TruthSource::Build(&hidden)))
        .err()
        .expect("refused");
    assert!(matches!(err, RenderError::Limit(LimitError::ImagePixels { .. })), "{err}");
    let few = Limits { max_triangles: 100, ..Limits::DEFAULT };
    let err = render_config(64, 64, 48)
        .check(&scene, &few)
        .and_then(|job| render(&job, TruthSource::Build(&hidden)))
        .err()
        .expect("refused");
    assert!(matches!(err, RenderError::Limit(LimitError::Triangles { max: 100, .. })), "{err}");
    // Zero is the configuration's to refuse, and named as the map's.
    let err = render_config(0, 64, 48)
        .check(&scene, &Limits::DEFAULT)
        .and_then(|job| render(&job, TruthSource::Build(&hidden)))
        .err()
        .expect("refused");
    assert!(
        matches!(err, RenderError::Config(umbra::sim::render::RenderConfigError::Zero { quantity: "map_size" })),
        "{err}"
    );
}

#[test]
fn bytes_that_are_not_text_name_their_line() {
    let mut bytes = GOOD.as_bytes().to_vec();
    let at = GOOD.find("[camera]").expect("has a camera");
    bytes.splice(at..at, [0xff, 0xfe, b'\n']);
    let line = GOOD[..at].matches('\n').count() + 1;
    let p = problem(Scene::parse_bytes(&bytes, Path::new("probe.toml"), &Limits::DEFAULT), &format!("line {line}"));
    assert!(matches!(&p, Problem::Syntax(m) if m == &format!("not UTF-8 text at byte {at}")), "{p}");
    let dir = scratch("hostile-bytes");
    let file = dir.join("latin1.toml");
    std::fs::write(&file, &bytes).expect("write");
    let p = problem(Scene::load(&file, &Limits::DEFAULT), &format!("line {line}"));
    assert!(matches!(p, Problem::Syntax(_)), "{p}");
}

/// A directory, a device: refused by kind, never read (a device such as
/// `/dev/zero` would never end). A material library is never opened, so an
/// OBJ naming `/dev/zero` as one loads.
#[test]
fn directories_and_devices_are_not_files() {
    let dir = scratch("hostile-kinds");
    let p = problem(Scene::load(&dir, &Limits::DEFAULT), "(file)");
    assert!(matches!(p, Problem::NotAFile), "{p}");
    assert!(matches!(Mesh::load_obj(&dir, &Limits::DEFAULT), Err(MeshError::NotAFile { .. })));
    let zero = Path::new("/dev/zero");
    if zero.exists() {
        assert!(matches!(Mesh::load_obj(zero, &Limits::DEFAULT), Err(MeshError::NotAFile { .. })));
        let p = problem(Scene::load(zero, &Limits::DEFAULT), "(file)");
        assert!(matches!(p, Problem::NotAFile), "{p}");
        let obj = dir.join("mtl.obj");
        std::fs::write(&obj, "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n").expect("write");
        let mesh = Mesh::load_obj(&obj, &Limits::DEFAULT).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(mesh.triangles.len(), 1);
    }
    let missing = dir.join("no-such.toml");
    let p = problem(Scene::load(&missing, &Limits::DEFAULT), "(file)");
    assert!(matches!(&p, Problem::Read(e) if e.kind() == std::io::ErrorKind::NotFound), "{p}");
}

/// Polylines (`l`) and points (`p`) are not surfaces: they are left out of
/// the mesh and counted, and they count against the primitive limit
/// before anything is loaded (one `l` record of many vertices used to
/// become that many filled triangles).
#[test]
fn polylines_and_points_are_counted_not_filled() {
    let dir = scratch("polyline");
    let path = dir.join("lines.obj");
    // Two triangles, a polyline of 6 vertices (5 segments), 2 points.
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n\
               f 1 2 3\nf 2 4 3\nl 1 2 3 4 5 6\np 5 6\n";
    std::fs::write(&path, obj).expect("write");
    let at = |max_triangles| Mesh::load_obj(&path, &Limits { max_triangles, ..Limits::DEFAULT });
    // 2 + 5 + 2 = 9 primitives: 8 is one short.
    let err = at(8).expect_err("over the limit");
    let nine = LimitError::Primitives { primitives: 9, triangles: 2, max: 8 };
    assert!(matches!(err, MeshError::Limit { source, .. } if source == nine), "{err}");
    let mesh = at(9).expect("at the limit");
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [1, 3, 2]], "the faces alone");
    assert_eq!((mesh.ignored.segments, mesh.ignored.points), (5, 2));
}

/// Every malformed record the loader reads is named with its file and
/// line, so the loader itself (which names none) never reports one.
#[test]
fn every_obj_error_names_its_line() {
    let dir = scratch("obj-lines");
    let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (bad, says) in [
        ("vt 0.5", "texture coordinate"),
        ("vn 0 1", "normal needs three"),
        ("v 1 2 3 0", "vertex is x y z"),
        ("v 1 2 3 4 5", "vertex is x y z"),
        ("l 1", "needs at least 2"),
        ("l 1 9", "names no vertex"),
        ("p 0", "names no vertex"),
        ("usemtl", "names no material"),
        ("f 1 2 3/7", "no texture coordinate"),
    ] {
        let path = dir.join("bad.obj");
        std::fs::write(&path, format!("{head}f 1 2 3\n{bad}\n")).expect("write");
        let err = Mesh::load_obj(&path, &Limits::DEFAULT).expect_err(bad);
        assert!(matches!(err, MeshError::Syntax { line: 5, .. }), "{bad}: {err}");
        let text = err.to_string();
        assert!(text.contains("bad.obj:5") && text.contains(says), "{bad}: {text}");
    }
}

/// A camera that sees no surface facing the light, and a light that sees
/// no triangle, are errors naming the scene key, never "0 pixels
/// evaluated, 0.000 % misclassified".
#[test]
fn nothing_to_measure_is_an_error_not_a_perfect_score() {
    let hidden = indicatif::ProgressBar::hidden();
    let run = |scene: Scene| {
        render_config(64, 64, 48)
            .check(&scene, &Limits::DEFAULT)
            .and_then(|job| render(&job, TruthSource::Build(&hidden)))
    };
    let away = with("target = [0.0, 0.0, 0.0]\nfov", "target = [0.0, 2.0, 10.0]\nfov").expect("valid");
    let err = run(away).err().expect("the camera looks away from the ball");
    assert!(matches!(err, RenderError::NothingEvaluated { .. }) && err.to_string().starts_with("camera:"), "{err}");
    let aside = with(
        "position = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]",
        "position = [9.0, 5.0, 0.0]\ntarget = [9.0, 0.0, 0.0]",
    )
    .expect("valid");
    let err = run(aside).err().expect("the light's box misses the ball");
    assert!(matches!(err, RenderError::EmptyMap(_)) && err.to_string().starts_with("lights[0]:"), "{err}");
}
