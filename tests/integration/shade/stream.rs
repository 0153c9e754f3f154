//! The camera pass streamed by tile equals the full-frame pass bit for bit
//! on every bundled scene, and the vertex cache's size changes no result.

use umbra::core::front::vertex::VertexCache;
use umbra::core::probe::Totals;
use umbra::core::shade::MapUnit;
use umbra::core::shadow::{Bias, DepthTest, Filter, ShadowConfig};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::base::maps::Tiling;
use umbra::sim::pass::camera::{CameraFrame, CameraOptions, map_view, streamed};
use umbra::sim::pass::light::{LightMaps, LightOptions};
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::BUNDLED;

use crate::common::camera_image;

/// Every bundled scene, at an image of whole tiles and at one whose edge
/// tiles are cut (70 × 45 of 16-pixel tiles), with second depth, virtual
/// samples and a 3×3 box: the streamed pass's pixels are the full-frame
/// pass's. Shading in tile order instead of row order would change no bit
/// either, so this also checks every pixel keeps its place: a tile shaded
/// at the wrong origin fails it (and did, before `shade_rect` offset its
/// pixels).
#[test]
fn streaming_by_tile_is_bit_identical_to_the_whole_frame() {
    let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 3 }, true).expect("valid");
    for (name, _) in BUNDLED {
        let scene = Scene::bundled(name).expect("bundled");
        let raster = RasterConfig::new(128, 128, 32, 8).expect("valid");
        let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
        let draws = scene.draws(scene.light().view_projection(), CullMode::None);
        let (maps, _) = LightMaps::draw::<D24, _>(config, &draws, LightOptions::default(), NoProbe).expect("renders");
        let view = map_view::<D24>(&maps, false).expect("sized");
        for (w, h, tile) in [(64, 48, 16), (70, 45, 16), (64, 64, 32)] {
            let whole = camera_image::<D24, _>(
                &mut CameraFrame::default(),
                &scene,
                &maps,
                (shadow, true),
                (w, h),
                &mut NoProbe,
            );
            let options = CameraOptions {
                width: w,
                height: h,
                shadow,
                virtual_samples: true,
                tiling: Tiling { tile, per_draw: false },
            };
            let mut totals = Totals::default();
            let tiles = streamed(&scene, &view, &MapUnit, &options, &mut totals).expect("streams");
            let differ = whole.pixels.iter().zip(&tiles.pixels).filter(|(a, b)| a != b).count();
            assert_eq!((tiles.pixels.len(), differ), (whole.pixels.len(), 0), "{name} at {w}×{h}, {tile}-pixel tiles");
            let covered = whole.pixels.iter().filter(|p| p.triangle != umbra::core::NO_TRIANGLE).count() as u64;
            assert_eq!(totals.pixels_shaded, covered, "{name}: every covered pixel shaded once");
        }
    }
}

/// A post-transform cache of no entry, of three, and of the default 256
/// give the same maps: the cache saves work, it decides nothing.
#[test]
fn the_vertex_cache_size_changes_no_result() {
    use umbra::core::front::setup::Setup;
    use umbra::core::raster::bin::Bin;
    use umbra::core::{LightBuffers, LightPass, TileState};
    let scene = Scene::bundled("double-torus").expect("bundled");
    let raster = RasterConfig::new(96, 96, 16, 8).expect("valid");
    let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    let run = |draw: &dyn Fn(&mut LightPass<'_, D24, Totals, 8>, &umbra::sim::pass::light::Draw<'_>)| {
        let (mut z1, mut z2) = (vec![0u32; 96 * 96], vec![0u32; 96 * 96]);
        let mut tiles = vec![TileState::cleared(0, 0); 36];
        let mut bins = vec![Bin::<8>::new(); 36];
        let mut setups = vec![Setup::EMPTY; 64];
        let buffers = LightBuffers {
            z1: &mut z1,
            z2: &mut z2,
            ids: &mut [],
            tiles: &mut tiles,
            bins: &mut bins,
            setups: &mut setups,
        };
        let mut pass = LightPass::new(cfg, buffers, Totals::default()).expect("sized");
        draws.iter().for_each(|d| draw(&mut pass, d));
        let totals = pass.finish();
        (z1, z2, totals.fragments)
    };
    let default = run(&|p, d| p.draw_mesh(d.positions, d.triangles, &d.transform, d.cull).expect("valid"));
    assert!(default.2 > 1000, "the scene draws");
    let none = run(&|p, d| {
        p.draw_mesh_cached(d.positions, d.triangles, &d.transform, d.cull, &mut VertexCache::<0>::new()).expect("valid")
    });
    let three = run(&|p, d| {
        p.draw_mesh_cached(d.positions, d.triangles, &d.transform, d.cull, &mut VertexCache::<3>::new()).expect("valid")
    });
    assert!(none == default && three == default, "a cache size changed the maps");
}
