//! The light pass fed arbitrary configurations (through the core's
//! validated constructors), arbitrary f32 bits for vertices and matrices
//! (NaN, infinities, 1e38), arbitrary indices and clip-space triangles.
//!
//! Besides never panicking, the maps must not depend on the tile size, the
//! bin capacity, the setup-store size or max-z culling (ARCHITECTURE.md,
//! "Determinism"), `z1 ≤ z2` in a dual map, and every tile's stored bounds
//! must be the exact bounds of its texels.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use umbra_core::depth::Texel;
use umbra_core::front::setup::Setup;
use umbra_core::glam::{Mat4, Vec3, Vec4};
use umbra_core::raster::bin::Bin;
use umbra_core::{
    ConfigError, CullMode, D16, D24, DepthFormat, DepthUnit, F32, LightBuffers, LightPass, LightPassConfig, NoProbe,
    RasterConfig, SubmitError, TileState,
};
use umbra_sim::base::counters::Counters;

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    tile_log: u8,
    subpixel_bits: u8,
    format: u8,
    dual: bool,
    max_z_cull: bool,
    bin: u8,
    setups: u8,
    matrix: [u32; 16],
    positions: Vec<[u32; 3]>,
    triangles: Vec<([u16; 3], u8)>,
    clip: Vec<([[u32; 4]; 3], u8)>,
}

fn cull(c: u8) -> CullMode {
    [CullMode::None, CullMode::Back, CullMode::Front][usize::from(c % 3)]
}

fn f(bits: u32) -> f32 {
    f32::from_bits(bits)
}

/// What one run produced.
#[derive(Debug, PartialEq, Eq)]
struct Out {
    z1: Vec<u32>,
    z2: Vec<u32>,
    submit: Option<SubmitError>,
}

struct Scene {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    culls: Vec<CullMode>,
    matrix: Mat4,
    clip: Vec<([Vec4; 3], CullMode)>,
}

fn run<F: DepthFormat, const B: usize>(
    cfg: LightPassConfig,
    setups: usize,
    s: &Scene,
    counted: bool,
) -> Result<Out, ConfigError> {
    let r = cfg.raster;
    let texels = r.texel_count();
    let mut z1 = vec![F::FAR; texels];
    let mut z2 = vec![F::FAR; if cfg.unit == DepthUnit::Dual { texels } else { 0 }];
    let mut tiles = vec![TileState::cleared(F::FAR, 0); r.tile_count()];
    let mut bins = vec![Bin::<B>::new(); r.tile_count()];
    let mut store = vec![Setup::EMPTY; setups];
    let buffers =
        LightBuffers { z1: &mut z1, z2: &mut z2, ids: &mut [], tiles: &mut tiles, bins: &mut bins, setups: &mut store };
    let mut submit = None;
    if counted {
        let mut pass = LightPass::<F, Counters, B>::new(cfg, buffers, Counters::new(&r))?;
        draw(&mut pass, s, &mut submit);
        let _ = pass.finish();
    } else {
        let mut pass = LightPass::<F, NoProbe, B>::new(cfg, buffers, NoProbe)?;
        draw(&mut pass, s, &mut submit);
        pass.finish();
    }
    // Stored bounds are exact, z1 ≤ z2.
    for (i, t) in tiles.iter().enumerate() {
        let rect = r.tile_rect(r.tile_id(i));
        let texels_of = |buf: &[F::Texel]| {
            let w = r.width() as usize;
            (rect.y0..rect.y1)
                .flat_map(move |y| (rect.x0..rect.x1).map(move |x| y as usize * w + x as usize))
                .map(|j| buf[j])
                .collect::<Vec<_>>()
        };
        let v1 = texels_of(&z1);
        assert_eq!((t.z1_min, t.z1_max), (*v1.iter().min().unwrap(), *v1.iter().max().unwrap()), "tile {i} z1 bounds");
        if cfg.unit == DepthUnit::Dual {
            let v2 = texels_of(&z2);
            assert_eq!(
                (t.z2_min, t.z2_max),
                (*v2.iter().min().unwrap(), *v2.iter().max().unwrap()),
                "tile {i} z2 bounds"
            );
        }
    }
    for (a, b) in z1.iter().zip(&z2) {
        assert!(a <= b, "z1 {a:?} above z2 {b:?}");
    }
    let raw = |v: Vec<F::Texel>| v.into_iter().map(Texel::to_raw).collect();
    Ok(Out { z1: raw(z1), z2: raw(z2), submit })
}

fn draw<F: DepthFormat, P: umbra_core::Probe, const B: usize>(
    pass: &mut LightPass<'_, F, P, B>,
    s: &Scene,
    submit: &mut Option<SubmitError>,
) {
    // One draw call per cull mode run of the list, as a scene's objects.
    let mut start = 0;
    while start < s.triangles.len() {
        let mode = s.culls[start];
        let end = (start..s.triangles.len()).find(|&i| s.culls[i] != mode).unwrap_or(s.triangles.len());
        if let Err(e) = pass.draw_mesh(&s.positions, &s.triangles[start..end], &s.matrix, mode) {
            submit.get_or_insert(e);
        }
        start = end;
    }
    for &(tri, mode) in &s.clip {
        pass.draw_clip(tri, mode);
    }
}

fn both<F: DepthFormat>(input: &Input, raster: RasterConfig, s: &Scene) {
    let unit = if input.dual { DepthUnit::Dual } else { DepthUnit::Single };
    let cfg = LightPassConfig { raster, unit, max_z_cull: input.max_z_cull };
    let setups = usize::from(input.setups);
    let a = match input.bin % 3 {
        0 => run::<F, 1>(cfg, setups, s, true),
        1 => run::<F, 3>(cfg, setups, s, false),
        _ => run::<F, 64>(cfg, setups, s, false),
    };
    let Ok(a) = a else {
        assert_eq!(setups, 0, "only an empty setup store is refused");
        return;
    };
    // The same maps with another tile size, deep bins, a large store and
    // culling the other way.
    let tile = if raster.tile_size() == 16 { 64 } else { 16 };
    let other = RasterConfig::new(raster.width(), raster.height(), tile, raster.subpixel_bits()).expect("valid");
    let b = run::<F, 256>(LightPassConfig { raster: other, unit, max_z_cull: !input.max_z_cull }, 4096, s, false)
        .expect("valid buffers");
    assert_eq!(a, b, "maps depend on tiling, binning or culling");
}

fuzz_target!(|input: Input| {
    let Ok(raster) = RasterConfig::new(
        u32::from(input.width),
        u32::from(input.height),
        1u32 << (input.tile_log % 9),
        u32::from(input.subpixel_bits % 10),
    ) else {
        return;
    };
    let positions: Vec<Vec3> = input.positions.iter().take(64).map(|p| Vec3::new(f(p[0]), f(p[1]), f(p[2]))).collect();
    let n = positions.len() as u32 + 1; // one past the end: a bad index now and then
    let (triangles, culls) =
        input.triangles.iter().take(96).map(|(t, c)| (t.map(|i| u32::from(i) % n.max(1)), cull(*c))).unzip();
    let clip = input
        .clip
        .iter()
        .take(32)
        .map(|(t, c)| (t.map(|v| Vec4::new(f(v[0]), f(v[1]), f(v[2]), f(v[3]))), cull(*c)))
        .collect();
    let s = Scene { positions, triangles, culls, matrix: Mat4::from_cols_array(&input.matrix.map(f)), clip };
    match input.format % 3 {
        0 => both::<D16>(&input, raster, &s),
        1 => both::<D24>(&input, raster, &s),
        _ => both::<F32>(&input, raster, &s),
    }
});
