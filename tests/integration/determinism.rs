//! The same input gives the same bits: the light pass's maps and a whole
//! render (maps, camera pass, reference, metrics, event counts) are equal
//! run after run and on 1, 2 and all cores. (`reference.rs` checks the
//! reference alone across thread counts.)

use umbra::core::probe::Totals;
use umbra::core::shade::Shaded;
use umbra::core::shadow::Filter;
use umbra::core::{CullMode, DepthFormatKind, DepthUnit, LightPassConfig, RasterConfig};
use umbra::sim::Algorithm;
use umbra::sim::base::counters::Counters;
use umbra::sim::pass::light::RawMaps;
use umbra::sim::render::{Render, RenderConfig, TruthSource, render};
use umbra::sim::world::scene::Scene;

/// 1, 2 and every core of the machine (at least 3, so the pools differ).
fn thread_counts() -> [usize; 3] {
    let all = std::thread::available_parallelism().map_or(1, usize::from);
    [1, 2, all.max(3)]
}

fn on<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool").install(f)
}

/// Every output of a render as bits: floats by their bit patterns, so that
/// `-0.0` and `0.0` (or two NaNs) would not pass as equal.
fn bits(r: &Render) -> (RawMaps, Vec<u64>, Vec<u64>, Vec<u64>, [Totals; 2]) {
    let shaded = |s: &Shaded| {
        let [x, y, z] = s.normal.to_array().map(f32::to_bits);
        let light = s.light.map_or([0; 3], |l| [l.x.to_bits() as u64, l.y.to_bits() as u64, l.z.to_bits() as u64]);
        [u64::from(s.triangle), u64::from(s.shadow.to_bits()), u64::from(x), u64::from(y), u64::from(z)]
            .into_iter()
            .chain(light)
            .collect::<Vec<_>>()
    };
    let truth = r
        .truth
        .iter()
        .flat_map(|t| t.map_or([u64::MAX; 3], |t| [u64::from(t.faces_light), u64::from(t.lit), t.visibility.to_bits()]))
        .collect();
    let m = &r.metrics;
    let metrics = vec![
        m.evaluated,
        m.false_shadow,
        m.false_light,
        m.false_shadow_percent.to_bits(),
        m.false_light_percent.to_bits(),
        m.misclassified_percent.to_bits(),
        m.mean_abs_error.to_bits(),
    ];
    let events = [r.light_events.totals, r.camera_events.totals];
    (r.maps.clone(), r.image.pixels.iter().flat_map(shaded).collect(), truth, metrics, events)
}

/// The light pass of a bundled scene in every format and unit: the same
/// maps twice in a row and in pools of 1, 2 and all threads.
#[test]
fn light_maps_are_the_same_on_any_thread_count() {
    let scene = Scene::bundled("double-torus").expect("bundled");
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    for format in [DepthFormatKind::D16, DepthFormatKind::D24, DepthFormatKind::F32] {
        for unit in [DepthUnit::Single, DepthUnit::Dual] {
            let cfg =
                LightPassConfig { raster: RasterConfig::new(160, 96, 16, 8).expect("valid"), unit, max_z_cull: true };
            let pass = || RawMaps::render(cfg, format, &draws, Counters::new(&cfg.raster)).expect("renders").0;
            let first = pass();
            assert_eq!(first, pass(), "{format:?} {unit:?}: a second run differs");
            for threads in thread_counts() {
                assert_eq!(first, on(threads, pass), "{format:?} {unit:?} on {threads} threads");
            }
            let far = umbra::sim::base::maps::raw_far(format);
            assert!(first.maps.z1.iter().any(|&t| t != far), "the scene is in view of the light");
        }
    }
}

/// A whole render of the default scene at a small size, on 1, 2 and all
/// threads and twice on one: every output equal to the bit.
#[test]
fn a_render_is_the_same_on_any_thread_count() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let cfg = RenderConfig {
        algorithm: Algorithm::Second,
        format: DepthFormatKind::D24,
        map_size: 128,
        filter: Filter::Bilinear,
        bias: 0.0,
        virtual_samples: true,
        width: 80,
        height: 45,
        reference_rays: 2,
        ..RenderConfig::DEFAULT
    };
    let hidden = indicatif::ProgressBar::hidden();
    let go = || {
        bits(
            &cfg.check(&scene, &umbra::sim::input::limits::Limits::DEFAULT)
                .and_then(|job| render(&job, TruthSource::Build(&hidden)))
                .expect("renders"),
        )
    };
    let first = go();
    assert_eq!(first, go(), "a second run differs");
    for threads in thread_counts() {
        assert_eq!(first, on(threads, go), "on {threads} threads");
    }
    assert!(first.3[0] > 500, "most of the image is evaluated: {}", first.3[0]);
}

/// Every tile's stored bounds of `z1` and `z2` (not how often it was
/// stored, which depends on the flush schedule).
fn tile_bounds<T: Copy>(m: &umbra::sim::pass::light::LightMaps<T>) -> Vec<(T, T, T, T)> {
    m.tiles.iter().map(|t| (t.z1_min, t.z1_max, t.z2_min, t.z2_max)).collect()
}

/// The light pass on bands of tile rows in parallel gives exactly the maps
/// of one pass over the whole target — every texel of `z1` and `z2` and
/// every tile's bounds — for scenes under both kinds of light, 16- and
/// 24-bit, single and dual, on 1, 2 and more threads (so 1, 2 and more
/// bands, bands of unequal height and a partial last tile row included).
#[test]
fn banded_and_per_draw_light_passes_equal_the_whole_pass() {
    use umbra::core::{D16, D24, DepthFormat};
    use umbra::sim::pass::light::{LightMaps, LightOptions};
    fn check<F: DepthFormat>(scene: &Scene, side: u32, tile: u32, unit: DepthUnit) {
        let raster = RasterConfig::new(side, side - 8, tile, 8).expect("valid");
        assert!(raster.window(0, tile / 2, side, tile).is_err(), "a window starts on a tile boundary");
        assert!(raster.window(0, tile, side, side).is_err(), "a window lies inside the target");
        let config = LightPassConfig { raster, unit, max_z_cull: true };
        let draws = scene.draws(scene.light().view_projection(), CullMode::None);
        let (whole, _) =
            LightMaps::draw::<F, _>(config, &draws, LightOptions::default(), umbra::core::NoProbe).expect("renders");
        for threads in [1, 2, 3, 5] {
            let banded = on(threads, || {
                LightMaps::draw::<F, _>(config, &draws, LightOptions::BANDS, umbra::core::NoProbe).map(|(m, _)| m)
            })
            .expect("renders");
            assert!(
                banded.z1 == whole.z1 && banded.z2 == whole.z2,
                "{}: texels differ on {threads} threads",
                scene.name
            );
            assert!(
                tile_bounds(&banded) == tile_bounds(&whole),
                "{}: tile bounds differ on {threads} threads",
                scene.name
            );
        }
        // Drawn as an immediate-mode machine draws, each draw finished
        // before the next: the same texels and bounds, more flushes.
        let per_draw = LightOptions { per_draw: true, ..LightOptions::default() };
        let (flushed, counted) =
            LightMaps::draw::<F, _>(config, &draws, per_draw, umbra::core::probe::Totals::default()).expect("renders");
        assert!(flushed.z1 == whole.z1 && flushed.z2 == whole.z2, "{}: texels differ per draw", scene.name);
        assert!(tile_bounds(&flushed) == tile_bounds(&whole), "{}: tile bounds differ per draw", scene.name);
        assert!(counted.flushes_draw > 0, "{}: flushed per draw", scene.name);
    }
    for name in ["table-and-sphere", "weiskopf-l", "crowd"] {
        let scene = Scene::bundled(name).expect("bundled");
        check::<D16>(&scene, 200, 16, DepthUnit::Single);
        check::<D24>(&scene, 256, 32, DepthUnit::Dual);
    }
}

/// A pass no probe watches may flush on its own schedule (a setup store
/// that stays in cache: 4096 setups here, for 10 000 triangles), and still
/// draws exactly the texels and tile bounds of a counted pass, whose store
/// holds the whole scene (only the count of stores per tile differs).
#[test]
fn an_unwatched_pass_draws_the_maps_of_a_counted_one() {
    use umbra::core::D24;
    use umbra::core::glam::Vec3;
    use umbra::sim::base::counters::Counters;
    use umbra::sim::pass::light::{Draw, LightMaps, LightOptions};
    use umbra::sim::world::mesh::Mesh;
    use umbra::sim::world::scene::Perspective;
    let mesh = Mesh::torus(Vec3::ZERO, 1.0, 0.4, 100, 50);
    assert_eq!(mesh.triangles.len(), 10_000);
    let light = Perspective {
        position: Vec3::new(0.0, 2.2, 2.6),
        target: Vec3::ZERO,
        fov_degrees: 55.0,
        near: 1.0,
        far: 8.0,
        up: Vec3::Y,
    };
    let draw = Draw {
        positions: &mesh.positions,
        triangles: &mesh.triangles,
        transform: light.view_projection(),
        cull: CullMode::None,
    };
    for unit in [DepthUnit::Single, DepthUnit::Dual] {
        let raster = RasterConfig::new(96, 64, 16, 8).expect("valid");
        let config = LightPassConfig { raster, unit, max_z_cull: true };
        let (unwatched, _) =
            LightMaps::draw::<D24, _>(config, &[draw], LightOptions::default(), umbra::core::NoProbe).expect("renders");
        let (counted, counters) =
            LightMaps::draw::<D24, _>(config, &[draw], LightOptions::default(), Counters::new(&raster))
                .expect("renders");
        assert_eq!(counters.totals.flushes_setup_full, 0, "the counted store holds the scene");
        assert!(unwatched.z1 == counted.z1 && unwatched.z2 == counted.z2, "{unit:?}: the texels differ");
        assert!(tile_bounds(&unwatched) == tile_bounds(&counted), "{unit:?}: the tile bounds differ");
    }
}

/// A camera frame kept between passes draws what a new one does: the same
/// pixels and the same counted events, after passes of other scenes at
/// other sizes have left their buffers in it.
#[test]
fn a_reused_camera_frame_draws_what_a_new_one_does() {
    use umbra::core::shadow::{Bias, DepthTest, ShadowConfig};
    use umbra::core::{D24, NoProbe};
    use umbra::sim::pass::camera::CameraFrame;
    use umbra::sim::pass::light::{LightMaps, LightOptions};

    use crate::common::camera_image;
    let shadow = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 3 }, true).expect("valid");
    let mut frame = CameraFrame::default();
    for (name, (w, h)) in [
        ("table-and-sphere", (96, 64)),
        ("double-torus", (40, 30)),
        ("table-and-sphere", (96, 64)),
        ("table-and-sphere", (33, 71)),
    ] {
        let scene = Scene::bundled(name).expect("bundled");
        let raster = RasterConfig::new(128, 128, 32, 8).expect("valid");
        let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
        let draws = scene.draws(scene.light().view_projection(), CullMode::None);
        let (maps, _) = LightMaps::draw::<D24, _>(config, &draws, LightOptions::default(), NoProbe).expect("renders");
        let target = RasterConfig::new(w, h, 32, 8).expect("valid");
        let (mut new, mut reused) = (Counters::new(&target), Counters::new(&target));
        let image =
            camera_image::<D24, _>(&mut CameraFrame::default(), &scene, &maps, (shadow, true), (w, h), &mut new);
        let kept = camera_image::<D24, _>(&mut frame, &scene, &maps, (shadow, true), (w, h), &mut reused);
        assert_eq!(kept.pixels, image.pixels, "{name} at {w}×{h}");
        assert_eq!(reused.totals, new.totals, "{name} at {w}×{h}");
        assert!(image.pixels.iter().any(|p| p.light.is_some()), "{name}: something is shaded");
    }
}

/// A light frame kept between passes draws what new buffers do, whole and
/// banded in turn: the same maps and tile states, after passes of other
/// scenes, sizes, units and the other pass have left their buffers in it.
#[test]
fn a_reused_light_frame_draws_what_new_buffers_do() {
    use umbra::core::{D16, D24, DepthFormat, NoProbe};
    use umbra::sim::pass::light::{LightFrame, LightMaps, LightOptions, render};
    let mut frame16: LightFrame<u16> = LightFrame::new();
    let mut frame24: LightFrame<u32> = LightFrame::new();
    let passes = [("table-and-sphere", 128, DepthUnit::Dual, true), ("double-torus", 96, DepthUnit::Single, false)];
    for (name, side, unit, cull) in passes.into_iter().cycle().take(5) {
        let scene = Scene::bundled(name).expect("bundled");
        let raster = RasterConfig::new(side, side + 32, 32, 8).expect("valid");
        let config = LightPassConfig { raster, unit, max_z_cull: cull };
        let draws = scene.draws(scene.light().view_projection(), CullMode::None);
        let (new, _) = LightMaps::draw::<D24, _>(config, &draws, LightOptions::default(), NoProbe).expect("renders");
        assert!(new.z1.iter().any(|&z| z < D24::FAR), "{name}: something is drawn");
        assert_eq!(
            render::<D24, _, _>(&mut frame24, config, &draws, LightOptions::default(), NoProbe).expect("renders").0,
            &new,
            "{name}"
        );
        let banded = on(2, || {
            render::<D24, _, _>(&mut frame24, config, &draws, LightOptions::BANDS, umbra::core::NoProbe)
                .map(|(m, _)| m)
                .cloned()
        })
        .expect("renders");
        assert_eq!(unstored(&banded), unstored(&new), "{name}, banded into the whole pass's frame");
        let new = on(2, || {
            LightMaps::draw::<D16, _>(config, &draws, LightOptions::BANDS, umbra::core::NoProbe).map(|(m, _)| m)
        })
        .expect("renders");
        let banded = on(2, || {
            render::<D16, _, _>(&mut frame16, config, &draws, LightOptions::BANDS, umbra::core::NoProbe)
                .map(|(m, _)| m)
                .cloned()
        })
        .expect("renders");
        assert_eq!(banded, new, "{name}, banded");
        let whole =
            render::<D16, _, _>(&mut frame16, config, &draws, LightOptions::default(), NoProbe).expect("renders").0;
        assert_eq!(unstored(whole), unstored(&new), "{name}, whole into the banded pass's frame");
    }
}

/// `m` with each tile's count of stores cut to whether it was stored: a
/// band flushes its own setup store, so the count follows the band's
/// schedule; everything else is the serial pass's.
fn unstored<T: Clone>(m: &umbra::sim::pass::light::LightMaps<T>) -> umbra::sim::pass::light::LightMaps<T> {
    let mut m = m.clone();
    m.tiles.iter_mut().for_each(|t| t.stores = t.stores.min(1));
    m
}
