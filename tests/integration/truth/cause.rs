//! Wrong pixels judged by their cause, against references independent of
//! the judge: maps written by hand, the same scene with every other
//! object removed, the same map at bias 0, and Reeves' filter at more
//! samples.

use umbra::core::D24;
use umbra::core::DepthFormat;
use umbra::core::depth::PlaneZ;
use umbra::core::shadow::{Bias, DepthTest, Filter, Lookup, MapCoord, Shadow, ShadowConfig, shadow};
use umbra::sim::Algorithm;
use umbra::sim::render::{Render, RenderConfig, TruthSource, render};
use umbra::sim::truth::cause::{Cause, Judge, Receiver, Sight, Taps};
use umbra::sim::truth::metrics::Verdict;
use umbra::sim::{Limits, Scene};

use crate::shadow::shadow_unit::Map;

/// One step of the 24-bit format, as a depth.
const STEP: f32 = 1.0 / 16_777_215.0;

/// A lookup at the centre of texel `(1, 1)` of a hand-built map, at depth `z`.
fn at(z: f32) -> Lookup {
    Lookup {
        x: MapCoord::from_num(1.5),
        y: MapCoord::from_num(1.5),
        z: D24::plane_z(f64::from(z)),
        footprint: [MapCoord::ZERO; 2],
        seed: 1,
        slope: None,
    }
}

/// The cause the judge gives lookup `l` on a 4×4 map of `z1` and `z2`
/// under `test`, `filter` and `bias`, too dark when `dark`; `occluder`
/// says which texels' exact rays meet a surface in front of the receiver
/// (the construction's own truth).
fn judged(
    (z1, z2): (&[f32; 16], &[f32; 16]),
    (test, filter, bias): (DepthTest, Filter, f32),
    l: &Lookup,
    dark: bool,
    occluder: impl Fn(i64, i64) -> bool,
) -> (Shadow, Cause) {
    let map = Map::<D24>::new(4, 4, z1, z2);
    let cfg = ShadowConfig::new(test, Bias::Constant(D24::plane_z(f64::from(bias))), filter, true).expect("valid");
    let mut taps = Taps::default();
    let s = shadow(&map.view(), &cfg, l, &mut taps);
    assert!(!taps.taps().is_empty(), "the taps are recorded");
    let judge = Judge { test, shade: s, dark, soft: Judge::softens(filter) };
    let sight = |t: &umbra::core::probe::Tap| if occluder(t.x, t.y) { Sight::Occluded } else { Sight::Clear };
    (s, judge.cause(taps.taps(), &Receiver::flat::<D24>(l.z.to_bits()), sight))
}

/// A tap whose stored depth is the receiver's own (one step in front of
/// it, as rounding leaves a plane's own depth) shadows it: acne. The
/// same tap two steps in front of a flat receiver (span: one step) is a
/// surface truly in front: aliasing.
#[test]
fn a_tap_at_the_receivers_own_depth_is_acne() {
    let z1 = [0.5; 16];
    let behind = |steps: i64| Lookup { z: D24::plane_z(0.5) + PlaneZ::from_bits(steps << 32), ..at(0.5) };
    let (s, cause) = judged((&z1, &[1.0; 16]), (DepthTest::First, Filter::Point, 0.0), &behind(1), true, |_, _| false);
    assert_eq!((s, cause), (Shadow::ONE, Cause::Acne));
    let (s, cause) = judged((&z1, &[1.0; 16]), (DepthTest::First, Filter::Point, 0.0), &behind(2), true, |_, _| false);
    assert_eq!((s, cause), (Shadow::ONE, Cause::Aliasing));
}

/// A separate occluder 10 steps in front of the receiver in two of the
/// bilinear filter's four texels, the other two holding the receiver:
/// the taps straddle the occluder's edge, aliasing, though the pixel is
/// darkened; a box filter of Reeves' softens the same edge on purpose:
/// penumbra.
#[test]
fn a_separate_occluder_beside_a_tap_that_misses_it_is_aliasing() {
    let z = 0.5;
    let mut z1 = [z; 16];
    for k in [5, 9] {
        // Texels (1, 1) and (1, 2): the occluder.
        z1[k] = z - 10.0 * STEP;
    }
    // The point between texel centres (1, 1), (2, 1), (1, 2), (2, 2).
    let l = Lookup { x: MapCoord::from_num(2.0), y: MapCoord::from_num(2.0), ..at(z) };
    let test = DepthTest::First;
    let (s, cause) = judged((&z1, &[1.0; 16]), (test, Filter::Bilinear, 0.0), &l, true, |x, _| x == 1);
    assert_eq!((s, cause), (Shadow::from_num(0.5), Cause::Aliasing));
    let (s, cause) = judged((&z1, &[1.0; 16]), (test, Filter::Box { size: 2 }, 0.0), &l, true, |x, _| x == 1);
    assert_eq!((s, cause), (Shadow::from_num(0.5), Cause::Penumbra));
}

/// Under an occluder whose front is 0.3 and back 0.7, a receiver at 0.5
/// compared against the second depth is lit: the compared depth lies
/// behind the receiver under a first-layer occluder, a leak. The same
/// receiver against the first depth, with a bias that moves it past an
/// occluder just in front: detachment. With no occluder on the tap's
/// exact ray: aliasing.
#[test]
fn a_second_depth_behind_the_receiver_under_a_first_layer_occluder_is_a_leak() {
    let (z1, z2) = ([0.3; 16], [0.7; 16]);
    let point = |test, bias| (test, Filter::Point, bias);
    let (s, cause) = judged((&z1, &z2), point(DepthTest::Second, 0.0), &at(0.5), false, |_, _| true);
    assert_eq!((s, cause), (Shadow::ZERO, Cause::Leak));
    let near = [0.49; 16];
    let (s, cause) = judged((&near, &z2), point(DepthTest::First, 0.02), &at(0.5), false, |_, _| true);
    assert_eq!((s, cause), (Shadow::ZERO, Cause::Detachment));
    let (_, cause) = judged((&near, &z2), point(DepthTest::First, 0.02), &at(0.5), false, |_, _| false);
    assert_eq!(cause, Cause::Aliasing);
    // The dual depth held to its offset (0.005 above z1 = 0.49, below the
    // half thickness) moves the comparison past: detachment; held to its
    // half thickness (a thin occluder), the midpoint's leak.
    let offset = DepthTest::Dual { offset: D24::plane_z(0.005) };
    let (_, cause) = judged((&near, &z2), point(offset, 0.0), &at(0.493), false, |_, _| true);
    assert_eq!(cause, Cause::Detachment);
    let thin = [0.496; 16];
    let (_, cause) = judged((&near, &thin), point(offset, 0.0), &at(0.492), false, |_, _| true);
    assert_eq!(cause, Cause::Leak);
}

/// The configuration of a render at `size` with `algo`, `bias`, `filter`
/// and map side `map`.
pub(super) fn config((algo, bias, filter): (Algorithm, f64, &str), map: u32, size: (u32, u32)) -> RenderConfig {
    RenderConfig {
        algorithm: algo,
        bias,
        filter: filter.parse().expect("a filter"),
        map_size: map,
        width: size.0,
        height: size.1,
        reference_rays: 2,
        ..RenderConfig::DEFAULT
    }
}

/// A render of `scene` as `cfg` says.
pub(super) fn render_with(scene: &Scene, cfg: &RenderConfig) -> Render {
    cfg.check(scene, &Limits::DEFAULT).and_then(|job| render(&job, TruthSource::Quiet)).expect("renders")
}

/// A render of `scene` at `size` with `algo`, `bias`, `filter` and map side `map`.
pub(super) fn rendered(scene: &Scene, algo: (Algorithm, f64, &str), map: u32, size: (u32, u32)) -> Render {
    render_with(scene, &config(algo, map, size))
}

/// The object of each pixel's visible triangle (`None` for the background).
pub(super) fn objects(scene: &Scene, r: &Render) -> Vec<Option<usize>> {
    let of = scene.triangle_objects();
    r.image.pixels.iter().map(|p| of.get(p.triangle as usize).map(|&o| o as usize)).collect()
}

/// `scene` with only object `keep`.
pub(super) fn alone(scene: &Scene, keep: usize) -> Scene {
    Scene { objects: vec![scene.objects[keep].clone()], ..scene.clone() }
}

/// The texel a point lookup of pixel `p` reads, and what the map holds there.
pub(super) fn texel_under(r: &Render, p: &umbra::core::shade::Shaded) -> Option<u32> {
    let l = p.light?;
    let (x, y) = (l.x.to_num::<i64>(), l.y.to_num::<i64>());
    let w = i64::from(r.maps.maps.config.raster.width());
    let h = i64::from(r.maps.maps.config.raster.height());
    let k = usize::try_from(y * w + x).ok().filter(|_| (0..w).contains(&x) && (0..h).contains(&y))?;
    r.maps.maps.z1.get(k).copied()
}

/// Pixels lit in truth (every reference ray sees the light) and shaded
/// too dark — the shade above the reference by more than the step, or
/// shadowed by the ½ verdict — whose receiver, rendered alone, is shaded
/// bit for bit the same from the same stored depth (the point lookup's
/// texel holds the same value with every other object removed: no other
/// object is in it): the receiver darkened itself, whatever lies near it.
/// Every one must be acne in both renders. Returns how many.
fn self_shadowed_pixels_are_acne(name: &str, algo: (Algorithm, f64, &str), map: u32, size: (u32, u32)) -> usize {
    let scene = Scene::bundled(name).expect("bundled");
    let full = rendered(&scene, algo, map, size);
    let of = objects(&scene, &full);
    let mut checked = 0;
    // The objects the camera sees, each alone.
    for keep in (0..scene.objects.len()).filter(|&o| of.contains(&Some(o))) {
        let own = rendered(&alone(&scene, keep), algo, map, size);
        for (k, (p, t)) in full.image.pixels.iter().zip(&full.truth).enumerate() {
            let Some(t) = t.filter(|t| t.faces_light && t.visibility == 1.0) else { continue };
            let too_dark = p.shadow.to_num::<f64>() > 0.1 || p.shadow > Shadow::from_num(0.5);
            let same = own.image.pixels[k].shadow == p.shadow && texel_under(&full, p) == texel_under(&own, p);
            if of[k] != Some(keep) || !too_dark || !t.lit || !same {
                continue;
            }
            checked += 1;
            let acne = Verdict::Wrong(Cause::Acne);
            assert_eq!(full.verdicts[k], acne, "{name}: pixel {k} darkened by its own object {keep}");
            assert_eq!(own.verdicts[k], acne, "{name}: pixel {k} with object {keep} alone");
        }
    }
    checked
}

/// Three scenes: a curved occluder (Reeves' sphere, whose own terminator
/// and the floor under it shadow themselves at bias 0), a floor lit at
/// grazing (the crowd's, 256² map), and acne within a few pixels of a
/// shadow (Wang & Molnar's table, first depth at a small bias, the floor's
/// acne beside the legs' shadows). Each set is large (hundreds of pixels;
/// asserted at least 50) so that the rule is held where it matters.
#[test]
fn a_receiver_shadowed_by_itself_is_acne_with_or_without_its_neighbours() {
    let first = |bias| (Algorithm::First, bias, "point");
    for (name, algo, map) in
        [("reeves-sphere", first(0.0), 512), ("crowd-grazing", first(0.0), 256), ("wang-molnar-4", first(0.002), 512)]
    {
        let n = self_shadowed_pixels_are_acne(name, algo, map, (240, 200));
        println!("{name}: {n} self-shadowed pixels, all acne");
        assert!(n >= 50, "{name}: only {n} self-shadowed pixels to hold the rule to");
    }
}

/// Wang & Molnar's table at bias 0.03 (the bias that clears the floor's
/// acne) and at bias 0, on the same map: every pixel too light at 0.03
/// and right at 0 — right because the legs, not the floor's own surface,
/// shadow it there (lit at bias 0 with the floor alone) — is detachment.
#[test]
fn a_pixel_the_bias_alone_makes_too_light_is_detachment() {
    let scene = Scene::bundled("wang-molnar-4").expect("bundled");
    let size = (256, 256);
    let point = |bias| (Algorithm::First, bias, "point");
    let (biased, unbiased) = (rendered(&scene, point(0.03), 512, size), rendered(&scene, point(0.0), 512, size));
    let of = objects(&scene, &biased);
    let floor = scene.objects.iter().position(|o| o.name == "floor").expect("a floor");
    let floor_alone = rendered(&alone(&scene, floor), point(0.0), 512, size);
    let wrong_light = |v: Verdict| matches!(v, Verdict::Wrong(Cause::Detachment | Cause::Leak | Cause::Aliasing));
    let mut checked = 0;
    for (k, object) in of.iter().enumerate() {
        let t = biased.truth[k].filter(|t| t.faces_light);
        let too_light = t.is_some_and(|t| biased.image.pixels[k].shadow.to_num::<f64>() < 1.0 - t.visibility - 0.1);
        let right_at_zero = unbiased.verdicts[k] == Verdict::Right;
        let floor_lit = *object == Some(floor) && floor_alone.image.pixels[k].shadow == Shadow::ZERO;
        if too_light && right_at_zero && floor_lit {
            checked += 1;
            assert!(wrong_light(biased.verdicts[k]), "pixel {k} is wrong the light way");
            assert_eq!(biased.verdicts[k], Verdict::Wrong(Cause::Detachment), "pixel {k}");
        }
    }
    println!("{checked} pixels detached by the bias alone");
    assert!(checked >= 100, "only {checked} pixels to hold the rule to");
    assert!(biased.metrics.detachment >= checked as u64);
}

/// Reeves' filter on the sphere at 1024² with ResFactor 3 and bias 0.01:
/// its soft edge is penumbra, so more samples (1, 4, 16) do not raise the
/// artifacts, while the penumbra appears with the filter's softness.
#[test]
fn more_samples_of_reeves_filter_do_not_raise_the_artifacts() {
    let scene = Scene::bundled("reeves-sphere").expect("bundled");
    let runs: Vec<Render> = ["jitter1", "jitter4", "jitter16"]
        .iter()
        .map(|f| rendered(&scene, (Algorithm::First, 0.01, f), 1024, (512, 512)))
        .collect();
    let artifacts: Vec<u64> = runs.iter().map(|r| r.metrics.acne + r.metrics.detachment + r.metrics.leaks).collect();
    let penumbra: Vec<u64> = runs.iter().map(|r| r.metrics.penumbra).collect();
    println!("artifacts {artifacts:?}, penumbra {penumbra:?}");
    assert!(artifacts.windows(2).all(|w| w[1] <= w[0]), "artifacts {artifacts:?} rise with samples");
    assert!(penumbra[1] >= 500 && penumbra[2] >= 500, "penumbra {penumbra:?}");
}

/// The judge reads the depths the unit compared: a receiver whose plane
/// is steep has a span of its slope across a texel, so its own depth a
/// texel away is within it.
#[test]
fn a_receivers_span_is_its_slope_across_a_texel_and_one_step() {
    let tri = [
        umbra::core::glam::DVec3::new(-1.0, -1.0, 0.2),
        umbra::core::glam::DVec3::new(1.0, -1.0, 0.6),
        umbra::core::glam::DVec3::new(-1.0, 1.0, 0.2),
    ];
    // An orthographic light looking down −z onto a 100² map: x ∈ [−1, 1]
    // across 100 texels, depth z → (z − 0)/1 … identity in clip space.
    let light = umbra::core::glam::DMat4::IDENTITY;
    let r = Receiver::of::<D24>(&tri, &light, (100, 100)).expect("a plane");
    // Depth rises 0.4 over 100 texels along u: 0.004 a texel, in PlaneZ
    // bits of the 24-bit format, plus one step.
    let unit = D24::SCALE as f64 * umbra::core::budget::PLANE_ONE;
    let slope = 0.004 * unit;
    assert!((r.span() - (slope + umbra::core::budget::PLANE_ONE)).abs() < 1e-6 * unit, "{}", r.span());
    assert!((r.at(0, 50) - (0.2 + 0.002) * unit).abs() < 1e-6 * unit, "{}", r.at(0, 50));
}

/// The error map paints each wrong pixel in its class's colour: Wang &
/// Molnar's table at the bias that clears the floor's acne, decoded. The
/// detachment at the legs' feet shows in its colour (rings add to it, so
/// at least as many pixels as the metrics count), and a pixel judged
/// right stays grey (the background its own blue) unless a ring round an
/// artifact within 10 pixels covers it.
#[test]
fn the_error_map_paints_each_class_its_colour() {
    use umbra::sim::render::pictures::{ERROR_COLOURS, write_error_image};
    let scene = Scene::bundled("wang-molnar-4").expect("bundled");
    let r = rendered(&scene, (Algorithm::First, 0.03, "point"), 512, (256, 256));
    let dir = std::env::temp_dir().join(format!("umbra-error-map-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut folder = umbra::sim::output::folder::OutputFolder::create(
        &dir,
        umbra::sim::output::folder::Claim::new(umbra::sim::output::folder::RunKind::Render),
    )
    .expect("folder");
    let path = write_error_image(&mut folder, "error.png", &r.image, &r.verdicts, (&r.truth, &[], "wang-molnar-4"))
        .expect("written");
    let png = image::open(&path).expect("a PNG").to_rgb8();
    let _ = std::fs::remove_dir_all(&dir);
    let (w, h) = (r.image.width, r.image.height);
    let (x0, y0) = umbra::sim::output::picture::BODY_ORIGIN;
    assert!(png.width() >= w && png.height() > y0 + h, "the caption above, the key below the image");
    let pixel = |x: u32, y: u32| png.get_pixel(x0 + x, y0 + y).0;
    let colour = |c: Cause| ERROR_COLOURS.iter().find(|e| e.0 == c).expect("a colour").2;
    let detached = colour(Cause::Detachment);
    let painted = (0..w * h).filter(|k| pixel(k % w, k / w) == detached).count() as u64;
    assert!(r.metrics.detachment >= 100, "{} detachment", r.metrics.detachment);
    assert!(painted >= r.metrics.detachment, "{painted} purple pixels for {} detachment", r.metrics.detachment);
    let artifacts: Vec<(i64, i64)> = (0..w * h)
        .filter(|&k| matches!(r.verdicts[k as usize], Verdict::Wrong(c) if c.is_artifact()))
        .map(|k| (i64::from(k % w), i64::from(k / w)))
        .collect();
    for k in (0..w * h).filter(|&k| r.verdicts[k as usize] == Verdict::Right) {
        let (x, y) = (i64::from(k % w), i64::from(k / w));
        let [red, green, blue] = pixel(k % w, k / w);
        let ringed = artifacts.iter().any(|&(ax, ay)| (ax - x).abs() <= 10 && (ay - y).abs() <= 10);
        let surface = r.image.pixels[k as usize].triangle != umbra::core::NO_TRIANGLE;
        let background = [red, green, blue] == umbra::sim::output::picture::BACKGROUND;
        assert!(
            ringed || (surface && red == green && green == blue) || (!surface && background),
            "pixel ({x}, {y}) judged right is coloured"
        );
    }
}
