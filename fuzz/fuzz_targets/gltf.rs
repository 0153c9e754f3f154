//! glTF files from arbitrary bytes (`.glb` when they start as one, else
//! `.gltf` JSON), read as a model and as a scene: a scene whose every
//! index is in range and every coordinate finite, or a typed error, never
//! a panic, never more than the limits allow, and never a byte read from
//! outside the model's folder.
#![no_main]

use libfuzzer_sys::fuzz_target;
use umbra_sim::input::limits::Limits;
use umbra_sim::world::gltf::Gltf;
use umbra_sim::world::scene::Scene;

/// Small limits keep each run fast (and its memory within the fuzzer's
/// bound); the checks are the same at any size.
const LIMITS: Limits =
    Limits { max_triangles: 20_000, max_file_bytes: 1 << 20, max_memory: 512 << 20, ..Limits::DEFAULT };

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("umbra-fuzz-gltf-{}", std::process::id()));
    let model = dir.join("model");
    let _ = std::fs::create_dir_all(&model);
    // A file beside the model's folder: never to be read.
    let _ = std::fs::write(dir.join("outside.bin"), [0u8; 64]);
    let _ = std::fs::write(model.join("beside.bin"), [0u8; 64]);
    let path = model.join(if data.starts_with(b"glTF") { "model.glb" } else { "model.gltf" });
    if std::fs::write(&path, data).is_err() {
        return;
    }
    if let Ok(g) = Gltf::read(&path, None, &LIMITS) {
        let triangles: usize = g.instances.iter().map(|i| i.mesh.triangles.len()).sum();
        assert!(triangles as u64 <= LIMITS.max_triangles, "{triangles} triangles");
        for i in &g.instances {
            let n = i.mesh.positions.len();
            assert!(i.mesh.triangles.iter().flatten().all(|&v| (v as usize) < n), "{}: dangling index", i.name);
        }
    }
    if let Ok(scene) = Scene::of_gltf(&path, None, &LIMITS) {
        assert!(!scene.lights.is_empty() && !scene.objects.is_empty());
        assert!(scene.image.iter().all(|&s| (1..=LIMITS.max_image_side).contains(&s)));
        for o in &scene.objects {
            assert!(o.mesh.positions.iter().all(|p| p.is_finite()), "{}: a coordinate not finite", o.name);
        }
        let _ = (scene.light().view_projection(), scene.camera.view_projection_aspect(1.5));
    }
    assert!(!umbra_sim::base::reads::was_read(&dir.join("outside.bin")), "a file outside the model's folder was read");
});
