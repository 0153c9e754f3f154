//! The metrics on synthetic images with known answers: a boundary moved by
//! k pixels is displaced by k; exactly the pixels off the reference (by
//! the ½ verdict or by more than the shade step) are judged, each counted
//! under the cause it is given, wherever it lies; stripes a filter dims
//! below ½ are wrong by their magnitude; a footprint is read along each
//! axis; a filtered image equal to the area reference has no area error
//! and no wrong pixel; ties are counted.

use umbra::core::depth::PlaneZ;
use umbra::core::glam::Vec3;
use umbra::core::shade::{LightPoint, Shaded};
use umbra::core::shadow::{MapCoord, Shadow};
use umbra::sim::truth::cause::Cause;
use umbra::sim::truth::metrics::{Fields, Metrics, compare};
use umbra::sim::truth::reference::PixelTruth;

const W: usize = 40;
const H: usize = 30;

fn px(shadow: f64) -> Shaded {
    Shaded { triangle: 0, light: None, normal: Vec3::Y, shadow: Shadow::from_num(shadow) }
}

/// Truth: shadowed left of column `edge`, lit from it on; every pixel
/// faces the light, its visibility its centre's verdict.
fn truth(edge: usize) -> Vec<Option<PixelTruth>> {
    (0..W * H)
        .map(|k| {
            let lit = k % W >= edge;
            Some(PixelTruth { faces_light: true, lit, visibility: f64::from(u8::from(lit)), light_cos: 1.0 })
        })
        .collect()
}

/// A render shadowed left of column `edge`.
fn render(edge: usize) -> Vec<Shaded> {
    (0..W * H).map(|k| px(if k % W >= edge { 0.0 } else { 1.0 })).collect()
}

/// The metrics of `render` against `t`, every too-dark pixel judged acne
/// and every too-light one detachment (the causes are the judge's; these
/// tests hold the counting), and the pixels the judge was asked about,
/// too dark or not.
fn judged(render: &[Shaded], t: &[Option<PixelTruth>]) -> (Metrics, Vec<(usize, bool)>) {
    let mut asked = Vec::new();
    let mut causes = |k: usize, _: &Shaded, dark: bool| {
        asked.push((k, dark));
        if dark { Cause::Acne } else { Cause::Detachment }
    };
    let (m, _) = compare(render, t, &Fields::new(t, W as u32), &mut causes);
    (m, asked)
}

fn measured(render: &[Shaded], t: &[Option<PixelTruth>]) -> Metrics {
    judged(render, t).0
}

#[test]
fn a_boundary_moved_by_k_pixels_is_displaced_by_k() {
    let t = truth(20);
    for k in 0..5usize {
        let (m, asked) = judged(&render(20 + k), &t);
        // The boundary's lit column moved from 20 to 20 + k.
        let expected = [k as f64; 3];
        assert_eq!(m.displacement, expected, "k = {k}");
        // The shadow reaches k columns into the lit side: false shadows,
        // every one judged too dark, none spared for lying by the edge.
        assert_eq!(m.false_shadow, (k * H) as u64);
        assert_eq!(m.acne, (k * H) as u64, "k = {k}");
        assert!(asked.iter().all(|&(p, dark)| dark && (20..20 + k).contains(&(p % W))), "k = {k}");
        // Moved the other way, the pixels are too light.
        if k >= 1 {
            let m = measured(&render(20 - k), &t);
            assert_eq!((m.false_light, m.detachment), ((k * H) as u64, (k * H) as u64), "k = {k}");
            assert_eq!(m.displacement, expected, "k = -{k}");
        }
    }
}

/// A checker of false shadows far from the edge and the same along it
/// are judged alike: a distance to the edge excuses nothing.
#[test]
fn wrong_pixels_near_an_edge_are_judged_like_those_far_from_it() {
    let t = truth(20);
    let mut far = render(20);
    let mut near = render(20);
    for y in (4..H - 4).step_by(2) {
        far[y * W + 30] = px(1.0);
        near[y * W + 20] = px(1.0);
    }
    let (f, n) = (measured(&far, &t), measured(&near, &t));
    assert_eq!((f.false_shadow, f.acne, f.aliasing), (11, 11, 0));
    assert_eq!((n.false_shadow, n.acne, n.aliasing), (11, 11, 0));
    assert!(f.artifact_percent > 0.0 && f.artifact_percent == n.artifact_percent);
}

#[test]
fn a_filtered_image_equal_to_the_area_reference_has_no_area_error() {
    // Visibility ramps across the image; the render's fraction matches it.
    let t: Vec<Option<PixelTruth>> = (0..W * H)
        .map(|k| {
            let v = (k % W) as f64 / (W - 1) as f64;
            Some(PixelTruth { faces_light: true, lit: v > 0.5, visibility: v, light_cos: 1.0 })
        })
        .collect();
    let exact: Vec<Shaded> = t.iter().map(|p| px(1.0 - p.expect("evaluated").visibility)).collect();
    let m = measured(&exact, &t);
    // Fractions are stored at 16 bits: within 2^-16 a pixel.
    assert!(m.mean_abs_error < 2e-5 && m.rms_error < 2e-5, "{} {}", m.mean_abs_error, m.rms_error);
    // Off by 0.25 everywhere: both errors are 0.25.
    let off: Vec<Shaded> = t.iter().map(|p| px((1.0 - p.expect("evaluated").visibility - 0.25).max(0.0))).collect();
    let m = measured(&off, &t);
    assert!(m.rms_error >= m.mean_abs_error && m.mean_abs_error > 0.2, "{} {}", m.mean_abs_error, m.rms_error);
}

#[test]
fn ties_at_one_half_count_as_lit_and_are_counted() {
    let t = truth(20);
    let mut r = render(20);
    for x in 0..5 {
        r[10 * W + x] = px(0.5);
    }
    let m = measured(&r, &t);
    assert_eq!((m.ties, m.false_light), (5, 5));
}

/// `r` with light-space points that move `sx` texels a pixel along x and
/// `sy` along y (a map magnified `1/sx` times along x).
fn with_light(mut r: Vec<Shaded>, sx: f64, sy: f64) -> Vec<Shaded> {
    for (k, p) in r.iter_mut().enumerate() {
        let (x, y) = ((k % W) as f64, (k / W) as f64);
        p.light = Some(LightPoint {
            x: MapCoord::from_num(10.0 + x * sx),
            y: MapCoord::from_num(10.0 + y * sy),
            z: PlaneZ::from_num(0.5),
        });
    }
    r
}

/// Stripes of shadow fraction 0.3 on the lit side, below the ½ verdict:
/// each is wrong by its magnitude 0.3 (none of them a false shadow by the
/// ½ verdict); at 0.05, under the visible step, none is wrong.
#[test]
fn stripes_a_filter_dims_below_one_half_are_acne_of_their_magnitude() {
    let t = truth(10);
    let striped = |f: f64| {
        let mut r = render(10);
        for y in (2..H - 2).step_by(3) {
            for x in 20..36 {
                r[y * W + x] = px(f);
            }
        }
        r
    };
    let stripes = (2..H - 2).step_by(3).count() as u64 * 16;
    let m = measured(&striped(0.3), &t);
    assert_eq!((m.acne, m.false_shadow), (stripes, 0));
    assert!((m.acne_area - 0.3 * stripes as f64).abs() < 1e-3, "{}", m.acne_area);
    assert_eq!(judged(&striped(0.05), &t).1, []);
}

/// A floor seen so that one pixel steps 0.25 texels along x and 3 along
/// y: the footprint says magnified along x and minified along y.
#[test]
fn a_footprint_is_read_along_each_axis() {
    let m = measured(&with_light(render(20), 0.25, 3.0), &truth(20));
    assert!((m.footprint_x[0] - 0.25).abs() < 1e-3 && (m.footprint_x[1] - 0.25).abs() < 1e-3, "{:?}", m.footprint_x);
    assert!((m.footprint_y[0] - 3.0).abs() < 1e-3, "{:?}", m.footprint_y);
}

/// A filtered image equal to the area reference, soft shadow included,
/// has no wrong pixel to judge.
#[test]
fn a_filtered_image_equal_to_the_reference_counts_no_artifact() {
    let t: Vec<Option<PixelTruth>> = (0..W * H)
        .map(|k| {
            let v = ((k % W) as f64 / 10.0 - 1.0).clamp(0.0, 1.0);
            Some(PixelTruth { faces_light: true, lit: v >= 0.5, visibility: v, light_cos: 1.0 })
        })
        .collect();
    let exact: Vec<Shaded> = t.iter().map(|p| px(1.0 - p.expect("evaluated").visibility)).collect();
    let (m, asked) = judged(&with_light(exact, 0.5, 0.5), &t);
    assert_eq!((m.acne, m.leaks, m.aliasing, asked.len()), (0, 0, 0, 0));
}
