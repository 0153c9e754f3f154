#![allow(missing_docs, clippy::cast_possible_truncation, clippy::cast_precision_loss, reason = "bench harness")]
//! The light pass beside a peer, and how its cost grows.
//!
//! * `peer`: the same procedural torus of 100 000 triangles drawn depth-only
//!   at 1024² by Umbra's light pass (24-bit, one core, 32-pixel tiles, max-z
//!   culling off and on) and by the `euc` software rasterizer (f32 depth,
//!   less-or-equal test with writes, no culling of either facing). The
//!   fragments each covers are counted once, outside the timing, and
//!   printed, so that fragments per second follow from the times. Each
//!   draws into new buffers every frame, and again into buffers kept from
//!   frame to frame (Umbra's `LightFrame`; euc's cleared depth buffer),
//!   and Umbra's banded pass on every core into a kept frame.
//! * `peer/triangles`: both into kept buffers over the torus cut into
//!   1 000 … 100 000 triangles, timed in turns and then each by criterion.
//! * `scaling/triangles`: 1k … 1M triangles of the same torus at 1024².
//! * `scaling/map`: the 100k torus at 64² … 4096².
//!
//! Run briefly: `cargo bench --bench peer -- --warm-up-time 1 --measurement-time 3`.

use std::cell::Cell;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, Triangles};
use euc::{DepthStrategy, Pipeline, Target};
use std::hint::black_box;
use umbra::core::front;
use umbra::core::glam::{Mat4, Vec3};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, NoProbe, Probe, RasterConfig};
use umbra::sim::base::counters::Counters;
use umbra::sim::pass::light::{Draw, LightFrame, LightMaps, LightOptions, render};
use umbra::sim::world::mesh::Mesh;
use umbra::sim::world::scene::Perspective;

/// A torus of `2 · rings · sides` triangles, filling most of a spot light's view.
fn torus(rings: u32, sides: u32) -> Mesh {
    Mesh::torus(Vec3::ZERO, 1.0, 0.4, rings, sides)
}

fn light() -> Mat4 {
    Perspective {
        position: Vec3::new(0.0, 2.2, 2.6),
        target: Vec3::ZERO,
        fov_degrees: 55.0,
        near: 1.0,
        far: 8.0,
        up: Vec3::Y,
    }
    .view_projection()
}

fn umbra_config(size: u32, cull: bool) -> LightPassConfig {
    LightPassConfig {
        raster: RasterConfig::new(size, size, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
            .expect("valid"),
        unit: DepthUnit::Single,
        max_z_cull: cull,
    }
}

fn umbra_draw(mesh: &Mesh) -> Draw<'_> {
    Draw { positions: &mesh.positions, triangles: &mesh.triangles, transform: light(), cull: CullMode::None }
}

/// Umbra's light pass into a frame kept from pass to pass.
fn umbra_kept(frame: &mut LightFrame<u32>, cfg: LightPassConfig, draw: Draw<'_>) {
    render::<D24, _, _>(frame, cfg, black_box(&[draw]), LightOptions::default(), NoProbe).map(|_| ()).expect("renders");
}

fn umbra_pass<P: Probe>(mesh: &Mesh, size: u32, cull: bool, probe: P) -> P {
    LightMaps::draw::<D24, P>(umbra_config(size, cull), &[umbra_draw(mesh)], LightOptions::default(), probe)
        .expect("renders")
        .1
}

/// `euc`'s pipeline: positions through the light's matrix, no colour.
struct Depth<'a> {
    matrix: Mat4,
    /// Counts the fragment shader's calls when present.
    count: Option<&'a Cell<u64>>,
}

impl Pipeline for Depth<'_> {
    type Vertex = Vec3;
    type VsOut = ();
    type Pixel = ();

    #[inline]
    fn vert(&self, p: &Vec3) -> ([f32; 4], ()) {
        ((self.matrix * p.extend(1.0)).to_array(), ())
    }

    #[inline]
    fn frag(&self, (): &()) {
        if let Some(c) = self.count {
            c.set(c.get() + 1);
        }
    }

    fn get_depth_strategy(&self) -> DepthStrategy {
        // Counting: every covered pixel reaches the fragment shader.
        if self.count.is_some() { DepthStrategy::None } else { DepthStrategy::IfLessWrite }
    }
}

/// The mesh as `euc` takes it: three vertices per triangle.
fn soup(mesh: &Mesh) -> Vec<Vec3> {
    mesh.triangles.iter().flat_map(|t| t.map(|i| mesh.positions[i as usize])).collect()
}

fn euc_pass(vertices: &[Vec3], size: usize, count: Option<&Cell<u64>>) -> Buffer2d<f32> {
    let mut colour = Buffer2d::new([size, size], ());
    let mut depth = Buffer2d::new([size, size], 1.0f32);
    euc_draw(vertices, &mut colour, &mut depth, count);
    depth
}

/// `euc` into kept buffers: the depth buffer cleared, then drawn.
fn euc_draw(vertices: &[Vec3], colour: &mut Buffer2d<()>, depth: &mut Buffer2d<f32>, count: Option<&Cell<u64>>) {
    depth.clear(1.0);
    Depth { matrix: light(), count }.draw::<Triangles<'_, Buffer2d<f32>, BackfaceCullingDisabled>, _>(
        vertices,
        colour,
        Some(depth),
    );
}

fn peer(c: &mut Criterion) {
    let mesh = torus(250, 200);
    let triangles = mesh.triangles.len() as u64;
    let vertices = soup(&mesh);
    let covered = umbra_pass(&mesh, 1024, false, Counters::new(&RasterConfig::new(1024, 1024, 32, 8).expect("valid")))
        .totals
        .fragments;
    let culled = umbra_pass(&mesh, 1024, true, Counters::new(&RasterConfig::new(1024, 1024, 32, 8).expect("valid")))
        .totals
        .fragments;
    let euc_covered = Cell::new(0);
    euc_pass(&vertices, 1024, Some(&euc_covered));
    eprintln!(
        "peer: {triangles} triangles at 1024²; fragments covered: umbra {covered} ({culled} with max-z culling), euc {}",
        euc_covered.get()
    );
    let mut g = c.benchmark_group("peer");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function("umbra d24, culling off", |b| b.iter(|| umbra_pass(black_box(&mesh), 1024, false, NoProbe)));
    g.bench_function("umbra d24, culling on", |b| b.iter(|| umbra_pass(black_box(&mesh), 1024, true, NoProbe)));
    g.bench_function("euc f32", |b| b.iter(|| euc_pass(black_box(&vertices), 1024, None)));
    // Both into buffers kept from frame to frame, as hardware keeps its
    // memory: no fresh pages in the timing.
    let mut frame: LightFrame<u32> = LightFrame::new();
    let (cfg, draw) = (umbra_config(1024, false), umbra_draw(&mesh));
    g.bench_function("umbra d24, culling off, kept frame", |b| {
        b.iter(|| umbra_kept(&mut frame, cfg, draw));
    });
    // Beside them, the banded pass on every core into a kept frame: the
    // same maps, bit for bit; euc draws on one core.
    let mut banded: LightFrame<u32> = LightFrame::new();
    g.bench_function("umbra d24, culling off, kept frame, every core", |b| {
        b.iter(|| {
            render::<D24, _, _>(&mut banded, cfg, black_box(&[draw]), LightOptions::BANDS, NoProbe)
                .map(|_| ())
                .expect("renders")
        });
    });
    let (mut colour, mut depth) = (Buffer2d::new([1024, 1024], ()), Buffer2d::new([1024, 1024], 1.0f32));
    g.bench_function("euc f32, kept buffers", |b| {
        b.iter(|| euc_draw(black_box(&vertices), &mut colour, &mut depth, None));
    });
    // The front end alone (vertex unit, clipping, snap, setup): the share of
    // the light pass that comes before binning and rasterization.
    let raster = RasterConfig::new(1024, 1024, 32, 8).expect("valid");
    g.bench_function("umbra d24, front end only", |b| {
        b.iter(|| {
            let mut set_up = 0u32;
            let cache = &mut front::vertex::VertexCache::<{ front::vertex::CACHE_ENTRIES }>::new();
            front::mesh::<D24, { front::vertex::CACHE_ENTRIES }>(
                &raster,
                &mesh.positions,
                black_box(&mesh.triangles),
                &light(),
                CullMode::None,
                0,
                cache,
                &mut |o| {
                    set_up += u32::from(matches!(o, front::Output::Setup(_)));
                },
            );
            set_up
        });
    });
    g.finish();
}

fn scaling(c: &mut Criterion) {
    let mut g = c.benchmark_group("scaling/triangles");
    g.sample_size(10);
    for (rings, sides) in [(25, 20), (100, 50), (250, 200), (1000, 500)] {
        let mesh = torus(rings, sides);
        let n = mesh.triangles.len() as u64;
        g.throughput(Throughput::Elements(n));
        g.bench_with_input(BenchmarkId::from_parameter(n), &mesh, |b, m| b.iter(|| umbra_pass(m, 1024, true, NoProbe)));
    }
    g.finish();
    let mesh = torus(250, 200);
    let mut g = c.benchmark_group("scaling/map");
    g.sample_size(10);
    for size in [64u32, 256, 1024, 4096] {
        g.throughput(Throughput::Elements(u64::from(size) * u64::from(size)));
        g.bench_with_input(BenchmarkId::from_parameter(size), &size, |b, &s| {
            b.iter(|| umbra_pass(&mesh, s, true, NoProbe));
        });
    }
    g.finish();
}

/// The light pass on every core (`LightOptions::BANDS`: the front end on runs of
/// triangles in parallel, then bands of tile rows in parallel; bit-identical
/// to the single pass) on 1, 2 and every core, beside the whole pass on one,
/// at 2048² where each band has enough tiles to keep a core busy; each with
/// new buffers every frame and into a kept `LightFrame`.
fn cores(c: &mut Criterion) {
    let mesh = torus(250, 200);
    let cfg = LightPassConfig {
        raster: RasterConfig::new(2048, 2048, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
            .expect("valid"),
        unit: DepthUnit::Single,
        max_z_cull: true,
    };
    let draw = umbra_draw(&mesh);
    let mut g = c.benchmark_group("cores");
    g.sample_size(10);
    g.bench_function("whole pass", |b| {
        b.iter(|| {
            LightMaps::draw::<D24, _>(cfg, black_box(&[draw]), LightOptions::default(), NoProbe).expect("renders")
        });
    });
    let mut frame: LightFrame<u32> = LightFrame::new();
    g.bench_function("whole pass, kept frame", |b| {
        b.iter(|| umbra_kept(&mut frame, cfg, draw));
    });
    let all = std::thread::available_parallelism().map_or(1, usize::from);
    let mut counts = vec![1, 2, all];
    counts.dedup();
    for threads in counts {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        g.bench_function(BenchmarkId::from_parameter(threads), |b| {
            b.iter(|| {
                pool.install(|| {
                    LightMaps::draw::<D24, _>(cfg, black_box(&[draw]), LightOptions::BANDS, NoProbe)
                        .map(|(m, _)| m)
                        .expect("renders")
                })
            });
        });
        g.bench_function(BenchmarkId::new("kept frame", threads), |b| {
            b.iter(|| {
                pool.install(|| {
                    render::<D24, _, _>(&mut frame, cfg, black_box(&[draw]), LightOptions::BANDS, NoProbe)
                        .map(|_| ())
                        .expect("renders")
                });
            });
        });
    }
    g.finish();
}

/// Turns each rasterizer takes in [`peer_sizes`]'s interleaved comparison.
const ROUNDS: u32 = 25;

/// The fastest of `rounds` runs of each of `a` and `b`, taken in turns, so
/// that both see the same phases of a noisy machine.
fn interleaved(rounds: u32, mut a: impl FnMut(), mut b: impl FnMut()) -> (Duration, Duration) {
    let mut best = (Duration::MAX, Duration::MAX);
    for _ in 0..rounds {
        let t = Instant::now();
        a();
        best.0 = best.0.min(t.elapsed());
        let t = Instant::now();
        b();
        best.1 = best.1.min(t.elapsed());
    }
    best
}

/// Both rasterizers into kept buffers over the same torus cut into fewer,
/// larger triangles: where per-triangle work gives way to fill. Before the
/// timed groups, the two take turns for [`ROUNDS`] rounds and the fastest
/// of each is printed with their ratio, the figure that holds on a noisy
/// machine.
fn peer_sizes(c: &mut Criterion) {
    let mut g = c.benchmark_group("peer/triangles");
    g.sample_size(10);
    let (mut colour, mut depth) = (Buffer2d::new([1024, 1024], ()), Buffer2d::new([1024, 1024], 1.0f32));
    let mut frame: LightFrame<u32> = LightFrame::new();
    let cfg = umbra_config(1024, false);
    for (rings, sides) in [(25, 20), (50, 40), (100, 50), (250, 200)] {
        let mesh = torus(rings, sides);
        let n = mesh.triangles.len() as u64;
        let vertices = soup(&mesh);
        g.throughput(Throughput::Elements(n));
        let draw = umbra_draw(&mesh);
        let (umbra, euc) = interleaved(
            ROUNDS,
            || umbra_kept(&mut frame, cfg, draw),
            || euc_draw(black_box(&vertices), &mut colour, &mut depth, None),
        );
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        eprintln!(
            "peer/triangles/{n}, fastest of {ROUNDS} in turns: umbra {:.2} ms, euc {:.2} ms, umbra {:.2}× euc's speed",
            ms(umbra),
            ms(euc),
            euc.as_secs_f64() / umbra.as_secs_f64()
        );
        g.bench_function(BenchmarkId::new("umbra d24, kept frame", n), |b| {
            b.iter(|| umbra_kept(&mut frame, cfg, draw));
        });
        g.bench_function(BenchmarkId::new("euc f32, kept buffers", n), |b| {
            b.iter(|| euc_draw(black_box(&vertices), &mut colour, &mut depth, None));
        });
    }
    g.finish();
}

criterion_group!(benches, peer, peer_sizes, scaling, cores);
criterion_main!(benches);
