//! The camera pass end to end: visibility, projective interpolation into
//! light space, and the shadow unit with virtual samples.

use proptest::prelude::*;
use umbra::core::glam::{Mat4, Vec3, Vec4};
use umbra::core::grid::TileRect;
use umbra::core::probe::Probe;
use umbra::core::probe::Totals;
use umbra::core::shade::{
    MapUnit, MapUnitWith, Normals, SceneTriangle, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, shade, shade_rect,
    shade_with,
};
use umbra::core::shadow::{Bias, BoxFilter, DepthTest, Filter, Jitter, MapCoord, MapView, Shadow, ShadowConfig};
use umbra::core::{ConfigError, CullMode, D16, D24, DepthFormat, DepthUnit, F32, NO_TRIANGLE, NoProbe};

use crate::common::{config, run, run_visibility};

const CAMERA: u32 = 64;

fn perspective(eye: Vec3, target: Vec3, fov: f32, near: f32, far: f32) -> Mat4 {
    let up = if (target - eye).normalize().cross(Vec3::Y).length() < 1e-3 { Vec3::Z } else { Vec3::Y };
    umbra::core::glam::camera::rh::proj::directx::perspective(fov, 1.0, near, far)
        * umbra::core::glam::camera::rh::view::look_at_mat4(eye, target, up)
}

fn camera() -> Mat4 {
    perspective(Vec3::new(0.3, 2.5, 2.5), Vec3::ZERO, 0.9, 0.5, 10.0)
}

/// Triangles with flat normals, and a light pass of them drawn `sides` times
/// (twice, with both windings, makes every surface two-sided).
struct Scene {
    tris: Vec<SceneTriangle>,
}

impl Scene {
    fn add(&mut self, a: Vec3, b: Vec3, c: Vec3) {
        let n = (b - a).cross(c - a).normalize();
        self.tris.push(SceneTriangle { positions: [a, b, c], normals: [n; 3] });
    }

    fn cuboid(&mut self, lo: Vec3, hi: Vec3) {
        let m = umbra::sim::world::mesh::Mesh::cuboid(lo, hi);
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            self.add(a, b, c);
        }
    }

    fn clip(&self, m: &Mat4, two_sided: bool) -> Vec<[Vec4; 3]> {
        let mut out: Vec<[Vec4; 3]> = self.tris.iter().map(|t| t.positions.map(|p| *m * p.extend(1.0))).collect();
        if two_sided {
            out.extend(
                self.tris.iter().map(|t| [t.positions[0], t.positions[2], t.positions[1]].map(|p| *m * p.extend(1.0))),
            );
        }
        out
    }
}

/// Render the dual map under `light`, the camera's visibility, and shade.
fn render<F: DepthFormat, P: Probe>(
    scene: &Scene,
    light: Mat4,
    map_size: u32,
    shadow_cfg: ShadowConfig,
    normals: Normals,
    probe: &mut P,
) -> Vec<Shaded> {
    let cfg = config(map_size, 16, DepthUnit::Dual, true);
    let (maps, _) = run::<F, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
    let view = MapView::<F>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let cam = camera_config(light, shadow_cfg, true, normals);
    let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
    let source = |id: u32| scene.tris.get(id as usize).copied();
    shade(&cam, &ids, &view, &source, &mut out, probe).expect("sized");
    out
}

/// The camera of these tests, looking at the origin, shading with `shadow`.
fn camera_config(light: Mat4, shadow: ShadowConfig, virtual_samples: bool, normals: Normals) -> ShadeConfig {
    ShadeConfig { camera: camera(), light, width: CAMERA, height: CAMERA, shadow, virtual_samples, normals, seed: 7 }
}

fn filters() -> [Filter; 4] {
    [Filter::Point, Filter::Bilinear, Filter::Box { size: 3 }, Filter::Jittered(Jitter::REEVES)]
}

fn second(filter: Filter) -> ShadowConfig {
    ShadowConfig::new(DepthTest::Second, Bias::ZERO, filter, true).expect("valid")
}

/// A direction on the unit sphere from two angles.
fn direction(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Wang & Molnar's claim: a planar receiver needs no bias. A lone plane
    /// (one large two-sided triangle, so it is its own second depth) lit
    /// from any direction: second depth with virtual samples at bias 0
    /// shadows no pixel, for every map size, precision and filter. Without
    /// virtual samples the same set-up self-shadows.
    #[test]
    fn a_lone_plane_never_shadows_itself(theta in 0.1f32..1.4, phi in 0.0f32..std::f32::consts::TAU, below in any::<bool>()) {
        let mut scene = Scene { tris: Vec::new() };
        scene.add(Vec3::new(-4.0, 0.0, 3.0), Vec3::new(4.0, 0.0, 3.0), Vec3::new(0.0, 0.0, -5.0));
        let d = direction(theta, phi) * if below { -1.0 } else { 1.0 };
        let light = perspective(d * 6.0, Vec3::ZERO, 1.6, 1.0, 20.0);
        let mut counts = Totals::default();
        for size in [64, 128, 256] {
            for filter in filters() {
                for (name, out) in [
                    ("d16", render::<D16, _>(&scene, light, size, second(filter), Normals::Flat, &mut counts)),
                    ("d24", render::<D24, _>(&scene, light, size, second(filter), Normals::Flat, &mut counts)),
                    ("f32", render::<F32, _>(&scene, light, size, second(filter), Normals::Flat, &mut counts)),
                ] {
                    let shadowed = out.iter().filter(|s| s.triangle != NO_TRIANGLE && s.shadow > Shadow::ZERO).count();
                    prop_assert_eq!(shadowed, 0, "{} map {}² {:?}", name, size, filter);
                    prop_assert!(out.iter().filter(|s| s.triangle == 0).count() > 1000, "the plane fills the view");
                }
            }
        }
        prop_assert!(counts.tangent_setups > 0, "some pixels needed virtual samples");
    }
}

/// The same plane without virtual samples shadows itself (the comparison
/// the virtual samples exist for); and a plane entirely behind a solid box
/// is entirely shadowed, for every filter.
#[test]
fn acne_without_virtual_samples_and_a_plane_behind_a_box() {
    let mut scene = Scene { tris: Vec::new() };
    scene.add(Vec3::new(-4.0, 0.0, 3.0), Vec3::new(4.0, 0.0, 3.0), Vec3::new(0.0, 0.0, -5.0));
    let light = perspective(Vec3::new(2.0, 3.0, 1.0), Vec3::ZERO, 1.6, 1.0, 20.0);
    let cfg = config(128, 16, DepthUnit::Dual, true);
    let (maps, _) = run::<D24, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
    let view = MapView::<D24>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let cam = camera_config(light, second(Filter::Box { size: 3 }), false, Normals::Flat);
    let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
    let source = |id: u32| scene.tris.get(id as usize).copied();
    shade(&cam, &ids, &view, &source, &mut out, &mut NoProbe).expect("sized");
    let acne = out.iter().filter(|s| s.triangle == 0 && s.shadow > Shadow::ZERO).count();
    assert!(acne > 500, "ordinary second depth at bias 0 on its own surface: {acne} pixels shadowed");

    // A solid wall between a low light and the plane: every ray from the
    // light to the plane passes through it (the light is no higher than the
    // wall's top), and the camera sees the plane past the wall's end.
    let mut scene = Scene { tris: Vec::new() };
    scene.add(Vec3::new(-1.0, 0.0, 0.8), Vec3::new(1.0, 0.0, 0.8), Vec3::new(0.0, 0.0, -1.2));
    scene.cuboid(Vec3::new(-2.5, -0.5, -3.0), Vec3::new(-2.0, 3.0, 3.0));
    let light = perspective(Vec3::new(-6.0, 3.0, 0.0), Vec3::ZERO, 1.2, 1.0, 20.0);
    for filter in filters() {
        let mut counts = Totals::default();
        let out = render::<D24, _>(&scene, light, 128, second(filter), Normals::Flat, &mut counts);
        let plane: Vec<&Shaded> = out.iter().filter(|s| s.triangle == 0).collect();
        assert!(!plane.is_empty());
        assert!(plane.iter().all(|s| s.shadow == Shadow::ONE), "{filter:?}");
    }
}

/// Culling lookups by the tiles' bounds gives exactly the verdicts of the
/// unculled camera pass, with flat and smooth normals, and skips lookups.
#[test]
fn culled_camera_pass_equals_unculled() {
    let mut scene = Scene { tris: Vec::new() };
    scene.add(Vec3::new(-4.0, 0.0, 3.0), Vec3::new(4.0, 0.0, 3.0), Vec3::new(0.0, 0.0, -5.0));
    scene.cuboid(Vec3::new(-0.5, 0.3, -0.5), Vec3::new(0.5, 0.9, 0.2));
    scene.cuboid(Vec3::new(0.6, 0.0, 0.4), Vec3::new(1.0, 1.2, 0.8));
    let light = perspective(Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, 1.4, 1.0, 20.0);
    for normals in [Normals::Flat, Normals::Smooth] {
        for filter in filters() {
            for test in [
                DepthTest::First,
                DepthTest::Second,
                DepthTest::Midpoint,
                DepthTest::Dual { offset: D24::plane_z(0.01) },
            ] {
                let on = ShadowConfig::new(test, Bias::Constant(D24::plane_z(0.0005)), filter, true).expect("valid");
                let off = on.with_cull_lookups(false);
                let mut counts = Totals::default();
                let culled = render::<D24, _>(&scene, light, 128, on, normals, &mut counts);
                let plain = render::<D24, _>(&scene, light, 128, off, normals, &mut NoProbe);
                assert_eq!(culled, plain, "{normals:?} {filter:?} {test:?}");
                assert!(counts.lookups_culled > 0, "{normals:?} {filter:?} {test:?}: nothing culled");
                assert!(culled.iter().any(|s| s.shadow == Shadow::ONE), "the boxes cast shadows");
                assert!(culled.iter().all(|s| s.shadow <= Shadow::ONE));
            }
        }
    }
}

/// A floor and six boxes of rising heights in a row.
fn row_of_boxes() -> Scene {
    let mut scene = Scene { tris: Vec::new() };
    scene.add(Vec3::new(-4.0, 0.0, 3.0), Vec3::new(4.0, 0.0, 3.0), Vec3::new(0.0, 0.0, -5.0));
    for i in 0..6u8 {
        let x = f32::from(i) * 0.35 - 1.0;
        scene.cuboid(Vec3::new(x, 0.0, -0.6), Vec3::new(x + 0.2, 0.4 + f32::from(i) * 0.1, 0.6));
    }
    scene
}

/// A shadow unit built with the box filter alone shades as the unit
/// built with every filter, pixel and event alike, for the configurations
/// it has; it refuses the others, naming what it lacks, before it shades.
#[test]
fn a_box_only_unit_shades_as_the_whole_unit_and_refuses_the_rest() {
    let scene = row_of_boxes();
    let light = perspective(Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, 1.4, 1.0, 20.0);
    let cfg = config(128, 16, DepthUnit::Dual, true);
    let (maps, _) = run::<D16, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
    let view = MapView::<D16>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let source = |id: u32| scene.tris.get(id as usize).copied();
    let shade_by = |cam: &ShadeConfig, boxed: bool| {
        let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
        let mut totals = Totals::default();
        let r = if boxed {
            shade_with(
                &ShadeInputs { cfg: cam, map: &view, scene: &source, unit: &MapUnitWith::<BoxFilter>::new() },
                &ids,
                &mut out,
                &mut [],
                &mut totals,
            )
        } else {
            shade_with(
                &ShadeInputs { cfg: cam, map: &view, scene: &source, unit: &MapUnit },
                &ids,
                &mut out,
                &mut [],
                &mut totals,
            )
        };
        r.map(|()| (out, totals))
    };
    for size in [1, 2, 3] {
        for test in [DepthTest::First, DepthTest::Second] {
            for virtual_samples in [false, true] {
                let bias = if test == DepthTest::First { Bias::Constant(D16::plane_z(0.002)) } else { Bias::ZERO };
                let shadow = ShadowConfig::new(test, bias, Filter::Box { size }, true).expect("valid");
                let cam = camera_config(light, shadow, virtual_samples, Normals::Flat);
                let (whole, boxed) = (shade_by(&cam, false).unwrap(), shade_by(&cam, true).unwrap());
                assert!(whole.0.iter().any(|p| p.shadow == Shadow::ONE), "the boxes cast shadows");
                assert!(whole == boxed, "box {size}, {test:?}, virtual samples {virtual_samples}");
            }
        }
    }
    let refused = |shadow: ShadowConfig, normals: Normals, missing: &'static str| {
        let cam = camera_config(light, shadow, true, normals);
        assert_eq!(shade_by(&cam, true).map(drop), Err(ConfigError::ShadowNotBuilt { missing }));
        assert!(shade_by(&cam, false).is_ok(), "the whole unit takes {missing}");
    };
    refused(second(Filter::Point), Normals::Flat, "the point filter");
    refused(second(Filter::Bilinear), Normals::Flat, "the bilinear filter");
    refused(second(Filter::Jittered(Jitter::REEVES)), Normals::Flat, "the jittered filter");
    let range = ShadowConfig::new(
        DepthTest::First,
        Bias::Range { lo: D16::plane_z(0.0), hi: D16::plane_z(0.01) },
        Filter::Box { size: 2 },
        true,
    )
    .unwrap();
    refused(range, Normals::Flat, "a bias range");
    refused(second(Filter::Box { size: 2 }), Normals::Smooth, "tangent planes from smooth normals");
}

/// A pass that keeps only each pixel's shadow fraction writes the
/// fractions the whole results hold, and reports the same events.
#[test]
fn the_fraction_alone_is_the_whole_results_fraction() {
    let scene = row_of_boxes();
    let light = perspective(Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, 1.4, 1.0, 20.0);
    let cfg = config(128, 16, DepthUnit::Dual, true);
    let (maps, _) = run::<D24, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
    let view = MapView::<D24>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let source = |id: u32| scene.tris.get(id as usize).copied();
    for filter in filters() {
        let cam = camera_config(light, second(filter), true, Normals::Flat);
        let n = (CAMERA * CAMERA) as usize;
        let (mut whole, mut fractions) = (vec![Shaded::BACKGROUND; n], vec![Shadow::ONE; n]);
        let (mut a, mut b) = (Totals::default(), Totals::default());
        let inputs = ShadeInputs { cfg: &cam, map: &view, scene: &source, unit: &MapUnit };
        shade_with(&inputs, &ids, &mut whole, &mut [], &mut a).expect("sized");
        shade_with(&inputs, &ids, &mut fractions, &mut [], &mut b).expect("sized");
        assert!(whole.iter().any(|p| p.shadow == Shadow::ONE) && whole.iter().any(|p| p.shadow == Shadow::ZERO));
        assert!(whole.iter().map(|p| p.shadow).eq(fractions.iter().copied()), "{filter:?}");
        assert_eq!(a, b, "{filter:?}");
    }
}

/// Blocks of pixels at the map's edge: under a light whose map covers only
/// part of the boxes' shadows (outside it is lit), the fractions by
/// blocks (a fraction-only pass with no probe) are the pixel unit's, over
/// the whole image and over rectangles of it.
#[test]
fn blocks_at_the_maps_edge_give_the_pixel_units_fractions() {
    let scene = row_of_boxes();
    for fov in [0.35f32, 0.5, 0.7] {
        let light = perspective(Vec3::new(0.6, 4.0, 1.0), Vec3::new(-0.3, 0.0, 0.0), fov, 1.0, 20.0);
        let cfg = config(128, 16, DepthUnit::Dual, true);
        let (maps, _) = run::<D24, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
        let view = MapView::<D24>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
        let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
        let source = |id: u32| scene.tris.get(id as usize).copied();
        for size in [2, 3] {
            let cam = camera_config(light, second(Filter::Box { size }), true, Normals::Flat);
            let n = (CAMERA * CAMERA) as usize;
            let (mut whole, mut fractions) = (vec![Shaded::BACKGROUND; n], vec![Shadow::ONE; n]);
            let inputs = ShadeInputs { cfg: &cam, map: &view, scene: &source, unit: &MapUnit };
            shade_with(&inputs, &ids, &mut whole, &mut [], &mut NoProbe).expect("sized");
            shade_with(&inputs, &ids, &mut fractions, &mut [], &mut NoProbe).expect("sized");
            let outside = whole
                .iter()
                .filter(|p| p.light.is_some_and(|l| l.x < MapCoord::ZERO || l.x.to_num::<u32>() >= 128))
                .count();
            assert!(
                outside > 100 && whole.iter().any(|p| p.shadow == Shadow::ONE),
                "fov {fov}: the map's edge crosses the image"
            );
            assert!(whole.iter().map(|p| p.shadow).eq(fractions.iter().copied()), "fov {fov}, box {size}");
            // By rectangles whose sides are no multiple of a block's: the
            // blocks cut at each rectangle's edges give the same fractions.
            let mut by_rects = vec![Shadow::ONE; n];
            for (y0, x0) in (0..CAMERA).step_by(11).flat_map(|y| (0..CAMERA).step_by(13).map(move |x| (y, x))) {
                let rect = TileRect { x0, y0, x1: (x0 + 13).min(CAMERA), y1: (y0 + 11).min(CAMERA) };
                let at = |x: u32, y: u32| (y * CAMERA + x) as usize;
                let rows = || (rect.y0..rect.y1).map(|y| at(rect.x0, y)..at(rect.x1, y));
                let rect_ids: Vec<u32> = rows().flat_map(|r| ids[r].to_vec()).collect();
                let mut out = vec![Shadow::ONE; rect_ids.len()];
                shade_rect(
                    &ShadeInputs { cfg: &cam, map: &view, scene: &source, unit: &MapUnit },
                    rect,
                    &rect_ids,
                    &mut out,
                    &mut [],
                    &mut NoProbe,
                )
                .expect("sized");
                for (r, chunk) in rows().zip(out.chunks(rect.width() as usize)) {
                    by_rects[r].copy_from_slice(chunk);
                }
            }
            assert!(
                whole.iter().map(|p| p.shadow).eq(by_rects.iter().copied()),
                "fov {fov}, box {size}, by rectangles"
            );
        }
    }
}

/// The shading unit's setup store only saves work: with no store (every
/// run of pixels set up anew), one entry, a few, many, or a store left
/// full by a pass under another light, the pixels are the same.
#[test]
fn setup_stores_of_any_size_shade_alike() {
    let scene = row_of_boxes();
    let light = perspective(Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, 1.4, 1.0, 20.0);
    let other = perspective(Vec3::new(-2.0, 3.0, 1.0), Vec3::ZERO, 1.2, 1.0, 20.0);
    let cfg = config(128, 16, DepthUnit::Dual, true);
    let (maps, _) = run::<D24, _, 64>(cfg, &scene.clip(&light, true), CullMode::None, 4096, NoProbe);
    let view = MapView::<D24>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let source = |id: u32| scene.tris.get(id as usize).copied();
    let with = |light: Mat4, setups: &mut [ShadeSetup]| {
        let cam = camera_config(light, second(Filter::Box { size: 3 }), true, Normals::Flat);
        let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
        shade_with(
            &ShadeInputs { cfg: &cam, map: &view, scene: &source, unit: &MapUnit },
            &ids,
            &mut out,
            setups,
            &mut NoProbe,
        )
        .expect("sized");
        out
    };
    let reference = with(light, &mut []);
    let visible = reference.iter().filter(|p| p.triangle != NO_TRIANGLE).map(|p| p.triangle);
    assert!(visible.collect::<std::collections::BTreeSet<_>>().len() > 20, "rows cross many triangles");
    assert!(reference.iter().any(|p| p.shadow == Shadow::ONE), "the boxes cast shadows");
    for len in [1, 3, 16, 256] {
        assert_eq!(with(light, &mut vec![ShadeSetup::EMPTY; len]), reference, "a store of {len}");
    }
    let mut stale = vec![ShadeSetup::EMPTY; 256];
    assert_ne!(with(other, &mut stale), reference, "another light shades otherwise");
    assert_eq!(with(light, &mut stale), reference, "a store left by another light");
    let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
    let cam = camera_config(light, second(Filter::Box { size: 3 }), true, Normals::Flat);
    shade(&cam, &ids, &view, &source, &mut out, &mut NoProbe).expect("sized");
    assert_eq!(out, reference, "shade's own store");
}

/// Second depth from front-face culling: for a scene of closed solids the
/// single culled buffer is the dual unit's `z2`, so the camera pass gives
/// the same verdicts either way.
#[test]
fn front_face_culled_map_gives_the_dual_verdicts() {
    let mut scene = Scene { tris: Vec::new() };
    scene.cuboid(Vec3::new(-3.0, -0.3, -3.0), Vec3::new(3.0, 0.0, 3.0));
    scene.cuboid(Vec3::new(-0.5, 0.4, -0.5), Vec3::new(0.5, 1.0, 0.2));
    let light = perspective(Vec3::new(1.0, 5.0, 1.5), Vec3::ZERO, 1.4, 1.0, 20.0);
    let cfg = config(128, 16, DepthUnit::Single, true);
    let (ffc, _) = run::<D24, _, 64>(cfg, &scene.clip(&light, false), CullMode::Front, 4096, NoProbe);
    let dual_cfg = config(128, 16, DepthUnit::Dual, true);
    let (dual, _) = run::<D24, _, 64>(dual_cfg, &scene.clip(&light, false), CullMode::None, 4096, NoProbe);
    let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &scene.clip(&camera(), false), true);
    let source = |id: u32| scene.tris.get(id as usize).copied();
    for filter in filters() {
        let cam = camera_config(light, second(filter), true, Normals::Flat);
        let shade_with = |view: &MapView<'_, D24>| {
            let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
            shade(&cam, &ids, view, &source, &mut out, &mut NoProbe).expect("sized");
            out
        };
        let a = shade_with(&MapView::front_culled(cfg.raster, &ffc.z1, &ffc.tiles).expect("sized"));
        let b = shade_with(&MapView::new(dual_cfg.raster, &dual.z1, &dual.z2, &dual.tiles).expect("sized"));
        assert_eq!(ffc.z1, dual.z2, "the culled buffer is the second depth");
        assert_eq!(a, b, "{filter:?}");
        assert!(a.iter().any(|s| s.shadow == Shadow::ONE), "the small box shadows the slab");
    }
}

fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![4 => -3.0f32..3.0, 1 => Just(f32::NAN), 1 => Just(f32::INFINITY), 1 => Just(1.0e30f32), 1 => Just(0.0f32)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any matrices and triangles, NaN and infinities included: the camera
    /// pass never panics and every fraction stays in [0, 1].
    #[test]
    fn the_camera_pass_takes_any_input(
        cam in prop::array::uniform16(wild()),
        light in prop::array::uniform16(wild()),
        verts in prop::collection::vec(prop::array::uniform3((wild(), wild(), wild())), 1..6),
        smooth in any::<bool>(),
    ) {
        let tris: Vec<SceneTriangle> = verts
            .iter()
            .map(|t| {
                let p = t.map(|(x, y, z)| Vec3::new(x, y, z));
                SceneTriangle { positions: p, normals: [p[0], p[1], p[2]] }
            })
            .collect();
        let (cam, light) = (Mat4::from_cols_array(&cam), Mat4::from_cols_array(&light));
        let clip = |m: &Mat4| tris.iter().map(|t| t.positions.map(|p| *m * p.extend(1.0))).collect::<Vec<_>>();
        let cfg = config(32, 8, DepthUnit::Dual, true);
        let (maps, _) = run::<D16, _, 8>(cfg, &clip(&light), CullMode::None, 16, NoProbe);
        let view = MapView::<D16>::new(cfg.raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
        let (ids, _, _) = run_visibility::<D24>(CAMERA, 16, &clip(&cam), true);
        for filter in filters() {
            let normals = if smooth { Normals::Smooth } else { Normals::Flat };
            let c = ShadeConfig { camera: cam, ..camera_config(light, second(filter), true, normals) };
            let mut out = vec![Shaded::BACKGROUND; (CAMERA * CAMERA) as usize];
            let source = |id: u32| tris.get(id as usize).copied();
            shade(&c, &ids, &view, &source, &mut out, &mut NoProbe).expect("sized");
            prop_assert!(out.iter().all(|s| s.shadow <= Shadow::ONE));
        }
    }
}
