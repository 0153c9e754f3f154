#![allow(missing_docs, clippy::cast_possible_truncation, clippy::cast_precision_loss, reason = "bench harness")]
//! Light-pass throughput on one core: fill rate, small triangles, and what
//! max-z culling buys (front to back) and costs (back to front).
//!
//! Scenes are built in light clip space (identity transform, `w = 1`) at
//! 1024², each at least 50k triangles.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::core::glam::{Mat4, Vec3};
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::base::counters::Counters;
use umbra::sim::pass::light::{Draw, LightMaps, LightOptions};

const SIZE: u32 = 1024;

/// A triangle soup in NDC with depth in z.
struct Soup {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
}

impl Soup {
    fn new() -> Self {
        Self { positions: Vec::new(), triangles: Vec::new() }
    }

    fn push(&mut self, a: Vec3, b: Vec3, c: Vec3) {
        let n = self.positions.len() as u32;
        self.positions.extend([a, b, c]);
        self.triangles.push([n, n + 1, n + 2]);
    }

    fn draw(&self) -> Draw<'_> {
        Draw { positions: &self.positions, triangles: &self.triangles, transform: Mat4::IDENTITY, cull: CullMode::None }
    }
}

/// A small deterministic generator (xorshift), so scenes are the same every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// 50k large right triangles (legs of 64 px: ~2k fragments each), each
/// nearer than all before it, so every fragment passes.
fn large_passing() -> Soup {
    let mut s = Soup::new();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let n = 50_000;
    let leg = 2.0 * 64.0 / SIZE as f32;
    for i in 0..n {
        let z = 1.0 - (i as f32 + 1.0) / (n as f32 + 2.0);
        let (x, y) = (rng.next() * (2.0 - leg) - 1.0, rng.next() * (2.0 - leg) - 1.0);
        s.push(Vec3::new(x, y, z), Vec3::new(x + leg, y, z), Vec3::new(x, y + leg, z));
    }
    s
}

/// An indexed grid mesh of `nx × ny` quads over the map at depth `z(i, j)`,
/// two triangles per quad sharing their vertices, as a real mesh does.
fn grid(s: &mut Soup, nx: u32, ny: u32, z: impl Fn(u32, u32) -> f32) {
    let base = s.positions.len() as u32;
    for j in 0..=ny {
        for i in 0..=nx {
            s.positions.push(Vec3::new(-1.0 + 2.0 * i as f32 / nx as f32, -1.0 + 2.0 * j as f32 / ny as f32, z(i, j)));
        }
    }
    let at = |i: u32, j: u32| base + j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            s.triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            s.triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
}

/// ≈10-pixel triangles covering the map: a 228² grid with random depths,
/// 2 × 228² ≈ 104k triangles.
fn small_triangles() -> Soup {
    let mut s = Soup::new();
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let depths: Vec<f32> = (0..229 * 229).map(|_| 0.2 + 0.6 * rng.next()).collect();
    grid(&mut s, 228, 228, |i, j| depths[(j * 229 + i) as usize]);
    s
}

/// 32 layers of a 40×20-quad grid over the whole map (51 200 triangles),
/// in order of depth: front to back or back to front.
fn layers(front_to_back: bool) -> Soup {
    let mut s = Soup::new();
    let (nx, ny, layers) = (40u32, 20u32, 32u32);
    for l in 0..layers {
        let k = if front_to_back { l } else { layers - 1 - l };
        let z = 0.1 + 0.8 * k as f32 / layers as f32;
        for j in 0..ny {
            for i in 0..nx {
                let p =
                    |i: u32, j: u32| Vec3::new(-1.0 + 2.0 * i as f32 / nx as f32, -1.0 + 2.0 * j as f32 / ny as f32, z);
                s.push(p(i, j), p(i + 1, j), p(i + 1, j + 1));
                s.push(p(i, j), p(i + 1, j + 1), p(i, j + 1));
            }
        }
    }
    s
}

fn config(unit: DepthUnit, max_z_cull: bool) -> LightPassConfig {
    config_tiled(unit, max_z_cull, RasterConfig::DEFAULT_TILE_SIZE)
}

fn config_tiled(unit: DepthUnit, max_z_cull: bool, tile: u32) -> LightPassConfig {
    let raster = RasterConfig::new(SIZE, SIZE, tile, 8).expect("valid");
    LightPassConfig { raster, unit, max_z_cull }
}

fn fragments(soup: &Soup, unit: DepthUnit, cull: bool) -> u64 {
    let cfg = config(unit, cull);
    let (_, c) = LightMaps::draw::<D24, _>(cfg, &[soup.draw()], LightOptions::default(), Counters::new(&cfg.raster))
        .expect("renders");
    c.totals.fragments
}

fn run<F: DepthFormat>(soup: &Soup, unit: DepthUnit, cull: bool) {
    let (maps, _) =
        LightMaps::draw::<F, _>(config(unit, cull), &[soup.draw()], LightOptions::default(), NoProbe).expect("renders");
    black_box(maps);
}

fn variants() -> [(&'static str, DepthUnit, bool); 4] {
    [
        ("d16/single", DepthUnit::Single, false),
        ("d24/single", DepthUnit::Single, true),
        ("d16/dual", DepthUnit::Dual, false),
        ("d24/dual", DepthUnit::Dual, true),
    ]
}

fn bench_light_pass(c: &mut Criterion) {
    let large = large_passing();
    let mut g = c.benchmark_group("fill_large_passing");
    g.sample_size(10);
    for (name, unit, d24) in variants() {
        for cull in [false, true] {
            g.throughput(Throughput::Elements(fragments(&large, unit, cull)));
            let id = BenchmarkId::new(name, if cull { "cull" } else { "nocull" });
            if d24 {
                g.bench_function(id, |b| b.iter(|| run::<D24>(&large, unit, cull)));
            } else {
                g.bench_function(id, |b| b.iter(|| run::<D16>(&large, unit, cull)));
            }
        }
    }
    g.finish();

    let mut g = c.benchmark_group("fill_large_passing_by_tile");
    g.sample_size(10);
    g.throughput(Throughput::Elements(fragments(&large, DepthUnit::Single, false)));
    for tile in [16, 32, 64, 128] {
        g.bench_function(BenchmarkId::new("d16/single/nocull", tile), |b| {
            b.iter(|| {
                black_box(LightMaps::draw::<D16, _>(
                    config_tiled(DepthUnit::Single, false, tile),
                    &[large.draw()],
                    LightOptions::default(),
                    NoProbe,
                ))
            })
        });
    }
    g.finish();

    let small = small_triangles();
    let mut g = c.benchmark_group("small_triangles");
    g.sample_size(10);
    g.throughput(Throughput::Elements(small.triangles.len() as u64));
    for (name, unit, d24) in variants() {
        if d24 {
            g.bench_function(name, |b| b.iter(|| run::<D24>(&small, unit, true)));
        } else {
            g.bench_function(name, |b| b.iter(|| run::<D16>(&small, unit, true)));
        }
    }
    g.finish();

    let mut g = c.benchmark_group("max_z_culling");
    g.sample_size(10);
    for (order, ftb) in [("front_to_back", true), ("back_to_front", false)] {
        let soup = layers(ftb);
        g.throughput(Throughput::Elements(soup.triangles.len() as u64));
        for (unit_name, unit) in [("single", DepthUnit::Single), ("dual", DepthUnit::Dual)] {
            for cull in [false, true] {
                let id = BenchmarkId::new(format!("{order}/{unit_name}"), if cull { "cull" } else { "nocull" });
                g.bench_function(id, |b| b.iter(|| run::<D24>(&soup, unit, cull)));
            }
        }
    }
    g.finish();
}

/// The cycle-counting path (the Talisman model as the probe, and the
/// immediate-mode model with its depth cache fed fragment by fragment)
/// against the functional path (no probe) on the same render, in one run.
fn bench_probe_overhead(c: &mut Criterion) {
    use umbra::core::DepthFormatKind;
    use umbra::sim::cost::arch::Arch;
    use umbra::sim::cost::timing::{ArchProbe, PassKind};
    let small = small_triangles();
    let mut g = c.benchmark_group("probe_overhead");
    g.sample_size(10);
    g.throughput(Throughput::Elements(small.triangles.len() as u64));
    let cfg = config(DepthUnit::Dual, true);
    let (talisman, immediate) = (Arch::bundled("talisman"), Arch::bundled("immediate"));
    let (Ok(talisman), Ok(immediate)) = (talisman, immediate) else { return };
    g.bench_function("functional", |b| {
        b.iter(|| black_box(LightMaps::draw::<D24, _>(cfg, &[small.draw()], LightOptions::default(), NoProbe)))
    });
    g.bench_function("talisman_model", |b| {
        b.iter(|| {
            let probe = ArchProbe::<false>::new(&talisman, PassKind::Light, cfg.raster, DepthFormatKind::D24, 2);
            black_box(LightMaps::draw::<D24, _>(cfg, &[small.draw()], LightOptions::default(), probe))
        })
    });
    g.bench_function("immediate_model_depth_cache", |b| {
        b.iter(|| {
            let probe = ArchProbe::<true>::new(&immediate, PassKind::Light, cfg.raster, DepthFormatKind::D24, 2);
            black_box(LightMaps::draw::<D24, _>(cfg, &[small.draw()], LightOptions::default(), probe))
        })
    });
    g.finish();
}

criterion_group!(benches, bench_light_pass, bench_probe_overhead);
criterion_main!(benches);
