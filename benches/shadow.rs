//! Shadow-unit lookups per second on one core, per filter: 1920×1080
//! lookups spread over a 1024² dual map of a jittered height field, each at
//! the stored surface's own depth so the comparisons are mixed.
#![allow(
    missing_docs,
    clippy::cast_possible_truncation,
    clippy::cast_precision_loss,
    clippy::cast_sign_loss,
    reason = "bench harness"
)]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::core::depth::PlaneZ;
use umbra::core::glam::{Mat4, Vec3};
use umbra::core::shadow::{Bias, DepthTest, Lookup, MapCoord, MapView, ShadowConfig, shadow};
use umbra::core::{CullMode, D24, DepthFormat, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::pass::light::{Draw, LightMaps, LightOptions};

const MAP: u32 = 1024;
const W: u32 = 1920;
const H: u32 = 1080;

/// Two layers of a 128² grid with hashed heights: z1 and z2 both vary.
fn maps() -> LightMaps<u32> {
    let n = 128u32;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for layer in 0..2u32 {
        let base = positions.len() as u32;
        for j in 0..=n {
            for i in 0..=n {
                let h = ((i.wrapping_mul(2_654_435_761) ^ j.wrapping_mul(40_503)) % 1000) as f32 / 1000.0;
                let z = 0.3 + 0.3 * layer as f32 + 0.05 * h;
                positions.push(Vec3::new(-1.0 + 2.0 * i as f32 / n as f32, -1.0 + 2.0 * j as f32 / n as f32, z));
            }
        }
        let at = |i: u32, j: u32| base + j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    let raster = RasterConfig::new(MAP, MAP, 32, 8).expect("valid");
    let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draw = Draw { positions: &positions, triangles: &triangles, transform: Mat4::IDENTITY, cull: CullMode::None };
    LightMaps::draw::<D24, _>(cfg, &[draw], LightOptions::default(), NoProbe).expect("renders").0
}

fn bench_lookups(c: &mut Criterion) {
    let maps = maps();
    let view = MapView::<D24>::new(maps.config.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    // Lookups are made on the fly, in scanline order, as a camera pass would.
    let lookup = |k: u32| {
        let (px, py) = (k % W, k / W);
        let (x, y) = (px as f32 * MAP as f32 / W as f32 + 0.3, py as f32 * MAP as f32 / H as f32 + 0.6);
        let texel = maps.z1[((y as u32).min(MAP - 1) * MAP + (x as u32).min(MAP - 1)) as usize];
        Lookup {
            x: MapCoord::from_num(x),
            y: MapCoord::from_num(y),
            z: PlaneZ::from_bits(D24::widen(texel)),
            footprint: [MapCoord::from_num(0.5); 2],
            seed: u64::from(k),
            slope: None,
        }
    };
    let mut g = c.benchmark_group("shadow_lookups_1080p");
    g.sample_size(10);
    g.throughput(Throughput::Elements(u64::from(W * H)));
    let filters = umbra::sim::experiment::presets::FILTERS;
    for filter in filters {
        let name = filter.to_string();
        for cull in [false, true] {
            let cfg = ShadowConfig::new(DepthTest::Second, Bias::ZERO, filter, cull).expect("valid");
            g.bench_function(BenchmarkId::new(name.as_str(), if cull { "cull" } else { "nocull" }), |b| {
                b.iter(|| {
                    (0..W * H)
                        .map(|k| shadow(&view, &cfg, &lookup(k), &mut NoProbe).to_bits())
                        .fold(0u64, |a, s| a + u64::from(s))
                })
            });
        }
    }
    g.finish();
    black_box(&maps);
}

criterion_group!(benches, bench_lookups);
criterion_main!(benches);
