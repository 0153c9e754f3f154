//! Inputs the fuzz targets (`fuzz/`) found, each inline, each with what it
//! broke and what must hold now.

use umbra::core::glam::{Mat4, Vec3};
use umbra::core::shade::{Normals, SceneTriangle, ShadeConfig, Shaded, shade};
use umbra::core::shadow::{Bias, DepthTest, Filter, Jitter, MapCoord, MapView, ShadowConfig, jitter_grid};
use umbra::core::{D16, DepthFormat, RasterConfig, TileState};

/// `fuzz/fuzz_targets/shadow.rs`: a light matrix with NaN in its x row (the
/// fuzzer's had `0xfffc0000` there) and a finite `w` row made Reeves'
/// footprint NaN, and converting NaN to a map coordinate panicked. Now the
/// pixel has no light point and no footprint, and is lit.
#[test]
fn a_light_matrix_with_nan_in_a_row_shades_without_panicking() {
    let mut light = Mat4::IDENTITY.to_cols_array();
    light[0] = f32::from_bits(0xfffc_0000); // column 0, row 0: a NaN
    let raster = RasterConfig::new(16, 16, 8, 8).expect("valid");
    let (z1, z2) = (vec![D16::FAR; 256], vec![D16::FAR; 256]);
    let tiles = vec![TileState::cleared(D16::FAR, 64); 4];
    let map = MapView::<D16>::new(raster, &z1, &z2, &tiles).expect("buffers fit");
    let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Bilinear, true).expect("valid");
    let cfg = ShadeConfig {
        camera: Mat4::IDENTITY,
        light: Mat4::from_cols_array(&light),
        width: 8,
        height: 8,
        shadow,
        virtual_samples: true,
        normals: Normals::Flat,
        seed: 0,
    };
    let triangle = SceneTriangle {
        positions: [Vec3::new(-0.9, -0.9, 0.5), Vec3::new(0.9, -0.9, 0.5), Vec3::new(0.0, 0.9, 0.5)],
        normals: [Vec3::Z; 3],
    };
    let source = |id: u32| (id == 0).then_some(triangle);
    let ids = vec![0u32; 64];
    let mut out = vec![Shaded::BACKGROUND; 64];
    shade(&cfg, &ids, &map, &source, &mut out, &mut umbra::core::NoProbe).expect("buffers fit");
    assert!(out.iter().all(|s| s.triangle == 0 && s.light.is_none() && s.shadow == 0), "{:?}", out[0]);
}

/// `fuzz/fuzz_targets/shadow.rs`: a footprint 0.027 texels wide and 5 322
/// texels tall (after `ResFactor` 0.1875) made Reeves' `tres · N / sres`
/// overflow the fixed-point divider, which panicked. Now the ratio
/// saturates and Figure 4's clamps decide: `nt` is at most `NumSamples`
/// (255) and `ns = N / nt + ½ = 1` is raised to `MinSamples` (215).
#[test]
fn a_long_thin_jitter_footprint_clamps_its_sample_counts() {
    let j = Jitter {
        num_samples: 255,
        res_factor: MapCoord::from_bits(12_288),
        min_samples: 215,
        min_size: MapCoord::ZERO,
    };
    let (half, counts) = jitter_grid(&j, [MapCoord::from_bits(9_509), MapCoord::from_bits(-1_859_836_672)]);
    assert_eq!(counts, [215, 255]);
    // 1 859 836 672 · 3/16, exactly.
    assert_eq!(half[1], MapCoord::from_bits(348_719_376));
}

/// `fuzz/fuzz_targets/obj.rs`: a face corner `1/-3/1/` (a texture
/// coordinate three back from the last, with one defined) made the OBJ
/// loader's index arithmetic overflow, which panicked with overflow checks
/// on. Corners are now checked for every index they name, and for their
/// shape, before the loader sees them: each is a syntax error on its line.
#[test]
fn face_corners_naming_missing_texture_coordinates_or_normals_are_syntax_errors() {
    use umbra::sim::world::mesh::{Mesh, MeshError};
    let dir = crate::common::scratch("obj-corners");
    let header = "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    for (face, names) in [
        ("f 1/-3/1/ 1/1 3/1/1", "`1/-3/1/` is not v, v/vt, v//vn or v/vt/vn"),
        ("f 1/-3/1 2/1/1 3/1/1", "`1/-3/1` names no texture coordinate"),
        ("f 1/2 2/1 3/1", "`1/2` names no texture coordinate"),
        ("f 1//1 2//-2 3//1", "`2//-2` names no normal"),
        ("f 1/1/9 2/1/1 3/1/1", "`1/1/9` names no normal"),
    ] {
        let path = dir.join("mesh.obj");
        std::fs::write(&path, format!("{header}{face}\n")).expect("writes");
        match Mesh::load_obj(&path, &umbra::sim::input::limits::Limits::DEFAULT) {
            Err(MeshError::Syntax { line: 7, problem, .. }) => assert!(problem.contains(names), "{face}: {problem}"),
            other => panic!("{face}: {other:?}"),
        }
    }
    // The same corners, each naming what is there, load.
    for face in ["f 1/1/1 2/1/1 3/-1/-1", "f 1//1 2//1 3//1", "f 1/1 2/1 3/1", "f -3 -2 -1"] {
        let path = dir.join("mesh.obj");
        std::fs::write(&path, format!("{header}{face}\n")).expect("writes");
        let mesh = Mesh::load_obj(&path, &umbra::sim::input::limits::Limits::DEFAULT)
            .unwrap_or_else(|e| panic!("{face}: {e}"));
        assert_eq!(mesh.triangles.len(), 1, "{face}");
    }
}
