//! The fast clear: a pass over the buffers the last pass of the same
//! configuration drew ([`LightPass::new_kept`]) clears only the tiles that
//! pass wrote, and makes the maps, ids, tile summaries and events a pass
//! into cleared buffers makes — in the core, and through the simulator's
//! kept frame, whose configuration may change between passes.

use proptest::prelude::*;
use umbra::core::front::setup::Setup;
use umbra::core::glam::{Mat4, Vec3, Vec4};
use umbra::core::probe::Totals;
use umbra::core::raster::bin::Bin;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, NoProbe};
use umbra::sim::pass::light::{DEFAULT_BIN_CAPACITY, Draw, LightFrame, LightMaps, LightOptions, render};
use umbra::sim::world::mesh::Mesh;

use crate::common::{Buffers, config, triangles};

/// A pass over `b`, started by `new` or `new_kept`, handed to `run`.
fn with_pass<F: DepthFormat, R>(
    b: &mut Buffers<F, 8>,
    cfg: LightPassConfig,
    kept: bool,
    run: impl FnOnce(LightPass<'_, F, Totals, 8>) -> R,
) -> R {
    let (mut bins, mut setups) = (vec![Bin::<8>::new(); b.tiles.len()], vec![Setup::EMPTY; 16]);
    let buffers = LightBuffers {
        z1: &mut b.z1,
        z2: &mut b.z2,
        ids: &mut b.ids,
        tiles: &mut b.tiles,
        bins: &mut bins,
        setups: &mut setups,
    };
    let start = if kept { LightPass::new_kept } else { LightPass::new };
    run(start(cfg, buffers, Totals::default()).expect("sized"))
}

/// Draw `tris` over `b`, started by `new` or `new_kept`, and finish.
fn pass<F: DepthFormat>(b: &mut Buffers<F, 8>, cfg: LightPassConfig, tris: &[[Vec4; 3]], kept: bool) -> Totals {
    with_pass(b, cfg, kept, |mut p| {
        tris.iter().for_each(|t| p.draw_clip(*t, CullMode::None));
        p.finish()
    })
}

/// Start a kept pass over `b`, draw half of `tris` and drop it unfinished.
fn abandon<F: DepthFormat>(b: &mut Buffers<F, 8>, cfg: LightPassConfig, tris: &[[Vec4; 3]]) {
    with_pass(b, cfg, true, |mut p| tris.iter().take(tris.len() / 2).for_each(|t| p.draw_clip(*t, CullMode::None)));
}

/// A pass over the buffers of a finished pass and of a pass dropped
/// unfinished equals a pass into new ones.
fn second_pass_is_fresh<F: DepthFormat>(
    first: &[[Vec4; 3]],
    second: &[[Vec4; 3]],
    unit: DepthUnit,
    ids: bool,
    tile: u32,
) -> Result<(), TestCaseError> {
    let cfg = config(64, tile, unit, true);
    let mut kept = Buffers::<F, 8>::new(&cfg, 16, ids);
    pass(&mut kept, cfg, first, false);
    // A kept pass dropped before its finish (a draw that failed) leaves
    // the clears it did not do pending for the next.
    abandon(&mut kept, cfg, first);
    let kept_totals = pass(&mut kept, cfg, second, true);
    let mut fresh = Buffers::<F, 8>::new(&cfg, 16, ids);
    let fresh_totals = pass(&mut fresh, cfg, second, false);
    prop_assert!(kept.z1 == fresh.z1, "z1 ({unit:?}, ids {ids}, tile {tile})");
    prop_assert!(kept.z2 == fresh.z2, "z2 ({unit:?}, tile {tile})");
    prop_assert_eq!(&kept.ids, &fresh.ids);
    prop_assert_eq!(&kept.tiles, &fresh.tiles);
    prop_assert_eq!(kept_totals, fresh_totals);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn a_kept_pass_clears_what_the_last_one_wrote(
        first in triangles(24),
        second in triangles(24),
        tile in prop::sample::select(vec![8u32, 16]),
    ) {
        second_pass_is_fresh::<D16>(&first, &second, DepthUnit::Dual, false, tile)?;
        second_pass_is_fresh::<D24>(&first, &second, DepthUnit::Single, false, tile)?;
        second_pass_is_fresh::<D24>(&first, &second, DepthUnit::Single, true, tile)?;
        // Nothing drawn the second time: every tile the first wrote is cleared.
        second_pass_is_fresh::<D24>(&first, &[], DepthUnit::Single, true, tile)?;
    }
}

/// The simulator's kept frame: passes of changing scenes and changing
/// configurations — one of the same texel and tile counts but another
/// layout among them — each equal a pass into new maps, serial and banded.
#[test]
fn the_kept_frame_equals_new_maps_whatever_came_before() {
    let boxes = Mesh::cuboid(Vec3::new(-0.6, -0.2, -0.6), Vec3::new(0.1, 0.5, 0.2));
    let ball = Mesh::sphere(Vec3::new(0.3, 0.1, 0.2), 0.45, 12, 16);
    let light = |eye: Vec3| {
        umbra::core::glam::camera::rh::proj::directx::perspective(1.1, 1.0, 1.0, 8.0)
            * umbra::core::glam::camera::rh::view::look_at_mat4(eye, Vec3::ZERO, Vec3::Y)
    };
    let draw = |m: &'static Mesh, transform: Mat4| Draw {
        positions: &m.positions,
        triangles: &m.triangles,
        transform,
        cull: CullMode::None,
    };
    let (boxes, ball): (&'static Mesh, &'static Mesh) = (Box::leak(Box::new(boxes)), Box::leak(Box::new(ball)));
    let cfg = |w: u32, h: u32, tile: u32, unit: DepthUnit| LightPassConfig {
        raster: umbra::core::RasterConfig::new(w, h, tile, 8).expect("valid"),
        unit,
        max_z_cull: true,
    };
    let passes = [
        (cfg(128, 64, 16, DepthUnit::Dual), vec![draw(boxes, light(Vec3::new(1.0, 3.0, 2.0)))]),
        (cfg(128, 64, 16, DepthUnit::Dual), vec![draw(ball, light(Vec3::new(-1.0, 3.0, 1.0)))]),
        // The same texels and tiles, laid out otherwise.
        (cfg(64, 128, 16, DepthUnit::Dual), vec![draw(boxes, light(Vec3::new(1.0, 2.0, -2.0)))]),
        (cfg(64, 128, 16, DepthUnit::Single), vec![draw(ball, light(Vec3::new(0.0, 3.0, 1.0)))]),
        (cfg(64, 128, 16, DepthUnit::Single), vec![]),
        (cfg(64, 128, 32, DepthUnit::Single), vec![draw(boxes, light(Vec3::new(2.0, 2.0, 2.0)))]),
    ];
    for options in [LightOptions::default(), LightOptions::BANDS] {
        let mut frame = LightFrame::<u32, DEFAULT_BIN_CAPACITY>::new();
        for (k, (cfg, draws)) in passes.iter().enumerate() {
            let (kept, _) =
                render::<D24, NoProbe, DEFAULT_BIN_CAPACITY>(&mut frame, *cfg, draws, options, NoProbe).expect("draws");
            let (fresh, _) = LightMaps::draw::<D24, NoProbe>(*cfg, draws, options, NoProbe).expect("draws");
            // The maps, and the tile summaries whole.
            assert!(*kept == fresh, "pass {k} (bands {}) differs from new maps", options.bands);
        }
    }
}

/// The camera pass's kept frame: its visibility pass clears only the
/// tiles the last one wrote, so a pass after other scenes, sizes and
/// tilings gives the pixels and ids of a pass into a new frame.
#[test]
fn the_kept_camera_frame_equals_a_new_one() {
    use umbra::core::shade::MapUnit;
    use umbra::core::shadow::{Bias, DepthTest, Filter, ShadowConfig};
    use umbra::sim::base::maps::Tiling;
    use umbra::sim::pass::camera::{CameraFrame, CameraOptions, map_view, render as camera};
    use umbra::sim::world::scene::Scene;

    let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 3 }, true).expect("valid");
    let options = |width, height, tile| CameraOptions {
        width,
        height,
        shadow,
        virtual_samples: true,
        tiling: Tiling { tile, ..Tiling::DEFAULT },
    };
    let scenes = ["table-and-sphere", "crowd", "thin"].map(|n| Scene::bundled(n).expect("bundled"));
    let runs =
        [(0, options(160, 96, 16)), (1, options(160, 96, 16)), (2, options(96, 160, 16)), (0, options(96, 160, 32))];
    let mut frame = CameraFrame::default();
    for (k, (scene, options)) in runs.iter().enumerate() {
        let scene = &scenes[*scene];
        let light = LightPassConfig {
            raster: umbra::core::RasterConfig::new(256, 256, 32, 8).expect("valid"),
            unit: DepthUnit::Dual,
            max_z_cull: true,
        };
        let draws = scene.draws(scene.light().view_projection(), CullMode::None);
        let (maps, _) =
            LightMaps::draw::<D24, NoProbe>(light, &draws, LightOptions::default(), NoProbe).expect("draws");
        let view = map_view::<D24>(&maps, false).expect("sized");
        camera(&mut frame, scene, &view, &MapUnit, options, &mut NoProbe).expect("renders");
        let mut fresh = CameraFrame::default();
        camera(&mut fresh, scene, &view, &MapUnit, options, &mut NoProbe).expect("renders");
        assert!(frame.ids() == fresh.ids(), "run {k}: the ids differ from a new frame's");
        assert!(frame.pixels == fresh.pixels, "run {k}: the pixels differ from a new frame's");
        assert!(fresh.ids().iter().any(|&i| i != umbra::core::NO_TRIANGLE), "run {k} sees its scene");
    }
}
