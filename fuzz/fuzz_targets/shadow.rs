//! The shadow unit and the camera pass's shading unit with arbitrary
//! lookups, configurations (through `ShadowConfig::new`), matrices,
//! triangles and visibility ids, on maps from a light pass or of arbitrary
//! texels.
//!
//! Besides never panicking: a result is a fraction in `[0, 1]`, and on a map
//! whose tile bounds are true (one a light pass made) culling lookups by
//! those bounds never changes a result.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use umbra_core::depth::PlaneZ;
use umbra_core::front::setup::Setup;
use umbra_core::glam::{Mat4, Vec3, Vec4};
use umbra_core::raster::bin::Bin;
use umbra_core::shade::{Normals, SceneTriangle, ShadeConfig, Shaded, shade};
use umbra_core::shadow::{
    Bias, DepthTest, Filter, Jitter, Lookup, MapCoord, MapView, Shadow, ShadowConfig, Slope, TangentPlane, shadow,
    shadow_with_virtual_samples,
};
use umbra_core::{
    CullMode, D16, D24, DepthFormat, DepthUnit, F32, LightBuffers, LightPass, LightPassConfig, NoProbe, RasterConfig,
    TileState,
};

#[derive(Arbitrary, Debug)]
enum TestIn {
    First,
    Second,
    Midpoint,
    Dual(i64),
}

#[derive(Arbitrary, Debug)]
enum BiasIn {
    Constant(i64),
    Range(i64, i64),
}

#[derive(Arbitrary, Debug)]
enum FilterIn {
    Point,
    Bilinear,
    Box(u8),
    Jittered { num_samples: u16, res_factor: i32, min_samples: u16, min_size: i32 },
}

#[derive(Arbitrary, Debug)]
struct LookupIn {
    x: i32,
    y: i32,
    z: i64,
    footprint: [i32; 2],
    seed: u64,
    slope: Option<(i64, i64)>,
}

#[derive(Arbitrary, Debug)]
struct TriangleIn {
    positions: [[u32; 3]; 3],
    normals: [[u32; 3]; 3],
}

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    tile_log: u8,
    format: u8,
    /// Texels straight from the input (bounds not true) instead of a light pass.
    raw_texels: Option<Vec<u32>>,
    front_culled: bool,
    triangles: Vec<[[u32; 4]; 3]>,
    test: TestIn,
    bias: BiasIn,
    filter: FilterIn,
    lookups: Vec<LookupIn>,
    plane: ([u32; 3], [u32; 3], [u32; 16]),
    camera: [u32; 16],
    light: Option<[u32; 16]>,
    camera_size: (u8, u8),
    ids: Vec<u16>,
    scene: Vec<TriangleIn>,
    virtual_samples: bool,
    smooth: bool,
    seed: u64,
}

fn f(bits: u32) -> f32 {
    f32::from_bits(bits)
}

fn v3(b: [u32; 3]) -> Vec3 {
    Vec3::new(f(b[0]), f(b[1]), f(b[2]))
}

/// Maps of a light pass over clip-space triangles: the matrix it used is the identity.
fn light_pass<F: DepthFormat>(
    cfg: LightPassConfig,
    tris: &[[[u32; 4]; 3]],
) -> (Vec<F::Texel>, Vec<F::Texel>, Vec<TileState<F::Texel>>) {
    let r = cfg.raster;
    let mut z1 = vec![F::FAR; r.texel_count()];
    let mut z2 = vec![F::FAR; if cfg.unit == DepthUnit::Dual { r.texel_count() } else { 0 }];
    let mut tiles = vec![TileState::cleared(F::FAR, 0); r.tile_count()];
    let mut bins = vec![Bin::<16>::new(); r.tile_count()];
    let mut setups = vec![Setup::EMPTY; 64];
    let buffers = LightBuffers {
        z1: &mut z1,
        z2: &mut z2,
        ids: &mut [],
        tiles: &mut tiles,
        bins: &mut bins,
        setups: &mut setups,
    };
    let mut pass = LightPass::<F, NoProbe, 16>::new(cfg, buffers, NoProbe).expect("buffers fit");
    let cull = if cfg.unit == DepthUnit::Single { CullMode::Front } else { CullMode::None };
    for t in tris.iter().take(24) {
        pass.draw_clip(t.map(|v| Vec4::new(f(v[0]), f(v[1]), f(v[2]), f(v[3]))), cull);
    }
    pass.finish();
    (z1, z2, tiles)
}

fn config<F: DepthFormat>(input: &Input) -> Option<ShadowConfig> {
    let test = match input.test {
        TestIn::First => DepthTest::First,
        TestIn::Second => DepthTest::Second,
        TestIn::Midpoint => DepthTest::Midpoint,
        TestIn::Dual(o) => DepthTest::Dual { offset: PlaneZ::from_bits(o) },
    };
    let bias = match input.bias {
        BiasIn::Constant(b) => Bias::Constant(PlaneZ::from_bits(b)),
        BiasIn::Range(lo, hi) => Bias::Range { lo: PlaneZ::from_bits(lo), hi: PlaneZ::from_bits(hi) },
    };
    let filter = match input.filter {
        FilterIn::Point => Filter::Point,
        FilterIn::Bilinear => Filter::Bilinear,
        FilterIn::Box(size) => Filter::Box { size },
        FilterIn::Jittered { num_samples, res_factor, min_samples, min_size } => Filter::Jittered(Jitter {
            num_samples,
            res_factor: MapCoord::from_bits(res_factor),
            min_samples,
            min_size: MapCoord::from_bits(min_size),
        }),
    };
    ShadowConfig::new(test, bias, filter, true).ok()
}

fn check<F: DepthFormat>(input: &Input, raster: RasterConfig) {
    let Some(cfg) = config::<F>(input) else { return };
    let unit = if input.front_culled { DepthUnit::Single } else { DepthUnit::Dual };
    let (z1, z2, tiles, true_bounds) = match &input.raw_texels {
        None => {
            let (z1, z2, tiles) = light_pass::<F>(LightPassConfig { raster, unit, max_z_cull: true }, &input.triangles);
            (z1, z2, tiles, true)
        }
        Some(raw) => {
            let texel = |i: usize| {
                let bits = raw.get(i % raw.len().max(1)).copied().unwrap_or(0);
                F::texel(PlaneZ::from_bits(i64::from(bits) << 8))
            };
            let z1: Vec<_> = (0..raster.texel_count()).map(texel).collect();
            let z2 = if unit == DepthUnit::Dual {
                (0..raster.texel_count()).map(|i| texel(i + 7)).collect()
            } else {
                Vec::new()
            };
            let mut tiles = vec![TileState::cleared(F::FAR, 0); raster.tile_count()];
            for (i, t) in tiles.iter_mut().enumerate() {
                t.z1_min = texel(i);
                t.z2_max = texel(i + 3);
            }
            (z1, z2, tiles, false)
        }
    };
    let map = if input.front_culled {
        MapView::<F>::front_culled(raster, &z1, &tiles)
    } else {
        MapView::<F>::new(raster, &z1, &z2, &tiles)
    }
    .expect("buffers fit");
    let one = Shadow::ONE;
    for l in input.lookups.iter().take(16) {
        let lookup = Lookup {
            x: MapCoord::from_bits(l.x),
            y: MapCoord::from_bits(l.y),
            z: PlaneZ::from_bits(l.z),
            footprint: l.footprint.map(MapCoord::from_bits),
            seed: l.seed,
            slope: l.slope.map(|(du, dv)| Slope { du, dv }),
        };
        let culled = shadow(&map, &cfg, &lookup, &mut NoProbe);
        let read = shadow(&map, &cfg.with_cull_lookups(false), &lookup, &mut NoProbe);
        assert!(culled <= one && read <= one);
        if true_bounds {
            assert_eq!(culled, read, "culling changed the result of {lookup:?}");
        }
        let v = shadow_with_virtual_samples(&map, &cfg, &lookup, || lookup.slope, &mut NoProbe);
        assert!(v <= one);
    }
    let (p, n, m) = &input.plane;
    let _ = TangentPlane::new(v3(*p), v3(*n), &Mat4::from_cols_array(&m.map(f))).slope::<F>(&raster);
    // The shading unit over arbitrary ids, triangles and matrices.
    let (w, h) = (u32::from(input.camera_size.0 % 24), u32::from(input.camera_size.1 % 24));
    let pixels = (w * h) as usize;
    let scene: Vec<SceneTriangle> = input
        .scene
        .iter()
        .take(16)
        .map(|t| SceneTriangle { positions: t.positions.map(v3), normals: t.normals.map(v3) })
        .collect();
    let ids: Vec<u32> = (0..pixels)
        .map(|i| match input.ids.get(i % input.ids.len().max(1)) {
            Some(&v) if v == u16::MAX => umbra_core::NO_TRIANGLE,
            Some(&v) => u32::from(v) % (scene.len() as u32 + 1),
            None => umbra_core::NO_TRIANGLE,
        })
        .collect();
    let camera = ShadeConfig {
        camera: Mat4::from_cols_array(&input.camera.map(f)),
        light: input.light.map_or(Mat4::IDENTITY, |m| Mat4::from_cols_array(&m.map(f))),
        width: w,
        height: h,
        shadow: cfg,
        virtual_samples: input.virtual_samples,
        normals: if input.smooth { Normals::Smooth } else { Normals::Flat },
        seed: input.seed,
    };
    let source = |id: u32| scene.get(id as usize).copied();
    let mut out = vec![Shaded::BACKGROUND; pixels];
    shade(&camera, &ids, &map, &source, &mut out, &mut NoProbe).expect("buffers fit");
    assert!(out.iter().all(|s| s.shadow <= one));
    // Buffers of the wrong length are errors.
    if pixels > 0 {
        assert!(shade(&camera, &ids[1..], &map, &source, &mut out, &mut NoProbe).is_err());
    }
}

fuzz_target!(|input: Input| {
    let Ok(raster) =
        RasterConfig::new(u32::from(input.width % 80), u32::from(input.height % 80), 1u32 << (input.tile_log % 9), 8)
    else {
        return;
    };
    match input.format % 3 {
        0 => check::<D16>(&input, raster),
        1 => check::<D24>(&input, raster),
        _ => check::<F32>(&input, raster),
    }
});
