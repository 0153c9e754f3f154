#![allow(missing_docs, reason = "bench harness")]
//! The glTF loader against the OBJ loader on the same triangles: a
//! generated city (one building mesh placed by a node per building) as a
//! `.glb`, and the same triangles, placed, written out as an OBJ file.
//! Each is timed from the file to its world-space meshes, and to the scene
//! (every object checked, its closedness decided), and reported per
//! triangle (criterion's throughput in elements).
//!
//! `cargo bench --bench loaders`; `CITY_SIDE` sets the buildings along a
//! side (28 by default: 1 003 522 triangles).

use std::fmt::Write as _;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::sim::world::gltf::{City, Gltf};
use umbra::sim::world::mesh::Mesh;
use umbra::sim::{Limits, Scene};

fn loaders(c: &mut Criterion) {
    let side = std::env::var("CITY_SIDE").ok().and_then(|s| s.parse().ok()).unwrap_or(City::MILLION.side);
    let city = City { side, ..City::MILLION };
    let dir = std::env::temp_dir().join(format!("umbra-bench-loaders-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let glb = dir.join("city.glb");
    std::fs::write(&glb, city.glb().expect("the city")).expect("written");
    let limits = Limits::DEFAULT;
    // The same triangles, placed, as OBJ: every instance's vertices and faces.
    let read = Gltf::read(&glb, None, &limits).expect("reads");
    let mut obj = String::new();
    let mut base = 1usize;
    for i in &read.instances {
        for p in &i.mesh.positions {
            let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
        }
        for t in &i.mesh.triangles {
            let _ = writeln!(obj, "f {} {} {}", base + t[0] as usize, base + t[1] as usize, base + t[2] as usize);
        }
        base += i.mesh.positions.len();
    }
    let obj_path = dir.join("city.obj");
    std::fs::write(&obj_path, obj).expect("written");
    let size = |p: &std::path::Path| std::fs::metadata(p).map_or(0, |m| m.len());
    eprintln!("city.glb {} bytes, city.obj {} bytes", size(&glb), size(&obj_path));
    let triangles: u64 = read.instances.iter().map(|i| i.mesh.triangles.len() as u64).sum();
    assert_eq!(triangles, city.triangles());
    let mut group = c.benchmark_group("load");
    group.sample_size(10);
    group.throughput(Throughput::Elements(triangles));
    // The loaders alone: world-space meshes from the file.
    group.bench_function("gltf", |b| b.iter(|| black_box(Gltf::read(&glb, None, &limits).expect("reads"))));
    group.bench_function("obj", |b| b.iter(|| black_box(Mesh::load_obj(&obj_path, &limits).expect("reads"))));
    // The scenes: each object checked and its closedness decided (a
    // closed building each for the glTF, one open mesh for the OBJ).
    let (glb_name, obj_name) = (glb.to_str().expect("UTF-8"), obj_path.as_path());
    group.bench_function("gltf scene", |b| b.iter(|| black_box(Scene::open(glb_name, &limits).expect("opens"))));
    group.bench_function("obj scene", |b| b.iter(|| black_box(Scene::of_obj(obj_name, &limits).expect("opens"))));
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, loaders);
criterion_main!(benches);
