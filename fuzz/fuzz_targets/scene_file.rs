//! Scene files from arbitrary bytes (not necessarily UTF-8): parsing and
//! validation end in a scene or a `SceneError`, never a panic, and never
//! build more triangles than the limits allow.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use umbra_sim::input::limits::Limits;
use umbra_sim::world::scene::Scene;

/// Small limits keep each run fast; the checks are the same at any size.
const LIMITS: Limits = Limits { max_triangles: 20_000, max_file_bytes: 1 << 20, ..Limits::DEFAULT };

fuzz_target!(|data: &[u8]| {
    let file = std::env::temp_dir().join("umbra-fuzz-scene").join("scene.toml");
    if let Ok(scene) = Scene::parse_bytes(data, Path::new(&file), &LIMITS) {
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        assert!(triangles as u64 <= LIMITS.max_triangles, "{triangles} triangles built");
        assert!(!scene.lights.is_empty() && !scene.objects.is_empty());
        assert!(scene.image.iter().all(|&s| (1..=LIMITS.max_image_side).contains(&s)));
        for o in &scene.objects {
            let n = o.mesh.positions.len();
            assert!(o.mesh.triangles.iter().flatten().all(|&i| (i as usize) < n), "{}: dangling index", o.name);
        }
        // The matrices a render would use.
        let _ = (scene.light().view_projection(), scene.camera.view_projection_aspect(1.5));
    }
});
