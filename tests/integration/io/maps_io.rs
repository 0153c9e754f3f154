//! The simulator's edges: OBJ meshes (including the real ones in
//! `../shared/meshes/`), the row-major matrix convention, and `.npy` output.

use std::path::{Path, PathBuf};

use umbra::core::glam::Vec4;
use umbra::core::{CullMode, DepthFormatKind, DepthUnit, LightPassConfig, RasterConfig};
use umbra::sim::base::counters::Counters;
use umbra::sim::base::maps::raw_far;
use umbra::sim::input::limits::Limits;
use umbra::sim::output::formats::{RawMap, write_npy};
use umbra::sim::pass::light::{Draw, RawMaps};
use umbra::sim::world::mesh::{Mesh, MeshError};
use umbra::sim::world::scene::{MatrixError, Perspective, Scene, parse_matrix};

use crate::common::scratch;

#[test]
fn matrices_are_row_major() {
    let m = parse_matrix("[[2,0,0,5],[0,1,0,0],[0,0,1,0],[0,0,0,1]]").expect("valid");
    // Row 0 is clip x = 2x + 5: scale and a translation in the last column.
    assert_eq!(m * Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(7.0, 0.0, 0.0, 1.0));
    assert!(matches!(parse_matrix("[[1,0,0],[0,1,0],[0,0,1]]"), Err(MatrixError::Shape { rows: 3, .. })));
    assert!(matches!(
        parse_matrix("[[1,0,0,0],[0,1,0,0],[0,0,1e39,0],[0,0,0,1]]"),
        Err(MatrixError::NonFinite { row: 2, col: 2, .. })
    ));
    assert!(matches!(parse_matrix("{\"a\": 1}"), Err(MatrixError::Json(_))));
}

#[test]
fn mesh_errors_name_the_file_and_the_problem() {
    let dir = scratch("obj");
    let missing = dir.join("missing.obj");
    let err = Mesh::load_obj(&missing, &Limits::DEFAULT).expect_err("missing file");
    assert!(matches!(err, MeshError::Read { .. }));
    assert!(err.to_string().contains("missing.obj"), "{err}");
    let nan = dir.join("nan.obj");
    std::fs::write(&nan, "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n").expect("write");
    assert!(matches!(Mesh::load_obj(&nan, &Limits::DEFAULT), Err(MeshError::NonFinite { vertex: 2, .. })));
    // Truncated mid-record, and not an OBJ at all: the file and the line.
    let cut = dir.join("cut.obj");
    std::fs::write(&cut, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 0.5 0.").expect("write");
    let err = Mesh::load_obj(&cut, &Limits::DEFAULT).expect_err("truncated");
    assert!(matches!(err, MeshError::Syntax { line: 5, .. }), "{err}");
    assert!(err.to_string().contains("cut.obj:5"), "{err}");
    let png = dir.join("picture.obj");
    std::fs::write(&png, b"\x89PNG\r\n\x1a\n\x00\x00\xff\xfe").expect("write");
    let err = Mesh::load_obj(&png, &Limits::DEFAULT).expect_err("not an OBJ");
    assert!(matches!(err, MeshError::Syntax { line: 1, .. }), "{err}");
    let dangling = dir.join("dangling.obj");
    std::fs::write(&dangling, "v 0 0 0\nv 1 0 0\nf 1 2 3\n").expect("write");
    assert!(matches!(Mesh::load_obj(&dangling, &Limits::DEFAULT), Err(MeshError::Syntax { line: 3, .. })));
    let empty = dir.join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\n").expect("write");
    assert!(matches!(Mesh::load_obj(&empty, &Limits::DEFAULT), Err(MeshError::Empty { .. })));
    let quad = dir.join("quad.obj");
    std::fs::write(&quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").expect("write");
    assert_eq!(Mesh::load_obj(&quad, &Limits::DEFAULT).expect("valid").triangles.len(), 2);
}

/// Every real mesh renders in every format: fragments land, `z1 ≤ z2`, and
/// the coarser format never claims more precision than the finer one.
#[test]
#[ignore = "needs the shared meshes in ../shared/meshes (or UMBRA_MESHES): run with `cargo test --test integration shared_mesh -- --ignored`"]
fn shared_meshes_all_render() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes");
    assert!(dir.is_dir(), "{} is not present", dir.display());
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("readable")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 6, "expected the six shared meshes, found {}", paths.len());
    for path in paths {
        let mesh = Mesh::load_obj(&path, &Limits::DEFAULT).unwrap_or_else(|e| panic!("{e}"));
        let (lo, hi) = mesh.bounds().expect("vertices");
        let c = (lo + hi) / 2.0;
        let r = (hi - lo).length() / 2.0;
        let light = Perspective {
            position: c + umbra::core::glam::Vec3::new(0.3, 1.0, 0.6).normalize() * 3.0 * r,
            target: c,
            fov_degrees: 45.0,
            near: 1.5 * r,
            far: 4.5 * r,
            up: umbra::core::glam::Vec3::Y,
        };
        let draw = Draw {
            positions: &mesh.positions,
            triangles: &mesh.triangles,
            transform: light.view_projection(),
            cull: CullMode::None,
        };
        let raster = RasterConfig::new(128, 128, 16, 8).expect("valid");
        let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
        for format in DepthFormatKind::ALL {
            let (maps, c) = RawMaps::render(cfg, format, &[draw], Counters::new(&raster)).expect("renders");
            let name = path.display();
            assert!(c.totals.fragments > 100, "{name} {format:?}: only {} fragments", c.totals.fragments);
            assert_eq!(c.totals.submitted, mesh.triangles.len() as u64);
            assert!(maps.maps.z1.iter().zip(&maps.maps.z2).all(|(a, b)| a <= b), "{name}: z1 > z2");
            assert!(maps.maps.z1.iter().any(|&z| z != raw_far(format)), "{name}: empty map");
        }
    }
}

/// The `.npy` files hold the raw stored integers with the right header:
/// checked byte by byte against the NumPy format, and read back.
#[test]
fn npy_holds_raw_texels() {
    let scene = Scene::default_scene();
    let raster = RasterConfig::new(48, 32, 16, 8).expect("valid");
    let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    let dir = scratch("npy");
    let mut folder = umbra::sim::output::folder::OutputFolder::create(
        &dir,
        umbra::sim::output::folder::Claim::new(umbra::sim::output::folder::RunKind::Depth),
    )
    .expect("folder");
    for (format, descr, bytes) in [(DepthFormatKind::D16, "<u2", 2usize), (DepthFormatKind::D24, "<u4", 4)] {
        let (maps, _) = RawMaps::render(cfg, format, &draws, umbra::core::NoProbe).expect("renders");
        let map = RawMap { format, width: 48, height: 32, raw: &maps.maps.z1 };
        let path = write_npy(&mut folder, &format!("{}.npy", format.name()), &map).expect("writes");
        let file = std::fs::read(&path).expect("reads");
        assert_eq!(&file[..6], b"\x93NUMPY");
        let header_len = usize::from(u16::from_le_bytes([file[8], file[9]]));
        let header = std::str::from_utf8(&file[10..10 + header_len]).expect("ascii header");
        assert!(header.contains(&format!("'descr': '{descr}'")), "{header}");
        assert!(header.contains("'shape': (32, 48"), "{header}");
        assert_eq!((10 + header_len) % 16, 0, "data aligned");
        let data = &file[10 + header_len..];
        assert_eq!(data.len(), 48 * 32 * bytes);
        let values: Vec<u32> =
            data.chunks_exact(bytes).map(|c| c.iter().rev().fold(0u32, |acc, &b| (acc << 8) | u32::from(b))).collect();
        assert_eq!(values, maps.maps.z1);
        assert!(values.iter().any(|&v| v != raw_far(format)));
    }
}
