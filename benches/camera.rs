//! The camera pass at 1920×1080 on one core, per filter: visibility with
//! the camera's matrix, then shading against a 1024² dual 24-bit map of the
//! bundled default scene (second depth, virtual samples), into a frame kept
//! from one pass to the next as a framebuffer is; for the 3×3 box also into
//! a new frame each time (83 MB of results to allocate) and keeping only
//! each pixel's shadow fraction (4 bytes, not 40). Also prints the
//! fraction of covered pixels that needed virtual samples.
#![allow(missing_docs, clippy::cast_precision_loss, reason = "bench harness")]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::core::shade::MapUnit;
use umbra::core::shadow::{Bias, DepthTest, Shadow, ShadowConfig};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, NO_TRIANGLE, NoProbe, RasterConfig};
use umbra::sim::base::counters::Counters;
use umbra::sim::base::maps::Tiling;
use umbra::sim::pass::camera::{CameraFrame, CameraOptions, map_view, render, render_into};
use umbra::sim::pass::light::{LightMaps, LightOptions};
use umbra::sim::world::scene::Scene;

const W: u32 = 1920;
const H: u32 = 1080;

fn bench_camera(c: &mut Criterion) {
    let scene = Scene::default_scene();
    let raster = RasterConfig::new(1024, 1024, 32, 8).expect("valid");
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let (maps, _) = LightMaps::draw::<D24, _>(
        config,
        &scene.draws(scene.light().view_projection(), CullMode::None),
        LightOptions::default(),
        NoProbe,
    )
    .expect("renders");
    let view = map_view::<D24>(&maps, false).expect("sized");
    let filters = umbra::sim::experiment::presets::FILTERS;
    let mut g = c.benchmark_group("camera_pass_1080p");
    g.sample_size(10);
    g.throughput(Throughput::Elements(u64::from(W * H)));
    for filter in filters {
        let name = filter.to_string();
        let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, filter, true).expect("valid");
        let options = CameraOptions { width: W, height: H, shadow, virtual_samples: true, tiling: Tiling::DEFAULT };
        let mut counters = Counters::new(&RasterConfig::new(W, H, 32, 8).expect("valid"));
        let mut frame = CameraFrame::default();
        render(&mut frame, &scene, &view, &MapUnit, &options, &mut counters).expect("renders");
        let covered = frame.pixels.iter().filter(|p| p.triangle != NO_TRIANGLE).count() as f64;
        eprintln!(
            "{name}: virtual samples for {:.2} % of {covered} covered pixels, {} lookups culled",
            100.0 * counters.totals.tangent_setups as f64 / covered,
            counters.totals.lookups_culled
        );
        g.bench_function(BenchmarkId::new(name.as_str(), "virtual_samples"), |b| {
            b.iter(|| {
                render(&mut frame, &scene, &view, &MapUnit, &options, &mut NoProbe).expect("renders");
                black_box(&frame.pixels);
            })
        });
        if name == "box3" {
            // The shadow fraction alone, 4 bytes a pixel, into a kept buffer.
            let mut shadows: Vec<Shadow> = Vec::new();
            g.bench_function(BenchmarkId::new(name.as_str(), "fraction_only"), |b| {
                b.iter(|| {
                    render_into(&mut frame, &scene, &view, &MapUnit, &options, &mut NoProbe, &mut shadows)
                        .expect("renders");
                    black_box(&shadows);
                })
            });
            g.bench_function(BenchmarkId::new(name.as_str(), "new_frame"), |b| {
                b.iter(|| {
                    let mut frame = CameraFrame::default();
                    render(&mut frame, &scene, &view, &MapUnit, &options, &mut NoProbe).expect("renders");
                    black_box(frame.take_image())
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench_camera);
criterion_main!(benches);
