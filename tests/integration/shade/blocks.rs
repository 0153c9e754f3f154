//! The shading unit by blocks: a pass that keeps only the shadow fraction
//! and watches no events settles 8×8 and 4×4 blocks of one flat triangle
//! at once where the shadow unit can (images whose sides are no multiple
//! of a block's, so that blocks are cut at their edges). Its fractions are the pixel-by-pixel
//! unit's, bit for bit, on every bundled scene, depth test and box.

use umbra::core::shade::{MapUnit, MapUnitWith, ShadowUnit};
use umbra::core::shadow::{Bias, BoxFilter, DepthTest, Filter, Shadow, ShadowConfig};
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::base::maps::Tiling;
use umbra::sim::pass::camera::{CameraFrame, CameraOptions, map_view, render, render_into};
use umbra::sim::pass::light::{LightMaps, LightOptions};
use umbra::sim::world::scene::Scene;

/// The fractions by blocks (`render_into`, no probe) and the whole
/// results' fractions pixel by pixel, for one scene and configuration;
/// and how many pixels are covered and shadowed.
fn both<F: DepthFormat, U: ShadowUnit<F>>(
    scene: &Scene,
    map: u32,
    unit: &U,
    options: &CameraOptions,
) -> (Vec<Shadow>, Vec<Shadow>) {
    let config = LightPassConfig {
        raster: RasterConfig::new(map, map, 32, 8).expect("valid"),
        unit: DepthUnit::Dual,
        max_z_cull: true,
    };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    let (maps, _) = LightMaps::draw::<F, NoProbe>(config, &draws, LightOptions::default(), NoProbe).expect("draws");
    let view = map_view::<F>(&maps, false).expect("sized");
    let mut frame = CameraFrame::default();
    render(&mut frame, scene, &view, unit, options, &mut NoProbe).expect("renders");
    let whole: Vec<Shadow> = frame.pixels.iter().map(|p| p.shadow).collect();
    let mut fractions = Vec::new();
    render_into(&mut frame, scene, &view, unit, options, &mut NoProbe, &mut fractions).expect("renders");
    (whole, fractions)
}

#[test]
fn blocks_give_the_pixel_units_fractions() {
    let mut shadowed = 0;
    for name in ["table-and-sphere", "crowd", "grazing", "thin", "weiskopf-l", "factory"] {
        let scene = Scene::bundled(name).expect("bundled");
        for (test, bias) in [
            (DepthTest::Second, Bias::ZERO),
            // At bias 0 a flat receiver's depth is its own stored depth:
            // the comparisons that settle blocks meet their boundary.
            (DepthTest::First, Bias::ZERO),
            (DepthTest::First, Bias::Constant(D24::plane_z(0.0004))),
            (DepthTest::Midpoint, Bias::ZERO),
            (
                DepthTest::Dual { offset: D24::plane_z(0.002) },
                Bias::Range { lo: D24::plane_z(0.0), hi: D24::plane_z(0.0008) },
            ),
        ] {
            for (size, virtual_samples) in [(2, true), (3, true), (1, false), (5, false)] {
                let shadow = ShadowConfig::new(test, bias, Filter::Box { size }, true).expect("valid");
                let options =
                    CameraOptions { width: 203, height: 117, shadow, virtual_samples, tiling: Tiling::DEFAULT };
                let (whole, fractions) = both::<D24, _>(&scene, 256, &MapUnit, &options);
                assert!(whole == fractions, "{name}: {test:?}, box {size}, virtual samples {virtual_samples}");
                shadowed += whole.iter().filter(|&&s| s == Shadow::ONE).count();
            }
        }
        // The unit built with the box alone settles blocks too.
        let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 2 }, true).expect("valid");
        let options = CameraOptions { width: 157, height: 94, shadow, virtual_samples: true, tiling: Tiling::DEFAULT };
        let (whole, fractions) = both::<D16, _>(&scene, 128, &MapUnitWith::<BoxFilter>::new(), &options);
        assert!(whole == fractions, "{name}: the box-only unit");
    }
    assert!(shadowed > 10_000, "the scenes cast shadows: {shadowed} shadowed pixels");
}
