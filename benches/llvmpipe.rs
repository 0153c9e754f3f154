#![allow(missing_docs, clippy::cast_precision_loss, reason = "bench harness")]
//! The light pass beside Mesa's llvmpipe, the rasterizer a graphics
//! architect reaches for to render a depth map on a CPU.
//!
//! Every shared mesh (`../shared/meshes`, or `$UMBRA_MESHES`) at 1024² and
//! 4096², from the spot light that frames it (`Perspective::framing`, the
//! view `umbra depth --mesh` draws), on one thread:
//! * Umbra: the light pass, 24-bit depth, single unit, max-z culling, into
//!   a frame kept from pass to pass, no probe (criterion, and timed in
//!   turns with llvmpipe for the ratio);
//! * llvmpipe: the same mesh depth-only into a 24-bit depth texture through
//!   EGL surfaceless with `LP_NUM_THREADS=1`, warm frames (clear, draw,
//!   `glFinish`), by the harness `hosts/llvmpipe` (built here; the driving
//!   needs FFI, which the project keeps out of its own crates).
//!
//! It prints, per mesh and size, both medians and Umbra's time over
//! llvmpipe's. Without llvmpipe (`apt-get install libegl1 libegl-mesa0
//! libgl1-mesa-dri`) or the meshes it says so and times Umbra alone.
//!
//! Run: `cargo bench --bench llvmpipe -- --warm-up-time 1 --measurement-time 3`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::input::limits::Limits;
use umbra::sim::pass::light::{Draw, LightFrame, LightOptions, render};
use umbra::sim::world::mesh::Mesh;
use umbra::sim::world::scene::Perspective;
use umbra::sim::world::scene_file::shared_meshes;

const SIDES: [u32; 2] = [1024, 4096];
const FRAMES: usize = 15;

/// The workspace's root, where `../shared/meshes` is read from as
/// `umbra` reads it (cargo runs a bench in its package's folder).
fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// The shared meshes, by name.
fn meshes() -> Vec<(String, PathBuf)> {
    let dir = root().join(shared_meshes());
    let mut found: Vec<(String, PathBuf)> = std::fs::read_dir(&dir)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "obj"))
                .filter_map(|p| Some((p.file_stem()?.to_string_lossy().into_owned(), p)))
                .collect()
        })
        .unwrap_or_default();
    found.sort();
    found
}

/// Build the llvmpipe harness; its path, or why not.
fn harness() -> Result<PathBuf, String> {
    let root = root();
    let out = Command::new(option_env!("CARGO").unwrap_or("cargo"))
        .args(["build", "--release", "--quiet", "-p", "umbra-llvmpipe"])
        .current_dir(root)
        .output()
        .map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    Ok(target.join("release/umbra-llvmpipe"))
}

/// llvmpipe's median warm frame, ms, on one thread.
fn llvmpipe_ms(harness: &Path, mesh: &Path, side: u32) -> Result<f64, String> {
    let out = Command::new(harness)
        .arg(mesh)
        .arg(side.to_string())
        .arg(FRAMES.to_string())
        .env("LP_NUM_THREADS", "1")
        .env("EGL_PLATFORM", "surfaceless")
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() || !text.contains("drawn=true") {
        return Err(format!("{}{text}", String::from_utf8_lossy(&out.stderr)));
    }
    text.lines()
        .find_map(|l| l.strip_prefix("ms_median="))
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| format!("no ms_median in {text}"))
}

fn config(side: u32) -> LightPassConfig {
    let raster = RasterConfig::new(side, side, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
        .expect("valid");
    LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true }
}

/// One Umbra light pass into `frame`.
fn umbra(frame: &mut LightFrame<u32>, side: u32, draw: Draw<'_>) {
    render::<D24, _, _>(frame, config(side), black_box(&[draw]), LightOptions::default(), NoProbe)
        .map(|_| ())
        .expect("renders");
}

/// Umbra's median frame, ms.
fn umbra_ms(frame: &mut LightFrame<u32>, side: u32, draw: Draw<'_>) -> f64 {
    umbra(frame, side, draw);
    let mut ms: Vec<f64> = (0..FRAMES)
        .map(|_| {
            let t = Instant::now();
            umbra(frame, side, draw);
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    ms[ms.len() / 2]
}

fn bench(c: &mut Criterion) {
    let meshes = meshes();
    if meshes.is_empty() {
        eprintln!("llvmpipe: no meshes in {} (set UMBRA_MESHES)", root().join(shared_meshes()).display());
        return;
    }
    let harness = harness();
    if let Err(e) = &harness {
        eprintln!("llvmpipe: the harness did not build, timing Umbra alone: {e}");
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a pool");
    let mut g = c.benchmark_group("llvmpipe");
    let mut table = Vec::new();
    for (name, path) in &meshes {
        let Ok(mesh) = Mesh::load_obj(path, &Limits::DEFAULT) else { continue };
        let Some(light) = Perspective::framing(&mesh) else { continue };
        let draw = Draw {
            positions: &mesh.positions,
            triangles: &mesh.triangles,
            transform: light.view_projection(),
            cull: CullMode::None,
        };
        for side in SIDES {
            let mut frame = LightFrame::new();
            // In turns, the one after the other, for the ratio.
            let ours = pool.install(|| umbra_ms(&mut frame, side, draw));
            let peer = harness.as_ref().map_err(Clone::clone).and_then(|h| llvmpipe_ms(h, path, side));
            table.push((name.clone(), side, mesh.triangles.len(), ours, peer));
            g.bench_with_input(BenchmarkId::new(format!("umbra d24 {name}"), side), &side, |b, &side| {
                pool.install(|| b.iter(|| umbra(&mut frame, side, draw)));
            });
        }
    }
    g.finish();
    println!("\n| mesh | triangles | map | Umbra ms | llvmpipe ms | Umbra / llvmpipe |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (name, side, triangles, ours, peer) in table {
        match peer {
            Ok(p) => println!("| {name} | {triangles} | {side}² | {ours:.3} | {p:.3} | {:.2} |", ours / p),
            Err(e) => {
                println!("| {name} | {triangles} | {side}² | {ours:.3} | — | — ({}) |", e.lines().next().unwrap_or(""))
            }
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
