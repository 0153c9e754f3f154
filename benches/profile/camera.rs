//! The camera pass's shading unit, repeated, for profilers: the bundled
//! default scene at 1920×1080 against its 1024² dual 24-bit map, second
//! depth with virtual samples and a 3×3 box, as the `camera` bench runs it.
//! A preset filter's name (`point`, `bilinear`, `box3`, `jitter4`,
//! `jitter16`) as the second argument shades with that filter instead.
//! With `all`, it shades every bundled scene with every filter, flat and
//! smooth normals, with and without virtual samples, once each, and prints
//! one digest of all their bits and of every event and texel read the
//! shading unit reported: a change to the hot path that keeps the digest
//! keeps the results and the counts.
//!
//! ```sh
//! cargo build --release --bin camera_profile
//! perf record -g target/release/camera_profile 20
//! target/release/camera_profile 1 all
//! ```

use std::hash::{DefaultHasher, Hash, Hasher};

use umbra::core::depth::PlaneZ;
use umbra::core::probe::TexelRead;
use umbra::core::shade::{MapUnit, Normals, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, TriangleSource, shade_with};
use umbra::core::shadow::{Bias, DepthTest, Filter, MapView, ShadowConfig};
use umbra::core::{ConfigError, CullMode, D24, DepthUnit, Event, LightPassConfig, NoProbe, Probe, RasterConfig};
use umbra::sim::base::maps::Tiling;
use umbra::sim::experiment::presets::FILTERS;
use umbra::sim::pass::camera::{CameraFrame, SHADE_SETUPS, map_view, visibility};
use umbra::sim::pass::light::{LightMaps, LightOptions};
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::BUNDLED;

/// A probe that folds every event and texel read, in order, into a digest.
struct Trace<'a>(&'a mut DefaultHasher);

impl Probe for Trace<'_> {
    const TEXELS: bool = true;

    fn event(&mut self, event: Event) {
        format!("{event:?}").hash(self.0);
    }

    fn texel_read(&mut self, read: TexelRead) {
        read.hash(self.0);
    }
}

/// One shading pass, as the `camera` bench's frame runs it (the map unit,
/// the simulator's setup store).
fn shade_once<P: Probe>(
    cfg: &ShadeConfig,
    ids: &[u32],
    view: &MapView<'_, D24>,
    source: &impl TriangleSource,
    pixels: &mut [Shaded],
    setups: &mut [ShadeSetup],
    probe: &mut P,
) -> Result<(), ConfigError> {
    shade_with(&ShadeInputs { cfg, map: view, scene: source, unit: &MapUnit }, ids, pixels, setups, probe)
}

/// Shade `scene` once per configuration and fold every pixel's bits into
/// `digest`; with `trace`, the events and texel reads too.
fn shade_scene(
    scene: &Scene,
    configs: &[(ShadowConfig, bool, Normals)],
    passes: u32,
    (width, height): (u32, u32),
    trace: bool,
    digest: &mut DefaultHasher,
) -> Result<(), Box<dyn std::error::Error>> {
    let raster = RasterConfig::new(1024, 1024, 32, 8)?;
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let (maps, _) = LightMaps::draw::<D24, _>(
        config,
        &scene.draws(scene.light().view_projection(), CullMode::None),
        LightOptions::default(),
        NoProbe,
    )?;
    let view = map_view::<D24>(&maps, false)?;
    let mut frame = CameraFrame::default();
    let camera = visibility(&mut frame, scene, (width, height), Tiling::DEFAULT, &mut NoProbe)?.camera;
    let ids = frame.ids();
    let triangles = scene.triangles();
    let source = |id: u32| triangles.get(id as usize).copied();
    let mut pixels = vec![Shaded::BACKGROUND; ids.len()];
    let mut setups = vec![ShadeSetup::EMPTY; SHADE_SETUPS];
    for &(shadow, virtual_samples, normals) in configs {
        let light = scene.light().view_projection();
        let cfg = ShadeConfig { camera, light, width, height, shadow, virtual_samples, normals, seed: 0x5eed };
        for _ in 0..passes {
            if trace {
                shade_once(&cfg, ids, &view, &source, &mut pixels, &mut setups, &mut Trace(digest))?;
            } else {
                shade_once(&cfg, ids, &view, &source, &mut pixels, &mut setups, &mut NoProbe)?;
            }
        }
        for p in &pixels {
            p.triangle.hash(digest);
            p.light.map(|l| (l.x.to_bits(), l.y.to_bits(), l.z.to_bits())).hash(digest);
            p.normal.to_array().map(f32::to_bits).hash(digest);
            p.shadow.to_bits().hash(digest);
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let passes: u32 = std::env::args().nth(1).map_or(Ok(1), |s| s.parse())?;
    let all = std::env::args().nth(2).is_some_and(|a| a == "all");
    let mut digest = DefaultHasher::new();
    if all {
        let mut configs = Vec::new();
        for filter in FILTERS {
            for (test, bias) in [
                (DepthTest::Second, Bias::ZERO),
                (DepthTest::First, Bias::Range { lo: PlaneZ::ZERO, hi: PlaneZ::from_num(300) }),
            ] {
                for virtual_samples in [false, true] {
                    for normals in [Normals::Flat, Normals::Smooth] {
                        configs.push((ShadowConfig::new(test, bias, filter, true)?, virtual_samples, normals));
                    }
                }
            }
        }
        for (name, _) in BUNDLED {
            shade_scene(&Scene::bundled(name)?, &configs, passes, (320, 200), true, &mut digest)?;
        }
    } else {
        // A preset's name picks its filter instead of the 3×3 box.
        let named = std::env::args().nth(2).and_then(|n| n.parse::<umbra::core::shadow::Filter>().ok());
        let filter = named.unwrap_or(Filter::Box { size: 3 });
        let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, filter, true)?;
        shade_scene(
            &Scene::default_scene(),
            &[(shadow, true, Normals::Flat)],
            passes,
            (1920, 1080),
            false,
            &mut digest,
        )?;
    }
    println!("{passes} passes, digest {:016x}", digest.finish());
    Ok(())
}
