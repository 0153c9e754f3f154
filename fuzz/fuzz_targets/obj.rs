//! OBJ files from arbitrary bytes: a mesh whose every index is in range and
//! every coordinate finite, or a `MeshError`, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use umbra_sim::input::limits::Limits;
use umbra_sim::world::mesh::Mesh;

const LIMITS: Limits = Limits { max_triangles: 50_000, max_file_bytes: 1 << 20, ..Limits::DEFAULT };

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("umbra-fuzz-obj-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join("mesh.obj");
    if std::fs::write(&path, data).is_err() {
        return;
    }
    if let Ok(mesh) = Mesh::load_obj(&path, &LIMITS) {
        let n = mesh.positions.len();
        assert!(!mesh.triangles.is_empty());
        assert!(mesh.triangles.len() as u64 <= LIMITS.max_triangles);
        assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
        let _ = (mesh.is_closed(), mesh.bounds());
    }
});
