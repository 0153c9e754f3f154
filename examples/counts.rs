#![allow(missing_docs, clippy::cast_possible_truncation, clippy::cast_precision_loss)]
use umbra::core::glam::{Mat4, Vec3};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::light::{Draw, render};
const SIZE: u32 = 1024;
include!("/tmp/soup.rs");
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let soup = match args[1].as_str() { "large" => large_passing(), "small" => small_triangles(), "ftb" => layers(true), _ => layers(false) };
    let unit = if args[2] == "dual" { DepthUnit::Dual } else { DepthUnit::Single };
    let cull = args[3] == "cull";
    let raster = RasterConfig::new(SIZE, SIZE, 32, 8).unwrap();
    let cfg = LightPassConfig { raster, unit, max_z_cull: cull };
    let t = std::time::Instant::now();
    for _ in 0..10 {
        let (m, _) = render::<D24, _>(cfg, &[soup.draw()], NoProbe).unwrap();
        std::hint::black_box(m);
    }
    println!("{:?}", t.elapsed() / 10);
    let (_, c) = render::<D24, _>(cfg, &[soup.draw()], umbra::sim::counters::Counters::new(&raster)).unwrap();
    println!("updates {} culled {} {} frags {}", c.totals.tile_max_updates, c.totals.culled_triangles, c.totals.culled_blocks, c.totals.fragments);
}
#[allow(dead_code)]
fn unused() {}
