//! One light pass, repeated, for profilers: the `peer` bench's torus of
//! 100 000 triangles, by default at 1024² (24-bit, single, max-z culling
//! off), into one `LightFrame` kept from pass to pass (or, with `-new`, a
//! new one each pass).
//!
//! ```sh
//! cargo build --release --bin light_profile
//! valgrind --tool=callgrind target/release/light_profile 2
//! perf record -g target/release/light_profile 50
//! target/release/light_profile 50 bands 2048   # LightOptions::BANDS, 2048²
//! RAYON_NUM_THREADS=1 target/release/light_profile 4 bands 2048
//! target/release/light_profile 1 whole 1024 digest
//! target/release/light_profile 20 bands-new 2048   # a new frame each pass
//! ```
//!
//! With `digest` it prints a digest of the last maps' bits too: a change
//! to the hot path must keep it. Instruction counts under callgrind are
//! the same from run to run, so they compare changes to the hot path on a
//! noisy machine where times do not.
//!
//! The environment varies the pass: `TORUS=50x40` (rings × sides: 4 000
//! larger triangles), `MESH=path.obj` (an OBJ mesh in place of the torus,
//! from the spot light that frames it, as the `llvmpipe` bench draws it), `UNIT=single|dual`, `CULL=0|1` (max-z culling),
//! `ARCH=talisman|immediate|…` (the counting path: that bundled
//! architecture's timing probe on every event, the immediate-mode ones
//! with their depth cache fed fragment by fragment):
//!
//! ```sh
//! TORUS=25x20 UNIT=dual CULL=1 target/release/light_profile 1 whole 2048 digest
//! ```

use std::hash::{DefaultHasher, Hash, Hasher};

use umbra::core::glam::Vec3;
use umbra::core::{CullMode, D24, DepthFormat, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::cost::arch::Arch;
use umbra::sim::cost::timing::{ArchProbe, PassKind};
use umbra::sim::input::limits::Limits;
use umbra::sim::pass::light::{Draw, LightFrame, LightOptions, render};
use umbra::sim::world::mesh::Mesh;
use umbra::sim::world::scene::Perspective;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let passes: u32 = std::env::args().nth(1).map_or(Ok(1), |s| s.parse())?;
    let mode = std::env::args().nth(2).unwrap_or_default();
    let bands = mode.starts_with("bands");
    // `whole-new`, `bands-new`: new maps and scratch every pass.
    let new = mode.ends_with("-new");
    let side: u32 = std::env::args().nth(3).map_or(Ok(1024), |s| s.parse())?;
    let digest = std::env::args().nth(4).is_some_and(|a| a == "digest");
    let (rings, sides): (u32, u32) = match std::env::var("TORUS") {
        Ok(t) => {
            let (r, s) = t.split_once('x').ok_or("TORUS is rings x sides, as 50x40")?;
            (r.parse()?, s.parse()?)
        }
        Err(_) => (250, 200),
    };
    let (mesh, light) = match std::env::var("MESH") {
        // An OBJ mesh from the spot light that frames it, as the `llvmpipe` bench draws it.
        Ok(path) => {
            let mesh = Mesh::load_obj(std::path::Path::new(&path), &Limits::DEFAULT)?;
            let light = Perspective::framing(&mesh).ok_or("the mesh has no extent to frame")?.view_projection();
            (mesh, light)
        }
        Err(_) => (
            Mesh::torus(Vec3::ZERO, 1.0, 0.4, rings, sides),
            Perspective {
                position: Vec3::new(0.0, 2.2, 2.6),
                target: Vec3::ZERO,
                fov_degrees: 55.0,
                near: 1.0,
                far: 8.0,
                up: Vec3::Y,
            }
            .view_projection(),
        ),
    };
    let raster = RasterConfig::new(side, side, 32, 8)?;
    let unit = match std::env::var("UNIT").as_deref() {
        Ok("dual") => DepthUnit::Dual,
        Ok("single") | Err(_) => DepthUnit::Single,
        Ok(other) => return Err(format!("UNIT is single or dual, not {other}").into()),
    };
    let max_z_cull = match std::env::var("CULL").as_deref() {
        Ok("1") => true,
        Ok("0") | Err(_) => false,
        Ok(other) => return Err(format!("CULL is 0 or 1, not {other}").into()),
    };
    let cfg = LightPassConfig { raster, unit, max_z_cull };
    let draw = Draw { positions: &mesh.positions, triangles: &mesh.triangles, transform: light, cull: CullMode::None };
    // One frame for every pass, as hardware keeps its memory: after the
    // first, a pass touches no fresh pages.
    let mut frame: LightFrame<u32> = LightFrame::new();
    let start = std::time::Instant::now();
    let arch = std::env::var("ARCH").ok().map(|a| Arch::bundled(&a)).transpose()?;
    for _ in 0..passes {
        if new {
            frame = LightFrame::<u32>::new();
        }
        if let Some(arch) = &arch {
            let buffers = unit.buffers();
            if arch.on_chip.light_depth {
                let probe = ArchProbe::<false>::new(arch, PassKind::Light, raster, D24::KIND, buffers);
                std::hint::black_box(render::<D24, _, _>(&mut frame, cfg, &[draw], LightOptions::default(), probe)?.1);
            } else {
                let probe = ArchProbe::<true>::new(arch, PassKind::Light, raster, D24::KIND, buffers);
                std::hint::black_box(render::<D24, _, _>(&mut frame, cfg, &[draw], LightOptions::default(), probe)?.1);
            }
        } else if bands {
            render::<D24, _, _>(&mut frame, cfg, &[draw], LightOptions::BANDS, NoProbe)?;
        } else {
            render::<D24, _, _>(&mut frame, cfg, &[draw], LightOptions::default(), NoProbe)?;
        }
    }
    let took = start.elapsed();
    let maps = frame.maps();
    let lit = maps.map_or(0, |m| m.z1.iter().filter(|&&z| z < D24::FAR).count());
    let each = took.as_secs_f64() * 1e3 / f64::from(passes.max(1));
    println!("{passes} passes, {lit} texels covered, {each:.1} ms a pass");
    if digest {
        // A digest of the map's bits: a change to the hot path must keep it.
        let mut hasher = DefaultHasher::new();
        maps.map(|m| &m.z1).hash(&mut hasher);
        // The dual unit's second map too (a single unit's is empty).
        if let Some(m) = maps.filter(|m| !m.z2.is_empty()) {
            m.z2.hash(&mut hasher);
        }
        println!("map digest {:016x}", hasher.finish());
    }
    Ok(())
}
