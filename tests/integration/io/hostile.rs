//! Arbitrary input never panics; degenerate triangles emit nothing; bad
//! configurations and buffers are typed errors.

use proptest::prelude::*;
use umbra::core::front::setup::Setup;
use umbra::core::glam::{Mat4, Vec3, Vec4};
use umbra::core::raster::bin::Bin;
use umbra::core::{
    ConfigError, CullMode, D16, D24, DepthFormat, DepthUnit, F32, LightBuffers, LightPass, LightPassConfig,
    RasterConfig, SubmitError, TileState,
};

use crate::common::{Buffers, Recorder, config, run};

fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -2.0f32..2.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(1.0e38f32),
        1 => Just(-1.0e38f32),
        1 => Just(f32::MAX),
        1 => Just(0.0f32),
        1 => Just(f32::MIN_POSITIVE),
        1 => prop::num::f32::ANY,
    ]
}

fn wild_vertex() -> impl Strategy<Value = Vec4> {
    (wild(), wild(), wild(), wild()).prop_map(|(x, y, z, w)| Vec4::new(x, y, z, w))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_vertices_never_panic(tris in prop::collection::vec([wild_vertex(), wild_vertex(), wild_vertex()], 1..12), tile in prop::sample::select(vec![8u32, 32, 128])) {
        for unit in [DepthUnit::Single, DepthUnit::Dual] {
            let (maps, rec) = run::<D16, _, 2>(config(40, tile, unit, true), &tris, CullMode::None, 3, Recorder::default());
            prop_assert_eq!(rec.fragments.len() as u64, rec.fragment_events);
            prop_assert!(rec.fragments.iter().all(|f| f.x < 40 && f.y < 40));
            prop_assert_eq!(maps.z1.len(), 1600);
            let _ = run::<F32, _, 4>(config(40, tile, unit, false), &tris, CullMode::Back, 8, Recorder::default());
        }
    }

    #[test]
    fn arbitrary_transforms_never_panic(m in prop::array::uniform16(wild()), p in prop::collection::vec((wild(), wild(), wild()), 3..9)) {
        let positions: Vec<Vec3> = p.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
        let n = positions.len() as u32;
        let triangles: Vec<[u32; 3]> = (0..n - 2).map(|i| [i, i + 1, i + 2]).collect();
        let cfg = config(24, 8, DepthUnit::Dual, true);
        let mut b = Buffers::<D24, 4>::new(&cfg, 2, false);
        let mut pass = b.pass(cfg, Recorder::default());
        pass.draw_mesh(&positions, &triangles, &Mat4::from_cols_array(&m), CullMode::None).expect("indices valid");
        let rec = pass.finish();
        prop_assert!(rec.fragments.iter().all(|f| f.x < 24 && f.y < 24 && f.depth <= 0x00ff_ffff));
    }

    /// Hand-made snapped vertices of any value: setup and every query on the
    /// result are total.
    #[test]
    fn setup_of_any_snapped_vertices_never_panics(v in prop::array::uniform3((any::<i64>(), any::<i64>(), any::<i64>())), px in any::<i64>(), py in any::<i64>()) {
        use umbra::core::depth::PlaneZ;
        use umbra::core::front::snap::{SnappedVertex, SubPx};
        use umbra::core::grid::TileRect;
        let raster = RasterConfig::new(64, 64, 16, 8).expect("valid");
        let verts = v.map(|(x, y, z)| SnappedVertex { x: SubPx(x), y: SubPx(y), z: PlaneZ::from_bits(z) });
        if let Ok(s) = Setup::new(&raster, verts, CullMode::None, 0) {
            prop_assert!(s.bbox.x1 <= 64 && s.bbox.y1 <= 64);
            let r = TileRect { x0: 0, y0: 0, x1: 64, y1: 64 };
            let _ = (s.covers(px, py), s.classify(&r), s.plane.at(px, py), s.plane.range_over(&r));
        }
    }

    /// Hand-made setups of any value, handed straight to the pass (the way
    /// in for a front end run elsewhere), for the target or moved into it
    /// as a window of a larger one at any offset: drawing them never panics
    /// or hangs, and no fragment lands outside the target.
    #[test]
    fn hand_made_setups_of_any_value_never_panic(
        edges in prop::array::uniform3((any::<i64>(), any::<i64>(), any::<i64>())),
        plane in prop::array::uniform3(any::<i128>()),
        bbox in prop::array::uniform4(prop_oneof![0u32..48, any::<u32>()]),
        z in (any::<i64>(), any::<i64>()),
        by in prop::array::uniform2(prop_oneof![0u32..48, any::<u32>()]),
    ) {
        use umbra::core::depth::PlaneZ;
        use umbra::core::front::setup::{DepthPlane, Edge};
        use umbra::core::grid::TileRect;
        let setup = Setup {
            edges: edges.map(|(dx, dy, c)| Edge { dx, dy, c }),
            plane: DepthPlane { a: plane[0], b: plane[1], c: plane[2] },
            bbox: TileRect { x0: bbox[0], y0: bbox[1], x1: bbox[2], y1: bbox[3] },
            z_min: PlaneZ::from_bits(z.0),
            z_max: PlaneZ::from_bits(z.1),
            triangle: 7,
        };
        for unit in [DepthUnit::Single, DepthUnit::Dual] {
            for cull in [false, true] {
                let cfg = config(40, 16, unit, cull);
                let mut b = Buffers::<D24, 2>::new(&cfg, 2, false);
                let mut pass = b.pass(cfg, Recorder::default());
                for _ in 0..3 {
                    pass.draw_setup(&setup);
                    pass.draw_setup_from(&setup, by);
                }
                let rec = pass.finish();
                prop_assert!(rec.fragments.iter().all(|f| f.x < 40 && f.y < 40));
            }
        }
    }

    /// Zero area on the grid: a repeated vertex or three points on one row.
    #[test]
    fn degenerate_triangles_emit_nothing(a in wild_vertex(), b in wild_vertex(), y in -1.0f32..1.0, xs in [-1.5f32..1.5, -1.5f32..1.5, -1.5f32..1.5], z in 0.0f32..1.0) {
        let row = xs.map(|x| Vec4::new(x, y, z, 1.0));
        let tris = [[a, a, b], [a, b, b], [b, b, b], row];
        let (maps, rec) = run::<D24, _, 8>(config(32, 8, DepthUnit::Dual, false), &tris, CullMode::None, 16, Recorder::default());
        prop_assert!(rec.fragments.is_empty());
        prop_assert!(maps.z1.iter().chain(&maps.z2).all(|&t| t == D24::FAR));
    }
}

#[test]
fn bad_configurations_are_typed_errors() {
    assert_eq!(RasterConfig::new(0, 16, 8, 8), Err(ConfigError::TargetSize { width: 0, height: 16 }));
    assert_eq!(RasterConfig::new(16, 65536, 8, 8), Err(ConfigError::TargetSize { width: 16, height: 65536 }));
    assert_eq!(RasterConfig::new(64, 64, 24, 8), Err(ConfigError::TileSize { size: 24 }));
    assert_eq!(RasterConfig::new(64, 64, 256, 8), Err(ConfigError::TileSize { size: 256 }));
    assert_eq!(RasterConfig::new(64, 64, 8, 0), Err(ConfigError::SubpixelBits { bits: 0 }));
    assert_eq!(RasterConfig::new(64, 64, 8, 9), Err(ConfigError::SubpixelBits { bits: 9 }));
    let msg = RasterConfig::new(64, 64, 24, 8).unwrap_err().to_string();
    assert!(msg.contains("tile size 24"), "{msg}");
}

#[test]
fn wrong_buffers_are_named() {
    let cfg = LightPassConfig {
        raster: RasterConfig::new(16, 16, 8, 8).expect("valid"),
        unit: DepthUnit::Dual,
        max_z_cull: true,
    };
    let (mut z1, mut z2) = (vec![0u16; 256], vec![0u16; 255]);
    let mut tiles = vec![TileState::cleared(0, 0); 4];
    let mut bins = vec![Bin::<4>::new(); 4];
    let mut setups = vec![Setup::EMPTY; 4];
    let buffers = LightBuffers::<D16, 4> {
        z1: &mut z1,
        z2: &mut z2,
        ids: &mut [],
        tiles: &mut tiles,
        bins: &mut bins,
        setups: &mut setups,
    };
    let err = LightPass::<D16, Recorder, 4>::new(cfg, buffers, Recorder::default()).err();
    assert_eq!(err, Some(ConfigError::BufferLength { buffer: "z2", expected: 256, found: 255 }));
}

#[test]
fn bad_indices_are_reported_before_drawing() {
    let cfg = config(16, 8, DepthUnit::Single, true);
    let mut b = Buffers::<D16, 4>::new(&cfg, 4, false);
    let mut pass = b.pass(cfg, Recorder::default());
    let positions = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let err = pass.draw_mesh(&positions, &[[0, 1, 2], [0, 1, 7]], &Mat4::IDENTITY, CullMode::None);
    assert_eq!(err, Err(SubmitError::IndexOutOfRange { triangle: 1, index: 7, vertices: 3 }));
    let rec = pass.finish();
    assert!(rec.fragments.is_empty(), "nothing is drawn from a list with a bad index");
}
